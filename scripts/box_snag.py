#!/usr/bin/python3
"""A frictionless rigid box sliding on a stiff FE slab keeps its speed, whatever its size against the
elements (issue 57; docs/validation.md, "Frictionless box on FE slabs").

The slab: meshes/slide_slab_coarse.msh, slide_slab.msh, slide_slab_fine.msh (1 m x 0.3 m x 5 cm,
elements of 5, 2.5 and 1.25 cm), linear, E = 2e7, bottom fixed, its top at z = 0 from x = -0.1 to 0.9;
the box (2000 kg/m^3) starts on it at x = -0.095 + its half edge, launched along x, mu = 0, h = 0.005,
the alarm distance 5 mm, -contact_facing_face 1 (--default: 0, the default), for T = min(0.5 s, the time its front face takes to 5 cm from the slab's end). Printed per case: the speed kept (the mean
speed of the last 5 steps over the launch speed), the hop (the range of the box's height), its
lowest speed, /steps/crossings and /steps/intersections summed over the steps.

Usage: scripts/box_snag.py [--np P] [--edges 1,2,4] [--speeds 0.5,1,2] [--meshes coarse,medium,fine]
  from the repository root after scripts/build.sh (uses build/fecontact, or $FECONTACT)."""
import argparse
import os
import subprocess
import tempfile

import h5py
import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
EXE = os.environ.get("FECONTACT", os.path.join(ROOT, "build", "fecontact"))
ENV = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1", OPENBLAS_NUM_THREADS="1")
MESHES = {"coarse": ("slide_slab_coarse", 0.05), "medium": ("slide_slab", 0.025), "fine": ("slide_slab_fine", 0.0125)}
H = 0.005
FACE = True  # -contact_facing_face (--default: the default, off)


def options(mesh, half, v):
    steps = int(round(min(0.5, (0.85 - (-0.095 + 2 * half)) / v) / H))  # its front face stays 5 cm from the end
    return ["-scene_bodies", "slab,box", "-contact_pairs", "slab:box", "-time_step", H, "-time_steps", steps,
            "-contact_mu", "0", "-contact_distance", "0.005", "-slab_type", "fem", "-slab_dm_plex_filename",
            "meshes/%s.msh" % mesh, "-slab_material", "linear", "-slab_young", "2e7", "-slab_density", "1000",
            "-slab_translate", "0.4,0,-0.05", "-slab_fixed_box", "-3,-3,-1,3,3,-0.049", "-box_type", "rigid",
            "-box_shape", "box", "-box_half_extents", "%g,%g,%g" % (half, half, half), "-box_density", "2000",
            "-box_center", "%g,0.0125,%g" % (-0.095 + half, half), "-box_velocity", "%g,0,0" % v,
            "-contact_facing_face", "1" if FACE else "0"]


def slide(mesh, half, v, np_=1, extra=(), tmp=None):
    """(speed kept, hop, lowest speed, crossings, intersections) of one case"""
    f = os.path.join(tmp or tempfile.mkdtemp(prefix="fc-snag-"), "snag.h5")
    cmd = [EXE] + [str(a) for a in options(mesh, half, v) + list(extra)] + ["-quiet", "-output_file", f]
    if np_ > 1:
        cmd = ["mpirun", "-n", str(np_), "--oversubscribe"] + cmd
    subprocess.run(cmd, cwd=ROOT, env=ENV, check=True, capture_output=True)
    with h5py.File(f, "r") as g:
        x = g["bodies/box/centroid"][:]
        speed = np.diff(np.concatenate([[[-0.095 + half, 0.0125, half]], x])[:, 0]) / H
        return (speed[-5:].mean() / v, x[:, 2].max() - x[:, 2].min(), speed.min() / v,
                int(g["steps/crossings"][:].sum()), int(g["steps/intersections"][:].sum()))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--np", type=int, default=1)
    ap.add_argument("--edges", default="1,2,4")
    ap.add_argument("--speeds", default="0.5,1,2")
    ap.add_argument("--meshes", default="coarse,medium,fine")
    ap.add_argument("--default", action="store_true", help="without -contact_facing_face (the default)")
    a = ap.parse_args()
    global FACE
    FACE = not a.default
    tmp = tempfile.mkdtemp(prefix="fc-snag-")
    print("frictionless rigid box on an FE slab (np %d, -contact_facing_face %d): speed kept, hop, lowest speed / "
          "launch speed" % (a.np, FACE))
    print("%-7s %7s %6s %5s | %7s %9s %7s %6s %6s" % ("mesh", "element", "edge", "v", "kept", "hop m", "lowest",
                                                   "cross", "inter"))
    for m in a.meshes.split(","):
        mesh, el = MESHES[m]
        for e in (float(x) for x in a.edges.split(",")):
            for v in (float(x) for x in a.speeds.split(",")):
                k, hop, low, cr, it = slide(mesh, 0.5 * e * el, v, a.np, tmp=tmp)
                print("%-7s %7.4f %6.4f %5.2f | %7.4f %9.2e %7.4f %6d %6d" % (m, el, e * el, v, k, hop, low, cr, it))


if __name__ == "__main__":
    main()
