#!/usr/bin/python3
"""Our contact solvers against Siconos' on the problems of tests/data/fclib (or $FCLIB_DIR), to a
tolerance (default 1e-8). Two tables, from one run:

nsgs: our PGS (exact local Coulomb solve) against Siconos NSGS: sweeps, residual and time. Both
solvers' residuals in the table are the natural-map error divided by ||q|| (ours, and Siconos 4.4's
fc3d_compute_error with that norm), computed here (numpy) on each solver's r. Siconos' solvers stop
on their own measure, which is not always that one (on the two-way FE-FE problem of
scripts/redundant_solvers.py it is the same error over ||r||): it is the column "Siconos' own".
Siconos' fc3d_compute_error evaluated on our solution is an independent check (3D problems).

solvers: -contact_solver pgs, newton (sweeps, then nonsmooth Newton on the Alart-Curnier function,
src/contact/newton.c) and auto (the default: the sweeps, then Newton where their rate says they will
not converge within the budget, the default 1000) against Siconos' NSGS and nonsmooth Newton solvers
(FC3D_NSN_AC, FC3D_NSN_FB; 3D problems in Siconos' .dat format only: Siconos 4.4 cannot read FCLIB
.hdf5). Times are the best of --repeat solves from r = 0 (ours: fclib_solve -repeat); iterations:
sweeps for PGS and NSGS, sweeps and Newton steps for ours, Newton steps for Siconos' NSN. PGS and
newton run with a budget of --max-it iterations, Siconos' NSN with 1000 Newton steps. A solver that
does not reach the tolerance is marked "no".

Usage: scripts/bench_contact_solver.py [--tol 1e-8] [--max-it 100000] [--repeat 3] [--tables nsgs,solvers]
                                       [--markdown FILE] [--json FILE]
--markdown FILE replaces the blocks between FILE's "<!-- begin/end bench_contact_solver.py -->"
markers (the nsgs table; docs/contact-solver.md: the section "Against Siconos NSGS") and
"<!-- begin/end bench_contact_solver.py solvers -->" markers (the section "Nonsmooth Newton") and
keeps the rest of the page."""
import argparse
import glob
import json
import os
import subprocess
import sys
import time

import h5py
import numpy as np
import siconos.numerics as sn

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SRC = os.environ.get("FCLIB_DIR", os.path.join(ROOT, "tests", "data", "fclib"))
if not os.path.isdir(SRC):
    sys.exit("bench_contact_solver: no fclib problems in %s (tests/data/fclib of the repository, or set FCLIB_DIR)" % SRC)


def siconos_solve(path, tol, max_it):
    p = sn.frictionContact_new_from_filename(path)
    n = p.dimension * p.numberOfContacts
    r, u = np.zeros(n), np.zeros(n)
    if p.dimension == 3:
        so = sn.SolverOptions(sn.SICONOS_FRICTION_3D_NSGS)
        solve = sn.fc3d_nsgs
    else:
        so = sn.SolverOptions(sn.SICONOS_FRICTION_2D_NSGS)
        solve = sn.fc2d_driver
    so.iparam[sn.SICONOS_IPARAM_MAX_ITER] = max_it
    so.dparam[sn.SICONOS_DPARAM_TOL] = tol
    t = time.perf_counter()
    info = solve(p, r, u, so)
    t = time.perf_counter() - t
    return dict(info=int(info), sweeps=int(so.iparam[sn.SICONOS_IPARAM_ITER_DONE]), residual=float(so.dparam[sn.SICONOS_DPARAM_RESIDU]), time=t, r=r, problem=p)


def ours(h5, tol, max_it, sol):
    exe = os.environ.get("FCLIB_SOLVE", os.path.join(ROOT, "build", "fclib_solve"))  # ctest sets it
    out = subprocess.run([exe, "-problem", h5, "-pgs_tol", str(tol), "-pgs_max_it", str(max_it), "-solution", sol],
                         capture_output=True, text=True, timeout=600, check=True).stdout.split()
    d = dict(zip(out[0::2], out[1::2]))
    with h5py.File(sol, "r") as f:
        r = f["r"][:]
    return dict(sweeps=int(d["sweeps"]), residual=float(d["residual"]), time=float(d["time"]), converged=d["converged"] == "1", r=r)


