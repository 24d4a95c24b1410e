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
  - On an FE slab (elements of 2.5 cm), a ball of r = 5 cm, a capsule and a cylinder on their side, each
    touching at the slab's surface points nearest its core (the cylinder: under its lowest line;
    -contact_rounded_surface exact, the default, src/collision/roundedsurface.c), keep 98 % of their
    speed over 0.5 s at 1 m/s, on a row of the slab's vertices, off it and between rows, with the
    height varying by less than 1 micrometre; down a 30-degree slope (gravity tilted) they accelerate
    as on the plane, within 2 %.
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
# On an FE slab (the slab of input/sliding.opts: 1 m x 0.3 m x 5 cm, elements of 2.5 cm, E = 1e8, its
# bottom fixed) a ball of r = 5 cm (a capsule on its side) touches at the points of the slab's
# surface nearest its core (-contact_rounded_surface exact), not at its picture's points nor only at the
# slab's vertices. Lanes: along a row of vertices (y = 0), 5 mm off it, and between two rows.
SLAB = ["-scene_bodies", "slab,ball", "-contact_pairs", "slab:ball", "-contact_rounded_surface", "exact",
        "-contact_distance", "0.005", "-slab_type", "fem",
        "-slab_dm_plex_filename", "meshes/slide_slab.msh", "-slab_material", "linear", "-slab_young", "1e8",
        "-slab_density", "1000", "-slab_translate", "0.4,0,-0.05", "-slab_fixed_box", "-3,-3,-1,3,3,-0.049"]
SMALL = ["-ball_radius", "0.05", "-ball_angular_velocity", "0,20,0"]


def go_slab(tag, args, tol=1e-8):
    common = SLAB + args + ["-quiet", "-time_step", "0.005", "-time_steps", "100", "-contact_mu", "0.5", "-ball_type",
                            "rigid", "-ball_density", "1000"]
    f = out("%s_np%d.h5" % (tag, NP))
    run(common + ["-output_file", f], np_=NP)
    if NP > 1:
        f1 = out("%s_np1.h5" % tag)
        run(common + ["-output_file", f1], np_=1)
        a, b = h5py.File(f1, "r")["bodies/ball/centroid"][:], h5py.File(f, "r")["bodies/ball/centroid"][:]
        d = np.abs(a - b).max() / np.abs(a).max()
        c.check(d <= tol, "%s: %d ranks vs 1, centroid trajectory rel. diff %.1e <= %.0e" % (tag, NP, d, tol))
    return h5py.File(f, "r")


# N ranks against 1: the ball's contacts are its foot and the slab's vertices, the same rows on any
# number of ranks (measured 1e-17 to 6e-16 relative); the capsule lies on a line of the slab's
# vertices, nearly redundant rows whose forces are not unique, and MUMPS' parallel round-off moves
# its trajectory by 4.0e-7 and 4.9e-7 relative (level, slope): bound 5e-6. The cylinder's line has
# its two ends awake and the points between dormant: 1e-8
for name, opts, lanes, tol in [("sphere", ["-ball_shape", "sphere"], [0.0, 0.005, 0.0125], 1e-8),
                               ("capsule", ["-ball_shape", "capsule", "-ball_length", "0.1", "-ball_rotate", "1,0,0,90"],
                                [0.0125], 5e-6),
                               ("cylinder", ["-ball_shape", "cylinder", "-ball_length", "0.1", "-ball_rotate", "1,0,0,90"],
                                [0.0, 0.0125], 1e-8)]:
    for y in lanes:
        H = go_slab("%s_slab_y%g" % (name, y), opts + SMALL + ["-ball_center", "0.1125,%g,0.05" % y, "-ball_velocity", "1,0,0"], tol)
        x = H["bodies/ball/centroid"][:]
        v = np.diff(x[:, 0]) / h
        bump = x[1:, 2].max() - x[1:, 2].min()
        c.check(v[-1] >= 0.98 and bump < 1e-6 and H["steps/residual"][:].max() <= 1.0001e-8,
                "%s (r 5 cm) rolling at 1 m/s on an FE slab, lane y = %g m: %.4f m/s after 0.5 s (>= 0.98), height varies "
                "by %.1e m after step 1 (< 1e-6), every step converged" % (name, y, v[-1], bump))
    # down a 30-degree FE slope (gravity tilted), from rest
    x = go_slab("%s_slab_incline" % name, opts + SMALL + [
        "-ball_center", "0.1125,0.0125,0.05", "-ball_velocity", "0,0,0", "-ball_angular_velocity", "0,0,0",
        "-gravity", "%.17g,0,%.17g" % (g * np.sin(th), -g * np.cos(th))], tol)["bodies/ball/centroid"][:]
    t = h * np.arange(1, len(x) + 1)
    a = 2.0 * np.polyfit(t[10:], x[10:, 0] - x[0, 0], 2)[0]
    jr = SHAPES[name][1]
    want = g * np.sin(th) / (1.0 + jr)
    c.check(abs(a / want - 1) <= 0.02, "%s rolling down a 30-degree FE slope: a = %.4f m/s^2, g sin / (1 + %.4f) = %.4f "
            "(rel. %.1e <= 2e-2)" % (name, a, jr, want, abs(a / want - 1)))

c.done()
