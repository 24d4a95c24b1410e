"""The Python examples of issue 40 (examples/python/), each run as a user runs it (the script under this
Python, under mpirun -n NP --oversubscribe for --np > 1), on --np ranks:

- gripper.py: each finger reaches its normal force target (4 N) within 5 %, the mean over the hold's
  second half and every step of the hold; the force control keeps both within 10 % through the lift
  and the carry (the hanging ball's weight shifts from the plane to the fingers' friction); the ball
  rises with the fingers: its centre's lift within 5 mm of the fingers' 30 mm (what it lags is its
  elastic sag as its weight passes from the plane to the fingers' friction, of the order of its
  indentation under its weight on the plane, about 3 mm by Hertz; a ball that slipped would lag by a
  good part of the 30 mm), it slides down the fingers by less than 0.5 mm over the carry's second half
  (0.1 s: a slip goes on, and at a hundredth of g it covers 0.5 mm in that time), and it is off the
  plane (no ground force, its lowest point above 2 cm);
- with mu = 0.3 instead of 1 (2 mu F = 2.4 N, less than the ball's 5.5 N weight; 1 rank) the same
  grip lets the ball slip: it stays on the plane (lift below 5 mm), so the check above can fail;
- mu_sweep.py: its PNG, CSV and one HDF5 file per mu; the block slides (more than 1 mm) iff
  tan(30) > mu, as Coulomb says, by the distance of the backward Euler steps a h^2 n (n + 1) / 2 to
  1e-6 m, and not at all (below 1e-6 m) otherwise;
- campaign.py (two drop heights, one Young's modulus): one complete HDF5 file per run and the
  summary table naming each, its impact speed within 3 % of sqrt(2 g h) (the largest speed of the
  centroid over a step, a step's fall short of the contact)."""
import csv
import json
import os
import subprocess
import sys
import time

import h5py
import numpy as np

from fctest import out, Checker, np_from_argv, ROOT, ENV

NP = np_from_argv()
c = Checker("python_examples np%d" % NP)
EXAMPLES = os.path.join(ROOT, "examples", "python")


def example(script, *args, np_=NP):
    """Run examples/python/<script> with args on np_ ranks from the repository root; its stdout"""
    cmd = [sys.executable, os.path.join(EXAMPLES, script)] + [str(a) for a in args]
    if np_ > 1:
        cmd = ["mpirun", "-n", str(np_), "--oversubscribe"] + cmd
    t0 = time.time()
    p = subprocess.run(cmd, cwd=ROOT, env=ENV, capture_output=True, text=True, errors="replace", timeout=600)
    print("%s: %.1f s" % (" ".join(cmd[-len(args) - 2:]), time.time() - t0))
    if p.returncode:
        sys.stderr.write(p.stdout + p.stderr)
        raise RuntimeError("%s failed (%d)" % (" ".join(cmd), p.returncode))
    return p.stdout


# the gripper
fig = out("gripper.json")
example("gripper.py", "--output", out("gripper.h5"), "--json", fig)
g = json.load(open(fig))
for f in ("left", "right"):
    c.check(abs(g["force_reached"][f] / g["target"] - 1) <= 0.05,
            "%s finger: %.4f N reached over the hold, target %.1f N (within 5 %%)" %
            (f, g["force_reached"][f], g["target"]))
c.check(g["hold_error"] <= 0.05, "every step of the hold within 5 %% of the target (largest error %.2f %%)" %
        (100 * g["hold_error"]))
c.check(g["lift_error"] <= 0.10, "through the lift and the carry within 10 %% (largest error %.2f %%)" %
        (100 * g["lift_error"]))
c.check(abs(g["finger_lift"] - g["ball_lift"]) <= 5e-3,
        "the ball rose %.2f mm with the fingers' %.2f mm (within 5 mm)" %
        (1e3 * g["ball_lift"], 1e3 * g["finger_lift"]))
c.check(abs(g["carry_slip"]) <= 5e-4, "it slid %.3f mm down the fingers over the carry's second half (below 0.5 mm)" %
        (1e3 * g["carry_slip"]))
c.check(g["ground_force"] == 0 and g["ball_min_z"] > 0.02, "off the plane: ground force %g N, lowest point %.1f mm" %
        (g["ground_force"], 1e3 * g["ball_min_z"]))
with h5py.File(out("gripper.h5"), "r") as o:
    S, steps = int(o["complete"][0]), int(o.attrs["time_steps"])
c.check(S == steps == g["steps"], "its output file complete: %d of %d steps" % (S, steps))

if NP == 1:  # the same grip with too little friction: the ball slips out
    fig = out("gripper_mu03.json")
    example("gripper.py", "--output", out("gripper_mu03.h5"), "--json", fig, "--mu", 0.3)
    g = json.load(open(fig))
    c.check(g["ball_lift"] < 5e-3 and 2 * g["mu"] * g["target"] < g["weight"],
            "mu = 0.3 (2 mu F = %.1f N < weight %.2f N): the ball slipped out, lifted %.2f mm of %.0f mm" %
            (2 * g["mu"] * g["target"], g["weight"], 1e3 * g["ball_lift"], 1e3 * g["finger_lift"]))

# the sweep of mu
png, outdir = out("sweep/mu_sweep.png"), out("sweep")
example("mu_sweep.py", "--png", png, "--outdir", outdir)
rows = list(csv.DictReader(open(out("sweep/mu_sweep.csv"))))
c.check(open(png, "rb").read(8) == b"\x89PNG\r\n\x1a\n" and all(os.path.exists(r["file"]) for r in rows)
        and len(rows) >= 10, "the plot, the CSV and one HDF5 file per mu (%d values) written" % len(rows))
tan = np.tan(np.radians(30))
for r in rows:
    mu, d, e = float(r["mu"]), float(r["distance"]), float(r["expected_steps"])
    slides = tan > mu
    ok = (d > 1e-3 and abs(d - e) <= 1e-6) if slides else abs(d) <= 1e-6
    c.check(ok, "mu = %.2f: %s %.6f m (backward Euler steps: %.6f m)" % (mu, "slid" if slides else "stuck", d, e))

# the campaign
camp = out("campaign")
text = example("campaign.py", camp, "--heights", "0.05,0.1", "--young", "1e5")
for h in (0.05, 0.1):
    name = "ball_h%.3f_E1e+05.h5" % h
    f = os.path.join(camp, name)
    with h5py.File(f, "r") as o:
        S = int(o["complete"][0])
        zc = np.concatenate([[o["bodies/ball"].attrs["initial_centroid"][2]], o["bodies/ball/centroid"][:S, 2]])
        v = -np.diff(zc).min() / o.attrs["time_step"]
        steps = int(o.attrs["time_steps"])
    line = [ln for ln in text.splitlines() if ln.startswith(name)]
    c.check(S == steps and len(line) == 1 and abs(v / np.sqrt(2 * 9.81 * h) - 1) <= 0.03,
            "campaign h = %.2f m: %s complete (%d of %d steps), in the summary; impact %.3f m/s, sqrt(2gh) = %.3f m/s" %
            (h, name, S, steps, v, np.sqrt(2 * 9.81 * h)))
c.done()
