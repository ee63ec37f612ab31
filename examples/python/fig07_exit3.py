"""Paper Fig. 7: C slid left along E towards exit III (Fig. 6). The table's
force at vertex 17 (-0.5, 0) grows and at vertex 18 (0.5, 0) falls, to zero at
C's x = -8.25; at the next tick E tips (the dashed line). Units of C's weight.

    PYTHONPATH=build/python python3 examples/python/fig07_exit3.py -o fig07.png
"""

import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import paper_figure  # noqa: E402

import cairn  # noqa: E402


def figure():
    s = paper_figure.simulate("paper_fig6.json", "paper_fig6_c_exit3.plan.json", normalize="C")
    return s, cairn.plot.timeline(s, contacts="point", parts=["table"],
                                  title="Fig. 7: C towards exit III (weight of C)")


if __name__ == "__main__":
    paper_figure.main(figure, __doc__, "fig07.png")
