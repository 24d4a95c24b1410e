/* Tetrahedral mesh of a body (src/mesh/): reading, validation, per-cell vertex lists, partitioners */
#pragma once

#include "../util/util.h"

typedef struct {
  DM         dm; /* DMPlex, distributed, interpolated                            */
  PetscInt   cStart, cEnd, vStart, vEnd;
  PetscInt  *cellVerts;                      /* (cEnd-cStart) x 4 local vertex points in closure order      */
  PetscReal *X;                              /* (vEnd-vStart) x 3 placed reference coordinates              */
  PetscBool *owned;                          /* (vEnd-vStart) vertex owned by this rank                      */
  IS         vertexNumbering, cellNumbering; /* global numbers (negative: not owned)      */
  PetscInt  *visVert;                        /* owned vertices (local index) in increasing global number    */
  PetscInt  *cellOrigin; /* (cEnd-cStart) each cell's index in the mesh as read, before distribution: the partition */
} FCMesh;
/* src/mesh/partmetis.c: the PetscPartitioner type "metis" (METIS k-way on the gathered cell graph) */
#define FC_PARTITIONER_METIS "metis"
PETSC_INTERN PetscErrorCode FCPartitionerRegisterMetis(void);
/* The largest accepted magnitude of a mesh coordinate (m): a cell's volume, the cube of its size,
   stays finite with room to spare */
#define FC_MESH_MAX_COORDINATE 1e100
PETSC_INTERN PetscErrorCode FCMeshLoad(MPI_Comm, const char prefix[], const char bodyname[], FCMesh *);
/* src/mesh/read.c: the mesh file of -<prefix>dm_plex_filename checked and read on rank 0 into mesh->dm, not
   distributed; fname: the file, distribute: -<prefix>dm_distribute */
PETSC_INTERN PetscErrorCode FCMeshRead(MPI_Comm, const char prefix[], const char bodyname[], FCMesh *,
                                       char fname[PETSC_MAX_PATH_LEN], PetscBool *distribute);
/* src/mesh/partreplay.c: -<body>_partition_file, the partition recorded in an earlier run's output
   (/bodies/<body>/mesh/rank and cell_origin) set on the partitioner of the mesh as read (rank 0);
   nothing without the option */
PETSC_INTERN PetscErrorCode FCMeshPartitionReplay(DM serial, PetscPartitioner, const char prefix[],
                                                  const char bodyname[]);
PETSC_INTERN PetscErrorCode FCMeshTransform(FCMesh *, const PetscReal center[3], const PetscReal R[9],
                                            const PetscReal t[3]);
PETSC_INTERN PetscErrorCode FCMeshCheckCells(FCMesh *, const char bodyname[]);
PETSC_INTERN PetscErrorCode FCMeshComputeMassProperties(FCMesh *, PetscReal *volume, PetscReal centroid[3],
                                                        PetscReal J[9]);
PETSC_INTERN PetscErrorCode FCMeshCreateVisual(FCMesh *, FCBodyVisual *);
PETSC_INTERN PetscErrorCode FCMeshGetBoundary(FCMesh *, PetscInt *nbv, PetscInt **bv, PetscInt *ntri, PetscInt **triv);
PETSC_INTERN PetscErrorCode FCMeshBoundaryLabel(FCMesh *, DMLabel *);
PETSC_INTERN PetscErrorCode FCMeshOrientedFace(FCMesh *, PetscInt face, PetscInt tv[3]);
PETSC_INTERN PetscErrorCode FCMeshDestroy(FCMesh *);
/* src/mesh/region.c: a region of the mesh, "box:x0,y0,z0,x1,y1,z1" (placed coordinates) or a gmsh
   physical group by name or number: vmark[v] = 1 on every local copy of its vertices; its boundary
   faces this rank holds (outward local vertex triples, *nface, *facev) and its cells of this rank
   (cmark[c] = 1), each optional (NULL); option names the option in errors */
PETSC_INTERN PetscErrorCode FCMeshRegion(FCMesh *, const char region[], const char option[], const char bodyname[],
                                         PetscBool vmark[], PetscInt *nface, PetscInt **facev, PetscBool cmark[]);
