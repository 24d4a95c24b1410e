"""Self-contact scenes, on --np ranks: input/u_bend.opts (a soft bar bent into a U by two hands
attached to its ends, whose arms close the U's neck below the hands), input/finger_fold.opts (a
soft finger clamped at its base whose two notched joints a pusher closes), input/sheet_fold.opts (a
thin sheet on a floor folded in half by a hand attached to one end) and the hard cases
input/hard/u_bend_fast.opts (the same fold at 2 m/s) and input/hard/u_bend_stick.opts (a tighter
fold with mu = 1).

U-bend:
- the neck closes and stays closed: self-contacts at every step from the first touch, between the
  two arms (contact points on the bar's plane of symmetry, below the hands);
- zero self-intersections at every step (/steps/intersections) and no contact deeper than
  -contact_intersection_depth at the end of its step;
- the contact forces balance the hands' reactions: a self-contact pushes both arms, equal and
  opposite, so in the held pose the two end faces' reactions cancel, force and moment, while the
  neck carries ~150 N (a contact applied to one side only would leave its force unbalanced);
- every contact solve converged (residual <= 10 pgs_tol);
- --np > 1: the 1-rank run's contacts at every step, their forces to 1e-10 (relative) and the
  positions to 1e-10 m (the neck's contacts are well-conditioned: measured 3e-13 and 5e-15 m).

Finger fold:
- each joint's notch closes and stays closed: self-contacts carrying force at every step from the
  first touch, every one on a notch's faces (its nearest vertex at the end lies on a notch in the
  reference configuration), both joints loaded at the end;
- zero self-intersections at every step, no contact deeper than -contact_intersection_depth at the
  end of its step, every contact solve converged;
- in the held pose, the base's reaction, the pusher's contact forces on the finger and its weight
  balance: the self-contacts, each pushing both faces of a notch equal and opposite, add no force,
  though they carry more than the pusher does; their moments balance to a few percent of the
  base's (the self-contacts leave a small couple; without them the moments balance to 1e-10 N m);
- --np > 1: the 1-rank run's contacts at every step, their forces to 1e-10 (relative) until the
  joints close; then the self-contacts' total, the pusher's force and the base's reaction to 1e-3
  (relative) and the positions to 5e-5 m: the closed notches' nearly redundant self-contacts make
  an ill-conditioned contact problem, whose forces solved to -pgs_tol amplify the ranks' round-off
  (measured 3.5e-4 and 1.1e-5 m).

Sheet fold:
- self-contacts at every step from the first touch, zero self-intersections, every solve converged
  (as the U-bend);
- the contacts are between the two layers, where the upper half lies on the lower one near the
  hand (the lower half's top face, normals vertical), carrying part of the upper half's weight;
- --np > 1: over the first 1.2 s (0.2 s past the first touch), the 1-rank contacts at every step,
  their forces to 1e-10 (relative) and the positions to 1e-10 m.

Hard cases (1 rank): no self-intersection, the neck held closed to the end, every solve
converged; the letter fold (input/hard/sheet_fold_twice.opts, three layers): the same, and at the
end loaded contacts between the bottom and middle layers and between the middle and top ones; with
mu = 1, sticking contacts that carry tangential force inside the Coulomb cone and
hold the neck without creeping."""
import h5py
import numpy as np

from fctest import run, out, Checker, np_from_argv, same_as_1_rank

NP = np_from_argv()
c = Checker("selfcontact scenes np%d" % NP)
PGS_TOL, DEPTH = 1e-8, 1e-4


def scene(opts, np_, name, extra=()):
    f = out("%s_np%d.h5" % (name, np_))
    run(["-options_file", opts, "-output_file", f, "-quiet"] + list(extra), np_)
    return h5py.File(f, "r")


def self_contacts(H):
    """The contacts of each step whose two sides are the same body (a self pair), as a mask of /contacts/* rows
    and a count per step"""
    b, off = H["contacts/bodies"][:], H["contacts/offset"][:]
    mask = b[:, 0] == b[:, 1]
    return mask, np.add.reduceat(np.append(mask, False).astype(int), off[:-1]) * (np.diff(off) > 0)


