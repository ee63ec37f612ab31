"""cairn.margin: the dict equals `cairn margin --json` for the same inputs,
and its answers are the closed forms of tests/stability/margin_test.cpp."""

import json
import math

import pytest

import cairn
from conftest import example, shared_file


def cli_margin(cli, *args):
    code, out, err = cli("margin", *args, "--json")
    assert code in (0, 1), err
    return json.loads(out)


@pytest.mark.parametrize("scene,kwargs,args", [
    ("examples/incline.json", dict(friction=True), ["--friction"]),
    ("examples/incline_slides.json", dict(friction=True), ["--friction"]),
    ("examples/ladder.json", dict(friction=True), ["--friction"]),
    ("examples/ladder.json", dict(tilt=(0, 0, 1)), ["--tilt", "0,0,1"]),
    ("examples/overhang.json", dict(tilt=[0, 0, -1]), ["--tilt", "0,0,-1"]),
    ("examples/paper_fig16.json", dict(load="Q", point=(5, 1.5), direction=(0, -1)),
     ["--load", "Q", "--point", "5,1.5", "--direction", "0,-1"]),
    ("examples/paper_fig1.json", dict(friction=True, without=["C"]), ["--friction", "--without", "C"]),
])
def test_margin_equals_cli(cli, scene, kwargs, args):
    r = cairn.margin(cairn.load(scene), **kwargs)
    assert r == cli_margin(cli, scene, *args)


def test_margin_closed_forms():
    r = cairn.margin(cairn.load(example("incline.json")), friction=True)["margin"]
    assert r["quantity"] == "friction"
    assert r["critical"] == pytest.approx(math.tan(math.radians(20)), abs=1e-5)
    t = cairn.margin(cairn.load(example("overhang.json"), friction=3), tilt=(0, 0, 1))["margin"]
    assert t["critical_deg"][0] == pytest.approx(-math.degrees(math.atan(0.8)), abs=1e-5)
    assert t["critical_deg"][1] == pytest.approx(math.degrees(math.atan(2.0)), abs=1e-5)


def test_margin_compas_wedge():
    path = shared_file("compas_cra/type-c.json")
    m = cairn.load(path, format="compas", friction=0.84, supports=[0, 1])
    r = cairn.margin(m, tilt=(0, 1, 0))["margin"]
    assert r["critical_deg"][1] == pytest.approx(65.71, abs=0.01)


def test_margin_bad_input():
    m = cairn.load(example("incline.json"))
    with pytest.raises(cairn.InputError):
        cairn.margin(m)
    with pytest.raises(cairn.InputError):
        cairn.margin(m, friction=True, tilt=(0, 0, 1))
    with pytest.raises(cairn.InputError):
        cairn.margin(m, load="incline", point=(0, 0), direction=(1, 0))
    with pytest.raises(cairn.InputError):
        cairn.margin(m, tilt="abc")
