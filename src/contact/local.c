/* One contact's frictional problem, solved exactly (not by a projection pass):
     open   r = 0                                   when q_n >= 0
     stick  W r = -q, u = 0                         when r lies in the cone
     slip   u_n = 0, r_T = -mu r_n t, u_T = s t (s > 0): a root of g(theta) = u_T x t over the
            slip direction t = (cos theta, sin theta), found by Newton's method on theta from the
            direction the stick solution leaves the cone by (a few iterations, to round-off);
            when Newton does not land on an admissible root, the roots are bracketed on a grid of
            256 directions and bisected to machine precision (2D: t = +-1)
   The candidate is accepted when its natural-map residual is at round-off level; otherwise a
   projected fixed-point iteration finishes the job (degenerate or non-symmetric W). */
#include "contactimpl.h"

/* Projection on the Coulomb cone {||x_T|| <= mu x_n} (d = 2, 3) or on R+ (d = 1) */
void FCContactProjectCone(PetscInt d, PetscReal mu, const PetscReal x[], PetscReal p[])
{
  PetscReal t = 0.0;
  if (d == 1) {
    p[0] = PetscMax(x[0], 0.0);
    return;
  }
  for (PetscInt a = 1; a < d; a++) t += x[a] * x[a];
  t = PetscSqrtReal(t);
  if (t <= mu * x[0]) {
    for (PetscInt a = 0; a < d; a++) p[a] = x[a];
  } else if (mu * t <= -x[0]) {
    for (PetscInt a = 0; a < d; a++) p[a] = 0.0;
  } else {
    PetscReal s = (x[0] + mu * t) / (1.0 + mu * mu);
    p[0]        = s;
    for (PetscInt a = 1; a < d; a++) p[a] = mu * s * x[a] / t;
  }
}

PetscReal FCContactNaturalMapError2(PetscInt d, PetscReal mu, const PetscReal r[], const PetscReal u[])
{
  PetscReal x[3] = {0, 0, 0}, p[3], uT = 0.0, e2 = 0.0;
  for (PetscInt a = 1; a < d; a++) uT += u[a] * u[a];
  uT = PetscSqrtReal(uT);
  for (PetscInt a = 0; a < d; a++) x[a] = r[a] - u[a] - (a == 0 ? mu * uT : 0.0);
  FCContactProjectCone(d, mu, x, p);
  for (PetscInt a = 0; a < d; a++) e2 += PetscSqr(r[a] - p[a]);
  return e2;
}

/* Accept a candidate when its residual is round-off relative to the larger of |q| and |r|
   (r = -W^-1 q carries the round-off of |r|, which may exceed |q| by the conditioning of W) */
static PetscBool Accept(PetscInt d, PetscReal e2, const PetscReal q[], const PetscReal r[])
{
  PetscReal s2q = 0.0, s2r = 0.0;
  for (PetscInt a = 0; a < d; a++) {
    s2q += q[a] * q[a];
    s2r += r[a] * r[a];
  }
  return e2 <= PetscSqr(1e-12) * PetscMax(PetscMax(s2q, s2r), PETSC_SMALL * PETSC_SMALL) ? PETSC_TRUE : PETSC_FALSE;
}

static PetscReal LocalError2(PetscInt d, const PetscReal W[], const PetscReal q[], PetscReal mu, const PetscReal r[])
{
  PetscReal u[3];
  for (PetscInt a = 0; a < d; a++) {
    u[a] = q[a];
    for (PetscInt b = 0; b < d; b++) u[a] += W[a * d + b] * r[b];
  }
  return FCContactNaturalMapError2(d, mu, r, u);
}

/* Solve the d x d system W r = -q; returns false if singular */
static PetscBool SolveStick(PetscInt d, const PetscReal W[], const PetscReal q[], PetscReal r[])
{
  if (d == 1) {
    if (W[0] <= 0.0) return PETSC_FALSE;
    r[0] = -q[0] / W[0];
    return PETSC_TRUE;
  } else if (d == 2) {
    PetscReal det = W[0] * W[3] - W[1] * W[2];
    if (det == 0.0) return PETSC_FALSE;
    r[0] = (-q[0] * W[3] + q[1] * W[1]) / det;
    r[1] = (-q[1] * W[0] + q[0] * W[2]) / det;
    return PETSC_TRUE;
  } else {
    PetscReal Wi[9], det = FCMat3Det(W);
    if (det == 0.0 || !PetscIsNormalReal(det)) return PETSC_FALSE;
    if (FCMat3Inverse(W, Wi)) return PETSC_FALSE;
    for (int a = 0; a < 3; a++) r[a] = -(Wi[3 * a] * q[0] + Wi[3 * a + 1] * q[1] + Wi[3 * a + 2] * q[2]);
    return PETSC_TRUE;
  }
}

