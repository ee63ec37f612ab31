"""Paper Fig. 3: the contact forces of Fig. 1's blocks along the stable
sequence D-C-B-A, in units of B's weight. Each block's forces drop to zero as
it is lifted; every other force stays positive.

    PYTHONPATH=build/python python3 examples/python/fig03_dcba.py -o fig03.png
"""

import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import paper_figure  # noqa: E402

import cairn  # noqa: E402


def figure():
    s = paper_figure.simulate("paper_fig1.json", "paper_fig1_dcba.plan.json", normalize="B")
    return s, cairn.plot.timeline(s, contacts="pair",
                                  title="Fig. 3: D-C-B-A (weight of B)")


if __name__ == "__main__":
    paper_figure.main(figure, __doc__, "fig03.png")
