"""Contact solver on bare problems (W, q, mu):
- the one-contact exact case (docs/method.md, section 5, FrictionContact3D_1c) to 1e-10: the given
  solution (7 digits), Siconos NSGS's answer, and the sliding conditions u_n = 0,
  r_T = -mu r_n u_T / ||u_T|| hold;
- every problem of tests/data/fclib (its README.md: origin, licence; $FCLIB_DIR overrides it)
  that Siconos NSGS solves to 1e-8 is solved by our PGS to 1e-8, measured three ways: our
  residual, Siconos' fc3d_compute_error on our r (3D), and an independent numpy natural-map
  residual (all divided by ||q||);
- FCLIB .hdf5 problems (which Siconos 4.4 cannot read) run without crash or hang;
- -contact_solver newton (sweeps, then nonsmooth Newton on the Alart-Curnier function,
  src/contact/newton.c) solves every problem our PGS solves to 1e-8, to 1e-8 by the numpy
  residual, and BoxesStack1 (5621 PGS sweeps) in fewer than 100 sweeps and Newton steps.
The side-by-side timing table is scripts/bench_contact_solver.py, not a test."""
import os
import subprocess
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "scripts"))
import bench_contact_solver as B  # noqa: E402
from fctest import Checker, TMP  # noqa: E402

c = Checker("contact solver")
conv = os.path.join(TMP, "fclib")
subprocess.run([sys.executable, os.path.join(B.ROOT, "scripts", "fclib_convert.py"), B.SRC, conv], check=True)
tol, max_it = 1e-8, 100000

# one contact, exact
s = B.siconos_solve(os.path.join(B.SRC, "FrictionContact3D_1c.dat"), 1e-14, 1000)
o = B.ours(os.path.join(conv, "FrictionContact3D_1c.h5"), 1e-14, 1000, os.path.join(TMP, "1c.sol.h5"))
r = o["r"]
W = np.array([[15, -1, -2], [-1, 14, 1], [-2, 1, 16.0]])
u = W @ r + np.array([-1, 2, 3.0])
c.check(o["residual"] < 1e-10, "1 contact: residual %.2e < 1e-10" % o["residual"])
c.check(np.abs(r - [0.0656957, -0.0036786, -0.0054431]).max() < 5e-8, "1 contact: r = %s matches the published 7 digits" % r)
c.check(np.abs(r - s["r"]).max() < 1e-10 * np.abs(r).max(), "1 contact: r matches Siconos to %.1e" % (np.abs(r - s["r"]).max() / np.abs(r).max()))
ut = u[1:]
c.check(abs(u[0]) < 1e-12 and np.abs(r[1:] + 0.1 * r[0] * ut / np.linalg.norm(ut)).max() < 1e-12,
        "1 contact: sliding conditions u_n = %.1e, r_T = -mu r_n u_T/|u_T| (u = %s)" % (u[0], u))

for dat in sorted(B.glob.glob(os.path.join(B.SRC, "*.dat"))):
    name = os.path.basename(dat)[:-4]
    s = B.siconos_solve(dat, tol, max_it)
    h5 = os.path.join(conv, name + ".h5")
    o = B.ours(h5, tol, max_it, os.path.join(TMP, name + ".sol.h5"))
    Wd, q, mu, d = B.load_h5(h5)
    e_np = B.natural_map_error(Wd, q, mu, o["r"], d)
    if s["residual"] <= tol:
        e_s = B.siconos_error_of(s["problem"], o["r"], tol)
        ok = o["converged"] and o["residual"] <= tol and e_np <= tol * (1 + 1e-6) and (np.isnan(e_s) or e_s <= tol * (1 + 1e-6))
        c.check(ok, "%s (Siconos %.2e in %d sweeps): ours %.2e in %d sweeps, numpy %.2e, Siconos' measure %.2e"
                % (name, s["residual"], s["sweeps"], o["residual"], o["sweeps"], e_np, e_s))
    else:
        c.check(abs(e_np - o["residual"]) <= 1e-6 * o["residual"], "%s (Siconos stalls at %.2e): ours ran, %.2e after %d sweeps, no crash"
                % (name, s["residual"], o["residual"], o["sweeps"]))
