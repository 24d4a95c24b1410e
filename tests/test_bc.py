"""Boundary conditions, loads and reactions on regions (docs/scenes.md), against analytic solutions,
on --np ranks:

- uniaxial compression: a unit cube (nu = 0) clamped on gmsh's "zmin" with "zmax" moved down by
  -cube_displacement to a strain of 1 %: with nu = 0 the clamps do not restrain a lateral
  expansion, and the P1 space holds the exact linear field, so the reactions are E A eps
  (+ on zmin, - on zmax) to round-off, their moments about the faces' centroids vanish, and the
  elastic energy is 1/2 E eps^2 V. The same strain from a -cube_force of E A eps on "zmax" gives
  the displacement eps L. Static solutions come from one implicit Euler step with h = 1e3 s
  (tests/test_cantilever.py), the tables held at their last row;
- Lame: a thick hollow sphere (a = 0.5, b = 1, E = 1e6, nu = 0.3) under -shell_pressure 1e3 on
  "inner" (strains of 1e-4: the follower pressure's growth with the area is negligible): the mean
  radial displacement at r = a and r = b against
  u(r) = p a^3 / (E (b^3 - a^3)) ((1 - 2 nu) r + (1 + nu) b^3 / (2 r^2)), within 2 % on the
  finer mesh (lc 0.05), and closer than on the coarser one (lc 0.1; the error falls as lc^2); on
  --np > 1 the coarser mesh's errors equal the 1-rank ones (1e-7: the free body's rigid modes are
  held only by M / h^2);
- a force on a Physical Point group (the finger's tip corner), statically, is the base's reaction;
- the reaction is the contact force: a rigid box rests on an FE block clamped at "zmin"; at every
  step the block's discrete momentum balance holds, R + F_contact + m g = m (c'' + alpha c') with c
  the block's centroid (the sum of the rows of the step's equations: the elastic forces of a linear
  body sum to zero), to 1e-8 of m g;
- a load on a region sharing vertices with the fixed one (xmax, the volume group "body"): its share
  on the fixed vertices goes to the support, statically the reaction is the whole load (and the
  weight);
- quasi-static (-time_integration static): the compression's reaction follows its ramp at every
  step; the sphere of input/pressed.opts pressed on its block: the cap's reaction is the contact
  force at every step, and its contact_pressure field sums to that force over the vertex areas;
  damping, an FE body held by nothing and a rigid body are refused;
- an attachment (-cube_attach zmin:hand): under a turning kinematic hand, statically, the
  co-rotational cube turns with its base as a rigid body; dynamically the region is at the hand's
  pose at every frame; an unknown body and a rigid one are refused;
- a kinematic body follows its -trajectory table exactly (centre, and orientation by slerp);
- restart: a prescribed motion restarted at step 10 ends where the uninterrupted run does; another
  -cube_young is refused naming it, a table with new rows is accepted;
- a constrained region against a kinematic plane: no contact is made there (the rule of
  docs/scenes.md) and the run converges;
- bad input: an unknown region (the message lists the mesh's groups), a table whose time does not
  increase, a NaN in a table, a region both fixed and prescribed, a missing table file."""
import numpy as np
import h5py
from fctest import run, out, Checker, np_from_argv

NP = np_from_argv()
c = Checker("bc")
E, H = 1e5, 1e3


def cube(name, extra, mesh="meshes/cube_coarse.msh"):
    f = out(name + ".h5")
    run(["-scene_bodies", "cube", "-cube_type", "fem", "-cube_dm_plex_filename", mesh, "-cube_material", "linear",
         "-cube_young", E, "-cube_poisson", 0, "-cube_density", 100, "-gravity", "0,0,0", "-time_step", H,
         "-time_steps", 1, "-output_file", f, "-quiet"] + extra, NP)
    return h5py.File(f, "r")