/* 3D slip at direction theta: r_n from u_n = 0, then u_T; returns false when r_n <= 0 */
static PetscBool Slip3(const PetscReal W[9], const PetscReal q[3], PetscReal mu, PetscReal theta, PetscReal r[3],
                       PetscReal *g, PetscReal *dot)
{
  PetscReal t[2] = {PetscCosReal(theta), PetscSinReal(theta)}, D, uT[2];
  D              = W[0] - mu * (W[1] * t[0] + W[2] * t[1]);
  if (!(D > 0.0)) return PETSC_FALSE;
  r[0] = -q[0] / D;
  r[1] = -mu * r[0] * t[0];
  r[2] = -mu * r[0] * t[1];
  for (int a = 0; a < 2; a++)
    uT[a] = q[1 + a] + W[3 * (1 + a)] * r[0] + W[3 * (1 + a) + 1] * r[1] + W[3 * (1 + a) + 2] * r[2];
  *g   = uT[0] * t[1] - uT[1] * t[0];
  *dot = uT[0] * t[0] + uT[1] * t[1];
  return r[0] > 0.0 ? PETSC_TRUE : PETSC_FALSE;
}

/* Slip at direction t = (c, s) (unit), with the derivative of g along the rotation of t:
   r_n = -q_n / D(t), r_T = -mu r_n t, u_T = q_T + W_Tn r_n + W_TT r_T, g = u_T x t, dot = u_T . t */
static PetscBool Slip3Newton(const PetscReal W[9], const PetscReal q[3], PetscReal mu, PetscReal c, PetscReal s,
                             PetscReal r[3], PetscReal *g, PetscReal *dg, PetscReal *dot)
{
  PetscReal D, dD, drn, drT[2], uT[2], duT[2];
  D  = W[0] - mu * (W[1] * c + W[2] * s);
  dD = -mu * (-W[1] * s + W[2] * c);
  if (!(D > 0.0)) return PETSC_FALSE;
  r[0]   = -q[0] / D;
  drn    = -r[0] * dD / D;
  r[1]   = -mu * r[0] * c;
  r[2]   = -mu * r[0] * s;
  drT[0] = -mu * (drn * c - r[0] * s);
  drT[1] = -mu * (drn * s + r[0] * c);
  for (int a = 0; a < 2; a++) {
    const PetscReal *w = &W[3 * (1 + a)];
    uT[a]              = q[1 + a] + w[0] * r[0] + w[1] * r[1] + w[2] * r[2];
    duT[a]             = w[0] * drn + w[1] * drT[0] + w[2] * drT[1];
  }
  *g   = uT[0] * s - uT[1] * c;
  *dg  = duT[0] * s + uT[0] * c - duT[1] * c + uT[1] * s;
  *dot = uT[0] * c + uT[1] * s;
  return r[0] > 0.0 ? PETSC_TRUE : PETSC_FALSE;
}

/* Newton on the angle of t, from the direction (c, s) (not necessarily unit): each step rotates t
   by atan(step) (t += step t_perp, normalized: no trigonometry); true when it ends on an admissible
   slip (r_n > 0, u_T along t) whose residual is at round-off */
static PetscBool SolveSlip3Newton(const PetscReal W[9], const PetscReal q[3], PetscReal mu, PetscReal c, PetscReal s,
                                  PetscReal r[3])
{
  PetscReal g, dg, dot, rr[3], nt = PetscSqrtReal(c * c + s * s);
  if (!(nt > 0.0)) return PETSC_FALSE;
  c /= nt;
  s /= nt;
  for (int it = 0; it < 40; it++) {
    PetscReal step, c1;
    if (!Slip3Newton(W, q, mu, c, s, rr, &g, &dg, &dot)) return PETSC_FALSE;
    if (g == 0.0 || dg == 0.0) break;
    step = -g / dg;
    if (step > 0.5) step = 0.5; /* no jump to another branch */
    if (step < -0.5) step = -0.5;
    c1 = c - step * s;
    s  = s + step * c;
    nt = PetscSqrtReal(c1 * c1 + s * s);
    c  = c1 / nt;
    s /= nt;
    if (PetscAbsReal(step) <= 4 * PETSC_MACHINE_EPSILON) break;
  }
  if (!Slip3Newton(W, q, mu, c, s, rr, &g, &dg, &dot) || dot < 0.0) return PETSC_FALSE;
  if (!Accept(3, LocalError2(3, W, q, mu, rr), q, rr)) return PETSC_FALSE;
  for (int a = 0; a < 3; a++) r[a] = rr[a];
  return PETSC_TRUE;
}

