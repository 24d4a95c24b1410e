"""The contact solver split over N ranks (-pgs_ranks split, src/contact/pgs_split.c: Gauss-Seidel
inside each rank's block of contacts, damped Jacobi between blocks) against the replicated
solver on 1 rank, on bare problems run by tools/fclib_solve -dense.
- The problem of an FE scene (the cube dropped on a plane, dumped by -pgs_dump_problem), what the
  split solver is for: it converges (its residual and an independent numpy natural-map residual
  <= 1e-8) and its velocities u = W r + q equal the replicated solver's to 1e-6 ||q|| (u is unique
  where r may not be).
- The 3D problems of tests/data/fclib (multibody stacks, capsules, towers) that the replicated
  solver solves to 1e-8 (frictional problems, whose solutions need not be unique, velocities
  included: only the residual is compared): the Jacobi coupling between blocks does not converge on every one of
  them within 5000 sweeps (docs/contact-solver.md lists which); checked is that the solver
  never claims a convergence it does not have: converged, it meets both residuals and the
  velocities; not converged, it says so and its residual is above 1e-8 by numpy too.
- -pgs_ranks auto (the default; here from 1 row on, -pgs_split_min_rows 1) converges on every one
  of those problems: the split sweeps where they converge, else rank 0 goes on from their iterate
  once they would not converge within -pgs_split_max_it sweeps (the stacks).
- A whole scene with -pgs_ranks split on N ranks ends where the replicated run does (1e-8).
- W_k by block rows (the fast scheme, -fast_wk_rows, the default where the sweeps are split: the
  co-rotational cube resting on its 972 rows): rank 0 forms only its rows (the CongruenceWk flops
  of the log, at most 1/N + 10 % of W_k whole's), and the motion is that of W_k whole to 1e-10,
  also when rank 0 takes over from the split sweeps (-pgs_split_max_it 2: W gathered on rank 0)
  and when the problem is written (-pgs_dump_problem: the same W to 1e-14 of its largest entry);
  a rank whose block is empty (4 contacts on 5 ranks) gives the 1-rank answer (1e-8); with
  -fast_update sweep (the solver does not split) W_k stays whole.
- Newton's sparse LU (-contact_newton_lu sparse) on N ranks gives the 1-rank motion of the 1:1e4 mass-ratio stack.
Usage: test_contact_split.py --np N"""
import os
import subprocess
import sys

import h5py
import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "scripts"))
import bench_contact_solver as B  # noqa: E402
from fctest import ENV, Checker, TMP, final_state, np_from_argv, out, run  # noqa: E402

NP = np_from_argv(2)
c = Checker("contact split np%d" % NP)
EXE = os.environ.get("FCLIB_SOLVE", os.path.join(B.ROOT, "build", "fclib_solve"))
conv = os.path.join(TMP, "fclib")
subprocess.run([sys.executable, os.path.join(B.ROOT, "scripts", "fclib_convert.py"), B.SRC, conv], check=True)


def solve(path, np_, extra):
    sol = path + ".np%d.sol.h5" % np_
    cmd = [EXE, "-problem", path, "-dense", "-pgs_max_it", "5000", "-solution", sol] + extra
    if np_ > 1:
        cmd = ["mpirun", "-n", str(np_), "--oversubscribe"] + cmd
    p = subprocess.run(cmd, capture_output=True, text=True, env=ENV, timeout=600, check=True)
    d = dict(zip(p.stdout.split()[0::2], p.stdout.split()[1::2]))
    with h5py.File(sol, "r") as f:
        return int(d["sweeps"]), float(d["residual"]), f["r"][:], f["u"][:]


dump = out("cube.hdf5")
run(["-options_file", "input/cube_drop.opts", "-time_steps", "45", "-pgs_dump_problem", dump, "-output_file",
     out("cube_dump.h5"), "-quiet"])
# a stack it does not converge on, two it does, a small one (the suite's time: the others are in
# scripts/bench_contact_solver.py's data and take minutes)
SUBSET = ["BoxesStack-local_problem_test.h5", "Capsules-i125-1213.h5", "LMGC_100_PR_PerioBox-i00361-60-03000.h5",
          "FC3D_Example1.h5"]
