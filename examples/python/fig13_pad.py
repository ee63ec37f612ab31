"""Paper Fig. 13 (3-D, Figs. 9-12): C slid along +X over B's edge, held up by
the gripper's pad G (0 to 25 s), then A (25 to 65 s) and B lifted, per pair of
parts (the forces at the corners of a 3-D face are not determined, their sums
are). C rests on B and on the pad, which carries its share of C's weight all
along the path; the table carries A, B and the rest of C, then B alone, then
nothing; nothing breaks (stable). Units of C's weight.

    PYTHONPATH=build/python python3 examples/python/fig13_pad.py -o fig13.png
"""

import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import paper_figure  # noqa: E402

import cairn  # noqa: E402


def figure():
    s = paper_figure.simulate("paper_fig9.json", "paper_fig9_cab_plus_x_pad.plan.json",
                              normalize="C")
    return s, cairn.plot.timeline(s, contacts="pair",
                                  title="Fig. 13: C along +X on the pad (weight of C)")


if __name__ == "__main__":
    paper_figure.main(figure, __doc__, "fig13.png")
