#!/usr/bin/python3
"""Step control (src/scene/stepcontrol.c, docs/method.md "Step control"):
- on by default, and with no failing step the run is the one of -time_step_control off, bit for bit (1 rank);
- a planted failure (-time_step_fail_at k) is redone from the step's start with h/2: /steps/substeps
  is 2 at step k, 1 elsewhere, /steps/substep_min h/2 there, the run ends at the same final time, and
  its free fall is implicit Euler's with that step in two halves (closed form);
- a real failure: a Neo-Hookean block compressed by half in 2 quasi-static steps (its Newton free
  motion diverges) completes with cuts and ends at the equilibrium a run of 8 steps reaches; with
  -time_step_control off the same run stops with the Newton error; a -time_step_min above the cuts
  it needs stops it with that error and the step control's note;
- on 2 ranks (--np 2) every run above gives the 1-rank answer (positions to 1e-10 m)."""
import os
import sys

import h5py
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import fctest as T  # noqa: E402

NP = T.np_from_argv()
c = T.Checker("step control np%d" % NP)
DROP = ["-options_file", "input/cube_drop.opts", "-time_steps", "12", "-output_every", "1"]


def run(name, args, np_=NP, check=True):
    f = T.out("%s_np%d.h5" % (name, np_))
    p = T.run(args + ["-output_file", f], np_=np_, check=check)
    return f, p


def datasets(h):
    """Every dataset of a run's file but the timings, by path"""
    out = {}
    h.visititems(lambda k, v: out.__setitem__(k, v[()]) if isinstance(v, h5py.Dataset)
                 and "timing" not in k and "wall_time" not in k and "memory" not in k and "restart" not in k else None)
    return out


# 1. no failure: on (the default) and off give the same file (on 1 rank bit for bit; on several, two runs may get
# different partitions: the same positions to round-off)
fon, _ = run("on", DROP)
foff, _ = run("off", DROP + ["-time_step_control", "off"])
with h5py.File(fon) as a, h5py.File(foff) as b:
    if NP == 1:
        da, db = datasets(a), datasets(b)
        differ = [k for k in da if k not in db or da[k].shape != db[k].shape or not np.array_equal(da[k], db[k])]
        c.check(set(da) == set(db) and not differ,
                "no failing step: -time_step_control on gives off's run bit for bit (%d datasets; differing: %s)"
                % (len(da), differ[:5] or "none"))
    else:
        d = np.abs(T.final_state(a) - T.final_state(b)).max()
        c.check(d < 1e-12, "no failing step: -time_step_control on gives off's positions (max %.1e m)" % d)
    c.check(np.all(a["steps/substeps"][:] == 1) and np.all(a["steps/substep_min"][:] == 0.01),
            "no failing step: /steps/substeps all 1, /steps/substep_min all h")

# 2. a planted failure at step 4 (the cube still falls freely: no contact before step ~30)
ffail, p = run("fail", DROP + ["-time_step_fail_at", "4"])
with h5py.File(ffail) as h, h5py.File(fon) as a:
    sub, hmin = h["steps/substeps"][:], h["steps/substep_min"][:]
    c.check(sub[3] == 2 and np.all(np.delete(sub, 3) == 1) and hmin[3] == 0.005,
            "planted failure at step 4: redone in 2 sub-steps of h/2 (substeps %s)" % sub.tolist())
    c.check(h["steps/time"][-1] == a["steps/time"][-1] and h["steps/step"][-1] == 12,
            "the run ends at the same final time %.3f s and step" % h["steps/time"][-1])
    # backward Euler free fall: v_{k+1} = v_k - g h, z_{k+1} = z_k + h v_{k+1}; step 4 in two halves
    g, z, v, zs = 9.81, 0.0, 0.0, []
    for k in range(12):
        for hs in ([0.005, 0.005] if k == 3 else [0.01]):
            v -= g * hs
            z += hs * v
        zs.append(z)
    dz = h["bodies/cube/centroid"][:, 2] - h["bodies/cube/centroid"][0, 2]  # a row per step, from step 1
    err = np.abs(dz - (np.array(zs) - zs[0])).max()
    c.check(err < 1e-12, "the centroid falls as implicit Euler with step 4 in two halves (max error %.1e m)" % err)
c.check("step 4 redone from t = 0.03 s with a time step of 0.005 s: a failure planted by -time_step_fail_at 4"
        in p.stdout and "step control: 1 step(s) cut" in p.stdout,
        "the cut has its line and the summary counts it")

# 3. a real failure: Newton diverges on a 25 % increment of a Neo-Hookean block
BLOCK = ["-options_file", "input/block_compress.opts"]
fref, _ = run("block8", BLOCK)
f2, p2 = run("block2", BLOCK + ["-time_steps", "2", "-time_step", "0.5"])
with h5py.File(f2) as h, h5py.File(fref) as r:
    sub = h["steps/substeps"][:]
    c.check(len(sub) == 2 and sub.min() >= 2, "block halved in 2 steps: completes with cuts (substeps %s)"
            % sub.tolist())
    _, x2 = T.sorted_positions(h, "block")
    _, x8 = T.sorted_positions(r, "block")
    d = np.abs(x2 - x8).max()
    c.check(d < 1e-6, "it ends at the equilibrium of the 8-step run (max vertex distance %.1e m)" % d)
_, poff = run("block2off", BLOCK + ["-time_steps", "2", "-time_step", "0.5", "-time_step_control", "off"], check=False)
c.check(poff.returncode != 0 and "Newton free motion of body 'block' did not converge" in poff.stdout + poff.stderr,
        "-time_step_control off: the same run stops with the Newton error (exit %d)" % poff.returncode)
_, pmin = run("block2min", BLOCK + ["-time_steps", "2", "-time_step", "0.5", "-time_step_min", "0.3"], check=False)
msg = pmin.stdout + pmin.stderr
c.check(pmin.returncode != 0 and "did not converge" in msg and "-time_step_min 0.3" in msg,
        "-time_step_min 0.3: stops with the Newton error and the step control's note (exit %d)" % pmin.returncode)

# 4. restart: a cut run stopped after step 1 and continued ends as the run that did not stop (the sub-step in
# use and its successes are in the restart state)
f1, _ = run("block2first", BLOCK + ["-time_steps", "1", "-time_step", "0.5"])
fr, _ = run("block2rest", BLOCK + ["-time_steps", "2", "-time_step", "0.5", "-restart", f1])
with h5py.File(fr) as h, h5py.File(f2) as a:
    d = np.abs(T.sorted_positions(h, "block")[1] - T.sorted_positions(a, "block")[1]).max()
    same = h["steps/substeps"][-1] == a["steps/substeps"][-1]
    c.check(d < 1e-12 and same, "restart after a cut step: step 2 in %d sub-steps as without the stop, positions "
            "to %.1e m" % (h["steps/substeps"][-1], d))

# 5. 2 ranks: the 1-rank answers
if NP > 1:
    for name, args in [("fail", DROP + ["-time_step_fail_at", "4"]), ("block2", BLOCK + ["-time_steps", "2",
                                                                                        "-time_step", "0.5"])]:
        f1, _ = run(name, args, np_=1)
        with h5py.File(f1) as a, h5py.File(T.out("%s_np%d.h5" % (name, NP))) as b:
            d = np.abs(T.final_state(a) - T.final_state(b)).max()
            same = np.array_equal(a["steps/substeps"][:], b["steps/substeps"][:])
            c.check(d < 1e-10 and same, "%s: %d ranks give the 1-rank sub-steps and positions (max %.1e m)"
                    % (name, NP, d))
c.done()
