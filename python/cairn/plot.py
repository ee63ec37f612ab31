"""Figures of Cairn's results with matplotlib (imported only when used):
contact force against time, as the paper's Figs. 3, 5, 7-8, 13, 16, 18 and 20
draw it, and a 2-D scene with its contact forces as arrows.

    s = cairn.simulate(m, "examples/plans/paper_fig1_c_first.plan.json")
    ax = cairn.plot.timeline(s, parts=["B"])          # one line per pair
    ax.figure.savefig("fig3.png")

From the command line, for a ``cairn simulate --timeline`` CSV:

    python3 -m cairn.plot TIMELINE.csv -o fig.png [--contacts pair|patch] [--parts A,B]
"""

import argparse
import sys

import numpy as np

__all__ = ["timeline_series", "timeline", "scene", "main"]


def _pyplot():
    import matplotlib.pyplot as plt  # only when a figure is drawn
    return plt


def timeline_series(s, contacts="pair", parts=None, normalize=None, force="normal_force"):
    """The data :func:`timeline` draws: {label: (time, force)}, the force of
    each contact pair (or patch) summed over its contact points per time step
    (the timeline has one row per tick and contact point), 0 at the time steps
    where the pair does not touch (also at the ticks after the last part left
    everything, which the timeline has no row for: ``s["steps"]`` counts
    them). ``s`` is :func:`cairn.simulate`'s result (or a dict with its
    ``timeline``).

    - ``contacts``: "pair" (one line per pair of parts), "patch" (3-D: per
      pair and contact patch, as numbered at each tick), "point" (per pair and
      contact point, as the paper's vertices 17 and 18: for contacts that do
      not move), or a list of pairs [("A", "E"), ...] to draw (in either order).
    - ``parts``: only contacts that touch one of these parts.
    - ``normalize``: divide every force by this number (a weight; or run the
      simulation with ``normalize="A"`` for units of A's weight).
    - ``force``: the column summed, "normal_force" (default) or, in 2-D,
      "friction_force"; in 3-D the friction force's norm with "friction".
    """
    t = s["timeline"] if "timeline" in s else s
    a, b = t["part_a"], t["part_b"]
    if force == "friction" and "friction_x" in t:
        values = np.sqrt(t["friction_x"] ** 2 + t["friction_y"] ** 2 + t["friction_z"] ** 2)
    else:
        values = np.asarray(t[force], dtype=float)
    if normalize is not None:
        if isinstance(normalize, str):
            raise TypeError("normalize: a number here; for a part's weight, simulate with "
                            f"normalize={normalize!r}")
        values = values / float(normalize)

    # The time steps, in order: (step, tick) pairs as the rows give them, and
    # their times.
    row_times = dict(zip(zip(t["step"].tolist(), t["tick"].tolist()), t["time"].tolist()))
    ticks = _with_ticks_without_contacts(list(row_times), s.get("steps", []), row_times)
    row_tick = {k: i for i, k in enumerate(ticks)}
    times = np.array([row_times[k] for k in ticks], dtype=float)

    wanted = None
    dim = 3 if "z" in t else 2
    coords = np.stack([t["x"], t["y"]] + ([t["z"]] if dim == 3 else []), axis=1)
    if contacts not in ("pair", "patch", "point"):
        wanted = {frozenset(map(str, pair)) for pair in contacts}
    keep_parts = None if parts is None else {str(p) for p in parts}
    series = {}
    for i in range(len(values)):
        pair = frozenset((a[i], b[i]))
        if wanted is not None and pair not in wanted:
            continue
        if keep_parts is not None and not (pair & keep_parts):
            continue
        label = f"{a[i]}–{b[i]}"
        if contacts == "patch" and "patch" in t:
            key = (pair, int(t["patch"][i]))
            label += f" patch {int(t['patch'][i])}"
        elif contacts == "point":
            point = tuple(float(f"{c:.6g}") for c in coords[i])
            key = (pair, point)
            label += " at (" + ", ".join(f"{c:g}" for c in point) + ")"
        else:
            key = pair
        if key not in series:
            series[key] = (label, np.zeros(len(ticks)))
        series[key][1][row_tick[(int(t["step"][i]), int(t["tick"][i]))]] += values[i]
    return {label: (times, f) for label, f in series.values()}


def _with_ticks_without_contacts(ticks, steps, times):
    """The timeline has no row at a tick without contacts: once the last part
    is lifted off everything, a step's remaining ticks are missing. Adds them
    (where the simulation's `steps` say how many ticks a step had), at the
    step's even spacing from start_time to end_time, so that the forces drop
    to 0 there instead of the line ending at the last loaded tick."""
    out = []
    last_of_step = {}
    for k, (st, tk) in enumerate(ticks):
        last_of_step[st] = k
    extra = {}
    for step in steps:
        st, n = step["index"], step["time_steps"]
        recorded = [tk for (s2, tk) in ticks if s2 == st]
        if st not in last_of_step or n <= max(recorded) + 1 or n < 2:
            continue
        dt = (step["end_time"] - step["start_time"]) / (n - 1)
        extra[st] = [(st, tk) for tk in range(max(recorded) + 1, n)]
        for key in extra[st]:
            times[key] = step["start_time"] + key[1] * dt
    for k, key in enumerate(ticks):
        out.append(key)
        if last_of_step.get(key[0]) == k:
            out.extend(extra.get(key[0], []))
    return out


