/* The constraint schemes (src/scheme/): each step's contacts to forces and corrected motions */
#pragma once

#include "../body/body.h"

typedef struct {
  PetscInt  contacts, rows, sweeps;
  PetscReal residual;
  PetscInt  newton; /* Newton iterations (recursive schemes; 1 for explicit) */
} FCSchemeStats;

/* FCScheme: a constraint scheme (src/scheme/), -constraint_scheme explicit|standard|fast. It owns
   the contact solver and, per step, turns the contact set into forces and corrected motions. */
#define FCSCHEMEEXPLICIT "explicit"
#define FCSCHEMESTANDARD "standard"
#define FCSCHEMEFAST "fast"
PETSC_EXTERN PetscFunctionList FCSchemeList;
PETSC_INTERN PetscErrorCode    FCSchemeRegisterAll(void);
PETSC_INTERN PetscErrorCode    FCSchemeCreate(MPI_Comm, PetscInt nbodies, FCBody bodies[], FCScheme *);
PETSC_INTERN PetscErrorCode    FCSchemeSetType(FCScheme, FCSchemeType);
PETSC_INTERN PetscErrorCode    FCSchemeSetFromOptions(FCScheme);
/* One step's contacts: forces (set->c[k].force, state) and the bodies' corrected dv */
PETSC_INTERN PetscErrorCode FCSchemeSolve(FCScheme, FCContactSet *, const FCContactSet *previous, FCSchemeStats *);
/* Stops the step (PETSC_ERR_CONV_FAILED) when the solve ended above -pgs_fail_residual */
PETSC_INTERN PetscErrorCode FCSchemeCheck(FCScheme, PetscInt step, const FCSchemeStats *);
/* bytes this rank keeps from step to step: W_H and W_k (0 for a scheme that keeps neither) */
PETSC_INTERN PetscErrorCode FCSchemeGetHeldMemory(FCScheme, PetscReal *wh, PetscReal *wk);
PETSC_INTERN PetscErrorCode FCSchemeDestroy(FCScheme *);

struct _FCContactSetView {
  const FCContactSet      *set;
  const FCSchemeStats     *stats;
  const FCContactMeasures *measures;
};
