"""Self-contact of an FE body (-contact_pairs a:a, src/collision/selfcontact.c), on --np ranks:

- a body at rest or turning freely has no self-contacts: the coarse cube, the finger, the hollow
  sphere (a 0.5 m wall), the thin slab (0.02 m thick), the bar and the sheet (one element, 0.025 m,
  thick; also at rest), spinning at 3 rad/s without
  gravity, with an alarm distance of 0.05 m and of 0.3 m (larger than the slab's thickness: the
  rule that leaves out the triangles across the body's own thickness), and no self-intersection
  counted (the sheet at rest is where a ray from just inside a face vertex crossed that face again
  where its triangles meet: the count casts it from just outside, away from the face);
- one body of two components is two bodies: the coarse cube and a copy of it 1.2 m above, in one
  mesh (written here from meshes/cube_coarse.msh) paired with itself, fall on a plane and the upper
  lands on the lower; the same two cubes as two bodies paired a:b (both passes, no dormant second
  pass: a self pair has one pass, each vertex against the whole surface) give the same contacts at
  every step, the same sum of normal forces (1e-6 relative: the contact solver's tolerance) and the
  same positions (1e-5 of the displacement);
- every compliance builder gives dense's contact forces to 1e-10 (relative) on that self-contact
  scene, with plain PGS (whose iterates are a smooth function of W, tests/test_compliance.py);
- edge-edge: the crossed bars of input/hard/crossed_bars.opts in one mesh paired with itself: the one
  edge-edge contact at every step that holds the top bar as two bodies do, the same force and positions
  at the first step it pushes (1e-10), no self-intersection; without edge-edge contacts the edges pass
  through each other, and the count sees it as for two bodies;
- the start-inside rule: the same two cubes 0.6 m apart, with discrete detection and a long step,
  so that the upper falls 6 cm into the lower within a step: the vertices inside get contacts
  (deeper than the alarm distance) that push them out by about -contact_separation_speed x h a
  step (the contacts' slack), and none is left inside, as for two bodies;
- self-intersections: two cubes overlapping by 0.1 m in one mesh: the count is the number of surface
  vertices of each inside the other deeper than the depth, counted from the geometry;
- mutual self-contacts (each vertex a corner of the other's triangle) leave one active, the other
  dormant (the default): the stack holds as with every contact active (1e-3 of the displacement);
- --np > 1: with the dormant rule, the 1-rank positions to 1e-10 m over the whole run; with every
  contact active, to the first self-contact step, the contact forces and positions to 1e-10 (later,
  the stack's nearly redundant mutual contacts leave the positions to the solver's tolerance over
  W's conditioning: 1e-7 to 8e-7 m between 1 and 2 ranks, two bodies too);
- bad input: a rigid and a kinematic body paired with itself, -contact_self_ring 0: errors naming
  them."""
import subprocess

import h5py
import numpy as np

from fctest import run, out, Checker, np_from_argv, ROOT

NP = np_from_argv()
c = Checker("selfcontact np%d" % NP)

# at rest and in free rotation
for mesh, w in [(m, "0,0,3") for m in ["cube_coarse", "finger", "hollow_sphere", "thin_slab", "bar", "sheet"]] + \
        [("sheet", "0,0,0")]:
    for d in [0.05, 0.3]:
        f = out("rest_%s_%s_%g.h5" % (mesh, w, d))
        run(["-scene_bodies", "b", "-b_type", "fem", "-b_dm_plex_filename", "meshes/%s.msh" % mesh, "-b_material",
             "corotational", "-b_young", 1e5, "-b_density", 1000, "-b_angular_velocity", w, "-gravity", "0,0,0",
             "-contact_pairs", "b:b", "-contact_distance", d, "-time_steps", 5, "-output_file", f, "-quiet"], NP)
        h = h5py.File(f, "r")
        c.check(h["steps/contacts"][:].max() == 0 and h["steps/intersections"][:].max() == 0,
                "%s %s, alarm distance %g m: %d self-contacts, %d self-intersections counted" %
                (mesh, "at rest" if w == "0,0,0" else "spinning", d, h["steps/contacts"][:].max(),
                 h["steps/intersections"][:].max()))


