/* One requested time step of a scene (FCSceneStep): free motion (eq. 5) -> [contacts] -> integration
   (eq. 2) -> the end-of-step measures and checks -> output, in sub-steps of h / 2^k where one fails
   (step control: stepcontrol.c; docs/method.md, 2.5). */
#include "sceneimpl.h"

static PetscErrorCode PlantedFailure(FCScene s, PetscInt step)
{
  PetscFunctionBegin;
  if (step != s->control.fail_at) PetscFunctionReturn(0);
  s->control.fail_at = 0; /* once */
  SETERRQ(s->comm, PETSC_ERR_CONV_FAILED, "a failure planted by -time_step_fail_at %" PetscInt_FMT, step);
}

/* The crossing audit's verdict on a sub-step of hs with -contact_crossings redo: a step failure, which step control
   redoes with half the step, while the step has been cut fewer than -contact_crossings_cuts times and is above
   -time_step_min; then the sub-step is kept with its crossings counted (docs/method.md, 2.7) */
static PetscErrorCode Crossed(FCScene s, PetscReal hs)
{
  const FCContactMeasures *m = &s->measures;
  PetscReal                floor;

  PetscFunctionBegin;
  if (s->pairs->crossings != FC_CROSSINGS_REDO || !m->crossings || !s->control.on) PetscFunctionReturn(0);
  floor = s->h / PetscPowReal(2.0, (PetscReal)s->pairs->crossing_cuts);
  if (hs <= floor * (1.0 + 1e-9) || hs < 2.0 * s->control.hmin * (1.0 - 1e-9)) PetscFunctionReturn(0);
  SETERRQ(s->comm, PETSC_ERR_CONV_FAILED,
          "%" PetscInt_FMT " point(s) or edge(s) went through another body's surface over the step, the deepest ending "
          "%g m behind it (-contact_crossings redo)",
          m->crossings, (double)m->crossing_depth);
}

/* One sub-step from s->t with the bodies' time step hs: free motion (eq. 5) -> [contacts] ->
   integration (eq. 2) -> the end-of-step measures and checks; `step` is the requested step it belongs to */
static PetscErrorCode SubStep(FCScene s, PetscInt step, PetscReal hs, PetscBool *failed)
{
  PetscFunctionBegin;
  *failed = PETSC_FALSE;
  if (s->pairs->n) PetscCall(FCCollisionAuditStart(s->collision));
  for (PetscInt i = 0; i < s->nbodies; i++) STEP_TRY(s, failed, FCBodyComputeFreeMotion(s->bodies[i], s->t));
  if (s->pairs->n) {
    PetscCall(FCPhaseBegin(FC_PHASE_COLLISION));
    PetscCall(FCCollisionDetect(s->collision, PETSC_TRUE, &s->set));
    PetscCall(FCPhaseEnd(FC_PHASE_COLLISION));
    PetscCall(FCSceneSolveContacts(s, step, failed)); /* with the nonlinear bodies settled (settle.c) */
    if (*failed) PetscFunctionReturn(0);
    PetscCall(FCContactSetCopy(&s->set, &s->previous));
  }
  for (PetscInt i = 0; i < s->nbodies; i++) PetscCall(FCBodyIntegrate(s->bodies[i], s->t));
  if (s->pairs->n) { /* accuracy of the step on the real end-of-step geometry */
    PetscCall(FCPhaseBegin(FC_PHASE_COLLISION));
    PetscCall(FCCollisionEndGaps(s->collision, &s->set));
    FCContactSetMeasure(&s->set, s->pairs->check_cone, s->pairs->check_complementarity, &s->measures);
    PetscCall(FCCollisionCountIntersections(s->collision, &s->measures.intersections));
    PetscCall(FCCollisionCountCrossings(s->collision, &s->measures.crossings, &s->measures.crossing_depth));
    PetscCall(FCPhaseEnd(FC_PHASE_COLLISION));
    STEP_TRY(s, failed, Crossed(s, hs));
  }
  for (PetscInt i = 0; i < s->nbodies; i++) STEP_TRY(s, failed, FCBodyCheckState(s->bodies[i], step));
  STEP_TRY(s, failed, FCEnergyGuardCheck(&s->guard, s->comm, s->nbodies, s->bodies, step, s->t + hs, hs));
  STEP_TRY(s, failed, PlantedFailure(s, step));
  PetscFunctionReturn(0);
}

