"""The partitions that lost a boundary vertex from the contact candidates (issue 31) give the 1-rank
answer: the contacts of every step and the final state (1e-8 relative, test_parallel.py's bound), and
no intersection. Before the boundary marks were summed to the owners (src/mesh/boundary.c), each of these
lost one vertex, which then sank through the other body unseen:
  --np 2: the cube at lc 0.15 (meshes/cube_015.msh) dropped on a plane, partitioner simple: 73
          contacts from step 20 where 1 rank has 74;
  --np 8: the 6-tet cube (meshes/six_tets.msh), the default partitioner (ptscotch): 3 instead of 4;
  --np 4: two_cubes with the left cube turned 180 degrees, partitioner simple: 34 instead of 35.
--np 2 and --np 4 also replay the partition of a ptscotch run (-<body>_partition_file,
src/mesh/partreplay.c): the same cells on the same ranks as recorded, and the same state; a replay
on another number of ranks is refused.
Usage: test_candidates.py --np N"""
import h5py
import numpy as np
from fctest import Checker, final_state, np_from_argv, out, run

NP = np_from_argv(2)
c = Checker("candidates np%d" % NP)

TWO_CUBES = ["-options_file", "input/two_cubes.opts", "-time_steps", "20", "-contact_fe_passes", "1",
             "-left_rotate", "0,0,1,180"]
SCENES = {
    2: ("cube_015, simple", ["-options_file", "input/cube_drop.opts", "-cube_dm_plex_filename", "meshes/cube_015.msh",
                             "-time_steps", "40"], ["-cube_petscpartitioner_type", "simple"]),
    8: ("six_tets, ptscotch", ["-options_file", "input/cube_drop.opts", "-cube_dm_plex_filename", "meshes/six_tets.msh",
                               "-cube_material", "linear", "-cube_translate", "0,0,0.05", "-time_steps", "40"], []),
    4: ("two_cubes turned, simple", TWO_CUBES, ["-left_petscpartitioner_type", "simple",
                                                "-right_petscpartitioner_type", "simple"]),
}


def partition(h, body):
    """the rank of every cell of the mesh as read"""
    r = np.full(len(h["bodies/%s/mesh/rank" % body]), -1)
    r[h["bodies/%s/mesh/cell_origin" % body][:]] = h["bodies/%s/mesh/rank" % body][:]
    return r


if NP in SCENES:
    name, args, nonly = SCENES[NP]
    f1, fn = out("one.h5"), out("many.h5")
    run(args + ["-quiet", "-output_file", f1], np_=1)
    run(args + nonly + ["-quiet", "-output_file", fn], np_=NP)
    a, b = h5py.File(f1, "r"), h5py.File(fn, "r")
    ca, cb = a["steps/contacts"][:], b["steps/contacts"][:]
    c.check(np.array_equal(ca, cb) and ca.max() > 0,
            "%s: contacts at every step, %d ranks as 1 (%s)" % (name, NP, "same" if np.array_equal(ca, cb) else
                                                                 "1 rank %s, %d ranks %s" % (ca.tolist(), NP, cb.tolist())))
    x, y = final_state(a), final_state(b)
    d = np.abs(x - y).max() / np.abs(x).max()
    c.check(d <= 1e-8, "%s: final state, %d ranks vs 1: rel. diff %.1e <= 1e-8" % (name, NP, d))
    # two_cubes runs one detection pass (-contact_fe_passes 1): the right cube's vertices are not
    # constrained and do enter the left cube, on 1 rank as on N
    ia, ib = a["steps/intersections"][:], b["steps/intersections"][:]
    c.check(np.array_equal(ia, ib), "%s: intersections at every step as on 1 rank (at most %d)" % (name, ia.max()))
    for body in b["bodies"]:
        g = b["bodies/" + body]
        if "mesh/rank" in g:
            r = partition(b, body)
            c.check(g["mesh"].attrs["ranks"] == NP and r.min() >= 0 and r.max() < NP and np.bincount(r).max() > 0,
                    "%s: body %s's partition recorded, every cell on a rank: cells per rank %s"
                    % (name, body, np.bincount(r, minlength=NP).tolist()))

if NP in (2, 4):  # the replay of a ptscotch partition
    f, fr = out("ptscotch.h5"), out("replay.h5")
    run(TWO_CUBES + ["-quiet", "-output_file", f], np_=NP)
    run(TWO_CUBES + ["-left_partition_file", f, "-right_partition_file", f, "-quiet", "-output_file", fr], np_=NP)
    a, b = h5py.File(f, "r"), h5py.File(fr, "r")
    for body in ("left", "right"):
        same = np.array_equal(partition(a, body), partition(b, body))
        cells = np.array_equal(a["bodies/%s/mesh/cells" % body][:], b["bodies/%s/mesh/cells" % body][:])
        c.check(same and cells, "replay: body %s has the recorded cells on each rank (%s) and the same numbering"
                % (body, np.bincount(partition(b, body)).tolist()))
    d = np.abs(final_state(a) - final_state(b)).max() / np.abs(final_state(a)).max()
    c.check(d <= 1e-8 and np.array_equal(a["steps/contacts"][:], b["steps/contacts"][:]),
            "replay: the same contacts every step, final state rel. diff %.1e <= 1e-8" % d)
    # a replay on another number of ranks is refused, naming the option
    other = 3 if NP == 2 else 2
    p = run(TWO_CUBES + ["-left_partition_file", f, "-quiet", "-output_file", out("x.h5")], np_=other, check=False)
    c.check(p.returncode != 0 and "-left_partition_file" in p.stderr and
            "%d ranks, this run has %d" % (NP, other) in p.stderr,
            "replay on %d ranks of a %d-rank partition: refused (%s)" % (other, NP, p.stderr.strip().splitlines()[0][:140]))
c.done()
