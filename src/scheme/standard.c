/* Algorithm 2: recursive corrective motion with the standard update, the honest baseline of the
   fast scheme. Newton iteration k:
       W_k = sum_b J_b,k A_b^-1 J_b,k^T, rebuilt through solves with the step's factorization by
             the bodies' compliance builder (-compliance_type)                          (eq. 17)
       PGS on the total force lambda (warm-started from the previous iteration)
       dv_b = dv_free,b + h A_b^-1 J_b,k^T lambda                                       (eq. 22, 24)
       proximity positions p_{k+1} = G(q_{k+1}) measured on the corrected state         (eq. 6)
       frames and gaps re-linearized at p_{k+1} as in the fast scheme (recursive.c)
   With a fixed A in the step (both schemes assemble A at its start) and fixed proximity maps it
   gives the fast scheme's forces and positions to round-off; it costs a solve per contact row
   per iteration instead of two matrix products. Options: -newton_max_it, -newton_tol (recursive.c). */
#include "schemeimpl.h"

/* W (M^2), replicated */
static PetscErrorCode Memory_Standard(FCScheme scheme, const FCContactSet *set, PetscReal *bytes, const char **what)
{
  PetscFunctionBegin;
  *bytes = 8.0 * (PetscReal)set->nrows * set->nrows;
  *what  = "dense W_k";
  PetscFunctionReturn(0);
}

static PetscErrorCode Solve_Standard(FCScheme scheme, FCContactSet *set, const FCContactSet *previous,
                                     FCSchemeStats *st)
{
  PetscInt         nc = set->n, n3 = 3 * set->n, M = set->nrows, *dims;
  PetscReal       *W, *dfree, *d0, *d, *q, *qold, *mu, *lambda, *x, *Fw, change = 0.0;
  FCContactProblem prob;
  PetscBool        conv;

  PetscFunctionBegin;
  for (PetscInt b = 0; b < scheme->nbodies; b++) PetscCall(FCBodySaveFreeMotion(scheme->bodies[b]));
  PetscCall(PetscMalloc6(n3, &dfree, n3, &d0, n3, &d, M, &q, M, &qold, nc, &mu));
  PetscCall(PetscMalloc5(nc, &dims, M, &lambda, M * M, &W, 6 * nc, &x, 3 * nc, &Fw));
  FCSchemeStartLinearization(set, dfree, d0, q, mu, dims);
  FCContactSetWarmStart(set, previous, lambda);
  for (PetscInt it = 1; it <= scheme->newton_max_it; it++) {
    PetscInt sweeps;
    PetscCall(PetscLogEventBegin(FC_EVENT_NEWTON, 0, 0, 0, 0));
    PetscCall(FCPhaseBegin(FC_PHASE_REBUILD_W));
    PetscCall(FCSchemeCompliance(scheme, set, NULL, W, NULL));
    PetscCall(FCPhaseEnd(FC_PHASE_REBUILD_W));
    FCContactSetNormalCompliance(set, W);
    PetscCall(FCPhaseBegin(FC_PHASE_CONTACT_SOLVE));
    PetscCall(FCContactProblemCreateDense(nc, dims, mu, W, q, &prob));
    PetscCall(FCSchemeContactSolve(scheme, set, prob, lambda));
    PetscCall(FCContactSolverGetConvergence(scheme->solver, &sweeps, &st->residual, &conv));
    PetscCall(FCContactProblemDestroy(&prob));
    st->sweeps += sweeps;
    PetscCall(FCPhaseEnd(FC_PHASE_CONTACT_SOLVE));
    FCContactSetStoreForces(set, lambda);
    /* corrective motion of the total force from dv_free */
    PetscCall(FCPhaseBegin(FC_PHASE_CORRECTION));
    for (PetscInt b = 0; b < scheme->nbodies; b++) PetscCall(FCBodyRestoreFreeMotion(scheme->bodies[b]));
    PetscCall(FCSchemeCorrect(scheme, set, lambda));
    PetscCall(FCPhaseEnd(FC_PHASE_CORRECTION));
    st->newton = it;
    PetscCall(PetscLogEventEnd(FC_EVENT_NEWTON, 0, 0, 0, 0));
    if (it == scheme->newton_max_it) break;
    /* p_{k+1} = G(q_{k+1}): the proximity points on the corrected state, summed over the ranks */
    PetscCall(FCPhaseBegin(FC_PHASE_PROXIMITY));
    PetscCall(PetscArrayzero(x, 6 * nc));
    for (PetscInt k = 0; k < nc; k++)
      for (int s = 0; s < 2; s++) {
        PetscCall(FCBodyAddTrialPosition(scheme->bodies[set->c[k].body[s]], &set->c[k].prox[s], &x[6 * k + 3 * s]));
      }
    PetscCall(MPIU_Allreduce(MPI_IN_PLACE, x, 6 * nc, MPIU_REAL, MPIU_SUM, scheme->comm));
    for (PetscInt k = 0; k < nc; k++)
      for (int i = 0; i < 3; i++) d[3 * k + i] = x[6 * k + i] - x[6 * k + 3 + i];
    for (PetscInt k = 0; k < nc; k++) FCContactForceWorld(&set->c[k], &Fw[3 * k]); /* before the frames move */
    PetscCall(PetscArraycpy(qold, q, M));
    PetscCall(FCSchemeLinearize(scheme, set, dfree, d0, d, q, &change));
    PetscCall(FCPhaseEnd(FC_PHASE_PROXIMITY));
    if (FCSchemeConverged(scheme, M, q, qold, change)) break;
    /* warm start in the new frames: the force of this iteration, projected */
    for (PetscInt k = 0; k < nc; k++)
      for (PetscInt a = 0; a < set->c[k].dim; a++)
        lambda[set->c[k].row + a] = FCDot(a == 0 ? set->c[k].n : (a == 1 ? set->c[k].t1 : set->c[k].t2), &Fw[3 * k]);
  }
  FCContactSetUpdateStates(set);
  PetscCall(PetscFree6(dfree, d0, d, q, qold, mu));
  PetscCall(PetscFree5(dims, lambda, W, x, Fw));
  PetscFunctionReturn(0);
}

PetscErrorCode FCSchemeCreate_Standard(FCScheme scheme)
{
  PetscFunctionBegin;
  scheme->ops.setfromoptions = FCSchemeRecursiveSetFromOptions;
  scheme->ops.memory         = Memory_Standard;
  scheme->ops.solve          = Solve_Standard;
  PetscFunctionReturn(0);
}
