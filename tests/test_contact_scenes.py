"""Contact scenes (Algorithm 1) against closed forms:
- incline: a rigid box on a kinematic plane tilted by theta, mu = 0.5. At tan(theta) = 0.8 mu it
  sticks (slides less than 1e-3 of what a frictionless box would in 1 s); at tan(theta) = 1.25 mu
  it slides with a = g (sin - mu cos) within 2% (a from the discrete implicit Euler distance
  s_N = a h^2 N (N+1) / 2);
- a rigid box sliding on flat ground at v0 stops after v0^2 / (2 mu g) within 3%;
- an FE cube resting on a plane: after 1 s the penetration on the real end-of-step geometry is
  below 1e-3 of its edge and it does not drift;
- a frictionless scene has exactly one constraint row per contact (three with friction);
- a rigid box set on another box (rigid or kinematic, 0.4 x 0.4 x 0.2 m) face to face rests on it,
  as wide as it (corners on the edges), wider, half over it, turned 45 degrees or across it: after
  1 s its centroid is where it was put, on the lower box's top (src/collision/boxbox.c);
- 2 MPI ranks give the same contact forces as 1 rank (1e-8 relative to the largest force).
Usage: test_contact_scenes.py [--np N] (N > 1 adds the rank comparison)"""
import numpy as np
import h5py
from fctest import run, out, Checker, np_from_argv

NP = np_from_argv()
c = Checker("contact scenes np%d" % NP)
g, mu, h = 9.81, 0.5, 0.01


def box_on_plane(name, theta_deg, v0=0.0, steps=100, extra=()):
    th = np.radians(theta_deg)
    ctr = 0.1 * np.array([np.sin(th), 0.0, np.cos(th)])  # box centre above the tilted plane
    f = out("%s_np%d.h5" % (name, NP))
    run(["-scene_bodies", "box,ground", "-time_step", h, "-time_steps", steps, "-output_every", steps,
         "-contact_pairs", "box:ground", "-contact_mu", mu, "-contact_distance", "0.01", "-pgs_max_it", "5000",
         "-pgs_tol", "1e-10", "-output_file", f, "-quiet",
         "-box_type", "rigid", "-box_shape", "box", "-box_half_extents", "0.2,0.2,0.1", "-box_density", "500",
         "-box_rotate", "0,1,0,%.12g" % theta_deg, "-box_center", "%.15g,%.15g,%.15g" % tuple(ctr),
         "-box_velocity", "%.15g,0,%.15g" % (v0 * np.cos(th), -v0 * np.sin(th)),
         "-ground_type", "kinematic", "-ground_shape", "plane", "-ground_rotate", "0,1,0,%.12g" % theta_deg] + list(extra), np_=NP)
    H = h5py.File(f, "r")
    slope = np.array([np.cos(th), 0.0, -np.sin(th)])  # down the slope
    x = H["bodies/box/centroid"][:]
    x0 = H["bodies/box"].attrs["initial_centroid"]
    return H, (x - x0) @ slope, th


N = 100
H, s, th = box_on_plane("stick", np.degrees(np.arctan(0.8 * mu)))
free = g * np.sin(th) * h * h * N * (N + 1) / 2
c.check(abs(s[-1]) < 1e-3 * free, "incline tan = 0.8 mu: slides %.3e m in 1 s, frictionless %.3f m (ratio %.1e < 1e-3)" % (s[-1], free, abs(s[-1]) / free))
H, s, th = box_on_plane("slide", np.degrees(np.arctan(1.25 * mu)))
a_exact = g * (np.sin(th) - mu * np.cos(th))
a = 2 * s[-1] / (h * h * N * (N + 1))
c.check(abs(a - a_exact) / a_exact < 0.02, "incline tan = 1.25 mu: a = %.4f m/s^2, g (sin - mu cos) = %.4f (%.2f%%)" % (a, a_exact, 100 * abs(a - a_exact) / a_exact))
c.check(np.all(H["steps/contacts"][:] >= 4), "box on incline keeps its 4 corner contacts")

v0 = 2.0
H, s, th = box_on_plane("sliding", 0.0, v0=v0, steps=70)
d_exact = v0 * v0 / (2 * mu * g)
c.check(abs(s[-1] - d_exact) / d_exact < 0.03, "sliding at %.1f m/s stops after %.4f m, v0^2/(2 mu g) = %.4f (%.2f%%)" % (v0, s[-1], d_exact, 100 * abs(s[-1] - d_exact) / d_exact))
c.check(abs(s[-1] - s[-10]) < 1e-9, "and stays stopped (last 10 steps moved %.1e m)" % abs(s[-1] - s[-10]))

