"""One front door: every command, on every bundled example (and a COMPAS
file, the Bourjault pen in STEP, the ASAP beams), gives the same document
through the CLI and through Python, since both call the same app function;
the pages and files they write are the same bytes."""

import json
import os
import re

import pytest

import cairn
from conftest import SOURCE_DIR, example, shared_file

EXAMPLES = sorted(f for f in os.listdir(os.path.join(SOURCE_DIR, "examples"))
                  if f.endswith(".json"))


def strip(doc):
    """The document without Python's numpy extras and the planner's
    wall-clock `stats.time`."""
    doc = {k: v for k, v in doc.items() if k not in ("contact_arrays", "timeline")}
    if "stats" in doc:
        doc["stats"] = {k: v for k, v in doc["stats"].items() if k != "time"}
    return doc


def cli_json(cli, *args, codes=(0, 1, 3)):
    code, out, err = cli(*args, "--json")
    assert code in codes, err
    return strip(json.loads(out))


def same_bytes(a, b):
    """Two files, byte for byte, but for the planner's wall-clock
    `"time":...` that a plan's page carries."""
    wall_clock = re.compile(rb'"time":[0-9.e+-]+')
    return wall_clock.sub(b'"time":0', a.read_bytes()) == wall_clock.sub(b'"time":0', b.read_bytes())


def parts_of(name):
    with open(example(name), encoding="utf-8") as f:
        return len(json.load(f)["parts"])


@pytest.mark.parametrize("name", EXAMPLES)
def test_check_and_blocking_of_every_example(cli, tmp_path, name):
    scene = os.path.join("examples", name)
    m = cairn.load(scene)
    page = tmp_path / "py.html"
    assert strip(cairn.check(m, html=page)) == cli_json(cli, "check", scene, "--html",
                                                         str(tmp_path / "cli.html"))
    assert page.read_bytes() == (tmp_path / "cli.html").read_bytes()
    # The whole NDBG (but of the 100-brick wall, whose 1 056 cells take a
    # minute under the sanitizers: its one direction below).
    if len(m.parts) <= 60:
        assert cairn.blocking(m, html=tmp_path / "py-b.html") == cli_json(
            cli, "blocking", scene, "--html", str(tmp_path / "cli-b.html"))
        assert (tmp_path / "py-b.html").read_bytes() == (tmp_path / "cli-b.html").read_bytes()
    # One direction: the cell at it, the resolver the CLI's.
    d = [0.6, 0.8] if m.dimension == 2 else [0.0, 0.6, 0.8]
    assert cairn.blocking(m, direction=d) == cli_json(cli, "blocking", scene, "--direction",
                                                       ",".join(map(str, d)))


@pytest.mark.parametrize("name", [n for n in EXAMPLES if parts_of(n) <= 12])
def test_plan_and_margin_of_every_small_example(cli, tmp_path, name):
    scene = os.path.join("examples", name)
    m = cairn.load(scene)
    if m.has_interfaces:
        with pytest.raises(cairn.InputError):
            cairn.plan(m)
        assert cli("plan", scene)[0] == 2
    else:
        p = cairn.plan(m, max=1, threads=1, html=tmp_path / "py.html", dot=tmp_path / "py.dot",
                       emit_plans=tmp_path / "py")
        assert strip(p) == cli_json(cli, "plan", scene, "--max", "1", "--threads", "1", "--html",
                                    str(tmp_path / "cli.html"), "--dot",
                                    str(tmp_path / "cli.dot"), "--emit-plans",
                                    str(tmp_path / "cli"))
        for f in ("html", "dot"):
            assert same_bytes(tmp_path / f"py.{f}", tmp_path / f"cli.{f}")
        assert sorted(os.listdir(tmp_path / "py")) == sorted(os.listdir(tmp_path / "cli"))
        for f in os.listdir(tmp_path / "py"):
            assert (tmp_path / "py" / f).read_bytes() == (tmp_path / "cli" / f).read_bytes()
    axis = [0, 0, 1] if m.dimension == 2 else [1, 0, 0]
    assert strip(cairn.margin(m, tilt=axis, html=tmp_path / "py-m.html")) == cli_json(
        cli, "margin", scene, "--tilt", ",".join(map(str, axis)), "--html",
        str(tmp_path / "cli-m.html"))
    assert (tmp_path / "py-m.html").read_bytes() == (tmp_path / "cli-m.html").read_bytes()


def plans_with_scenes():
    """Every bundled plan beside the example whose name begins its own (the
    longest such), or Fig. 16 for Fig. 15's (a plan of the same parts)."""
    out = []
    for plan in sorted(os.listdir(os.path.join(SOURCE_DIR, "examples", "plans"))):
        stems = [n[:-5] for n in EXAMPLES if plan.startswith(n[:-5] + "_")]
        scene = max(stems, key=len) + ".json" if stems else None
        if plan.startswith("paper_fig15"):
            scene = "paper_fig16.json"
        if scene:
            out.append((scene, plan))
    return out


