/* Shapes (src/shape/): analytic geometry of rigid and kinematic bodies */
#pragma once

#include "../util/util.h"

struct _p_FCShape {
  char      type[FC_MAX_NAME];
  PetscReal radius, half_extents[3], length, normal[3];
  PetscBool bounded;    /* a plane is not: it has no mass and can only be kinematic */
  PetscBool smooth;     /* no edges or corners (sphere, capsule): -contact_shape_points' kind of contact */
  PetscInt  ncore;      /* a rounded shape is the set of points within `radius` of its core, a point */
  PetscReal core[2][3]; /* (sphere, ncore 1) or a segment (capsule, cylinder: ncore 2), body frame */
  PetscBool flat;       /* ... cut by flat ends through the segment's ends (cylinder); 0 for others */
  void     *data;       /* shape-specific (the mesh of a mesh shape)               */
  PetscErrorCode (*setfromoptions)(PetscOptionItems *, FCShape, const char bodyname[]);
  PetscErrorCode (*setup)(FCShape, MPI_Comm, const char prefix[], const char bodyname[]);
  PetscErrorCode (*destroy)(FCShape);
  /* Volume, and inertia tensor per unit density about the centre, in the body frame */
  PetscErrorCode (*massproperties)(FCShape, PetscReal *volume, PetscReal J[9]);
  /* Signed distance of a body-frame point x to the surface (negative inside), the outward
     unit normal there and the closest surface point (body frame) */
  PetscErrorCode (*distance)(FCShape, const PetscReal x[3], PetscReal *d, PetscReal n[3], PetscReal cp[3]);
  /* Triangulated surface in the body frame for pictures: nv vertices, nt triangles */
  PetscErrorCode (*tessellate)(FCShape, PetscInt *nv, PetscReal **xyz, PetscInt *nt, PetscInt **tri);
};
PETSC_EXTERN PetscFunctionList FCShapeList;
PETSC_INTERN PetscErrorCode    FCShapeRegisterAll(void);
PETSC_INTERN PetscErrorCode FCShapeCreateFromOptions(MPI_Comm, const char prefix[], const char bodyname[], FCShape *);
PETSC_INTERN PetscErrorCode FCShapeDestroy(FCShape *);
