#!/usr/bin/python3
"""How two cores share the memory a contact solve streams: one dense product y = W x (numpy, BLAS
dgemv, OPENBLAS_NUM_THREADS=1) per size, first on core 0 alone, then on cores 0 and 1 at once (two
processes, each its own W), the time of one product and the bandwidth it reached (bytes of W over
time). The sizes are those of docs/contact-solver.md's split solver: the 36k box's W (1440 x 1440,
16.6 MB, in the 32 MB L3 cache alone, not with a second copy beside it), the half of it each rank
sweeps on 2 ranks (720 x 1440), the 149k box's W (4800 x 4800, 184 MB, main memory) and its half.

    scripts/bench_bandwidth.py [--reps-scale 1.0]"""
import argparse
import os
import subprocess
import sys
import time

SIZES = [(1440, 1440, 2000), (720, 1440, 4000), (4800, 4800, 100), (2400, 4800, 200)]


def one(m, n, reps):
    import numpy as np
    a = np.random.rand(m, n)
    x = np.random.rand(n)
    for _ in range(3):
        a @ x
    t = time.perf_counter()
    for _ in range(reps):
        a @ x
    dt = (time.perf_counter() - t) / reps
    print("%.6f %.3f" % (dt, a.nbytes / dt / 1e9), flush=True)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--reps-scale", type=float, default=1.0, help="scale the repetitions of each size")
    ap.add_argument("--one", nargs=3, type=int, help=argparse.SUPPRESS)
    a = ap.parse_args()
    if a.one:
        one(*a.one)
        return
    env = dict(os.environ, OPENBLAS_NUM_THREADS="1")
    print("| W (rows x columns) | MB | alone: ms per product | GB/s | two at once: ms per product (core 0, core 1) | GB/s (core 0, core 1) |")
    print("|---|---:|---:|---:|---:|---:|")
    for m, n, reps in SIZES:
        reps = max(1, int(reps * a.reps_scale))
        cmd = [sys.executable, os.path.abspath(__file__), "--one", str(m), str(n), str(reps)]
        alone = subprocess.run(["taskset", "-c", "0"] + cmd, env=env, capture_output=True, text=True, check=True)
        t1, b1 = map(float, alone.stdout.split())
        ps = [subprocess.Popen(["taskset", "-c", str(c)] + cmd, env=env, stdout=subprocess.PIPE, text=True) for c in (0, 1)]
        both = [tuple(map(float, p.communicate()[0].split())) for p in ps]
        print("| %d x %d | %.1f | %.3f | %.1f | %.3f, %.3f | %.1f, %.1f |" % (
            m, n, 8.0 * m * n / 1e6, 1e3 * t1, b1, 1e3 * both[0][0], 1e3 * both[1][0], both[0][1], both[1][1]), flush=True)


if __name__ == "__main__":
    main()
