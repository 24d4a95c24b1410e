/* Step control (src/scene/stepcontrol.c): a failed step redone with half the time step */
#pragma once

#include "../fcimpl.h"

typedef struct {
  PetscBool    on;         /* -time_step_control */
  PetscReal    h;          /* the requested step (-time_step) */
  PetscReal    hmin;       /* -time_step_min */
  PetscReal    hnow;       /* the sub-step in use (h when nothing failed) */
  PetscInt     grow_after; /* -time_step_grow_after */
  PetscInt     successes;  /* sub-steps accepted since the last cut or growth */
  PetscInt     fail_at;    /* -time_step_fail_at: a test hook */
  PetscInt     cuts;       /* over the run */
  PetscReal    smallest;   /* the smallest sub-step of the run */
  PetscInt     nbodies;    /* the snapshot: each body's state, the last contacts */
  PetscReal  **state;
  FCContactSet previous;
} FCStepControl;

PETSC_INTERN PetscErrorCode FCStepControlSetFromOptions(FCStepControl *, MPI_Comm, PetscReal h);
PETSC_INTERN PetscErrorCode FCStepControlSetUp(FCStepControl *, PetscInt nbodies, FCBody[]);
PETSC_INTERN PetscErrorCode FCStepControlSave(FCStepControl *, FCBody[], const FCContactSet *previous);
PETSC_INTERN PetscErrorCode FCStepControlRestore(FCStepControl *, FCBody[], PetscReal t, FCContactSet *previous);
PETSC_INTERN PetscReal      FCStepControlNext(FCStepControl *, PetscReal done);
PETSC_INTERN void           FCStepControlCut(FCStepControl *, PetscReal hs, PetscBool *again);
PETSC_INTERN PetscErrorCode FCStepControlDestroy(FCStepControl *);
/* The state a restart carries (h, the sub-step in use, its successes), and back: taken only where
   the restarted run has the same -time_step */
PETSC_INTERN void FCStepControlGetState(const FCStepControl *, PetscReal state[3]);
PETSC_INTERN void FCStepControlSetState(FCStepControl *, const PetscReal state[3]);
