#!/usr/bin/python3
"""What continuous collision detection costs against discrete, per step (issue 15).

Runs each scene with -contact_detection discrete and continuous, alternately, REPEAT times, and
prints per scene: the mean time of a step (the sum of the /steps/timing phases, step 1 excluded:
it holds set-up work such as the first factorization of a co-rotational body), the mean time of
the collision phase (detection at the start of the step and the end-of-step gaps, measures and
intersection check: /steps/timing/collision), both the smallest over the repetitions (the
machine is shared), and what continuous adds to a step, in per cent.

Usage: scripts/detection_cost.py [--repeat N] [--np P] [opts files...]
  default scenes: input/table1_18k.opts input/grasp_rotate.opts; run from the repository root
  after scripts/build.sh (uses build/fecontact, or $FECONTACT)."""
import argparse
import os
import subprocess
import tempfile

import h5py
import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
EXE = os.environ.get("FECONTACT", os.path.join(ROOT, "build", "fecontact"))
ENV = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1", OPENBLAS_NUM_THREADS="1")


def run(opts, detection, np_, tmp):
    f = os.path.join(tmp, "cost.h5")
    cmd = [EXE, "-options_file", opts, "-contact_detection", detection, "-output_file", f, "-quiet"]
    if np_ > 1:
        cmd = ["mpirun", "-n", str(np_)] + cmd
    subprocess.run(cmd, cwd=ROOT, env=ENV, check=True, capture_output=True)
    with h5py.File(f, "r") as H:
        T = H["steps/timing"]
        total = sum(T[p][:] for p in T)[1:]
        coll = T["collision"][1:]
        steps = len(H["steps/step"])
        work = (H["steps/contacts"][:].sum(), H["steps/pgs_iterations"][:].sum())
    return total.mean(), coll.mean(), steps, work


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--np", type=int, default=1)
    ap.add_argument("scenes", nargs="*", default=["input/table1_18k.opts", "input/grasp_rotate.opts"])
    a = ap.parse_args()
    tmp = tempfile.mkdtemp(prefix="fc-cost-")
    print("per-step cost of -contact_detection (np %d, best of %d runs, step 1 excluded)" % (a.np, a.repeat))
    print("%-28s %5s | %-10s %12s %12s | %-10s %12s %12s | %s" %
          ("scene", "steps", "discrete", "step s", "collision s", "continuous", "step s", "collision s", "added"))
    for opts in a.scenes:
        best = {"discrete": [np.inf, np.inf], "continuous": [np.inf, np.inf]}
        work = {}
        for _ in range(a.repeat):
            for det in ("discrete", "continuous"):
                t, c, n, w = run(opts, det, a.np, tmp)
                best[det] = [min(best[det][0], t), min(best[det][1], c)]
                work[det] = w
        d, c = best["discrete"], best["continuous"]
        # added: the collision time continuous detection adds, as a fraction of a discrete step. It
        # is what the option costs when it finds no more contacts (the same contacts and sweeps:
        # the other phases do the same work, and their times differ by the machine's noise, shown
        # by the step totals); when it does find more, the contacts and sweeps say so.
        added = (c[1] - d[1]) / d[0]
        print("%-28s %5d | %-10s %12.5f %12.5f | %-10s %12.5f %12.5f | %+.2f %% of a step (collision %+.6f s)" %
              (os.path.basename(opts), n, "", d[0], d[1], "", c[0], c[1], 100 * added, c[1] - d[1]))
        print("%-28s       contacts (sum over steps) / PGS sweeps: discrete %d / %d, continuous %d / %d%s" %
              ("", work["discrete"][0], work["discrete"][1], work["continuous"][0], work["continuous"][1],
               "" if work["discrete"] == work["continuous"] else "  (continuous found other contacts: the step totals count them)"))


if __name__ == "__main__":
    main()