/* One requested time step of -time_step h, in sub-steps of h / 2^k where one fails (step control) */
static PetscErrorCode SceneStep(FCScene s)
{
  PetscReal      timing[FC_PHASE_NUM + 1]; /* per phase, then the step's wall time */
  PetscLogDouble now;
  PetscReal      tstart, done = 0.0;
  PetscInt       step = s->step + 1;

  PetscFunctionBegin;
  PetscCall(FCSceneSetUp(s));
  PetscCheck(s->step < s->nsteps, s->comm, PETSC_ERR_USER_INPUT,
             "The scene is at step %" PetscInt_FMT ", the last of -time_steps %" PetscInt_FMT
             ": no further step (raise -time_steps)",
             s->step, s->nsteps);
  tstart      = s->t;
  s->substeps = 0;
  s->hsub     = s->h;
  while (done < s->h) {
    PetscReal hs = s->control.on ? FCStepControlNext(&s->control, done) : s->h;
    PetscBool failed;
    for (PetscInt i = 0; i < s->nbodies; i++) PetscCall(FCBodyChangeTimeStep(s->bodies[i], hs));
    if (s->control.on) PetscCall(FCStepControlSave(&s->control, s->bodies, &s->previous));
    PetscCall(SubStep(s, step, hs, &failed));
    if (failed) {
      PetscBool again;
      char      why[1024];
      PetscCall(PetscStrncpy(why, FCGetLastErrorMessage(), sizeof(why)));
      FCStepControlCut(&s->control, hs, &again);
      PetscCheck(again, s->comm, PETSC_ERR_CONV_FAILED,
                 "%s [step control: at the smallest time step, %g s (-time_step_min %g)]", why, (double)hs,
                 (double)s->control.hmin);
      PetscCall(FCStepControlRestore(&s->control, s->bodies, s->t, &s->previous));
      s->guard.reported = PETSC_FALSE;
      if (!s->quiet)
        PetscCall(PetscPrintf(s->comm, "step %" PetscInt_FMT " redone from t = %.6g s with a time step of %g s: %s\n",
                              step, (double)s->t, (double)s->control.hnow, why));
      continue;
    }
    done += hs;
    s->substeps++;
    s->hsub = PetscMin(s->hsub, hs);
    s->control.successes++;
    s->t = tstart + done;
  }
  if (s->substeps > 1) s->steps_cut++;
  for (PetscInt i = 0; i < s->nbodies; i++) { /* elements inside out at the step's end (its last sub-step's check) */
    FCInverted inv;
    PetscBool  has;
    PetscCall(FCBodyGetInverted(s->bodies[i], &inv, &has));
    if (!has || !inv.count) continue;
    s->inverted[i].worst = s->inverted[i].steps ? PetscMin(s->inverted[i].worst, inv.min_J) : inv.min_J;
    s->inverted[i].most  = PetscMax(s->inverted[i].most, inv.count);
    s->inverted[i].steps++;
  }
  if (s->pairs->n) {
    if (s->measures.intersections) s->checks.intersecting++;
    if (s->measures.crossings) s->checks.crossed++;
    if (s->measures.beyond) s->checks.beyond++;
    s->checks.cone            = PetscMax(s->checks.cone, s->measures.cone_violation);
    s->checks.complementarity = PetscMax(s->checks.complementarity, s->measures.max_complementarity);
  }
  s->step++;
  s->t = s->t0 + (s->step - s->step0) * s->h; /* no drift from repeated additions */
  /* per phase the largest time of a rank; the step's wall time (the ranks meet here every step, so
     the time since the last meeting, largest over the ranks) is not their sum: a rank that waits
     for another in one phase does not add that wait to the step twice */
  PetscCall(FCPhaseGetTimes(timing));
  PetscCall(PetscTime(&now));
  timing[FC_PHASE_NUM] = (PetscReal)(now - s->tmark);
  s->wall += now - s->tmark;
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, timing, FC_PHASE_NUM + 1, MPIU_REAL, MPIU_MAX, s->comm));
  PetscCall(PetscTime(&s->tmark));
  for (int p = 0; p < FC_PHASE_NUM; p++) s->phase_total[p] += timing[p];
  PetscCall(FCMemoryUpdate(s->scheme, s->nbodies, s->bodies, s->memory));
  PetscCall(FCPhaseResetTimes());
  /* the output of this step (frame and flush) is counted in the next step's row */
  PetscCall(FCOutputRecordStep(s->output, s->step, s->t, timing, timing[FC_PHASE_NUM], s->substeps, s->hsub, s->nbodies,
                               s->bodies));
  if (s->pairs->n) {
    struct _FCContactSetView v = {&s->set, &s->stats, &s->measures};
    PetscCall(FCOutputRecordContacts(s->output, &v));
  }
  if (s->step % s->every == 0 || s->step == s->nsteps) PetscCall(FCSceneWriteOutputStep(s));
  PetscFunctionReturn(0);
}

/* collective failure: an error on one rank is raised on every rank (FCErrorAgree) */
PetscErrorCode FCSceneStep(FCScene s)
{
  PetscFunctionBegin;
  FCValidPointer(s, 1);
  PetscCall(FCErrorAgree(s->comm, SceneStep(s)));
  PetscFunctionReturn(0);
}
