#!/usr/bin/python3
"""Uniaxial compression of the unit cube (E = 1e5, nu = 0.3) to a 1 % strain, quasi-statically, on
the three cube meshes (docs/scenes.md): its top region "zmax" moved down by -cube_displacement, its
base on a frictionless kinematic floor (free to slide). The top's reaction against E A eps: the
top is held in x and y too (a constrained vertex is constrained in every direction), which
restrains the lateral expansion there, so the reaction converges to a value above E A eps.

Usage: /usr/bin/python3 scripts/compression.py [--np N]"""
import argparse
import os
import sys

import h5py

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "tests"))
from fctest import run  # noqa: E402  (fecontact under mpirun, the environment, an error on failure)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--np", type=int, default=1)
    a = ap.parse_args()
    print("| mesh | vertices | contacts | reaction / (E A eps) - 1 |")
    print("|---|---:|---:|---:|")
    for m in ["cube_coarse", "cube_medium", "cube"]:
        f = "/tmp/compression_%s.h5" % m
        cmd = ["-scene_bodies", "cube,floor", "-contact_pairs", "cube:floor", "-contact_mu", "0", "-cube_type", "fem",
               "-cube_dm_plex_filename", "meshes/%s.msh" % m, "-cube_young", "1e5", "-cube_poisson", "0.3",
               "-cube_density", "100", "-cube_displacement", "zmax=0:0,0,0;1:0,0,-0.01", "-floor_type", "kinematic",
               "-floor_shape", "plane", "-floor_center", "0,0,-0.5", "-time_integration", "static", "-time_step", "0.25",
               "-time_steps", "4", "-gravity", "0,0,0", "-output_file", f, "-quiet"]
        run(cmd, a.np)
        h = h5py.File(f, "r")
        R = -h["bodies/cube/reactions/zmax"][-1][2]
        print("| %s | %d | %d | %+.2f %% |" % (m, h["bodies/cube/mesh/reference"].shape[0], h["steps/contacts"][-1],
                                           100 * (R / (1e5 * 0.01) - 1)))


if __name__ == "__main__":
    main()
