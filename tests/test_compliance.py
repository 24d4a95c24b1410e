"""Compliance builders: -compliance_type dense, sparse, schur, inverse, redundant and condensed
give the same contact forces and positions (1e-10 relative) on an FE cube dropped on a plane (the
same W to round-off drives the same solver path; condensed also does the free motion and the
correction with its own Schur-ordered factor, and misses its first contact); on more than one rank
sparse is refused with a clear error. condensed_balance: condensed with the top of its nested
dissection bisected in balance of the vertices next to S (-compliance_condensed_balance 1); on
several ranks condensed with Sigma^-1 by ScaLAPACK or by the ranks' blocks of columns
(-compliance_condensed_inverse scalapack, columns). Every builder handles contacts whose DOFs are all fixed (a
box on a slab whose top face is held: W_b = 0, the box rests on the fixed face). The co-rotational grasp (A refactored every step) checks that W_H follows A with every
builder, the redundant copies of A included. precomputed is exact for a linear material (1e-10) and, rotation-warped, close to
dense for a co-rotational one. -blas_gemv_forward (dgemm with one column as dgemv, src/util/blas.c)
is reached by MUMPS' solves on every rank and leaves the motion as it was (1e-12). Usage:
test_compliance.py [--np N]"""
import re

import numpy as np
import h5py
from fctest import run, out, Checker, np_from_argv, sorted_positions

NP = np_from_argv()
c = Checker("compliance np%d" % NP)
# plain PGS: its iterates are a smooth function of W, so W equal to round-off gives forces equal
# to round-off. NNCG (the default) branches on residual comparisons, which round-off can flip: its
# answers then agree only to the PGS tolerance (measured 2.4e-10 on 2 ranks), which says nothing
# about the builders.
# The builders are compared with A factored at every step (-<body>_factorization every_step, the
# default; reuse, an older factor warped, is the condensed builder's only: tests/test_factorization.py).
base = ["-options_file", "input/cube_drop.opts", "-time_steps", "28", "-pgs_tol", "1e-10", "-pgs_max_it", "20000", "-quiet",
        "-pgs_acceleration", "none"]


def result(ctype, extra=()):
    f = out("comp_%s%s_np%d.h5" % (ctype, "_".join(extra), NP))
    run(base + ["-compliance_type", ctype, "-output_file", f] + list(extra), np_=NP)
    return h5py.File(f, "r")


a = result("dense")
others = (["sparse"] if NP == 1 else []) + ["schur", "inverse", "inverse8", "redundant", "condensed", "condensed2",
                                               "condensed_balance"] + (
    ["redundant1", "condensed_scalapack", "condensed_columns"] if NP > 1 else [])
for ctype in others:
    # redundant1: one copy of A, distributed over all ranks (-compliance_redundant_groups 1);
    # inverse8: MUMPS computing the entries of A^-1 8 columns at a time instead of 256
    if ctype == "redundant1":
        b = result("redundant", ("-compliance_redundant_groups", "1"))
    elif ctype == "inverse8":
        b = result("inverse", ("-compliance_inverse_block", "8"))
    elif ctype == "condensed2":  # two rings of surface neighbours in the Schur block
        b = result("condensed", ("-compliance_condensed_ring", "2"))
    elif ctype == "condensed_balance":  # the top of the dissection bisected in balance of the vertices next to S
        b = result("condensed", ("-compliance_condensed_balance", "1"))
    elif ctype in ("condensed_scalapack", "condensed_columns"):  # Sigma^-1 over the ranks, not on rank 0 alone
        b = result("condensed", ("-compliance_condensed_inverse", ctype.split("_")[1]))
    else:
        b = result(ctype)
    same = np.array_equal(a["contacts/offset"][:], b["contacts/offset"][:])
    c.check(same and a["contacts/offset"][-1] > 0, "%s: same contacts as dense (%d records)" % (ctype, a["contacts/offset"][-1]))
    fa, fb = a["contacts/force"][:], b["contacts/force"][:]
    err = np.abs(fa - fb).max() / np.abs(fa).max() if same else np.inf
    c.check(err < 1e-10, "%s vs dense: forces rel. diff %.2e < 1e-10" % (ctype, err))
    pa, pb = sorted_positions(a, "cube")[1], sorted_positions(b, "cube")[1]
    c.check(np.abs(pa - pb).max() / np.abs(pa).max() < 1e-10, "%s vs dense: positions agree" % ctype)
