#!/usr/bin/python3
"""Two-way FE-FE detection, the stall of issue 15: which solvers converge on its contact problem?

Dumps the first contact problem the solver does not converge on in the stiffness-contrast hard
case detected both ways as before issue 15's fix (input/hard/stiffness_contrast.opts -contact_fe_passes 2
-contact_fe_pass2_dormant -1 -contact_facing 0, the step of
docs/hard-cases.md), then solves it with:
- ours (build/fclib_solve): as dumped; frictionless (mu = 0); mu = 1; the contacts in reversed and
  in random order (NNCG on, the default, and off);
- Siconos (python3-siconos, the same problem built from W, q, mu): NSGS, PROX (proximal point
  with a nonsmooth Newton inside), NSN_AC (nonsmooth Newton on Alart-Curnier), ACLMFP (fixed
  point on the De Saxce term, convex cone problems inside), TFP (Tresca fixed point), ADMM,
  VI_FPP, SOCLCP.
It prints iterations, residual and time for each, and the spectrum of W (scripts/spectrum.py's
count of eigenvalues below 1e-8 of the largest).

Two residuals, the same natural map sqrt(sum_i ||r_i - Proj_K(r_i - (u_i + mu_i ||u_T,i|| e_N))||^2)
with two normalizations: ours divides it by ||q|| (FCContactProblemResidual, -pgs_tol), while on
this problem Siconos 4.4's solvers stop on it divided by ||r|| (their dparam[SICONOS_DPARAM_RESIDU]). On this
problem ||r|| / ||q|| is about 270, so a Siconos run "converged to 1e-8" is at about 3e-6 in ours.
Every row gives ours, computed here (numpy) on the solver's r; the Siconos rows also give their
own. PROX and NSN_AC are run a second time with their tolerance scaled by ||q|| / ||r|| (r of the
first run), to see whether they reach 1e-8 in ours.

Usage: /usr/bin/python3 scripts/redundant_solvers.py [--max-it N]   (from the repository root,
after scripts/build.sh; about 3 minutes, most of it PROX asked for 1e-8 in ours)"""
import argparse
import os
import subprocess
import sys
import tempfile
import time

import h5py
import numpy as np
import scipy.sparse as sp
import siconos.numerics as sn

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from bench_contact_solver import natural_map_error  # noqa: E402  (ours, in numpy)

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
BUILD = os.path.join(ROOT, "build")
ENV = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1", OPENBLAS_NUM_THREADS="1")


def load(path):
    with h5py.File(path, "r") as f:
        g = f["fclib_local"]
        w = g["W"]
        n = int(w["m"][0])
        W = sp.csr_matrix((w["x"][:], w["i"][:], w["p"][:]), shape=(n, n))
        return W, g["vectors/q"][:], g["vectors/mu"][:]


def write(path, src, W, q, mu):
    """src's layout with W, q, mu replaced"""
    W = sp.csr_matrix(W)
    with h5py.File(src, "r") as f, h5py.File(path, "w") as g:
        f.copy("fclib_local", g)
        w = g["fclib_local/W"]
        for k in ("p", "i", "x"):
            del w[k]
        w["p"], w["i"], w["x"] = W.indptr.astype(np.int64), W.indices.astype(np.int64), W.data
        g["fclib_local/vectors/q"][:] = q
        g["fclib_local/vectors/mu"][:] = mu


def ours(path, max_it, extra=()):
    t = time.time()
    p = subprocess.run([os.path.join(BUILD, "fclib_solve"), "-problem", path, "-pgs_max_it", str(max_it)] + list(extra),
                       cwd=ROOT, env=ENV, capture_output=True, text=True, check=True)
    words = p.stdout.split()
    return int(words[words.index("sweeps") + 1]), float(words[words.index("residual") + 1]), time.time() - t


