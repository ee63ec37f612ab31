"""Bad input raises cairn.InputError (a ValueError) whose str() is the CLI's
message: the file, the JSON path and what is wrong."""

import copy

import pytest

import cairn
from conftest import example, load_json, shared_file


def test_bad_scene_names_the_file_and_the_json_path(cli):
    path = "examples/bad/self_intersecting.json"
    with pytest.raises(cairn.InputError) as e:
        cairn.load(path)
    assert isinstance(e.value, ValueError)
    assert e.value.file == path
    assert e.value.json_path == 'parts[1] ("bow-tie").polygon'
    assert e.value.message == "self-intersecting: edge 1 crosses edge 3"
    assert str(e.value) == f'{path}: parts[1] ("bow-tie").polygon: ' + e.value.message
    # The same line as the CLI's, after its "cairn: error: ".
    code, out, err = cli("check", path)
    assert code == 2 and out == ""
    assert err == f"cairn: error: {e.value}\n"


@pytest.mark.parametrize("name,path", [
    ("overlapping_parts.json", 'parts[2] ("B")'),
    ("mixed_dimensions.json", 'parts[1] ("cube").box'),
    ("fixture_off_part.json", "fixtures[0].point"),
])
def test_every_bad_scene(name, path):
    with pytest.raises(cairn.InputError) as e:
        cairn.load(example("bad", name))
    assert e.value.json_path == path and path in str(e.value)


def test_unknown_part_and_bad_plan():
    m = cairn.load(example("paper_fig1.json"))
    with pytest.raises(cairn.InputError, match="no part named 'Q'"):
        cairn.check(m, without=["Q"])
    plan = load_json(example("plans", "paper_fig1_c_first.plan.json"))
    bad = copy.deepcopy(plan)
    bad["steps"][0]["remove"] = ["Q"]
    with pytest.raises(cairn.InputError) as e:
        cairn.simulate(m, bad)
    assert e.value.file == "plan" and e.value.json_path.startswith("steps[0]")
    with pytest.raises(cairn.InputError):
        cairn.load(example("paper_fig1.json"), format="step")


def test_bad_compas_dict_names_the_json_path():
    data = load_json(shared_file("compas_assembly/two-blocks_assembly.json"))
    node = data["data"]["graph"]["data"]["node"]
    key = sorted(node)[0]
    del node[key]["block"]["data"]["face"]
    with pytest.raises(cairn.InputError) as e:
        cairn.from_compas(data, friction=0.5)
    assert e.value.file == "assembly_data"
    assert e.value.json_path.startswith(f"data.graph.data.node.{key}")


def test_bad_arguments_of_the_python_api():
    m = cairn.load(example("paper_fig1.json"))
    with pytest.raises(cairn.InputError) as e:
        cairn.blocking(m, direction=[0, 0])
    assert e.value.json_path == "direction" and str(e.value).startswith("direction: ")
    with pytest.raises(cairn.InputError) as e:
        cairn.load(example("paper_fig1.json"), interfaces="found")
    assert e.value.json_path == "interfaces"
    with pytest.raises(cairn.InputError) as e:
        cairn.read_timeline(example("paper_fig1.json"))
    assert e.value.file.endswith("paper_fig1.json") and "timeline" in e.value.message


def test_max_ticks_as_the_cli(cli):
    scene, plan = "examples/paper_fig1.json", "examples/plans/paper_fig1_dcba.plan.json"
    with pytest.raises(cairn.InputError) as e:
        cairn.simulate(cairn.load(scene), plan, max_ticks=2)
    code, out, err = cli("simulate", scene, plan, "--max-ticks", "2")
    assert code == 2 and out == "" and err == f"cairn: error: {e.value}\n"
    assert cairn.simulate(cairn.load(scene), plan, max_ticks=7)["stable"]


# What the Python fuzzer (fuzz/python_fuzz.py) found: helpers that took any
# object and failed inside with AttributeError, IndexError or a bare
# ValueError. Bad input is InputError; an argument of the wrong type TypeError.
def test_read_timeline_refuses_what_is_not_a_timeline(tmp_path):
    import io
    for wrong in ([], 7, False, None):
        with pytest.raises(TypeError, match="a path or a text file object"):
            cairn.read_timeline(wrong)
    with pytest.raises(cairn.InputError, match="cannot read the file"):
        cairn.read_timeline(str(tmp_path / "absent.csv"))
    with pytest.raises(cairn.InputError, match="not a regular file"):
        cairn.read_timeline(str(tmp_path))  # a folder
    with pytest.raises(cairn.InputError, match="NUL byte"):
        cairn.read_timeline("\x00")
    with pytest.raises(cairn.InputError, match="not a regular file"):
        cairn.read_timeline("/dev/zero")  # read until memory ran out
    with pytest.raises(cairn.InputError, match="not a Cairn timeline CSV"):
        cairn.read_timeline(io.BytesIO(b"time,step\n0,1\n"))  # a binary file
    with pytest.raises(cairn.InputError) as e:
        cairn.read_timeline(io.StringIO("time,step\n0.5,1\n0.6\n"))
    assert e.value.json_path == "line 3"
    assert "1 fields where the header has 2" in e.value.message
    with pytest.raises(cairn.InputError) as e:
        cairn.read_timeline(io.StringIO("time,step\n0.5,x\n"))
    assert e.value.json_path == "step"


def test_compas_forces_refuses_what_is_not_its_data():
    r = cairn.check(cairn.load(example("stack3.json")))
    with pytest.raises(TypeError, match="the dict cairn.check returns"):
        cairn.compas_forces({}, ["step"])
    with pytest.raises(cairn.InputError, match="not a result of cairn.check"):
        cairn.compas_forces({}, {"dimension": 3})
    for data in (False, [1, 2], {"graph": {"edge": {"0": {"1": {"interfaces": [{}]}}}}}):
        with pytest.raises(cairn.InputError):
            cairn.compas_forces(data, dict(r, dimension=3))
    with pytest.raises(cairn.InputError, match="not of a 3-D"):
        cairn.compas_forces({}, r)
