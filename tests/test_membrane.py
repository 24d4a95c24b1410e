"""A steel ball dropped at 3 m/s onto a soft co-rotational membrane held at two edges
(input/membrane.opts: two -sheet_fixed_box boxes), on 1 and 2 ranks.

- E = 1e5: the membrane stretches (the ball sinks below its rest plane) and throws the ball back up;
  no element turns inside out, no sheet vertex enters the ball, every contact solve converges, and no
  point of either body is inside the other deeper than 1 mm at any step (-contact_intersection_depth
  1e-3; the ball's exact surface between the points of its picture may dip below the default 0.1 mm
  into a stretched membrane, docs/validation.md); with the default -contact_rounded_surface exact and
  with picture. Every frame's vertices of the fixed edges stay where they were.
- E = 1e4: the membrane is stretched through its own thickness. By default (co-rotational: its
  elements are turned back) the run goes on (20 steps) with elements inside out, counted in
  /steps/inverted_elements (at each frame's step, the tetrahedra of the frame's positions with a
  non-positive volume) with J <= 0 in /steps/min_volume_ratio, the state finite; -sheet_inverted
  error stops at the end of the step where an element turns inside out, non-zero, with an error
  naming the body and the cause, and the completed steps readable (/complete).
- 2 ranks: the same steps and ball trajectory as 1 rank (1e-8 m)."""
import numpy as np
import h5py
from fctest import run, out, Checker, np_from_argv

NP = np_from_argv()
c = Checker("membrane np%d" % NP)
base = ["-options_file", "input/membrane.opts", "-quiet", "-output_every", "1"]


def tets_inverted_per_frame(f):
    P, cells = f["bodies/sheet/positions"][:], f["bodies/sheet/mesh/cells"][:]
    q = P[:, cells]
    vol = np.einsum("fij,fij->fi", q[:, :, 1] - q[:, :, 0], np.cross(q[:, :, 2] - q[:, :, 0], q[:, :, 3] - q[:, :, 0]))
    return (vol <= 0).sum(axis=1)


def tets_inverted(f):
    return int(tets_inverted_per_frame(f).sum())


runs = {}
for np_ in sorted({1, NP}):
    f = out("membrane_stiff_np%d.h5" % np_)
    run(base + ["-contact_intersection_depth", "1e-3", "-output_file", f], np_=np_)
    runs[np_] = h5py.File(f, "r")


def stiff_checks(f, how):
    z = f["bodies/ball/centroid"][:, 2]
    P = f["bodies/sheet/positions"][:]
    cen = np.concatenate([[[0, 0, 0.075]], f["bodies/ball/centroid"][:]])[f["frames/step"][:]]
    inside = (np.linalg.norm(P - cen[:, None, :], axis=2) < 0.05 - 1e-6).sum()
    c.check(z.min() < 0.0 and z[-1] > 0.1,
            "E = 1e5 (%s): the ball sinks to z = %.3f (the membrane's top at 0.02) and is thrown back to %.3f" % (
                how, z.min(), z[-1]))
    c.check(tets_inverted(f) == 0 and f["steps/inverted_elements"][:].max() == 0 and inside == 0
            and f["steps/intersections"][:].max() == 0
            and f["steps/residual"][:].max() <= 1.0001e-8,
            "E = 1e5 (%s): no element inside out, %d sheet vertices in the ball, intersections deeper than 1 mm at "
            "most %d, every contact solve converged (%.1e)" % (how, inside, f["steps/intersections"][:].max(),
                                                              f["steps/residual"][:].max()))


# the default (-contact_rounded_surface exact: the ball's exact points while the membrane's own free motion does
# not turn the ball's normal at them, its picture's points where it does) and the picture's points throughout
f = runs[NP]
stiff_checks(f, "exact")
fp = out("membrane_stiff_picture_np%d.h5" % NP)
run(base + ["-contact_intersection_depth", "1e-3", "-contact_rounded_surface", "picture", "-output_file", fp], np_=NP)
stiff_checks(h5py.File(fp, "r"), "picture")
P = f["bodies/sheet/positions"][:]
X = f["bodies/sheet/mesh/reference"][:]
edge = np.abs(X[:, 0]) >= 0.149
c.check(np.abs(P[:, edge] - X[edge]).max() == 0.0, "E = 1e5: the %d vertices of the two fixed edges stay put" % edge.sum())
if NP > 1:
    a, b = runs[1], runs[NP]
    d = np.abs(a["bodies/ball/centroid"][:] - b["bodies/ball/centroid"][:]).max()
    c.check(len(a["steps/step"]) == len(b["steps/step"]) and d < 1e-8,
            "E = 1e5: %d ranks give the 1-rank trajectory of the ball (%.1e m)" % (NP, d))

f = out("membrane_soft_np%d.h5" % NP)
p = run(base + ["-sheet_young", "1e4", "-sheet_inverted", "error", "-output_file", f], np_=NP, check=False)
msg = p.stdout + p.stderr
h = h5py.File(f, "r")
S, _ = h["complete"][:]
c.check(p.returncode != 0 and "Body 'sheet'" in msg and "inside out" in msg and "-sheet_inverted allow" in msg,
        "E = 1e4, -sheet_inverted error: the run stops (exit %d) naming the body and the cause: %s" % (
            p.returncode, [l for l in msg.splitlines() if "inside out" in l][:1]))
c.check(S > 0 and len(h["steps/step"]) >= S and tets_inverted(h) == 0,
        "E = 1e4, -sheet_inverted error: the %d completed steps are readable, with no element inside out in them" % S)
f = out("membrane_soft_default_np%d.h5" % NP)
run(base + ["-sheet_young", "1e4", "-time_steps", "20", "-output_file", f], np_=NP)
h = h5py.File(f, "r")
n, J = h["steps/inverted_elements"][:], h["steps/min_volume_ratio"][:]
counted = tets_inverted_per_frame(h)[1:]  # frames 1, 2, ...: the steps of h["frames/step"][1:]
c.check(len(n) == 20 and n.max() > 0 and (J[n > 0] <= 0).all() and np.array_equal(counted, n[h["frames/step"][1:] - 1])
        and np.isfinite(h["bodies/sheet/positions"][:]).all() and np.isfinite(h["bodies/sheet/velocity"][:]).all(),
        "E = 1e4, default (co-rotational: allow): runs on, up to %d elements inside out (J down to %.3f), the counts "
        "those of the frames' positions, the state finite" % (n.max(), J.min()))
c.done()
