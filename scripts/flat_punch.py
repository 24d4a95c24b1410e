#!/usr/bin/python3
"""The flat punch (docs/scenes.md, "Flat punch"): runs input/flat_punch.opts (a kinematic box, 6 x 6 cm face,
pressed 0.5 mm into an elastic block, then slid 16 cm with mu = 0.2, quasi-statically) and reads the punch's force,
the sum of its contacts' world forces (tests/fctest.py, contact_force_on): |F_t / F_n| at every sliding step, which
Coulomb's law makes mu where the whole face slips, with the end-of-step measures of /steps (cone violation,
complementarity, violation) and what the box's corner points (its picture's points against the block's triangles,
-contact_shape_points) carry.

Usage: /usr/bin/python3 scripts/flat_punch.py [--np N] [--mesh meshes/punch_block.msh] [--table] [-- fecontact options]
e.g. scripts/flat_punch.py -- -constraint_scheme explicit. Prints one summary line (and with --table the steps)."""
import argparse
import os
import sys

import h5py
import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "tests"))
from fctest import contact_force_on, run  # noqa: E402

MU, SLIDE = 0.2, 0.1  # -contact_mu; the punch slides from t = 0.1 s (its -punch_trajectory)


def measure(h):
    """Per step: time, the punch's force (3), |F_t / F_n|, and the corner points' share of F_n and their largest
    normal tilt (degrees)"""
    t, F = h["steps/time"][:], contact_force_on(h, "punch")
    ratio = np.hypot(F[:, 0], F[:, 1]) / np.abs(F[:, 2])
    ip = h.attrs["scene_bodies"].decode().split(",").index("punch")
    off, b, n, fw = (h["contacts/" + k][:] for k in ("offset", "bodies", "normal", "force_world"))
    share, tilt = np.zeros(len(t)), np.zeros(len(t))
    for k in range(len(t)):
        s = slice(off[k], off[k + 1])
        corner = b[s, 0] == ip  # the punch's own points (side 1) against the block's triangles
        share[k] = fw[s][corner, 2].sum() / F[k, 2] if F[k, 2] else 0.0
        tilt[k] = np.degrees(np.arccos(np.clip(np.abs(n[s][corner, 2]), 0, 1))).max() if corner.any() else 0.0
    return t, F, ratio, share, tilt


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--np", type=int, default=1)
    ap.add_argument("--mesh", default="meshes/punch_block.msh")
    ap.add_argument("--table", action="store_true")
    ap.add_argument("extra", nargs="*", help="fecontact options, after --")
    a = ap.parse_args()
    f = "/tmp/flat_punch_np%d.h5" % a.np
    p = run(["-options_file", "input/flat_punch.opts", "-block_dm_plex_filename", a.mesh, "-output_file", f, "-quiet"] +
            a.extra, a.np, check=False)
    h = h5py.File(f, "r")
    t, F, ratio, share, tilt = measure(h)
    cv, comp, viol = (h["steps/" + k][:] for k in ("cone_violation", "complementarity", "violation"))
    newton, inside = h["steps/newton_iterations"][:], h["steps/intersections"][:]
    if a.table:
        print("| t (s) | punch | F_n (N) | F_t (N) | abs(F_t / F_n) | cone violation | complementarity (m) | "
              "violation (m) | corners' share of F_n | Newton |")
        print("|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|")
        for k in range(len(t)):
            print("| %.3f | %s | %.1f | %.1f | %.4f | %.3f | %.1e | %.1e | %.2f | %d |" %
                  (t[k], "pressed" if t[k] <= SLIDE + 1e-9 else "slides", F[k, 2], np.hypot(F[k, 0], F[k, 1]), ratio[k],
                   cv[k], comp[k], viol[k], share[k], newton[k]))
    s = t > SLIDE + 1e-9
    if p.returncode:
        print("fecontact stopped after step %d: %s" % (len(t), (p.stdout + p.stderr).strip().splitlines()[-1][:300]))
    if s.any():
        print("sliding (%d steps): abs(F_t/F_n) mean %.4f, min %.4f, max %.4f (mu %.1f; largest abs(ratio/mu - 1) %.3f); "
              "cone violation max %.3f; complementarity max %.1e m; violation max %.1e m; Newton iterations mean %.2f, "
              "max %d; corner points' share of F_n %.2f-%.2f, their normals tilted up to %.1f deg; points inside max %d" %
              (s.sum(), ratio[s].mean(), ratio[s].min(), ratio[s].max(), MU, np.abs(ratio[s] / MU - 1).max(), cv[s].max(),
               comp[s].max(), viol[s].max(), newton[s].mean(), newton[s].max(), share[s].min(), share[s].max(),
               tilt[s].max(), inside[s].max()))


if __name__ == "__main__":
    main()