def two_cubes(path, dz=1.2):
    """meshes/cube_coarse.msh and a copy of it dz above, one mesh of two components (gmsh's 2.2 format)"""
    m22 = out("cube_coarse22.msh")
    subprocess.run(["gmsh", "meshes/cube_coarse.msh", "-save", "-format", "msh22", "-o", m22], cwd=ROOT, check=True,
                   capture_output=True)
    L = open(m22).read().split("\n")
    i, j = L.index("$Nodes"), L.index("$Elements")
    nodes = L[i + 2:L.index("$EndNodes")]
    elems = L[j + 2:L.index("$EndElements")]
    nn, ne = len(nodes), len(elems)
    moved = []
    for ln in nodes:
        k, x, y, z = ln.split()
        moved.append("%d %s %s %.17g" % (int(k) + nn, x, y, float(z) + dz))
    copies = []
    for ln in elems:
        t = ln.split()
        ntag = int(t[2])
        head = [str(int(t[0]) + ne)] + t[1:3 + ntag]
        copies.append(" ".join(head + [str(int(v) + nn) for v in t[3 + ntag:]]))
    with open(path, "w") as g:
        g.write("\n".join(L[:i + 1] + [str(2 * nn)] + nodes + moved + ["$EndNodes", "$Elements", str(2 * ne)] + elems +
                          copies + ["$EndElements", ""]))


TWO = out("two_cubes.msh")
two_cubes(TWO)
COMMON = ["-time_step", 0.01, "-time_steps", 26, "-output_every", 26, "-contact_mu", 0, "-contact_distance", 0.015,
          "-contact_edge_edge", 0, "-pgs_tol", 1e-13, "-pgs_max_it", 5000, "-pgs_fail_residual", 1, "-quiet",
          "-ground_type", "kinematic", "-ground_shape", "plane", "-ground_length", 3]
FE = ["_type", "fem", "_material", "corotational", "_young", 2e5, "_density", 1000]


def fe(name, mesh, z):
    o = ["-%s_dm_plex_filename" % name, mesh, "-%s_translate" % name, "0,0,%g" % z]
    for k in range(0, len(FE), 2):
        o += ["-" + name + FE[k], FE[k + 1]]
    return o


def self_scene(np_, extra=()):
    f = out("self_%d_%s.h5" % (np_, "_".join(str(e) for e in extra)))
    run(COMMON + ["-scene_bodies", "stack,ground", "-contact_pairs", "stack:ground,stack:stack"] +
        fe("stack", TWO, 0.5001) + ["-output_file", f] + list(extra), np_)
    return h5py.File(f, "r")


A = self_scene(NP, ["-contact_fe_pass2_dormant", -1])  # every contact active, as the two bodies' below
fb = out("two_bodies.h5")
run(COMMON + ["-scene_bodies", "lo,hi,ground", "-contact_pairs", "lo:ground,hi:ground,lo:hi", "-contact_fe_pass2_dormant",
              -1] + fe("lo", "meshes/cube_coarse.msh", 0.5001) + fe("hi", "meshes/cube_coarse.msh", 1.7001) +
    ["-output_file", fb], NP)
B = h5py.File(fb, "r")
ra = A["bodies/stack/mesh/reference"][:]
rb = np.vstack([B["bodies/lo/mesh/reference"][:], B["bodies/hi/mesh/reference"][:]])


def order(r):
    return np.lexsort(np.round(r, 9).T[::-1])


ia, ib = order(ra), order(rb)
pa = A["bodies/stack/positions"][-1][ia]
pb = np.vstack([B["bodies/lo/positions"][-1], B["bodies/hi/positions"][-1]])[ib]
disp = np.abs(pa - ra[ia]).max()
na, nb = A["steps/contacts"][:], B["steps/contacts"][:]
fa, fbb = A["contacts/force"][:], B["contacts/force"][:]
sa, sb = fa[-na[-1]:, 0].sum(), fbb[-nb[-1]:, 0].sum()
self_rows = A["contacts/bodies"][-na[-1]:]
c.check(np.array_equal(na, nb) and (self_rows[:, 0] == self_rows[:, 1]).sum() > 0,
        "two components = two bodies: the same contacts at every step (%d at the end, %d of them self-contacts)" %
        (na[-1], (self_rows[:, 0] == self_rows[:, 1]).sum()))
