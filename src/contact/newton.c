/* Nonsmooth Newton on FC(W, q, mu) (-contact_solver newton): the Alart-Curnier function of the 3D
   Coulomb law (Alart & Curnier 1991; Siconos' FC3D_NSN_AC), per contact with rho = 1 / lambda_max(W_ii)
   (Siconos' default) and x_N = r_N - rho u_N, y = r_T - rho u_T, R = mu max(0, x_N):
       Phi_N = r_N - max(0, x_N)
       Phi_T = r_T - P_{disc of radius R}(y)
   with u = W r + q. Phi(r) = 0 exactly at the solutions of the Coulomb problem (the same as those
   of De Saxce's cone complementarity the natural-map residual measures). A Newton step solves
   (H + reg I) dr = -Phi with H = A + B W, A and B the block-diagonal generalized derivatives of Phi
   in r and u (d x d per contact: stick, slide or open), factored by newton_jacobian.c (dense or
   sparse LU); reg, 1e-8 at first, stands against the singular W of redundant contacts.
   Globalization: backtracking (Armijo) on psi = |Phi|^2 / 2 along dr, whose slope is -2 psi for the
   Newton direction; where no step along dr lowers psi (a kink between the contacts' states), the
   shortest step tried is taken (a full step there, as Siconos takes, makes the iterates of a
   degenerate problem depend on W's round-off: 1 and 2 ranks then part). Three steps in a row without
   descent or shorter than 1/64 make a stall: Newton goes on from the best iterate with reg ten
   times larger (the step then leaves the null space of a degenerate H alone), up to 1e-3, as long as
   the last regularization paid (halved the best residual), and after that stops. Stops on the natural-map
   residual / ||q|| <= tol, the test of the sweeps (pgs.c), or after max_it Newton steps; returns the iterate of the
   lowest residual met (the caller sweeps from it if it is above tol). A dormant contact (FCContactProblemSetDormant)
   keeps r_i = 0 (Phi_i = r_i). */
#include "contactimpl.h"

/* Newton stalls after FC_NEWTON_STALE steps in a row shorter than FC_NEWTON_SHORT (or without descent): then
   the regularization of H grows tenfold, from the best iterate, up to FC_NEWTON_REG_MAX while the last one
   paid, and after that the solver stops (the caller sweeps) */
#define FC_NEWTON_STALE 3
#define FC_NEWTON_SHORT (1.0 / 64)
#define FC_NEWTON_REG_MIN 1e-8
#define FC_NEWTON_REG_MAX 1e-3
#define FC_NEWTON_PAID 0.5 /* a regularization paid: its steps at least halved the best residual */

/* Phi_i and its derivatives A_i (in r_i) and B_i (in u_i), d x d row-major */
static void ACBlock(PetscInt d, PetscReal mu, PetscReal rho, const PetscReal r[], const PetscReal u[], PetscReal phi[],
                    PetscReal A[9], PetscReal B[9])
{
  PetscReal xN = r[0] - rho * u[0], R, y[2] = {0, 0}, ny = 0.0;

  for (PetscInt k = 0; k < d * d; k++) A[k] = B[k] = 0.0;
  if (xN > 0.0) {
    phi[0] = rho * u[0];
    B[0]   = rho;
  } else {
    phi[0] = r[0];
    A[0]   = 1.0;
  }
  if (d == 1) return;
  R = mu * PetscMax(0.0, xN);
  for (PetscInt a = 0; a < d - 1; a++) {
    y[a] = r[1 + a] - rho * u[1 + a];
    ny += y[a] * y[a];
  }
  ny = PetscSqrtReal(ny);
  if (ny <= R) { /* stick: Phi_T = r_T - y = rho u_T */
    for (PetscInt a = 0; a < d - 1; a++) {
      phi[1 + a]               = rho * u[1 + a];
      B[(1 + a) * d + (1 + a)] = rho;
    }
    return;
  }
  { /* slide (or open, R = 0): Phi_T = r_T - R y / |y| */
    PetscReal yh[2], s = R / ny, dR = xN > 0.0 ? mu : 0.0;
    for (PetscInt a = 0; a < d - 1; a++) yh[a] = y[a] / ny;
    for (PetscInt a = 0; a < d - 1; a++) {
      phi[1 + a]     = r[1 + a] - R * yh[a];
      A[(1 + a) * d] = -dR * yh[a];
      B[(1 + a) * d] = dR * rho * yh[a];
      for (PetscInt b = 0; b < d - 1; b++) {
        PetscReal P            = (a == b ? 1.0 : 0.0) - yh[a] * yh[b];
        A[(1 + a) * d + 1 + b] = (a == b ? 1.0 : 0.0) - s * P;
        B[(1 + a) * d + 1 + b] = rho * s * P;
      }
    }
  }
}

