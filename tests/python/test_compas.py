"""COMPAS assemblies in (a dict, as json.load gives it) and Cairn's forces back
out (cairn.compas_forces), on the shared COMPAS files."""

import copy
import json

import numpy as np
import pytest

import cairn
from cairn._compas import _edges, _interfaces
from conftest import load_json, shared_file

G = np.array([0.0, 0.0, -9.81])  # COMPAS: -z, Cairn's 3-D default


def test_leaning_stack_falls_and_stands_without_the_top_three():
    data = load_json(shared_file("compas_assembly/stack_assembly.json"))
    m = cairn.from_compas(data, friction=0.84)
    assert m.parts == [str(k) for k in range(10)]  # node keys as names
    assert m.fixed == ["0"]                         # is_support
    r = cairn.check(m)
    assert not r["stable"] and "9" in r["moving"]
    r = cairn.check(m, without=[7, 8, 9])
    assert r["stable"] and r["without"] == ["7", "8", "9"]
    # The ground (block 0) carries the weight of blocks 1-6.
    arrays = r["contact_arrays"]
    on_ground = arrays["normal_force"][(arrays["parts"] == 0).any(axis=1)]
    weight = sum(p["mass"] for p in r["parts"] if not p["fixed"]) * 9.81
    assert on_ground.sum() == pytest.approx(weight, rel=1e-9)


def test_from_compas_equals_load_of_the_file():
    path = shared_file("compas_assembly/stack_assembly.json")
    by_file = cairn.check(cairn.load(path, format="compas", friction=0.84), without=["9"])
    by_dict = cairn.check(cairn.from_compas(load_json(path), friction=0.84), without=["9"])
    for key in ("verdict", "moving", "parts", "contacts", "components"):
        assert by_file[key] == by_dict[key], key


def test_friction_is_required():
    data = load_json(shared_file("compas_assembly/two-blocks_assembly.json"))
    with pytest.raises(cairn.InputError, match="--friction"):
        cairn.from_compas(data)


def balance(doc, r):
    """Per free block: |net force| and |net moment about its centroid| of its
    weight and the interface forces stored in `doc` (compas_cra's convention:
    the force on v is (c_np - c_nn) n + c_u xaxis + c_v yaxis, -that on u)."""
    parts = {p["name"]: p for p in r["parts"]}
    force = {k: p["mass"] * G for k, p in parts.items() if not p["fixed"]}
    moment = {k: np.zeros(3) for k in force}
    for u, v, data, points, x, y, n in _interfaces(_edges(doc)):
        assert len(data["forces"]) == len(points)
        for p, f in zip(points, data["forces"]):
            assert f["c_np"] >= 0 and f["c_nn"] == 0  # Cairn's forces never pull
            on_v = (f["c_np"] - f["c_nn"]) * n + f["c_u"] * x + f["c_v"] * y
            for block, sign in ((v, 1.0), (u, -1.0)):
                if block in force:
                    force[block] = force[block] + sign * on_v
                    c = np.asarray(parts[block]["centroid"])
                    moment[block] = moment[block] + np.cross(p - c, sign * on_v)
    return {k: (np.linalg.norm(force[k]), np.linalg.norm(moment[k])) for k in force}


# The compas_cra samples that store interfaces, with their example's supports.
STORED = [("concave-short.json", [0]), ("concave-long.json", [0]),
          ("cube-curve-short.json", [0]), ("cube-curve-tall.json", [0]),
          ("curve-3-blocks.json", [0]), ("armadillo_cra.json", None)]


@pytest.mark.parametrize("name,supports", STORED)
def test_compas_forces_balance_every_block(name, supports):
    data = load_json(shared_file("compas_cra/" + name))
    before = copy.deepcopy(data)
    m = cairn.from_compas(data, friction=0.84, supports=supports, interfaces="stored")
    r = cairn.check(m)
    assert r["stable"]
    out = cairn.compas_forces(data, r)
    assert data == before  # a copy was filled
    json.dumps(out)        # serialisable, as compas.rpc and Rhino need
    weight = max(p["mass"] for p in r["parts"]) * 9.81
    for block, (f, mo) in balance(out, r).items():
        assert f <= 1e-8 * weight, block
        assert mo <= 1e-7 * weight, block