def held(H, what):
    """Self-contacts at every step from the first touch, and zero self-intersections at every step"""
    mask, n = self_contacts(H)
    ni = H["steps/intersections"][:]
    first = int(np.argmax(n > 0))
    gap = H["contacts/gap_end"][:][mask].min()
    c.check(n.max() > 0 and (n[first:] > 0).all(), "%s: the fold closes at t = %.3f s and stays closed (%d "
            "self-contacts at the end)" % (what, H["steps/time"][first], n[-1]))
    c.check(ni.max() == 0 and gap >= -DEPTH, "%s: no self-intersection at any step, the deepest contact at the end "
            "of its step %.1e m (depth %g)" % (what, gap, DEPTH))
    res = H["steps/residual"][:].max()
    c.check(res <= 10 * PGS_TOL, "%s: every contact solve converged (largest residual %.1e)" % (what, res))
    return first


def last_step(H, name):
    off = H["contacts/offset"][:]
    return H["contacts/" + name][off[-2]:off[-1]]


# the U-bend
U = scene("input/u_bend.opts", NP, "u_bend")
first = held(U, "U-bend")
pt = last_step(U, "point")
c.check((np.abs(pt[:, 0]) < 0.01).all() and (pt[:, 2] > 0.15).all() and (pt[:, 2] < 0.3).all(),
        "U-bend: the contacts are between the arms, below the hands (|x| <= %.4f m, z in [%.3f, %.3f] m)" %
        (np.abs(pt[:, 0]).max(), pt[:, 2].min(), pt[:, 2].max()))
fn = last_step(U, "force")[:, 0].sum()
X, P = U["bodies/bar/mesh/reference"][:], U["bodies/bar/positions"][-1]
RL, RR = U["bodies/bar/reactions/xmin"][-1], U["bodies/bar/reactions/xmax"][-1]
cL, cR = P[np.abs(X[:, 0] + 0.5) < 1e-9].mean(0), P[np.abs(X[:, 0] - 0.5) < 1e-9].mean(0)
F = RL[:3] + RR[:3]
M = RL[3:] + RR[3:] + np.cross(cL, RL[:3]) + np.cross(cR, RR[:3])
c.check(fn > 50 and np.linalg.norm(F) <= 1e-3 * fn,
        "U-bend, held: the end faces' reactions cancel, |F_xmin + F_xmax| = %.2e N against %.1f N of self-contact "
        "force (bound 1e-3 of it; the hands pull with %.0f N)" % (np.linalg.norm(F), fn, np.linalg.norm(RL[:3])))
ML = np.linalg.norm(RL[3:] + np.cross(cL, RL[:3]))
c.check(np.linalg.norm(M) <= 1e-2 * ML, "U-bend, held: their moments about the origin cancel, |M| = %.2e N m of "
        "%.1f N m (bound 1e-2 of it)" % (np.linalg.norm(M), ML))

if NP > 1:
    U1 = scene("input/u_bend.opts", 1, "u_bend")
    same, ef, dx = same_as_1_rank(U1, U, "bar")
    c.check(same and ef <= 1e-10 and dx <= 1e-10, "U-bend, %d ranks: the 1-rank contacts at every step (%s), forces "
            "to %.1e (relative), positions to %.1e m" % (NP, "same" if same else "DIFFERENT", ef, dx))

# the finger: clamped at its base, its joints closed by the pusher (body 1) on its last segment. Its notches
# (meshes/finger_fold.geo): across the inner side x = -0.01, at z = 0.05 and 0.08, 1 cm deep with a hole of
# radius 2.5 mm at the apex, 40 degrees open, so 3.6 mm either side of the joint on the inner face
Fi = scene("input/finger_fold.opts", NP, "finger_fold")
off, B, Fn = Fi["contacts/offset"][:], Fi["contacts/bodies"][:], Fi["contacts/force"][:, 0]
own = (B[:, 0] == 0) & (B[:, 1] == 0)
loaded = np.array([(own[off[k]:off[k + 1]] & (Fn[off[k]:off[k + 1]] > 0)).sum() for k in range(len(off) - 1)])
first = int(np.argmax(loaded > 0))
ni, gap, res = Fi["steps/intersections"][:], Fi["contacts/gap_end"][:].min(), Fi["steps/residual"][:].max()
c.check(loaded.max() > 0 and (loaded[first:] > 0).all(), "finger: the joints close at t = %.2f s and stay closed, "
        "loaded self-contacts at every step from then on (%d at the end)" % (Fi["steps/time"][first], loaded[-1]))