problems = [dump] + [os.path.join(conv, n) for n in SUBSET]
tested = converged = 0
for path in problems:
    W, q, mu, d = B.load_h5(path)
    name = os.path.basename(path)
    s1, res1, r1, u1 = solve(path, 1, [])
    if res1 > 1e-8:
        print("  %s: the replicated solver does not reach 1e-8 (%.1e): skipped" % (name, res1))
        continue
    sn, resn, rn, un = solve(path, NP, ["-pgs_ranks", "split"])
    e = B.natural_map_error(W, q, mu, rn, d)
    du = np.abs(un - u1).max() / max(np.linalg.norm(q), 1e-300)
    ok = resn <= 1e-8
    if path == dump:
        c.check(ok and e <= 1e-8 and du <= 1e-6,
                "%s (FE cube, %d contacts): split on %d ranks converges in %d sweeps (replicated %d): residual %.1e, "
                "numpy %.1e; velocities differ by %.1e ||q|| <= 1e-6" % (name, len(mu), NP, sn, s1, resn, e, du))
    elif ok:  # frictional problems can have several solutions, velocities included: the residual is the check
        c.check(e <= 1e-8, "%s (%d contacts): split converged in %d sweeps (replicated %d): numpy residual %.1e <= "
                "1e-8 (velocities %.1e ||q|| from the replicated solver's)" % (name, len(mu), sn, s1, e, du))
    else:
        c.check(e > 1e-8, "%s (%d contacts): split not converged after %d sweeps, and says so: residual %.1e, "
                "numpy %.1e > 1e-8" % (name, len(mu), sn, resn, e))
    # -pgs_ranks auto (the default) on any size: split sweeps, then rank 0 from there where they stall
    sa, resa, ra, ua = solve(path, NP, ["-pgs_ranks", "auto", "-pgs_split_min_rows", "1", "-pgs_split_max_it", "200"])
    ea = B.natural_map_error(W, q, mu, ra, d)
    c.check(resa <= 1e-8 and ea <= 1e-8,
            "%s: -pgs_ranks auto on %d ranks converges wherever the replicated solver does (%s): %d sweeps, residual "
            "%.1e, numpy %.1e <= 1e-8" % (name, NP, "split alone converged" if ok and sn <= 200 else "rank 0 took over from the split sweeps", sa, resa, ea))
    if ok and sn <= 200:
        c.check(sa == sn, "%s: auto on %d ranks sweeps as split does when split converges (%d, %d)" % (name, NP, sa, sn))
    tested += 1
    converged += ok
c.check(tested >= 3, "%d problems compared (at least 3), %d converged with split" % (tested, converged))

# a scene: the split solver in the time loop ends where the replicated one does
f1, fn = out("drop_rep.h5"), out("drop_split.h5")
args = ["-options_file", "input/cube_drop.opts", "-time_steps", "40", "-quiet"]
run(args + ["-output_file", f1], np_=NP)
run(args + ["-pgs_ranks", "split", "-output_file", fn], np_=NP)
a, b = h5py.File(f1, "r"), h5py.File(fn, "r")
dx = np.abs(final_state(a) - final_state(b)).max() / np.abs(final_state(a)).max()
c.check(dx <= 1e-8, "cube_drop on %d ranks: -pgs_ranks split vs the default (root at this size), final state rel. diff %.1e <= 1e-8" % (NP, dx))
c.check(b["steps/residual"][:].max() <= 1e-8, "cube_drop split: every step converged (max residual %.1e)" % b["steps/residual"][:].max())

# the Newton step's sparse LU (-contact_newton_lu sparse: MUMPS on each rank's own copy, the problem solved on
# rank 0 and broadcast) on N ranks: the 1-rank motion of the 1:1e4 mass-ratio stack
f1, fn = out("newton_sparse_1.h5"), out("newton_sparse_n.h5")
args = ["-options_file", "input/hard/mass_ratio_1e4.opts", "-time_steps", "30", "-contact_solver", "newton",
        "-contact_newton_lu", "sparse", "-quiet"]
run(args + ["-output_file", f1], np_=1)
run(args + ["-output_file", fn], np_=NP)
a, b = h5py.File(f1, "r"), h5py.File(fn, "r")
dx = max(np.abs(a["bodies/%s/centroid" % k][:] - b["bodies/%s/centroid" % k][:]).max() for k in a["bodies"])
c.check(dx <= 1e-10 and b["steps/residual"][:].max() <= 1e-8,
        "mass ratio 1:1e4, -contact_newton_lu sparse on %d ranks: centroids as on 1 rank to %.1e m (<= 1e-10), every step "
        "converged (max residual %.1e)" % (NP, dx, b["steps/residual"][:].max()))

# W_k by block rows: each rank forms and keeps the rows its split sweeps read
def flops_of(log, event):
    """Rank 0's flops of a log event (-log_view :file:ascii_csv, column FLOP)"""
    import csv
    with open(log) as fl:
        rows = list(csv.reader(fl))
    k = rows[0].index("FLOP")
    for row in rows[1:]:
        if len(row) > k and row[0] == "Main Stage" and row[1] == event and row[2] == "0":
            return float(row[k])
    return -1.0


