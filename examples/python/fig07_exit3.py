"""Paper Fig. 7: C slid left along E towards exit III (Fig. 6). The table's
force at vertex 17 (-0.5, 0) grows and at vertex 18 (0.5, 0) falls, to zero at
C's x = -8.25; at the next tick E tips (the dashed line). Units of C's weight.

    PYTHONPATH=build/python python3 examples/python/fig07_exit3.py -o fig07.png
"""
import argparse
import os

import cairn

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")


def figure():
    m = cairn.load(os.path.join(ROOT, "examples", "paper_fig6.json"))
    s = cairn.simulate(m, os.path.join(ROOT, "examples", "plans", "paper_fig6_c_exit3.plan.json"),
                       normalize="C")
    ax = cairn.plot.timeline(s, contacts="point", parts=["table"],
                             title="Fig. 7: C towards exit III (weight of C)")
    return s, ax


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("-o", "--output", default="fig07.png")
    s, ax = figure()
    ax.figure.savefig(parser.parse_args().output, dpi=150)
