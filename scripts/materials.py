"""The figures of docs/materials.md (issue 38):
1. the uniaxial stress-stretch curve of -<body>_material neohookean: the 5 x 1 x 1 bar
   (meshes/beam_n4.msh) clamped at x = 0 and moved at x = 5, quasi-static, stretched to 2 and
   compressed to 0.8 in 10 load steps each; per step the middle section's axial stretch and the
   reaction against the analytic nominal stress P11(stretch) A0 of the compressible Neo-Hookean
   model (uniaxial stress: lateral stretch from P22 = 0); plot docs/materials_uniaxial.png;
2. the time per step of neohookean (Newton free motion; its nonlinear contact correction, the default,
   and the linear one) against corotational (one linearization),
   the same run of input/cube_drop_peer.opts (17.5k DOFs, 40 steps, the cube lands in step 10),
   the mean of /steps/wall_time before the landing (steps 2-9) and in contact (steps 11-40), with
   the Newton iterations and factorizations per step.
Usage: /usr/bin/python3 scripts/materials.py [--np N] [--plot]"""
import argparse
import os
import subprocess
import sys

import h5py
import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "tests"))
from fctest import ENV, EXE, sorted_positions  # noqa: E402

OUT = os.path.join(ROOT, "build", "materials")
E, NU = 1e5, 0.3
LAM, MU = E * NU / ((1 + NU) * (1 - 2 * NU)), E / (2 * (1 + NU))
FIX = "box:-1,-1,-1,1e-9,1,1"


def run(args, np_, name):
    f = os.path.join(OUT, name + ".h5")
    cmd = ([] if np_ == 1 else ["mpirun", "-n", str(np_), "--oversubscribe"]) + [EXE] + [str(a) for a in args] + [
        "-output_file", f, "-quiet"]
    subprocess.run(cmd, cwd=ROOT, env=ENV, check=True, capture_output=True)
    return h5py.File(f, "r")


def uniaxial(l1):
    lo, hi = 0.3, 2.0
    for _ in range(100):
        l2 = 0.5 * (lo + hi)
        lo, hi = (l2, hi) if MU * (l2 * l2 - 1) + LAM * np.log(l1 * l2 * l2) < 0 else (lo, l2)
    return l2, MU * (l1 - 1 / l1) + LAM * np.log(l1 * l2 * l2) / l1


def curve(np_):
    rows = []
    for name, dx in [("stretch", 5.0), ("compression", -1.0)]:
        h = run(["-scene_bodies", "bar", "-bar_type", "fem", "-bar_dm_plex_filename", "meshes/beam_n4.msh",
                 "-bar_material", "neohookean", "-bar_young", E, "-bar_poisson", NU, "-bar_density", 1000,
                 "-bar_fixed", FIX, "-bar_displacement", "box:4.999999,-1,-1,6,1,1=0:0,0,0;1:%g,0,0" % dx,
                 "-time_integration", "static", "-gravity", "0,0,0", "-time_step", 0.1, "-time_steps", 10,
                 "-output_every", 1], np_, "uniaxial_" + name)
        for k in range(1, h["bodies/bar/positions"].shape[0]):
            ref, pos = sorted_positions(h, "bar", k)
            a, b = (np.abs(ref[:, 0] - x) < 1e-9 for x in (2.0, 3.0))
            l1 = pos[b, 0].mean() - pos[a, 0].mean()
            force = -h["bodies/bar/reactions/" + FIX][k - 1][0]
            rows.append((l1, force, uniaxial(l1)[1], int(h["steps/free_motion_iterations"][k - 1])))
    rows.sort()
    print("| middle stretch | reaction (N) | analytic P11 A0 (N) | relative difference | Newton iterations |")
    print("|---:|---:|---:|---:|---:|")
    for l1, f, p, it in rows:
        print("| %.4f | %.1f | %.1f | %.1e | %d |" % (l1, f, p, abs(f - p) / abs(p), it))
    return rows


def timing(np_):
    print("\n| material | free motion, correction | before contact: s / step | in contact: s / step | Newton "
          "iterations / step (in contact) | factorizations / step (in contact) |")
    print("|---|---|---:|---:|---:|---:|")
    for mat, corr in [("corotational", None), ("neohookean", "nonlinear"), ("neohookean", "linear")]:
        h = run(["-options_file", "input/cube_drop_peer.opts", "-cube_material", mat, "-output_every", 40] +
                (["-cube_correction", corr] if corr else []), np_, "peer_%s_%s" % (mat, corr))
        w, s = h["steps/wall_time"][:], h["steps"]
        contact = np.nonzero(s["contacts"][:] > 0)[0]
        first = contact[0] if len(contact) else len(w)
        print("| %s | %s | %.3f | %.3f | %.1f | %.1f |" % (
            mat, "newton, " + corr if corr else "linearized, linear", w[1:first].mean(), w[first + 1:].mean(),
            s["free_motion_iterations"][first + 1:].mean(), s["factorizations"][first + 1:].mean()))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--np", type=int, default=1)
    ap.add_argument("--plot", action="store_true")
    a = ap.parse_args()
    os.makedirs(OUT, exist_ok=True)
    rows = curve(a.np)
    timing(a.np)
    if a.plot:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        l = np.linspace(0.75, 2.05, 200)
        fig, ax = plt.subplots(figsize=(6, 4))
        ax.plot(l, [uniaxial(x)[1] / E for x in l], "k-", label="analytic (compressible Neo-Hookean)")
        ax.plot(l, (l - 1), "k:", label="linear elasticity, E (stretch - 1)")
        ax.plot([r[0] for r in rows], [r[1] / E for r in rows], "o", mfc="none", label="fecontact: reaction / A0")
        ax.set_xlabel("axial stretch (middle of the bar)")
        ax.set_ylabel("nominal stress P11 / E")
        ax.legend()
        ax.grid(alpha=0.3)
        fig.tight_layout()
        fig.savefig(os.path.join(ROOT, "docs", "materials_uniaxial.png"), dpi=110)


if __name__ == "__main__":
    main()