def natural_map_error(W, q, mu, r, d):
    """numpy re-implementation (independent of the C code): sqrt(sum ||e_i||^2) / ||q||"""
    u = W @ r + q
    e2 = 0.0
    for i in range(len(mu)):
        ri, ui = r[d * i:d * i + d], u[d * i:d * i + d]
        ut = np.linalg.norm(ui[1:])
        x = ri - ui - np.r_[mu[i] * ut, np.zeros(d - 1)]
        xt = np.linalg.norm(x[1:])
        if xt <= mu[i] * x[0]:
            pr = x
        elif mu[i] * xt <= -x[0]:
            pr = np.zeros(d)
        else:
            sn_ = (x[0] + mu[i] * xt) / (1 + mu[i] ** 2)
            pr = np.r_[sn_, mu[i] * sn_ * x[1:] / xt]
        e2 += np.sum((ri - pr) ** 2)
    return np.sqrt(e2) / max(np.linalg.norm(q), np.finfo(float).eps)


def load_h5(path):
    with h5py.File(path, "r") as f:
        g = f["fclib_local"]
        n, p, i, x = g["W/m"][0], g["W/p"][:], g["W/i"][:], g["W/x"][:]
        W = np.zeros((n, n))
        for k in range(n):
            W[k, i[p[k]:p[k + 1]]] = x[p[k]:p[k + 1]]
        return W, g["vectors/q"][:], g["vectors/mu"][:], int(np.ravel(g["spacedim"][()])[0])


def siconos_error_of(problem, r, tol):
    if problem.dimension != 3:
        return float("nan")
    n = r.size
    u = np.zeros(n)
    nq = np.linalg.norm(problem.q)
    info, err = sn.fc3d_compute_error(problem, r.copy(), u, tol, None, nq)
    return err


BEGIN, END = "<!-- begin bench_contact_solver.py -->", "<!-- end bench_contact_solver.py -->"
BEGIN_S, END_S = "<!-- begin bench_contact_solver.py solvers -->", "<!-- end bench_contact_solver.py solvers -->"


def write_block(path, block, begin=BEGIN, end=END):
    """Writes the measured block between the page's markers begin and end and leaves the rest of the
    page (the hand-written sections) as it is; a new page gets a title and both tables' markers"""
    if not os.path.exists(path):
        with open(path, "w") as f:
            f.write("# Contact solvers against Siconos\n\n%s\n%s\n\n%s\n%s\n" % (BEGIN_S, END_S, BEGIN, END))
    with open(path) as f:
        text = f.read()
    i, j = text.find(begin), text.find(end)
    if i < 0 or j < i:
        sys.exit("%s has no '%s' ... '%s' block to replace: add the markers where the table goes" % (path, begin, end))
    text = text[:i + len(begin)] + "\n" + block + text[j:]
    with open(path, "w") as f:
        f.write(text)


SICONOS = [("NSGS", sn.SICONOS_FRICTION_3D_NSGS, sn.fc3d_nsgs),
           ("NSN_AC", sn.SICONOS_FRICTION_3D_NSN_AC, sn.fc3d_nonsmooth_Newton_AlartCurnier),
           ("NSN_FB", sn.SICONOS_FRICTION_3D_NSN_FB, sn.fc3d_nonsmooth_Newton_FischerBurmeister)]


def siconos_best(dat, sid, fn, tol, max_it, repeat):
    """Siconos' 3D solver sid: iterations, best time of repeat solves from r = 0, converged"""
    best, its, ok = None, 0, False
    for _ in range(repeat):
        p = sn.frictionContact_new_from_filename(dat)
        n = p.dimension * p.numberOfContacts
        r, u = np.zeros(n), np.zeros(n)
        so = sn.SolverOptions(sid)
        so.iparam[sn.SICONOS_IPARAM_MAX_ITER] = max_it if sid == sn.SICONOS_FRICTION_3D_NSGS else 1000
        so.dparam[sn.SICONOS_DPARAM_TOL] = tol
        t = time.perf_counter()
        info = fn(p, r, u, so)
        t = time.perf_counter() - t
        best = t if best is None else min(best, t)
        its, ok = int(so.iparam[sn.SICONOS_IPARAM_ITER_DONE]), info == 0 and so.dparam[sn.SICONOS_DPARAM_RESIDU] <= tol
    return its, best, ok


