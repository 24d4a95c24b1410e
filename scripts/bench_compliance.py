#!/usr/bin/python3
"""Time of the compliance builders (-compliance_type dense|sparse|schur|inverse|redundant) on a
scene, from -log_view (event BuildWH: W = J A^-1 J^T of every FE body, per Newton iteration with
contacts), with the numeric Cholesky factorizations of the run for comparison (Schur adds one of
the augmented matrix per build; redundant one of A's copy per factorization of A on > 1 rank). Usage: scripts/bench_compliance.py [--scene input/default.opts] [--steps 60] [--np 1]"""
import argparse
import csv
import os
import subprocess
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--scene", default="input/default.opts")
    ap.add_argument("--steps", type=int, default=60)
    ap.add_argument("--np", type=int, default=1)
    a = ap.parse_args()
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1", OPENBLAS_NUM_THREADS="1")
    print("scene %s, %d steps, %d rank(s)" % (a.scene, a.steps, a.np))
    print("| compliance_type | W builds | time per build (ms) | numeric factorizations | time per factorization (ms) |")
    print("|---|---:|---:|---:|---:|")
    for ct in ["dense", "sparse", "schur", "inverse", "redundant"]:
        if ct == "sparse" and a.np > 1:
            continue
        tmp = tempfile.mkdtemp(prefix="bench-")
        log = os.path.join(tmp, "log.csv")
        cmd = [os.path.join(ROOT, "build", "fecontact"), "-options_file", a.scene, "-time_steps", str(a.steps),
               "-compliance_type", ct, "-output_file", os.path.join(tmp, "o.h5"), "-quiet", "-log_view", ":%s:ascii_csv" % log]
        if a.np > 1:
            cmd = ["mpirun", "-n", str(a.np)] + cmd
        subprocess.run(cmd, cwd=ROOT, env=env, check=True)
        ev = {}
        with open(log) as f:
            for row in csv.reader(f):
                if len(row) > 4 and row[0] == "Main Stage" and row[1] in ("BuildWH", "MatCholFctrNum"):
                    n, t = int(row[3]), float(row[4])
                    ev[row[1]] = (n, max(t, ev.get(row[1], (0, 0.0))[1]))
        (nw, tw), (nf, tf) = ev["BuildWH"], ev["MatCholFctrNum"]
        print("| %s | %d | %.1f | %d | %.1f |" % (ct, nw, 1e3 * tw / max(nw, 1), nf, 1e3 * tf / max(nf, 1)), flush=True)


if __name__ == "__main__":
    main()
