"""The METIS partitioner (src/mesh/partmetis.c, -<body>_petscpartitioner_type metis) gives the
answer of PETSc's ptscotch on N ranks: the centroid trajectory of every body (every step) within
1e-10 relative, the final vertex positions within 1e-10; it really partitions differently (the
vertices, edges, faces or cells per rank of -<body>_dm_view differ from ptscotch's on at least one scene), it balances the
cells within its imbalance option, and its options are checked.
Scenes: a contact scene (cube_drop, an FE cube on a plane) and an FE-FE one (two_cubes).
Usage: test_partition.py --np N [--only SCENE]"""
import re

import h5py
import numpy as np
from fctest import Checker, final_state, np_from_argv, only_from_argv, out, run

NP = np_from_argv(2)
c = Checker("partition np%d" % NP)
SCENES = [("cube_drop", ["-options_file", "input/cube_drop.opts", "-time_steps", "30"], ["cube"]),
          ("two_cubes", ["-options_file", "input/two_cubes.opts", "-time_steps", "15", "-contact_edge_edge", "0"],
           ["left", "right"])]


def cells(stdout):
    return [[int(x) for x in m.split()] for m in re.findall(r"Number of 3-cells per rank:([ 0-9]+)", stdout)]


def counts(stdout):
    """every 'Number of d-cells per rank' line of -dm_view: vertices, edges, faces and cells"""
    return re.findall(r"Number of \d-cells per rank:([ 0-9]+)", stdout)


ONLY = only_from_argv()
differs = False
for name, args, bodies in SCENES:
    if ONLY is not None and name != ONLY:
        continue
    res = {}
    for ptype in ["ptscotch", "metis"]:
        f = out("%s_%s_np%d.h5" % (name, ptype, NP))
        extra = sum([["-%s_petscpartitioner_type" % b, ptype, "-%s_dm_view" % b] for b in bodies], [])
        p = run(args + extra + ["-quiet", "-output_file", f], np_=NP)
        res[ptype] = (h5py.File(f, "r"), cells(p.stdout), counts(p.stdout))
    (a, ca, na), (b, cb, nb) = res["ptscotch"], res["metis"]
    for body in bodies:
        x, y = a["bodies/%s/centroid" % body][:], b["bodies/%s/centroid" % body][:]
        d = np.abs(x - y).max() / np.abs(x).max()
        c.check(x.shape == y.shape and d <= 1e-10,
                "%s: body %s centroid trajectory (%d steps), metis vs ptscotch on %d ranks: rel. diff %.1e <= 1e-10"
                % (name, body, len(x), NP, d))
    d = np.abs(final_state(a) - final_state(b)).max() / np.abs(final_state(a)).max()
    c.check(d <= 1e-10, "%s: final vertex positions, metis vs ptscotch: rel. diff %.1e <= 1e-10" % (name, d))
    for body_cells in cb:
        imb = max(body_cells) / np.mean(body_cells)
        c.check(len(body_cells) == NP and imb <= 1.03 + 1e-9,
                "%s: metis cells per rank %s, imbalance %.3f <= 1.03 (the default tolerance)" % (name, body_cells, imb))
    differs = differs or na != nb
    print("  %s: vertices, edges, faces, cells per rank: ptscotch %s, metis %s" % (name, na, nb))
if ONLY is not None:  # one scene repeated: the checks of the whole set are not made
    c.done()
c.check(differs, "metis partitions differently from ptscotch on at least one body")

# the objective and the imbalance options reach METIS: communication volume gives the same answer
f = out("vol_np%d.h5" % NP)
run(SCENES[0][1] + ["-cube_petscpartitioner_type", "metis", "-cube_petscpartitioner_metis_objective", "volume",
                    "-quiet", "-output_file", f], np_=NP)
x = h5py.File(f, "r")["bodies/cube/centroid"][:]
y = h5py.File(out("cube_drop_ptscotch_np%d.h5" % NP), "r")["bodies/cube/centroid"][:]
c.check(np.abs(x - y).max() / np.abs(y).max() <= 1e-10, "metis objective volume: the same trajectory")
for opt, val, msg in [("imbalance", "1", "-cube_petscpartitioner_metis_imbalance must lie in (1, 100)"),
                      ("objective", "speed", "-cube_petscpartitioner_metis_objective"),
                      ("seed", "-2", "-cube_petscpartitioner_metis_seed must be an integer in [0, ")]:
    p = run(SCENES[0][1] + ["-cube_petscpartitioner_type", "metis", "-cube_petscpartitioner_metis_" + opt, val,
                            "-quiet", "-output_file", out("bad.h5")], np_=NP, check=False)
    c.check(p.returncode != 0 and msg in p.stdout + p.stderr,
            "bad -cube_petscpartitioner_metis_%s %s: exit %d, message names it" % (opt, val, p.returncode))
c.done()
