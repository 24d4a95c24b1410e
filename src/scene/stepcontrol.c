/* Step control: a step that fails is redone from its start with half the time step, down to
   -time_step_min, and the time step grows back by doubling after successes; the requested steps
   (-time_step, -time_steps, -output_every) keep their times, each made of the sub-steps it took.
   A failure is what a smaller step can cure (FCErrorIsStepFailure, src/util/errors.c): a Newton free
   motion that does not converge, an element turned inside out in a material that resists it, a contact
   solve left above -pgs_fail_residual, a state that is not finite, the energy guard. The scene raises
   them as errors at points where nothing of the step is left to free; with step control on it keeps
   them, restores every body's state and the last contacts from the snapshot taken at the sub-step's
   start, and tries again. The sub-steps are h / 2^k, so that they end exactly on the requested step's
   end; the step doubles after -time_step_grow_after successes when the sub-step then still ends on its
   own grid and within the requested step.
   Options: -time_step_control, -time_step_min, -time_step_grow_after, -time_step_fail_at (a test hook:
   the first sub-step of that requested step fails once); help strings below and docs/options.md. */
#include "../fcimpl.h"
#include "stepcontrol.h"

PetscErrorCode FCStepControlSetFromOptions(FCStepControl *c, MPI_Comm comm, PetscReal h)
{
  PetscFunctionBegin;
  c->on         = PETSC_TRUE;
  c->h          = h;
  c->hnow       = h;
  c->hmin       = h / 1024.0;
  c->grow_after = 2;
  c->fail_at    = 0;
  c->smallest   = h;
  PetscOptionsBegin(comm, NULL, "Step control", "FCScene");
  {
    const char *onoff[] = {"off", "on"};
    PetscInt    a       = 1;
    PetscCall(FCOptionsEList(PetscOptionsObject, "-time_step_control",
                             "Redo a failed step from its start with half the time step (on), or stop (off)", onoff, 2,
                             &a, NULL));
    c->on = a == 1 ? PETSC_TRUE : PETSC_FALSE;
  }
  PetscCall(FCOptionsReal(PetscOptionsObject, "-time_step_min",
                          "Smallest time step of step control (s; default -time_step / 1024)", &c->hmin, NULL));
  PetscCall(FCOptionsIntRange(PetscOptionsObject, "-time_step_grow_after",
                              "Step control: successful sub-steps after which the time step doubles", 1, PETSC_MAX_INT,
                              &c->grow_after, NULL));
  PetscCall(FCOptionsIntRange(PetscOptionsObject, "-time_step_fail_at",
                              "Test hook: the first attempt of this requested step fails once (0: none)", 0,
                              PETSC_MAX_INT, &c->fail_at, NULL));
  PetscOptionsEnd();
  PetscCheck(c->hmin > 0.0 && c->hmin <= h && PetscIsNormalReal(c->hmin), comm, PETSC_ERR_USER_INPUT,
             "Option -time_step_min must be > 0 and at most -time_step %g, got %g", (double)h, (double)c->hmin);
  PetscFunctionReturn(0);
}

/* The buffers of the snapshot: per body its state rows on this rank (src/io/restart.c's layout) */
PetscErrorCode FCStepControlSetUp(FCStepControl *c, PetscInt nbodies, FCBody bodies[])
{
  PetscFunctionBegin;
  if (!c->on) PetscFunctionReturn(0);
  c->nbodies = nbodies;
  PetscCall(PetscCalloc1(nbodies, &c->state));
  for (PetscInt i = 0; i < nbodies; i++) {
    const FCBodyVisual *vis;
    PetscInt            cols;
    PetscBool           pervertex;
    PetscCall(FCBodyGetStateLayout(bodies[i], &cols, &pervertex));
    PetscCall(FCBodyGetVisual(bodies[i], &vis));
    PetscCall(PetscMalloc1((pervertex ? vis->nv : 1) * cols + 1, &c->state[i]));
  }
  PetscFunctionReturn(0);
}

/* The state at the start of a sub-step: the bodies' and the last contacts (the warm start) */
PetscErrorCode FCStepControlSave(FCStepControl *c, FCBody bodies[], const FCContactSet *previous)
{
  PetscFunctionBegin;
  for (PetscInt i = 0; i < c->nbodies; i++) PetscCall(FCBodyGetState(bodies[i], c->state[i]));
  PetscCall(FCContactSetCopy(previous, &c->previous));
  PetscFunctionReturn(0);
}

/* Back to the snapshot, at time t (the bodies' prescribed motions are set there) */
PetscErrorCode FCStepControlRestore(FCStepControl *c, FCBody bodies[], PetscReal t, FCContactSet *previous)
{
  PetscFunctionBegin;
  for (PetscInt i = 0; i < c->nbodies; i++) {
    PetscCall(FCBodySetState(bodies[i], c->state[i]));
    PetscCall(FCBodySetTime(bodies[i], t));
  }
  PetscCall(FCContactSetCopy(&c->previous, previous));
  PetscFunctionReturn(0);
}

/* The next sub-step from time `done` (since the requested step's start) to its end h: the step in use,
   doubled after enough successes where it then still ends on its own grid, never past the end */
PetscReal FCStepControlNext(FCStepControl *c, PetscReal done)
{
  PetscReal left = c->h - done;

  if (c->hnow < c->h && c->successes >= c->grow_after) {
    PetscReal k = done / (2.0 * c->hnow);
    if (PetscAbsReal(k - PetscFloorReal(k + 0.5)) < 1e-6) { /* on the doubled grid */
      c->hnow *= 2.0;
      c->successes = 0;
    }
  }
  return PetscMin(c->hnow, left);
}

/* A failed sub-step of length hs: halve (collective verdict); *again false when below -time_step_min */
void FCStepControlCut(FCStepControl *c, PetscReal hs, PetscBool *again)
{
  c->successes = 0;
  c->hnow      = 0.5 * hs;
  *again       = (PetscBool)(c->on && c->hnow >= c->hmin * (1.0 - 1e-9));
  if (*again) {
    c->cuts++;
    c->smallest = PetscMin(c->smallest, c->hnow);
  }
}

void FCStepControlGetState(const FCStepControl *c, PetscReal state[3])
{
  state[0] = c->h;
  state[1] = c->hnow;
  state[2] = (PetscReal)c->successes;
}

void FCStepControlSetState(FCStepControl *c, const PetscReal state[3])
{
  if (state[0] != c->h || !(state[1] > 0.0 && state[1] <= c->h)) return;
  c->hnow      = state[1];
  c->successes = (PetscInt)state[2];
}

PetscErrorCode FCStepControlDestroy(FCStepControl *c)
{
  PetscFunctionBegin;
  for (PetscInt i = 0; i < c->nbodies && c->state; i++) PetscCall(PetscFree(c->state[i]));
  PetscCall(PetscFree(c->state));
  PetscCall(FCContactSetDestroy(&c->previous));
  PetscFunctionReturn(0);
}
