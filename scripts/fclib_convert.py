#!/usr/bin/python3
"""Converts the Siconos text problems (*.dat) of tests/data/fclib into the FCLIB HDF5 local
layout (/fclib_local/W as CSR, /fclib_local/vectors/{q,mu}, /fclib_local/spacedim) that
fecontact's FCContactProblemLoadFCLIB() reads; FCLIB *.hdf5 files are linked as they are.
Usage: scripts/fclib_convert.py SRC_DIR DST_DIR   (skips problems already converted)"""
import glob
import os
import sys

import h5py
import numpy as np
import siconos.numerics as sn


def dense(problem):
    M = problem.M
    n = M.size0
    B = sn.NM_create(sn.NM_DENSE, n, n)
    sn.NM_to_dense(M, B)
    return np.array([[B.get_matrix0(i, j) for j in range(n)] for i in range(n)])


def write(path, W, q, mu, dim):
    n = W.shape[0]
    rowptr, cols, vals = [0], [], []
    for i in range(n):
        nz = np.nonzero(W[i])[0]
        cols += list(nz)
        vals += list(W[i, nz])
        rowptr.append(len(cols))
    with h5py.File(path + ".tmp", "w") as f:
        g = f.create_group("fclib_local")
        w = g.create_group("W")
        w["m"], w["n"], w["nz"], w["nzmax"] = [n], [n], [-2], [len(vals)]
        w["p"], w["i"], w["x"] = np.array(rowptr, dtype=np.int64), np.array(cols, dtype=np.int64), np.array(vals)
        v = g.create_group("vectors")
        v["q"], v["mu"] = np.asarray(q, dtype=float), np.asarray(mu, dtype=float)
        g["spacedim"] = [dim]
    os.replace(path + ".tmp", path)


def main(src, dst):
    os.makedirs(dst, exist_ok=True)
    for f in sorted(glob.glob(os.path.join(src, "*.dat"))):
        out = os.path.join(dst, os.path.basename(f)[:-4] + ".h5")
        if os.path.exists(out) and os.path.getmtime(out) >= os.path.getmtime(f):
            continue
        p = sn.frictionContact_new_from_filename(f)
        write(out, dense(p), np.array(p.q), np.array(p.mu), p.dimension)
    for f in sorted(glob.glob(os.path.join(src, "*.hdf5"))):
        out = os.path.join(dst, os.path.basename(f)[:-5] + ".h5")
        if not os.path.exists(out):
            os.symlink(os.path.abspath(f), out)


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2])
