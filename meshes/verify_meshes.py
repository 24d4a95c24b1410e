#!/usr/bin/python3
"""Check fecontact meshes with PETSc DMPlex (petsc4py; run with /usr/bin/python3).

Usage: /usr/bin/python3 meshes/verify_meshes.py [file.msh ...]   (default: all meshes/*.msh)

For each mesh: dimension 3, vertex/cell counts, every cell a tetrahedron (4 closure vertices,
4 faces in the cone), detJ > 0 for every cell from DMPlexComputeCellGeometryFEM, total volume,
Euler characteristic V-E+F-C == 1, and every boundary face carrying a "Face Sets" value.
Exits non-zero if any check fails.
"""
import glob
import os
import sys
import time

import ctypes

import numpy as np
from petsc4py import PETSc

# petsc4py 3.18 does not wrap DMPlexComputeCellGeometryFEM: call it from the loaded libpetsc.
def _libpetsc():
    with open("/proc/self/maps") as f:
        for line in f:
            p = line.split()[-1]
            if os.path.basename(p).startswith("libpetsc") and ".so" in p:
                return ctypes.CDLL(p)
    raise RuntimeError("libpetsc not found in process maps")


_lib = _libpetsc()
_pint = ctypes.c_int64 if np.dtype(PETSc.IntType).itemsize == 8 else ctypes.c_int32
_fem = _lib.DMPlexComputeCellGeometryFEM
_fem.argtypes = [ctypes.c_void_p, _pint, ctypes.c_void_p, ctypes.c_void_p, ctypes.c_void_p,
                 ctypes.c_void_p, ctypes.c_void_p]
_fem.restype = ctypes.c_int
_v0, _J, _iJ, _dJ = (ctypes.c_double * 3)(), (ctypes.c_double * 9)(), (ctypes.c_double * 9)(), ctypes.c_double()


def compute_cell_geometry_fem(dm, c):
    """(v0, J, invJ, detJ) for cell c, affine (no quadrature), as dm.computeCellGeometryFEM would."""
    ierr = _fem(dm.handle, c, None, _v0, _J, _iJ, ctypes.byref(_dJ))
    if ierr:
        raise RuntimeError(f"DMPlexComputeCellGeometryFEM failed ({ierr}) on cell {c}")
    return list(_v0), list(_J), list(_iJ), _dJ.value


def check(path):
    t0 = time.time()
    dm = PETSc.DMPlex().createFromFile(path, interpolate=True)
    errs = []
    dim = dm.getDimension()
    if dim != 3:
        errs.append(f"dimension {dim}")
    vs, ve = dm.getDepthStratum(0)
    es, ee = dm.getDepthStratum(1)
    fs, fe = dm.getHeightStratum(1)
    cs, ce = dm.getHeightStratum(0)
    nv, nc = ve - vs, ce - cs
    coords = dm.getCoordinatesLocal().getArray().reshape(-1, 3)

    ndet_pos = ndet_neg = nbad = 0
    vol = 0.0
    sgn_closure = []  # signed volume from closure vertex order, for comparison
    for c in range(cs, ce):
        if dm.getConeSize(c) != 4:
            nbad += 1
            continue
        pts = dm.getTransitiveClosure(c)[0]
        vtx = [p for p in pts if vs <= p < ve]
        if len(vtx) != 4:
            nbad += 1
            continue
        X = coords[np.array(vtx) - vs]
        sgn_closure.append(np.dot(X[1] - X[0], np.cross(X[2] - X[0], X[3] - X[0])))
        _, _, _, detJ = (dm.computeCellGeometryFEM(c) if hasattr(dm, "computeCellGeometryFEM")
                         else compute_cell_geometry_fem(dm, c))
        if detJ > 0:
            ndet_pos += 1
        else:
            ndet_neg += 1
        vol += abs(detJ) * 4.0 / 3.0  # PETSc reference tet is [-1,1]^3 simplex, volume 4/3
    if nbad:
        errs.append(f"{nbad} non-tetrahedral cells")
    if ndet_neg:
        errs.append(f"{ndet_neg} cells with detJ <= 0 ({ndet_pos} positive)")
    sc = np.array(sgn_closure)

    euler = nv - (ee - es) + (fe - fs) - nc
    if euler != 1:
        errs.append(f"Euler characteristic {euler} != 1")
    bfaces = [f for f in range(fs, fe) if dm.getSupportSize(f) == 1]
    lab = dm.getLabel("Face Sets")
    nunl = sum(1 for f in bfaces if lab is None or lab.getValue(f) < 0)
    if nunl:
        errs.append(f"{nunl} of {len(bfaces)} boundary faces without a Face Sets value")
    fsets = {}
    if lab is not None:
        for v in lab.getValueIS().getIndices():
            fsets[int(v)] = lab.getStratumSize(v)
    lo, hi = coords.min(axis=0), coords.max(axis=0)
    name = os.path.basename(path)
    status = "OK" if not errs else "FAIL: " + "; ".join(errs)
    print(f"{name:18s} dim={dim} V={nv:6d} C={nc:7d} DOF={3*nv:6d} bfaces={len(bfaces):6d} "
          f"vol={vol:.6f} detJ>0:{ndet_pos}/{nc} closure-order-signed-vol>0:{int((sc>0).sum())}/{len(sc)} "
          f"bbox=[{lo[0]:.3g},{hi[0]:.3g}]x[{lo[1]:.3g},{hi[1]:.3g}]x[{lo[2]:.3g},{hi[2]:.3g}] "
          f"FaceSets={fsets} ({time.time()-t0:.1f}s) {status}")
    return not errs


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    paths = sys.argv[1:] or sorted(glob.glob(os.path.join(here, "*.msh")))
    ok = all([check(p) for p in paths])
    sys.exit(0 if ok else 1)


if __name__ == "__main__":
    main()
