"""The crossing audit (issue 57; docs/method.md, 2.6): what went through another body's surface over a
step's actual motion, /steps/crossings and /steps/crossing_depth, and the step redone smaller
(-contact_crossings redo, the default), on 1 and 2 ranks.

- A steel ball at 3 m/s onto a stretched co-rotational membrane (input/hard/ball_membrane.opts,
  E = 2e5, h = 0.02 and 0.005): the ball is caught (it ends above the membrane's lowest point and
  moves up again), no step keeps a crossing, no point is inside the other body at any step; at
  h = 0.02 the audit redoes at least one step smaller (/steps/substeps > 1) where the ball's picture
  went through the membrane's triangles with the step taken whole (-contact_crossings count: counted).
- The audit counts what a contact kind would have held: the ball's picture points against the
  membrane's triangles (-contact_shape_points 0, counted with -contact_crossings count) go through
  at the first steps, where the default kinds leave none.
- Two FE bars crossed edge on edge (input/hard/crossed_bars.opts): without the edge-edge contacts
  (-contact_edge_edge 0) the audit counts the edges that go through the other bar; with them none.
- -contact_crossings off: the audit is not run (the datasets hold 0); a bad value is an error
  naming the option.
- 2 ranks: the same steps and counts as 1 rank (the ball's trajectory within 1e-6 m)."""
import numpy as np
import h5py
from fctest import run, out, Checker, np_from_argv

NP = np_from_argv()
c = Checker("crossings np%d" % NP)
ball = ["-options_file", "input/hard/ball_membrane.opts", "-quiet", "-time_steps", "20"]


def steps(f, name):
    return f["steps/" + name][:].ravel()


def caught(f):
    z = f["bodies/ball/centroid"][:, 2]
    zs = f["bodies/sheet/positions"][:, :, 2].min(axis=1)
    k = int(np.argmin(z))
    return z, zs, k


runs = {}
for np_ in sorted({1, NP}):
    f = out("ball_membrane_np%d.h5" % np_)
    run(ball + ["-output_file", f], np_=np_)
    runs[np_] = h5py.File(f, "r")
f = runs[NP]
z, zs, k = caught(f)
c.check(steps(f, "crossings").sum() == 0 and steps(f, "intersections").sum() == 0,
        "h = 0.02: no step kept a crossing (%d) or a point inside the other body (%d)" % (
            steps(f, "crossings").sum(), steps(f, "intersections").sum()))
c.check(steps(f, "substeps").max() > 1, "h = 0.02: the audit redid %d step(s) smaller (at most %d sub-steps)" % (
    (steps(f, "substeps") > 1).sum(), steps(f, "substeps").max()))
c.check(z[k] > zs[k] and z[-1] > z[k] + 0.01,
        "h = 0.02: the ball is caught: its centre at its lowest %.3f m is above the membrane's lowest point %.3f m, "
        "and it rises to %.3f m" % (z[k], zs[k], z[-1]))
if NP > 1:
    a, b = runs[1], runs[NP]
    same = (steps(a, "substeps") == steps(b, "substeps")).all() and (steps(b, "crossings") == 0).all()
    dz = np.abs(a["bodies/ball/centroid"][:] - b["bodies/ball/centroid"][:]).max()
    c.check(same and dz < 1e-6, "2 ranks: the same sub-steps as 1 rank, no crossing kept, the ball within %.2g m" % dz)

fc = out("ball_membrane_count.h5")
run(ball + ["-contact_crossings", "count", "-output_file", fc], np_=NP)
with h5py.File(fc, "r") as g:
    n = steps(g, "crossings")
    c.check(n.sum() > 0 and (steps(g, "substeps") == 1).all(),
            "h = 0.02, -contact_crossings count: steps taken whole, %d crossing(s) counted over %d step(s), "
            "the deepest %.2g m" % (n.sum(), (n > 0).sum(), steps(g, "crossing_depth").max()))

f5 = out("ball_membrane_h005.h5")
run(ball + ["-time_step", "0.005", "-time_steps", "80", "-output_file", f5], np_=NP)
with h5py.File(f5, "r") as g:
    z, zs, k = caught(g)
    c.check(steps(g, "crossings").sum() == 0 and steps(g, "intersections").sum() == 0 and z[k] > zs[k]
            and z[-1] > z[k] + 0.01,
            "h = 0.005: caught (lowest %.3f m above the membrane's %.3f m, rises to %.3f m), no crossing, no "
            "intersection" % (z[k], zs[k], z[-1]))

fs = out("ball_membrane_noshape.h5")
run(ball + ["-time_steps", "3", "-contact_shape_points", "0", "-contact_crossings", "count", "-output_file", fs],
    np_=NP)
with h5py.File(fs, "r") as g:
    n = steps(g, "crossings")
    c.check(n[0] > 10 and runs[NP]["steps/crossings"][0] == 0,
            "the ball's picture points without their contacts (-contact_shape_points 0): %d crossing(s) at step 1 "
            "(the deepest %.2g m), 0 with them" % (n[0], steps(g, "crossing_depth")[0]))

bars = ["-options_file", "input/hard/crossed_bars.opts", "-quiet", "-contact_crossings", "count", "-time_steps", "10"]
counts = {}
for edges in (0, 1):
    fe = out("crossed_bars_edges%d.h5" % edges)
    run(bars + ["-contact_edge_edge", edges, "-output_file", fe], np_=NP)
    with h5py.File(fe, "r") as g:
        counts[edges] = (steps(g, "crossings").sum(), steps(g, "crossing_depth").max())
c.check(counts[0][0] > 0 and counts[1][0] == 0,
        "crossed bars: without the edge-edge contacts (-contact_edge_edge 0) %d edge crossing(s) counted (the "
        "deepest point %.2g m inside), with them %d" % (counts[0][0], counts[0][1], counts[1][0]))

fo = out("ball_membrane_off.h5")
run(ball + ["-time_steps", "3", "-contact_shape_points", "0", "-contact_crossings", "off", "-output_file", fo],
    np_=NP)
with h5py.File(fo, "r") as g:
    c.check((steps(g, "crossings") == 0).all(), "-contact_crossings off: no audit, the datasets hold 0")
p = run(ball + ["-contact_crossings", "sometimes"], np_=NP, check=False)
c.check(p.returncode == 1 and "-contact_crossings" in p.stdout + p.stderr,
        "-contact_crossings sometimes: exit %d, the error names the option" % p.returncode)
c.done()
