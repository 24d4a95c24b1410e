#!/usr/bin/python3
"""Two-way FE-FE detection: the scenes where the two passes' constraints duplicate or oppose each
other, run with the defaults (-contact_fe_pass2_dormant 0, -contact_facing 1) and with each of
those off, and one-way. Prints a markdown table read from each run's /steps: the largest number of
PGS sweeps in a step, the steps whose residual is above -pgs_tol, the largest residual, the largest
intersection count of the end-of-step check, the mean contact count, and the mean time of the
collision phase and of the contact solver. Usage: scripts/two_way.py [--np N] (docs/hard-cases.md)"""
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
TOL = 1e-8  # -pgs_tol, the default

SCENES = [("stiffness contrast (case 4), 40 steps", ["-options_file", "input/hard/stiffness_contrast.opts"]),
          ("two FE cubes, faces offset, 120 steps", ["-options_file", "input/two_cubes.opts", "-time_steps", "120"]),
          ("FE cubes start 0.1 m inside (case 13), 120 steps", ["-options_file", "input/hard/start_inside.opts"])]
VARIANTS = [("defaults (two passes, dormant, facing)", []),
            ("`-contact_facing 0`", ["-contact_facing", "0"]),
            ("`-contact_fe_pass2_dormant -1`", ["-contact_fe_pass2_dormant", "-1"]),
            ("`-contact_fe_pass2_dormant -1 -contact_facing 0` (before)", ["-contact_fe_pass2_dormant", "-1",
                                                                              "-contact_facing", "0"]),
            ("`-contact_fe_passes 1`", ["-contact_fe_passes", "1"])]


def main():
    np_ = int(sys.argv[sys.argv.index("--np") + 1]) if "--np" in sys.argv else 1
    tmp = tempfile.mkdtemp(prefix="two-way-")
    print("`/usr/bin/python3 scripts/two_way.py --np %d` on %s:\n" % (np_, time.strftime("%Y-%m-%d")))
    print("| scene | options | max sweeps | steps above pgs_tol | max residual | max intersections | contacts (mean) "
          "| collision (ms/step) | contact solver (ms/step) |")
    print("|---|---|---:|---:|---:|---:|---:|---:|---:|")
    for sname, sargs in SCENES:
        for k, (vname, vargs) in enumerate(VARIANTS):
            f = os.path.join(tmp, "run%d.h5" % k)
            cmd = [EXE] + sargs + vargs + ["-quiet", "-output_file", f]
            if np_ > 1:
                cmd = ["mpirun", "-n", str(np_), "--oversubscribe"] + cmd
            p = subprocess.run(cmd, cwd=ROOT, env=ENV, capture_output=True, text=True)
            if p.returncode:
                sys.stderr.write(p.stdout + p.stderr)
                print("| %s | %s | exit %d |  |  |  |  |  |  |" % (sname, vname, p.returncode))
                continue
            with h5py.File(f, "r") as h:
                s = h["steps"]
                it, res, inter = s["pgs_iterations"][:], s["residual"][:], s["intersections"][:]
                print("| %s | %s | %d | %d | %.1e | %d | %.0f | %.2f | %.2f |" % (
                    sname, vname, it.max(), int((res > 1.0001 * TOL).sum()), res.max(), inter.max(),
                    s["contacts"][:].mean(), 1e3 * s["timing/collision"][:].mean(),
                    1e3 * s["timing/contact_solver"][:].mean()), flush=True)


if __name__ == "__main__":
    main()
