"""The main scenes on N ranks (3 with --oversubscribe: an uneven split of every mesh) give the
1-rank answer: final vertex positions of every FE body and poses of rigid bodies (partition-
independent order), the number of contacts that carry a force at every step (a force-free
speculative contact may come and go with round-off), and the contact forces of the last step.
Tolerance 1e-8 relative: different partitions sum in different orders, and contact scenes
amplify round-off a little through the solver's stopping test (measured up to 1e-10).
Usage: test_parallel.py --np N [--only SCENE]"""
import h5py
import re
import numpy as np
from fctest import Checker, final_state, np_from_argv, only_from_argv, out, run

NP = np_from_argv(3)
c = Checker("parallel np%d" % NP)
# short runs: 3 ranks on 2 cores are oversubscribed (MUMPS polls), a step costs ~1-4 s here
SCENES = [("default", ["-options_file", "input/default.opts", "-time_steps", "25"]),
          ("cube_drop", ["-options_file", "input/cube_drop.opts", "-time_steps", "25"]),
          ("grasp_rotate", ["-options_file", "input/grasp_rotate.opts", "-time_steps", "12"]),
          ("two_cubes", ["-options_file", "input/two_cubes.opts", "-time_steps", "20", "-contact_fe_passes", "1"]),
          ("box_on_slab", ["-options_file", "input/box_on_slab.opts", "-time_steps", "20"]),
          # Sigma^-1 of the condensed builder by ScaLAPACK on the ranks instead of LAPACK on rank 0
          ("cube_drop, -compliance_condensed_inverse scalapack", ["-options_file", "input/cube_drop.opts", "-time_steps",
                                                                  "25", "-compliance_condensed_inverse", "scalapack"]),
          # Sigma^-1 from the host's Cholesky factor and each rank's block of columns of its inverse
          ("cube_drop, -compliance_condensed_inverse columns", ["-options_file", "input/cube_drop.opts", "-time_steps",
                                                                "25", "-compliance_condensed_inverse", "columns"]),
          # the contact problem solved on every rank instead of on rank 0 (auto, at this size) and broadcast
          ("cube_drop, -pgs_ranks all", ["-options_file", "input/cube_drop.opts", "-time_steps", "25", "-pgs_ranks", "all"]),
          # W_H from a sequential factor on every rank, 1/3 of the contact DOFs each (uneven shares)
          ("grasp_rotate, -compliance_type redundant", ["-options_file", "input/grasp_rotate.opts", "-time_steps", "12",
                                                        "-constraint_scheme", "fast", "-compliance_type", "redundant"]),
          # two copies of A on 3 ranks: one factored on ranks 0-1 (distributed), one on rank 2
          # (its last item: options of the N-rank run only, 1 rank cannot have 2 groups)
          ("grasp_rotate, redundant groups 2", ["-options_file", "input/grasp_rotate.opts", "-time_steps", "12",
                                                "-constraint_scheme", "fast", "-compliance_type", "redundant"],
           ["-compliance_redundant_groups", "2"])]


ONLY = only_from_argv()
for name, args, *np_only in SCENES:
    if ONLY is not None and name != ONLY:
        continue
    tag = re.sub(r"\W+", "_", name)
    f1, fn = out("%s_np1.h5" % tag), out("%s_np%d.h5" % (tag, NP))
    run(args + ["-quiet", "-output_file", f1], np_=1)
    run(args + sum(np_only, []) + ["-quiet", "-output_file", fn], np_=NP, timeout=1200)
    a, b = h5py.File(f1, "r"), h5py.File(fn, "r")
    x, y = final_state(a), final_state(b)
    d = np.abs(x - y).max() / np.abs(x).max()
    c.check(d <= 1e-8, "%s: %d ranks vs 1: final state rel. diff %.1e <= 1e-8" % (name, NP, d))
    if "contacts" in a:
        # the contacts that carry a force, step by step, and their forces at the last step. A
        # speculative contact (continuous detection) whose chord passes at the threshold of the
        # arc bound may be in one run and not the other, since the FE positions of 1 and N ranks
        # differ by round-off (MUMPS sums in another order, and its parallel factorization is not
        # reproducible from run to run): it carries no force either way, so it is counted apart
        def active(h):
            off, f = h["contacts/offset"][:], np.abs(h["contacts/force"][:]).max(axis=1) > 0
            return np.array([f[off[k]:off[k + 1]].sum() for k in range(len(off) - 1)]), off, f
        na, offa, acta = active(a)
        nb, offb, actb = active(b)
        same = np.array_equal(na, nb)
        fa = a["contacts/force"][offa[-2]:][acta[offa[-2]:]]
        fb = b["contacts/force"][offb[-2]:][actb[offb[-2]:]]
        e = np.abs(fa - fb).max() / max(np.abs(fa).max(), 1e-300) if same and fa.shape == fb.shape and fa.size else (0.0 if same else np.inf)
        extra = int(np.abs(a["steps/contacts"][:] - b["steps/contacts"][:]).sum())
        c.check(same and e <= 1e-6, "%s: same loaded contacts every step (%d in all; %d force-free ones differ), last forces "
                "rel. diff %.1e <= 1e-6" % (name, int(na.sum()), extra, e))
    if d > 1e-8 or ("contacts" in a and not same):
        # where the runs part: the step-by-step record of both (two_cubes once failed here in CI,
        # not reproduced since; most likely the tie that made test_fe_fe flaky: its alarm distance
        # sat on the gap of step 9, which input/two_cubes.opts now keeps clear of)
        for k in ("contacts", "pgs_iterations", "residual", "intersections", "max_penetration"):
            if k in a["steps"] and k in b["steps"]:
                print("  /steps/%s  1 rank: %s\n  /steps/%s %d ranks: %s" % (k, a["steps/" + k][:].tolist(), k, NP, b["steps/" + k][:].tolist()))
        if "contacts" in a:
            print("  loaded contacts per step, 1 rank: %s\n  %d ranks: %s" % (na.tolist(), NP, nb.tolist()))
c.done()