c.check(ni.max() == 0 and gap >= -DEPTH, "finger: no self-intersection at any step, the deepest contact at the end of "
        "its step %.1e m (depth %g)" % (gap, DEPTH))
c.check(res <= 10 * PGS_TOL, "finger: every contact solve converged (largest residual %.1e)" % res)
X, P = Fi["bodies/finger/mesh/reference"][:], Fi["bodies/finger/positions"][-1]
s_ = slice(off[-2], off[-1])
pt, f, fw, b = Fi["contacts/point_end"][s_], Fn[s_], Fi["contacts/force_world"][s_], B[s_]
me = own[s_]
Xc = X[[np.argmin(np.linalg.norm(P - q, axis=1)) for q in pt[me]]]
joint = np.full(len(Xc), -1)
for j, zc in enumerate((0.05, 0.08)):
    joint[(Xc[:, 0] <= 0.0 + 1e-9) & (np.abs(Xc[:, 2] - zc) <= 0.0037)] = j
fj = [f[me][joint == j].sum() for j in (0, 1)]
dz = np.abs(Xc[:, 2] - np.where(joint == 1, 0.08, 0.05)).max()
c.check((joint >= 0).all() and min(fj) > 0.1, "finger: the %d self-contacts at the end are on the notches' faces "
        "(nearest vertices in the reference configuration: x <= %.4f m, within %.4f m of a joint), both joints "
        "loaded (%.2f and %.2f N)" % (me.sum(), Xc[:, 0].max(), dz, fj[0], fj[1]))
# the held pose's balance: the base's reaction (its moment about the base's centroid, the origin), the pusher's
# contact forces on the finger (force_world is the force on side 1) at their points, the weight at the centre of mass
v = X[Fi["bodies/finger/mesh/cells"][:]]
vol = np.abs(np.einsum("ij,ij->i", v[:, 1] - v[:, 0], np.cross(v[:, 2] - v[:, 0], v[:, 3] - v[:, 0]))) / 6
W = 1100 * vol.sum() * np.array([0, 0, -9.81])
com = (vol[:, None] * P[Fi["bodies/finger/mesh/cells"][:]].mean(1)).sum(0) / vol.sum()
Fp_i = np.where((b[:, 0] == 0)[:, None], fw, -fw)[~me]
Fp, R = Fp_i.sum(0), Fi["bodies/finger/reactions/base"][-1]
F = R[:3] + Fp + W
M = R[3:] + np.cross(pt[~me], Fp_i).sum(0) + np.cross(com, W)
c.check(np.linalg.norm(F) <= 1e-3 * np.linalg.norm(Fp) and f[me].sum() > np.linalg.norm(Fp),
        "finger, held: base reaction + pusher + weight = %.1e N against the pusher's %.2f N (bound 1e-3 of it), "
        "the self-contacts carrying %.2f N" % (np.linalg.norm(F), np.linalg.norm(Fp), f[me].sum()))
# the moments: without a self-contact (the pusher's first 0.3 s, held) they cancel to 1e-10 N m; the self-contacts,
# equal and opposite forces, leave a couple of a few percent of the base's moment (docs/scenes.md)
MR = np.linalg.norm(R[3:])
c.check(np.linalg.norm(M) <= 5e-2 * MR, "finger, held: their moments about the base cancel to |M| = %.1e N m of the "
        "base's %.4f N m (bound 5e-2 of it: the self-contacts' couple)" % (np.linalg.norm(M), MR))
