#!/usr/bin/env python3
"""Writes a 2-D pyramid of 2 x 1 bricks (gaps 0.1 within a row, each brick
over the gap of two below) on a fixed ground, for `cairn plan` benchmarks
(docs/benchmarks.md, bench/mpi_bench.sh).

    python3 bench/pyramid_scene.py OUT.json ROWS [FRICTION]

ROWS: bricks per row from the bottom, e.g. 5,4,3,2,1 (15 bricks, 16 parts
with the ground)."""
import json
import sys


def main(argv):
    out, rows = argv[1], [int(r) for r in argv[2].split(",")]
    friction = float(argv[3]) if len(argv) > 3 else 0.0
    width = 2.0 * rows[0] + 2
    parts = [{"name": "ground", "fixed": True, "box": {"min": [-2, -1], "max": [width, 0]}}]
    for r, n in enumerate(rows):
        x0 = r * 1.0  # each row starts half a brick in
        for i in range(n):
            left = x0 + 2.0 * i + 0.05
            parts.append({"name": "r%d_%d" % (r, i),
                          "box": {"min": [round(left, 6), r], "max": [round(left + 1.9, 6), r + 1]}})
    scene = {"cairn": 1, "friction": friction, "gravity": [0, -9.81],
             "name": "a pyramid of %d bricks 2 x 1 (rows %s, gaps 0.1), friction %g"
                     % (sum(rows), "-".join(map(str, rows)), friction),
             "parts": parts}
    with open(out, "w") as f:
        json.dump(scene, f, indent=1)


if __name__ == "__main__":
    main(sys.argv)