c.check(abs(sa - sb) <= 1e-6 * abs(sb) and np.abs(pa - pb).max() <= 1e-5 * disp,
        "two components = two bodies: sum of normal forces %.10g against %.10g, positions to %.1e m of a %.2f m "
        "displacement" % (sa, sb, np.abs(pa - pb).max(), disp))

# the dormant rule (the default): of two mutual self-contacts (each vertex a corner of the other's
# triangle) the one whose vertex comes later is dormant; the stack then holds as it does with every
# contact active, and its positions no longer depend on the solver's path (2 ranks below)
Dm = self_scene(NP)
pd = Dm["bodies/stack/positions"][-1][order(Dm["bodies/stack/mesh/reference"][:])]
c.check(Dm["steps/intersections"][:].max() == 0 and np.abs(pd - pa).max() <= 1e-3 * disp,
        "dormant mutual self-contacts: no self-intersection, positions %.1e m from every contact active's" %
        np.abs(pd - pa).max())

# self-intersections: the two cubes overlapping by 0.1 m in the mesh itself (no contact holds them: the
# overlap is the reference configuration's, where every vertex of it is behind the other part); the
# count is every surface vertex of each cube inside the other deeper than -contact_intersection_depth
# (1e-4), counted here from the geometry of the two unit cubes
OV = out("two_cubes_overlap.msh")
two_cubes(OV, dz=0.9)
f = out("overlap.h5")
run(["-scene_bodies", "s", "-contact_pairs", "s:s", "-gravity", "0,0,0", "-time_steps", 1, "-output_file", f, "-quiet"] +
    fe("s", OV, 0), NP)
h = h5py.File(f, "r")
P = h["bodies/s/positions"][-1]
cells = h["bodies/s/mesh/cells"][:]
faces = np.sort(np.concatenate([cells[:, [0, 1, 2]], cells[:, [0, 1, 3]], cells[:, [0, 2, 3]], cells[:, [1, 2, 3]]]), axis=1)
u, n = np.unique(faces, axis=0, return_counts=True)
surf = np.unique(u[n == 1])
expect = 0
for lo_z, other in [(-0.5, 0.9), (0.4, 0.0)]:  # each cube's vertices against the other cube's box
    mine = surf[(P[surf, 2] > lo_z - 1e-9) & (P[surf, 2] < lo_z + 1.0 + 1e-9)]
    q = P[mine] - [0, 0, other]
    depth_in = np.min(np.hstack([0.5 - np.abs(q)]), axis=1)
    expect += int((depth_in > 1e-4).sum())
c.check(h["steps/intersections"][0] == expect and expect > 0,
        "self-intersections of two overlapping cubes in one body: %d counted, %d surface vertices inside the other "
        "cube deeper than 1e-4 m" % (h["steps/intersections"][0], expect))

# every builder gives dense's forces: a linear body (precomputed is exact for it), to the first steps
# with self-contacts, step 21 (later, the frictionless stack's mutual vertex-triangle constraints leave the
# forces' split between them to the solver's path)
PLAIN = ["-pgs_acceleration", "none", "-pgs_tol", 1e-10, "-pgs_max_it", 20000, "-stack_material", "linear",
         "-time_steps", 21, "-output_every", 21]
D = self_scene(NP, PLAIN + ["-compliance_type", "dense"])
builders = (["sparse"] if NP == 1 else []) + ["schur", "inverse", "redundant", "condensed", "precomputed"]
for b in builders:
    H = self_scene(NP, PLAIN + ["-compliance_type", b])
    fd, fh = D["contacts/force"][:], H["contacts/force"][:]
    ok = fd.shape == fh.shape
    err = np.abs(fd - fh).max() / np.abs(fd).max() if ok else np.inf
    nself = (H["contacts/bodies"][:, 0] == H["contacts/bodies"][:, 1]).sum()
    c.check(ok and err <= 1e-10 and nself > 0, "builder %s: dense's contact forces to %.1e (relative; %d self-contacts "
            "at step 21)" % (b, err, nself))