for h5 in sorted(B.glob.glob(os.path.join(B.SRC, "*.hdf5"))):
    name = os.path.basename(h5)[:-5]
    o = B.ours(os.path.join(conv, name + ".h5"), tol, 20000, os.path.join(TMP, name + ".sol.h5"))
    Wd, q, mu, d = B.load_h5(os.path.join(conv, name + ".h5"))
    e_np = B.natural_map_error(Wd, q, mu, o["r"], d)
    # agreement to 1e-6 relative, or to 1e-14 absolute: the round-off of evaluating a residual that
    # Newton (-contact_solver auto) takes to ~1e-14
    c.check(abs(e_np - o["residual"]) <= 1e-6 * o["residual"] + 1e-14, "%s (FCLIB file): %.2e after %d sweeps (converged %s), numpy agrees (%.2e)"
            % (name, o["residual"], o["sweeps"], o["converged"], e_np))

# -contact_solver newton on every problem PGS solves
def newton(h5, sol, extra=()):
    exe = os.environ.get("FCLIB_SOLVE", os.path.join(B.ROOT, "build", "fclib_solve"))
    res = subprocess.run([exe, "-problem", h5, "-pgs_tol", str(tol), "-pgs_max_it", str(max_it), "-contact_solver", "newton",
                          "-contact_newton_max_it", "1000", "-solution", sol] + list(extra), capture_output=True, text=True,
                         timeout=600, check=True)
    out = [w for line in res.stdout.splitlines() if line.startswith("problem") for w in line.split()]
    d = dict(zip(out[0::2], out[1::2]))
    with B.h5py.File(sol, "r") as f:
        r = f["r"][:]
    lu = "sparse" if "sparse LU" in res.stdout else "dense" if "dense LU" in res.stdout else None
    return dict(sweeps=int(d["sweeps"]), residual=float(d["residual"]), converged=d["converged"] == "1", r=r, lu=lu)


for h5 in sorted(B.glob.glob(os.path.join(conv, "*.h5"))):
    name = os.path.basename(h5)[:-3]
    p = B.ours(h5, tol, max_it, os.path.join(TMP, name + ".pgs.h5"))
    if not p["converged"]:
        continue
    o = newton(h5, os.path.join(TMP, name + ".newton.h5"))
    Wd, q, mu, d = B.load_h5(h5)
    e_np = B.natural_map_error(Wd, q, mu, o["r"], d)
    ok = o["converged"] and e_np <= tol * (1 + 1e-6)
    if name.startswith("BoxesStack1"):
        ok = ok and o["sweeps"] < 100
    c.check(ok, "%s, -contact_solver newton: %.2e (numpy %.2e) in %d sweeps and Newton steps (PGS: %d sweeps)" % (
        name, o["residual"], e_np, o["sweeps"], p["sweeps"]))
# the Newton step's two factorizations (-contact_newton_lu, src/contact/newton_jacobian.c): auto picks MUMPS'
# sparse LU on a large block-sparse W and LAPACK's dense LU on a small one; each converges on both kinds
for name, want in (("Capsules-i101-404", "sparse"), ("FrictionContactProblem00727", "sparse"), ("OneObject-i1028-138.hdf5", "dense")):
    h5 = os.path.join(conv, name + ".h5")
    Wd, q, mu, d = B.load_h5(h5)
    a = newton(h5, os.path.join(TMP, name + ".lu.h5"), ["-info", ":sys"])
    c.check(a["lu"] == want, "%s: -contact_newton_lu auto factors H with the %s LU (it chose %s)" % (name, want, a["lu"]))
    for lu in ("dense", "sparse"):
        o = newton(h5, os.path.join(TMP, name + "." + lu + ".h5"), ["-contact_newton_lu", lu])
        e_np = B.natural_map_error(Wd, q, mu, o["r"], d)
        c.check(o["converged"] and e_np <= tol * (1 + 1e-6), "%s, -contact_newton_lu %s: %.2e (numpy %.2e) in %d sweeps and "
                "Newton steps" % (name, lu, o["residual"], e_np, o["sweeps"]))
c.done()
