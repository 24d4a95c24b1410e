/* Shared tessellation helpers of the analytic shapes (pictures only). */
#pragma once
#include "../fcimpl.h"

/* A sphere of radius r whose two hemispheres are pulled apart along z by L (L = 0: sphere,
   L > 0: capsule), nlat rings per hemisphere, nlon vertices per ring. */
PETSC_INTERN PetscErrorCode FCTessellateCapsule(PetscReal r, PetscReal L, PetscInt nlat, PetscInt nlon, PetscInt *nv,
                                                PetscReal **xyz, PetscInt *nt, PetscInt **tri);
