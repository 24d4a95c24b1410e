#!/usr/bin/python3
"""The contact solver against its floor, on dense W taken from real scenes.

1. Each scene below runs a few steps with -pgs_dump_problem, which writes its first contact
   problem of at least the given size (the W the scheme built, dense) in the FCLIB layout;
   build/bench_pgs then times, in one run on that W, one solver sweep (the best of --repeat
   runs of exactly --sweeps sweeps, warm start 0, the default solver options: NNCG and the exact
   residual every 16 sweeps included) and one dense product W r (BLAS dgemv), and prints their
   ratio: the floor of a sweep is one pass over W.
2. The step of the 18k-DOF linear box with 300 contacts, explicit scheme, precomputed
   compliance, 30 sweeps: the mean time of a step (all phases but output) over the steps after
   the first (which computes the precomputed columns), per phase.

  /usr/bin/python3 scripts/bench_sweep.py [--sweeps 30] [--repeat 10] [--steps 8] [--markdown]
Needs build/fecontact and build/bench_pgs (scripts/build.sh). OPENBLAS_NUM_THREADS=1.
"""
import argparse
import os
import re
import subprocess
import sys

import h5py
import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
ENV = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1", OPENBLAS_NUM_THREADS="1")

# name, scene options, minimum rows of the problem to dump
SCENES = [
    ("Table 1 18k, linear box, explicit", ["-options_file", "input/table1_18k.opts", "-constraint_scheme", "explicit"], 900),
    ("co-rotational 18^3 cube resting (input/cube_rest.opts)", ["-options_file", "input/cube_rest.opts"], 900),
    ("Table 1 36k, linear box, explicit", ["-options_file", "input/table1_36k.opts", "-constraint_scheme", "explicit"], 1400),
]


def fecontact(args):
    subprocess.run([os.path.join(ROOT, "build", "fecontact")] + args + ["-quiet"], cwd=ROOT, env=ENV, check=True,
                   stdout=subprocess.DEVNULL)


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--sweeps", type=int, default=30)
    p.add_argument("--repeat", type=int, default=10)
    p.add_argument("--steps", type=int, default=8, help="steps of the 18k explicit precomputed run")
    p.add_argument("--markdown", action="store_true", help="print the tables as markdown")
    p.add_argument("--out", default=os.path.join(ROOT, "out", "bench_sweep"))
    a = p.parse_args()
    os.makedirs(a.out, exist_ok=True)
    rows = []
    for k, (name, opts, minrows) in enumerate(SCENES):
        prob = os.path.join(a.out, "problem%d.hdf5" % k)
        if os.path.exists(prob):
            os.remove(prob)
        fecontact(opts + ["-time_steps", "3", "-output_every", "3", "-output_file", os.path.join(a.out, "scene%d.h5" % k),
                          "-pgs_dump_problem", prob, "-pgs_dump_rows", str(minrows)])
        if not os.path.exists(prob):
            sys.exit("bench_sweep: %s gave no contact problem of %d rows or more" % (name, minrows))
        line = subprocess.run([os.path.join(ROOT, "build", "bench_pgs"), "-problem", prob, "-sweeps", str(a.sweeps),
                               "-repeat", str(a.repeat)], cwd=ROOT, env=ENV, check=True, capture_output=True,
                              text=True).stdout
        m = re.search(r"rows (\d+) contacts (\d+) dense sweep ([\d.]+) ms dgemv ([\d.]+) ms ratio ([\d.]+)", line)
        if not m:
            sys.exit("bench_sweep: unexpected bench_pgs output: " + line)
        rows.append((name, int(m.group(1)), int(m.group(2)), float(m.group(3)), float(m.group(4)), float(m.group(5))))
    if a.markdown:
        print("| W from | rows | contacts | one sweep (ms) | one dgemv (ms) | sweep / dgemv |")
        print("|---|---:|---:|---:|---:|---:|")
        for r in rows:
            print("| %s | %d | %d | %.3f | %.3f | %.2f |" % r)
    else:
        for r in rows:
            print("%-55s rows %5d contacts %4d  sweep %.3f ms  dgemv %.3f ms  ratio %.2f" % r)

    # 2. the 18k explicit precomputed step
    f = os.path.join(a.out, "step18k.h5")
    fecontact(["-options_file", "input/table1_18k.opts", "-constraint_scheme", "explicit", "-compliance_type",
               "precomputed", "-pgs_max_it", "30", "-time_steps", str(a.steps), "-output_every", str(a.steps),
               "-output_file", f])
    with h5py.File(f, "r") as h:
        t = h["steps/timing"]
        phases = [k for k in t if k != "output"]
        per = {k: float(np.mean(t[k][1:])) for k in phases}
        total = sum(per.values())
        sweeps = h["steps/pgs_iterations"][1:]
        rows18 = h["steps/constraint_rows"][1:]
    big = sorted(((v, k) for k, v in per.items() if v > 1e-4), reverse=True)
    if a.markdown:
        print("\n| 18k box, explicit, precomputed, %d sweeps, %d rows | ms per step |" % (sweeps.max(), rows18.max()))
        print("|---|---:|")
        print("| **total (all phases but output)** | **%.1f** |" % (1e3 * total))
        for v, k in big:
            print("| %s | %.1f |" % (k, 1e3 * v))
    else:
        print("18k box, explicit, precomputed, %d sweeps, %d rows: %.1f ms per step (mean of steps 2-%d): %s" % (
            sweeps.max(), rows18.max(), 1e3 * total, a.steps, ", ".join("%s %.1f" % (k, 1e3 * v) for v, k in big)))


if __name__ == "__main__":
    main()