def siconos(W, q, mu, name, max_it, tol=1e-8):
    n = len(q)
    p = sn.FrictionContactProblem(3, n // 3, W.toarray(), q, mu)
    so = sn.SolverOptions(getattr(sn, "SICONOS_FRICTION_3D_" + name))
    so.iparam[sn.SICONOS_IPARAM_MAX_ITER] = max_it
    so.dparam[sn.SICONOS_DPARAM_TOL] = tol
    r, u = np.zeros(n), np.zeros(n)
    t = time.time()
    info = sn.fc3d_driver(p, r, u, so)
    return (info, so.iparam[sn.SICONOS_IPARAM_ITER_DONE], so.dparam[sn.SICONOS_DPARAM_RESIDU], time.time() - t,
            natural_map_error(W.toarray(), q, mu, r, 3), np.linalg.norm(r))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--max-it", type=int, default=100000, help="sweeps for ours and Siconos' NSGS")
    a = ap.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        prob = os.path.join(tmp, "p.hdf5")
        subprocess.run([os.path.join(BUILD, "fecontact"), "-options_file", "input/hard/stiffness_contrast.opts",
                        "-contact_fe_passes", "2", "-time_steps", "12", "-pgs_dump_problem", prob,
                        # every contact of both passes, the nearest triangle whatever its side: the
                        # detection of before issue 15's fix, on which PGS stalls (docs/hard-cases.md)
                        "-contact_fe_pass2_dormant", "-1", "-contact_facing", "0",
                        "-pgs_dump_unconverged", "-output_file", os.path.join(tmp, "sc.h5"), "-quiet"],
                       cwd=ROOT, env=ENV, check=True, capture_output=True)
        W, q, mu = load(prob)
        nc = len(q) // 3
        ev = np.linalg.eigvalsh(0.5 * (W + W.T).toarray())
        print("problem: %d contacts, %d rows, mu = %g; W: %d of %d eigenvalues below 1e-8 of the largest (%.3g)\n"
              % (nc, len(q), mu[0], (ev < 1e-8 * ev[-1]).sum(), len(q), ev[-1]))
        print("| solver | variant | iterations | residual, ours (/ ||q||) | Siconos' own (/ ||r||) | time (s) |")
        print("|---|---|---:|---:|---:|---:|")
        rows = [("as dumped", prob, ())]
        for label, m in (("frictionless (mu = 0)", 0.0), ("mu = 1", 1.0)):
            f = os.path.join(tmp, "mu%g.hdf5" % m)
            write(f, prob, W, q, np.full(nc, m))
            rows.append((label, f, ()))
        for label, perm in (("reversed order", np.arange(nc)[::-1]),
                            ("random order (seed 1)", np.random.RandomState(1).permutation(nc))):
            P = np.concatenate([[3 * c, 3 * c + 1, 3 * c + 2] for c in perm])
            f = os.path.join(tmp, label.split()[0] + ".hdf5")
            write(f, prob, W[P][:, P], q[P], mu[perm])
            rows.append((label, f, ()))
            rows.append((label + ", no NNCG", f, ("-pgs_acceleration", "none")))
        for label, f, extra in rows:
            s, r, t = ours(f, a.max_it, extra)
            print("| ours (PGS + NNCG) | %s | %d sweeps | %.1e | | %.2f |" % (label, s, r, t), flush=True)
        qn = np.linalg.norm(q)
        for name in ("NSGS", "PROX", "NSN_AC", "ACLMFP", "TFP", "ADMM", "VI_FPP", "SOCLCP"):
            max_it = a.max_it if name == "NSGS" else 2000
            info, it, res, t, ours_res, rn = siconos(W, q, mu, name, max_it)
            print("| Siconos %s | as dumped, tol 1e-8%s | %d | %.1e | %.1e | %.2f |"
                  % (name, "" if info == 0 else " (its own test: not converged)", it, ours_res, res, t), flush=True)
            if name in ("PROX", "NSN_AC"):
                tol = 1e-8 * qn / rn
                info, it, res, t, ours_res, rn = siconos(W, q, mu, name, 300, tol)
                print("| Siconos %s | tol %.1e (1e-8 x ||q|| / ||r||)%s | %d | %.1e | %.1e | %.2f |"
                      % (name, tol, "" if info == 0 else " (its own test: not converged)", it, ours_res, res, t),
                      flush=True)


if __name__ == "__main__":
    main()