BASE0 = ["-scene_bodies", "cube", "-cube_type", "fem", "-cube_dm_plex_filename", "meshes/cube_coarse.msh",
         "-cube_young", 1e5, "-cube_density", 100, "-time_steps", 1, "-output_file", out("bad0.h5")]

# uniaxial compression by a prescribed displacement
h = cube("compress", ["-cube_fixed", "zmin", "-cube_displacement", "zmax=0:0,0,0;1:0,0,-0.01"])
R = h["bodies/cube/reactions"]
bot, top = R["zmin"][-1], R["zmax"][-1]
c.check(abs(bot[2] - E * 0.01) < 1e-6 * E * 0.01 and abs(top[2] + E * 0.01) < 1e-6 * E * 0.01,
        "reactions E A eps = %g: zmin %.9g, zmax %.9g" % (E * 0.01, bot[2], top[2]))
c.check(np.abs(np.r_[bot[:2], top[:2], bot[3:], top[3:]]).max() < 1e-8 * E * 0.01,
        "no lateral force, no moment about the faces' centroids: %.1e" % np.abs(np.r_[bot[:2], top[:2], bot[3:], top[3:]]).max())
el = h["bodies/cube/energy"][-1][1]
c.check(abs(el - 0.5 * E * 1e-4) < 1e-6 * 0.5 * E * 1e-4, "elastic energy 1/2 E eps^2 V = 5: %.9g" % el)
ref, pos = h["bodies/cube/mesh/reference"][:], h["bodies/cube/positions"][-1]
ontop = np.abs(ref[:, 2] - 0.5) < 1e-9
c.check(np.abs(pos[ontop, 2] - ref[ontop, 2] + 0.01).max() < 1e-12, "the top region is where its table puts it")

# the same strain from a force on the top
h = cube("force", ["-cube_fixed", "zmin", "-cube_force", "zmax=0:0,0,0;1:0,0,%g" % (-E * 0.01)])
ref, pos = h["bodies/cube/mesh/reference"][:], h["bodies/cube/positions"][-1]
uz = pos[:, 2] - ref[:, 2]
c.check(np.abs(uz - (-0.01) * (ref[:, 2] + 0.5)).max() < 1e-6 * 0.01,
        "a total force E A eps on zmax: u_z = -eps (z + 1/2) everywhere (%.1e)" % np.abs(uz + 0.01 * (ref[:, 2] + 0.5)).max())
c.check(abs(h["bodies/cube/reactions/zmin"][-1][2] - E * 0.01) < 1e-6 * E * 0.01, "its reaction on zmin is the force")

# a load on a region that shares vertices with the fixed one (xmax's bottom edge is on zmin; the volume
# group "body" holds zmin): the share on the fixed vertices goes to the support, so that statically the
# reaction is the whole load, and with gravity the load and the weight
for reg, g in [("xmax", 0.0), ("body", 0.0), ("xmax", -9.81)]:
    h = cube("share_" + reg, ["-cube_poisson", 0.3, "-cube_fixed", "zmin", "-cube_force", reg + "=0:100,0,0",
                              "-time_integration", "static", "-gravity", "0,0,%g" % g])
    R, W = h["bodies/cube/reactions/zmin"][-1], 100 * 1.0 * g
    c.check(np.abs(R[:3] - [-100.0, 0.0, -W]).max() < 1e-9 * 100,
            "100 N on %s of a cube fixed on zmin (gravity %g): the reaction is %s, the load and the weight"
            % (reg, g, R[:3]))


# quasi-static: every step is the equilibrium of its time
h = cube("static", ["-cube_fixed", "zmin", "-cube_displacement", "zmax=0:0,0,0;0.5:0,0,-0.01", "-time_integration",
                    "static", "-time_step", 0.1, "-time_steps", 7, "-output_every", 1])
