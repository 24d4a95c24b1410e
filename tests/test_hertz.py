"""Hertz as the accuracy check of FE-FE contact (input/hertz.opts, scripts/hertz.py, docs/hertz.md):
a linear FE sphere rests under gravity on a 1000x stiffer FE block with two-way detection. On the
two coarsest of the three meshes (d/R = 2 %): the run comes to rest (contact force = weight to
1e-3, d changes by less than 1e-3 over the last 10 steps), the contact solver converges, nothing
intersects; the indentation measured at three depths on the axis agrees (the far-field
correction holds); F / F_Hertz(d) - 1 is positive (linear tets are too stiff) and below 5 %
(measured +4.1 %) on mesh 1, below 3 % (measured +2.2 %) on mesh 2, and falls from mesh 1 to
mesh 2; N ranks give the F and d of one (1e-6). With -contact_fe_pass2_drop 0 on mesh 2: fewer
contacts, the same F and d, converged, no intersection. Usage: test_hertz.py [--np N]"""
import os
import sys

import h5py
import numpy as np
from fctest import run, out, Checker, np_from_argv, ROOT

sys.path.insert(0, os.path.join(ROOT, "scripts"))
import hertz  # noqa: E402

NP = np_from_argv()
c = Checker("Hertz np%d" % NP)
P = hertz.params()
G = 9.81
LIMIT = {1: 0.05, 2: 0.03}  # measured +4.10 % and +2.22 % (docs/hertz.md)
opts = ["-options_file", hertz.OPTS, "-quiet", "-gravity", "0,0,%g" % -G, "-output_every", "10"]
err = {}
for level in (1, 2):
    f = out("hertz_%d_np%d.h5" % (level, NP))
    run(opts + hertz.mesh_args(level) + ["-output_file", f], np_=NP)
    m = hertz.measure(f, P)
    with h5py.File(f, "r") as H:
        X = H["bodies/ball/positions"][0]
        T = X[H["bodies/ball/mesh/cells"][:]]
        vol = np.abs(np.einsum("ij,ij->i", T[:, 1] - T[:, 0], np.cross(T[:, 2] - T[:, 0], T[:, 3] - T[:, 0]))).sum() / 6
    weight = float(hertz.read_opts()["ball_density"]) * vol * G
    name = "mesh %d" % level
    c.check(abs(m["F"] / weight - 1) < 1e-3, "%s: at rest, contact force %.2f N = weight %.2f N" % (name, m["F"], weight))
    drift = abs(m["d"] / hertz.measure(f, P, frame=-2)["d"] - 1)
    c.check(drift < 1e-3, "%s: quasi-static, d changes by %.1e over the last 10 steps (kinetic energy %.1e J)" %
            (name, drift, m["kinetic"]))
    c.check(m["residual"] < 1e-8, "%s: contact solver converged, residual %.1e < 1e-8 (%d contacts, two-way)" %
            (name, m["residual"], m["contacts"]))
    c.check(m["intersections"] == 0, "%s: %d intersections" % (name, m["intersections"]))
    dz = np.array(list(m["d_depth"].values()))
    spread = (dz.max() - dz.min()) / m["d"]
    c.check(spread < 0.015, "%s: d from depths 0.2R, 0.5R, R agrees: %s m, spread %.2f %%" %
            (name, " ".join("%.5f" % v for v in dz), 100 * spread))
    err[level] = m["error"]
    m2 = m
    c.check(0 < m["error"] < LIMIT[level], "%s: F %.1f N, d %.5f m (d/R %.2f %%), F_Hertz(d) %.1f N: error %+.2f %% in (0, %g %%)" %
            (name, m["F"], m["d"], 100 * m["d"] / P["R"], m["F_hertz"], 100 * m["error"], 100 * LIMIT[level]))
    if NP > 1:
        f1 = out("hertz_%d_ref.h5" % level)
        run(opts + hertz.mesh_args(level) + ["-output_file", f1])
        m1 = hertz.measure(f1, P)
        dF, dd = abs(m["F"] / m1["F"] - 1), abs(m["d"] / m1["d"] - 1)
        c.check(dF < 1e-6 and dd < 1e-6, "%s: 1 and %d ranks: F rel. diff %.1e, d rel. diff %.1e" % (name, NP, dF, dd))
c.check(err[2] < err[1], "error falls with the mesh: %+.2f %% (mesh 1) -> %+.2f %% (mesh 2)" % (100 * err[1], 100 * err[2]))
# -contact_fe_pass2_drop 0 (docs/options.md): the block's vertices held by the sphere's contacts
# lose their own; measured on mesh 2: 105 contacts instead of 206, the same F and d to 1e-4,
# converged, no intersection (the finest mesh at g = 18, where two-way PGS otherwise stalls at
# 2.4e-8 after 1000 sweeps, converges in 22-24: docs/hertz.md)
f = out("hertz_drop_np%d.h5" % NP)
run(opts + hertz.mesh_args(2) + ["-contact_fe_pass2_drop", "0", "-output_file", f], np_=NP)
m = hertz.measure(f, P)
c.check(m["contacts"] < 0.75 * m2["contacts"], "pass-2 drop: %d contacts (without: %d)" % (m["contacts"], m2["contacts"]))
c.check(m["residual"] < 1e-8 and m["intersections"] == 0, "pass-2 drop: residual %.1e < 1e-8, %d intersections" %
        (m["residual"], m["intersections"]))
c.check(abs(m["error"] - m2["error"]) < 1e-3, "pass-2 drop: error %+.3f %% (without: %+.3f %%)" %
        (100 * m["error"], 100 * m2["error"]))
if NP > 1:
    f1 = out("hertz_drop_ref.h5")
    run(opts + hertz.mesh_args(2) + ["-contact_fe_pass2_drop", "0", "-output_file", f1])
    m1 = hertz.measure(f1, P)
    dF, dd = abs(m["F"] / m1["F"] - 1), abs(m["d"] / m1["d"] - 1)
    c.check(dF < 1e-6 and dd < 1e-6, "pass-2 drop: 1 and %d ranks: F rel. diff %.1e, d rel. diff %.1e" % (NP, dF, dd))
c.done()
