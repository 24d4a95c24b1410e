"""FE against FE contact (input/two_cubes.opts: two elastic cubes collide head-on, no gravity,
frictionless): momentum is conserved (the centroids' sum stays at its initial value, 1e-10 of the
travelled distance), the end-of-step penetration stays below 1e-3 of the edge, the cubes rebound
(velocities reversed after the impact), and N ranks give the same contacts and forces as one
(1e-8). Usage: test_fe_fe.py [--np N]"""
import numpy as np
import h5py
from fctest import run, out, Checker, np_from_argv

NP = np_from_argv()
c = Checker("FE-FE contact np%d" % NP)
f = out("two_cubes_np%d.h5" % NP)
opts = ["-options_file", "input/two_cubes.opts", "-pgs_tol", "1e-12", "-pgs_max_it", "20000", "-quiet"]
run(opts + ["-output_file", f], np_=NP)
H = h5py.File(f, "r")
L, R = H["bodies/left/centroid"][:], H["bodies/right/centroid"][:]
L0, R0 = H["bodies/left"].attrs["initial_centroid"], H["bodies/right"].attrs["initial_centroid"]
drift = np.abs((L + R) - (L0 + R0)).max()
c.check(drift < 1e-10 * 0.5, "momentum conserved: centroid sum drifts %.1e m" % drift)
nc = H["steps/contacts"][:]
c.check(nc.max() > 0, "the cubes touch (%d contacts at most)" % nc.max())
pen = H["steps/max_penetration"][:].max()
c.check(pen < 1e-3, "max end-of-step penetration %.2e m < 1e-3 edge" % pen)
vL = (L[-1, 0] - L[-2, 0]) / 0.005
c.check(vL < -0.3, "left cube rebounds: final velocity %.3f m/s (was +1)" % vL)
c.check(np.all(H["steps/constraint_rows"][:] == nc), "frictionless: one row per contact")
if NP > 1:
    f1 = out("two_cubes_ref.h5")
    run(opts + ["-output_file", f1])
    A = h5py.File(f1, "r")
    same = np.array_equal(A["contacts/offset"][:], H["contacts/offset"][:])
    c.check(same, "same contacts per step on 1 and %d ranks" % NP)
    if same:
        err = np.abs(A["contacts/force"][:] - H["contacts/force"][:]).max() / np.abs(A["contacts/force"][:]).max()
        c.check(err < 1e-8, "forces 1 vs %d ranks: rel. diff %.2e" % (NP, err))
c.done()
