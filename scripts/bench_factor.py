#!/usr/bin/python3
"""Factorization and solve times of one FE body at the four mesh sizes of the paper's Table 1
(18000, 23940, 30000, 36000 DOFs), on 1 and 2 MPI ranks, with the default solver (MUMPS Cholesky).

A co-rotational body is run for a few steps, so A is factored once at set-up and again at every
step after the first; the times are read from -log_view's CSV (max over ranks per event) and
divided by the event counts:
  assembly       FCAssembly      element loop of K and f_int (plus the mass at set-up)
  symbolic       MatCholFctrSym  MUMPS analysis (ordering), once per run
  numeric        MatCholFctrNum  one numeric Cholesky factorization of A
  solve          MatSolve        one forward/backward solve with one right-hand side

Usage: scripts/bench_factor.py [--steps N] [--ranks 1,2] [--markdown FILE]
Run it on an otherwise idle machine; it prints what it measured."""
import argparse
import csv
import os
import platform
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
EXE = os.path.join(ROOT, "build", "fecontact")
SIZES = ["18k", "24k", "30k", "36k"]
EVENTS = {"assembly": "FCAssembly", "symbolic": "MatCholFctrSym", "numeric": "MatCholFctrNum", "solve": "MatSolve"}


def measure(size, ranks, steps):
    tmp = tempfile.mkdtemp(prefix="bench-")
    csvfile = os.path.join(tmp, "log.csv")
    cmd = [EXE, "-scene_bodies", "b", "-b_type", "fem", "-b_dm_plex_filename", "meshes/table1_%s.msh" % size,
           "-b_material", "corotational", "-b_young", "1e5", "-b_density", "1000", "-time_steps", str(steps),
           "-output_file", os.path.join(tmp, "out.h5"), "-output_every", str(steps), "-quiet",
           "-log_view", ":%s:ascii_csv" % csvfile]
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1", OPENBLAS_NUM_THREADS="1")
    if ranks > 1:
        cmd = ["mpirun", "-n", str(ranks), "--oversubscribe"] + cmd
    subprocess.run(cmd, cwd=ROOT, env=env, check=True)
    t, n = {}, {}
    with open(csvfile) as f:
        for row in csv.reader(f):
            if len(row) > 4 and row[0] == "Main Stage" and row[1] in EVENTS.values():
                t[row[1]] = max(t.get(row[1], 0.0), float(row[4]))
                n[row[1]] = int(row[3])
    dofs = {"18k": 18000, "24k": 23940, "30k": 30000, "36k": 36000}[size]
    return dofs, {k: t[e] / max(n[e], 1) for k, e in EVENTS.items()}, {k: n[e] for k, e in EVENTS.items()}


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--steps", type=int, default=4)
    ap.add_argument("--ranks", default="1,2")
    ap.add_argument("--markdown")
    a = ap.parse_args()
    ranks = [int(r) for r in a.ranks.split(",")]
    lines = ["| DOFs | ranks | assembly (ms) | symbolic (ms) | numeric factorization (ms) | solve (ms) | factorizations | solves |",
             "| ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |"]
    print(lines[0])
    print(lines[1])
    for size in SIZES:
        for r in ranks:
            dofs, t, n = measure(size, r, a.steps)
            line = "| %d | %d | %.1f | %.1f | %.1f | %.2f | %d | %d |" % (dofs, r, 1e3 * t["assembly"], 1e3 * t["symbolic"], 1e3 * t["numeric"], 1e3 * t["solve"], n["numeric"], n["solve"])
            print(line, flush=True)
            lines.append(line)
    if a.markdown:
        with open(a.markdown, "w") as f:
            f.write("# Benchmarks\n\n## Factorization and solve of one FE body at the Table 1 sizes\n\n")
            f.write("Command: `scripts/bench_factor.py --steps %d --ranks %s --markdown %s`\n\n" % (a.steps, a.ranks, a.markdown))
            f.write("Machine: %s, %d cores, %s. PETSc 3.18 (Debian), MUMPS Cholesky, OpenBLAS, "
                    "OPENBLAS_NUM_THREADS=1. Co-rotational cube meshes `meshes/table1_*.msh`; times are per call, "
                    "max over ranks, from `-log_view`.\n\n" % (platform.node(), os.cpu_count(), platform.platform()))
            f.write("\n".join(lines) + "\n")
        print("wrote", a.markdown)


if __name__ == "__main__":
    sys.exit(main())
