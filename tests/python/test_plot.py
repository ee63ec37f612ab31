"""cairn.plot and examples/python: the plotted data are the simulation's
timeline summed per pair (or point) and time step, and obey the physics."""

import os
import runpy
import subprocess
import sys
from collections import defaultdict

import numpy as np
import pytest

import cairn
from conftest import SOURCE_DIR, example

pytest.importorskip("matplotlib")


def plotted(ax):
    """{label: (x, y)} of the Axes' data lines (not the failure marker)."""
    return {line.get_label(): (np.asarray(line.get_xdata(), dtype=float),
                               np.asarray(line.get_ydata(), dtype=float))
            for line in ax.get_lines() if not line.get_label().startswith("_")}


def reference(s, key_of):
    """Sums of normal_force per (key, time step), row by row, with 0 where a
    key has no row: what timeline() should draw, computed independently."""
    t = s["timeline"]
    steps = []
    sums = defaultdict(lambda: defaultdict(float))
    for i in range(len(t["time"])):
        tick = (int(t["step"][i]), int(t["tick"][i]), float(t["time"][i]))
        if tick not in steps:
            steps.append(tick)
        key = key_of(t, i)
        if key is not None:
            sums[key][tick] += float(t["normal_force"][i])
    times = np.array([time for _, _, time in steps])
    return {k: (times, np.array([v.get(tick, 0.0) for tick in steps])) for k, v in sums.items()}


def by_pair(t, i):
    return f"{t['part_a'][i]}–{t['part_b'][i]}"


def run_example(name):
    return runpy.run_path(os.path.join(SOURCE_DIR, "examples", "python", name))["figure"]()


def assert_same(lines, ref):
    # Labels may name a pair either way round: match by the unordered pair.
    def norm(label):
        head, _, rest = label.partition(" at ")
        return (frozenset(head.split("–")), rest)
    ref = {norm(k): v for k, v in ref.items()}
    assert sorted(map(norm, lines), key=str) == sorted(ref, key=str)
    for label, (x, y) in lines.items():
        rx, ry = ref[norm(label)]
        n = len(rx)
        assert np.array_equal(x[:n], rx), label
        assert np.allclose(y[:n], ry, rtol=0, atol=1e-12), label
        # Ticks after the last part has left everything have no rows: drawn at 0.
        assert np.all(y[n:] == 0), label


def test_fig03_dcba():
    s, ax = run_example("fig03_dcba.py")
    assert s["stable"] and s["force_unit"] == "weight of B"
    lines = plotted(ax)
    assert_same(lines, reference(s, by_pair))
    # The table carries everything at first: (2 + 3 + 1.5 + 3) / 3 weights of B.
    x, y = lines["A–E"]
    assert y[0] == pytest.approx(9.5 / 3)
    # While D is lifted (step 0) the forces between the others stay positive.
    t = s["timeline"]
    ticks_of_step0 = len(set(t["tick"][t["step"] == 0].tolist()))
    for pair in ("A–E", "A–B", "B–C"):
        _, f = lines[pair]
        assert np.all(f[:ticks_of_step0] > 0), pair
    # D's contact (with B) drops to zero once D is lifted and stays there.
    _, f_bd = lines["B–D"]
    assert f_bd[0] == pytest.approx(1.0) and f_bd[-1] == 0
    # A's weight (2/3 of B's) on the table until A is lifted too, then nothing,
    # to the end of the plan (ticks the timeline has no rows for).
    x, f_ae = lines["A–E"]
    assert x[-1] == s["steps"][-1]["end_time"] == 24
    assert f_ae[x < 18][-1] == pytest.approx(2 / 3) and np.all(f_ae[x > 18] == 0)


def test_fig07_exit3():
    s, ax = run_example("fig07_exit3.py")
    assert s["verdict"] == "unstable" and "E" in s["failure"]["parts"]
    assert s["failure"]["time"] == pytest.approx(5.4)
    lines = plotted(ax)

    def by_point(t, i):
        if "table" not in (t["part_a"][i], t["part_b"][i]):
            return None
        return f"{t['part_a'][i]}–{t['part_b'][i]} at ({t['x'][i]:g}, {t['y'][i]:g})"
    assert_same(lines, reference(s, by_point))
    x, f17 = lines["E–table at (-0.5, 0)"]
    _, f18 = lines["E–table at (0.5, 0)"]
    before = x < s["failure"]["time"]
    # Together they carry E, A, B, C and D: (13 + 4 * 2) / 2 weights of C.
    assert np.allclose((f17 + f18)[before], 21 / 2)
    # 17 grows and 18 falls as C moves left, 18 nearly to zero before E tips.
    assert np.all(np.diff(f17[before]) > 0) and np.all(np.diff(f18[before]) < 0)
    assert f18[before][-1] < 0.1 and f18[0] == pytest.approx(21 / 4)