# precomputed surface compliance: C_0 = A^-1 on the surface is exact for a linear material
lin = ["-cube_material", "linear"]
a_lin = result("dense", lin)
for ctype in ["precomputed", "condensed"]:  # condensed on a linear body: one factor, refactored only on a miss
    b_lin = result(ctype, lin)
    fa, fb = a_lin["contacts/force"][:], b_lin["contacts/force"][:]
    same = fa.shape == fb.shape and fa.size > 0
    err = np.abs(fa - fb).max() / np.abs(fa).max() if same else np.inf
    c.check(err < 1e-10, "%s vs dense, linear material: forces rel. diff %.2e < 1e-10" % (ctype, err))
    pa, pb = sorted_positions(a_lin, "cube")[1], sorted_positions(b_lin, "cube")[1]
    err = np.abs(pa - pb).max() / np.abs(pa).max()
    c.check(err < 1e-10, "%s vs dense, linear material: positions rel. diff %.2e < 1e-10" % (ctype, err))
# co-rotational: C_0 warped by the best-fit rotation is an approximation of the current
# compliance; on this drop (little rotation, small strain) the positions stay within 1e-4 m of
# dense (measured 1.2e-5 m at 28 steps), the contacts carry the weight and do not penetrate
b = result("precomputed")
pa, pb = sorted_positions(a, "cube")[1], sorted_positions(b, "cube")[1]
d = np.abs(pa - pb).max()
c.check(0 < d < 1e-4, "precomputed (warped) vs dense, co-rotational: positions differ by %.2e m (0 < d < 1e-4)" % d)
pen = b["steps/max_penetration"][:].max()
c.check(pen < 1e-6, "precomputed (warped): max penetration %.2e m < 1e-6" % pen)
# W_H of the fast scheme comes from the same builders (identity frames): all agree with dense
wh = {}
for ctype in ["dense", "schur", "inverse", "redundant", "condensed"]:
    f = out("wh_%s_np%d.h5" % (ctype, NP))
    run(["-options_file", "input/grasp_rotate.opts", "-time_steps", "10", "-constraint_scheme", "fast", "-pgs_tol", "1e-11",
         "-pgs_max_it", "50000", "-compliance_type", ctype, "-output_file", f, "-quiet", "-pgs_acceleration", "none"], np_=NP)
    wh[ctype] = h5py.File(f, "r")
for ctype in ["schur", "inverse", "redundant", "condensed"]:
    fa, fb = wh["dense"]["contacts/force"][:], wh[ctype]["contacts/force"][:]
    same = fa.shape == fb.shape and fa.size > 0
    err = np.abs(fa - fb).max() / np.abs(fa).max() if same else np.inf
    c.check(err < 1e-9, "fast scheme, co-rotational grasp, W_H by dense vs %s: forces rel. diff %.2e" % (ctype, err))
# FE-FE contacts (barycentric proximities on both bodies, two bodies' blocks of S and J_S). Without
# edge-edge contacts: with them, the cubes' coinciding edges add contacts that make W singular, so
# the forces are not unique (the same motion, to 2e-16 on 2 ranks, with forces 97 % apart at step
# 39): a builder comparison by forces needs a unique solution. tests/test_detection.py checks the
# edge-edge rows in every builder on the crossed bars.
fe = {}
for ctype in ["dense", "inverse", "redundant", "condensed"]:
    f = out("fefe_%s_np%d.h5" % (ctype, NP))
    run(["-options_file", "input/two_cubes.opts", "-time_steps", "60", "-compliance_type", ctype, "-output_file", f, "-quiet",
         "-pgs_acceleration", "none", "-pgs_tol", "1e-11", "-pgs_max_it", "20000", "-contact_edge_edge", "0"], np_=NP)
    fe[ctype] = h5py.File(f, "r")