/* Phi at (r, u) and psi = |Phi|^2 / 2; with A, B (n x 3 each, per contact d x d) when wanted */
static PetscReal Merit(FCContactProblem p, const PetscReal rho[], const PetscReal r[], const PetscReal u[],
                       PetscReal phi[], PetscReal *A, PetscReal *B)
{
  PetscReal psi = 0.0;
  for (PetscInt i = 0; i < p->nc; i++) {
    PetscInt  d = p->dim[i], o = p->off[i];
    PetscReal Ai[9], Bi[9];
    if (p->dormant && p->dormant[i]) {
      for (PetscInt a = 0; a < d; a++) phi[o + a] = r[o + a];
      for (PetscInt k = 0; k < d * d; k++) Ai[k] = (k % (d + 1) == 0) ? 1.0 : 0.0, Bi[k] = 0.0;
    } else
      ACBlock(d, p->mu[i], rho[i], &r[o], &u[o], &phi[o], Ai, Bi);
    for (PetscInt a = 0; a < d; a++) psi += 0.5 * phi[o + a] * phi[o + a];
    if (A)
      for (PetscInt k = 0; k < d * d; k++) {
        A[9 * i + k] = Ai[k];
        B[9 * i + k] = Bi[k];
      }
  }
  return psi;
}

/* rho_i = 1 / lambda_max(W_ii) (Siconos' default for FC3D_NSN_AC), by power iteration on the d x d block */
static PetscReal SpectralRho(FCContactProblem p, PetscInt i)
{
  PetscInt  d = p->dim[i];
  PetscReal Wii[9], x[3] = {1.0, 1.0, 1.0}, lam = 0.0;

  FCContactProblemDiagonalBlock(p, i, Wii);
  for (PetscInt it = 0; it < 40; it++) {
    PetscReal y[3], nn = 0.0;
    for (PetscInt a = 0; a < d; a++) {
      y[a] = 0.0;
      for (PetscInt b = 0; b < d; b++) y[a] += Wii[a * d + b] * x[b];
      nn += y[a] * y[a];
    }
    nn = PetscSqrtReal(nn);
    if (!(nn > 0.0)) break;
    lam = nn;
    for (PetscInt a = 0; a < d; a++) x[a] = y[a] / nn;
  }
  return lam > 0.0 ? 1.0 / lam : 1.0;
}

