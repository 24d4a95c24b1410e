#!/usr/bin/python3
"""Convert a gmsh mesh to PETSc's DMPlex HDF5 format, which fecontact reads in parallel:
each rank reads a slice of the cells and vertices, and the mesh is then partitioned. A gmsh file
is read whole on rank 0 instead, which bounds the mesh size by rank 0's memory (docs/scaling.md).

    /usr/bin/python3 scripts/msh2h5.py meshes/table1_36k.msh meshes/table1_36k.h5
    mpirun -n 4 build/fecontact -options_file input/table1_36k.opts -box_dm_plex_filename meshes/table1_36k.h5
"""
import sys

import petsc4py

petsc4py.init(sys.argv[:1])
from petsc4py import PETSc  # noqa: E402

if len(sys.argv) != 3:
    sys.exit(__doc__)
src, dst = sys.argv[1], sys.argv[2]
dm = PETSc.DMPlex().createFromFile(src, interpolate=True)
dm.setName("mesh")
viewer = PETSc.Viewer().createHDF5(dst, mode="w")
viewer.pushFormat(PETSc.Viewer.Format.HDF5_PETSC)
dm.view(viewer)
viewer.popFormat()
viewer.destroy()
print("wrote %s (%d cells)" % (dst, dm.getHeightStratum(0)[1] - dm.getHeightStratum(0)[0]))
