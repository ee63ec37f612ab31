"""What the figure scripts here share: running a bundled example's plan, and
the command line `-o FILE` that saves the figure."""
import argparse
import os

import cairn

EXAMPLES = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")


def simulate(scene, plan, normalize):
    """cairn.simulate of examples/SCENE along examples/plans/PLAN, forces in
    units of the weight of the part `normalize`."""
    m = cairn.load(os.path.join(EXAMPLES, scene))
    return cairn.simulate(m, os.path.join(EXAMPLES, "plans", plan), normalize=normalize)


def main(figure, doc, default_output):
    """Draws `figure()` (which returns the simulation and the Axes) and saves it."""
    parser = argparse.ArgumentParser(description=doc.splitlines()[0])
    parser.add_argument("-o", "--output", default=default_output)
    output = parser.parse_args().output
    _, ax = figure()
    ax.figure.tight_layout()
    ax.figure.savefig(output, dpi=150)
