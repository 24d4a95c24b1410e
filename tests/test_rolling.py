"""Rolling (issue 32): a rigid sphere, capsule and cylinder touch an analytic shape at the exact
closest points of their shape (src/collision/smooth.c), not at the vertices of their picture, so
they roll as their shape and not as a polyhedron.
  - On a level kinematic plane, rolling without slipping at 1 m/s, h = 0.005: each keeps at least
    98 % of its speed over 0.5 s, and its centre's height varies by less than 1 micrometre after
    the first step (no bumps).
  - Down a 30-degree plane (mu = 0.5, enough to roll without slipping), the centre accelerates at
    g sin(theta) / (1 + J / (m r^2)) within 2 %: (5/7) g sin(theta) for the sphere, (2/3) for the
    cylinder, the capsule's from its inertia about its axis.
  - A cylinder standing on its end on the plane, sliding at 0.5 m/s, stops and stays upright.
On N ranks, the answer of 1 rank (1e-8 relative).
Usage: test_rolling.py --np N"""
import numpy as np
import h5py
from fctest import Checker, np_from_argv, out, run

NP = np_from_argv(1)
c = Checker("rolling np%d" % NP)
g, h, r, th = 9.81, 0.005, 0.1, np.radians(30.0)
SHAPES = {  # body options (its axis along y where it has one), J / (m r^2) about the rolling axis
    "sphere": ([], 0.4),
    "cylinder": (["-ball_shape", "cylinder", "-ball_length", "0.2", "-ball_rotate", "1,0,0,90"], 0.5),
    "capsule": (["-ball_shape", "capsule", "-ball_length", "0.2", "-ball_rotate", "1,0,0,90"], None),
}
Vc, Vs = np.pi * r * r * 0.2, 4.0 / 3.0 * np.pi * r ** 3  # the capsule: cylinder and two half balls
SHAPES["capsule"] = (SHAPES["capsule"][0], (0.5 * Vc + 0.4 * Vs) / (Vc + Vs))


def go(tag, args):
    f = out("%s_np%d.h5" % (tag, NP))
    run(["-options_file", "input/rolling.opts"] + args + ["-quiet", "-output_file", f], np_=NP)
    if NP > 1:
        f1 = out("%s_np1.h5" % tag)
        run(["-options_file", "input/rolling.opts"] + args + ["-quiet", "-output_file", f1], np_=1)
        a, b = h5py.File(f1, "r")["bodies/ball/centroid"][:], h5py.File(f, "r")["bodies/ball/centroid"][:]
        d = np.abs(a - b).max() / np.abs(a).max()
        c.check(d <= 1e-8, "%s: %d ranks vs 1, centroid trajectory rel. diff %.1e <= 1e-8" % (tag, NP, d))
    return h5py.File(f, "r")


for name, (opts, jr) in SHAPES.items():
    x = go(name + "_level", opts)["bodies/ball/centroid"][:]
    v = np.diff(x[:, 0]) / h
    bump = x[1:, 2].max() - x[1:, 2].min()
    c.check(v[-1] >= 0.98 and bump < 1e-6, "%s rolling at 1 m/s on a plane: %.4f m/s after 0.5 s (>= 0.98), height "
            "varies by %.1e m after step 1 (< 1e-6)" % (name, v[-1], bump))
    incline = ["-ground_rotate", "0,1,0,30", "-ball_center", "%.17g,0,%.17g" % (r * np.sin(th), r * np.cos(th)),
               "-ball_velocity", "0,0,0", "-ball_angular_velocity", "0,0,0"]
    x = go(name + "_incline", opts + incline)["bodies/ball/centroid"][:]
    s = (x - x[0]) @ np.array([np.cos(th), 0.0, -np.sin(th)])
    t = h * np.arange(1, len(s) + 1)
    a = 2.0 * np.polyfit(t[10:], s[10:], 2)[0]
    want = g * np.sin(th) / (1.0 + jr)
    c.check(abs(a / want - 1) <= 0.02, "%s rolling down 30 degrees: a = %.4f m/s^2, g sin / (1 + %.4f) = %.4f "
            "(rel. %.1e <= 2e-2)" % (name, a, jr, want, abs(a / want - 1)))

f = go("standing", ["-ball_shape", "cylinder", "-ball_length", "0.3", "-ball_center", "0,0,0.2", "-ball_velocity",
                    "0.5,0,0", "-ball_angular_velocity", "0,0,0", "-time_steps", "200"])
x, q = f["bodies/ball/centroid"][:], f["bodies/ball/rotation"][:]
tilt = np.degrees(2 * np.arcsin(np.linalg.norm(q[-1, 1:3])))
c.check(abs(x[-1, 2] - 0.15) < 1e-3 and np.abs(np.diff(x[-20:, 0])).max() < 1e-9 and tilt < 0.1,
        "a cylinder standing on its end slides, stops (at x = %.4f m) and stays upright (tilt %.2g deg, centre at "
        "%.5f m)" % (x[-1, 0], tilt, x[-1, 2]))
c.done()
