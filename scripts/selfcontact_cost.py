"""The cost of self-contact detection on a body with no fold (issue 39): the 17.5k-DOF cube of
input/cube_drop_peer.opts (40 steps, it lands in step 10) with and without the pair cube:cube, the
runs alternated --repeat times; per variant the median over the runs of the mean /steps/wall_time
before the landing (steps 2-9) and in contact (steps 11-40), and of the collision phase's time a
step (/steps/timing, column collision), and the self-contacts found (none: the cube does not fold).
Usage: /usr/bin/python3 scripts/selfcontact_cost.py [--np N] [--repeat R]"""
import argparse
import os
import subprocess
import sys

import h5py
import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "tests"))
from fctest import ENV, EXE  # noqa: E402

OUT = os.path.join(ROOT, "build", "selfcontact_cost")


def run(pairs, np_, name):
    f = os.path.join(OUT, name + ".h5")
    cmd = ([] if np_ == 1 else ["mpirun", "-n", str(np_), "--oversubscribe"]) + [
        EXE, "-options_file", "input/cube_drop_peer.opts", "-contact_pairs", pairs, "-output_every", "40",
        "-output_file", f, "-quiet"]
    subprocess.run(cmd, cwd=ROOT, env=ENV, check=True, capture_output=True)
    return h5py.File(f, "r")


def figures(h):
    s = h["steps"]
    w = s["wall_time"][:]
    col = s["timing/collision"][:]
    bodies = h["contacts/bodies"][:]
    nself = int((bodies[:, 0] == bodies[:, 1]).sum()) if len(bodies) else 0
    return w[1:9].mean(), w[10:].mean(), col[1:9].mean(), col[10:].mean(), nself


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--np", type=int, default=1)
    ap.add_argument("--repeat", type=int, default=3)
    a = ap.parse_args()
    os.makedirs(OUT, exist_ok=True)
    res = {"cube:ground": [], "cube:ground,cube:cube": []}
    for r in range(a.repeat):
        for k, pairs in enumerate(res):
            res[pairs].append(figures(run(pairs, a.np, "cost_%d_%d" % (k, r))))
    print("| pairs | s / step before contact | s / step in contact | collision s / step before | collision s / step "
          "in contact | self-contacts |")
    print("|---|---:|---:|---:|---:|---:|")
    med = {}
    for pairs, rows in res.items():
        m = np.median(np.array(rows)[:, :4], axis=0)
        med[pairs] = m
        print("| %s | %.4f | %.4f | %.4f | %.4f | %d |" % (pairs, *m, max(r[4] for r in rows)))
    b, s = med["cube:ground"], med["cube:ground,cube:cube"]
    print("self-contact detection adds %.1f %% to the step before contact and %.1f %% in contact (%d ranks, "
          "median of %d runs each)" % (100 * (s[0] / b[0] - 1), 100 * (s[1] / b[1] - 1), a.np, a.repeat))


if __name__ == "__main__":
    main()
