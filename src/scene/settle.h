/* The contacts of a sub-step solved with the nonlinear bodies settled (settle.c) */
#pragma once
#include "../fcimpl.h"

typedef struct {
  PetscInt     max_it; /* -contact_settle_max_it: solves after the first */
  PetscReal    rtol;   /* -contact_settle_rtol */
  FCContactSet last;   /* the forces of the last solve: the warm start of the next */
} FCSettle;

PETSC_INTERN PetscErrorCode FCSettleSetFromOptions(FCSettle *, MPI_Comm);
PETSC_INTERN PetscErrorCode FCSettleDestroy(FCSettle *);
