#!/usr/bin/env python3
"""Fuzzing the command line's surfaces as a user meets them (fuzz/README.md).

Where a libFuzzer target would have to reach past a process boundary (STEP is
read in a child process; batch is a driver of files, timeouts and signals),
this runs the real `cairn` binary on mutated inputs, one process per case,
from a seeded generator:

  batch   a jobs file (every command, odd option values, junk lines) and an
          existing results file (valid lines, junk, no final newline), with
          --fresh, --resume or --retry-failed
  step    a part file of the Bourjault pen with lines deleted, NUL bytes put
          in, numbers made NaN / 1E400 / huge, references broken
  asap    the ASAP beam folder with config.json and OBJ lines mutated
  margin  margins on the bundled examples and the COMPAS files with odd
          axes, directions, points, parts and friction values
  html    check / simulate / plan / margin with --html on mutated scenes

The contract: exit 0, 1 or 3 (an answer), 2 (bad input: one line
"cairn: error: ..." on stderr), 5 (batch: a job timed out); never a signal,
a sanitizer report, exit 4, a hang past --timeout, an output written over an
input, or a page that is not whole. A finding prints the seed and the case's
folder, kept for replay.

    python3 fuzz/cli_fuzz.py --cairn build-test/cairn --surface step --seconds 1200
    python3 fuzz/cli_fuzz.py --cairn build-test/cairn --surface all --cases 10   # quick
"""

import argparse
import json
import os
import random
import re
import shutil
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
EXAMPLES = os.path.join(ROOT, "examples")
SHARED = os.environ.get("CAIRN_SHARED_DIR", os.path.join(os.path.dirname(ROOT), "shared"))
PEN = os.path.join(SHARED, "datasets", "aplan_bourjault_pen_simple")
ASAP = os.path.join(SHARED, "datasets", "asap_beam_assembly")
CRA = os.path.join(SHARED, "datasets", "compas_cra")
SMALL = ["stack3.json", "paper_fig1.json", "incline.json", "overhang_tips.json", "paper_fig9.json",
         "flush_joint.json", "peg_in_slot.json", "paper_fig6.json", "ladder.json"]
ODD = ["0", "-1", "1e155", "-1e155", "1e308", "5e-324", "1e-300", "nan", "inf", "1e400", "2147483648",
       "", "x", ",", "1,,2", "0.84", "3", "1,0", "1,0,0", "0,0,1", "1e155,1e155", "1e155,0,0",
       "0,0,0", "-1,2,-3", "é", "</script>"]
ENV = dict(os.environ, ASAN_OPTIONS="exitcode=86:detect_leaks=1",
           UBSAN_OPTIONS="halt_on_error=1:exitcode=87:print_stacktrace=1")
SANITIZER = re.compile(r"AddressSanitizer|LeakSanitizer|runtime error:|UndefinedBehaviorSanitizer")


class Finding(Exception):
    pass


def run(cairn, args, cwd, timeout):
    try:
        p = subprocess.run([cairn] + args, cwd=cwd, env=ENV, capture_output=True, text=True,
                           errors="replace", timeout=timeout, stdin=subprocess.DEVNULL)
    except subprocess.TimeoutExpired:
        raise Finding(f"a hang: no answer in {timeout} s: cairn " + " ".join(args))
    if p.returncode < 0:
        raise Finding(f"killed by signal {-p.returncode}")
    if SANITIZER.search(p.stderr):
        raise Finding("a sanitizer report:\n" + p.stderr[-3000:])
    if p.returncode == 4 or "internal error" in p.stderr:
        raise Finding("an internal error: " + p.stderr.strip()[-600:])
    if p.returncode not in (0, 1, 2, 3, 5):
        raise Finding(f"exit {p.returncode}: " + p.stderr.strip()[-600:])
    if p.returncode == 2:
        lines = p.stderr.strip().splitlines()
        errors = [l for l in lines if l.startswith("cairn: error: ")]
        if len(errors) != 1:
            raise Finding("bad input without exactly one 'cairn: error:' line: " + p.stderr[-600:])
    return p


