"""Continuous detection and the end-of-step intersection check (issue 15).

- Continuous detection never lets a fast body through a thin one: the ball of
  input/hard/ball_thin_slab.opts dropped at 5 to 40 m/s from heights that put the slab at different
  fractions of a step: its centre never goes below r above the slab's bottom, and no step ends
  with an intersection; the same scene with -contact_detection discrete goes through at 20 m/s.
- /steps/intersections counts the vertices inside the other body (the FE cube of
  input/hard/cube_thin_plate.opts, discrete: 16 vertices in the plate after step 1, 0 after), the
  progress line warns on such a step, -contact_fail_on_intersection stops the run there with a
  message naming the step and the option, the output closed and holding that step.
- Bad values of the new options are errors naming the option.
- A bounded shape's points against the FE triangles (-contact_shape_points, the default): a ball
  smaller than the elements (r = 8 mm, slab vertices 12.5 mm apart) at 20 m/s onto the stiff thin
  slab stays above it, the same run with the option off ends below the slab; the intersection
  check counts the ball's points inside the slab (discrete detection, option off: step 1 ends with
  the ball in it, no slab vertex inside the ball). A rigid box turning on an FE slab
  (input/box_on_slab.opts): its corners, against the slab's triangles, never end a step inside it;
  with the option off they do.
- An FE body all of whose free DOFs are contact DOFs (the soft one-element slab under the small
  ball: the condensed builder's Schur block grows to all of A, which MUMPS refuses) runs, and
  gives the dense builder's trajectory.
- Edge-edge contacts (two weights per side) in every compliance builder and both recursive
  schemes: the crossed bars give the same positions as with the dense builder.
Usage: test_detection.py [--np N]"""
import h5py
import numpy as np
from fctest import run, out, Checker, np_from_argv

NP = np_from_argv()
c = Checker("detection np%d" % NP)
BALL = ["-options_file", "input/hard/ball_thin_slab.opts", "-time_steps", "12"]
CUBE = ["-options_file", "input/hard/cube_thin_plate.opts", "-time_steps", "5"]

# continuous detection: no pass-through at any speed or phase of the crossing within a step
# The count sees the ball's points too (-contact_shape_points, the default): at 40 m/s (v h = 0.4 m,
# 20 slab thicknesses a step) the impact step from z = 0.3021 leaves one of them between 1e-4 and
# 2e-4 m inside the slab (measured: 1 point at the default depth 1e-4, none at 2e-4), so those runs
# count from 2e-4 m
for v, z in [(5, 0.17), (20, 0.17), (20, 0.1234), (40, 0.17), (40, 0.3021)]:
    f = out("ball_%g_%g_np%d.h5" % (v, z, NP))
    depth = ["-contact_intersection_depth", "2e-4"] if v >= 40 else []
    run(BALL + ["-ball_velocity", "0,0,-%g" % v, "-ball_center", "0,0,%g" % z, "-output_file", f, "-quiet"] + depth,
        np_=NP)
    with h5py.File(f, "r") as H:
        zmin, n = H["bodies/ball/centroid"][:, 2].min(), H["steps/intersections"][:].max()
    # the slab is 0.02 m thick, its bottom fixed at z = 0: a centre below r = 0.05 went into it
    c.check(zmin >= 0.05 and n == 0, "ball at %g m/s from z = %g: lowest centre %.4f m >= r = 0.05, intersections %d" % (v, z, zmin, n))
f = out("ball_discrete_np%d.h5" % NP)
run(BALL + ["-contact_detection", "discrete", "-output_file", f, "-quiet"], np_=NP)
with h5py.File(f, "r") as H:
    zend = H["bodies/ball/centroid"][-1, 2]
c.check(zend < 0, "discrete detection: the ball at 20 m/s goes through the slab (centre at %.2f m)" % zend)

# the intersection count, the warning and the fail option
f = out("cube_discrete_np%d.h5" % NP)
p = run(CUBE + ["-contact_detection", "discrete", "-output_file", f], np_=NP)
with h5py.File(f, "r") as H:
    n = H["steps/intersections"][:]
c.check(n[0] == 16 and not n[1:].any(), "discrete: /steps/intersections %s (16 vertices in the plate after step 1, then pushed out below it)" % n.tolist())
warn = [l for l in p.stdout.splitlines() if "WARNING" in l]
c.check(len(warn) == 1 and warn[0].startswith("step 1/5") and "16 point(s) inside another body" in warn[0],
        "the progress line of step 1 warns: %r" % (warn[0] if warn else p.stdout[-300:]))
f = out("cube_continuous_np%d.h5" % NP)
p = run(CUBE + ["-output_file", f], np_=NP)
with h5py.File(f, "r") as H:
    n = H["steps/intersections"][:]
c.check(not n.any() and "WARNING" not in p.stdout, "continuous: intersections %s, no warning" % n.tolist())
f = out("cube_fail_np%d.h5" % NP)
p = run(CUBE + ["-contact_detection", "discrete", "-contact_fail_on_intersection", "-output_file", f, "-quiet"], np_=NP, check=False)
txt = p.stdout + p.stderr
c.check(p.returncode != 0 and "step 1 " in txt and "-contact_fail_on_intersection" in txt and "16 point(s)" in txt,
        "-contact_fail_on_intersection: exit %d, the message names step 1, the 16 points and the option" % p.returncode)
with h5py.File(f, "r") as H:
    rows, n = len(H["steps/step"]), H["steps/intersections"][:].tolist()
