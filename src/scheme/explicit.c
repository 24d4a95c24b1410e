/* Algorithm 1 (explicit constraint resolution, once per step):
     W = sum_b J_b A_b^-1 J_b^T                               (eq. 17, per-body builders)
     delta_free: normal gap n.(p1 - p2) and tangential displacement t.(dp1 - dp2) after the free motion
     PGS on delta = delta_free + h^2 W lambda, Signorini-Coulomb    (eq. 18-19)
     dv_b = dv_free_b + h A_b^-1 J_b^T lambda                    (eq. 20)
   No options of its own. */
#include "schemeimpl.h"

/* W (M^2), replicated */
static PetscErrorCode Memory_Explicit(FCScheme scheme, const FCContactSet *set, PetscReal *bytes, const char **what)
{
  PetscFunctionBegin;
  *bytes = 8.0 * (PetscReal)set->nrows * set->nrows;
  *what  = "dense W";
  PetscFunctionReturn(0);
}

static PetscErrorCode Solve_Explicit(FCScheme scheme, FCContactSet *set, const FCContactSet *previous,
                                     FCSchemeStats *st)
{
  PetscInt         M = set->nrows, *dims;
  PetscReal       *W, *q, *mu, *lambda, *dfree, *d0;
  FCContactProblem prob;
  PetscBool        conv;

  PetscFunctionBegin;
  PetscCall(PetscMalloc1(M * M, &W));
  PetscCall(PetscMalloc6(M, &q, set->n, &mu, set->n, &dims, M, &lambda, 3 * set->n, &dfree, 3 * set->n, &d0));
  PetscCall(FCPhaseBegin(FC_PHASE_COMPLIANCE));
  PetscCall(FCSchemeCompliance(scheme, set, NULL, W, NULL));
  PetscCall(FCPhaseEnd(FC_PHASE_COMPLIANCE));
  FCContactSetNormalCompliance(set, W);
  FCSchemeStartLinearization(set, dfree, d0, q, mu, dims);
  PetscCall(FCPhaseBegin(FC_PHASE_CONTACT_SOLVE));
  PetscCall(FCContactProblemCreateDense(set->n, dims, mu, W, q, &prob));
  FCContactSetWarmStart(set, previous, lambda);
  PetscCall(FCSchemeContactSolve(scheme, set, prob, lambda));
  PetscCall(FCContactSolverGetConvergence(scheme->solver, &st->sweeps, &st->residual, &conv));
  PetscCall(FCContactProblemDestroy(&prob));
  PetscCall(FCPhaseEnd(FC_PHASE_CONTACT_SOLVE));
  FCContactSetStoreForces(set, lambda);
  FCContactSetUpdateStates(set);
  PetscCall(FCPhaseBegin(FC_PHASE_CORRECTION));
  PetscCall(FCSchemeCorrect(scheme, set, lambda));
  PetscCall(FCPhaseEnd(FC_PHASE_CORRECTION));
  st->newton = 1;
  PetscCall(PetscFree(W));
  PetscCall(PetscFree6(q, mu, dims, lambda, dfree, d0));
  PetscFunctionReturn(0);
}

PetscErrorCode FCSchemeCreate_Explicit(FCScheme scheme)
{
  PetscFunctionBegin;
  scheme->ops.memory = Memory_Explicit;
  scheme->ops.solve  = Solve_Explicit;
  PetscFunctionReturn(0);
}
