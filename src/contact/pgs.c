/* -contact_solver pgs: projected (block) Gauss-Seidel on FC(W, q, mu), eq. 19. A sweep visits the
   contacts in turn; for contact i, q_i' = q_i + sum_{j != i} W_ij r_j and r_i is the exact solution
   of the local problem (W_ii, q_i', mu_i) (local.c), relaxed by -pgs_omega and damped by
   -pgs_proximal. Accelerated by NNCG (-pgs_acceleration, Silcowitz, Niebe and Erleben 2010): after
   a sweep with step g, r += beta p, p = beta p + g, beta = |g|^2 / |g_prev|^2, restarted when
   beta > 1; the iterate is projected on the cones and a step that does not lower the residual is
   undone. Warm-started from the r given; stops when the natural-map residual / ||q||
   (FCContactProblemResidual, Siconos 4.4's normalization) is at most -pgs_tol, or after
   -pgs_max_it sweeps. Placed over the ranks by solver.c. */
#include "contactimpl.h"

/* One sweep over the contacts, in place (eq. 19). u = q + W r is kept current: contact i's local
   problem is (W_ii, u_i - W_ii r_i), and after it u += W[:, i] (r_i^new - r_i), the rows of
   contact i in W (W symmetric: every dense W) or in W^T, read once per sweep with unit stride. */
static PetscErrorCode Sweep(FCContactSolver s, FCContactProblem p, PetscReal r[], PetscReal u[])
{
  PetscFunctionBegin;
  for (PetscInt i = 0; i < p->nc; i++) {
    PetscReal delta[3];
    PetscBool changed;
    PetscCall(FCContactLocalUpdate(p, i, &u[p->off[i]], s->omega, s->proximal, r, delta, &changed));
    if (changed) FCContactProblemAddColumns(p, i, delta, u);
  }
  PetscFunctionReturn(0);
}

/* NNCG's state: the iterate before the sweep, the direction and W times it, the sweep's iterate */
typedef struct {
  PetscReal *rold, *uold, *dir, *wdir, *rsweep, *usweep, gg_old;
} NNCG;

/* NNCG: the sweep's step g = r - rold conjugated with the previous direction, r += beta dir, then back
   into the cones with u following; restarted (dir = g) when beta > 1. moved: r left the sweep's iterate */
static PetscErrorCode NNCGStep(FCContactProblem p, NNCG *c, PetscReal r[], PetscReal u[], PetscBool *moved)
{
  PetscInt  n  = p->n;
  PetscReal gg = 0.0, beta;

  PetscFunctionBegin;
  *moved = PETSC_FALSE;
  for (PetscInt k = 0; k < n; k++) gg += PetscSqr(r[k] - c->rold[k]);
  beta = c->gg_old > 0.0 ? gg / c->gg_old : 2.0;
  if (beta > 1.0) /* restart */
    for (PetscInt k = 0; k < n; k++) {
      c->dir[k]  = r[k] - c->rold[k];
      c->wdir[k] = u[k] - c->uold[k];
    }
  else {
    PetscCall(PetscArraycpy(c->rsweep, r, n));
    PetscCall(PetscArraycpy(c->usweep, u, n));
    for (PetscInt k = 0; k < n; k++) {
      PetscReal g = r[k] - c->rold[k], wg = u[k] - c->uold[k];
      r[k] += beta * c->dir[k];
      u[k] += beta * c->wdir[k];
      c->dir[k]  = beta * c->dir[k] + g;
      c->wdir[k] = beta * c->wdir[k] + wg;
    }
    for (PetscInt i = 0; i < p->nc; i++) { /* back into the cones, u following */
      PetscInt  d = p->dim[i], o = p->off[i];
      PetscReal x[3], delta[3];
      PetscBool changed = PETSC_FALSE;
      for (PetscInt a = 0; a < d; a++) x[a] = r[o + a];
      FCContactProjectCone(d, p->mu[i], x, &r[o]);
      for (PetscInt a = 0; a < d; a++) {
        delta[a] = r[o + a] - x[a];
        changed  = changed || delta[a] != 0.0;
      }
      if (changed) FCContactProblemAddColumns(p, i, delta, u);
    }
    *moved = PETSC_TRUE;
  }
  c->gg_old = gg;
  PetscFunctionReturn(0);
}

/* The sweeps, with u = q + W r carried along: the residual of the stopping test and NNCG's
   accept/undo decision come from (r, u) without a product with W. NNCG keeps W dir too (the change
   of u over a sweep is W times the sweep's step), so its step costs no product either. u is
   recomputed exactly (one product) every FC_PGS_EXACT sweeps, against the drift of the incremental
   updates, and before the solver stops. */
#define FC_PGS_EXACT 16
/* With s->giveup (-contact_solver auto), the sweeps stop, unconverged, from this many sweeps on, when
   the rate of the residual over the last FC_PGS_EXACT sweeps says they would not converge within max_it; before, NNCG's
   restarts make the rate noisy */
#define FC_PGS_GIVEUP 64
/* With s->giveup, every FC_PGS_EXACT sweeps: whether the rate of the residual over them says the sweeps will not
   reach the tolerance within max_it (checkpoint: the residual FC_PGS_EXACT sweeps before, updated) */