def timeline(s, contacts="pair", parts=None, normalize=None, force="normal_force", ax=None,
             title=None, unit=None):
    """Draws contact force against time (:func:`timeline_series`), one line
    per pair or patch, and returns the matplotlib Axes (its lines' data are
    the series)."""
    plt = _pyplot()
    if ax is None:
        _, ax = plt.subplots(figsize=(6.4, 4.0))
    for label, (times, f) in timeline_series(s, contacts, parts, normalize, force).items():
        ax.plot(times, f, label=label, drawstyle="default", marker=".", markersize=3)
    ax.set_xlabel("time (s)")
    if unit is None:
        unit = s.get("force_unit", "force units") if normalize is None else "normalised"
    ax.set_ylabel(f"{force.replace('_', ' ')} ({unit})")
    if title:
        ax.set_title(title)
    failure = s.get("failure")
    if failure:
        ax.axvline(failure["time"], color="0.5", linestyle="--", linewidth=0.8)
    ax.legend(fontsize="small")
    ax.grid(True, linewidth=0.3)
    return ax


def scene(r, m=None, ax=None, scale=None):
    """Draws a 2-D :func:`cairn.check` result: each contact's force (normal
    plus friction, on part a) as an arrow at its point, the parts' centroids
    and names, and, given the model ``m``, the parts' outlines. Returns the
    Axes; ``scale`` is the arrow length of a unit force (default: the largest
    force is a fifth of the scene's size)."""
    if r.get("dimension") != 2:
        raise ValueError("cairn.plot.scene draws 2-D scenes")
    plt = _pyplot()
    if ax is None:
        _, ax = plt.subplots(figsize=(6.4, 4.8))
    names = [p["name"] for p in r["parts"]]
    if m is not None:
        for name, points in zip(m.parts, m.vertices):
            if name in names:
                fixed = name in m.fixed
                xy = np.asarray(points)
                ax.fill(xy[:, 0], xy[:, 1], facecolor="0.85" if fixed else "0.95",
                        edgecolor="0.3", linewidth=0.8)
    for p in r["parts"]:
        x, y = p["centroid"]
        color = "tab:red" if p.get("moving") else "0.2"
        ax.plot([x], [y], marker="+", color=color)
        ax.annotate(p["name"], (x, y), textcoords="offset points", xytext=(3, 3), color=color)
    arrays = r["contact_arrays"]
    n = arrays["normal"]
    t = np.stack([-n[:, 1], n[:, 0]], axis=1)
    f = arrays["normal_force"][:, None] * n + arrays["friction_force"][:, None] * t
    pts = arrays["point"]
    if len(pts):
        size = np.ptp(np.vstack([pts] + [np.asarray([p["centroid"]]) for p in r["parts"]]), axis=0)
        biggest = np.max(np.linalg.norm(f, axis=1))
        if scale is None:
            scale = 0.2 * max(size.max(), 1e-12) / biggest if biggest > 0 else 1.0
        ax.quiver(pts[:, 0], pts[:, 1], f[:, 0] * scale, f[:, 1] * scale, angles="xy",
                  scale_units="xy", scale=1, color="tab:blue", width=0.004)
    ax.set_aspect("equal")
    verdict = r.get("verdict", "")
    ax.set_title(f"{r.get('scene', '')}: {verdict}", fontsize="small")
    return ax


def main(argv=None):
    parser = argparse.ArgumentParser(
        prog="python3 -m cairn.plot",
        description="Contact force against time from a `cairn simulate --timeline` CSV.")
    parser.add_argument("csv", help="the timeline CSV")
    parser.add_argument("-o", "--output", required=True, help="the figure (png, pdf, svg)")
    parser.add_argument("--contacts", default="pair", choices=("pair", "patch", "point"))
    parser.add_argument("--parts", default=None, help="only contacts of these parts: A,B")
    parser.add_argument("--normalize", type=float, default=None, help="divide forces by this")
    parser.add_argument("--force", default="normal_force")
    parser.add_argument("--title", default=None)
    args = parser.parse_args(argv)
    from . import read_timeline
    try:
        columns = read_timeline(args.csv)
    except (OSError, ValueError) as e:  # InputError, or not text at all
        parser.exit(2, f"cairn.plot: error: {e}\n")
    parts = None if args.parts is None else args.parts.split(",")
    ax = timeline({"timeline": columns}, contacts=args.contacts, parts=parts,
                  normalize=args.normalize, force=args.force, title=args.title,
                  unit="force units" if args.normalize is None else "normalised")
    ax.figure.tight_layout()
    ax.figure.savefig(args.output, dpi=150)
    return 0


if __name__ == "__main__":
    sys.exit(main())
