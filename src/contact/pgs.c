/* Projected (block) Gauss-Seidel on FC(W, q, mu), eq. 19: sweep over contacts; for contact i,
   q_i' = q_i + sum_{j != i} W_ij r_j and r_i is the exact solution of the local problem
   (W_ii, q_i', mu_i) (local.c). Warm-started from the r given. Stops when the natural-map
   residual divided by ||q|| (FCContactProblemResidual, Siconos 4.4's normalization) is at most
   -pgs_tol, or after -pgs_max_it sweeps.
   Options: -pgs_tol (default 1e-8, > 0), -pgs_max_it (default 1000, >= 1). */
#include "contactimpl.h"

struct _p_FCContactSolver {
  MPI_Comm  comm;
  PetscReal tol, residual;
  PetscInt  max_it, sweeps;
  PetscBool converged;
};

PetscErrorCode FCContactSolverCreate(MPI_Comm comm, FCContactSolver *solver)
{
  PetscFunctionBegin;
  PetscCall(PetscNew(solver));
  (*solver)->comm   = comm;
  (*solver)->tol    = 1e-8;
  (*solver)->max_it = 1000;
  PetscFunctionReturn(0);
}

PetscErrorCode FCContactSolverSetFromOptions(FCContactSolver s)
{
  PetscFunctionBegin;
  PetscOptionsBegin(s->comm, NULL, "Contact solver (projected Gauss-Seidel)", "FCContactSolver");
  PetscCall(FCOptionsReal(PetscOptionsObject, "-pgs_tol", "Stop when the natural-map residual / ||q|| is below this",
                          &s->tol, NULL));
  PetscCall(FCOptionsInt(PetscOptionsObject, "-pgs_max_it", "Maximum number of PGS sweeps", &s->max_it, NULL));
  PetscOptionsEnd();
  PetscCheck(s->tol > 0.0, s->comm, PETSC_ERR_USER_INPUT, "Option -pgs_tol must be > 0, got %g", (double)s->tol);
  PetscCheck(s->max_it >= 1, s->comm, PETSC_ERR_USER_INPUT, "Option -pgs_max_it must be >= 1, got %" PetscInt_FMT,
             s->max_it);
  PetscFunctionReturn(0);
}

PetscErrorCode FCContactSolverSetTolerances(FCContactSolver s, PetscReal tol, PetscInt max_it)
{
  PetscFunctionBegin;
  if (tol > 0) s->tol = tol;
  if (max_it > 0) s->max_it = max_it;
  PetscFunctionReturn(0);
}

PetscErrorCode FCContactSolverSolve(FCContactSolver s, FCContactProblem p, PetscReal r[])
{
  PetscFunctionBegin;
  s->converged = PETSC_FALSE;
  s->sweeps    = 0;
  for (PetscInt k = 0; k < p->n; k++)
    PetscCheck(!PetscIsInfOrNanReal(r[k]), PETSC_COMM_SELF, PETSC_ERR_FP,
               "Warm start of the contact solver has NaN/Inf");
  PetscCall(FCContactProblemResidual(p, r, NULL, &s->residual));
  while (s->residual > s->tol && s->sweeps < s->max_it) {
    for (PetscInt i = 0; i < p->nc; i++) {
      PetscInt         d = p->dim[i];
      PetscReal        qi[3];
      const PetscReal *Wii = &p->val[p->boff[p->diag[i]]];
      for (PetscInt a = 0; a < d; a++) qi[a] = p->q[p->off[i] + a];
      for (PetscInt b = p->rowptr[i]; b < p->rowptr[i + 1]; b++) {
        PetscInt         j = p->col[b], dj = p->dim[j];
        const PetscReal *B = &p->val[p->boff[b]];
        if (j == i) continue;
        for (PetscInt a = 0; a < d; a++)
          for (PetscInt c = 0; c < dj; c++) qi[a] += B[a * dj + c] * r[p->off[j] + c];
      }
      PetscCall(FCContactLocalSolve(d, Wii, qi, p->mu[i], &r[p->off[i]], NULL));
    }
    s->sweeps++;
    PetscCall(FCContactProblemResidual(p, r, NULL, &s->residual));
    PetscCheck(!PetscIsInfOrNanReal(s->residual), PETSC_COMM_SELF, PETSC_ERR_FP,
               "Contact solver diverged (NaN residual) after %" PetscInt_FMT " sweeps", s->sweeps);
  }
  s->converged = s->residual <= s->tol ? PETSC_TRUE : PETSC_FALSE;
  PetscFunctionReturn(0);
}

PetscErrorCode FCContactSolverGetConvergence(FCContactSolver s, PetscInt *sweeps, PetscReal *residual,
                                             PetscBool *converged)
{
  PetscFunctionBegin;
  if (sweeps) *sweeps = s->sweeps;
  if (residual) *residual = s->residual;
  if (converged) *converged = s->converged;
  PetscFunctionReturn(0);
}

PetscErrorCode FCContactSolverDestroy(FCContactSolver *s)
{
  PetscFunctionBegin;
  PetscCall(PetscFree(*s));
  PetscFunctionReturn(0);
}