# The steps are compared where both runs have the same number of contact records: on 2 ranks MUMPS'
# parallel factorization is not bitwise reproducible, and a vertex at the alarm distance may then be
# a contact in one run and not in the other at some step (seen in 3 of 7 runs of this test on 2 ranks
# in one session, at the first contact step or later; such a contact is speculative, with zero
# force). At least 90 % of the steps with contacts must be compared.
for ctype in ["inverse", "redundant", "condensed"]:
    oa, ob = fe["dense"]["contacts/offset"][:], fe[ctype]["contacts/offset"][:]
    fa, fb = fe["dense"]["contacts/force"][:], fe[ctype]["contacts/force"][:]
    err, same, steps = 0.0, 0, 0
    for st in range(min(len(oa), len(ob)) - 1):
        na, nb = oa[st + 1] - oa[st], ob[st + 1] - ob[st]
        if na == 0 and nb == 0:
            continue
        steps += 1
        if na != nb:
            continue
        same += 1
        err = max(err, np.abs(fa[oa[st]:oa[st + 1]] - fb[ob[st]:ob[st + 1]]).max())
    err = err / np.abs(fa).max() if same else np.inf
    c.check(steps > 0 and same >= 0.9 * steps and err < 1e-10, "FE-FE two cubes, %s vs dense: forces rel. diff %.2e < 1e-10 "
            "on the %d of %d contact steps with the same records (>= 90 %%)" % (ctype, err, same, steps))
# MUMPS out of workspace (INFOG(1) = -9, intermittent on several ranks; forced here with a margin of
# -60 %): the factor is replaced and retried with a larger margin (src/util/mumps.c), the body's own
# factor (dense builder) and a builder's (the schur builder's augmented matrix) alike, and the run
# ends where the reference does. Before, the builder's retry factored nothing (PETSc's numeric phase
# returns at once after a failure) and the body's was not retried.
for label, extra in [("the body's factor of A", ["-compliance_type", "dense", "-cube_mat_mumps_icntl_14", "-60"]),
                     ("the schur builder's factor", ["-compliance_type", "schur", "-mat_mumps_icntl_14", "-60"])]:
    f = out("comp_oom_%s_np%d.h5" % (extra[1], NP))
    p = run(base + extra + ["-output_file", f, "-info", ":mat"], np_=NP, check=False)
    retried = "MUMPS out of workspace" in p.stdout + p.stderr
    ok = p.returncode == 0
    err = np.inf
    if ok:
        b = h5py.File(f, "r")
        fa, fb = a["contacts/force"][:], b["contacts/force"][:]
        err = np.abs(fa - fb).max() / np.abs(fa).max() if fa.shape == fb.shape else np.inf
    c.check(ok and retried and err < 1e-10, "%s out of workspace: retried (%s), exit %d, forces vs dense %.1e < 1e-10" % (
        label, retried, p.returncode, err))