static PetscBool GiveUp(FCContactSolver s, PetscReal *checkpoint)
{
  PetscReal rate = *checkpoint > 0.0 ? s->residual / *checkpoint : 0.0;
  if (s->sweeps >= FC_PGS_GIVEUP && s->residual > s->tol &&
      (rate >= 1.0 || s->sweeps + FC_PGS_EXACT * PetscLogReal(s->tol / s->residual) / PetscLogReal(rate) > s->max_it))
    return PETSC_TRUE;
  *checkpoint = s->residual;
  return PETSC_FALSE;
}
PetscErrorCode FCContactSolverSweeps(FCContactSolver s, FCContactProblem p, PetscReal r[])
{
  PetscInt   n = p->n;
  PetscBool  exact;
  PetscReal *u;
  NNCG       g          = {0};
  PetscReal  checkpoint = 0.0; /* the residual FC_PGS_EXACT sweeps ago (giveup) */

  PetscFunctionBegin;
  s->converged = PETSC_FALSE;
  s->sweeps    = 0;
  for (PetscInt k = 0; k < n; k++)
    PetscCheck(!PetscIsInfOrNanReal(r[k]), PETSC_COMM_SELF, PETSC_ERR_FP,
               "Warm start of the contact solver has NaN/Inf");
  PetscCall(PetscMalloc1(n + 1, &u));
  PetscCall(FCContactProblemVelocity(p, r, u));
  exact       = PETSC_TRUE; /* u is W r + q, not carried */
  s->residual = FCContactProblemResidualFromVelocity(p, r, u);
  if (s->nncg)
    PetscCall(PetscCalloc6(n + 1, &g.rold, n + 1, &g.uold, n + 1, &g.dir, n + 1, &g.wdir, n + 1, &g.rsweep, n + 1,
                           &g.usweep));
  while (s->residual > s->tol && s->sweeps < s->max_it) {
    PetscBool moved    = PETSC_FALSE;
    PetscReal previous = s->residual;
    if (s->nncg) {
      PetscCall(PetscArraycpy(g.rold, r, n));
      PetscCall(PetscArraycpy(g.uold, u, n));
    }
    PetscCall(Sweep(s, p, r, u));
    if (s->nncg) PetscCall(NNCGStep(p, &g, r, u, &moved));
    s->sweeps++;
    exact = s->sweeps % FC_PGS_EXACT == 0 ? PETSC_TRUE : PETSC_FALSE;
    if (exact) PetscCall(FCContactProblemVelocity(p, r, u));
    s->residual = FCContactProblemResidualFromVelocity(p, r, u);
    if (moved && !(s->residual < previous)) { /* the step did not pay: back to the sweep's iterate, restart */
      PetscCall(PetscArraycpy(r, g.rsweep, n));
      PetscCall(PetscArraycpy(u, g.usweep, n));
      exact = PETSC_FALSE;
      for (PetscInt k = 0; k < n; k++) {
        g.dir[k]  = r[k] - g.rold[k];
        g.wdir[k] = u[k] - g.uold[k];
      }
      s->residual = FCContactProblemResidualFromVelocity(p, r, u);
    }
    if (s->update) { /* the caller re-linearizes at this iterate: a new problem, the same unknowns */
      PetscBool changed = PETSC_FALSE;
      PetscCall((*s->update)(s->updatectx, p, r, &changed));
      if (changed) {
        PetscCall(FCContactProblemVelocity(p, r, u));
        exact       = PETSC_TRUE;
        s->residual = FCContactProblemResidualFromVelocity(p, r, u);
        g.gg_old    = 0.0; /* NNCG restarts */
        checkpoint  = 0.0; /* and the rate is the new problem's */
      }
    }
    if (s->giveup && s->sweeps % FC_PGS_EXACT == 0 && GiveUp(s, &checkpoint)) break;
    if (s->residual <= s->tol && !exact) { /* converged on the carried u: confirm on the exact one */
      PetscCall(FCContactProblemVelocity(p, r, u));
      exact       = PETSC_TRUE;
      s->residual = FCContactProblemResidualFromVelocity(p, r, u);
    }
    PetscCheck(!PetscIsInfOrNanReal(s->residual), PETSC_COMM_SELF, PETSC_ERR_FP,
               "Contact solver diverged (NaN residual) after %" PetscInt_FMT " sweeps", s->sweeps);
  }
  if (!exact && s->residual > s->tol) { /* stopped by max_it: the exact residual */
    PetscCall(FCContactProblemVelocity(p, r, u));
    s->residual = FCContactProblemResidualFromVelocity(p, r, u);
  }
  if (s->nncg) PetscCall(PetscFree6(g.rold, g.uold, g.dir, g.wdir, g.rsweep, g.usweep));
  PetscCall(PetscFree(u));
  s->converged = s->residual <= s->tol ? PETSC_TRUE : PETSC_FALSE;
  PetscFunctionReturn(0);
}

/* The sweeps alone; they may be split over the ranks (-pgs_ranks) */
PetscErrorCode FCContactSolverCreate_PGS(FCContactSolver s)
{
  PetscFunctionBegin;
  s->solve  = FCContactSolverSweeps;
  s->splits = PETSC_TRUE;
  PetscFunctionReturn(0);
}