t, Rz = h["steps/time"][:], h["bodies/cube/reactions/zmax"][:, 2]
want = -E * 0.01 * np.minimum(t / 0.5, 1.0)
c.check(np.abs(Rz - want).max() < 1e-6 * E * 0.01 and np.abs(h["bodies/cube/energy"][:, 0]).max() == 0.0,
        "static: the reaction follows the prescribed ramp at every step (%.1e N), no kinetic energy" % np.abs(Rz - want).max())
f = out("pressed.h5")
run(["-options_file", "input/pressed.opts", "-ball_dm_plex_filename", "meshes/hertz_sphere_1.msh",
     "-block_dm_plex_filename", "meshes/hertz_block_1.msh", "-time_steps", 4, "-output_file", f, "-quiet",
     "-output_fields", "displacement,contact_pressure"], NP)
h = h5py.File(f, "r")
cap = [k for k in h["bodies/ball/reactions"] if k.startswith("box:-1,-1,0.95")][0]
Rc, off = h["bodies/ball/reactions/" + cap][:, 2], h["contacts/offset"][:]
Fn = np.array([h["contacts/force"][off[k]:off[k + 1], 0].sum() for k in range(len(off) - 1)])
c.check(Fn.min() > 500 and np.abs(Rc + Fn).max() < 1e-6 * Fn.max(),
        "static contact (input/pressed.opts): the cap's reaction is the contact force at every step (%.1e relative; "
        "%.0f N at step 4)" % (np.abs(Rc + Fn).max() / Fn.max(), Fn[-1]))
# contact_pressure: over the vertex areas (a third of the boundary faces' at each vertex) it sums to
# the normal contact force, and it is nonzero only on the contact patch (Hertz's radius a, give or
# take the elements)
cells, X = h["bodies/ball/mesh/cells"][:], h["bodies/ball/mesh/reference"][:]
faces = np.sort(np.concatenate([cells[:, [0, 1, 2]], cells[:, [0, 1, 3]], cells[:, [0, 2, 3]], cells[:, [1, 2, 3]]]), axis=1)
uf, cnt = np.unique(faces, axis=0, return_counts=True)
bf = uf[cnt == 1]
area = 0.5 * np.linalg.norm(np.cross(X[bf[:, 1]] - X[bf[:, 0]], X[bf[:, 2]] - X[bf[:, 0]]), axis=1)
Av = np.zeros(len(X))
for k in range(3):
    np.add.at(Av, bf[:, k], area / 3)
pc = h["bodies/ball/contact_pressure"][-1]
Es = 1 / ((1 - 0.09) / 5e6 + (1 - 0.09) / 5e9)
a_h = (3 * Fn[-1] * 0.5 / (4 * Es))**(1 / 3)
p0 = 3 * Fn[-1] / (2 * np.pi * a_h**2)
rmax = np.hypot(X[pc > 0, 0], X[pc > 0, 1]).max()
c.check(abs(np.sum(pc * Av) - Fn[-1]) < 1e-8 * Fn[-1] and rmax < a_h + 2 * 0.04,
        "contact_pressure: sum p A = the normal contact force (%.1e relative), nonzero within r = %.3f m of the axis "
        "(Hertz's a = %.3f m, elements 0.04 m); peak %.0f Pa against Hertz's p0 %.0f Pa on this coarse mesh"
        % (abs(np.sum(pc * Av) - Fn[-1]) / Fn[-1], rmax, a_h, pc.max(), p0))
for args, msg in [(["-cube_fixed", "zmin", "-cube_rayleigh_mass", "1"], "has no damping"), ([], "no fixed or prescribed vertex")]:
    p = run(BASE0 + ["-time_integration", "static"] + args, NP, check=False)
    c.check(p.returncode != 0 and msg in p.stdout + p.stderr, "static %s: '%s'" % (" ".join(map(str, args)) or "(nothing held)", msg))
