/* The contacts of a sub-step, with its nonlinear bodies settled (src/body/fem_nonlinear.c;
   docs/method.md, 2.6). The scheme solves the contact problem linearized at the free motions
   (eq. 20's correction is linear); each nonlinear body then solves its equilibrium with those forces,
   its contact vertices held by springs where the correction put them. While the springs of a body
   carry more than -contact_settle_rtol of its contact forces, the bodies' free motions are linearized
   at the settled states (their A and W_b rebuilt there, the contacts' free positions moved with them)
   and the scheme solves again, warm-started from its last forces, at most -contact_settle_max_it more
   times: a Newton iteration on the coupled problem whose linear solve is the contact problem. A
   linear or rigid body has nothing to settle: one solve, as before. */
#include "sceneimpl.h"

PetscErrorCode FCSettleSetFromOptions(FCSettle *st, MPI_Comm comm)
{
  PetscFunctionBegin;
  st->max_it = 4;
  st->rtol   = 1e-8;
  PetscOptionsBegin(comm, NULL, "Settling of nonlinear bodies", "FCScene");
  PetscCall(FCOptionsIntRange(PetscOptionsObject, "-contact_settle_max_it",
                              "Solves of the contact problem after the first, linearized at nonlinear bodies' "
                              "settled states (0: one solve and one settling)",
                              0, PETSC_MAX_INT, &st->max_it, NULL));
  PetscCall(FCOptionsReal(PetscOptionsObject, "-contact_settle_rtol",
                          "Solve again while the springs of a nonlinear body's settling carry more than this fraction "
                          "of its largest vertex contact force",
                          &st->rtol, NULL));
  PetscOptionsEnd();
  PetscCheck(st->rtol >= 0.0, comm, PETSC_ERR_USER_INPUT, "Option -contact_settle_rtol must be >= 0, got %g",
             (double)st->rtol);
  PetscFunctionReturn(0);
}

PetscErrorCode FCSettleDestroy(FCSettle *st)
{
  PetscFunctionBegin;
  PetscCall(FCContactSetDestroy(&st->last));
  PetscFunctionReturn(0);
}

/* The free positions of the contacts' points on the bodies relinearized (moving[b]): at the dv each
   now holds (the positions of the other bodies' points are those of their restored free motions) */
static PetscErrorCode MoveFreePoints(FCScene s, const PetscBool moving[])
{
  FCContactSet *set = &s->set;
  PetscReal    *x;

  PetscFunctionBegin;
  PetscCall(PetscCalloc1(6 * set->n + 1, &x));
  for (PetscInt k = 0; k < set->n; k++)
    for (int j = 0; j < 2; j++)
      if (moving[set->c[k].body[j]])
        PetscCall(FCBodyAddTrialPosition(s->bodies[set->c[k].body[j]], &set->c[k].prox[j], &x[6 * k + 3 * j]));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, x, 6 * set->n, MPIU_REAL, MPIU_SUM, s->comm));
  for (PetscInt k = 0; k < set->n; k++)
    for (int j = 0; j < 2; j++)
      if (moving[set->c[k].body[j]])
        for (int d = 0; d < 3; d++) set->c[k].pfree[j][d] = x[6 * k + 3 * j + d];
  PetscCall(PetscFree(x));
  PetscFunctionReturn(0);
}

/* The scheme's solve, its check, and the settling of the nonlinear bodies (header); *failed as
   STEP_TRY sets it */
PetscErrorCode FCSceneSolveContacts(FCScene s, PetscInt step, PetscBool *failed)
{
  FCSettle *st = &s->settle;
  PetscInt  sweeps;

  PetscFunctionBegin;
  *failed = PETSC_FALSE;
  for (PetscInt i = 0; i < s->nbodies; i++) PetscCall(FCBodySaveFreeMotion(s->bodies[i]));
  STEP_TRY(s, failed, FCSchemeSolve(s->scheme, &s->set, &s->previous, &s->stats));
  STEP_TRY(s, failed, FCSchemeCheck(s->scheme, step, &s->stats));
  sweeps = s->stats.sweeps;
  for (PetscInt it = 0;; it++) {
    PetscReal held = 0.0;
    PetscBool moving[FC_MAX_BODIES];
    for (PetscInt i = 0; i < s->nbodies; i++) {
      PetscReal m;
      STEP_TRY(s, failed, FCBodySettle(s->bodies[i], &s->set, s->t, &m));
      moving[i] = m > 0.0 ? PETSC_TRUE : PETSC_FALSE;
      held      = PetscMax(held, m);
    }
    if (held <= st->rtol || it == st->max_it || !s->set.n) break;
    for (PetscInt i = 0; i < s->nbodies; i++) {
      PetscCall(FCBodyRestoreFreeMotion(s->bodies[i]));
      if (moving[i]) STEP_TRY(s, failed, FCBodyRelinearize(s->bodies[i])); /* A there may be indefinite */
    }
    PetscCall(MoveFreePoints(s, moving));
    PetscCall(FCContactSetCopy(&s->set, &st->last));
    STEP_TRY(s, failed, FCSchemeSolve(s->scheme, &s->set, &st->last, &s->stats));
    STEP_TRY(s, failed, FCSchemeCheck(s->scheme, step, &s->stats));
    sweeps += s->stats.sweeps;
  }
  s->stats.sweeps = sweeps;
  PetscFunctionReturn(0);
}
