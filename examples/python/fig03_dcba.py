"""Paper Fig. 3: the contact forces of Fig. 1's blocks along the stable
sequence D-C-B-A, in units of B's weight. Each block's forces drop to zero as
it is lifted; every other force stays positive.

    PYTHONPATH=build/python python3 examples/python/fig03_dcba.py -o fig03.png
"""
import argparse
import os

import cairn

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")


def figure():
    m = cairn.load(os.path.join(ROOT, "examples", "paper_fig1.json"))
    s = cairn.simulate(m, os.path.join(ROOT, "examples", "plans", "paper_fig1_dcba.plan.json"),
                       normalize="B")
    ax = cairn.plot.timeline(s, contacts="pair", title="Fig. 3: D-C-B-A (weight of B)")
    return s, ax


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("-o", "--output", default="fig03.png")
    s, ax = figure()
    ax.figure.savefig(parser.parse_args().output, dpi=150)
