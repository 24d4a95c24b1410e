#!/usr/bin/python3
"""The ironing benchmark, simplified (docs/scenes.md): runs input/ironing.opts (a kinematic
cylinder pressed 5 cm into an FE slab, then slid 1.5 m with mu = 0.3, quasi-static) and reads the
slab's reaction at its clamped bottom, which is the force the die exerts on it: its normal part
F_z and its tangential part F_x over time, and their ratio while the die slides (for a rigid die
on a flat slab, Coulomb gives mu where the whole contact slips; the slab's bulge ahead of the die
tilts the contact normals, which makes it differ).

Usage: /usr/bin/python3 scripts/ironing.py [--np N] [--mesh meshes/slab.msh] [--scheme S] [--no-plot]
(--scheme: -constraint_scheme, the default's if not given.) Prints the Markdown table of docs/scenes.md and
writes docs/ironing.png."""
import argparse
import os
import sys

import h5py
import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "tests"))
from fctest import run  # noqa: E402  (fecontact under mpirun, the environment, an error on failure)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--np", type=int, default=1)
    ap.add_argument("--mesh", default="meshes/slab.msh")
    ap.add_argument("--scheme", help="-constraint_scheme (default: fecontact's)")
    ap.add_argument("--no-plot", action="store_true")
    a = ap.parse_args()
    f = "/tmp/ironing_np%d%s.h5" % (a.np, "_" + a.scheme if a.scheme else "")
    cmd = ["-options_file", "input/ironing.opts", "-slab_dm_plex_filename", a.mesh, "-output_file", f, "-quiet"]
    if a.scheme:
        cmd += ["-constraint_scheme", a.scheme]
    run(cmd, a.np)
    h = h5py.File(f, "r")
    t, R = h["steps/time"][:], h["bodies/slab/reactions/bottom"][:]
    n, inter = h["steps/contacts"][:], h["steps/intersections"][:]
    Fx, Fz = -R[:, 0], R[:, 2]  # the die's force on the slab: along x, and pressing down (-z)
    slide = t > 0.6  # the die slides from t = 0.5 s (its -die_trajectory), past the first 0.1 s of it
    ratio = Fx[slide] / Fz[slide]
    print("| t (s) | die | F_z (N) | F_x (N) | F_x / F_z | contacts | points inside |")
    print("|---:|---|---:|---:|---:|---:|---:|")
    for k in list(range(4, len(t), 10)) + [len(t) - 1]:
        print("| %.2f | %s | %.0f | %.0f | %.3f | %d | %d |" % (t[k], "pressed" if t[k] <= 0.5 else "slides", Fz[k], Fx[k],
                                                             Fx[k] / Fz[k] if Fz[k] else 0.0, n[k], inter[k]))
    print()
    print("sliding (t > 0.6 s): F_x / F_z mean %.3f, min %.3f, max %.3f (mu = 0.3); F_z mean %.0f N" %
          (ratio.mean(), ratio.min(), ratio.max(), Fz[slide].mean()))
    if not a.no_plot:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, ax = plt.subplots(figsize=(6, 4))
        ax.plot(t, Fz / 1e3, label="$F_z$ (normal)")
        ax.plot(t, Fx / 1e3, label="$F_x$ (tangential)")
        ax.plot(t, 0.3 * Fz / 1e3, "k--", lw=0.8, label="$\\mu F_z$")
        ax.axvline(0.5, color="gray", lw=0.5)
        ax.set_xlabel("t (s): pressed to 0.5 s, then slides 1.5 m")
        ax.set_ylabel("die force on the slab (kN)")
        ax.set_title("Ironing (simplified): rigid cylinder on FE slab, static")
        ax.legend()
        fig.tight_layout()
        fig.savefig(os.path.join(ROOT, "docs", "ironing.png"), dpi=100)


if __name__ == "__main__":
    main()