if NP > 1:
    # before the joints close, the 1-rank run to round-off; from then on the closed notches' self-contacts are an
    # ill-conditioned problem (nearly redundant contacts between two flat faces), whose forces, solved to
    # -pgs_tol, differ between runs whose inputs differ by round-off (MUMPS' parallel sums): the same contacts,
    # the resultants and the positions to the bounds below (docs/scenes.md)
    F1 = scene("input/finger_fold.opts", 1, "finger_fold")

    def resultants(H):
        o, B = H["contacts/offset"][:], H["contacts/bodies"][:]
        f, fw = H["contacts/force"][:, 0], H["contacts/force_world"][:]
        r = []
        for k in range(len(o) - 1):
            s, me = slice(o[k], o[k + 1]), (B[o[k]:o[k + 1], 0] == B[o[k]:o[k + 1], 1])
            r.append([f[s][me].sum(), *np.where((B[s, 0] == 0)[:, None], fw[s], -fw[s])[~me].sum(0)])
        return np.array(r), H["bodies/finger/reactions/base"][:, :3]

    same, ef, _ = same_as_1_rank(F1, Fi, "finger", steps=first)
    (a1, r1), (an, rn) = resultants(F1), resultants(Fi)
    er = max(np.abs(a1 - an).max() / np.abs(a1).max(), np.abs(r1 - rn).max() / np.abs(r1).max())
    i1, i_n = np.lexsort(F1["bodies/finger/mesh/reference"][:].T), np.lexsort(X.T)
    P1, Pn = F1["bodies/finger/positions"], Fi["bodies/finger/positions"]
    dx = max(np.abs(P1[k][i1] - Pn[k][i_n]).max() for k in range(len(F1["frames/time"])))
    c.check(same and ef <= 1e-10 and er <= 1e-3 and dx <= 5e-5, "finger, %d ranks: the 1-rank contacts at every step "
            "(%s) and their forces to %.1e (relative) before the joints close; then the self-contacts' total, the "
            "pusher's force and the base's reaction to %.1e (relative, bound 1e-3), the positions of every frame to "
            "%.1e m (bound 5e-5 m)" % (NP, "same" if same else "DIFFERENT", ef, er, dx))

# the sheet folded in half
if NP == 1:
    SF = scene("input/sheet_fold.opts", 1, "sheet_fold")
    held(SF, "sheet fold")
    mask, _ = self_contacts(SF)
    off = SF["contacts/offset"][:]
    m = mask[off[-2]:off[-1]]
    pt, nrm, f = last_step(SF, "point")[m], last_step(SF, "normal")[m], last_step(SF, "force")[m, 0]
    c.check(len(pt) > 0 and (pt[:, 0] > 0.25).all() and (pt[:, 0] < 0.55).all() and (np.abs(pt[:, 2] - 0.025) < 0.01).all()
            and (np.abs(nrm[:, 2]) > 0.9).all(), "sheet fold: the self-contacts lie between the two layers, where the "
            "upper half lies on the lower one (x in [%.3f, %.3f] m, z in [%.4f, %.4f] m, normals within %.0f degrees of "
            "vertical)" % (pt[:, 0].min(), pt[:, 0].max(), pt[:, 2].min(), pt[:, 2].max(),
                           np.degrees(np.arccos(np.abs(nrm[:, 2]).min()))))
    c.check(f.sum() > 1.0, "sheet fold: the layers press on each other, %.2f N over %d loaded contacts (the upper half "
            "weighs %.1f N)" % (f.sum(), (f > 0).sum(), 1000 * 0.6 * 0.2 * 0.025 * 9.81))
else:
    short = ["-time_steps", "120"]
    Sn, S1 = scene("input/sheet_fold.opts", NP, "sheet_fold", short), scene("input/sheet_fold.opts", 1, "sheet_fold", short)
    held(Sn, "sheet fold, %d ranks, to t = 1.2 s" % NP)
    same, ef, dx = same_as_1_rank(S1, Sn, "sheet")
    c.check(same and ef <= 1e-10 and dx <= 1e-10, "sheet fold, %d ranks, to t = 1.2 s: the 1-rank contacts at every "
            "step (%s), forces to %.1e (relative), positions to %.1e m" % (NP, "same" if same else "DIFFERENT", ef, dx))

