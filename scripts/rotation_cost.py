#!/usr/bin/python3
"""What the turning-frame step of a free co-rotational body (-<body>_rotation exact, the default;
src/body/fem_rotation.c) costs against eq. 2 as it is (-<body>_rotation linear), in one run of this
script on one machine: the 17.5k-DOF co-rotational cube resting on a plane (input/cube_rest.opts,
in contact from step 1) and the grasp (input/grasp_rotate.opts, a coarse cube turned by two
fingers). Runs alternate between the two settings; prints the median over repeats of the median
wall time of a step (steps after the first) and of its free-motion phase.
  /usr/bin/python3 scripts/rotation_cost.py [--repeat 3] [--exe build/fecontact]"""
import argparse
import os
import subprocess
import tempfile

import h5py
import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
ap.add_argument("--repeat", type=int, default=3)
ap.add_argument("--exe", default=os.path.join(ROOT, "build", "fecontact"))
a = ap.parse_args()
env = dict(os.environ, OPENBLAS_NUM_THREADS="1")
tmp = tempfile.mkdtemp(prefix="rotation-cost-")
scenes = [("cube_rest (17.5k DOFs, in contact)", "input/cube_rest.opts", "cube", ["-time_steps", "8"]),
          ("grasp_rotate (coarse cube, 2 fingers)", "input/grasp_rotate.opts", "object", [])]
print("| scene | rotation | step (s) | free motion (s) | ratio of steps |")
print("|---|---|---:|---:|---:|")
for label, opts, body, extra in scenes:
    res = {"linear": [], "exact": []}
    for r in range(a.repeat):
        for rot in ("linear", "exact"):
            f = os.path.join(tmp, "%s_%s_%d.h5" % (body, rot, r))
            subprocess.run([a.exe, "-options_file", opts, "-%s_rotation" % body, rot, "-output_file", f, "-quiet"] + extra,
                           cwd=ROOT, env=env, check=True)
            H = h5py.File(f, "r")
            wall = H["steps/wall_time"][1:]
            free = H["steps/timing/free_motion"][1:]
            res[rot].append((np.median(wall), np.median(free)))
    med = {k: np.median(np.array(v), axis=0) for k, v in res.items()}
    for rot in ("linear", "exact"):
        print("| %s | %s | %.4f | %.4f | %s |" % (label, rot, med[rot][0], med[rot][1],
                                                 "%.3f" % (med[rot][0] / med["linear"][0]) if rot == "exact" else ""))
