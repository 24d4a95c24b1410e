#!/usr/bin/python3
"""-contact_solver newton (sweeps, then nonsmooth Newton on the Alart-Curnier function,
src/contact/newton.c) against our PGS (NNCG) and against Siconos' NSGS and nonsmooth Newton
solvers (FC3D_NSN_AC, FC3D_NSN_FB; 3D problems in Siconos' .dat format only: Siconos 4.4 cannot
read FCLIB .hdf5) on the problems of tests/data/fclib (or $FCLIB_DIR), to a tolerance (default
1e-8). Our times are fclib_solve's best of --repeat solves from r = 0; Siconos' the best of
--repeat too. Iterations: sweeps for PGS and NSGS, sweeps and Newton steps for ours, Newton steps
for Siconos' NSN. A solver that does not reach the tolerance is marked "no". PGS and newton run
with a budget of 100000 iterations; auto (the default: the sweeps, then Newton where their rate
says they will not converge within the budget) with the default budget, 1000.
  /usr/bin/python3 scripts/bench_newton.py [--tol 1e-8] [--repeat 3]"""
import argparse
import glob
import os
import subprocess
import sys
import time

import numpy as np
import siconos.numerics as sn

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SRC = os.environ.get("FCLIB_DIR", os.path.join(ROOT, "tests", "data", "fclib"))
ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
ap.add_argument("--tol", type=float, default=1e-8)
ap.add_argument("--repeat", type=int, default=3)
ap.add_argument("--exe", default=os.path.join(ROOT, "build", "fclib_solve"))
a = ap.parse_args()
conv = os.path.join(ROOT, "build", "fclib")
subprocess.run([sys.executable, os.path.join(ROOT, "scripts", "fclib_convert.py"), SRC, conv], check=True)


def ours(h5, solver, max_it=100000):
    out = subprocess.run([a.exe, "-problem", h5, "-pgs_tol", str(a.tol), "-pgs_max_it", str(max_it), "-contact_solver", solver,
                          "-contact_newton_max_it", "1000", "-repeat", str(a.repeat)],
                         capture_output=True, text=True, timeout=900, check=True).stdout.split()
    d = dict(zip(out[0::2], out[1::2]))
    return int(d["sweeps"]), float(d["time"]), d["converged"] == "1", int(d["contacts"]), int(d["rows"])


SICONOS = [("NSGS", sn.SICONOS_FRICTION_3D_NSGS, sn.fc3d_nsgs),
           ("NSN_AC", sn.SICONOS_FRICTION_3D_NSN_AC, sn.fc3d_nonsmooth_Newton_AlartCurnier),
           ("NSN_FB", sn.SICONOS_FRICTION_3D_NSN_FB, sn.fc3d_nonsmooth_Newton_FischerBurmeister)]


def siconos(dat, sid, fn):
    best, its, ok = None, 0, False
    for _ in range(a.repeat):
        p = sn.frictionContact_new_from_filename(dat)
        n = p.dimension * p.numberOfContacts
        r, u = np.zeros(n), np.zeros(n)
        so = sn.SolverOptions(sid)
        so.iparam[sn.SICONOS_IPARAM_MAX_ITER] = 100000 if sid == sn.SICONOS_FRICTION_3D_NSGS else 1000
        so.dparam[sn.SICONOS_DPARAM_TOL] = a.tol
        t = time.perf_counter()
        info = fn(p, r, u, so)
        t = time.perf_counter() - t
        best = t if best is None else min(best, t)
        its, ok = int(so.iparam[sn.SICONOS_IPARAM_ITER_DONE]), info == 0 and so.dparam[sn.SICONOS_DPARAM_RESIDU] <= a.tol
    return its, best, ok


def cell(its, t, ok):
    return "%d, %.4f s%s" % (its, t, "" if ok else " (no)")


print("| problem | contacts | rows | ours: PGS | ours: newton | newton / PGS time | ours: auto, budget 1000 | Siconos NSGS | Siconos NSN_AC | Siconos NSN_FB |")
print("|---|---:|---:|---|---|---:|---|---|---|---|")
for h5 in sorted(glob.glob(os.path.join(conv, "*.h5"))):
    if h5.endswith(".sol.h5"):
        continue
    name = os.path.basename(h5)[:-3]
    ip, tp, okp, nc, n = ours(h5, "pgs")
    inn, tn, okn, _, _ = ours(h5, "newton")
    ia, ta, oka, _, _ = ours(h5, "auto", 1000)
    dat = os.path.join(SRC, name + ".dat")
    cols = []
    if os.path.exists(dat) and n == 3 * nc:
        for _, sid, fn in SICONOS:
            cols.append(cell(*siconos(dat, sid, fn)))
    else:
        cols = ["-"] * 3
    print("| %s | %d | %d | %s | %s | %.2f | %s | %s |" % (name, nc, n, cell(ip, tp, okp), cell(inn, tn, okn), tn / max(tp, 1e-9),
                                                      cell(ia, ta, oka), " | ".join(cols)), flush=True)
