"""The paper's Fig. 1 through the Python module: the assembly stands, B
topples without C, the C-first plan is unstable, D-C-B-A is the only stable
sequence of single parts; forces balance the weights."""

import numpy as np
import pytest

import cairn
from conftest import example

GRAVITY = np.array([0.0, -1.0])  # examples/paper_fig1.json: g = 1


@pytest.fixture(scope="module")
def fig1():
    return cairn.load(example("paper_fig1.json"))


MODEL_PARTS = ["E", "A", "B", "C", "D"]


def wrench_balance(r, gravity):
    """Per movable part: the net force and moment about its centroid of its
    weight and the contact forces of `contact_arrays` (2-D)."""
    arrays = r["contact_arrays"]
    n = arrays["normal"]
    t = np.stack([-n[:, 1], n[:, 0]], axis=1)  # docs/cli.md: tangent (-n_y, n_x)
    force_on_a = arrays["normal_force"][:, None] * n + arrays["friction_force"][:, None] * t
    out = {}
    for p in r["parts"]:
        if p["fixed"]:
            continue
        i = MODEL_PARTS.index(p["name"])  # contact_arrays["parts"] indexes the model's parts
        c = np.asarray(p["centroid"])
        f = p["mass"] * gravity
        moment = 0.0
        for k, (a, b) in enumerate(arrays["parts"]):
            sign = 1.0 if a == i else -1.0 if b == i else 0.0
            fk = sign * force_on_a[k]
            d = arrays["point"][k] - c
            f = f + fk
            moment += d[0] * fk[1] - d[1] * fk[0]
        out[p["name"]] = (f, moment)
    return out


def test_stands_and_forces_balance_weights(fig1):
    assert fig1.parts == MODEL_PARTS and fig1.fixed == ["E"] and fig1.dimension == 2
    assert repr(fig1).startswith('<cairn.Model "paper Fig. 1') and "(2-D, 5 parts)" in repr(fig1)
    r = cairn.check(fig1)
    assert r["stable"] and r["verdict"] == "stable" and r["moving"] == []
    arrays = r["contact_arrays"]
    n = len(r["contacts"])
    assert arrays["point"].shape == (n, 2) and arrays["normal"].shape == (n, 2)
    assert arrays["normal_force"].shape == (n,) and arrays["parts"].shape == (n, 2)
    assert np.all(arrays["normal_force"] >= 0)
    for name, (f, moment) in wrench_balance(r, GRAVITY).items():
        assert np.allclose(f, 0, atol=1e-9), name
        assert abs(moment) < 1e-9, name
    # The table carries the whole weight: 2 + 3 + 1.5 + 3 = 9.5.
    on_table = arrays["normal_force"][arrays["parts"][:, 1] == 0].sum()
    assert on_table == pytest.approx(sum(p["mass"] for p in r["parts"] if not p["fixed"]))
    assert on_table == pytest.approx(9.5)


def test_topples_without_c(fig1):
    r = cairn.check(fig1, without=["C"])
    assert not r["stable"]
    assert "B" in r["moving"]
    b = next(p for p in r["parts"] if p["name"] == "B")
    assert b["moving"] and b["motion"] == "tips"
    assert r["without"] == ["C"]
    # Without D it stands (x̄ = -0.75 over A).
    assert cairn.check(fig1, without="D")["stable"]


def test_normalize_divides_by_the_weight(fig1):
    plain = cairn.check(fig1)["contact_arrays"]["normal_force"]
    r = cairn.check(fig1, normalize="A")  # A's weight: 2
    assert r["force_unit"] == "weight of A"
    assert np.allclose(r["contact_arrays"]["normal_force"], plain / 2)


def test_c_first_plan_is_unstable(fig1):
    s = cairn.simulate(fig1, example("plans", "paper_fig1_c_first.plan.json"))
    assert not s["stable"] and s["verdict"] == "unstable"
    assert s["failure"]["verdict"] == "unstable" and "B" in s["failure"]["parts"]
    assert s["failure"]["time"] == pytest.approx(1.0)
    t = s["timeline"]
    assert set(t) >= {"time", "step", "tick", "part_a", "part_b", "normal_force", "breaks"}
    assert len({len(v) for v in t.values()}) == 1 and len(t["time"]) > 0
    # At tick 0, before C moves, the table carries every weight.
    first = (t["tick"] == 0) & (t["part_b"] == "E")
    assert t["normal_force"][first].sum() == pytest.approx(9.5)


def test_plan_as_a_dict_equals_the_file(fig1):
    from conftest import load_json
    path = example("plans", "paper_fig1_dcba.plan.json")
    by_file = cairn.simulate(fig1, path)
    by_dict = cairn.simulate(fig1, load_json(path))
    assert by_file["stable"] and by_dict["stable"]
    assert by_file["steps"] == by_dict["steps"]
    for k in by_file["timeline"]:
        assert np.array_equal(by_file["timeline"][k], by_dict["timeline"][k])


def test_plan_single_parts_finds_exactly_dcba(fig1):
    p = cairn.plan(fig1, single_parts=True)
    assert p["complete"]
    sequences = [[step["remove"] for step in s["steps"]] for s in p["sequences"]]
    assert sequences == [[["D"], ["C"], ["B"], ["A"]]]
    assert p["sequences"][0]["invertible"]


def test_blocking(fig1):
    b = cairn.blocking(fig1)
    assert b["dimension"] == 2 and b["cells"]
    up = cairn.blocking(fig1, direction=[0, 1])
    assert len(up["cells"]) == 1
    assert "D" in up["cells"][0]["removable"] and "A" not in up["cells"][0]["removable"]
