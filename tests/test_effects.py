"""A scene simulates only the effects it calls for (issue 6, docs/effects.md). Each line of the
table is proved from the PETSc log (-log_view CSV: event counts of rank 0) or the HDF5 statistics:
- no contact pairs: no Collision, BuildWH, PGS, Correction event, no /contacts;
- a linear material is factored once per run, whatever the number of steps; a co-rotational one
  once per step after the first (set-up's factor serves step 1), or every k steps with
  -<body>_factorization reuse with -<body>_refactor_every k;
- rigid and kinematic bodies need no FE assembly, factorization or linear solve;
- Rayleigh damping costs one MatMult per step only when -<body>_rayleigh_mass is non-zero;
- gravity costs one VecAXPBYPCZ call (PETSc logs it as VecAXPBYCZ) per FE body and step only when it is on;
- frictionless pairs give one constraint row per contact (no tangential rows), friction three;
- W (MatMatSolve, dense builder) only for FE bodies that have contacts in the step; the default
  builder factors a linear A at its first use and again when the first contacts show their DOFs,
  or once when the body starts in contact (the start-of-run proximity query gives them); the
  redundant builder's copies of a linear A are factored once;
- the default builder computes W_b = J_T C J_T^T only when the factor or the contacts' Jacobian
  changed (a linear body resting on a plane: once), and the fast scheme sums W_H and forms W_k only
  when a body's part or the frames changed (the same motion as forming them every time);
- the recursive scheme's Newton loop stops after one iteration on a plane (the frames cannot
  change), and iterates on the grasp's spheres.
Usage: test_effects.py [--np N]"""
import csv

import h5py
import numpy as np
from fctest import Checker, np_from_argv, out, run

NP = np_from_argv()
c = Checker("effects np%d" % NP)
n = [0]


def go(args):
    n[0] += 1
    f, log = out("eff%d_np%d.h5" % (n[0], NP)), out("eff%d_np%d.csv" % (n[0], NP))
    run(args + ["-quiet", "-output_file", f, "-log_view", ":%s:ascii_csv" % log], np_=NP)
    counts = {}
    with open(log) as fl:
        for row in csv.reader(fl):
            if len(row) > 3 and row[0] == "Main Stage" and row[2] == "0":
                counts[row[1]] = int(float(row[3]))
    return counts, h5py.File(f, "r")


fall = ["-options_file", "input/cube_fall.opts"]  # FE cube, rigid ball, kinematic plane; no pairs
e, h = go(fall + ["-time_steps", "6"])
c.check(all(e.get(k, 0) == 0 for k in ("Collision", "BuildWH", "PGS", "Correction", "RebuildW")) and "contacts" not in h,
        "no contact pairs: Collision %d, BuildWH %d, PGS %d, Correction %d events, no /contacts" % (
            e.get("Collision", -1), e.get("BuildWH", -1), e.get("PGS", -1), e.get("Correction", -1)))
c.check(e.get("FCFactorization") == 6, "co-rotational, 6 steps: %d factorizations (set-up + steps 2..6)" % e.get("FCFactorization", -1))
e4, _ = go(fall + ["-time_steps", "9", "-cube_factorization", "reuse", "-cube_refactor_every", "4",
                   "-cube_refactor_rotation", "10", "-cube_refactor_iterations", "1000"])
c.check(e4.get("FCFactorization") == 3, "reuse, refactor_every 4, 9 steps: %d factorizations (steps 1, 5 and 9)" % e4.get("FCFactorization", -1))
lin5, _ = go(fall + ["-time_steps", "5", "-cube_material", "linear"])
lin20, _ = go(fall + ["-time_steps", "20", "-cube_material", "linear"])
c.check(lin5.get("FCFactorization") == 1 and lin20.get("FCFactorization") == 1 and lin5.get("FCAssembly") == lin20.get("FCAssembly"),
        "linear: one factorization in 5 and in 20 steps, assembly only at set-up (%d and %d events)" % (
            lin5.get("FCAssembly", -1), lin20.get("FCAssembly", -1)))
