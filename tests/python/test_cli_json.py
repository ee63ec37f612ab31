"""One schema: the dicts equal the CLI's --json documents for the same inputs
(the numpy extras aside, and the planner's wall-clock `stats.time`)."""

import json

import pytest

import cairn

EXTRAS = ("contact_arrays", "timeline")


def strip(doc):
    doc = {k: v for k, v in doc.items() if k not in EXTRAS}
    if "stats" in doc:
        doc["stats"] = {k: v for k, v in doc["stats"].items() if k != "time"}
    return doc


def cli_json(cli, *args):
    code, out, err = cli(*args, "--json")
    assert code in (0, 1, 3), err
    return strip(json.loads(out))


@pytest.mark.parametrize("scene,without,normalize", [
    ("examples/paper_fig1.json", [], None),
    ("examples/paper_fig1.json", ["C"], "A"),
    ("examples/paper_fig4.json", ["A"], None),
    ("examples/incline.json", [], None),
    ("examples/stack3_tips.json", [], None),
    ("examples/ladder.json", [], None),
    ("examples/paper_fig9.json", ["A"], None),
    ("examples/wall.json", [], None),
])
def test_check(cli, scene, without, normalize):
    args = ["check", scene]
    if without:
        args += ["--without", ",".join(without)]
    if normalize:
        args += ["--normalize", normalize]
    r = cairn.check(cairn.load(scene), without=without, normalize=normalize)
    assert strip(r) == cli_json(cli, *args)


@pytest.mark.parametrize("scene,plan,extra", [
    ("examples/paper_fig1.json", "examples/plans/paper_fig1_c_first.plan.json", []),
    ("examples/paper_fig1.json", "examples/plans/paper_fig1_dcba.plan.json", []),
    ("examples/paper_fig4.json", "examples/plans/paper_fig4_lift_a.plan.json", ["--continue"]),
    ("examples/paper_fig16.json", "examples/plans/paper_fig15_slide_p.plan.json", []),
    ("examples/paper_fig19.json", "examples/plans/paper_fig19_slide_a.plan.json", []),
])
def test_simulate(cli, tmp_path, scene, plan, extra):
    csv = tmp_path / "timeline.csv"
    s = cairn.simulate(cairn.load(scene), plan, continue_after_failure=bool(extra))
    assert strip(s) == cli_json(cli, "simulate", scene, plan, "--timeline", str(csv), *extra)
    # The timeline columns are the CSV's, value for value.
    t = cairn.read_timeline(str(csv))
    assert list(t) == list(s["timeline"])
    for k in t:
        assert (t[k] == s["timeline"][k]).all(), k


def test_simulate_suggest_fixtures(cli, tmp_path):
    # simulate() always records the timeline, as --timeline does (the fixture
    # search then reuses the run instead of simulating it again: `simulations`).
    scene, plan = "examples/paper_fig4.json", "examples/plans/paper_fig4_lift_a.plan.json"
    s = cairn.simulate(cairn.load(scene), plan, suggest_fixtures=True, max_fixels=2)
    assert s["fixtures"] is not None
    assert strip(s) == cli_json(cli, "simulate", scene, plan, "--suggest-fixtures",
                                "--max-fixels", "2", "--timeline", str(tmp_path / "t.csv"))


@pytest.mark.parametrize("scene,kwargs,args", [
    ("examples/paper_fig1.json", {"single_parts": True}, ["--single-parts"]),
    ("examples/paper_fig1.json", {}, []),
    ("examples/paper_fig17.json", {"max": 2}, ["--max", "2"]),
    ("examples/paper_fig4.json", {"allow_fixtures": 2}, ["--allow-fixtures", "2"]),
])
def test_plan(cli, scene, kwargs, args):
    p = cairn.plan(cairn.load(scene), threads=1, **kwargs)
    assert strip(p) == cli_json(cli, "plan", scene, "--threads", "1", *args)


@pytest.mark.parametrize("scene", ["examples/l_shapes.json", "examples/peg_in_slot.json",
                                   "examples/paper_fig9.json"])
def test_blocking(cli, scene):
    assert cairn.blocking(cairn.load(scene)) == cli_json(cli, "blocking", scene)


def test_compas(cli):
    from conftest import shared_file
    path = shared_file("compas_assembly/stack_assembly.json")
    r = cairn.check(cairn.load(path, format="compas", friction=0.84), without=["7", "8", "9"])
    assert strip(r) == cli_json(cli, "check", path, "--format", "compas", "--friction", "0.84",
                                "--without", "7,8,9")


def test_plan_with_candidate_paths_as_a_file_and_as_a_dict(cli):
    from conftest import load_json
    scene, paths = "examples/paper_fig6.json", "examples/paths/paper_fig6_exits.paths.json"
    m = cairn.load(scene)
    by_file = cairn.plan(m, paths=paths, max=2, threads=1)
    assert strip(by_file) == cli_json(cli, "plan", scene, "--paths", paths, "--max", "2",
                                      "--threads", "1")
    assert strip(cairn.plan(m, paths=load_json(paths), max=2, threads=1)) == strip(by_file)
