"""Constraint schemes (issue 4):
- contacts on a plane (frames independent of positions): the fast scheme's recursion stops after
  the first Newton iteration (newton_tol > 0) and gives the explicit scheme's motion (1e-12);
- the grasp scene (input/grasp_rotate.opts, normals turning fast within a step): the end-of-step
  constraint violation on the real geometry (/steps/violation) is at least 10 times smaller with the
  fast scheme than with the explicit one, and within the contact solver's tolerance scale (1e-6 m).
Usage: test_schemes.py [--np N]"""
import numpy as np
import h5py
from fctest import run, out, Checker, np_from_argv, sorted_positions

NP = np_from_argv()
c = Checker("schemes np%d" % NP)
res = {}
for sch in ["explicit", "fast"]:
    f = out("plane_%s_np%d.h5" % (sch, NP))
    run(["-options_file", "input/cube_drop.opts", "-time_steps", "60", "-constraint_scheme", sch, "-newton_tol", "1e-10",
         "-pgs_tol", "1e-12", "-pgs_max_it", "20000", "-output_file", f, "-quiet"], np_=NP)
    res[sch] = h5py.File(f, "r")
nit = res["fast"]["steps/newton_iterations"][:]
nc = res["fast"]["steps/contacts"][:]
c.check(np.all(nit[nc > 0] == 1) and (nc > 0).sum() > 10, "plane: fast stops after 1 Newton iteration in all %d contact steps" % (nc > 0).sum())
pa, pb = sorted_positions(res["explicit"], "cube")[1], sorted_positions(res["fast"], "cube")[1]
err = np.abs(pa - pb).max()
c.check(err < 1e-9, "plane: fast and explicit give the same positions (max diff %.1e m)" % err)

viol = {}
for sch in ["explicit", "fast"]:
    f = out("grasp_%s_np%d.h5" % (sch, NP))
    run(["-options_file", "input/grasp_rotate.opts", "-time_steps", "40", "-constraint_scheme", sch, "-output_file", f, "-quiet"], np_=NP)
    H = h5py.File(f, "r")
    v = H["steps/violation"][:]
    viol[sch] = v[H["steps/contacts"][:] > 0].max()
c.check(viol["fast"] * 10 <= viol["explicit"], "grasp: end-of-step violation fast %.2e m vs explicit %.2e m (ratio %.1e)" % (viol["fast"], viol["explicit"], viol["explicit"] / max(viol["fast"], 1e-300)))
c.check(viol["fast"] < 1e-6, "grasp: fast violation %.2e m within the solver tolerance scale" % viol["fast"])
c.done()
