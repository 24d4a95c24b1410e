/* The exact local solve of one contact (src/contact/local.c), with Newton's method on the slip
   direction, against the solver it replaced (the slip direction bracketed on a 256-point grid and
   bisected, FCContactLocalSolveReference), on thousands of random 3D problems of each kind:
   general (stick and slip mixed), open, frictionless (mu = 0), large mu, ill-conditioned W_ii,
   anisotropic W_ii (tangential compliance 100x the normal one, and coupled). Checks: every
   solution of either solver has a natural-map residual at round-off (1e-10 relative to |q|, |r|);
   the two agree to 1e-8 relative wherever the reference's solution is one (the local problem
   with large mu and anisotropic W can have several solutions: those are counted and printed,
   each checked to be a solution); and prints the time per solve of both. */
/* a unit test of the local solve against its grid reference, which only the contact package declares */
#include "contact/contactimpl.h"

static PetscReal Rand(PetscRandom rnd, PetscReal lo, PetscReal hi)
{
  PetscReal v;
  PetscRandomGetValueReal(rnd, &v);
  return lo + (hi - lo) * v;
}

/* W = R diag(e) R^T with a random rotation R and eigenvalues e, optionally scaled tangentially */
static void RandomW(PetscRandom rnd, const PetscReal e[3], PetscReal tscale, PetscReal W[9])
{
  PetscReal axis[3] = {Rand(rnd, -1, 1), Rand(rnd, -1, 1), Rand(rnd, -1, 1)}, qt[4], R[9], S[9] = {0};
  FCQuatFromAxisAngle(axis, Rand(rnd, 0, 2 * PETSC_PI), qt);
  FCQuatToMat3(qt, R);
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++)
      for (int k = 0; k < 3; k++) S[3 * i + j] += R[3 * i + k] * e[k] * R[3 * j + k];
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) W[3 * i + j] = S[3 * i + j] * (i ? tscale : 1.0) * (j ? tscale : 1.0);
}

static PetscReal Error(const PetscReal W[9], const PetscReal q[3], PetscReal mu, const PetscReal r[3])
{
  PetscReal u[3], s = 0.0;
  for (int a = 0; a < 3; a++) {
    u[a] = q[a];
    for (int b = 0; b < 3; b++) u[a] += W[3 * a + b] * r[b];
    s = PetscMax(s, PetscMax(PetscAbsReal(q[a]), PetscAbsReal(r[a])));
  }
  return PetscSqrtReal(FCContactNaturalMapError2(3, mu, r, u)) / PetscMax(s, PETSC_SMALL);
}

int main(int argc, char **argv)
{
  const char *kinds[] = {"general", "open", "mu = 0", "large mu", "ill-conditioned", "anisotropic"};
  const int   N       = 4000;
  PetscRandom rnd;
  int         fails = 0;

  PetscCall(PetscInitialize(&argc, &argv, NULL, NULL));
  PetscCall(PetscRandomCreate(PETSC_COMM_SELF, &rnd));
  PetscCall(PetscRandomSetSeed(rnd, 20261122));
  PetscCall(PetscRandomSeed(rnd));
  for (int kind = 0; kind < 6; kind++) {
    int            bad = 0, differ = 0, slip = 0, stick = 0, open = 0;
    PetscReal      worst = 0.0;
    PetscLogDouble tnew = 0, tref = 0;
    for (int k = 0; k < N; k++) {
      PetscReal      W[9], q[3], e[3], mu, rn[3] = {0, 0, 0}, rr[3] = {0, 0, 0}, en, er, dn = 0, nr = 0, ft;
      PetscLogDouble t0, t1, t2;
      e[0] = Rand(rnd, 0.2, 2.0);
      e[1] = Rand(rnd, 0.2, 2.0);
      e[2] = Rand(rnd, 0.2, 2.0);
      if (kind == 4) e[PetscMin(2, (int)Rand(rnd, 0, 3))] *= 1e-7; /* nearly singular */
      RandomW(rnd, e, kind == 5 ? 10.0 : 1.0, W);
      if (kind == 5 && k % 2) /* anisotropic and diagonal in the frame: tangential 100x, coupling off */
        for (int a = 0; a < 9; a++) W[a] = a == 0 ? e[0] : (a == 4 ? 100 * e[1] : (a == 8 ? e[2] : 0.0));
      mu   = kind == 2 ? 0.0 : (kind == 3 ? Rand(rnd, 2.0, 20.0) : Rand(rnd, 0.05, 1.2));
      q[0] = kind == 1 ? Rand(rnd, 0.0, 1.0) : Rand(rnd, -1.0, -1e-3);
      q[1] = Rand(rnd, -2.0, 2.0);
      q[2] = Rand(rnd, -2.0, 2.0);
      PetscCall(PetscTime(&t0));
      PetscCall(FCContactLocalSolve(3, W, q, mu, rn, NULL));
      PetscCall(PetscTime(&t1));
      PetscCall(FCContactLocalSolveReference(3, W, q, mu, rr, NULL));
      PetscCall(PetscTime(&t2));
      tnew += t1 - t0;
      tref += t2 - t1;
      en    = Error(W, q, mu, rn);
      er    = Error(W, q, mu, rr);
      worst = PetscMax(worst, en);
      if (!(en <= 1e-10) && er <= 1e-10) bad++; /* the reference found a solution, the new solver did not */
      for (int a = 0; a < 3; a++) {
        dn = PetscMax(dn, PetscAbsReal(rn[a] - rr[a]));
        nr = PetscMax(nr, PetscAbsReal(rr[a]));
      }
      if (er <= 1e-10 && dn > 1e-8 * PetscMax(nr, 1e-12)) differ++; /* another solution (checked above) */
      ft = PetscSqrtReal(rn[1] * rn[1] + rn[2] * rn[2]);
      if (rn[0] <= 0.0)
        open++;
      else if (ft >= mu * rn[0] * (1 - 1e-9))
        slip++;
      else
        stick++;
    }
    fails += bad > 0 || worst > 1e-10 || (kind != 3 && kind != 5 && differ > N / 1000);
    PetscCall(PetscPrintf(PETSC_COMM_SELF,
                          "%-16s %d problems (open %d, stick %d, slip %d): worst residual %.1e, not solved %d, other "
                          "solution than the reference %d; %.2f us per solve (reference %.2f us)\n",
                          kinds[kind], N, open, stick, slip, (double)worst, bad, differ, 1e6 * tnew / N,
                          1e6 * tref / N));
  }
  PetscCall(PetscRandomDestroy(&rnd));
  PetscCall(PetscPrintf(PETSC_COMM_SELF, "local solve: %s\n", fails ? "FAILED" : "passed"));
  PetscCall(PetscFinalize());
  return fails ? 1 : 0;
}
