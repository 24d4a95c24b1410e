/* What the scene's files share (src/scene/) */
#pragma once

#include "../body/body.h"
#include "../io/io.h"

/* Memory per rank (src/scene/memory.c): peak RSS and the contact data held, in bytes */
#define FC_MEMORY_NUM 7
PETSC_EXTERN const char *const FCMemoryNames[FC_MEMORY_NUM];
/* after a step: peak[i] = max(peak[i], this rank's value now) */
PETSC_INTERN PetscErrorCode FCMemoryUpdate(FCScheme, PetscInt nbodies, FCBody[], PetscReal peak[FC_MEMORY_NUM]);
/* collective: the ranks' rows printed by rank 0 (print), and written to /memory (NULL output: not) */
PETSC_INTERN PetscErrorCode FCMemoryReport(MPI_Comm, const PetscReal peak[FC_MEMORY_NUM], PetscBool print, FCOutput);

/* The guard on the total energy of the scene (src/scene/energy.c): -energy_growth_limit */
typedef struct {
  PetscReal limit; /* stop when the energy grows by more than limit * scale (0: never) */
  PetscReal E0;    /* total energy at set-up (or at the restart point) */
  PetscReal scale; /* the energy the scene may receive (J) */
  PetscReal Eb0[FC_MAX_BODIES];
  PetscBool reported; /* stops once */
} FCEnergyGuard;
PETSC_INTERN PetscErrorCode FCEnergyGuardSetFromOptions(FCEnergyGuard *, MPI_Comm);
/* speed: the largest speed of separation the contact response may give (0: no contact pairs) */
PETSC_INTERN PetscErrorCode FCEnergyGuardSetUp(FCEnergyGuard *, MPI_Comm, PetscInt nbodies, FCBody[], PetscReal h,
                                               PetscInt nsteps, PetscReal speed);
PETSC_INTERN PetscErrorCode FCEnergyGuardCheck(FCEnergyGuard *, MPI_Comm, PetscInt nbodies, FCBody[], PetscInt step,
                                               PetscReal t, PetscReal h);