for fric in [0.0, 0.4]:
    f = out("rest_%g_np%d.h5" % (fric, NP))
    run(["-scene_bodies", "cube,ground", "-time_step", h, "-time_steps", 100, "-output_every", 50, "-contact_pairs", "cube:ground",
         "-contact_mu", fric, "-contact_distance", "0.01", "-output_file", f, "-quiet", "-cube_type", "fem",
         "-cube_dm_plex_filename", "meshes/cube_coarse.msh", "-cube_young", "1e6", "-cube_density", "1000", "-cube_translate", "0,0,0.5",
         "-ground_type", "kinematic", "-ground_shape", "plane"], np_=NP)
    H = h5py.File(f, "r")
    nc, rows = H["steps/contacts"][:], H["steps/constraint_rows"][:]
    if fric == 0.0:
        c.check(np.all(rows == nc) and nc.min() > 0, "frictionless: one row per contact every step (%d contacts, %d rows)" % (nc[-1], rows[-1]))
    else:
        c.check(np.all(rows == 3 * nc), "mu = %.1f: three rows per contact" % fric)
        pen = H["steps/max_penetration"][-1]
        c.check(pen < 1e-3 * 1.0, "resting FE cube: end-of-step penetration after 1 s %.2e m < 1e-3 edge" % pen)
        x = H["bodies/cube/centroid"][:]
        last = x[75:]  # the last 0.25 s: settled (a decaying oscillation of a few micrometres) and no trend
        drift = np.abs(last[:, :2] - last[0, :2]).max()
        sink = np.abs(last[:, 2] - last[0, 2]).max()
        c.check(drift < 1e-5 and sink < 1e-5, "resting FE cube does not drift: lateral %.1e m, vertical %.1e m over the last 0.25 s (< 1e-5 edge)" % (drift, sink))

# boxes on boxes: (label, upper half extents, centre x, y, turn about z in degrees, lower box's type)
BOXES = [("equal", "0.2,0.2,0.05", 0, 0, 0, "rigid"), ("wider", "0.4,0.3,0.05", 0, 0, 0, "rigid"),
         ("half over", "0.2,0.2,0.05", 0.1, 0.05, 0, "rigid"), ("turned 45", "0.2,0.2,0.05", 0, 0, 45, "rigid"),
         ("across", "0.5,0.1,0.05", 0, 0, 30, "rigid"), ("equal, on a kinematic box", "0.2,0.2,0.05", 0, 0, 0, "kinematic")]
for label, he, x, y, turn, lower in BOXES:
    f = out("box_on_box_%s_np%d.h5" % (label.replace(" ", "_").replace(",", ""), NP))
    pairs = "top:bot,bot:ground,top:ground" if lower == "rigid" else "top:bot,top:ground"
    run(["-scene_bodies", "top,bot,ground", "-time_step", h, "-time_steps", 100, "-output_every", 100, "-contact_pairs", pairs,
         "-contact_mu", mu, "-contact_distance", "0.01", "-output_file", f, "-quiet",
         "-top_type", "rigid", "-top_shape", "box", "-top_half_extents", he, "-top_density", "1000",
         "-top_center", "%g,%g,0.2501" % (x, y), "-top_rotate", "0,0,1,%g" % turn,
         "-bot_type", lower, "-bot_shape", "box", "-bot_half_extents", "0.2,0.2,0.1", "-bot_center", "0,0,0.1",
         "-ground_type", "kinematic", "-ground_shape", "plane"] + (["-bot_density", "1000"] if lower == "rigid" else []), np_=NP)
    H = h5py.File(f, "r")
    xt = H["bodies/top/centroid"][-1]
    # measured: 2.5e-10 m or less off (corners on the edges: the boxes settle to round-off of the
    # solver's tolerance); with the corners against the lower box's distance alone the upper box sank
    # through (equal) or fell through (wider). Bound 1e-8 m
    err = np.abs(xt - [x, y, 0.25]).max()
    c.check(err < 1e-8 and H["steps/residual"][:].max() <= 1.0001e-8,
            "box on box, %s: rests at (%.4f, %.4f, %.6f) after 1 s, %.1e m off (< 1e-8), %d contacts" % (label, xt[0], xt[1], xt[2], err, H["steps/contacts"][-1]))

if NP > 1:
    files = []
    for n in [1, NP]:
        f = out("forces_np%d.h5" % n)
        run(["-options_file", "input/cube_drop.opts", "-time_steps", "30", "-pgs_tol", "1e-10", "-pgs_max_it", "20000",
             "-output_file", f, "-quiet"], np_=n)
        files.append(h5py.File(f, "r"))
    a, b = files
    same = np.array_equal(a["contacts/offset"][:], b["contacts/offset"][:])
    c.check(same, "same contacts per step on 1 and %d ranks (%d contact records)" % (NP, a["contacts/offset"][-1]))
    if same:
        fa, fb = a["contacts/force"][:], b["contacts/force"][:]
        err = np.abs(fa - fb).max() / np.abs(fa).max()
        c.check(err < 1e-8, "contact forces 1 vs %d ranks: rel. diff %.2e < 1e-8" % (NP, err))
c.done()