def test_fig13_pad_3d():
    s, ax = run_example("fig13_pad.py")
    assert s["stable"]
    lines = plotted(ax)
    assert_same(lines, reference(s, by_pair))
    x, table = lines["B–table"]
    _, pad = lines["C–G"]
    step0 = x < 25
    # Frictionless, horizontal faces: the table and the pad carry A, B and C:
    # (1.5 + 4 + 3.75) / 3.75 weights of C.
    assert np.allclose((table + pad)[step0], 9.25 / 3.75)
    # After C and A are gone, the table carries B alone, until B is lifted too
    # (the third step, from 65 s).
    assert table[x == 65][-1] == pytest.approx(4 / 3.75)
    assert x[-1] == 105 and np.all(table[x > 65] == 0)


def test_patch_and_parts_selection():
    m = cairn.load(example("paper_fig9.json"))
    s = cairn.simulate(m, example("plans", "paper_fig9_cab_minus_y.plan.json"))
    series = cairn.plot.timeline_series(s, contacts="patch", parts=["A"])
    assert series and all("A" in label.split(" ")[0].split("–") for label in series)
    pairs = cairn.plot.timeline_series(s, contacts=[("table", "B")])
    assert list(pairs) == ["B–table"]
    total = sum(f for _, f in cairn.plot.timeline_series(s, contacts="patch",
                                                         parts=["table"]).values())
    assert np.allclose(total, pairs["B–table"][1])
    halved = cairn.plot.timeline_series(s, contacts=[("table", "B")], normalize=2.0)
    assert np.allclose(halved["B–table"][1], pairs["B–table"][1] / 2)


def test_scene_draws_each_contact_force():
    m = cairn.load(example("paper_fig1.json"))
    r = cairn.check(m, without=["C"])
    ax = cairn.plot.scene(r, m)
    quiver = [c for c in ax.collections if hasattr(c, "U")][0]
    arrays = r["contact_arrays"]
    assert np.allclose(np.asarray(quiver.X), arrays["point"][:, 0])
    arrows = np.stack([quiver.U, quiver.V], axis=1)
    # Frictionless: each arrow is its normal force along its normal, scaled alike.
    expected = arrays["normal_force"][:, None] * arrays["normal"]
    scale = np.linalg.norm(arrows, axis=1).max() / np.linalg.norm(expected, axis=1).max()
    assert np.allclose(arrows, expected * scale)
    assert len(ax.patches) == len(r["parts"])  # the outlines of the parts present


def test_plot_command_line(cli, tmp_path):
    csv, png = tmp_path / "t.csv", tmp_path / "fig.png"
    code, _, _ = cli("simulate", "examples/paper_fig6.json",
                     "examples/plans/paper_fig6_c_exit3.plan.json", "--timeline", str(csv),
                     "--normalize", "C")
    assert code == 1
    p = subprocess.run([sys.executable, "-m", "cairn.plot", str(csv), "-o", str(png),
                        "--contacts", "point", "--parts", "table"],
                       capture_output=True, text=True, check=False)
    assert p.returncode == 0, p.stderr
    with open(png, "rb") as f:
        assert f.read(8) == b"\x89PNG\r\n\x1a\n"
    # What it drew is what the module draws from the simulation itself.
    s = cairn.simulate(cairn.load(example("paper_fig6.json")),
                       example("plans", "paper_fig6_c_exit3.plan.json"), normalize="C")
    from_csv = cairn.plot.timeline_series({"timeline": cairn.read_timeline(str(csv))},
                                          contacts="point", parts=["table"])
    direct = cairn.plot.timeline_series(s, contacts="point", parts=["table"])
    assert list(from_csv) == list(direct)
    for k in direct:
        assert np.array_equal(from_csv[k][1], direct[k][1])
    bad = subprocess.run([sys.executable, "-m", "cairn.plot", str(png), "-o", str(png)],
                         capture_output=True, text=True, check=False)
    assert bad.returncode == 2 and "timeline" in bad.stderr
