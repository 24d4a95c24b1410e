#!/usr/bin/python3
"""The spectrum of W of an FCLIB contact problem (e.g. one dumped by -pgs_dump_problem): how many
eigenvalues of (W + W^T)/2 lie in each decade below the largest, all rows and normal rows only.
A cluster far below the largest is what makes projected Gauss-Seidel slow (docs/hard-cases.md).

    scripts/spectrum.py problem.hdf5"""
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from bench_contact_solver import load_h5  # noqa: E402

W, q, mu, d = load_h5(sys.argv[1])
edges = [-np.inf, -16, -12, -10, -8, -6, -4, -3, -2, -1, np.inf]
for name, idx in [("all rows", np.arange(len(q))), ("normal rows", np.arange(0, len(q), d))]:
    A = W[np.ix_(idx, idx)]
    ev = np.linalg.eigvalsh((A + A.T) / 2)
    rel = np.abs(ev) / ev[-1]
    h, _ = np.histogram(np.log10(np.maximum(rel, 1e-300)), bins=edges)
    print("%s (%d): largest eigenvalue %.3e; counts per decade of lambda / lambda_max:" % (name, len(idx), ev[-1]))
    for k in range(len(h)):
        lo = "0" if edges[k] == -np.inf else "1e%d" % edges[k]
        hi = "1" if edges[k + 1] == np.inf else "1e%d" % edges[k + 1]
        print("  [%s, %s): %d" % (lo, hi, h[k]))