# contacts on fixed DOFs: the slab's whole top face held (W_b of the slab is 0 and the box's own
# compliance carries the contacts; MUMPS refused the empty selection of the inverse builders), then
# only its x < 0 half (contacts on fixed and on free DOFs side by side: W_b differs by builder)
for label, box in [("all fixed", "-3,-3,-0.01,3,3,3"), ("half fixed", "-3,-3,-0.01,0,3,3")]:
    fixed = {}
    for ctype in ["dense", "schur", "inverse", "redundant", "precomputed", "condensed"] + (["sparse"] if NP == 1 else []):
        f = out("fixed_%s_%s_np%d.h5" % (label[:4], ctype, NP))
        p = run(["-options_file", "input/box_on_slab.opts", "-slab_fixed_box", box, "-time_steps", "24",
                 "-compliance_type", ctype, "-output_file", f, "-quiet"], np_=NP, check=False)
        c.check(p.returncode == 0, "%s, contact DOFs %s: runs to the end (exit %d)" % (ctype, label, p.returncode))
        if p.returncode == 0:
            fixed[ctype] = h5py.File(f, "r")
    if "dense" not in fixed:
        continue
    d = fixed.pop("dense")
    c.check(d["steps/contacts"][-1] > 0 and d["steps/max_penetration"][-1] < 1e-3,
            "box on the slab, contact DOFs %s: %d contacts, max penetration %.2e m < 1e-3" %
            (label, d["steps/contacts"][-1], d["steps/max_penetration"][-1]))
    for ctype, b in fixed.items():
        if ctype == "precomputed":  # warps A_0^-1 (co-rotational slab): an approximation, checked for penetration
            pen = b["steps/max_penetration"][-1]
            c.check(pen < 1e-3, "contact DOFs %s, precomputed: max penetration %.2e m < 1e-3" % (label, pen))
            continue
        fa, fb = d["contacts/force"][:], b["contacts/force"][:]
        same = fa.shape == fb.shape and fa.size > 0
        err = np.abs(fa - fb).max() / np.abs(fa).max() if same else np.inf
        c.check(err < 1e-10, "contact DOFs %s, %s vs dense: forces rel. diff %.2e < 1e-10" % (label, ctype, err))
# dgemm with one column computed as dgemv (src/util/blas.c): MUMPS' solves reach it (products
# counted by -info), and the motion is that of the BLAS library's dgemm to round-off
rest = ["-options_file", "input/cube_rest.opts", "-cube_dm_plex_filename", "meshes/cube_coarse.msh", "-time_steps", "3",
        "-quiet", "-info", ":sys"]
fwd = {}
for on in (1, 0):
    f = out("comp_gemv%d_np%d.h5" % (on, NP))
    p = run(rest + ["-blas_gemv_forward", str(on), "-output_file", f], np_=NP)
    n = [int(x) for x in re.findall(r"dgemm with one column computed as dgemv: (\d+) products", p.stdout + p.stderr)]
    fwd[on] = (n, sorted_positions(h5py.File(f, "r"), "cube")[-1])
d = np.abs(fwd[1][1] - fwd[0][1]).max() / np.abs(fwd[0][1]).max()
c.check(len(fwd[1][0]) == NP and min(fwd[1][0]) > 0 and fwd[0][0] == [0] * NP and d < 1e-12,
        "-blas_gemv_forward: %s one-column products as dgemv per rank (0 when off: %s); positions on vs off %.1e < 1e-12" % (
            fwd[1][0], fwd[0][0], d))
if NP > 1:
    p = run(base + ["-compliance_type", "sparse", "-output_file", out("comp_sparse_np%d.h5" % NP)], np_=NP, check=False)
    c.check(p.returncode != 0 and "one MPI rank only" in p.stderr + p.stdout, "sparse on %d ranks: clear error, exit %d" % (NP, p.returncode))
p = run(base + ["-compliance_type", "magic", "-output_file", out("comp_bad.h5")], check=False)
c.check(p.returncode != 0 and "Unknown compliance type 'magic'" in p.stderr + p.stdout, "unknown compliance type: clear error")
p = run(base + ["-compliance_type", "condensed", "-compliance_condensed_ring", "-1", "-output_file", out("comp_bad.h5")], check=False)
c.check(p.returncode != 0 and "-compliance_condensed_ring must be >= 0" in p.stderr + p.stdout, "negative ring: clear error")
p = run(base + ["-compliance_type", "condensed", "-compliance_condensed_balance", "9", "-output_file", out("comp_bad.h5")],
        check=False)
c.check(p.returncode != 0 and "-compliance_condensed_balance must be an integer in [0, 8]" in p.stderr + p.stdout,
        "balance out of range: clear error")
c.done()