p = run(["-scene_bodies", "b", "-b_type", "rigid", "-b_shape", "sphere", "-b_radius", 1, "-b_density", 1,
         "-time_integration", "static", "-time_steps", 1, "-output_file", out("r.h5")], NP, check=False)
c.check(p.returncode != 0 and "no static equilibrium of its own" in p.stdout + p.stderr, "static: a rigid body is refused")

# a Physical Point group: a force on the finger's tip corner, statically, is taken by its base
f = out("corner.h5")
run(["-scene_bodies", "finger", "-finger_type", "fem", "-finger_dm_plex_filename", "meshes/finger.msh", "-finger_young", 5e4,
     "-finger_density", 1100, "-finger_fixed", "base", "-finger_force", "tip_corner=0:0,0,0;1:0.01,-0.02,0.005",
     "-time_integration", "static", "-gravity", "0,0,0", "-time_step", 1, "-time_steps", 1, "-output_file", f, "-quiet"], NP)
h = h5py.File(f, "r")
R = h["bodies/finger/reactions/base"][-1]
X, P = h["bodies/finger/mesh/reference"][:], h["bodies/finger/positions"][-1]
moved = np.abs(P - X).max(axis=1).argmax()
c.check(np.abs(R[:3] + [0.01, -0.02, 0.005]).max() < 1e-9 and np.abs(X[moved] - [0.01, 0.01, 0.1]).max() < 1e-12,
        "a force on the Physical Point 'tip_corner' is taken by the base (%.1e N) and moves that vertex most" %
        np.abs(R[:3] + [0.01, -0.02, 0.005]).max())

# Lame's thick sphere
def lame(mesh, np_=NP):
    f = out("lame_%s_np%d.h5" % (mesh, np_))
    run(["-scene_bodies", "shell", "-shell_type", "fem", "-shell_dm_plex_filename", "meshes/%s.msh" % mesh,
         "-shell_material", "linear", "-shell_young", 1e6, "-shell_poisson", 0.3, "-shell_density", 1000,
         "-shell_pressure", "inner=0:0;1:1e3", "-gravity", "0,0,0", "-time_step", H, "-time_steps", 1,
         "-output_file", f, "-quiet"], np_)
    g = h5py.File(f, "r")
    X, x = g["bodies/shell/mesh/reference"][:], g["bodies/shell/positions"][-1]
    r = np.linalg.norm(X, axis=1)
    ur = np.sum((x - X) * X, axis=1) / r
    a, b, p, Ey, nu = 0.5, 1.0, 1e3, 1e6, 0.3
    u = lambda s: p * a**3 / (Ey * (b**3 - a**3)) * ((1 - 2 * nu) * s + (1 + nu) * b**3 / (2 * s**2))
    return [ur[np.abs(r - s) < 1e-3].mean() / u(s) - 1 for s in (a, b)]


coarse = lame("hollow_sphere")
if NP == 1:  # the convergence on 1 rank (the fine mesh's factorization is most of this test's time)
    fine = lame("hollow_sphere_fine")
    print("Lame radial displacement error at r = a, b: lc 0.1 %+.4f %+.4f, lc 0.05 %+.4f %+.4f" % (*coarse, *fine))
    c.check(max(abs(e) for e in fine) < 0.02, "Lame: within 2%% on the finer mesh (%.4f, %.4f)" % tuple(fine))
    c.check(all(abs(f_) < abs(e) for f_, e in zip(fine, coarse)), "Lame: closer on the finer mesh")
else:  # the pressure on NP ranks: the 1-rank errors
    one = lame("hollow_sphere", 1)
    d = max(abs(a - b) for a, b in zip(coarse, one))
    # 1e-7: the body is free, its rigid modes held only by M / h^2 (h = 1e3 s), whose round-off
    # the partition changes (measured 2.9e-9 on 2 ranks)
    c.check(d < 1e-7, "Lame: %d ranks give the 1-rank displacements at r = a, b (lc 0.1: %+.4f %+.4f; %.1e)" %
            (NP, *coarse, d))