if NP > 1:  # with the dormant rule, over the whole run
    Dm1 = self_scene(1)
    d1 = np.abs(Dm1["bodies/stack/positions"][-1][order(Dm1["bodies/stack/mesh/reference"][:])] - pd).max()
    c.check(d1 <= 1e-10, "%d ranks, dormant mutual self-contacts: the 1-rank positions to %.1e m after %d steps "
            "(every contact active: 1e-7 to 8e-7 m, the stack's mutual contacts nearly redundant)" %
            (NP, d1, len(Dm1["steps/contacts"])))
    # at the first self-contact step (later, the stack's nearly redundant mutual contacts leave the
    # positions to the solver's tolerance over W's conditioning: 1e-7 to 8e-7 m between 1 and 2 ranks, for the
    # same two cubes as two bodies too)
    D1 = self_scene(1, PLAIN + ["-compliance_type", "dense"])
    f1, fn = D1["contacts/force"][:], D["contacts/force"][:]
    ef = np.abs(f1 - fn).max() / np.abs(f1).max() if f1.shape == fn.shape else np.inf
    r1, x1, xn = D1["bodies/stack/mesh/reference"][:], D1["bodies/stack/positions"][-1], D["bodies/stack/positions"][-1]
    dx = np.abs(xn[order(D["bodies/stack/mesh/reference"][:])] - x1[order(r1)]).max()
    c.check(ef <= 1e-10 and dx <= 1e-10, "%d ranks: the 1-rank contact forces to %.1e (relative) and positions to "
            "%.1e m, to the first self-contact step" % (NP, ef, dx))

# the start-inside rule: the two cubes 0.6 m apart in one mesh, with discrete detection and a step of 0.05 s, so that
# the upper one falls 6 cm deep into the lower one within a step; then the contacts of the vertices inside (deeper
# than the alarm distance: the start-inside rule) push it back out by about -contact_separation_speed x h a step, as
# for the same two cubes as two bodies, the deepest gap a step to a quarter of v h (the two bodies' own deepest gaps
# on 1 and on 2 ranks differ by 1.3e-3 m: which vertices the solver leaves deepest depends on its path)
SI = out("two_cubes_apart.msh")
two_cubes(SI, dz=1.6)
V, H = 0.2, 0.05
SIO = ["-time_step", H, "-time_steps", 20, "-output_every", 1, "-contact_detection", "discrete", "-contact_fe_pass2_dormant",
       -1, "-contact_separation_speed", V]
f = out("start_inside_self.h5")
run(COMMON + SIO + ["-scene_bodies", "stack,ground", "-contact_pairs", "stack:ground,stack:stack"] + fe("stack", SI, 0.5001) +
    ["-output_file", f], NP)
S1 = h5py.File(f, "r")
f = out("start_inside_two.h5")
run(COMMON + SIO + ["-scene_bodies", "lo,hi,ground", "-contact_pairs", "lo:ground,hi:ground,lo:hi"] +
    fe("lo", "meshes/cube_coarse.msh", 0.5001) + fe("hi", "meshes/cube_coarse.msh", 2.1001) + ["-output_file", f], NP)
S2 = h5py.File(f, "r")


def deepest(h, self_pair):
    """per step: the number of contacts between the two cubes and the deepest start gap among them"""
    n, b, g = h["steps/contacts"][:], h["contacts/bodies"][:], h["contacts/gap"][:]
    off, res = np.concatenate([[0], np.cumsum(n)]), []
    for s in range(len(n)):
        bb, gg = b[off[s]:off[s + 1]], g[off[s]:off[s + 1]]
        m = (bb[:, 0] == bb[:, 1]) if self_pair else ((bb[:, 0] != bb[:, 1]) & (bb.max(axis=1) < 2))
        res.append((int(m.sum()), gg[m].min() if m.any() else 0.0))
    return res