c.check(rows == 1 and n == [16], "-contact_fail_on_intersection: the output is closed and holds step 1 (%d rows, intersections %s)" % (rows, n))

# a ball smaller than the slab's elements: its points against the slab's triangles hold it
SMALL = BALL[:2] + ["-time_steps", "8", "-ball_radius", "0.008", "-ball_center", "0.013,0.017,0.21", "-quiet"]
for sp in ("1", "0"):
    f = out("small_ball_sp%s_np%d.h5" % (sp, NP))
    run(SMALL + ["-slab_young", "1e10", "-contact_shape_points", sp, "-output_file", f], np_=NP)
    with h5py.File(f, "r") as H:
        z, n = H["bodies/ball/centroid"][:, 2], H["steps/intersections"][:]
    if sp == "1":  # the slab's top is at z = 0.02: a centre below 0.02 + r = 0.028 went into it
        c.check(z.min() >= 0.028 - 1e-4 and not n.any(),
                "small ball, shape points on: lowest centre %.5f m >= 0.028 - 1e-4, intersections %s" % (z.min(), n.tolist()))
    else:
        c.check(z[-1] < 0 and n.any(), "small ball, shape points off: through the slab (centre %.3f m), intersections %s"
                % (z[-1], n.tolist()))
# a box's corners (its picture's points, against the slab's triangles): the slab's vertices alone
# let them sink between those (measured: up to 4 corners inside in steps 18-23 and 31-40; at step 40
# 1.8-2.1 mm below the slab's undeformed top)
for sp in ("1", "0"):
    f = out("box_corners_sp%s_np%d.h5" % (sp, NP))
    run(["-options_file", "input/box_on_slab.opts", "-time_steps", "40", "-contact_shape_points", sp, "-output_file", f,
         "-quiet"], np_=NP)
    with h5py.File(f, "r") as H:
        n, res = H["steps/intersections"][:], H["steps/residual"][:].max()
    if sp == "1":
        c.check(not n.any() and res <= 1e-8, "box on slab, shape points on: intersections (max) %d, residual %.1e" % (n.max(), res))
    else:
        c.check(n.max() == 4, "box on slab, shape points off: its 4 bottom corners end inside the slab (%d)" % n.max())
f = out("small_ball_count_np%d.h5" % NP)
run(SMALL[:-1] + ["-time_steps", "1", "-slab_young", "1e10", "-contact_detection", "discrete",
                  "-contact_shape_points", "0", "-output_file", f, "-quiet"], np_=NP)
with h5py.File(f, "r") as H:
    z, n = H["bodies/ball/centroid"][0, 2], H["steps/intersections"][0]
c.check(0.008 < z < 0.012 and n > 100, "discrete, shape points off: the ball ends inside the slab (centre %.4f m), "
        "the check counts %d of its points inside (was 0: only slab vertices were tested)" % (z, n))
# the soft slab punched by the small ball (shape points off): every free DOF a contact DOF (condensed:
# Sigma = A; MUMPS refused it, INFOG(1) = -49)
ref = None
for t in ("dense", "condensed"):
    f = out("small_ball_soft_%s_np%d.h5" % (t, NP))
    p = run(SMALL + ["-time_steps", "4", "-contact_shape_points", "0", "-compliance_type", t, "-output_file", f], np_=NP,
            check=False)
    ok = p.returncode == 0
    with h5py.File(f, "r") as H:
        x = H["bodies/ball/centroid"][:]
    if ref is None:
        ref = x
    d = np.abs(x - ref).max() if x.shape == ref.shape else np.inf
    c.check(ok and len(x) == 4 and d <= 1e-8, "soft slab, %s builder: exit %d, 4 steps, ball %.1e m from dense's"
            % (t, p.returncode, d))

# bad values name the option
for opt, val in [("-contact_detection", "sweep"), ("-contact_separation_speed", "0"), ("-contact_intersection_depth", "-1")]:
    p = run(CUBE + [opt, val, "-output_file", out("bad_np%d.h5" % NP), "-quiet"], np_=NP, check=False)
    c.check(p.returncode != 0 and opt in p.stdout + p.stderr, "%s %s: an error naming the option (exit %d)" % (opt, val, p.returncode))
# edge-edge contacts (two weights per side) in every compliance builder and every scheme: the
# crossed bars (linear material, so that precomputed is exact too) give the dense builder's
# positions to 1e-10 m (measured <= 1.3e-15 m on 1 rank with corotational bars)
BARS = ["-options_file", "input/hard/crossed_bars.opts", "-time_steps", "15", "-top_material", "linear",
        "-bottom_material", "linear", "-quiet"]
ref = None
variants = [["-compliance_type", t] for t in ("dense", "sparse", "schur", "inverse", "redundant", "precomputed")
            if not (t == "sparse" and NP > 1)]  # sparse: one rank only (its own error says why)
for extra in variants + [["-constraint_scheme", "standard"], ["-constraint_scheme", "fast"]]:
    f = out("bars_%s_np%d.h5" % (extra[1], NP))
    run(BARS + extra + ["-output_file", f], np_=NP)
    with h5py.File(f, "r") as H:
        x = np.concatenate([np.sort(H["bodies/%s/positions" % b][-1], axis=0).ravel() for b in ("top", "bottom")])
        edge = H["steps/contacts"][-1] == 1 and H["contacts/force"][-1][0] > 0
    if ref is None:
        ref = x
    d = np.abs(x - ref).max()
    c.check(edge and d <= 1e-10, "crossed bars %s %s: the edge-edge contact pushes, positions %.1e m from dense's" % (extra[0], extra[1], d))
c.done()