# reaction = contact force (the block's momentum balance, every step)
f = out("rest.h5")
alpha, g0, hstep = 2.0, 9.81, 0.01
run(["-scene_bodies", "block,box", "-contact_pairs", "block:box", "-contact_mu", 0.3, "-time_step", hstep,
     "-time_steps", 30, "-output_every", 1, "-output_file", f, "-quiet",
     "-block_type", "fem", "-block_dm_plex_filename", "meshes/cube_coarse.msh", "-block_material", "linear",
     "-block_young", 1e5, "-block_poisson", 0.3, "-block_density", 100, "-block_rayleigh_mass", alpha,
     "-block_fixed", "zmin", "-box_type", "rigid", "-box_shape", "box", "-box_half_extents", "0.2,0.2,0.1",
     "-box_density", 500, "-box_center", "0,0,0.6"], NP)
h = h5py.File(f, "r")
m = 100.0
cz = np.r_[h["bodies/block"].attrs["initial_centroid"][2], h["bodies/block/centroid"][:, 2]]
Rz = h["bodies/block/reactions/zmin"][:, 2]
off, bod, Fw = h["contacts/offset"][:], h["contacts/bodies"][:], h["contacts/force_world"][:]
Fc = []
for s in range(len(Rz)):
    sl = slice(off[s], off[s + 1])
    sign = np.where(bod[sl, 0] == 0, 1.0, -1.0)  # force_world acts on side 1
    Fc.append(np.sum(sign * Fw[sl, 2]))
Fc = np.array(Fc)
acc = np.r_[np.nan, (cz[2:] - 2 * cz[1:-1] + cz[:-2]) / hstep**2]
vel = (cz[1:] - cz[:-1]) / hstep
res = np.abs(Rz + Fc - m * g0 - m * (acc + alpha * vel))[1:] / (m * g0)
c.check(Fc.min() < -0.5 * 0.4 * 0.4 * 0.2 * 500 * g0 and res.max() < 1e-8,
        "reaction + contact force + weight = momentum rate at every step: %.1e of m g (box weight %.1f N, last contact "
        "force %.1f N, reaction %.1f N)" % (res.max(), 0.4 * 0.4 * 0.2 * 500 * g0, -Fc[-1], Rz[-1]))

# a keyframed kinematic body
f = out("traj.h5")
run(["-scene_bodies", "tool", "-tool_type", "kinematic", "-tool_shape", "sphere", "-tool_radius", 0.05,
     "-tool_trajectory", "0:0,0,0.2,1,0,0,0;0.3:0,0,0.1,0.7071067811865476,0.7071067811865476,0,0;0.6:0.1,0,0.1,1,0,0,0",
     "-time_step", 0.01, "-time_steps", 80, "-output_every", 10, "-output_file", f, "-quiet"], NP)
h = h5py.File(f, "r")
t, cen, q = h["steps/time"][:], h["bodies/tool/centroid"][:], h["bodies/tool/rotation"][:]
want = np.array([np.interp(t, [0, 0.3, 0.6], k) for k in ([0, 0, 0.1], [0.2, 0.1, 0.1])])
c.check(np.abs(cen[:, 0] - want[0]).max() < 1e-12 and np.abs(cen[:, 2] - want[1]).max() < 1e-12,
        "the centre follows the table exactly (%.1e)" % max(np.abs(cen[:, 0] - want[0]).max(), np.abs(cen[:, 2] - want[1]).max()))
k = np.argmin(np.abs(t - 0.15))
c.check(abs(q[k][0] - np.cos(np.pi / 8)) < 1e-12 and abs(q[k][1] - np.sin(np.pi / 8)) < 1e-12,
        "halfway between keyframes the orientation is halfway by slerp (45 degrees about x)")
c.check(np.abs(cen[-1] - [0.1, 0, 0.1]).max() < 1e-12, "held at the last row after it")