PetscErrorCode FCContactSolveNewton(FCContactProblem p, FCNewtonJacobian J, PetscReal tol, PetscInt max_it,
                                    PetscReal r[], PetscInt *its, PetscReal *residual)
{
  PetscInt   n = p->n, nc = p->nc, stale = 0;
  PetscReal  reg = FC_NEWTON_REG_MIN, best, phase;
  PetscReal *u, *phi, *A, *B, *dr, *wdr, *rt, *ut, *rho, *rbest, psi;

  PetscFunctionBegin;
  *its = 0;
  for (PetscInt i = 0; i < nc; i++) { /* the warm start into the cones */
    PetscReal x[3];
    for (PetscInt a = 0; a < p->dim[i]; a++) x[a] = r[p->off[i] + a];
    FCContactProjectCone(p->dim[i], p->mu[i], x, &r[p->off[i]]);
    if (p->dormant && p->dormant[i])
      for (PetscInt a = 0; a < p->dim[i]; a++) r[p->off[i] + a] = 0.0;
  }
  PetscCall(PetscMalloc1(n + 1, &u));
  PetscCall(FCContactProblemVelocity(p, r, u));
  *residual = FCContactProblemResidualFromVelocity(p, r, u);
  if (*residual <= tol || !n) {
    PetscCall(PetscFree(u));
    PetscFunctionReturn(0);
  }
  PetscCall(PetscMalloc4(n, &phi, 9 * nc, &A, 9 * nc, &B, n, &rbest));
  PetscCall(PetscMalloc5(n, &dr, n, &wdr, n, &rt, n, &ut, nc, &rho));
  for (PetscInt i = 0; i < nc; i++) rho[i] = SpectralRho(p, i);
  psi   = Merit(p, rho, r, u, phi, A, B);
  best  = *residual;
  phase = best; /* the best residual when the current regularization began */
  PetscCall(PetscArraycpy(rbest, r, n));
  while (best > tol && *its < max_it && stale < FC_NEWTON_STALE) {
    PetscReal t = 1.0, psit = psi;
    PetscBool accepted = PETSC_FALSE, ok;
    for (PetscInt k = 0; k < n; k++) dr[k] = -phi[k];
    PetscCall(FCNewtonJacobianSolve(J, A, B, reg, dr, &ok));
    if (!ok) /* a singular H: a step along -Phi, the line search decides */
      for (PetscInt k = 0; k < n; k++) dr[k] = -phi[k];
    PetscCall(FCContactProblemMult(p, dr, wdr));
    for (PetscInt ls = 0; ls < 20; ls++, t *= 0.5) {
      for (PetscInt k = 0; k < n; k++) {
        rt[k] = r[k] + t * dr[k];
        ut[k] = u[k] + t * wdr[k];
      }
      psit = Merit(p, rho, rt, ut, phi, NULL, NULL);
      if (psit <= (1.0 - 2e-4 * t) * psi) {
        accepted = PETSC_TRUE;
        break;
      }
    }
    PetscCall(PetscArraycpy(r, rt, n));
    PetscCall(PetscArraycpy(u, ut, n));
    (*its)++;
    if (*its % 8 == 0) PetscCall(FCContactProblemVelocity(p, r, u)); /* against the drift of u += t W dr */
    psi       = Merit(p, rho, r, u, phi, A, B);
    *residual = FCContactProblemResidualFromVelocity(p, r, u);
    PetscCheck(!PetscIsInfOrNanReal(*residual), PETSC_COMM_SELF, PETSC_ERR_FP,
               "Contact solver (Newton) diverged (NaN residual) after %" PetscInt_FMT " iterations", *its);
    stale = accepted && t >= FC_NEWTON_SHORT ? 0 : stale + 1;
    if (*residual < best) {
      best = *residual;
      PetscCall(PetscArraycpy(rbest, r, n));
    }
    /* stalled: from the best iterate, more regularized, as long as the last regularization paid (the first
       always does: it may only be too small) */
    if (stale >= FC_NEWTON_STALE && 10.0 * reg <= FC_NEWTON_REG_MAX &&
        (reg == FC_NEWTON_REG_MIN || best < FC_NEWTON_PAID * phase)) {
      phase = best;
      reg *= 10.0;
      stale = 0;
      PetscCall(PetscArraycpy(r, rbest, n));
      PetscCall(FCContactProblemVelocity(p, r, u));
      psi = Merit(p, rho, r, u, phi, A, B);
      PetscCall(
          PetscInfo(NULL, "Newton stalled at residual %g: on with the regularization %g\n", (double)best, (double)reg));
    }
    PetscCall(PetscInfo(NULL, "Newton step %" PetscInt_FMT ": step length %g%s, |Phi| %g, residual %g\n", *its,
                        (double)t, accepted ? "" : " (no descent)", (double)PetscSqrtReal(2.0 * psi),
                        (double)*residual));
  }
  PetscCall(PetscArraycpy(r, rbest, n));
  PetscCall(FCContactProblemVelocity(p, r, u));
  *residual = FCContactProblemResidualFromVelocity(p, r, u);
  PetscCall(PetscFree4(phi, A, B, rbest));
  PetscCall(PetscFree5(dr, wdr, rt, ut, rho));
  PetscCall(PetscFree(u));
  PetscFunctionReturn(0);
}

/* -contact_solver newton on this rank (called by solver.c's placement): rounds of FC_NEWTON_SWEEPS sweeps (NNCG), then
   Newton steps from their iterate (newton.c), until converged or out of budget (-pgs_max_it sweeps and Newton steps
   together, -contact_newton_max_it Newton steps). The sweeps find the contacts' states roughly, from which Newton
   converges fast, and take over where a Newton step cannot lower |Phi| (kinks, redundant contacts); a round whose
   Newton steps do not lower the residual tenfold makes the next round's sweeps four times more, so that where Newton
   does not help the cost tends to the sweeps'. Newton steps that end with a larger natural-map residual than the
   sweeps' (|Phi| and the residual are different measures) are undone. Once the Newton steps are spent, the sweeps
   take the rest of the budget. Sweeps and steps both count as the solver's iterations. */