def test_compas_forces_agree_with_compas_cras_own():
    """armadillo_cra.json stores compas_cra's forces: per free block, the net
    interface force of theirs and of Cairn's both hold the block up."""
    data = load_json(shared_file("compas_cra/armadillo_cra.json"))
    r = cairn.check(cairn.from_compas(data, friction=0.84, interfaces="stored"))
    ours = cairn.compas_forces(data, r)

    def net(doc):
        total = {}
        for u, v, d, points, x, y, n in _interfaces(_edges(doc)):
            for f in d["forces"] or []:
                on_v = (f["c_np"] - f["c_nn"]) * n + f["c_u"] * x + f["c_v"] * y
                total[v] = total.get(v, 0) + on_v
                total[u] = total.get(u, 0) - on_v
        return total

    theirs, mine = net(data), net(ours)
    free = [p["name"] for p in r["parts"] if not p["fixed"]]
    assert all(theirs[k][2] > 0 and mine[k][2] > 0 for k in free)


def test_compas_forces_of_detected_contacts():
    # The stack's stored interfaces are the faces Cairn finds: found contacts map too.
    data = load_json(shared_file("compas_assembly/stack_assembly.json"))
    r = cairn.check(cairn.from_compas(data, friction=0.84), without=[7, 8, 9])
    out = cairn.compas_forces(data, r)
    balances = balance(out, r)  # the blocks present: 1 to 6
    assert sorted(balances) == ["1", "2", "3", "4", "5", "6"]
    for block, (f, mo) in balances.items():
        assert f <= 1e-8 and mo <= 1e-8, block


class FakeCompasObject:
    """Stands in for a COMPAS object (no COMPAS here): `__dtype__` and
    `__data__`, nested as COMPAS 2 nests its data structures."""

    def __init__(self, dtype, data):
        self.__dtype__, self.__data__ = dtype, data


def as_objects(value):
    if isinstance(value, dict):
        if "dtype" in value and "data" in value:
            return FakeCompasObject(value["dtype"], as_objects(value["data"]))
        return {k: as_objects(v) for k, v in value.items()}
    if isinstance(value, list):
        return [as_objects(v) for v in value]
    return value


def test_from_compas_takes_the_assembly_object():
    data = load_json(shared_file("compas_assembly/stack_assembly.json"))
    assembly = as_objects(data)  # as assembly.__data__ would hold Graph and Mesh objects
    assert isinstance(assembly, FakeCompasObject)
    by_object = cairn.check(cairn.from_compas(assembly, friction=0.84), without=[7, 8, 9])
    by_dict = cairn.check(cairn.from_compas(data, friction=0.84), without=[7, 8, 9])
    assert by_object["contacts"] == by_dict["contacts"] and by_object["stable"]


def test_the_rule_decides_what_rigid_bodies_leave_open():
    # The H frame: an equilibrium exists (a squeeze), and loaded from rest on
    # compliant contacts the bar slides down (docs/loaded-from-rest.md).
    m = cairn.load(shared_file("compas_cra/H.json"), format="compas", friction=0.84,
                   supports=[0, 1])
    loaded = cairn.check(m)
    assert not loaded["stable"] and loaded["moving"] == ["2"]
    assert loaded["rule"] == "loaded-from-rest"
    assert loaded["loaded_from_rest"] == "gives way"
    assert loaded["static_equilibrium"] is True
    rbe = cairn.check(m, rule="equilibrium")
    assert rbe["stable"] and rbe["rule"] == "equilibrium" and rbe["stability"] != "strong"
    with pytest.raises(cairn.InputError, match="rule"):
        cairn.check(m, rule="rbe")
    # The margin takes the same rule: its verdict at the nominal μ is the
    # check's, and with the equilibrium rule its threshold is μ* itself.
    by_loading = cairn.margin(m, friction=True)["margin"]
    assert by_loading["holds_at_nominal"] and not by_loading["stands_at_nominal"]
    by_equilibrium = cairn.margin(m, friction=True, rule="equilibrium")["margin"]
    assert by_equilibrium["stands_at_nominal"] and by_equilibrium["rule"] == "equilibrium"
    assert by_equilibrium["verdict_critical"] == by_equilibrium["critical"]
    with pytest.raises(cairn.InputError, match="rule"):
        cairn.margin(m, friction=True, rule="rbe")
