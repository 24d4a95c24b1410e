#!/usr/bin/python3
"""Mesh partitioners compared: PETSc's ptscotch and simple against fecontact's metis
(src/mesh/partmetis.c, METIS k-way), on the Table 1 boxes (18k and 36k DOFs, made co-rotational so
that every step factors A), the co-rotational 17.5k cube at rest (input/cube_rest.opts) and the
149k box of scripts/scaling.py, on 2 and 4 ranks.

For each run: the load imbalance (largest part / mean part, in cells), the edge cut (faces shared
by two ranks: the sum of the ranks' face counts from -<body>_dm_view minus the 1-rank count; the
cut of the dual graph METIS and PT-Scotch minimize), the factorization and the solve (free motion)
per step (mean of /steps/timing over the steps after the first), and the final state against the
ptscotch run of the same rank count (relative). 4 ranks are oversubscribed on a 2-core machine:
their times are printed for completeness, not as a speed.

    scripts/partitioners.py [--ranks 2,4] [--steps 4] [--scenes 18k,36k,cube,149k] [--markdown FILE]"""
import argparse
import os
import re
import subprocess
import sys

import h5py
import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
EXE = os.path.join(ROOT, "build", "fecontact")
ENV = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1", OPENBLAS_NUM_THREADS="1")
OUT = os.path.join(ROOT, "build", "partitioners")
sys.path.insert(0, os.path.join(ROOT, "tests"))
sys.path.insert(0, os.path.join(ROOT, "scripts"))
from fctest import final_state  # noqa: E402
from scaling import big_mesh  # noqa: E402

TYPES = ["ptscotch", "metis", "simple"]


def scenes(names):
    s = {}
    corot = ["-box_material", "corotational"]
    if "18k" in names:
        s["18k"] = ("box", ["-options_file", "input/table1_18k.opts"] + corot)
    if "36k" in names:
        s["36k"] = ("box", ["-options_file", "input/table1_36k.opts"] + corot)
    if "cube" in names:
        s["cube"] = ("cube", ["-options_file", "input/cube_rest.opts"])
    if "149k" in names:
        s["149k"] = ("box", ["-options_file", "input/table1_36k.opts", "-box_dm_plex_filename", big_mesh()] + corot)
    return s


def run(opts, body, ptype, np_, steps, tag):
    f = os.path.join(OUT, "%s_%s_np%d.h5" % (tag, ptype, np_))
    cmd = [EXE] + opts + ["-time_steps", str(steps), "-output_every", str(steps), "-output_file", f, "-quiet",
                          "-%s_petscpartitioner_type" % body, ptype, "-%s_dm_view" % body]
    if np_ > 1:
        cmd = ["mpirun", "-n", str(np_), "--oversubscribe"] + cmd
    p = subprocess.run(cmd, cwd=ROOT, env=ENV, capture_output=True, text=True, timeout=3600)
    if p.returncode:
        sys.stderr.write(p.stdout + p.stderr)
        raise RuntimeError("failed: " + " ".join(cmd))
    counts = {}
    for d in (2, 3):
        m = re.search(r"Number of %d-cells per rank:([ 0-9]+)" % d, p.stdout)
        counts[d] = [int(x) for x in m.group(1).split()]
    with h5py.File(f, "r") as h:
        t = h["steps/timing"]
        fac = t["factorization"][1:].mean() if steps > 1 else t["factorization"][0]
        sol = t["free_motion"][1:].mean() if steps > 1 else t["free_motion"][0]
        state = final_state(h)
    return dict(faces=counts[2], cells=counts[3], factor=fac, solve=sol, state=state)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--ranks", default="2,4")
    ap.add_argument("--steps", type=int, default=4)
    ap.add_argument("--scenes", default="18k,36k,cube,149k")
    ap.add_argument("--markdown")
    a = ap.parse_args()
    os.makedirs(OUT, exist_ok=True)
    ranks = [int(x) for x in a.ranks.split(",")]
    lines = ["| scene | ranks | partitioner | cells per rank | imbalance | edge cut (faces) | factorization (s/step) | "
             "solve (s/step) | state vs ptscotch |", "|---|---:|---|---|---:|---:|---:|---:|---:|"]
    for tag, (body, opts) in scenes(a.scenes.split(",")).items():
        one = run(opts, body, "ptscotch", 1, 1, tag)
        faces1 = one["faces"][0]
        for np_ in ranks:
            ref = None
            for ptype in TYPES:
                r = run(opts, body, ptype, np_, a.steps, tag)
                cut = sum(r["faces"]) - faces1
                imb = max(r["cells"]) / np.mean(r["cells"])
                if ref is None:
                    ref = r["state"]
                diff = np.abs(r["state"] - ref).max() / np.abs(ref).max()
                line = "| %s | %d%s | %s | %s | %.3f | %d | %.3f | %.4f | %.1e |" % (
                    tag, np_, " (oversubscribed)" if np_ > os.cpu_count() else "", ptype,
                    " ".join(str(c) for c in r["cells"]), imb, cut, r["factor"], r["solve"], diff)
                print(line, flush=True)
                lines.append(line)
    if a.markdown:
        with open(a.markdown, "w") as f:
            f.write("Machine: %s, %d cores; `scripts/partitioners.py --ranks %s --steps %d --scenes %s`.\n\n" %
                    (os.uname().nodename, os.cpu_count(), a.ranks, a.steps, a.scenes))
            f.write("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
