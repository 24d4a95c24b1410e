"""The crossing audit (issue 57; docs/method.md, 2.7): what went through another body's surface over a
step's actual motion, /steps/crossings and /steps/crossing_depth, and the step redone smaller
(-contact_crossings redo; the default, count, records and warns), on 1 and 2 ranks.

- A steel ball at 3 m/s onto a stretched co-rotational membrane (input/hard/ball_membrane.opts,
  E = 2e5): at h = 0.02 the ball's picture goes through the membrane's triangles at a step, counted
  by the default (-contact_crossings count) with the step taken whole; with -contact_crossings redo
  that step is redone smaller (/steps/substeps > 1), and no step keeps a crossing or ends with a
  point inside; at h = 0.005 none with the default. The ball is caught every time (it ends above the
  membrane's lowest point and moves up again). Softer (E = 5e4), count and redo the same way. Where
  smaller steps cannot cure it (a contact kind switched off), redo halves the step
  -contact_crossings_cuts times and keeps it, counted.
- The audit counts what a contact kind would have held: the ball's picture points against the
  membrane's triangles (-contact_shape_points 0, counted with -contact_crossings count) go through
  at the first steps, where the default kinds leave none.
- Two FE bars crossed edge on edge (input/hard/crossed_bars.opts): without the edge-edge contacts
  (-contact_edge_edge 0) the audit counts the edges that go through the other bar; with them none.
- -contact_crossings off: the audit is not run (the datasets hold 0); a bad value is an error
  naming the option; the default (count) counts as count does and warns on the progress line.
- 2 ranks: the same steps and counts as 1 rank (the ball's trajectory within 1e-6 m)."""
import numpy as np
import h5py
from fctest import run, out, Checker, np_from_argv

NP = np_from_argv()
c = Checker("crossings np%d" % NP)
ball = ["-options_file", "input/hard/ball_membrane.opts", "-quiet", "-time_steps", "20"]
base = None  # the scene with -contact_crossings redo (h = 0.02)
soft = ball + ["-sheet_young", "5e4"]


def steps(f, name):
    return f["steps/" + name][:].ravel()


def caught(f):
    z = f["bodies/ball/centroid"][:, 2]
    zs = f["bodies/sheet/positions"][:, :, 2].min(axis=1)
    k = int(np.argmin(z))
    return z, zs, k


for h, n, mode in (("0.02", 20, "count"), ("0.02", 20, "redo"), ("0.005", 80, "count")):
    fh = out("ball_membrane_h%s_%s.h5" % (h, mode))
    run(ball + ["-time_step", h, "-time_steps", n, "-contact_crossings", mode, "-output_file", fh], np_=NP)
    with h5py.File(fh, "r") as g:
        z, zs, k = caught(g)
        cr, it = steps(g, "crossings").sum(), steps(g, "intersections").sum()
        ok = z[k] > zs[k] and z[-1] > z[k] + 0.01
        what = "E = 2e5, h = %s, -contact_crossings %s: caught (the ball's centre at its lowest %.3f m above the " \
               "membrane's lowest point %.3f m, rising to %.3f m), %d crossing(s), %d point(s) inside over the steps" % (
                   h, mode, z[k], zs[k], z[-1], cr, it)
        if h == "0.02" and mode == "count":  # the step taken whole: the ball's picture goes through at one step
            ok = ok and cr > 0 and (steps(g, "substeps") == 1).all()
        else:
            ok = ok and cr == 0 and it == 0
        if mode == "redo":
            base = fh
            ok = ok and steps(g, "substeps").max() > 1
            what += ", %d step(s) redone smaller" % (steps(g, "substeps") > 1).sum()
        c.check(ok, what)

fc = out("ball_membrane_count.h5")
run(soft + ["-contact_crossings", "count", "-output_file", fc], np_=NP)
with h5py.File(fc, "r") as g:
    n = steps(g, "crossings")
    c.check(n.sum() > 0 and (steps(g, "substeps") == 1).all(),
            "E = 5e4, -contact_crossings count: steps taken whole, %d crossing(s) counted over %d step(s), "
            "the deepest %.2g m" % (n.sum(), (n > 0).sum(), steps(g, "crossing_depth").max()))
runs = {}
for np_ in sorted({1, NP}):
    f = out("ball_membrane_redo_np%d.h5" % np_)
    run(soft + ["-contact_crossings", "redo", "-output_file", f], np_=np_)
    runs[np_] = h5py.File(f, "r")
f = runs[NP]
z, zs, k = caught(f)
c.check(steps(f, "crossings").sum() == 0 and steps(f, "substeps").max() > 1 and z[k] > zs[k] and z[-1] > z[k] + 0.01,
        "E = 5e4, -contact_crossings redo: %d step(s) redone smaller (at most %d sub-steps), no crossing kept, the "
        "ball caught (lowest %.3f m above the membrane's %.3f m)" % ((steps(f, "substeps") > 1).sum(),
                                                                     steps(f, "substeps").max(), z[k], zs[k]))
if NP > 1:
    a, b = runs[1], runs[NP]
    same = (steps(a, "substeps") == steps(b, "substeps")).all() and (steps(b, "crossings") == 0).all()
    dz = np.abs(a["bodies/ball/centroid"][:] - b["bodies/ball/centroid"][:]).max()
    c.check(same and dz < 1e-6, "2 ranks: the same sub-steps as 1 rank, no crossing kept, the ball within %.2g m" % dz)

fs = out("ball_membrane_noshape.h5")
run(ball + ["-time_steps", "3", "-contact_shape_points", "0", "-contact_crossings", "count", "-output_file", fs],
    np_=NP)
with h5py.File(fs, "r") as g:
    n = steps(g, "crossings")
    c.check(n[0] > 10 and h5py.File(base, "r")["steps/crossings"][0] == 0,
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

fk = out("ball_membrane_noshape_redo.h5")
run(ball + ["-time_steps", "1", "-contact_shape_points", "0", "-contact_crossings", "redo", "-output_file", fk],
    np_=NP)
with h5py.File(fk, "r") as g:
    c.check(steps(g, "substeps")[0] == 4 and steps(g, "crossings")[0] > 0,
            "-contact_crossings redo, shape points off: step 1 halved twice (-contact_crossings_cuts 2: %d sub-steps), "
            "then kept with its %d crossing(s) counted" % (steps(g, "substeps")[0], steps(g, "crossings")[0]))

fo = out("ball_membrane_off.h5")
run(ball + ["-time_steps", "3", "-contact_shape_points", "0", "-contact_crossings", "off", "-output_file", fo],
    np_=NP)
with h5py.File(fo, "r") as g:
    c.check((steps(g, "crossings") == 0).all(), "-contact_crossings off: no audit, the datasets hold 0")
fd = out("ball_membrane_default.h5")
p = run(["-options_file", "input/hard/ball_membrane.opts", "-time_steps", "3", "-contact_shape_points", "0",
         "-output_file", fd], np_=NP)
with h5py.File(fd, "r") as g, h5py.File(fs, "r") as h:
    c.check((steps(g, "crossings") == steps(h, "crossings")).all() and "went through another body's surface" in p.stdout,
            "the default (-contact_crossings count): the same counts as count, the progress line warns")
p = run(ball + ["-contact_crossings", "sometimes"], np_=NP, check=False)
c.check(p.returncode == 1 and "-contact_crossings" in p.stdout + p.stderr,
        "-contact_crossings sometimes: exit %d, the error names the option" % p.returncode)
c.done()
