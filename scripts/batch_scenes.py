#!/usr/bin/env python3
"""Generates small 2-D scenes with verdicts known analytically, and the jobs
file of `cairn batch` that checks them (docs/batch.md, tests/cli/batch_command_test.cpp,
docs/benchmarks.md).

    python3 scripts/batch_scenes.py OUT N [--seed S]

writes OUT/scenes/NNNN.json, OUT/jobs.jsonl (one `check` job per scene, id
"NNNN") and OUT/expected.jsonl ({"id", "stable", "kind"}). Three kinds, in
turn:

- stack: blocks of different widths (density 1, frictionless) on a fixed
  table, each offset from the one below. Every contact is horizontal, so a
  stack stands iff, at every interface, the centroid of everything above lies
  inside the interface's interval [a, b] (the resultant of nonnegative normal
  forces lies in their hull).
- arch: two mirrored corbelled piers (blocks stepping inwards) and a lintel
  resting on both tops (frictionless). By symmetry (the equilibrium
  conditions are linear, a solution's mirror image is one, and so is their
  mean) each pier carries half the lintel's weight W/2, at a point p of its
  top interface it is free to choose. Level j (interface [a_j, b_j], mass M_j
  above it with centroid c_j) stands iff
      a_j ≤ (M_j c_j + W/2 p) / (M_j + W/2) ≤ b_j,
  an interval of p; the arch stands iff these intervals and the top interface
  have a common point.
- wall: a running-bond wall (half bricks at the ends of odd courses, μ = 0.5)
  with a brick laid across the end of its top course, overhanging by o. The
  wall under it is supported over every brick's full base, so the verdict is
  the overhanging brick's: stable iff its centroid is over the wall, o < L/2.

Cases closer to the boundary than MARGIN (a fraction of the block width) are
drawn again: the verdicts are far from the tolerances.
"""
import json
import os
import random
import sys

MARGIN = 0.05  # of the block width, in the length unit of the scenes (~1)


def box(name, x0, y0, x1, y1, fixed=False):
    part = {"name": name, "box": {"min": [round(x0, 6), round(y0, 6)],
                                  "max": [round(x1, 6), round(y1, 6)]}}
    if fixed:
        part["fixed"] = True
    return part


def stack(rng):
    while True:
        n = rng.randint(2, 6)
        h = rng.uniform(0.3, 1.0)
        blocks = []  # (left, right)
        x = 0.0
        for _ in range(n):
            w = rng.uniform(1.0, 2.0)
            blocks.append((x, x + w))
            x += rng.uniform(-0.45, 0.75) * w
        # Interface j below block j: with the table (block 0's base) or block j-1.
        verdicts = []
        ambiguous = False
        for j in range(n):
            a, b = blocks[j] if j == 0 else (max(blocks[j - 1][0], blocks[j][0]),
                                             min(blocks[j - 1][1], blocks[j][1]))
            if b - a < 0.1:
                ambiguous = True  # (nearly) not touching
                break
            mass = sum(r - l for l, r in blocks[j:])
            c = sum((r - l) * (l + r) / 2 for l, r in blocks[j:]) / mass
            inside = min(c - a, b - c)
            if abs(inside) < MARGIN:
                ambiguous = True
                break
            verdicts.append(inside > 0)
        if ambiguous:
            continue
        parts = [box("table", -20, -1, 20, 0, fixed=True)]
        for i, (l, r) in enumerate(blocks):
            parts.append(box("B%d" % i, l, i * h, r, (i + 1) * h))
        return {"cairn": 1, "name": "stack", "friction": 0, "parts": parts}, all(verdicts)


def arch(rng):
    while True:
        k = rng.randint(1, 4)
        h = rng.uniform(0.3, 0.8)
        pier = []  # left pier, (left, right)
        x = 0.0
        for _ in range(k):
            w = rng.uniform(1.0, 1.6)
            pier.append((x, x + w))
            x += rng.uniform(0.0, 0.6) * w
        top_l, top_r = pier[-1]
        overlap = rng.uniform(0.15, 0.9) * (top_r - top_l)
        gap = rng.uniform(0.2, 2.0)
        centre = max(r for _, r in pier) + gap / 2
        lintel = (top_r - overlap, 2 * centre - (top_r - overlap))
        hl = rng.uniform(0.2, 0.6)
        half = (lintel[1] - lintel[0]) * hl / 2  # W/2 (density 1)
        lo, hi = top_r - overlap, top_r  # where p may be
        for j in range(k):
            a, b = pier[0] if j == 0 else (max(pier[j - 1][0], pier[j][0]),
                                           min(pier[j - 1][1], pier[j][1]))
            mass = sum((r - l) * h for l, r in pier[j:])
            c = sum((r - l) * h * (l + r) / 2 for l, r in pier[j:]) / mass
            lo = max(lo, ((mass + half) * a - mass * c) / half)
            hi = min(hi, ((mass + half) * b - mass * c) / half)
        if abs(hi - lo) < MARGIN:
            continue
        parts = [box("ground", -20, -1, 40, 0, fixed=True)]
        for i, (l, r) in enumerate(pier):
            parts.append(box("L%d" % i, l, i * h, r, (i + 1) * h))
            parts.append(box("R%d" % i, 2 * centre - r, i * h, 2 * centre - l, (i + 1) * h))
        parts.append(box("lintel", lintel[0], k * h, lintel[1], k * h + hl))
        return {"cairn": 1, "name": "arch", "friction": 0, "parts": parts}, hi > lo


def wall(rng):
    while True:
        bricks = rng.randint(2, 4)  # per course
        courses = rng.randint(2, 5)
        length, height = 2.0, 0.5
        o = rng.uniform(0.1, 1.9)
        if abs(o - length / 2) < MARGIN * length:
            continue
        parts = [box("ground", -20, -1, 20, 0, fixed=True)]
        for c in range(courses):
            y = c * height
            edges = [i * length for i in range(bricks + 1)]
            if c % 2:
                edges = [0.0] + [length / 2 + i * length for i in range(bricks)] + [bricks * length]
            for i in range(len(edges) - 1):
                parts.append(box("c%db%d" % (c, i), edges[i], y, edges[i + 1], y + height))
        wall_end = bricks * length
        y = courses * height
        parts.append(box("overhang", wall_end + o - length, y, wall_end + o, y + height))
        return {"cairn": 1, "name": "wall", "friction": 0.5, "parts": parts}, o < length / 2


def main(argv):
    if len(argv) < 3:
        sys.exit("usage: batch_scenes.py OUT N [--seed S]")
    out, n = argv[1], int(argv[2])
    seed = int(argv[argv.index("--seed") + 1]) if "--seed" in argv else 19
    rng = random.Random(seed)
    os.makedirs(os.path.join(out, "scenes"), exist_ok=True)
    kinds = [("stack", stack), ("arch", arch), ("wall", wall)]
    with open(os.path.join(out, "jobs.jsonl"), "w") as jobs, \
            open(os.path.join(out, "expected.jsonl"), "w") as expected:
        for i in range(n):
            kind, make = kinds[i % len(kinds)]
            scene, stable = make(rng)
            scene["name"] = "%s %04d" % (kind, i)
            path = os.path.join(out, "scenes", "%04d.json" % i)
            with open(path, "w") as f:
                json.dump(scene, f, indent=1)
            ident = "%04d" % i
            jobs.write(json.dumps({"id": ident, "command": "check", "model": path}) + "\n")
            expected.write(json.dumps({"id": ident, "stable": stable, "kind": kind}) + "\n")


if __name__ == "__main__":
    main(sys.argv)