rk, hk = go(["-options_file", "input/incline.opts", "-time_steps", "5"])  # rigid box on a kinematic plane
# the only MatMults: the fast scheme's, two per Newton iteration on the contacts' small matrices (the forces in the
# frames C F, the proximity update d = d_free + W_H F)
newton = int(hk["steps/newton_iterations"][:].sum())
c.check(all(rk.get(k, 0) == 0 for k in ("FCAssembly", "FCFactorization", "KSPSolve")) and rk.get("MatMult", 0) == 2 * newton,
        "rigid and kinematic bodies only: no FE assembly, factorization or KSPSolve (%d, %d, %d), MatMult only the "
        "fast scheme's two per Newton iteration (%d, Newton iterations %d)" % (rk.get("FCAssembly", 0), rk.get("FCFactorization", 0),
                                                          rk.get("KSPSolve", 0), rk.get("MatMult", 0), newton))
d0, _ = go(fall + ["-time_steps", "5", "-cube_material", "linear"])
d1, _ = go(fall + ["-time_steps", "5", "-cube_material", "linear", "-cube_rayleigh_mass", "0.5"])
c.check(d1.get("MatMult", 0) - d0.get("MatMult", 0) == 5, "Rayleigh mass damping: +%d MatMult in 5 steps (one M v per step; none without)" % (
    d1.get("MatMult", 0) - d0.get("MatMult", 0)))
g0, _ = go(fall + ["-time_steps", "5", "-gravity", "0,0,0"])
c.check(g0.get("VecAXPBYCZ", 0) == 0 and e.get("VecAXPBYCZ", 0) == 6, "gravity off: %d VecAXPBYCZ (on: %d in 6 steps, one per step)" % (
    g0.get("VecAXPBYCZ", 0), e.get("VecAXPBYCZ", 0)))

drop = ["-options_file", "input/cube_drop.opts", "-time_steps", "30"]
_, h0 = go(drop + ["-contact_mu", "0"])
_, h3 = go(drop + ["-contact_mu", "0.3"])
nc0, r0 = h0["steps/contacts"][:], h0["steps/constraint_rows"][:]
nc3, r3 = h3["steps/contacts"][:], h3["steps/constraint_rows"][:]
c.check(nc0.sum() > 0 and np.array_equal(r0, nc0) and np.array_equal(r3, 3 * nc3),
        "frictionless: rows = contacts (%d rows); mu = 0.3: rows = 3 x contacts (%d rows)" % (r0.sum(), r3.sum()))
# a second FE cube far above the ground has no contact: W only for the one that has
two = drop + ["-scene_bodies", "cube,far,ground", "-contact_pairs", "cube:ground,far:ground", "-far_type", "fem",
              "-far_dm_plex_filename", "meshes/cube_coarse.msh", "-far_young", "1e6", "-far_density", "1000",
              "-far_translate", "0,0,50", "-far_material", "linear"]
ew, hw = go(two + ["-compliance_type", "dense"])
steps_with = int((hw["steps/contacts"][:] > 0).sum())
c.check(steps_with > 0 and ew.get("MatMatSolve", -1) == steps_with,
        "W only for bodies in contact: %d MatMatSolve for %d steps with contacts (the far cube has none)" % (
            ew.get("MatMatSolve", -1), steps_with))
# the default builder (condensed) owns the factor of a linear A: factored at its first use, once
# more when the first contacts show their DOFs (the Schur block), never again while they stay
l5, h5_ = go(drop + ["-time_steps", "5", "-cube_material", "linear"])
l40, h40 = go(drop + ["-time_steps", "40", "-cube_material", "linear"])
touch = int((h40["steps/contacts"][:] > 0).sum())
c.check(h5_["steps/contacts"][:].sum() == 0 and l5.get("SchurNumeric", -1) == 1 and touch >= 10 and
        l40.get("SchurNumeric", -1) == 2 and l5.get("MatCholFctrNum", 0) == l40.get("MatCholFctrNum", 0) == 0,
        "contact scene, linear, default builder: %d factorization in 5 steps without contact, %d in 40 steps (%d in "
        "contact), %d by the KSP" % (l5.get("SchurNumeric", -1), l40.get("SchurNumeric", -1), touch,
                                      l40.get("MatCholFctrNum", 0)))
