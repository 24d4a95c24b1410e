#!/usr/bin/python3
"""The contact solvers on the hard cases that stall projected Gauss-Seidel, and on the scenes where it
converges: each scene run with -contact_solver pgs, newton and auto (the default), one rank, the
defaults otherwise (-pgs_tol 1e-8, -pgs_max_it 1000). Prints, per scene and solver: the run's wall
time (best of --repeat), the steps whose contact solves did not converge to the tolerance, the
largest residual, the most sweeps and Newton steps in a step and their total, and auto's time over
pgs'. A run that stops (residual above -pgs_fail_residual) is marked "stopped at step k".
  /usr/bin/python3 scripts/hard_solvers.py [--repeat 3] [--scenes name,...]"""
import argparse
import os
import subprocess
import sys
import time

import h5py
import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
EXE = os.environ.get("FECONTACT", os.path.join(ROOT, "build", "fecontact"))
SCENES = {
    # the classes that stall the sweeps (issue 33)
    "mass_ratio": ["-options_file", "input/hard/mass_ratio.opts"],
    "mass_ratio_1e4": ["-options_file", "input/hard/mass_ratio_1e4.opts"],
    "mass_ratio_fe": ["-options_file", "input/hard/mass_ratio_fe.opts"],
    "stiff_on_soft": ["-options_file", "input/hard/stiff_on_soft.opts"],
    "stack10": ["-options_file", "input/hard/stack10.opts"],
    "stack_nonconforming": ["-options_file", "input/hard/stack_nonconforming.opts"],
    # where the sweeps converge: auto must cost the same
    "grasp": ["-options_file", "input/hard/grasp_fast.opts"],
    "stack5": ["-options_file", "input/hard/stack5.opts"],
    "cube_rest": ["-options_file", "input/cube_rest.opts"],
    "table1_18k": ["-options_file", "input/table1_18k.opts"],
}
ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
ap.add_argument("--repeat", type=int, default=3)
ap.add_argument("--scenes", default=",".join(SCENES))
a = ap.parse_args()
env = dict(os.environ, OPENBLAS_NUM_THREADS="1")
out = os.path.join(ROOT, "out")
os.makedirs(out, exist_ok=True)


def run(name, solver):
    f = os.path.join(out, "hard_solvers_%s_%s.h5" % (name, solver))
    best, p = None, None
    for _ in range(a.repeat):
        t = time.time()
        p = subprocess.run([EXE] + SCENES[name] + ["-contact_solver", solver, "-output_file", f, "-quiet"], cwd=ROOT,
                           env=env, capture_output=True, text=True)
        best = min(best or 1e30, time.time() - t)
    with h5py.File(f, "r") as H:
        res, its = H["steps/residual"][:], H["steps/pgs_iterations"][:]
        steps = int(np.ravel(H.attrs["time_steps"])[0])
    stopped = "" if p.returncode == 0 else "stopped at step %d" % (len(res) + 1)
    return dict(wall=best, bad=int((res > 1e-8).sum()), n=len(res), steps=steps, res=res.max() if len(res) else np.nan,
                its=its.max() if len(its) else 0, total=its.sum(), stopped=stopped)


print("| scene | solver | wall s | steps unconverged | max residual | max its/step | total its | auto / pgs |")
print("|---|---|---:|---|---:|---:|---:|---:|")
for name in a.scenes.split(","):
    r = {s: run(name, s) for s in ("pgs", "newton", "auto")}
    for s in ("pgs", "newton", "auto"):
        x = r[s]
        bad = x["stopped"] or "%d of %d" % (x["bad"], x["n"])
        ratio = "%.3f" % (x["wall"] / r["pgs"]["wall"]) if s == "auto" and not r["pgs"]["stopped"] else ""
        print("| %s | %s | %.2f | %s | %.1e | %d | %d | %s |" % (name, s, x["wall"], bad, x["res"], x["its"], x["total"], ratio))
    sys.stdout.flush()
