"""Hyperelastic bodies (-<body>_material neohookean, the Newton free motion), on --np ranks:
- uniaxial stretch (to 1.5) and compression (to 0.9) of the 5 x 1 x 1 bar, clamped at xmin and
  moved at xmax, quasi-static: in the middle of the bar (Saint-Venant: two widths from the ends) the
  axial and lateral stretches and the reaction at xmin follow the analytic uniaxial curve of the
  compressible Neo-Hookean model (lateral stretch from P22 = 0, force P11 A0) to 1 %;
- Newton converges quadratically: in the SNES history of the stretch's last step some iterate with
  a relative residual e_k below 1e-2 has e_(k+1) <= 10 e_k^2;
- energy: a free spinning cube (no gravity, no damping) loses energy to implicit Euler at O(h): the
  loss over 0.4 s halves with the time step (ratio 1.7-2.3);
- contact on top: the cube dropped on the plane (input/cube_drop.opts) comes to rest where the
  co-rotational one does (small strain: to 1e-4 m), no element inverted, on 1 rank and --np;
- hard case: the soft block crushed to 30 % by a kinematic plate (input/hard/crush_neohookean.opts)
  runs to the end with no element inverted, no intersection, its top at the plate; the ball caught by
  the Neo-Hookean membrane (input/hard/membrane_neohookean.opts) at more than 90 % stretch and thrown
  back, no element inverted, no sheet vertex in the ball, no intersection deeper than 1 mm (the
  ball's exact surface between its picture's points, tests/test_membrane.py), while the co-rotational
  membrane with the same E and nu turns an element inside out (1 rank; -sheet_inverted error stops
  it there, the co-rotational default running on);
- -restart: the drop continued from step 28 (with another -snes_rtol) ends where the uninterrupted
  run does, to 1e-9 m;
- --np > 1: the stretch's reaction and the drop's positions are the 1-rank ones to 1e-8;
- bad input: -free_motion with an unknown value, newton with -rayleigh_stiffness, neohookean with
  -factorization reuse: an error naming the option."""
import re

import h5py
import numpy as np

from fctest import run, out, Checker, np_from_argv, sorted_positions

NP = np_from_argv()
c = Checker("hyperelastic")
E, NU = 1e5, 0.3
LAM, MU = E * NU / ((1 + NU) * (1 - 2 * NU)), E / (2 * (1 + NU))


def uniaxial(l1):
    """Lateral stretch and nominal stress P11 of the compressible Neo-Hookean model in uniaxial stress"""
    lo, hi = 0.3, 2.0  # P22 = 0 by bisection: mu (l2^2 - 1) + lambda ln(l1 l2^2) grows with l2
    for _ in range(100):
        l2 = 0.5 * (lo + hi)
        lo, hi = (l2, hi) if MU * (l2 * l2 - 1) + LAM * np.log(l1 * l2 * l2) < 0 else (lo, l2)
    return l2, MU * (l1 - 1 / l1) + LAM * np.log(l1 * l2 * l2) / l1


def bar(name, dx, np_, extra=()):
    f = out("%s_np%d.h5" % (name, np_))
    p = run(["-scene_bodies", "bar", "-bar_type", "fem", "-bar_dm_plex_filename", "meshes/beam_n4.msh",
             "-bar_material", "neohookean", "-bar_young", E, "-bar_poisson", NU, "-bar_density", 1000,
             "-bar_fixed", "box:-1,-1,-1,1e-9,1,1", "-bar_displacement", "box:4.999999,-1,-1,6,1,1=0:0,0,0;1:%g,0,0" % dx, "-time_integration", "static",
             "-gravity", "0,0,0", "-time_step", 0.25, "-time_steps", 4, "-output_every", 4, "-output_file", f,
             "-quiet"] + list(extra), np_)
    return h5py.File(f, "r"), p