def mutate_text(rng, text, numbers=True):
    lines = text.split("\n")
    for _ in range(rng.randint(1, 4)):
        k = rng.randrange(6 if numbers else 4)
        i = rng.randrange(len(lines))
        if k == 0:
            del lines[i]
            if not lines:
                lines = [""]
        elif k == 1:
            lines.insert(i, lines[rng.randrange(len(lines))])
        elif k == 2:
            j = rng.randrange(len(lines[i]) + 1)
            lines[i] = lines[i][:j] + rng.choice(["\0" * rng.randint(1, 100), "#", ")", "'", "(", ","]) + lines[i][j:]
        elif k == 3:
            j = rng.randrange(len(lines[i]) + 1)
            lines[i] = lines[i][:j]
        else:
            nums = list(re.finditer(r"-?\d+\.?\d*(?:[eE][-+]?\d+)?", lines[i]))
            if nums:
                m = rng.choice(nums)
                new = rng.choice(["NAN", "1.E400", "-1.E400", "1E308", "0.", "1E-320", "#999999",
                                  "INF", "-0.", "1E155", str(rng.randint(-10**6, 10**6))])
                lines[i] = lines[i][:m.start()] + new + lines[i][m.end():]
    return "\n".join(lines)


def mutate_json(rng, doc):
    doc = json.loads(json.dumps(doc))
    for _ in range(rng.randint(1, 3)):
        node, trail = doc, []
        for _ in range(rng.randint(1, 5)):
            if isinstance(node, dict) and node:
                key = rng.choice(sorted(node))
            elif isinstance(node, list) and node:
                key = rng.randrange(len(node))
            else:
                break
            trail.append((node, key))
            node = node[key]
        if trail:
            parent, key = trail[-1]
            parent[key] = rng.choice([None, True, -1, 0, 1e308, 1e-320, "x", [], {}, [1, 2],
                                      float("nan"), 1e155, "A", ["A", ""], 2**63])
    return doc


# ---- surfaces --------------------------------------------------------------------

def case_step(rng, cairn, work, timeout):
    part = rng.choice(["body", "button", "cap", "cartridge", "head", "ink"])
    text = open(os.path.join(PEN, part + ".stp"), errors="replace").read()
    path = os.path.join(work, part + ".stp")
    with open(path, "w") as f:
        f.write(mutate_text(rng, text))
    cmd = rng.choice([["check"], ["blocking", "--direction", "1,0,0"], ["convert"]])
    args = cmd[:1] + [path] + (["out.json"] if cmd[0] == "convert" else []) + cmd[1:] + ["--format", "step"]
    run(cairn, args, work, timeout)


def case_asap(rng, cairn, work, timeout):
    folder = os.path.join(work, "asap")
    shutil.copytree(ASAP, folder, ignore=shutil.ignore_patterns("*.txt", "*.md"))
    if rng.random() < 0.5:
        cfg = json.load(open(os.path.join(folder, "config.json")))
        with open(os.path.join(folder, "config.json"), "w") as f:
            f.write(json.dumps(mutate_json(rng, cfg)) if rng.random() < 0.8 else mutate_text(rng, json.dumps(cfg, indent=1)))
    else:
        name = rng.choice(["0", "1", "2", "3", "6"])
        p = os.path.join(folder, name + ".obj")
        text = open(p).read()
        with open(p, "w") as f:
            f.write(mutate_text(rng, text))
    extra = rng.choice([[], ["--tolerance", "1e-4"], ["--tolerance", rng.choice(ODD)], ["--fixed", "6"]])
    # The whole NDBG of the beams' 40 000 facets takes minutes (one cell per
    # facet normal); one direction reads and checks the same geometry.
    cmd = rng.choice([["check"], ["blocking", "--direction", "0,0,1"]])
    run(cairn, cmd[:1] + [folder, "--format", "asap"] + cmd[1:] + extra, work, timeout)


def an_example(rng):
    return os.path.join(EXAMPLES, rng.choice(SMALL))