# an attachment: "zmin" follows a kinematic body that turns (and, dynamically, translates)
def attach(name, extra):
    f = out(name + ".h5")
    run(["-scene_bodies", "cube,hand", "-time_step", 0.01, "-time_steps", 50, "-output_every", 10, "-output_file", f,
         "-quiet", "-cube_type", "fem", "-cube_dm_plex_filename", "meshes/cube_coarse.msh", "-cube_material",
         "corotational", "-cube_young", 1e6, "-cube_density", 100, "-cube_attach", "zmin:hand", "-hand_type",
         "kinematic", "-hand_shape", "sphere", "-hand_radius", 0.05, "-hand_center", "0,0,-0.6"] + extra, NP)
    g = h5py.File(f, "r")
    X, P, t = g["bodies/cube/mesh/reference"][:], g["bodies/cube/positions"][:], g["frames/time"][:]
    return X, P, t


def rigid(X, t, w, v):
    th = w * t
    R = np.array([[np.cos(th), -np.sin(th), 0], [np.sin(th), np.cos(th), 0], [0, 0, 1]])
    return np.array([v * t, 0, -0.6]) + (X - [0, 0, -0.6]) @ R.T


X, P, t = attach("attach_static", ["-time_integration", "static", "-gravity", "0,0,0", "-hand_angular_velocity", "0,0,0.2"])
dev = max(np.abs(P[k] - rigid(X, t[k], 0.2, 0)).max() for k in range(len(t)))
c.check(dev < 1e-5, "static, the hand turning 0.1 rad: the co-rotational cube turns with its base as a rigid body (%.1e m)" % dev)
X, P, t = attach("attach_dyn", ["-hand_angular_velocity", "0,0,2", "-hand_velocity", "0.2,0,0", "-cube_rayleigh_mass", 5])
base = np.abs(X[:, 2] + 0.5) < 1e-9
dev = max(np.abs(P[k][base] - rigid(X[base], t[k], 2, 0.2)).max() for k in range(len(t)))
c.check(dev < 1e-12, "dynamic, turning at 2 rad/s and moving: the attached region is at the hand's pose (%.1e m)" % dev)
for extra, msg in [(["-cube_attach", "zmin:nobody"], "no other body"), (["-hand_type", "rigid", "-hand_density", 1], "kinematic body only")]:
    p = run(["-scene_bodies", "cube,hand", "-time_steps", 1, "-output_file", out("ab.h5"), "-cube_type", "fem",
             "-cube_dm_plex_filename", "meshes/cube_coarse.msh", "-cube_young", 1e5, "-cube_density", 100,
             "-cube_attach", "zmin:hand", "-hand_type", "kinematic", "-hand_shape", "sphere", "-hand_radius", 0.05,
             "-hand_center", "0,0,-0.6"] + [str(e) for e in extra], NP, check=False)
    c.check(p.returncode != 0 and msg in p.stdout + p.stderr, "-cube_attach %s: '%s'" % (" ".join(map(str, extra)), msg))

# restart: a prescribed motion continues exactly; a changed scene is refused, a changed table is not
RS = ["-scene_bodies", "cube", "-cube_type", "fem", "-cube_dm_plex_filename", "meshes/cube_coarse.msh", "-cube_material",
      "corotational", "-cube_young", 1e5, "-cube_density", 100, "-cube_fixed", "zmin", "-cube_displacement",
      "zmax=0:0,0,0;0.3:0.05,0,-0.05", "-time_step", 0.01, "-quiet"]
