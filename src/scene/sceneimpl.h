/* The scene's state, shared by its files: scene.c (options, set-up, the run, the summary), step.c (one
   requested step and its sub-steps), settle.c (its contacts with nonlinear bodies settled) */
#pragma once

#include "../fcimpl.h"
#include "stepcontrol.h"
#include "settle.h"

struct _p_FCScene {
  PetscBool      quasistatic; /* -time_integration static */
  MPI_Comm       comm;
  PetscInt       nbodies;
  FCBody         bodies[FC_MAX_BODIES];
  PetscReal      h, t, gravity[3];
  PetscInt       nsteps, step, every, fields; /* fields: the -output_fields mask */
  PetscInt       written;   /* the step of the last output step written completely (frame and restart state) */
  PetscReal      t0;        /* the time of step step0: 0 and 0, or a restart's stored time and step; step k */
  PetscInt       step0;     /* is at t0 + (k - step0) h, whatever time step the earlier run had */
  FCEnergyGuard  guard;     /* -energy_growth_limit (energy.c) */
  FCStepControl  control;   /* -time_step_control (stepcontrol.c) */
  PetscInt       substeps;  /* sub-steps of the last requested step (1 when nothing failed) */
  PetscReal      hsub;      /* the smallest of them */
  PetscInt       steps_cut; /* requested steps with a cut, over the run */
  char           output_file[PETSC_MAX_PATH_LEN], restart[PETSC_MAX_PATH_LEN];
  PetscBool      quiet, setupcalled;
  FCOutput       output;
  FCProgress     progress;
  PetscReal      phase_total[FC_PHASE_NUM];
  PetscReal      memory[FC_MEMORY_NUM]; /* this rank's largest over the steps (memory.c) */
  PetscLogDouble tmark; /* when the ranks last met at the end of a step (FCSceneStep: the wall time of a step) */
  PetscLogDouble wall;  /* the steps' wall time so far (the summary's) */
  /* contact */
  FCCollision           collision; /* the contact pairs and their detection (src/collision/pairs.c) */
  const FCContactPairs *pairs;     /* the collision's pairs and detection options */
  FCContactSet          set;
  FCContactSet          previous; /* last step's contacts and forces: warm start of the scheme */
  FCScheme              scheme;   /* owns the contact solver */
  FCSchemeStats         stats;
  FCContactMeasures     measures;
  FCSettle              settle;      /* -contact_settle_* (settle.c) */
  struct {                           /* the end-of-step checks over the steps run (the summary's) */
    PetscInt  intersecting, beyond;  /* steps with points inside another body; with contacts beyond the check */
    PetscInt  crossed;               /* steps that kept crossings (-contact_crossings count, or at the smallest step) */
    PetscReal cone, complementarity; /* the worst cone violation and contact natural-map error of the run */
  } checks;
  struct { /* per FE body over the steps run (the summary's): the steps that ended with an element inside out, */
    PetscInt  steps, most; /* the most at the end of one, the smallest J at their ends */
    PetscReal worst;
  } inverted[FC_MAX_BODIES];
};

/* A call of a sub-step whose failure step control redoes (FCErrorIsStepFailure: raised where nothing
   of the step is left to free, on every rank alike): with step control on, such an error ends the
   sub-step with *failed set and its message kept (FCGetLastErrorMessage); any other error, or any error
   with step control off, stops the run as always */
#define STEP_TRY(s, failed, call)                                                                                      \
  do {                                                                                                                 \
    PetscErrorCode ierr_;                                                                                              \
    if ((s)->control.on) PetscCall(FCPushStepErrorHandler());                                                          \
    ierr_ = (call);                                                                                                    \
    if ((s)->control.on) PetscCall(PetscPopErrorHandler());                                                            \
    if (ierr_ && (s)->control.on && FCErrorIsStepFailure(ierr_)) {                                                     \
      *(failed) = PETSC_TRUE;                                                                                          \
      PetscFunctionReturn(0);                                                                                          \
    }                                                                                                                  \
    PetscCall(ierr_);                                                                                                  \
  } while (0)

/* The contacts of a sub-step: the scheme's solve and check, with the nonlinear bodies settled (settle.c) */
PETSC_INTERN PetscErrorCode FCSceneSolveContacts(FCScene, PetscInt step, PetscBool *failed);

/* The state of the current step as a frame and a restart state (scene.c) */
PETSC_INTERN PetscErrorCode FCSceneWriteOutputStep(FCScene);