d1, d2 = deepest(S1, True), deepest(S2, False)
i1, i2 = S1["steps/intersections"][:], S2["steps/intersections"][:]
k = next(s for s in range(len(d1)) if d1[s][0])  # the first step with contacts between the cubes
gaps, gaps2 = np.array([g for _, g in d1[k:k + 6]]), np.array([g for _, g in d2[k:k + 6]])
c.check(d1[k][1] < -3 * 0.015 and d1[k][0] == d2[k][0] and abs(d1[k][1] - d2[k][1]) <= 1e-6 and i1[k - 1] > 0,
        "start inside, self pair: at step %d, %d vertices inside the other cube (counted), %d contacts, the deepest "
        "%.4f m (two bodies: %d contacts, %.4f m)" % (k + 1, i1[k - 1], d1[k][0], d1[k][1], d2[k][0], d2[k][1]))
c.check(np.all(np.diff(gaps) <= 1.1 * V * H) and np.all(np.diff(gaps) > 0.5 * V * H) and
        np.abs(gaps - gaps2).max() <= 0.25 * V * H,
        "start inside, self pair: pushed out by about v h = %.3f m a step (the constraint's own slack; the cubes' "
        "elastic rebound adds a little), the deepest gap %s (two bodies: %s)" %
        (V * H, " ".join("%.4f" % g for g in gaps), " ".join("%.4f" % g for g in gaps2)))
z1, z2 = int(np.argmax(i1[k:] == 0)) + k, int(np.argmax(i2[k:] == 0)) + k
c.check(i1[k:].min() == 0 and abs(z1 - z2) <= 1, "start inside, self pair: no vertex inside from step %d (two bodies: "
        "%d)" % (z1 + 1, z2 + 1))

# edge-edge: the crossed bars of input/hard/crossed_bars.opts (the top bar rests on the bottom one edge on
# edge, where neither has a vertex) as one body of two components paired with itself


def rotation(axis, deg):
    a = np.array(axis, float) / np.linalg.norm(axis)
    K, th = np.array([[0, -a[2], a[1]], [a[2], 0, -a[0]], [-a[1], a[0], 0]]), np.radians(deg)
    return np.eye(3) + np.sin(th) * K + (1 - np.cos(th)) * K @ K


def crossed_bars(path):
    """meshes/bar.msh twice, placed as the two bodies of crossed_bars.opts, one mesh (gmsh 2.2)"""
    m22 = out("bar22.msh")
    subprocess.run(["gmsh", "meshes/bar.msh", "-save", "-format", "msh22", "-o", m22], cwd=ROOT, check=True,
                   capture_output=True)
    L = open(m22).read().split("\n")
    i, j = L.index("$Nodes"), L.index("$Elements")
    nodes, elems = L[i + 2:L.index("$EndNodes")], L[j + 2:L.index("$EndElements")]
    nn, ne, c = len(nodes), len(elems), np.array([0, 0, 0.05])  # -<bar>_center
    poses = [(rotation([1, 0, 0], 45), [0, 0, 0]),  # -bottom_rotate; -top_rotate, -top_translate
             (rotation([0.38268343, 0.38268343, 0.92387953], 98.42105), [0, 0, 0.1514])]
    on, oe = [], []
    for b, (R, t) in enumerate(poses):
        for ln in nodes:
            k, x, y, z = ln.split()
            on.append("%d %.17g %.17g %.17g" % (int(k) + b * nn, *(c + R @ (np.array([x, y, z], float) - c) + t)))
        for ln in elems:
            e = ln.split()
            ntag = int(e[2])
            oe.append(" ".join([str(int(e[0]) + b * ne)] + e[1:3 + ntag] + [str(int(v) + b * nn) for v in e[3 + ntag:]]))
    with open(path, "w") as g:
        g.write("\n".join(L[:i + 1] + [str(2 * nn)] + on + ["$EndNodes", "$Elements", str(2 * ne)] + oe +
                          ["$EndElements", ""]))


BARS = out("crossed_bars_one.msh")
crossed_bars(BARS)