for name, dx in [("stretch", 2.5), ("compression", -0.5)]:
    h, p = bar(name, dx, NP, ["-bar_snes_monitor"] if name == "stretch" else [])
    ref, pos = sorted_positions(h, "bar")
    mid = [np.abs(ref[:, 0] - x) < 1e-9 for x in (2.0, 2.5, 3.0)]
    l1 = pos[mid[2], 0].mean() - pos[mid[0], 0].mean()  # the reference planes are 1 apart
    l2 = (pos[mid[1], 1].max() - pos[mid[1], 1].min()) / (ref[mid[1], 1].max() - ref[mid[1], 1].min())
    force = -h["bodies/bar/reactions/box:-1,-1,-1,1e-9,1,1"][-1][0]
    w2, P11 = uniaxial(l1)
    e2, ef = abs(l2 - w2) / abs(w2 - 1), abs(force - P11) / abs(P11)  # A0 = 1
    c.check(e2 < 0.01 and ef < 0.01,
            "%s to %.2f: middle stretch %.4f, lateral %.4f (analytic %.4f: %.1e of its change), reaction %.5g N "
            "(analytic P11 A0 %.5g N: %.1e)" % (name, 1 + dx / 5, l1, l2, w2, e2, force, P11, ef))
    if name == "stretch":
        norms = [float(x) for x in re.findall(r"SNES Function norm ([0-9.eE+-]+)", p.stdout)]
        starts = [i for i, l in enumerate(re.findall(r"(\d+) SNES Function norm", p.stdout)) if l == "0"]
        last = norms[starts[-1]:]
        e = [r / last[0] for r in last]
        quad = [k for k in range(len(e) - 1) if e[k] < 1e-2 and e[k + 1] <= 10 * e[k] ** 2]
        c.check(len(quad) > 0 and len(e) <= 8,
                "Newton's last step: relative residuals %s; quadratic at iterate(s) %s" %
                (" ".join("%.1e" % x for x in e), quad))
        its = h["steps/free_motion_iterations"][:]
        c.check(its.min() >= 2, "/steps/free_motion_iterations counts them: %s" % its)
        if NP > 1:
            h1, _ = bar(name, dx, 1)
            r1 = -h1["bodies/bar/reactions/box:-1,-1,-1,1e-9,1,1"][-1][0]
            c.check(abs(r1 - force) <= 1e-8 * abs(force), "%d ranks: the 1-rank reaction to %.1e" %
                    (NP, abs(r1 - force) / abs(force)))


def spin(dt):
    f = out("spin_%g.h5" % dt)
    run(["-scene_bodies", "cube", "-cube_type", "fem", "-cube_dm_plex_filename", "meshes/cube_coarse.msh",
         "-cube_material", "neohookean", "-cube_young", 2e4, "-cube_poisson", 0.3, "-cube_density", 1000,
         "-cube_angular_velocity", "0,0,2", "-gravity", "0,0,0", "-time_step", dt, "-time_steps", int(round(0.4 / dt)),
         "-output_every", 1000, "-output_file", f, "-quiet"], NP)
    h = h5py.File(f, "r")
    return h.attrs["initial_energy"][0] - h["steps/energy"][-1]


l1, l2 = spin(0.01), spin(0.005)
c.check(l1 > 0 and 1.7 <= l1 / l2 <= 2.3, "energy lost by implicit Euler over 0.4 s: %.4g J at h = 0.01, %.4g J at "
        "h = 0.005: ratio %.2f (first order: 2)" % (l1, l2, l1 / l2))


def drop(material, np_):
    f = out("drop_%s_np%d.h5" % (material, np_))
    run(["-options_file", "input/cube_drop.opts", "-cube_material", material, "-time_steps", 60,
         "-output_every", 60, "-output_file", f, "-quiet"], np_)
    return h5py.File(f, "r")


nh, cr = drop("neohookean", NP), drop("corotational", NP)
znh, zcr = nh["bodies/cube/centroid"][-1][2], cr["bodies/cube/centroid"][-1][2]
c.check(abs(znh - zcr) < 1e-4 and nh["steps/contacts"][-1] > 0,
        "dropped on the plane: at rest at z = %.6f m (co-rotational %.6f m), %d contacts" %
        (znh, zcr, nh["steps/contacts"][-1]))
# -restart: the drop continued from its step 28 ends where the uninterrupted run does (the Newton free
# motion has no state of its own beyond u and v)
half, rest = out("drop_half.h5"), out("drop_rest.h5")
base = ["-options_file", "input/cube_drop.opts", "-cube_material", "neohookean", "-output_every", 4, "-quiet"]
run(base + ["-time_steps", 28, "-output_file", half], NP)
run(base + ["-time_steps", 60, "-output_file", rest, "-restart", half, "-cube_snes_rtol", 1e-11], NP)
_, xr = sorted_positions(h5py.File(rest, "r"), "cube")
_, xf = sorted_positions(nh, "cube")
c.check(np.abs(xr - xf).max() < 1e-9, "-restart at step 28 (a new -cube_snes_rtol allowed): the 60-step positions "
        "to %.1e m" % np.abs(xr - xf).max())
if NP > 1:
    ref, x = sorted_positions(nh, "cube")
    _, x1 = sorted_positions(drop("neohookean", 1), "cube")
    c.check(np.abs(x - x1).max() < 1e-8, "%d ranks: the drop's positions are the 1-rank ones to %.1e m" %
            (NP, np.abs(x - x1).max()))

