"""Arguments the Python API shares with the CLI are refused where the CLI
refuses them, with cairn.InputError naming the keyword; a cairn.Model that no
loader made cannot be used; directions and axes are read by the CLI's own
resolvers (a direction given with huge components is the same direction)."""

import json
import subprocess
import sys

import pytest

import cairn
from conftest import SOURCE_DIR, example

SCENE = "examples/stack3.json"
FIG1 = "examples/paper_fig1.json"
FIG1_PLAN = "examples/plans/paper_fig1_b_first.plan.json"


@pytest.fixture(scope="module")
def stack3():
    return cairn.load(example("stack3.json"))


@pytest.fixture(scope="module")
def fig1():
    return cairn.load(example("paper_fig1.json"))


# (function, keyword, value, the CLI's option and value): each value the CLI
# refuses (exit 2), so the keyword refuses it too.
REFUSED = [
    ("plan", "max", -1, ["--max", "-1"]),
    ("plan", "threads", -1, ["--threads", "-1"]),
    ("plan", "allow_fixtures", -1, ["--allow-fixtures", "-1"]),
    ("plan", "allow_fixtures", 21, ["--allow-fixtures", "21"]),
    ("plan", "max", 1.5, ["--max", "1.5"]),
    ("simulate", "max_fixels", 0, ["--max-fixels", "0"]),
    ("simulate", "max_fixels", 21, ["--max-fixels", "21"]),
    ("simulate", "max_ticks", -1, ["--max-ticks", "-1"]),
]


def call(function, model, **kwargs):
    if function == "plan":
        return cairn.plan(model, **kwargs)
    return cairn.simulate(model, FIG1_PLAN, suggest_fixtures=True, **kwargs)


def command_line(function, option):
    if function == "plan":
        return ["plan", SCENE, *option]
    return ["simulate", FIG1, FIG1_PLAN, "--suggest-fixtures", *option]


@pytest.mark.parametrize("function,keyword,value,option", REFUSED)
def test_refused_as_the_cli_refuses(cli, stack3, fig1, function, keyword, value, option):
    code, out, err = cli(*command_line(function, option))
    assert code == 2 and out == "" and err.startswith("cairn: error: "), err
    model = stack3 if function == "plan" else fig1
    with pytest.raises(cairn.InputError) as e:
        call(function, model, **{keyword: value})
    assert e.value.json_path == keyword
    assert str(e.value).startswith(f"{keyword}: must be a whole number")
    assert repr(value) in str(e.value) or str(value) in str(e.value)


@pytest.mark.parametrize("function,keyword,value,option", [
    ("plan", "max", 0, ["--max", "0"]),
    ("plan", "threads", 0, ["--threads", "0"]),
    ("plan", "allow_fixtures", 20, ["--allow-fixtures", "20"]),
    ("simulate", "max_fixels", 1, ["--max-fixels", "1"]),
    ("simulate", "max_fixels", 20, ["--max-fixels", "20"]),
])
def test_the_ends_of_the_ranges_are_accepted_by_both(cli, stack3, fig1, function, keyword,
                                                      value, option):
    code, _, err = cli(*command_line(function, option))
    assert code in (0, 1), err
    model = stack3 if function == "plan" else fig1
    doc = call(function, model, **{keyword: value})
    assert doc["verdict"] if function == "simulate" else doc["sequences"]


def test_max_fixels_zero_is_an_input_error_not_an_assertion(fig1):
    with pytest.raises(cairn.InputError) as e:
        cairn.simulate(fig1, FIG1_PLAN, suggest_fixtures=True, max_fixels=0)
    assert type(e.value) is cairn.InputError
    assert str(e.value) == "max_fixels: must be a whole number from 1 to 20 (got 0)"


@pytest.mark.parametrize("function,kwargs,keyword", [
    ("plan", dict(max="3"), "max"),
    ("plan", dict(threads=None), "threads"),
    ("plan", dict(allow_fixtures=True), "allow_fixtures"),
    ("plan", dict(single_parts="no"), "single_parts"),
    ("plan", dict(max=2**40), "max"),
    ("simulate", dict(continue_after_failure=2), "continue_after_failure"),
    ("simulate", dict(max_ticks=2.5), "max_ticks"),
    ("margin", dict(friction=0.5), "friction"),
    ("margin", dict(tilt="1,0,0"), "tilt"),
    ("margin", dict(tilt=(1, "x", 0)), "tilt"),
    ("blocking", dict(direction=(0, "up")), "direction"),
    ("blocking", dict(direction=5), "direction"),
    ("blocking", dict(direction=(0, 1, 0, 0)), "direction"),
    ("load", dict(friction="high"), "friction"),
    ("load", dict(tolerance=[1]), "tolerance"),
    ("load", dict(gravity=(0, "down")), "gravity"),
])
def test_wrong_kinds_of_values_name_the_keyword(fig1, function, kwargs, keyword):
    with pytest.raises(cairn.InputError) as e:
        if function == "load":
            cairn.load(example("paper_fig1.json"), **kwargs)
        elif function == "simulate":
            cairn.simulate(fig1, FIG1_PLAN, **kwargs)
        else:
            getattr(cairn, function)(fig1, **kwargs)
    assert e.value.json_path == keyword
    assert str(e.value).startswith(f"{keyword}: ")