def ours_best(h5, solver, tol, max_it, repeat):
    """-contact_solver solver: iterations, best time of repeat solves from r = 0, converged, contacts, rows"""
    exe = os.environ.get("FCLIB_SOLVE", os.path.join(ROOT, "build", "fclib_solve"))
    out = subprocess.run([exe, "-problem", h5, "-pgs_tol", str(tol), "-pgs_max_it", str(max_it), "-contact_solver", solver,
                          "-contact_newton_max_it", "1000", "-repeat", str(repeat)],
                         capture_output=True, text=True, timeout=900, check=True).stdout.split()
    d = dict(zip(out[0::2], out[1::2]))
    return int(d["sweeps"]), float(d["time"]), d["converged"] == "1", int(d["contacts"]), int(d["rows"])


def cell(its, t, ok):
    return "%d, %.4f s%s" % (its, t, "" if ok else " (no)")


HDR_S = ("| problem | contacts | rows | ours: PGS | ours: newton | newton / PGS time | ours: auto, budget 1000 | Siconos NSGS | "
         "Siconos NSN_AC | Siconos NSN_FB | ours best / Siconos best |")


def solvers_table(a, conv):
    """The solvers table: each of our solvers and Siconos' three on every problem; the last column is the
    time of our fastest converged solver over Siconos' fastest converged one"""
    rows = []
    print(HDR_S)
    print("|---|---:|---:|---|---|---:|---|---|---|---|---:|")
    for h5 in sorted(glob.glob(os.path.join(conv, "*.h5"))):
        if h5.endswith(".sol.h5"):
            continue
        name = os.path.basename(h5)[:-3]
        ip, tp, okp, nc, n = ours_best(h5, "pgs", a.tol, a.max_it, a.repeat)
        inn, tn, okn, _, _ = ours_best(h5, "newton", a.tol, a.max_it, a.repeat)
        ia, ta, oka, _, _ = ours_best(h5, "auto", a.tol, 1000, a.repeat)
        dat = os.path.join(SRC, name + ".dat")
        cols, sic = [], []
        if os.path.exists(dat) and n == 3 * nc:
            for _, sid, fn in SICONOS:
                its, t, ok = siconos_best(dat, sid, fn, a.tol, a.max_it, a.repeat)
                cols.append(cell(its, t, ok))
                if ok:
                    sic.append(t)
        else:
            cols = ["-"] * 3
        mine = [t for t, ok in [(tp, okp), (tn, okn), (ta, oka)] if ok]
        if sic and mine:
            best = "%.2f" % (min(mine) / min(sic)) if min(sic) >= 1e-3 else "(below 1 ms)"
        elif not sic:
            best = "-" if cols[0] == "-" else "Siconos does not converge"
        else:
            best = "ours do not converge"
        line = "| %s | %d | %d | %s | %s | %.2f | %s | %s | %s |" % (name, nc, n, cell(ip, tp, okp), cell(inn, tn, okn),
                                                                tn / max(tp, 1e-9), cell(ia, ta, oka), " | ".join(cols), best)
        print(line, flush=True)
        rows.append(line)
    return rows


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--tol", type=float, default=1e-8)
    ap.add_argument("--max-it", type=int, default=100000)
    ap.add_argument("--repeat", type=int, default=3, help="solves per solver in the solvers table (the best time)")
    ap.add_argument("--tables", default="nsgs,solvers", help="which tables: nsgs, solvers or both")
    ap.add_argument("--markdown")
    ap.add_argument("--json")
    a = ap.parse_args()
    tables = a.tables.split(",")
    for t in tables:
        if t not in ("nsgs", "solvers"):
            sys.exit("bench_contact_solver: --tables takes nsgs and/or solvers, not '%s'" % t)
    conv = os.path.join(ROOT, "build", "fclib")
    subprocess.run([sys.executable, os.path.join(ROOT, "scripts", "fclib_convert.py"), SRC, conv], check=True)
    if "solvers" in tables:
        srows = solvers_table(a, conv)
        if a.markdown:
            import platform
            block = ("Command: `scripts/bench_contact_solver.py --tol %g --max-it %d --repeat %d --tables solvers --markdown %s` (%s, %d cores, "
                     "%s; Siconos 4.4)\n\n" % (a.tol, a.max_it, a.repeat, a.markdown, platform.node(), os.cpu_count(),
                                               time.strftime("%Y-%m-%d"))
                     + HDR_S + "\n|---|---:|---:|---|---|---:|---|---|---|---|---:|\n" + "\n".join(srows) + "\n")
            write_block(a.markdown, block, BEGIN_S, END_S)
    if "nsgs" not in tables:
        return
    rows, results = [], []
    hdr = ("| problem | contacts | dim | Siconos sweeps | Siconos residual | Siconos' own | Siconos time (s) | our sweeps | "
           "our residual | Siconos error of our r | our time (s) | ms per sweep, Siconos / ours | time, ours / Siconos |")
    print(hdr)
    print("|" + "---|" * 13)
    for dat in sorted(glob.glob(os.path.join(SRC, "*.dat"))):
        name = os.path.basename(dat)[:-4]
        s = siconos_solve(dat, a.tol, a.max_it)
        o = ours(os.path.join(conv, name + ".h5"), a.tol, a.max_it, os.path.join(conv, name + ".sol.h5"))
        e = siconos_error_of(s["problem"], o["r"], a.tol)
        W, q, mu, d = load_h5(os.path.join(conv, name + ".h5"))
        e_np = natural_map_error(W, q, mu, o["r"], d)
        s_np = natural_map_error(W, q, mu, s["r"], d)
        nc = s["problem"].numberOfContacts
        per = "%.4f / %.4f" % (1e3 * s["time"] / max(s["sweeps"], 1), 1e3 * o["time"] / max(o["sweeps"], 1))
        ratio = "%.2f" % (o["time"] / s["time"]) if s["time"] >= 1e-3 else "(below 1 ms)"
        line = "| %s | %d | %d | %d | %.2e | %.2e | %.3f | %d | %.2e | %.2e | %.3f | %s | %s |" % (
            name, nc, s["problem"].dimension, s["sweeps"], s_np, s["residual"], s["time"], o["sweeps"], o["residual"], e,
            o["time"], per, ratio)
        print(line, flush=True)
        rows.append(line)
        results.append(dict(name=name, contacts=nc, dim=s["problem"].dimension, siconos_sweeps=s["sweeps"], siconos_residual=s["residual"],
                            siconos_time=s["time"], siconos_info=s["info"], our_sweeps=o["sweeps"], our_residual=o["residual"],
                            our_converged=o["converged"], siconos_error_of_ours=e, numpy_error_of_ours=e_np,
                            numpy_error_of_siconos=s_np, our_time=o["time"], our_r=list(o["r"][:3]), siconos_r=list(s["r"][:3])))
    if a.json:
        with open(a.json, "w") as f:
            json.dump(results, f, indent=1)
    if a.markdown:
        import platform
        block = ("Command: `scripts/bench_contact_solver.py --tol %g --max-it %d --markdown %s`\n\n" % (a.tol, a.max_it, a.markdown)
                 + "Machine: %s, %d cores, %s. Siconos %s (Debian python3-siconos), fc3d_nsgs / fc2d_nsgs with default "
                 "local solvers; ours: `build/fclib_solve` (projected Gauss-Seidel with the exact local solve of "
                 "src/contact/local.c, NNCG acceleration, the default). Both residuals: natural-map error "
                 "sqrt(sum ||e_i||^2) / ||q||, computed on each solver's r; 'Siconos' own' is the residual Siconos stops on "
                 "(its dparam[1]); the column 'Siconos error of our r' is Siconos' own fc3d_compute_error evaluated on our "
                 "solution (3D only). Times are each solver's wall time of the whole solve (set-up included), so the time per "
                 "sweep of a problem solved in one or two sweeps is mostly set-up. One run, same machine.\n\n"
                 % (platform.node(), os.cpu_count(), time.strftime("%Y-%m-%d"), "4.4")
                 + hdr + "\n|" + "---|" * 13 + "\n" + "\n".join(rows) + "\n")
        write_block(a.markdown, block)
        print("wrote", a.markdown)


if __name__ == "__main__":
    main()