full, half, rest = out("rs_full.h5"), out("rs_half.h5"), out("rs_rest.h5")
run(RS + ["-time_steps", 20, "-output_every", 10, "-output_file", full], NP)
run(RS + ["-time_steps", 10, "-output_every", 10, "-output_file", half], NP)
run(RS + ["-time_steps", 20, "-output_every", 10, "-output_file", rest, "-restart", half], NP)
a, b = h5py.File(full, "r"), h5py.File(rest, "r")
d = np.abs(a["bodies/cube/positions"][-1] - b["bodies/cube/positions"][-1]).max() if NP == 1 else \
    np.abs(np.sort(a["bodies/cube/positions"][-1], axis=0) - np.sort(b["bodies/cube/positions"][-1], axis=0)).max()
r = np.abs(a["bodies/cube/reactions/zmax"][-1] - b["bodies/cube/reactions/zmax"][-1]).max()
c.check(d < 1e-12 and r < 1e-9 * np.abs(a["bodies/cube/reactions/zmax"][-1]).max(),
        "a restart at step 10 of a prescribed motion ends where the uninterrupted run does (%.1e m, reaction %.1e N)" % (d, r))
p = run(RS + ["-time_steps", 20, "-output_file", out("rs_bad.h5"), "-restart", half, "-cube_young", 2e5], NP, check=False)
c.check(p.returncode != 0 and "option -cube_young is" in p.stdout + p.stderr and "the run that wrote it" in p.stdout + p.stderr,
        "a restart with another -cube_young is refused, naming it")
p = run(RS[:-3] + ["-cube_displacement", "zmax=0:0,0,0;0.3:0.05,0,-0.05;1:0,0,0", "-time_step", 0.01, "-quiet", "-time_steps", 20,
                   "-output_file", out("rs_table.h5"), "-restart", half], NP, check=False)
c.check(p.returncode == 0, "a restart whose table continues with new rows runs (the rule)")
# a table moved to another region, a region that names other vertices, a body dropped from the
# scene, and an option of a body whose name extends another's: each another scene, refused
def refused(extra, scene, what, opts=None):
    p = run((opts or RS) + ["-time_steps", 20, "-output_file", out("rs_bad.h5"), "-restart", half] + extra, NP, check=False)
    text = p.stdout + p.stderr
    c.check(p.returncode == 1 and what in text, "a restart with %s is refused, naming %s" % (scene, what))
refused(["-cube_displacement", "box:-0.3,-0.3,0.45,0.3,0.3,1=0:0,0,0;0.3:0.05,0,-0.05"], "the prescribed motion moved",
        "has the regions [fixed:zmin displacement:box:-0.3,-0.3,0.45,0.3,0.3,1] here but [fixed:zmin displacement:zmax]")
refused(["-cube_force", "xmax=0:0,0,0;1:1,0,0"], "a load added", "[fixed:zmin displacement:zmax force:xmax] here")
PAD = ["-cube_force_type", "rigid", "-cube_force_shape", "sphere", "-cube_force_radius", 0.1, "-cube_force_density", 100,
       "-cube_force_center", "0,3,0"]
RS2 = RS + PAD + ["-scene_bodies", "cube,ball,cube_force", "-ball_type", "kinematic", "-ball_shape", "sphere",
                  "-ball_radius", 0.1, "-ball_center", "0,0,3"]
half2 = out("rs_half2.h5")
run(RS2 + ["-time_steps", 10, "-output_every", 10, "-output_file", half2], NP)
p = run(RS2 + ["-time_steps", 20, "-output_file", out("rs_ok2.h5"), "-restart", half2], NP, check=False)
c.check(p.returncode == 0, "a restart of the three-body scene as written runs")
p = run(RS + PAD + ["-scene_bodies", "cube,cube_force", "-time_steps", 20, "-output_file", out("rs_bad.h5"), "-restart", half2],
        NP, check=False)
c.check(p.returncode == 1 and "option -scene_bodies is 'cube,cube_force' here but 'cube,ball,cube_force'" in p.stdout + p.stderr,
        "a restart with a body dropped from -scene_bodies is refused, naming it")
p = run(RS2 + ["-cube_force_density", 200, "-time_steps", 20, "-output_file", out("rs_bad.h5"), "-restart", half2], NP,
        check=False)
