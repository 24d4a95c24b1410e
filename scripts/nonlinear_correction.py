"""The nonlinear correction (-<body>_correction nonlinear, the default of a body with a Newton free motion)
against the linear one (eq. 20 from the free motion), on the Neo-Hookean scenes (docs/method.md 2.6):
  block:    input/neohookean_compress.opts, a block (nu = 0.49) pushed 50 % onto a frictionless floor in 20
            static steps: steps completed, the worst force balance |reaction + contact forces| / |reaction|,
            Newton iterations a step;
  crush:    input/hard/crush_neohookean.opts, a block crushed to 30 % by a plate (mu = 0.3), h = 0.01: the
            reaction on its base at the end, against the same run at h / 2 and h / 4 (a converged reaction
            does not move with h), penetration, Newton iterations a step, seconds;
  membrane: input/hard/membrane_neohookean.opts, a ball caught by a sheet: the ball's height at the end,
            sheet vertices in the ball, seconds;
  impact:   input/heavy_impact.opts (with --impact; it runs for minutes): steps completed, elements
            inverted, penetration.
The runs of a scene alternate linear and nonlinear; seconds are the sum of /steps/wall_time.
Usage: /usr/bin/python3 scripts/nonlinear_correction.py [--scene block|crush|membrane|impact|all] [--impact]"""
import argparse
import os
import subprocess
import sys

import h5py
import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "tests"))
from fctest import ENV, EXE  # noqa: E402

OUT = os.path.join(ROOT, "build", "nonlinear_correction")
SCENES = {"block": ("input/neohookean_compress.opts", "block"), "crush": ("input/hard/crush_neohookean.opts", "block"),
          "membrane": ("input/hard/membrane_neohookean.opts", "sheet"), "impact": ("input/heavy_impact.opts", "slab")}


def run(scene, correction, extra=(), tag=""):
    opts, body = SCENES[scene]
    f = os.path.join(OUT, "%s_%s%s.h5" % (scene, correction, tag))
    cmd = [EXE, "-options_file", opts, "-%s_correction" % body, correction, "-output_file", f, "-quiet",
           "-output_every", "1"] + [str(x) for x in extra]
    p = subprocess.run(cmd, cwd=ROOT, env=ENV, capture_output=True, text=True)
    return h5py.File(f, "r"), p.returncode


def balance(h, region):
    R = h["bodies/block/reactions/" + region][:, :3]
    off, fw, bod = h["contacts/offset"][:], h["contacts/force_world"][:], h["contacts/bodies"][:]
    out = [np.abs(R[k] + (fw[off[k]:off[k + 1]] * np.where(bod[off[k]:off[k + 1], 0] == 0, 1.0, -1.0)[:, None]).sum(0))
           .max() / np.abs(R[k]).max() for k in range(len(R))]
    return max(out) if out else float("nan")


def seconds(h):
    return float(np.sum(h["steps/wall_time"][:]))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--scene", default="all", choices=["block", "crush", "membrane", "impact", "all"])
    ap.add_argument("--impact", action="store_true", help="with --scene all: the heavy impact too")
    a = ap.parse_args()
    os.makedirs(OUT, exist_ok=True)
    scenes = [a.scene] if a.scene != "all" else ["block", "crush", "membrane"] + (["impact"] if a.impact else [])
    for sc in scenes:
        for c in ["linear", "nonlinear"]:
            h, rc = run(sc, c)
            s = h["steps"]
            n = len(s["step"])
            line = "%-9s %-9s exit %d, %d steps, Newton %.2f a step, %.1f s" % (
                sc, c, rc, n, s["free_motion_iterations"][:].mean() if n else 0, seconds(h))
            if sc == "block":
                line += ", force balance %.1e" % balance(h, "zmax")
            if sc == "crush":
                line += ", penetration %.1e m, reaction at the end %.4g N" % (
                    s["max_penetration"][:].max(), h["bodies/block/reactions/zmin"][-1, 2])
                for k, hk in [(2, 0.005), (4, 0.0025)]:
                    hh, _ = run(sc, c, ["-time_step", hk, "-time_steps", 100 * k], "_h%d" % k)
                    line += "; at h/%d %.4g N" % (k, hh["bodies/block/reactions/zmin"][-1, 2])
            if sc == "membrane":
                P = h["bodies/sheet/positions"][:]
                cen = np.concatenate([[[0, 0, 0.075]], h["bodies/ball/centroid"][:]])[h["frames/step"][:]]
                inside = (np.linalg.norm(P - cen[:, None, :], axis=2) < 0.05 - 1e-6).sum()
                line += ", ball at z = %.3f m at the end, %d sheet vertex positions in the ball" % (
                    h["bodies/ball/centroid"][-1, 2], inside)
            if sc == "impact" and n:
                line += ", %d elements inverted at most, penetration %.1e m, %d sub-steps in step 1" % (
                    s["inverted_elements"][:].max(), s["max_penetration"][:].max(), s["substeps"][0])
            print(line, flush=True)


if __name__ == "__main__":
    main()