def case_margin(rng, cairn, work, timeout):
    if rng.random() < 0.25 and os.path.isdir(CRA):
        f = rng.choice(["cubes.json", "type-a.json", "type-b.json", "curve-3-blocks.json", "H.json",
                        "cube-curve-short.json", "concave-short.json"])
        model = [os.path.join(CRA, f), "--format", "compas", "--supports", "0",
                 "--friction", rng.choice(["0.84", "0.3", "0", "1e-9", "1000"])]
        if rng.random() < 0.3:
            model += ["--interfaces", "stored"]
    else:
        model = [an_example(rng)]
    q = rng.randrange(4)
    if q == 0:
        args = ["--friction"]
    elif q == 1:
        args = ["--tilt", rng.choice(ODD[17:24] + ["1,0,0", "0,1,0", "0,0,1", "0,0,-1", "1,1,1"])]
    else:
        args = ["--load", rng.choice(["A", "B", "C", "D", "block", "x"]), "--point",
                rng.choice(["0,1", "0,0,0", "1,1,1", "1e155,0", "nan,0"]), "--direction",
                rng.choice(ODD[17:24] + ["1,0", "0,1", "-1,0"])]
    if rng.random() < 0.2:
        args += ["--gravity", rng.choice(["0,0", "0,-9.81", "0,0,-9.81", "0,0,0", "1e308,0"])]
    if rng.random() < 0.3:
        args += ["--json"]
    run(cairn, ["margin"] + model + args, work, timeout)


def mutated_example(rng, work):
    src = an_example(rng)
    doc = json.load(open(src))
    if rng.random() < 0.7:
        doc = mutate_json(rng, doc)
    path = os.path.join(work, os.path.basename(src))
    with open(path, "w") as f:
        json.dump(doc, f)
    return path


def page_is_whole(path):
    page = open(path, encoding="utf-8", errors="replace").read()
    m = re.search(r'<script id="cairn-data" type="application/json">(.*?)</script', page, re.S)
    if not page.rstrip().endswith("</html>") or not m:
        raise Finding("the page is not whole")
    json.loads(m.group(1))


def case_html(rng, cairn, work, timeout):
    scene = mutated_example(rng, work)
    page = os.path.join(work, "page.html")
    cmd = rng.choice(["check", "check", "plan", "margin", "simulate"])
    if cmd == "simulate":
        args = ["simulate", os.path.join(EXAMPLES, "paper_fig1.json"),
                os.path.join(EXAMPLES, "plans", "paper_fig1_b_first.plan.json")]
    elif cmd == "plan":
        args = ["plan", scene, "--max", "1", "--threads", "1"]
    elif cmd == "margin":
        args = ["margin", scene, "--friction"]
    else:
        args = ["check", scene] + rng.choice([[], ["--without", "A"], ["--without", "A,,B"]])
    p = run(cairn, args + ["--html", page], work, timeout)
    if os.path.exists(page):
        if p.returncode == 2:
            raise Finding("a page written although the input was refused")
        page_is_whole(page)
    if not os.path.exists(scene):
        raise Finding("the scene is gone")


JOB_TEMPLATES = [
    {"command": "check", "model": "stack3.json"},
    {"command": "check", "model": "paper_fig1.json", "options": {"without": "C"}},
    {"command": "blocking", "model": "paper_fig9.json", "options": {"direction": "1,0,0"}},
    {"command": "simulate", "model": "paper_fig1.json", "plan": "plans/paper_fig1_b_first.plan.json"},
    {"command": "plan", "model": "stack3.json", "options": {"max": 1, "threads": 1}},
    {"command": "margin", "model": "stack3.json", "options": {"friction": ""}},
    {"command": "margin", "model": "paper_fig9.json", "options": {"tilt": "1,0,0"}},
]