# a body that starts in contact: a proximity query before the first free motion gives the default
# builder its Schur block, so A is factored once in the first step (not plain, then again at the miss)
rest = ["-options_file", "input/cube_rest.opts", "-cube_dm_plex_filename", "meshes/cube_coarse.msh", "-time_steps", "3"]
rl, hl = go(rest + ["-cube_material", "linear"])
rc, _ = go(rest)
c.check(hl["steps/contacts"][0] > 0 and rl.get("SchurNumeric", -1) == 1 and rc.get("SchurNumeric", -1) == 3,
        "resting from step 1 (%d contacts), default builder: %d factorization in 3 steps (linear), %d (co-rotational, "
        "one per step)" % (hl["steps/contacts"][0], rl.get("SchurNumeric", -1), rc.get("SchurNumeric", -1)))
# the co-rotational one keeps its first Schur block (the start contacts, no ring of margin: it
# refactors anyway) through steps 2 and 3, whose contacts are the same: one analysis
c.check(rc.get("SchurAnalysis", -1) == 1,
        "resting from step 1, co-rotational: %d analysis in 3 steps (the first Schur block is the contacts')" % (
            rc.get("SchurAnalysis", -1)))
# a co-rotational K, assembled every step, is summed through the COO map built once at set-up
# (src/body/fem_step.c, -<body>_assembly coo, the default): one MatSetPreallCOO, one MatSetValuesCOO
# per assembly (set-up's zeros, set-up's K, then one per step: a free co-rotational body takes K at
# its turned state from step 1 on, src/body/fem_rotation.c); -<body>_assembly values and a linear K
# build no map; the motion is the same as by values to 1e-12 (the sums in another order)
rcv, hcv = go(rest + ["-cube_assembly", "values"])
_, hcc = go(rest)
dx = np.abs(hcc["bodies/cube/centroid"][:] - hcv["bodies/cube/centroid"][:]).max() / np.abs(hcv["bodies/cube/centroid"][:]).max()
c.check(rc.get("MatSetPreallCOO", -1) == 1 and rc.get("MatSetValuesCOO", -1) == 2 + 3 and
        rcv.get("MatSetValuesCOO", 0) == rcv.get("MatSetPreallCOO", 0) == rl.get("MatSetValuesCOO", 0) == 0 and dx <= 1e-12,
        "co-rotational K, 3 steps: %d COO map(s), %d COO sums (values: %d, linear: %d); centroids as by values to "
        "%.1e <= 1e-12" % (rc.get("MatSetPreallCOO", -1), rc.get("MatSetValuesCOO", -1), rcv.get("MatSetValuesCOO", 0),
                           rl.get("MatSetValuesCOO", 0), dx))
# the default builder reuses W_b while neither the factor nor the contacts' Jacobian change: the
# linear cube resting on the plane computes it in step 1 and again only where its contact set
# changes (CondensedWb events; measured: contacts 104, 104, 100, so 2 in 3 steps), the
# co-rotational one, refactored every step, in each; and the reused W_b moves the cube as the
# inverse builder, which computes its W_b every step, does (1e-10 relative)
ri, hi = go(rest + ["-cube_material", "linear", "-compliance_type", "inverse"])
dx = np.abs(hl["bodies/cube/centroid"][:] - hi["bodies/cube/centroid"][:]).max() / np.abs(hi["bodies/cube/centroid"][:]).max()
nc = hl["steps/contacts"][:]
changed = 1 + int((nc[1:] != nc[:-1]).sum())
c.check(changed <= rl.get("CondensedWb", -1) < (nc > 0).sum() and rc.get("CondensedWb", -1) == 3 and dx <= 1e-10,
        "resting from step 1, default builder: W_b computed %d time(s) in %d steps with contacts %s (linear: from %d, "
        "at least one reuse), %d (co-rotational); linear centroids as the inverse builder's to %.1e <= 1e-10" % (
            rl.get("CondensedWb", -1), (nc > 0).sum(), list(nc), changed, rc.get("CondensedWb", -1), dx))
