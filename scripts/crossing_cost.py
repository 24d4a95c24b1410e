#!/usr/bin/python3
"""What the crossing audit costs per contact step (issue 57; docs/hard-cases.md, "What the crossing audit costs").

Runs each scene with -contact_crossings off, count and redo, alternately, REPEAT times, and prints
per scene: the mean time of a contact step (the sum of the /steps/timing phases over the steps
with contacts, step 1 excluded: it holds set-up work such as the first factorization), the mean
collision phase (/steps/timing/collision: detection, end-of-step gaps, intersection count and the
audit), each the smallest over the repetitions (the machine is shared), and:
- the audit's cost: count's collision phase minus off's, in per cent of off's contact step (count
  takes every step as off does, so the other phases do the same work: their difference is noise);
- redo (the default): the steps it redid smaller (/steps/substeps > 1) and its contact step's time
  against off's, in per cent (a redone step costs its sub-steps).

Usage: scripts/crossing_cost.py [--repeat N] [--np P] [opts files...]
  default scenes: input/grasp_rotate.opts input/table1_18k.opts input/cube_drop_peer.opts; run from
  the repository root after scripts/build.sh (uses build/fecontact, or $FECONTACT)."""
import argparse
import os
import subprocess
import tempfile

import h5py
import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
EXE = os.environ.get("FECONTACT", os.path.join(ROOT, "build", "fecontact"))
ENV = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1", OPENBLAS_NUM_THREADS="1")
MODES = ("off", "count", "redo")


def run(opts, mode, np_, tmp):
    f = os.path.join(tmp, "cost.h5")
    cmd = [EXE, "-options_file", opts, "-contact_crossings", mode, "-output_file", f, "-quiet"]
    if np_ > 1:
        cmd = ["mpirun", "-n", str(np_)] + cmd
    subprocess.run(cmd, cwd=ROOT, env=ENV, check=True, capture_output=True)
    with h5py.File(f, "r") as H:
        T = H["steps/timing"]
        total = sum(T[p][:] for p in T)
        contact = H["steps/contacts"][:].ravel() > 0
        contact[0] = False
        if not contact.any():
            raise SystemExit("%s: no contact step" % opts)
        out = (total[contact].mean(), T["collision"][contact].mean(), contact.sum(),
               int((H["steps/substeps"][:] > 1).sum()), int(H["steps/crossings"][:].sum()))
    return out


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--np", type=int, default=1)
    ap.add_argument("scenes", nargs="*",
                    default=["input/grasp_rotate.opts", "input/table1_18k.opts", "input/cube_drop_peer.opts"])
    a = ap.parse_args()
    tmp = tempfile.mkdtemp(prefix="fc-cross-")
    print("per contact step: -contact_crossings off / count / redo (np %d, best of %d runs, step 1 excluded)" %
          (a.np, a.repeat))
    print("%-22s %5s | %10s %10s | %10s %10s %8s | %10s %6s %6s" % (
        "scene", "steps", "off step", "collision", "count coll", "audit", "crossed", "redo step", "added", "redone"))
    for opts in a.scenes:
        best = {m: [np.inf, np.inf] for m in MODES}
        info = {}
        for _ in range(a.repeat):
            for m in MODES:
                t, c, n, redone, crossed = run(opts, m, a.np, tmp)
                best[m] = [min(best[m][0], t), min(best[m][1], c)]
                info[m] = (n, redone, crossed)
        off, cnt, redo = best["off"], best["count"], best["redo"]
        print("%-22s %5d | %10.5f %10.5f | %10.5f %+9.2f%% %8d | %10.5f %+5.1f%% %6d" % (
            os.path.basename(opts), info["off"][0], off[0], off[1], cnt[1], 100 * (cnt[1] - off[1]) / off[0],
            info["count"][2], redo[0], 100 * (redo[0] - off[0]) / off[0], info["redo"][1]))


if __name__ == "__main__":
    main()
