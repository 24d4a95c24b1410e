#!/usr/bin/python3
"""Where the contact solver runs, on whole scenes: each scene on 1 rank, then --repeat times on 2
ranks with -pgs_ranks root and with the default (auto: split over the ranks from
-pgs_split_min_rows rows, rank 0 finishing a split solve that stalls), alternating. Printed per
run: the largest contact problem (rows), the largest sweep count and residual of a step, the
steps that end with a point inside (/steps/intersections), the wall time of the steps, and the
final state's largest difference from the 1-rank run, relative (tests/fctest.py, final_state:
every FE vertex in an order independent of the partition, the rigid bodies' poses).

    scripts/placement_check.py [--scenes ball_thin_slab,cube_thin_plate,stiffness_contrast] [--repeat 3]

The scenes are input/hard/<name>.opts."""
import argparse
import os
import subprocess
import sys

import h5py
import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "tests"))
from fctest import final_state  # noqa: E402

EXE = os.path.join(ROOT, "build", "fecontact")
ENV = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1", OPENBLAS_NUM_THREADS="1")
OUT = os.path.join(ROOT, "build", "placement_check")


def run(scene, np_, extra, tag):
    f = os.path.join(OUT, "%s_%s.h5" % (scene, tag))
    cmd = [EXE, "-options_file", "input/hard/%s.opts" % scene, "-output_file", f, "-quiet"] + extra
    if np_ > 1:
        cmd = ["mpirun", "-n", str(np_)] + cmd
    subprocess.run(cmd, cwd=ROOT, env=ENV, check=True, capture_output=True)
    return h5py.File(f, "r")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--scenes", default="ball_thin_slab,cube_thin_plate,stiffness_contrast")
    ap.add_argument("--repeat", type=int, default=3)
    a = ap.parse_args()
    os.makedirs(OUT, exist_ok=True)
    print("| scene | run | rows (max) | sweeps (max) | residual (max) | steps with a point inside | wall (s) | "
          "final state vs 1 rank |")
    print("|---|---|---:|---:|---:|---:|---:|---:|")
    for sc in a.scenes.split(","):
        ref = run(sc, 1, [], "np1")
        x = final_state(ref)
        runs = [("1 rank", ref)]
        for k in range(a.repeat):
            runs.append(("2 ranks, root, %d" % (k + 1), run(sc, 2, ["-pgs_ranks", "root"], "root%d" % k)))
            runs.append(("2 ranks, auto, %d" % (k + 1), run(sc, 2, [], "auto%d" % k)))
        for name, h in runs:
            s = h["steps"]
            d = np.abs(final_state(h) - x).max() / np.abs(x).max()
            print("| %s | %s | %d | %d | %.1e | %d | %.2f | %.1e |" % (
                sc, name, s["constraint_rows"][:].max(), s["pgs_iterations"][:].max(), s["residual"][:].max(),
                int((s["intersections"][:] > 0).sum()), s["wall_time"][:].sum(), d), flush=True)


if __name__ == "__main__":
    main()