def case_batch(rng, cairn, work, timeout):
    for f in ("stack3.json", "paper_fig1.json", "paper_fig9.json"):
        shutil.copy(os.path.join(EXAMPLES, f), work)
    os.makedirs(os.path.join(work, "plans"), exist_ok=True)
    shutil.copy(os.path.join(EXAMPLES, "plans", "paper_fig1_b_first.plan.json"), os.path.join(work, "plans"))
    lines = []
    for i in range(rng.randint(1, 5)):
        job = dict(rng.choice(JOB_TEMPLATES), id=f"j{i}")
        if rng.random() < 0.5:
            job = mutate_json(rng, job)
        text = json.dumps(job)
        if rng.random() < 0.15:
            text = mutate_text(rng, text, numbers=True)
        lines.append(text)
    jobs = "\n".join(lines) + ("\n" if rng.random() < 0.8 else "")
    with open(os.path.join(work, "jobs.jsonl"), "w") as f:
        f.write(jobs)
    mode = rng.choice(["--fresh", "--resume", "--retry-failed", None])
    if mode != "--fresh" and rng.random() < 0.7:
        results = [json.dumps({"id": f"j{i}", "exit": rng.choice([0, 1, 2, 4, 5])}) for i in range(rng.randint(0, 3))]
        text = "\n".join(results)
        if rng.random() < 0.3:
            text = mutate_text(rng, text)
        if rng.random() < 0.7:
            text += "\n"
        with open(os.path.join(work, "results.jsonl"), "w") as f:
            f.write(text)
    before = open(os.path.join(work, "jobs.jsonl")).read()
    args = ["batch", "jobs.jsonl", "-o", "results.jsonl", "--threads", "1",
            "--job-timeout", rng.choice(["20", "1e308", "0.001", "9.3e9"])]
    if mode:
        args.append(mode)
    p = run(cairn, args, work, timeout)
    if open(os.path.join(work, "jobs.jsonl")).read() != before:
        raise Finding("the jobs file was changed")
    if p.returncode in (0, 1, 5) and os.path.exists(os.path.join(work, "results.jsonl")):
        for n, line in enumerate(open(os.path.join(work, "results.jsonl")), 1):
            try:
                json.loads(line)
            except ValueError:
                raise Finding(f"results line {n} is not JSON after exit {p.returncode}")


SURFACES = {"batch": case_batch, "step": case_step, "asap": case_asap, "margin": case_margin,
            "html": case_html}


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--cairn", required=True)
    ap.add_argument("--surface", default="all", choices=sorted(SURFACES) + ["all"])
    ap.add_argument("--seconds", type=float, default=0)
    ap.add_argument("--cases", type=int, default=20, help="cases per surface, when --seconds is 0")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--timeout", type=float, default=120, help="seconds one case may take")
    ap.add_argument("--keep", default=os.path.join(tempfile.gettempdir(), "cairn_cli_fuzz_findings"))
    args = ap.parse_args()
    cairn = os.path.abspath(args.cairn)
    surfaces = sorted(SURFACES) if args.surface == "all" else [args.surface]
    needs = {"step": PEN, "asap": ASAP}
    total = findings = 0
    for s in surfaces:
        if s in needs and not os.path.isdir(needs[s]):
            print(f"cli_fuzz: {s}: skipped ({needs[s]} is absent)")
            continue
        start, n, seed = time.time(), 0, args.seed
        while (time.time() - start < args.seconds) if args.seconds else n < args.cases:
            rng = random.Random(f"{s}:{seed}")
            work = tempfile.mkdtemp(prefix=f"cairn_fuzz_{s}_")
            try:
                SURFACES[s](rng, cairn, work, args.timeout)
                shutil.rmtree(work)
            except Finding as e:
                findings += 1
                os.makedirs(args.keep, exist_ok=True)
                kept = os.path.join(args.keep, f"{s}_{seed}")
                shutil.rmtree(kept, ignore_errors=True)
                shutil.move(work, kept)
                print(f"FINDING {s} seed {seed} (case kept in {kept}): {e}", flush=True)
            n += 1
            seed += 1
        total += n
        print(f"cli_fuzz: {s}: {n} cases in {time.time() - start:.0f} s", flush=True)
    print(f"cli_fuzz: {total} cases, {findings} findings" + ("" if findings else ": no finding"))
    sys.exit(1 if findings else 0)


if __name__ == "__main__":
    main()