@pytest.mark.parametrize("scene,plan", plans_with_scenes())
def test_simulate_every_bundled_plan(cli, tmp_path, scene, plan):
    scene, plan = os.path.join("examples", scene), os.path.join("examples", "plans", plan)
    s = cairn.simulate(cairn.load(scene), plan, html=tmp_path / "py.html",
                       timeline=tmp_path / "py.csv")
    assert strip(s) == cli_json(cli, "simulate", scene, plan, "--html",
                                str(tmp_path / "cli.html"), "--timeline",
                                str(tmp_path / "cli.csv"))
    for f in ("html", "csv"):
        assert (tmp_path / f"py.{f}").read_bytes() == (tmp_path / f"cli.{f}").read_bytes()


def test_options_the_python_module_lacked(cli):
    # plan's dt, speed and directions; simulate's margin.
    scene = "examples/paper_fig1.json"
    m = cairn.load(scene)
    p = cairn.plan(m, max=1, threads=1, dt=0.05, speed=2, directions="axes")
    assert strip(p) == cli_json(cli, "plan", scene, "--max", "1", "--threads", "1", "--dt",
                                "0.05", "--speed", "2", "--directions", "axes")
    plan = "examples/plans/paper_fig1_c_first.plan.json"
    s = cairn.simulate(m, plan, margin="friction")
    assert "margin" in s
    assert strip(s) == cli_json(cli, "simulate", scene, plan, "--margin", "friction")
    with pytest.raises(cairn.InputError, match="directions"):
        cairn.plan(m, directions="diagonals")
    with pytest.raises(cairn.InputError, match="dt"):
        cairn.plan(m, dt=0)


def test_an_output_never_replaces_an_input(tmp_path):
    scene, plan = tmp_path / "scene.json", tmp_path / "lift.plan.json"
    scene.write_bytes(open(example("paper_fig1.json"), "rb").read())
    plan.write_bytes(open(example("plans", "paper_fig1_c_first.plan.json"), "rb").read())
    m = cairn.load(scene)
    with pytest.raises(cairn.InputError, match="html: is the input file"):
        cairn.check(m, html=scene)
    with pytest.raises(cairn.InputError, match="timeline: is the input file"):
        cairn.simulate(m, plan, timeline=plan)
    assert scene.read_bytes() == open(example("paper_fig1.json"), "rb").read()
    assert plan.read_bytes() == open(example("plans", "paper_fig1_c_first.plan.json"), "rb").read()


def test_compas_file(cli):
    path = shared_file("compas_cra/cube-curve-short.json")
    m = cairn.load(path, format="compas", friction=0.84, supports=["0"], interfaces="stored")
    args = ["--format", "compas", "--friction", "0.84", "--supports", "0", "--interfaces",
            "stored"]
    assert strip(cairn.check(m)) == cli_json(cli, "check", path, *args)
    # margin's --friction MU alone asks for the friction margin at that μ.
    assert strip(cairn.margin(m, friction=True)) == cli_json(
        cli, "margin", path, "--format", "compas", "--supports", "0", "--interfaces", "stored",
        "--friction", "0.84")
    assert cairn.blocking(m, direction=[0, 0, 1]) == cli_json(cli, "blocking", path, *args,
                                                              "--direction", "0,0,1")


def test_step_pen(cli):
    folder = shared_file("aplan_bourjault_pen_simple")
    steps = sorted(f for f in os.listdir(folder) if f.lower().endswith((".step", ".stp")))
    if not steps:
        pytest.skip("no STEP file in the pen's folder")
    path = os.path.join(folder, steps[0])
    m = cairn.load(path, format="step")
    assert m.parts
    assert strip(cairn.check(m)) == cli_json(cli, "check", path, "--format", "step")


def test_step_pen_fastened(cli):
    # --fastened through Python as a tuple and through the CLI as A:B: the
    # same model, body and head fused into one part named in the model's
    # order, where the head comes first: "head_001+body_001".
    path = shared_file("aplan_bourjault_pen_simple/asm_bourjault_ballpoint.stp")
    m = cairn.load(path, format="step", fastened=[("body_001", "head_001")])
    assert m.parts[0] == "head_001+body_001" and len(m.parts) == 5
    assert strip(cairn.check(m)) == cli_json(cli, "check", path, "--format", "step",
                                             "--fastened", "body_001:head_001")
    with pytest.raises(cairn.InputError, match="is not a pair of part names A:B"):
        cairn.load(path, format="step", fastened=["body_001"])


def asap_beams_0_and_2(tmp_path):
    """Two of ASAP's beams (0 and 2, which touch) in a folder as ASAP's own
    holds them: the whole assembly's 40 000 facets take minutes under the
    sanitizers (tests/cli/step_command_test.cpp reads it whole)."""
    source = shared_file("asap_beam_assembly")
    with open(os.path.join(source, "config.json"), encoding="utf-8") as f:
        config = json.load(f)
    folder = tmp_path / "asap"
    folder.mkdir()
    (folder / "config.json").write_text(json.dumps({k: config[k] for k in ("0", "2")}))
    for k in ("0", "2"):
        (folder / f"{k}.obj").write_bytes(open(os.path.join(source, f"{k}.obj"), "rb").read())
    return folder