# the fast scheme keeps W_H from step to step while every body's part is the last one, and W_k while
# W_H and the frames are (src/scheme/fast.c): on the linear cube resting on the plane both are
# formed where W_b is (ComplianceSum and CongruenceWk events, once per change of the contact set),
# and the motion is that of the general path, which forms both every time (-frames_mat_type aij:
# not the host's default types), to 1e-10
fast = rest + ["-cube_material", "linear", "-constraint_scheme", "fast", "-newton_max_it", "5"]
rk, hk = go(fast)
rg, hg = go(fast + ["-frames_mat_type", "aij"])
dx = np.abs(hk["bodies/cube/centroid"][:] - hg["bodies/cube/centroid"][:]).max() / np.abs(hg["bodies/cube/centroid"][:]).max()
nk = hk["steps/contacts"][:]
c.check(rk.get("ComplianceSum", -1) == rk.get("CongruenceWk", -1) == rk.get("CondensedWb", -2) == 1 + int((nk[1:] != nk[:-1]).sum())
        and rg.get("ComplianceSum", -1) == (nk > 0).sum() and rg.get("CongruenceWk", 0) == 0 and dx <= 1e-10,
        "fast scheme, linear cube resting, contacts %s: W_H summed %d times, W_k formed %d times, W_b computed %d times "
        "(the general path: W_H %d times); centroids as the general path's to %.1e <= 1e-10" % (
            list(nk), rk.get("ComplianceSum", -1), rk.get("CongruenceWk", -1), rk.get("CondensedWb", -1),
            rg.get("ComplianceSum", -1), dx))
# where the frames follow the contacts (spheres grasping a cube), W_k is formed at every Newton iteration
rw, hw = go(["-options_file", "input/grasp_rotate.opts", "-time_steps", "6"])
rv, hv = go(["-options_file", "input/grasp_rotate.opts", "-time_steps", "6", "-frames_mat_type", "aij"])
dx = np.abs(hw["bodies/object/centroid"][:] - hv["bodies/object/centroid"][:]).max() / np.abs(hv["bodies/object/centroid"][:]).max()
c.check(rw.get("CongruenceWk", -1) == rw.get("NewtonIteration", -2) > 6 and dx <= 1e-10,
        "fast scheme on the grasp: W_k formed %d times in %d Newton iterations (frames change); centroid as the "
        "general path's to %.1e <= 1e-10" % (rw.get("CongruenceWk", -1), rw.get("NewtonIteration", -1), dx))
# the redundant builder keeps a sequential copy of a linear A on every rank: factored with A, never again
r5, _ = go(drop + ["-time_steps", "5", "-cube_material", "linear", "-compliance_type", "redundant"])
r20, _ = go(drop + ["-time_steps", "20", "-cube_material", "linear", "-compliance_type", "redundant"])
c.check(r5.get("MatCholFctrNum", -1) == r20.get("MatCholFctrNum", -2) == (1 if NP == 1 else 2),
        "contact scene, linear, redundant builder: %d numeric factorizations in 5 steps, %d in 20 (A%s)" % (
            r5.get("MatCholFctrNum", -1), r20.get("MatCholFctrNum", -1), "" if NP == 1 else " and its copy"))
ef, hf = go(drop + ["-constraint_scheme", "fast", "-newton_max_it", "5"])
it = hf["steps/newton_iterations"][:][hf["steps/contacts"][:] > 0]
c.check(it.size > 0 and (it == 1).all() and ef.get("NewtonIteration") == it.sum(),
        "fast scheme on a plane: 1 Newton iteration in each of the %d steps with contacts (of 5 allowed), %d NewtonIteration events" % (
            it.size, ef.get("NewtonIteration", -1)))
eg, hg = go(["-options_file", "input/grasp_rotate.opts", "-time_steps", "10"])
itg = hg["steps/newton_iterations"][:]
c.check(itg.max() > 1, "fast scheme on the grasp (spheres): up to %d Newton iterations (frames change)" % itg.max())
c.done()