/* Newton's start: the slip direction t opposes the tangential force, so the direction in which the
   stick solution rs leaves the cone; without one (W singular), the free tangential velocity q_T */
static PetscBool SolveSlip3Fast(const PetscReal W[9], const PetscReal q[3], PetscReal mu, PetscReal rs[3])
{
  if (rs[1] != 0.0 || rs[2] != 0.0) return SolveSlip3Newton(W, q, mu, -rs[1], -rs[2], rs);
  return SolveSlip3Newton(W, q, mu, q[1], q[2], rs);
}

static PetscBool SolveSlip3Grid(const PetscReal W[9], const PetscReal q[3], PetscReal mu, PetscReal r[3])
{
  const int N    = 256;
  PetscReal best = PETSC_MAX_REAL, rb[3] = {0, 0, 0};
  PetscReal th0 = 0.0, g0 = 0.0, d0 = 0.0, rr[3];
  PetscBool v0 = Slip3(W, q, mu, th0, rr, &g0, &d0);
  for (int k = 1; k <= N; k++) {
    PetscReal th1 = 2.0 * PETSC_PI * k / N, g1, d1;
    PetscBool v1  = Slip3(W, q, mu, th1, rr, &g1, &d1);
    if (v0 && v1 && (g0 == 0.0 || g0 * g1 < 0.0) && (d0 > 0.0 || d1 > 0.0)) {
      PetscReal a = th0, b = th1, ga = g0;
      for (int it = 0; it < 200 && b - a > 4 * PETSC_MACHINE_EPSILON; it++) {
        PetscReal m = 0.5 * (a + b), gm, dm;
        if (!Slip3(W, q, mu, m, rr, &gm, &dm)) break;
        if (gm == 0.0) {
          a = b = m;
          break;
        }
        if ((ga < 0.0) == (gm < 0.0)) {
          a  = m;
          ga = gm;
        } else
          b = m;
      }
      {
        PetscReal gm, dm, e2;
        if (Slip3(W, q, mu, 0.5 * (a + b), rr, &gm, &dm) && dm >= 0.0) {
          e2 = LocalError2(3, W, q, mu, rr);
          if (e2 < best) {
            best = e2;
            for (int c = 0; c < 3; c++) rb[c] = rr[c];
          }
          if (Accept(3, e2, q, rr)) break;
        }
      }
    }
    th0 = th1;
    g0  = g1;
    d0  = d1;
    v0  = v1;
  }
  if (best == PETSC_MAX_REAL) return PETSC_FALSE;
  for (int c = 0; c < 3; c++) r[c] = rb[c];
  return Accept(3, best, q, r);
}

static PetscBool SolveSlip2(const PetscReal W[4], const PetscReal q[2], PetscReal mu, PetscReal r[2])
{
  for (int s = -1; s <= 1; s += 2) {
    PetscReal D = W[0] - s * mu * W[1], rr[2];
    if (!(D > 0.0)) continue;
    rr[0] = -q[0] / D;
    rr[1] = -s * mu * rr[0];
    if (rr[0] > 0.0 && Accept(2, LocalError2(2, W, q, mu, rr), q, rr)) {
      r[0] = rr[0];
      r[1] = rr[1];
      return PETSC_TRUE;
    }
  }
  return PETSC_FALSE;
}

/* Last resort: r <- Proj_K(r - rho (u + mu ||u_T|| e_N)) with rho = 1 / ||W||_F */
static void FixedPoint(PetscInt d, const PetscReal W[], const PetscReal q[], PetscReal mu, PetscReal r[])
{
  PetscReal nW = 0.0, rho;
  for (PetscInt a = 0; a < d * d; a++) nW += W[a] * W[a];
  rho = 1.0 / PetscMax(PetscSqrtReal(nW), PETSC_MACHINE_EPSILON);
  for (int it = 0; it < 100000; it++) {
    PetscReal u[3] = {0, 0, 0}, x[3] = {0, 0, 0}, uT = 0.0;
    for (PetscInt a = 0; a < d; a++) {
      u[a] = q[a];
      for (PetscInt b = 0; b < d; b++) u[a] += W[a * d + b] * r[b];
    }
    for (PetscInt a = 1; a < d; a++) uT += u[a] * u[a];
    uT = PetscSqrtReal(uT);
    for (PetscInt a = 0; a < d; a++) x[a] = r[a] - rho * (u[a] + (a == 0 ? mu * uT : 0.0));
    FCContactProjectCone(d, mu, x, r);
    if (it % 16 == 0 && Accept(d, LocalError2(d, W, q, mu, r), q, r)) break;
  }
}

