"""The contact phase distributed over the ranks (issue 37) against the replicated one, on the same
ranks, forced by the thresholds:
- distributed: the fast scheme's W_H held by block rows (-fast_distributed_contacts 0), the
  condensed builder's Sigma and C by block-cyclic columns from MUMPS and ScaLAPACK
  (-compliance_condensed_inverse distributed) and its W_b by the rows of each rank;
- replicated: W_H whole on every rank (-fast_distributed_contacts 1000000), Sigma and C on rank 0
  (-compliance_condensed_inverse host).
Checked, with the contact solver converged tightly (-pgs_tol 1e-13) and its sweeps split the same
way in both (-pgs_ranks split):
- an FE cube dropped on a kinematic plane (fast scheme): the contact forces of every step equal
  the replicated ones to 1e-10 of the largest, and the final positions to 1e-10 of the
  displacement; per rank, W_H, W_b and Sigma / C (/memory) are at most 1.2 / N of their replicated
  size (W_H and W_b whole on every rank there, Sigma on rank 0); /memory_phases has a row per rank,
  no negative growth, and the factorization's growth;
- a rigid box on an FE slab (fast scheme; the rigid body's part of W_H by rows too), frictionless:
  the forces to 1e-10 (with the scene's mu = 0.3 the split sweeps stop at -pgs_max_it short of
  1e-13 on one step where the box sticks, and what they leave there is not the same to better than
  1e-2 from any perturbation at round-off, the replicated path run twice included: no reference);
- the standard scheme, whose W stays whole, with C distributed: the forces to 1e-10;
- bad thresholds: an error naming the option.
Usage: test_distributed.py --np N (N >= 2)"""
import h5py
import numpy as np

from fctest import Checker, np_from_argv, out, run, sorted_positions

NP = np_from_argv(3)
c = Checker("distributed np%d" % NP)
TIGHT = ["-pgs_ranks", "split", "-pgs_tol", "1e-13", "-pgs_max_it", "3000", "-quiet"]
REP = ["-fast_distributed_contacts", "1000000", "-compliance_condensed_inverse", "host"]
DIST = ["-fast_distributed_contacts", "0", "-compliance_condensed_inverse", "distributed"]
COLS = ["peak_rss", "W_H", "W_k", "W_b", "Sigma", "factor", "contact_data"]


def go(name, scene, steps, opts):
    path = out(name + ".h5")
    run(["-options_file", scene, "-time_steps", steps, "-output_file", path] + TIGHT + opts, NP)
    return h5py.File(path, "r")


def forces(f):
    return f["contacts/force"][:]


def memory(f, col):
    return f["memory"][:, COLS.index(col)]


# the FE cube on the plane, fast scheme
rep = go("cube_rep", "input/cube_drop.opts", 40, ["-constraint_scheme", "fast"] + REP)
dist = go("cube_dist", "input/cube_drop.opts", 40, ["-constraint_scheme", "fast"] + DIST)
fr, fd = forces(rep), forces(dist)
e = np.abs(fd - fr).max() / np.abs(fr).max() if fr.shape == fd.shape else np.inf
c.check(fr.shape[0] > 100 and e <= 1e-10,
        "cube, fast: %d contact rows over the run, forces of the distributed path = replicated to %.1e (<= 1e-10)"
        % (fr.shape[0], e))
ref, xr = sorted_positions(rep, "cube")
_, xd = sorted_positions(dist, "cube")
scale = np.abs(xr - ref).max()
c.check(np.abs(xd - xr).max() <= 1e-10 * scale,
        "cube, fast: final positions to %.1e of the displacement (<= 1e-10)" % (np.abs(xd - xr).max() / scale))
for col, whole in (("W_H", memory(rep, "W_H").max()), ("W_b", memory(rep, "W_b").max()),
                   ("Sigma", memory(rep, "Sigma").max())):
    mine = memory(dist, col).max()
    c.check(whole > 0 and mine <= 1.2 / NP * whole,
            "cube: %s per rank %.0f kB distributed, %.0f kB replicated (largest rank): %.2f of it (<= 1.2/%d = %.2f)"
            % (col, mine / 1e3, whole / 1e3, mine / whole, NP, 1.2 / NP))
ph = dist["memory_phases"]
cols = ph.attrs["columns"].decode().split(",") if isinstance(ph.attrs["columns"], bytes) else ph.attrs["columns"].split(",")
gap = np.abs(ph[:].sum(axis=1) - memory(dist, "peak_rss")).max()
c.check(cols[0] == "set_up" and "factorization" in cols and ph.shape[0] == NP and gap < 1.0 and
        (ph[:] >= 0).all() and ph[:, cols.index("factorization")].min() > 0,
        "/memory_phases: %d ranks x %s; no phase's growth negative (the phases' sum within the peak RSS: set_up "
        ">= 0, down to %.1f MB), the factorization grew it (down to %.1f MB)"
        % (ph.shape[0], ",".join(cols), ph[:, 0].min() / 2**20, ph[:, cols.index("factorization")].min() / 2**20))

# a rigid box on the FE slab, fast scheme
rep = go("slab_rep", "input/box_on_slab.opts", 30, ["-constraint_scheme", "fast", "-contact_mu", "0"] + REP)
dist = go("slab_dist", "input/box_on_slab.opts", 30, ["-constraint_scheme", "fast", "-contact_mu", "0"] + DIST)
fr, fd = forces(rep), forces(dist)
e = np.abs(fd - fr).max() / np.abs(fr).max() if fr.shape == fd.shape else np.inf
c.check(fr.shape[0] > 50 and e <= 1e-10,
        "box on slab, fast, frictionless: %d contact rows, forces distributed = replicated to %.1e (<= 1e-10)" % (fr.shape[0], e))

# the standard scheme: W whole, C distributed
rep = go("std_rep", "input/cube_drop.opts", 40, ["-constraint_scheme", "standard"] + REP[2:])
dist = go("std_dist", "input/cube_drop.opts", 40, ["-constraint_scheme", "standard"] + DIST[2:])
fr, fd = forces(rep), forces(dist)
e = np.abs(fd - fr).max() / np.abs(fr).max() if fr.shape == fd.shape else np.inf
c.check(fr.shape[0] > 100 and e <= 1e-10,
        "cube, standard: forces with C distributed = C on rank 0 to %.1e (<= 1e-10)" % e)
c.check(memory(dist, "Sigma").max() <= 1.2 / NP * memory(rep, "Sigma").max(),
        "cube, standard: Sigma / C per rank %.2f of rank 0's whole (<= 1.2/%d)"
        % (memory(dist, "Sigma").max() / memory(rep, "Sigma").max(), NP))

# bad input
for opts, word in ((["-constraint_scheme", "fast", "-fast_distributed_contacts", "-1"], "-fast_distributed_contacts"),
                   (["-compliance_condensed_distributed_size", "-5"], "-compliance_condensed_distributed_size"),
                   (["-compliance_condensed_inverse", "everywhere"], "-compliance_condensed_inverse")):
    p = run(["-options_file", "input/cube_drop.opts", "-time_steps", "2", "-output_file", out("bad.h5")] + opts, NP,
            check=False)
    msg = p.stdout + p.stderr
    c.check(p.returncode != 0 and p.returncode < 128 and word in msg,
            "%s: exit %d, the message names %s" % (" ".join(opts), p.returncode, word))
c.done()
