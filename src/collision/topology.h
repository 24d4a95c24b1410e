/* The topology of a body's gathered surface triangles, kept per body for the run (topology.c) */
#pragma once
#include "../fcimpl.h"

/* The reference topology of ntri gathered triangles: nv vertices V (3 each, sorted by
   reference position) with first, a corner (3 t + a) of each, in triangle order; tv, each corner's
   vertex; vt[off[v] .. off[v + 1]), vertex v's triangles in order; the ne interior edges as their
   two half-edges (3 t + a: triangle t's edge from corner a to a + 1), sorted by reference ends */
struct _FCSurfaceTopology {
  PetscInt   ntri, nv, ne;
  PetscReal *X; /* 9 ntri: the triangles' reference corners it was built from */
  PetscReal *V;
  PetscInt  *first, *tv, *off, *vt;
  PetscInt (*edge)[2];
};
/* The topology of the ntri triangles tri of body ib: pairs' cached one (rebuilt if tri is not the
   surface it was built from), or a new one when pairs keeps none; Restore frees that one */
PETSC_INTERN PetscErrorCode FCSurfaceTopologyGet(const FCContactPairs *, PetscInt ib, PetscInt ntri,
                                                 const FCSurfaceTriangle *tri, FCSurfaceTopology **);
PETSC_INTERN PetscErrorCode FCSurfaceTopologyRestore(const FCContactPairs *, FCSurfaceTopology **);
PETSC_INTERN PetscErrorCode FCSurfaceTopologyDestroy(FCSurfaceTopology **);
