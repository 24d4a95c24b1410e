#!/usr/bin/python3
"""The nonlinear correction of a body with a Newton free motion (-<body>_correction nonlinear, its default;
src/body/fem_nonlinear.c, src/scene/settle.c, docs/method.md 2.6), on input/neohookean_compress.opts (the
Neo-Hookean block, nu = 0.49, pushed down 50 % onto a frictionless floor in 20 static steps):
- it completes; every step ends in an equilibrium with its contact forces: the reaction on the pushed
  face plus the contact forces close to 1e-8 of the reaction (the linear correction's miss by more than
  1 % at 25 %), with no point inside the floor, no contact beyond the end-of-step check and no element
  inverted; at most 8 Newton iterations a step on average;
- the block's volume stays above 0.95 of its start;
- restart: a run stopped after step 10 and continued ends as the run that did not stop (f_c and the
  sticking vertices are in the restart state);
- -block_correction nonlinear with a linearized free motion is an error naming the options;
- on 2 ranks (--np 2) the 1-rank positions to 1e-8 m."""
import os
import sys

import h5py
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import fctest as T  # noqa: E402

NP = T.np_from_argv()
c = T.Checker("nonlinear correction np%d" % NP)
BLOCK = ["-options_file", "input/neohookean_compress.opts", "-quiet"]


def run(name, args, np_=NP, check=True):
    f = T.out("nlc_%s_np%d.h5" % (name, np_))
    p = T.run(BLOCK + args + ["-output_file", f], np_=np_, check=check)
    return f, p


def balance(h):
    """per step |reaction + sum of the contact forces on the block| / |reaction|"""
    R = h["bodies/block/reactions/zmax"][:, :3]
    off, fw, bod = h["contacts/offset"][:], h["contacts/force_world"][:], h["contacts/bodies"][:]
    out = []
    for k in range(len(R)):
        sgn = np.where(bod[off[k]:off[k + 1], 0] == 0, 1.0, -1.0)
        out.append(np.abs(R[k] + (fw[off[k]:off[k + 1]] * sgn[:, None]).sum(0)).max() / np.abs(R[k]).max())
    return np.array(out)


def volume(h):
    P = h["bodies/block/positions"][:]
    q = P[:, h["bodies/block/mesh/cells"][:]]
    v = np.einsum("fij,fij->fi", q[:, :, 1] - q[:, :, 0], np.cross(q[:, :, 2] - q[:, :, 0], q[:, :, 3] - q[:, :, 0]))
    return np.abs(v.sum(1)) / abs(v[0].sum())


fn, _ = run("nonlinear", [])  # the default
fl, _ = run("linear", ["-block_correction", "linear", "-time_steps", "10"])
with h5py.File(fn) as h, h5py.File(fl) as l:
    s = h["steps"]
    bn, bl = balance(h), balance(l)
    c.check(len(s["step"]) == 20 and bn.max() < 1e-8,
            "nonlinear: 20 steps (50 %%), force balance to %.1e of the reaction (reaction %.0f N at 50 %%)" %
            (bn.max(), -h["bodies/block/reactions/zmax"][-1, 2]))
    c.check(bl.max() > 1e-2, "linear: the force balance misses by %.1e of the reaction" % bl.max())
    c.check(s["intersections"][:].max() == 0 and s["contacts_beyond_check"][:].max() == 0 and
            s["inverted_elements"][:].max() == 0 and s["free_motion_iterations"][:].mean() <= 8,
            "nonlinear: no point inside the floor, natural-map error %.1e m (check 2e-4), no element inverted, "
            "%.2f Newton iterations a step" % (s["max_complementarity"][:].max(), s["free_motion_iterations"][:].mean()))
    vol = volume(h)
    c.check(vol.min() >= 0.95, "nonlinear: the block's volume at least %.4f of its start" % vol.min())

# restart
f5, _ = run("first10", ["-block_correction", "nonlinear", "-time_steps", "10"])
fr, _ = run("rest10", ["-block_correction", "nonlinear", "-restart", f5])
with h5py.File(fr) as h, h5py.File(fn) as a:
    d = np.abs(T.sorted_positions(h, "block")[1] - T.sorted_positions(a, "block")[1]).max()
    c.check(d < 1e-12, "restart after step 10: the end of the run that did not stop to %.1e m" % d)

# bad input
_, p = run("bad", ["-block_correction", "nonlinear", "-block_free_motion", "linearized"], check=False)
c.check(p.returncode != 0 and "-block_correction nonlinear" in p.stdout + p.stderr and
        "-block_free_motion newton" in p.stdout + p.stderr,
        "nonlinear with a linearized free motion: an error naming both options (exit %d)" % p.returncode)

if NP > 1:
    f1, _ = run("nonlinear", [], np_=1)
    with h5py.File(f1) as a, h5py.File(fn) as b:
        d = np.abs(T.final_state(a) - T.final_state(b)).max()
        c.check(d < 1e-8, "%d ranks: the 1-rank final state to %.1e" % (NP, d))
c.done()