# the hard case: a soft block crushed to 30 % of its height by a kinematic plate (input/hard/crush_neohookean.opts)
f = out("crush.h5")
p = run(["-options_file", "input/hard/crush_neohookean.opts", "-output_file", f, "-quiet"], NP, check=False)
h = h5py.File(f, "r")
s = h["steps"]
top = h["bodies/block/positions"][-1][:, 2].max()
c.check(p.returncode == 0 and len(s["step"]) == 100 and s["intersections"][:].max() == 0 and
        s["max_penetration"][:].max() < 1e-6 and abs(top + 0.2) < 1e-3,
        "crushed to 30 %%: %d steps, no element inverted (the run's check), no intersection, penetration %.1e m, top at "
        "z = %.4f m (the plate: -0.2), Newton %d-%d iterations a step" %
        (len(s["step"]), s["max_penetration"][:].max(), top, s["free_motion_iterations"][:].min(),
         s["free_motion_iterations"][:].max()))

# the hard case: the ball caught by a Neo-Hookean membrane at about 100 % stretch (input/hard/membrane_neohookean.opts);
# the co-rotational membrane with the same E and nu is stretched through its thickness. On 1 rank only: the
# Neo-Hookean body in contact runs on 2 ranks in the drop and the crush above.
if NP == 1:
    f = out("membrane_nh.h5")
    p = run(["-options_file", "input/hard/membrane_neohookean.opts", "-output_file", f, "-output_every", 1, "-quiet",
             "-contact_intersection_depth", 1e-3], NP, check=False)
    h = h5py.File(f, "r")
    s = h["steps"]
    z = h["bodies/ball/centroid"][:, 2]
    P = h["bodies/sheet/positions"][:]
    cells = h["bodies/sheet/mesh/cells"][:]
    q = P[:, cells]
    vol = np.einsum("fij,fij->fi", q[:, :, 1] - q[:, :, 0], np.cross(q[:, :, 2] - q[:, :, 0], q[:, :, 3] - q[:, :, 0]))
    cen = np.concatenate([[[0, 0, 0.075]], h["bodies/ball/centroid"][:]])[h["frames/step"][:]]
    inside = (np.linalg.norm(P - cen[:, None, :], axis=2) < 0.05 - 1e-6).sum()
    stretch = np.hypot(0.15, P[:, :, 2].min()) / 0.15
    c.check(p.returncode == 0 and len(s["step"]) == 160 and stretch > 1.9 and z[-1] > 0.1 and (vol <= 0).sum() == 0 and
            inside == 0 and s["intersections"][:].max() == 0 and s["residual"][:].max() <= 1.0001e-8,
            "membrane: %d steps, caught at %.0f %% stretch (the sheet's lowest point %.3f m) and thrown back to z = %.3f, "
            "no element inverted, %d sheet vertices in the ball, no intersection deeper than 1 mm, contact residual %.1e" %
            (len(s["step"]), 100 * (stretch - 1), P[:, :, 2].min(), z[-1], inside, s["residual"][:].max()))
    f = out("membrane_corot.h5")
    p = run(["-options_file", "input/hard/membrane_neohookean.opts", "-output_file", f, "-quiet",
             "-sheet_material", "corotational", "-sheet_inverted", "error"], NP, check=False)
    c.check(p.returncode != 0 and "inside out" in p.stdout + p.stderr,
            "membrane: co-rotational with the same E and nu is stretched through its thickness (exit %d, step %d)" %
            (p.returncode, h5py.File(f, "r")["complete"][0]))

BAD = ["-scene_bodies", "cube", "-cube_type", "fem", "-cube_dm_plex_filename", "meshes/cube_coarse.msh",
       "-cube_young", 1e5, "-cube_density", 100, "-time_steps", 1, "-output_file", out("bad.h5")]
for args, opt in [(["-cube_material", "neohookean", "-cube_free_motion", "quadratic"], "-cube_free_motion"),
                  (["-cube_material", "neohookean", "-cube_rayleigh_stiffness", 0.01], "-cube_rayleigh_stiffness"),
                  (["-cube_material", "neohookean", "-cube_factorization", "reuse"], "-cube_factorization")]:
    p = run(BAD + args, NP, check=False)
    c.check(p.returncode != 0 and opt in p.stdout + p.stderr and "Traceback" not in p.stderr,
            "%s: exit %d, the message names %s" % (" ".join(map(str, args)), p.returncode, opt))
c.done()
