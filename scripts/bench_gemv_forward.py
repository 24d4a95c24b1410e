#!/usr/bin/python3
"""dgemm with one column as dgemv (src/util/blas.c, -blas_gemv_forward) against every dgemm to the
BLAS library, in one binary: the 36k Table 1 box (linear: after step 1 a step is two solves with
the kept factor and the contact phases) and the co-rotational 17.5k cube at rest (refactored every
step), fast scheme, 5 Newton iterations, on 1 and 2 ranks. Each repeat runs off then on, one after
the other, so that both see the machine in the same state. Reported per run: the mean wall time of
the steps after the first (/steps/wall_time), the time in MUMPS' solves (-log_view's SchurSolve,
summed over the run, largest rank) and in its numeric factorizations (SchurNumeric), and the final
positions' distance between off and on (relative, matched by reference coordinates).

  /usr/bin/python3 scripts/bench_gemv_forward.py [--repeat 2] [--steps 6] [--ranks 1,2]
(docs/benchmarks.md, "One-column products")"""
import argparse
import csv
import os
import subprocess
import sys
import tempfile
import time

import h5py
import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
EXE = os.path.join(ROOT, "build", "fecontact")
ENV = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1", OPENBLAS_NUM_THREADS="1")
sys.path.insert(0, os.path.join(ROOT, "tests"))
from fctest import sorted_positions  # noqa: E402

EVENTS = ("SchurSolve", "SchurNumeric")
SCENES = [("36k box", ["-options_file", "input/table1_36k.opts"], "box"),
          ("cube at rest 17.5k", ["-options_file", "input/cube_rest.opts"], "cube")]


def run(args, np_, steps, forward, f):
    """The mean wall time of steps 2.., and EVENTS' times over the run (largest rank, -log_view's CSV)"""
    log = f[:-3] + ".csv"
    cmd = [EXE] + args + ["-constraint_scheme", "fast", "-newton_max_it", "5", "-time_steps", str(steps), "-output_every",
                          str(steps), "-quiet", "-output_file", f, "-blas_gemv_forward", "1" if forward else "0",
                          "-log_view", ":%s:ascii_csv" % log]
    if np_ > 1:
        cmd = ["mpirun", "-n", str(np_), "--oversubscribe"] + cmd
    subprocess.run(cmd, cwd=ROOT, env=ENV, check=True)
    ev = dict.fromkeys(EVENTS, float("nan"))
    with open(log) as fl:
        for row in csv.reader(fl):
            if len(row) > 4 and row[0] == "Main Stage" and row[1] in ev:
                ev[row[1]] = np.fmax(ev[row[1]], float(row[4]))
    with h5py.File(f, "r") as h:
        wall = float(h["steps/wall_time"][1:].mean())
    return wall, ev


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--repeat", type=int, default=2)
    ap.add_argument("--steps", type=int, default=6)
    ap.add_argument("--ranks", default="1,2")
    a = ap.parse_args()
    tmp = tempfile.mkdtemp(prefix="gemv-forward-")
    print("`/usr/bin/python3 scripts/bench_gemv_forward.py --repeat %d --steps %d --ranks %s` on %s "
          "(`OPENBLAS_NUM_THREADS=1`; times in s):\n" % (a.repeat, a.steps, a.ranks, time.strftime("%Y-%m-%d")))
    print("| scene | ranks | repeat | steps 2.. off | on | on / off | SchurSolve off | on | on / off "
          "| SchurNumeric off | on | positions off vs on |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    for name, args, body in SCENES:
        for np_ in [int(r) for r in a.ranks.split(",")]:
            for k in range(a.repeat):
                f0, f1 = os.path.join(tmp, "off.h5"), os.path.join(tmp, "on.h5")
                w0, e0 = run(args, np_, a.steps, False, f0)
                w1, e1 = run(args, np_, a.steps, True, f1)
                p0, p1 = (sorted_positions(h5py.File(g, "r"), body)[1] for g in (f0, f1))
                d = np.abs(p0 - p1).max() / np.abs(p0).max()
                print("| %s | %d | %d | %.3f | %.3f | %.2f | %.3f | %.3f | %.2f | %.3f | %.3f | %.1e |" % (
                    name, np_, k + 1, w0, w1, w1 / w0, e0["SchurSolve"], e1["SchurSolve"],
                    e1["SchurSolve"] / e0["SchurSolve"], e0["SchurNumeric"], e1["SchurNumeric"], d), flush=True)


if __name__ == "__main__":
    main()