def test_whole_numbers_of_other_types_are_accepted(stack3):
    import numpy as np
    a = cairn.plan(stack3, max=np.int64(1), threads=1.0, allow_fixtures=np.int32(0))
    b = cairn.plan(stack3, max=1, threads=1)
    assert [s["steps"] for s in a["sequences"]] == [s["steps"] for s in b["sequences"]]


# ---- a cairn.Model that no loader made ----

UNMADE = """
import cairn
ms = [cairn.load({scene!r}) for _ in range(3)]; del ms
junk = list(range(10**6)); del junk
{body}
"""


def run_python(body):
    """Runs `body` in a fresh interpreter (a crash must not take pytest down):
    its exit code and output."""
    code = UNMADE.format(scene=example("stack3.json"), body=body)
    p = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                       cwd=SOURCE_DIR, timeout=120, check=False)
    return p.returncode, p.stdout, p.stderr


def test_model_new_is_refused():
    code, out, err = run_python("""
try:
    cairn.Model.__new__(cairn.Model)
except TypeError as e:
    print("TypeError:", e)
""")
    assert code == 0, err
    assert out.startswith("TypeError: this cairn.Model holds no model: make models with "
                          "cairn.load(file) or cairn.from_compas(data)"), out


def test_model_made_around_new_is_unusable():
    # Around the refusing __new__: the base type's, which makes the object.
    code, out, err = run_python("""
base = cairn.Model.__mro__[1]
m = base.__new__(cairn.Model)
for what in ("file", "name", "dimension", "parts", "fixed", "has_interfaces", "vertices"):
    try:
        getattr(m, what)
        print(what, "read")
    except TypeError as e:
        print(what, "TypeError", "holds no model" in str(e))
for name, call in [("repr", lambda: repr(m)), ("check", lambda: cairn.check(m)),
                   ("plan", lambda: cairn.plan(m)), ("blocking", lambda: cairn.blocking(m)),
                   ("blocking_direction", lambda: cairn.blocking(m, direction=(0, 1))),
                   ("margin", lambda: cairn.margin(m, friction=True)),
                   ("simulate", lambda: cairn.simulate(m, {scene!r})),
                   ("raw_check", lambda: cairn._cairn.check(m, [], "", False))]:
    try:
        call()
        print(name, "ran")
    except TypeError as e:
        print(name, "TypeError", "holds no model" in str(e))
""".replace("{scene!r}", repr(example("stack3.json"))))
    if "Model.__new__" in err and code != 0:
        pytest.fail(err)
    lines = out.splitlines()
    assert code == 0, err
    assert len(lines) == 15, out
    assert all(line.endswith("TypeError True") for line in lines), out


def test_not_a_model_is_a_type_error():
    with pytest.raises(TypeError, match="expected a cairn.Model"):
        cairn._cairn.check("examples/stack3.json", [], "", False)
    with pytest.raises(TypeError, match="expected a cairn.Model"):
        cairn.check("examples/stack3.json")


# ---- directions and axes: the CLI's resolvers ----


def cli_json(cli, *args):
    code, out, err = cli(*args, "--json")
    assert code in (0, 1), err
    return json.loads(out)


def test_blocking_direction_is_the_cli_blocking_direction(cli):
    fig1 = cairn.load(FIG1)  # as the CLI names it
    r = cairn.blocking(fig1, direction=(0, 1))
    assert r == cli_json(cli, "blocking", FIG1, "--direction", "0,1,0")
    assert len(r["cells"]) == 1 and r["cells"][0]["removable"] == ["C", "D"]
    # A 2-D direction may be given with its Z = 0, as the CLI takes it.
    assert cairn.blocking(fig1, direction=(0, 1, 0)) == r
    with pytest.raises(cairn.InputError) as e:
        cairn.blocking(fig1, direction=(0, 1, 1))
    assert e.value.json_path == "direction" and "(or X,Y,0)" in str(e.value)


@pytest.mark.parametrize("scale", [1e155, 1e300, 1e-300])
def test_blocking_direction_of_any_size_is_the_same_direction(fig1, scale):
    m9 = cairn.load(example("paper_fig9.json"))
    for m, d in ((fig1, (1, 0)), (fig1, (1, 1)), (m9, (1, 0, 0)), (m9, (0, -1, 1))):
        unit = cairn.blocking(m, direction=d)["cells"][0]
        scaled = cairn.blocking(m, direction=[scale * x for x in d])["cells"][0]
        assert scaled["removable"] == unit["removable"]
        assert scaled["infinity"] == unit["infinity"]
        assert scaled["direction"] == pytest.approx(unit["direction"], abs=1e-15)


@pytest.mark.parametrize("scale", [1e155, 1e300])
def test_margin_axis_and_direction_of_any_size_are_the_same(scale):
    m9 = cairn.load(example("paper_fig9.json"))
    tilt = cairn.margin(m9, tilt=(1, 0, 0))["margin"]
    big = cairn.margin(m9, tilt=(scale, 0, 0))["margin"]
    assert big["critical_deg"] == tilt["critical_deg"] and big["axis"] == tilt["axis"]
    m = cairn.load(example("stack3.json"))
    load = cairn.margin(m, load="A", point=(0, 1), direction=(1, 1))["margin"]
    big = cairn.margin(m, load="A", point=(0, 1), direction=(scale, scale))["margin"]
    assert big["critical"] == load["critical"] and big["direction"] == load["direction"]