def bars(one, extra=()):
    f = out("bars_%s_%s.h5" % ("one" if one else "two", "_".join(str(e) for e in extra)))
    if one:
        o = ["-scene_bodies", "bars", "-bars_dm_plex_filename", BARS, "-bars_fixed_box", "-1,-1,-0.03,1,1,-0.02",
             "-contact_pairs", "bars:bars", "-contact_mu", 0.3, "-time_step", 0.01, "-time_steps", 40]
        for k, v in [("type", "fem"), ("material", "corotational"), ("young", 1e6), ("poisson", 0.3), ("density", 1000)]:
            o += ["-bars_" + k, v]
    else:
        o = ["-options_file", "input/hard/crossed_bars.opts"]
    run(o + ["-output_every", 1, "-output_file", f, "-quiet"] + list(extra), NP)
    h = h5py.File(f, "r")
    return h, (h["bodies/bars/mesh/reference"][:] if one else
               np.vstack([h["bodies/bottom/mesh/reference"][:], h["bodies/top/mesh/reference"][:]]))


def bar_positions(h, one, k):
    return h["bodies/bars/positions"][k] if one else np.vstack([h["bodies/bottom/positions"][k],
                                                               h["bodies/top/positions"][k]])


(O, ro), (T, rt) = bars(True), bars(False)
io, it = np.lexsort(np.round(ro, 9).T), np.lexsort(np.round(rt, 9).T)
no, nt = O["steps/contacts"][:], T["steps/contacts"][:]
oo, ot = O["contacts/offset"][:], T["contacts/offset"][:]
fsum = np.add.reduceat(np.abs(O["contacts/force"][:, 0]), oo[:-1]) * (np.diff(oo) > 0) if oo[-1] else np.zeros(1)
k1 = int(np.argmax(fsum > 0))  # the first step whose contact pushes (the first are speculative, at rest)
fo, ft = O["contacts/force"][oo[k1]:oo[k1 + 1], 0], T["contacts/force"][ot[k1]:ot[k1 + 1], 0]
dx = np.abs(bar_positions(O, True, k1 + 1)[io] - bar_positions(T, False, k1 + 1)[it]).max()
ef = np.abs(fo - ft).max() / np.abs(ft).max() if fo.shape == ft.shape and len(ft) else np.inf
c.check(np.array_equal(no, nt) and (no[k1:] == 1).all() and fsum[k1] > 0 and ef <= 1e-10 and dx <= 1e-10,
        "crossed bars in one body: one edge-edge self-contact at every step, as two bodies; at the first that pushes "
        "(step %d) the same normal force to %.1e (relative) and positions to %.1e m" % (k1 + 1, ef, dx))
ni = O["steps/intersections"][:]
c.check(ni.max() == 0, "crossed bars in one body: no self-intersection over %d steps (the top bar rests on the "
        "bottom one, %.1f N)" % (len(ni), O["contacts/force"][oo[-2]:oo[-1], 0].sum()))
(O0, _), (T0, _) = bars(True, ["-contact_edge_edge", 0]), bars(False, ["-contact_edge_edge", 0])
n0, t0 = O0["steps/intersections"][:].max(), T0["steps/intersections"][:].max()
c.check(n0 > 0 and n0 == t0, "crossed bars, -contact_edge_edge 0: the edges pass through each other, %d "
        "self-intersections counted (%d as two bodies)" % (n0, t0))

# bad input
CUBE = ["-b_type", "fem", "-b_dm_plex_filename", "meshes/cube_coarse.msh", "-b_young", 1e5, "-b_density", 1000]
for args, what in [(["-scene_bodies", "ball", "-ball_type", "rigid", "-ball_shape", "sphere", "-ball_radius", 0.1,
                     "-ball_density", 1000, "-contact_pairs", "ball:ball"], "'ball' with itself"),
                   (["-scene_bodies", "b,g", "-g_type", "kinematic", "-g_shape", "plane", "-contact_pairs", "g:g"] + CUBE,
                    "'g' with itself"),
                   (["-scene_bodies", "b", "-contact_pairs", "b:b", "-contact_self_ring", 0] + CUBE,
                    "-contact_self_ring")]:
    p = run(args + ["-time_steps", 1, "-output_file", out("bad.h5")], NP, check=False)
    msg = p.stdout + p.stderr
    c.check(p.returncode != 0 and what in msg, "refused (exit %d): %s" %
            (p.returncode, [ln for ln in msg.splitlines() if what in ln][:1]))
c.done()
