/* Algorithm 1 (explicit constraint resolution, once per step):
     W = sum_b J_b A_b^-1 J_b^T                               (eq. 17, per-body builders)
     delta_free: normal gap n.(p1 - p2) and tangential displacement t.(dp1 - dp2) after the free motion
     PGS on delta = delta_free + h^2 W lambda, Signorini-Coulomb    (eq. 18-19)
     dv_b = dv_free_b + h A_b^-1 J_b^T lambda                    (eq. 20)                     */
#include "../fcimpl.h"

PetscErrorCode FCSchemeExplicit(MPI_Comm comm, PetscInt nbodies, FCBody bodies[], FCContactSet *set,
                                const FCContactSet *previous, FCContactSolver solver, FCSchemeStats *st)
{
  PetscInt         M = set->nrows, *dims;
  PetscReal       *W, *q, *mu, *lambda, *dfree, *d0;
  FCContactProblem prob;
  PetscBool        conv;

  PetscFunctionBegin;
  FCSchemeStatsReset(set, st);
  if (!set->n) PetscFunctionReturn(0);
  PetscCall(PetscMalloc1(M * M, &W));
  PetscCall(PetscMalloc6(M, &q, set->n, &mu, set->n, &dims, M, &lambda, 3 * set->n, &dfree, 3 * set->n, &d0));
  PetscCall(FCPhaseBegin(FC_PHASE_COMPLIANCE));
  PetscCall(FCSchemeCompliance(nbodies, bodies, set, W));
  PetscCall(FCPhaseEnd(FC_PHASE_COMPLIANCE));
  FCContactSetNormalCompliance(set, W);
  FCSchemeStartLinearization(set, dfree, d0, q, mu, dims);
  PetscCall(FCPhaseBegin(FC_PHASE_CONTACT_SOLVE));
  PetscCall(FCContactProblemCreateDense(set->n, dims, mu, W, q, &prob));
  /* warm start: the force of the same contact (pair, side-1 point) in the previous step */
  PetscCall(PetscArrayzero(lambda, M));
  for (PetscInt k = 0; previous && k < set->n; k++) {
    const FCContact *old = FCContactSetFind(previous, &set->c[k]);
    if (old)
      for (PetscInt a = 0; a < set->c[k].dim; a++) lambda[set->c[k].row + a] = old->force[a];
  }
  PetscCall(FCContactSolverSolve(solver, prob, lambda));
  PetscCall(FCContactSolverGetConvergence(solver, &st->sweeps, &st->residual, &conv));
  PetscCall(FCContactProblemDestroy(&prob));
  PetscCall(FCPhaseEnd(FC_PHASE_CONTACT_SOLVE));
  for (PetscInt k = 0; k < set->n; k++) {
    FCContact *c = &set->c[k];
    for (PetscInt a = 0; a < 3; a++) c->force[a] = a < c->dim ? lambda[c->row + a] : 0.0;
  }
  FCContactSetUpdateStates(set);
  PetscCall(FCPhaseBegin(FC_PHASE_CORRECTION));
  for (PetscInt b = 0; b < nbodies; b++)
    if (bodies[b]->ops.applycorrection) PetscCall((*bodies[b]->ops.applycorrection)(bodies[b], b, set, lambda));
  PetscCall(FCPhaseEnd(FC_PHASE_CORRECTION));
  PetscCall(PetscFree(W));
  PetscCall(PetscFree6(q, mu, dims, lambda, dfree, d0));
  PetscFunctionReturn(0);
}