static PetscErrorCode LocalSolve(PetscInt d, const PetscReal W[], const PetscReal q[], PetscReal mu, PetscReal r[],
                                 PetscReal *residual, PetscBool newton)
{
  PetscReal rr[3] = {0.0, 0.0, 0.0};

  PetscFunctionBegin;
  if (q[0] >= 0.0) { /* open: r = 0, u = q, and u_n >= 0 makes u + mu ||u_T|| e_N dual-admissible */
    for (PetscInt a = 0; a < d; a++) r[a] = 0.0;
  } else if (SolveStick(d, W, q, rr) && Accept(d, LocalError2(d, W, q, mu, rr), q, rr)) {
    for (PetscInt a = 0; a < d; a++) r[a] = rr[a];
  } else if (d == 3 && ((newton && SolveSlip3Fast(W, q, mu, rr)) || SolveSlip3Grid(W, q, mu, rr))) {
    for (PetscInt a = 0; a < d; a++) r[a] = rr[a];
  } else if (d == 2 && SolveSlip2(W, q, mu, rr)) {
    for (PetscInt a = 0; a < d; a++) r[a] = rr[a];
  } else {
    FixedPoint(d, W, q, mu, r); /* starts from the caller's r (warm start) */
  }
  if (residual) *residual = PetscSqrtReal(LocalError2(d, W, q, mu, r));
  PetscFunctionReturn(0);
}

PetscErrorCode FCContactLocalSolve(PetscInt d, const PetscReal W[], const PetscReal q[], PetscReal mu, PetscReal r[],
                                   PetscReal *residual)
{
  PetscFunctionBegin;
  PetscCall(LocalSolve(d, W, q, mu, r, residual, PETSC_TRUE));
  PetscFunctionReturn(0);
}

/* The solver before Newton's slip direction (the grid bracket only): the reference of
   tests/test_local_solve.c */
PetscErrorCode FCContactLocalSolveReference(PetscInt d, const PetscReal W[], const PetscReal q[], PetscReal mu,
                                            PetscReal r[], PetscReal *residual)
{
  PetscFunctionBegin;
  PetscCall(LocalSolve(d, W, q, mu, r, residual, PETSC_FALSE));
  PetscFunctionReturn(0);
}

/* One contact's step of a sweep (pgs.c, pgs_split.c): the local problem (W_ii, u_i - W_ii r_i) with u_i
   its rows of u = q + W r, damped by the proximal term and relaxed by omega; r_i updated in place,
   delta its change */
PetscErrorCode FCContactLocalUpdate(FCContactProblem p, PetscInt i, const PetscReal ui[], PetscReal omega,
                                    PetscReal proximal, PetscReal r[], PetscReal delta[], PetscBool *changed)
{
  PetscInt  d = p->dim[i], o = p->off[i];
  PetscReal qi[3], Wi[9], ri[3], *r0 = &r[o];

  PetscFunctionBegin;
  *changed = PETSC_FALSE;
  if (p->dormant && p->dormant[i]) {
    for (PetscInt a = 0; a < d; a++) delta[a] = 0.0;
    PetscFunctionReturn(0);
  }
  FCContactProblemDiagonalBlock(p, i, Wi);
  for (PetscInt a = 0; a < d; a++) {
    qi[a] = ui[a];
    for (PetscInt b = 0; b < d; b++) qi[a] -= Wi[a * d + b] * r0[b];
  }
  for (PetscInt a = 0; a < d; a++) ri[a] = r0[a];
  if (proximal > 0.0) { /* (W_ii + sigma I) r = -(q_i - sigma r_i): the same fixed points */
    PetscReal tr = 0.0, sigma;
    for (PetscInt a = 0; a < d; a++) tr += Wi[a * d + a];
    sigma = proximal * tr / d;
    for (PetscInt a = 0; a < d; a++) {
      Wi[a * d + a] += sigma;
      qi[a] -= sigma * r0[a];
    }
  }
  PetscCall(FCContactLocalSolve(d, Wi, qi, p->mu[i], ri, NULL));
  if (omega != 1.0) {
    PetscReal x[3];
    for (PetscInt a = 0; a < d; a++) x[a] = (1.0 - omega) * r0[a] + omega * ri[a];
    FCContactProjectCone(d, p->mu[i], x, ri);
  }
  for (PetscInt a = 0; a < d; a++) {
    delta[a] = ri[a] - r0[a];
    *changed = *changed || delta[a] != 0.0;
    r0[a]    = ri[a];
  }
  PetscFunctionReturn(0);
}
