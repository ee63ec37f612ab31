#!/usr/bin/env python3
"""Fuzzing the Python module's surface (fuzz/README.md, "The Python module").

Every public function of `cairn` is called with arguments drawn from a seeded
generator: the bundled examples and mutations of them (as files and as
dicts), and for every keyword values of every kind a user might pass (None,
negative, zero, huge, NaN, infinite, huge vectors, empty and odd strings,
lists of the wrong length, nested junk), plus models made without
``__init__``. The contract is the CLI's: bad input raises ``cairn.InputError``
(or ``TypeError`` for an argument of the wrong Python type, pybind11's answer);
anything else escaping -- another exception, a crash, a hang -- is a finding.

Each round runs in a child interpreter, so a crash is seen (and its seed
printed) instead of ending the run:

    python3 fuzz/python_fuzz.py --module build/python --seconds 1200
    python3 fuzz/python_fuzz.py --module build/python --rounds 4 --calls 60   # the test suite's replay

A finding prints the seed and the call; `--seed S --calls N --verbose` in one
round replays it.
"""

import argparse
import inspect
import json
import math
import os
import random
import subprocess
import sys
import tempfile
import time

from cli_fuzz import mutate_json  # beside this file: the same mutations of JSON data

HERE = os.path.dirname(os.path.abspath(__file__))
EXAMPLES = os.path.join(os.path.dirname(HERE), "examples")
SMALL = ["stack3.json", "paper_fig1.json", "incline.json", "overhang_tips.json",
         "paper_fig9.json", "flush_joint.json", "peg_in_slot.json"]
PLANS = ["plans/paper_fig1_b_first.plan.json"]

ODD_NUMBERS = [0, -1, 1, 2, 3, 7, -0.0, 0.5, 1e-320, 5e-324, 1e155, -1e155, 1e308, -1e308,
               float("nan"), float("inf"), -float("inf"), 2**31, 2**63, -(2**63), 10**30]
ODD_STRINGS = ["", " ", "A", "B", "C", "table", "x", "--", ",", "A,,B", "\x00", "é🧱",
               "</script>", "../../etc/passwd", "/dev/zero", "/", "a" * 300, "friction",
               "tilt", "load", "detect", "stored", "scene", "compas", "step", "asap", "axes",
               "ndbg", "full", "none", "both", "strong"]


def odd_value(rng, depth=0):
    kind = rng.randrange(10 if depth < 2 else 6)
    if kind == 0:
        return None
    if kind == 1:
        return rng.choice([True, False])
    if kind == 2:
        return rng.choice(ODD_NUMBERS)
    if kind == 3:
        return rng.choice(ODD_STRINGS)
    if kind == 4:
        return rng.randint(-5, 50)
    if kind == 5:
        return rng.uniform(-10, 10)
    if kind == 6:  # a vector, maybe of the wrong length or with odd entries
        n = rng.choice([0, 1, 2, 3, 3, 3, 4])
        return [rng.choice(ODD_NUMBERS + [0, 1, -1]) for _ in range(n)]
    if kind == 7:
        return [rng.choice(ODD_STRINGS) for _ in range(rng.randrange(4))]
    if kind == 8:
        return {rng.choice(ODD_STRINGS): odd_value(rng, depth + 1) for _ in range(rng.randrange(3))}
    return tuple(odd_value(rng, depth + 1) for _ in range(rng.randrange(4)))