rest = ["-options_file", "input/cube_rest.opts", "-time_steps", "3", "-constraint_scheme", "fast", "-newton_max_it", "5",
        "-quiet"]
res = {}
for rows in (1, 0):
    for extra, tag in (([], "auto"), (["-pgs_split_max_it", "2", "-pgs_dump_problem", out("rows%d.dump.h5" % rows)], "root")):
        f, log = out("rows%d_%s.h5" % (rows, tag)), out("rows%d_%s.csv" % (rows, tag))
        run(rest + extra + ["-fast_wk_rows", str(rows), "-output_file", f, "-log_view", ":%s:ascii_csv" % log], np_=NP)
        res[rows, tag] = (h5py.File(f, "r"), flops_of(log, "CongruenceWk"))
for tag in ("auto", "root"):
    a, b = res[1, tag][0], res[0, tag][0]
    dx = np.abs(a["bodies/cube/centroid"][:] - b["bodies/cube/centroid"][:]).max() / np.abs(b["bodies/cube/centroid"][:]).max()
    share = res[1, tag][1] / res[0, tag][1]
    c.check(a["steps/constraint_rows"][:].min() >= 900 and share <= 1.0 / NP + 0.1 and dx <= 1e-10,
            "cube resting (%d rows), fast scheme, %s on %d ranks: W_k by rows, rank 0 forms %.2f of W_k whole's flops "
            "(<= 1/%d + 0.1); centroids as with W_k whole to %.1e <= 1e-10 (sweeps %s and %s)" % (
                a["steps/constraint_rows"][:].min(), "split sweeps" if tag == "auto" else "rank 0 taking over after 2 split sweeps",
                NP, share, NP, dx, list(a["steps/pgs_iterations"][:]), list(b["steps/pgs_iterations"][:])))
# with -fast_update sweep the solver calls back after every sweep and does not split: W_k whole
fs_, fw = out("rows_sweep.h5"), out("whole_sweep.h5")
run(rest + ["-fast_update", "sweep", "-output_file", fs_], np_=NP)
run(rest + ["-fast_update", "sweep", "-fast_wk_rows", "0", "-output_file", fw], np_=NP)
a, b = h5py.File(fs_, "r"), h5py.File(fw, "r")
dx = np.abs(a["bodies/cube/centroid"][:] - b["bodies/cube/centroid"][:]).max() / np.abs(b["bodies/cube/centroid"][:]).max()
c.check(a["steps/step"].size == 3 and dx <= 1e-12,
        "-fast_update sweep on %d ranks (%d rows): W_k whole, 3 steps, the motion of -fast_wk_rows 0 to %.1e <= 1e-12 "
        "(MUMPS' parallel sums differ run to run)" % (NP, a["steps/constraint_rows"][:].min(), dx))
# a rank whose block is empty (a plank on the incline: 4 contacts, 12 rows, on 5 ranks, run once):
# no rows to form or hold, the same answer as 1 rank (split from 1 row on; rank 0 takes over where
# block Jacobi stalls on a rigid body)
if NP == 3:
    plank = ["-options_file", "input/incline.opts", "-box_half_extents", "0.2,0.01,0.1", "-time_steps", "20",
             "-constraint_scheme", "fast", "-pgs_split_min_rows", "1", "-quiet"]
    run(plank + ["-output_file", out("plank1.h5")])
    run(plank + ["-output_file", out("plank5.h5")], np_=5)
    p1, p5 = h5py.File(out("plank1.h5"), "r"), h5py.File(out("plank5.h5"), "r")
    dx = np.abs(p1["bodies/box/centroid"][:] - p5["bodies/box/centroid"][:]).max() / np.abs(p1["bodies/box/centroid"][:]).max()
    c.check(p5["steps/contacts"][:].max() == 4 and dx <= 1e-8,
            "plank on the incline, %d contacts on 5 ranks (rank 4's block empty), W_k by rows: centroids as on 1 rank "
            "to %.1e <= 1e-8" % (p5["steps/contacts"][:].max(), dx))
d1, d0 = h5py.File(out("rows1.dump.h5"), "r"), h5py.File(out("rows0.dump.h5"), "r")
x1, x0 = d1["fclib_local/W/x"][:], d0["fclib_local/W/x"][:]
dw = np.abs(x1 - x0).max() / np.abs(x0).max() if x1.shape == x0.shape else np.inf
c.check(dw <= 1e-14, "-pgs_dump_problem with W_k by rows writes W gathered whole: %d entries, as W_k whole's to %.1e" % (
    x1.size, dw))
c.done()
