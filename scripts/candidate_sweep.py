#!/usr/bin/python3
"""Contact candidates on every partition: for each mesh, partitioner and rank count, the FE body is
run one step 50 m above a kinematic plane with an alarm distance of 100 m, so that every candidate
point (an owned boundary vertex, src/mesh/boundary.c) is a contact of step 1; the contacts' points are
compared with the 1-rank run's. Prints one line per mesh and partitioner and a markdown table
(docs/partitioners.md, "Contact candidates on every partition"); exits 1 if any run differs.

  /usr/bin/python3 scripts/candidate_sweep.py [--ranks 1-8] [--partitioners simple,metis,ptscotch]
      [--meshes cube_coarse,...] [--repeat k] [--exe build/fecontact]

--repeat runs every partitioned case k times (ptscotch's partitions vary from run to run). More
ranks than cores are oversubscribed (mpirun --oversubscribe): this checks answers, not speed."""
import argparse
import os
import subprocess
import sys
import tempfile

import h5py
import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
MESHES = ["six_tets", "small_cube", "bar", "thin_slab", "cube_coarse", "cube_015", "cube_medium", "sphere_coarse",
          "sphere", "cylinder", "beam_n4", "hertz_sphere_1", "hertz_block_1"]
ENV = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1", OPENBLAS_NUM_THREADS="1")


def ranks_arg(s):
    if "-" in s:
        a, b = s.split("-")
        return list(range(int(a), int(b) + 1))
    return [int(x) for x in s.split(",")]


def candidates(exe, mesh, n, part, tmp):
    """the sorted start points of the contacts of step 1 (one per candidate vertex)"""
    f = os.path.join(tmp, "c.h5")
    cmd = [exe, "-options_file", "input/cube_drop.opts", "-cube_dm_plex_filename", "meshes/%s.msh" % mesh,
           "-cube_material", "linear", "-cube_translate", "0,0,50", "-contact_distance", "100", "-time_steps", "1",
           "-quiet", "-output_file", f]
    if part:
        cmd += ["-cube_petscpartitioner_type", part]
    if n > 1:
        cmd = ["mpirun", "-n", str(n), "--oversubscribe"] + cmd
    p = subprocess.run(cmd, cwd=ROOT, env=ENV, capture_output=True, text=True)
    if p.returncode:
        sys.exit("candidate_sweep: failed (%d): %s\n%s" % (p.returncode, " ".join(cmd), p.stderr[-2000:]))
    with h5py.File(f, "r") as h:
        pts = h["contacts/point"][h["contacts/offset"][0]:h["contacts/offset"][1]]
    return pts[np.lexsort(np.round(pts, 9).T[::-1])]


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--ranks", type=ranks_arg, default=list(range(1, 9)))
    ap.add_argument("--partitioners", default="simple,metis,ptscotch")
    ap.add_argument("--meshes", default=",".join(MESHES))
    ap.add_argument("--repeat", type=int, default=1)
    ap.add_argument("--exe", default=os.path.join(ROOT, "build", "fecontact"))
    a = ap.parse_args()
    subprocess.run([os.path.join(ROOT, "scripts", "make_meshes.sh")], check=True)
    parts = a.partitioners.split(",")
    rows, bad = [], 0
    with tempfile.TemporaryDirectory() as tmp:
        for mesh in a.meshes.split(","):
            ref = candidates(a.exe, mesh, 1, None, tmp)
            for part in parts:
                diffs = []
                for n in a.ranks:
                    if n == 1:
                        continue
                    for _ in range(a.repeat):
                        got = candidates(a.exe, mesh, n, part, tmp)
                        if got.shape != ref.shape or np.abs(got - ref).max() > 1e-12:
                            diffs.append("%d ranks: %d of %d" % (n, len(got), len(ref)))
                bad += len(diffs)
                rows.append((mesh, len(ref), part, diffs))
                print("%-15s %4d candidates  %-8s  %s" % (mesh, len(ref), part, "; ".join(diffs) or "no difference"),
                      flush=True)
    print("\n| mesh | candidates (1 rank) | partitioner | ranks | runs | differences |")
    print("|---|---:|---|---|---:|---|")
    nr = len([n for n in a.ranks if n > 1])
    for mesh, nc, part, diffs in rows:
        print("| %s | %d | %s | %s | %d | %s |" % (mesh, nc, part, ",".join(str(n) for n in a.ranks if n > 1),
                                                   nr * a.repeat, "; ".join(diffs) or "none"))
    sys.exit(1 if bad else 0)


if __name__ == "__main__":
    main()