if NP == 1:
    Fa = scene("input/hard/u_bend_fast.opts", 1, "u_bend_fast")
    held(Fa, "fast fold (2 m/s)")
    S = scene("input/hard/u_bend_stick.opts", 1, "u_bend_stick", ["-output_every", 1])
    held(S, "fold with mu = 1")
    st, ft, f = last_step(S, "state"), last_step(S, "force_tangential"), last_step(S, "force")
    stick = st == 1
    ratio = ft[stick] / f[stick, 0] if stick.any() else np.zeros(1)
    c.check(stick.sum() >= 3 and ratio.max() >= 0.1 and (ft <= (1 + 1e-9) * f[:, 0]).all(),
            "fold with mu = 1: %d sticking contacts at the end, tangential/normal up to %.2f, all inside the cone" %
            (stick.sum(), ratio.max()))
    # no creep: over the hold (t >= 1.1 s), the surface vertices nearest each loaded contact of the last
    # step move together; frictionless, the same fold's arms slide along each other as the loop settles

    def creep(H, which):
        t, Ps, X = H["frames/time"][:], H["bodies/bar/positions"], H["bodies/bar/mesh/reference"][:]
        k0 = int(np.argmax(t >= 1.1))
        L, R = np.where(X[:, 0] < -0.05)[0], np.where(X[:, 0] > 0.05)[0]
        p0, p1, m = Ps[k0], Ps[-1], 0.0
        for q in last_step(H, "point")[which(H)]:
            a, b = L[np.argmin(np.linalg.norm(p0[L] - q, axis=1))], R[np.argmin(np.linalg.norm(p0[R] - q, axis=1))]
            m = max(m, np.linalg.norm((p1[a] - p0[a]) - (p1[b] - p0[b])))
        return m

    S0 = scene("input/hard/u_bend_stick.opts", 1, "u_bend_slide", ["-output_every", 1, "-contact_mu", 0])
    c1, c0 = creep(S, lambda H: last_step(H, "state") == 1), creep(S0, lambda H: last_step(H, "force")[:, 0] > 0)
    c.check(c1 <= 0.1 * c0, "fold with mu = 1: the sticking arms do not creep over the hold (t = 1.1 to 1.5 s), "
            "%.1e m between facing vertices; frictionless %.1e m (bound a tenth of it)" % (c1, c0))

if NP == 1:
    # the letter fold: each self-contact of the last step between two of the sheet's thirds (by reference x), side 1
    # the vertex nearest its point, side 2 the vertex of another third nearest the point moved back along the normal
    L = scene("input/hard/sheet_fold_twice.opts", 1, "sheet_fold_twice")
    held(L, "letter fold")
    X, P = L["bodies/sheet/mesh/reference"][:], L["bodies/sheet/positions"][-1]
    third = np.where(X[:, 0] < -0.2 - 1e-9, "left", np.where(X[:, 0] > 0.2 + 1e-9, "right", "middle"))
    mask, _ = self_contacts(L)
    off = L["contacts/offset"][:]
    m = mask[off[-2]:off[-1]]
    between = {}
    for p, nrm, g, f in zip(last_step(L, "point")[m], last_step(L, "normal")[m], last_step(L, "gap")[m],
                            last_step(L, "force")[m, 0]):
        t1 = third[np.argmin(np.linalg.norm(P - p, axis=1))]
        d = np.linalg.norm(P - (p - max(g, 0.002) * nrm), axis=1)
        d[third == t1] = np.inf
        k = tuple(sorted((t1, third[np.argmin(d)])))
        between[k] = between.get(k, np.zeros(2)) + [f > 0, f]
    lo, hi = between.get(("left", "middle"), np.zeros(2)), between.get(("left", "right"), np.zeros(2))
    c.check(lo[0] > 0 and hi[0] > 0, "letter fold, at the end: the left third on the middle one (%d loaded contacts, "
            "%.2f N) and the right third on the left one (%d, %.2f N): three layers in contact" % (lo[0], lo[1], hi[0], hi[1]))
c.done()