#define FC_NEWTON_SWEEPS 20
PetscErrorCode FCContactSolverNewton(FCContactSolver s, FCContactProblem p, PetscReal r[])
{
  PetscInt         max_it = s->max_it, total = 0, newton = 0, sweeps = FC_NEWTON_SWEEPS;
  PetscReal       *rs;
  FCNewtonJacobian J = NULL; /* created at the first Newton steps, kept for the solve's later rounds */

  PetscFunctionBegin;
  PetscCall(PetscMalloc1(p->n + 1, &rs));
  for (;;) {
    PetscInt  its;
    PetscReal before;
    s->max_it = newton < s->newton_max_it ? PetscMin(sweeps, max_it - total) : max_it - total;
    PetscCall(FCContactSolverSweeps(s, p, r));
    total += s->sweeps;
    if (s->converged || total >= max_it) break;
    before = s->residual;
    PetscCall(PetscArraycpy(rs, r, p->n));
    if (!J) PetscCall(FCNewtonJacobianCreate(p, (FCNewtonLU)s->newton_lu, &J)); /* its pattern analysed once */
    PetscCall(
        FCContactSolveNewton(p, J, s->tol, PetscMin(s->newton_max_it - newton, max_it - total), r, &its, &s->residual));
    newton += its;
    total += its;
    if (s->residual > before) { /* worse than the sweeps left it: back to their iterate */
      PetscCall(PetscArraycpy(r, rs, p->n));
      s->residual = before;
    }
    if (s->residual > 0.1 * before) sweeps *= 4; /* Newton did not pay: more sweeps before the next try */
    if (s->update) { /* -fast_update sweep: re-linearized at Newton's forces too; a new problem, the sweeps go on */
      PetscBool changed = PETSC_FALSE;
      PetscCall((*s->update)(s->updatectx, p, r, &changed));
      if (changed) {
        PetscReal *u;
        PetscCall(FCNewtonJacobianDestroy(&J)); /* a new W: its pattern found again */
        PetscCall(PetscMalloc1(p->n + 1, &u));
        PetscCall(FCContactProblemVelocity(p, r, u));
        s->residual = FCContactProblemResidualFromVelocity(p, r, u);
        PetscCall(PetscFree(u));
      }
    }
    s->converged = s->residual <= s->tol ? PETSC_TRUE : PETSC_FALSE;
    if (s->converged || total >= max_it) break;
  }
  PetscCall(FCNewtonJacobianDestroy(&J));
  PetscCall(PetscFree(rs));
  s->max_it = max_it;
  s->sweeps = total;
  PetscCall(PetscInfo(NULL,
                      "contact solver newton: %" PetscInt_FMT " sweeps and Newton steps, %" PetscInt_FMT
                      " of them Newton steps, residual %g\n",
                      total, newton, (double)s->residual));
  PetscFunctionReturn(0);
}

/* -contact_solver auto: the sweeps as -contact_solver pgs, stopped once their rate of convergence (residuals
   FC_PGS_EXACT sweeps apart, pgs.c) says they would not reach the tolerance within max_it; then FCContactSolverNewton
   with the budget left, from the warm start the solve began with: the iterate of sweeps that stall is a poor start
   for Newton (on stacks its steps stay short near the contacts' kinks: docs/contact-solver.md), the driver's own 20
   sweeps a good one. A problem the sweeps converge on at a steady rate within their budget is solved by them alone,
   as by pgs; one on which they stall (mass or stiffness ratios: docs/hard-cases.md) by Newton. */
PetscErrorCode FCContactSolverAuto(FCContactSolver s, FCContactProblem p, PetscReal r[])
{
  PetscInt max_it = s->max_it, sweeps;

  PetscReal *r0;

  PetscFunctionBegin;
  PetscCall(PetscMalloc1(p->n + 1, &r0));
  PetscCall(PetscArraycpy(r0, r, p->n));
  s->giveup = PETSC_TRUE;
  PetscCall(FCContactSolverSweeps(s, p, r));
  s->giveup = PETSC_FALSE;
  if (!s->converged && s->sweeps < max_it) PetscCall(PetscArraycpy(r, r0, p->n)); /* Newton from the warm start */
  PetscCall(PetscFree(r0));
  if (s->converged || s->sweeps >= max_it) PetscFunctionReturn(0);
  sweeps = s->sweeps;
  PetscCall(PetscInfo(NULL,
                      "contact solver auto: the sweeps would not converge (residual %g after %" PetscInt_FMT
                      "); Newton from there\n",
                      (double)s->residual, sweeps));
  s->max_it = max_it - sweeps;
  PetscCall(FCContactSolverNewton(s, p, r));
  s->max_it = max_it;
  s->sweeps += sweeps;
  PetscFunctionReturn(0);
}

/* -contact_solver newton: on rank 0 (or every rank), never split */
PetscErrorCode FCContactSolverCreate_Newton(FCContactSolver s)
{
  PetscFunctionBegin;
  s->solve  = FCContactSolverNewton;
  s->newton = PETSC_TRUE;
  PetscFunctionReturn(0);
}

/* -contact_solver auto (the default): its sweeps may be split over the ranks, as pgs' */
PetscErrorCode FCContactSolverCreate_Auto(FCContactSolver s)
{
  PetscFunctionBegin;
  s->solve  = FCContactSolverAuto;
  s->splits = PETSC_TRUE;
  s->newton = PETSC_TRUE;
  PetscFunctionReturn(0);
}