c.check(p.returncode == 1 and "option -cube_force_density is '200' here but '100'" in p.stdout + p.stderr,
        "a restart with another -cube_force_density (body cube_force beside body cube) is refused, naming it")

# constrained vertices against a kinematic plane: no contact there
f = out("fixplane.h5")
run(["-scene_bodies", "cube,ground", "-contact_pairs", "cube:ground", "-time_step", 0.01, "-time_steps", 3,
     "-output_file", f, "-quiet", "-cube_type", "fem", "-cube_dm_plex_filename", "meshes/cube_coarse.msh",
     "-cube_material", "linear", "-cube_young", 1e5, "-cube_density", 100, "-cube_fixed", "zmin",
     "-cube_translate", "0,0,0.499", "-ground_type", "kinematic", "-ground_shape", "plane", "-ground_length", 3], NP)
h = h5py.File(f, "r")
c.check(int(h["steps/contacts"][:].max()) == 0, "a fixed region on a kinematic plane makes no contact (the rule)")

# bad input
BASE = ["-scene_bodies", "cube", "-cube_type", "fem", "-cube_dm_plex_filename", "meshes/cube_coarse.msh",
        "-cube_young", 1e5, "-cube_density", 100, "-time_steps", 1, "-output_file", out("bad.h5")]
bad = [(["-cube_fixed", "bottom"], "no region 'bottom'", "zmin (5)"),
       (["-cube_displacement", "zmax=0:0,0,0;0:0,0,1"], "does not increase", "-cube_displacement"),
       (["-cube_displacement", "zmax=0:0,0,0;1:0,nan,1"], "not a finite number", "zmax"),
       (["-cube_fixed", "zmax", "-cube_displacement", "zmax=0:0,0,0;1:0,0,1"], "share vertices", "zmax"),
       (["-cube_displacement", "zmax=/nonexistent.csv"], "cannot read the table file", "/nonexistent.csv"),
       (["-cube_pressure", "body=0:0;1:1"], "no boundary face", "body")]
for args, msg, name in bad:
    p = run(BASE + args, NP, check=False)
    err = p.stdout + p.stderr
    c.check(p.returncode != 0 and msg in err and name in err and "Segmentation" not in err,
            "%s: exit %d, '%s' naming %s" % (" ".join(args), p.returncode, msg, name))
# a surface group whose number is also a volume group's (meshes/beam_n4.msh: volume 1, surface "xmin" 1;
# meshes/finger.msh: "finger" 1, "base" 1): the region is the surface's vertices only (PETSc 3.18's
# reader also marks the volume's nodes in the surface's label: src/mesh/region.c)
f = out("beam_xmin.h5")
run(["-scene_bodies", "bar", "-bar_type", "fem", "-bar_dm_plex_filename", "meshes/beam_n4.msh", "-bar_young", 1e5,
     "-bar_density", 1000, "-bar_fixed", "xmin", "-bar_displacement", "xmax=0:0,0,0;1:0.025,0,0", "-time_integration",
     "static", "-gravity", "0,0,0", "-time_step", 1, "-time_steps", 1, "-output_file", f, "-quiet"], NP)
h = h5py.File(f, "r")
r = h["bodies/bar/mesh/reference"][:]
u = h["bodies/bar/positions"][-1] - r
still = np.all(u == 0, axis=1)
mid = np.abs(r[:, 0] - 2.5) < 1e-9
c.check(still.sum() == 25 and np.all(r[still, 0] == 0) and abs(u[mid, 0].mean() - 0.0125) < 1e-4,
        "beam_n4 (volume and surface 'xmin' both numbered 1): -bar_fixed xmin fixes the %d vertices of x = 0 only; "
        "the middle moves by %.5f m (uniform stretch: 0.0125)" % (still.sum(), u[mid, 0].mean()))
c.done()
