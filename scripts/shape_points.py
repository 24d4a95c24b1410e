#!/usr/bin/python3
"""What -contact_shape_points (a bounded shape's points against the FE triangles, issue 15) buys
and costs, on the scenes with an FE body against a sphere or a box.

Runs each scene with the option off and on, REPEAT times alternately, and prints per scene and
setting: the largest end-of-step intersection count (/steps/intersections: points deeper than
-contact_intersection_depth inside the other body, which since this option also counts the
shape's points inside the FE body), the largest contact count, the mean and largest sweeps of the
contact solver, the largest residual, and the mean step wall time (/steps/wall_time, step 1
excluded, the smallest mean over the repetitions: the machine is shared).

Usage: scripts/shape_points.py [--repeat N] [--np P] [opts files...]
  default scenes: input/grasp_rotate.opts input/box_on_slab.opts input/hard/grasp_fast.opts
  input/hard/ball_thin_slab.opts input/hard/cube_thin_plate.opts, and the ball of
  input/hard/ball_thin_slab.opts shrunk below the slab's element size (r = 8 mm) on a stiff slab;
  run from the repository root after scripts/build.sh (uses build/fecontact, or $FECONTACT)."""
import argparse
import os
import subprocess
import tempfile

import h5py
import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
EXE = os.environ.get("FECONTACT", os.path.join(ROOT, "build", "fecontact"))
ENV = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1", OPENBLAS_NUM_THREADS="1")
SMALL_BALL = ["-options_file", "input/hard/ball_thin_slab.opts", "-time_steps", "8", "-ball_radius", "0.008",
              "-ball_center", "0.013,0.017,0.21", "-slab_young", "1e10"]


def run(args, on, np_, tmp):
    f = os.path.join(tmp, "sp.h5")
    cmd = [EXE] + args + ["-contact_shape_points", "1" if on else "0", "-output_file", f, "-quiet"]
    if np_ > 1:
        cmd = ["mpirun", "-n", str(np_)] + cmd
    subprocess.run(cmd, cwd=ROOT, env=ENV, check=True, capture_output=True)
    with h5py.File(f, "r") as H:
        s = H["steps"]
        return dict(inter=int(s["intersections"][:].max()), contacts=int(s["contacts"][:].max()),
                    sweeps=float(s["pgs_iterations"][:].mean()), maxsweeps=int(s["pgs_iterations"][:].max()),
                    res=float(s["residual"][:].max()), step=float(s["wall_time"][1:].mean()))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--repeat", type=int, default=2)
    ap.add_argument("--np", type=int, default=1)
    ap.add_argument("scenes", nargs="*")
    a = ap.parse_args()
    scenes = [(s, ["-options_file", s]) for s in a.scenes] or \
        [(s, ["-options_file", s]) for s in ("input/grasp_rotate.opts", "input/box_on_slab.opts",
                                              "input/hard/grasp_fast.opts", "input/hard/ball_thin_slab.opts",
                                              "input/hard/cube_thin_plate.opts")] + \
        [("ball_thin_slab.opts, r = 8 mm, E = 1e10", SMALL_BALL)]
    print("| scene | shape points | intersections (max) | contacts (max) | sweeps mean / max | residual max | "
          "step wall (s) |")
    print("|---|---|---:|---:|---:|---:|---:|")
    with tempfile.TemporaryDirectory() as tmp:
        for name, args in scenes:
            best = {}
            for _ in range(a.repeat):
                for on in (False, True):
                    r = run(args, on, a.np, tmp)
                    if on not in best or r["step"] < best[on]["step"]:
                        best[on] = r
            for on in (False, True):
                r = best[on]
                print("| %s | %s | %d | %d | %.0f / %d | %.1e | %.4f |" % (name, "on" if on else "off", r["inter"],
                      r["contacts"], r["sweeps"], r["maxsweeps"], r["res"], r["step"]), flush=True)
            print("| | on / off step | | | | | **%.2f** |" % (best[True]["step"] / best[False]["step"]), flush=True)


if __name__ == "__main__":
    main()