def test_asap_folder(cli, tmp_path):
    folder = asap_beams_0_and_2(tmp_path)
    m = cairn.load(folder, format="asap", tolerance=1e-4)
    assert m.parts == ["0", "2"]
    assert cairn.blocking(m, direction=[0, 0, 1]) == cli_json(
        cli, "blocking", str(folder), "--format", "asap", "--tolerance", "1e-4", "--direction",
        "0,0,1")


def test_asap_beams_overlap_depth(cli, tmp_path):
    # ASAP's beams 0 and 2 interpenetrate by ~2.6e-5 (inches), more than the
    # default tolerance: overlap_depth reads that as contact, as
    # --overlap-depth does, and Model.overlaps lists the pair with its depth.
    folder = asap_beams_0_and_2(tmp_path)
    with pytest.raises(cairn.InputError, match="--overlap-depth 4e-05"):
        cairn.load(folder, format="asap")
    m = cairn.load(folder, format="asap", overlap_depth=1e-4)
    assert [o["parts"] for o in m.overlaps] == [("0", "2")]
    assert 2e-5 < m.overlaps[0]["depth"] < 1e-4
    assert strip(cairn.check(m)) == cli_json(cli, "check", str(folder), "--format", "asap",
                                             "--overlap-depth", "1e-4")
    with pytest.raises(cairn.InputError, match="overlap-depth: must be a length"):
        cairn.load(folder, format="asap", overlap_depth=-1)


@pytest.mark.parametrize("name", ["stack3.json", "pyramid10.json", "paper_fig1.json"])
def test_sequence_through_both_doors(cli, name):
    """`cairn sequence --json` and `cairn.sequence`: the same build order, the
    same holds and bound (but the wall-clock seconds)."""
    scene = os.path.join("examples", name)
    m = cairn.load(scene)

    def no_clock(doc):
        doc = strip(doc)
        doc["stats"] = {k: v for k, v in doc["stats"].items() if k != "seconds"}
        return doc

    for args, kwargs in (((), {}), (("--directions", "axes", "--beam", "1"),
                                    dict(directions="axes", beam=1)),
                         (("--directions", "ndbg"), dict(directions="ndbg"))):
        py = no_clock(cairn.sequence(m, **kwargs))
        assert py == no_clock(cli_json(cli, "sequence", scene, *args))
        assert py["complete"] == (len(py["order"]) == sum(
            1 for p in json.load(open(example(name), encoding="utf-8"))["parts"]
            if not p.get("fixed", False)))
    with pytest.raises(cairn.InputError):
        cairn.sequence(m, temporary="crane")
    with pytest.raises(cairn.InputError):
        cairn.sequence(m, emit_plans=scene)  # a file, not a folder
    with pytest.raises(cairn.InputError):
        cairn.sequence(m, rule="none")
    with pytest.raises(cairn.InputError):
        cairn.sequence(m, directions="sideways")


@pytest.mark.parametrize("name", ["paper_fig4.json", "paper_fig17.json"])
def test_sequence_emits_the_plan_the_cli_emits(cli, name, tmp_path):
    """`emit_plans`: the order as an assembly plan with its holds, the same
    file as `cairn sequence --emit-plans` writes; `cairn.simulate` runs it
    stable, and unstable once its holds are taken out."""
    scene = os.path.join("examples", name)
    m = cairn.load(scene)
    doc = cairn.sequence(m, emit_plans=tmp_path / "py")
    assert doc["temporary"]["max_in_place"] == 1
    assert cli("sequence", scene, "--emit-plans", str(tmp_path / "cli"))[0] == 0
    name = "sequence.assemble.plan.json"
    py_plan = (tmp_path / "py" / name).read_text(encoding="utf-8")
    assert py_plan == (tmp_path / "cli" / name).read_text(encoding="utf-8")
    assert cairn.simulate(m, str(tmp_path / "py" / name))["stable"]
    plan = json.loads(py_plan)
    assert any(step["hold"] or step["hold_at_rest"] for step in plan["steps"])
    for step in plan["steps"]:
        step["hold"], step["hold_at_rest"] = [], []
    (tmp_path / "bare.json").write_text(json.dumps(plan), encoding="utf-8")
    assert not cairn.simulate(m, str(tmp_path / "bare.json"))["stable"]
    # The page: the CLI's (but the wall-clock seconds in its document).
    cairn.sequence(m, html=tmp_path / "py.html")
    assert cli("sequence", scene, "--html", str(tmp_path / "cli.html"))[0] == 0

    def page_data(path):
        text = path.read_text(encoding="utf-8")
        start = text.index('<script id="cairn-data" type="application/json">')
        data = json.loads(text[text.index(">", start) + 1:text.index("</script>", start)])
        del data["result"]["stats"]["seconds"]
        return data
    py_page = page_data(tmp_path / "py.html")
    assert py_page["kind"] == "sequence"
    assert len(py_page["sequence"]["states"]) == len(doc["steps"])
    assert py_page == page_data(tmp_path / "cli.html")