def run_round(module_dir, seed, calls, verbose):
    sys.path.insert(0, module_dir)
    import cairn  # noqa: E402

    rng = random.Random(seed)
    tmp = tempfile.mkdtemp(prefix="cairn_pyfuzz_")
    functions = {name: getattr(cairn, name) for name in
                 ("load", "from_compas", "check", "simulate", "plan", "blocking", "margin",
                  "compas_forces", "read_timeline")}
    models = [cairn.load(os.path.join(EXAMPLES, f)) for f in SMALL]

    def a_model():
        r = rng.random()
        if r < 0.05:
            try:
                return cairn.Model.__new__(cairn.Model)  # never initialised
            except TypeError:  # refused: models are made by load and from_compas
                return odd_value(rng)
        if r < 0.1:
            return odd_value(rng)
        if r < 0.2:  # a mutated scene, loaded
            doc = mutate_json(rng, json.load(open(os.path.join(EXAMPLES, rng.choice(SMALL)))))
            path = os.path.join(tmp, "m.json")
            with open(path, "w") as f:
                json.dump(doc, f, allow_nan=True)
            try:
                return cairn.load(path)
            except (cairn.InputError, TypeError):  # refused: the mutation broke the scene
                return rng.choice(models)
        return rng.choice(models)

    def argument(name):
        r = rng.random()
        if name in ("m", "model"):
            return a_model()
        if name in ("file", "plan", "source") and r < 0.6:
            pool = SMALL if name == "file" else PLANS
            return os.path.join(EXAMPLES, rng.choice(pool))
        if name in ("without", "keep", "supports", "load", "normalize") and r < 0.5:
            return rng.choice([["A"], ["B"], "C", ["table"], ["A", "B"]])
        if name in ("direction", "tilt", "point", "gravity") and r < 0.5:
            scale = rng.choice([1, 1e-300, 1e155, 1e300])
            return [scale * rng.choice([-1, 0, 1]) for _ in range(rng.choice([2, 3]))]
        if name in ("max", "threads") and r < 0.3:
            return rng.choice([1, 2])
        if name in ("html", "timeline", "dot", "emit_plans"):  # outputs: the scratch folder only
            return os.path.join(tmp, "out." + name) if r < 0.5 else None
        return odd_value(rng)

    for i in range(calls):
        name = rng.choice(sorted(functions))
        fn = functions[name]
        params = [p for p in inspect.signature(fn).parameters.values()
                  if p.kind in (p.POSITIONAL_OR_KEYWORD, p.KEYWORD_ONLY)]
        kwargs = {}
        for p in params:
            required = p.default is inspect.Parameter.empty
            if required or rng.random() < 0.4:
                kwargs[p.name] = argument(p.name)
        if name == "plan":  # keep the search small
            kwargs["max"] = 1
            kwargs.setdefault("threads", 1)
            if not isinstance(kwargs.get("threads"), int) or not 1 <= kwargs["threads"] <= 2:
                kwargs["threads"] = 1
        call = f"cairn.{name}(" + ", ".join(f"{k}={v!r}" for k, v in kwargs.items()) + ")"
        if verbose:
            print(f"  [{seed}:{i}] {call}"[:400], flush=True)
        try:
            fn(**kwargs)
        except (cairn.InputError, TypeError):
            pass
        except Exception as e:  # a finding
            print(f"FINDING seed={seed} call {i}: {call}\n  {type(e).__name__}: {e}", flush=True)
            return 1
    return 0


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--module", required=True, help="folder holding the cairn package")
    ap.add_argument("--seconds", type=float, default=0, help="run rounds for this long")
    ap.add_argument("--rounds", type=int, default=1, help="rounds, when --seconds is 0")
    ap.add_argument("--calls", type=int, default=40, help="calls per round")
    ap.add_argument("--seed", type=int, default=1, help="the first round's seed")
    ap.add_argument("--round-timeout", type=float, default=300, help="seconds a round may take")
    ap.add_argument("--verbose", action="store_true")
    ap.add_argument("--child", action="store_true", help=argparse.SUPPRESS)
    args = ap.parse_args()
    if args.child:
        sys.exit(run_round(args.module, args.seed, args.calls, args.verbose))
    start, seed, rounds, findings = time.time(), args.seed, 0, 0
    while (time.time() - start < args.seconds) if args.seconds else rounds < args.rounds:
        cmd = [sys.executable, os.path.abspath(__file__), "--child", "--module", args.module,
               "--seed", str(seed), "--calls", str(args.calls)] + (["--verbose"] if args.verbose else [])
        try:
            rc = subprocess.run(cmd, timeout=args.round_timeout).returncode
        except subprocess.TimeoutExpired:
            rc = "timeout"
        if rc != 0:
            findings += 1
            why = "a hang" if rc == "timeout" else ("a crash (signal %d)" % -rc if rc < 0 else "above")
            print(f"python_fuzz: round with seed {seed} ended with {why}; replay: "
                  f"--seed {seed} --calls {args.calls} --rounds 1 --verbose", flush=True)
        seed += 1
        rounds += 1
    print(f"python_fuzz: {rounds} rounds of {args.calls} calls, {findings} with a finding"
          + ("" if findings else ": no finding"), flush=True)
    sys.exit(1 if findings else 0)


if __name__ == "__main__":
    main()
