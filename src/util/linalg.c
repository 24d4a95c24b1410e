/* Small dense kernels: 3-vectors, 3x3 matrices (row-major), unit quaternions q = (w, x, y, z). */
#include "../fcimpl.h"

void FCMat3Identity(PetscReal A[9])
{
  for (int i = 0; i < 9; i++) A[i] = (i % 4 == 0) ? 1.0 : 0.0;
}

void FCMat3Mult(const PetscReal A[9], const PetscReal B[9], PetscReal C[9])
{
  PetscReal T[9];
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) T[3 * i + j] = A[3 * i] * B[j] + A[3 * i + 1] * B[3 + j] + A[3 * i + 2] * B[6 + j];
  for (int i = 0; i < 9; i++) C[i] = T[i];
}

void FCMat3MultTranspose(const PetscReal A[9], const PetscReal B[9], PetscReal C[9])
{
  PetscReal T[9];
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) T[3 * i + j] = A[i] * B[j] + A[3 + i] * B[3 + j] + A[6 + i] * B[6 + j];
  for (int i = 0; i < 9; i++) C[i] = T[i];
}

void FCMat3Transpose(const PetscReal A[9], PetscReal B[9])
{
  PetscReal T[9];
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) T[3 * j + i] = A[3 * i + j];
  for (int i = 0; i < 9; i++) B[i] = T[i];
}

void FCMat3Vec(const PetscReal A[9], const PetscReal x[3], PetscReal y[3])
{
  PetscReal t[3];
  for (int i = 0; i < 3; i++) t[i] = A[3 * i] * x[0] + A[3 * i + 1] * x[1] + A[3 * i + 2] * x[2];
  for (int i = 0; i < 3; i++) y[i] = t[i];
}

void FCMat3TVec(const PetscReal A[9], const PetscReal x[3], PetscReal y[3])
{
  PetscReal t[3];
  for (int i = 0; i < 3; i++) t[i] = A[i] * x[0] + A[3 + i] * x[1] + A[6 + i] * x[2];
  for (int i = 0; i < 3; i++) y[i] = t[i];
}

PetscReal FCMat3Det(const PetscReal A[9])
{
  return A[0] * (A[4] * A[8] - A[5] * A[7]) - A[1] * (A[3] * A[8] - A[5] * A[6]) + A[2] * (A[3] * A[7] - A[4] * A[6]);
}

PetscErrorCode FCMat3Inverse(const PetscReal A[9], PetscReal B[9])
{
  PetscReal d = FCMat3Det(A), T[9];

  PetscFunctionBegin;
  PetscCheck(d != 0.0 && PetscIsNormalReal(d), PETSC_COMM_SELF, PETSC_ERR_FP, "Singular 3x3 matrix (determinant %g)",
             (double)d);
  T[0] = (A[4] * A[8] - A[5] * A[7]) / d;
  T[1] = (A[2] * A[7] - A[1] * A[8]) / d;
  T[2] = (A[1] * A[5] - A[2] * A[4]) / d;
  T[3] = (A[5] * A[6] - A[3] * A[8]) / d;
  T[4] = (A[0] * A[8] - A[2] * A[6]) / d;
  T[5] = (A[2] * A[3] - A[0] * A[5]) / d;
  T[6] = (A[3] * A[7] - A[4] * A[6]) / d;
  T[7] = (A[1] * A[6] - A[0] * A[7]) / d;
  T[8] = (A[0] * A[4] - A[1] * A[3]) / d;
  for (int i = 0; i < 9; i++) B[i] = T[i];
  PetscFunctionReturn(0);
}

/* Symmetric 3x3 eigen-decomposition by cyclic Jacobi: S = V diag(w) V^T, V columns = vectors */
static void SymEig3(const PetscReal S[9], PetscReal w[3], PetscReal V[9])
{
  PetscReal a[9];
  for (int i = 0; i < 9; i++) a[i] = S[i];
  FCMat3Identity(V);
  for (int sweep = 0; sweep < 50; sweep++) {
    PetscReal off = a[1] * a[1] + a[2] * a[2] + a[5] * a[5], diag = a[0] * a[0] + a[4] * a[4] + a[8] * a[8];
    if (off <= 1e-34 * diag || off == 0.0) break;
    for (int p = 0; p < 2; p++)
      for (int q = p + 1; q < 3; q++) {
        PetscReal apq = a[3 * p + q], theta, t, c, s;
        if (apq == 0.0) continue;
        theta = (a[3 * q + q] - a[3 * p + p]) / (2.0 * apq);
        t     = (theta >= 0 ? 1.0 : -1.0) / (PetscAbsReal(theta) + PetscSqrtReal(theta * theta + 1.0));
        c     = 1.0 / PetscSqrtReal(t * t + 1.0);
        s     = t * c;
        for (int k = 0; k < 3; k++) { /* A <- A G */
          PetscReal akp = a[3 * k + p], akq = a[3 * k + q];
          a[3 * k + p] = c * akp - s * akq;
          a[3 * k + q] = s * akp + c * akq;
        }
        for (int k = 0; k < 3; k++) { /* A <- G^T A */
          PetscReal apk = a[3 * p + k], aqk = a[3 * q + k];
          a[3 * p + k] = c * apk - s * aqk;
          a[3 * q + k] = s * apk + c * aqk;
        }
        for (int k = 0; k < 3; k++) {
          PetscReal vkp = V[3 * k + p], vkq = V[3 * k + q];
          V[3 * k + p] = c * vkp - s * vkq;
          V[3 * k + q] = s * vkp + c * vkq;
        }
      }
  }
  w[0] = a[0];
  w[1] = a[4];
  w[2] = a[8];
}

/* The polar factor by Newton's iteration X <- (g X + X^-T / g) / 2 from X = F, with Higham's
   determinant scaling g = |det X|^(-1/3) in the first iterations: quadratic convergence to the
   orthogonal factor, the same as U V^T to round-off. Only where det F is not small against the
   size of F (the iteration keeps the sign of det F, and converges slowly near a singular F);
   returns whether it converged */
static PetscBool PolarNewton(const PetscReal F[9], PetscReal R[9])
{
  PetscReal X[9], n2 = 0.0, d;

  for (int i = 0; i < 9; i++) {
    X[i] = F[i];
    n2 += F[i] * F[i];
  }
  d = FCMat3Det(F);
  if (!(d > 1e-2 * n2 * PetscSqrtReal(n2) / (3.0 * PetscSqrtReal(3.0)))) return PETSC_FALSE;
  for (int it = 0; it < 30; it++) {
    PetscReal C[9], det, g, change = 0.0;
    C[0] = X[4] * X[8] - X[5] * X[7]; /* the cofactors: X^-T = C / det X */
    C[1] = X[5] * X[6] - X[3] * X[8];
    C[2] = X[3] * X[7] - X[4] * X[6];
    C[3] = X[2] * X[7] - X[1] * X[8];
    C[4] = X[0] * X[8] - X[2] * X[6];
    C[5] = X[1] * X[6] - X[0] * X[7];
    C[6] = X[1] * X[5] - X[2] * X[4];
    C[7] = X[2] * X[3] - X[0] * X[5];
    C[8] = X[0] * X[4] - X[1] * X[3];
    det  = X[0] * C[0] + X[1] * C[1] + X[2] * C[2];
    if (!(det > 0.0)) return PETSC_FALSE;
    g = it < 4 ? PetscPowReal(det, -1.0 / 3.0) : 1.0;
    for (int i = 0; i < 9; i++) {
      PetscReal y = 0.5 * (g * X[i] + C[i] / (g * det));
      change += (y - X[i]) * (y - X[i]);
      X[i] = y;
    }
    if (change < 1e-28 && it >= 1) {
      for (int i = 0; i < 9; i++) R[i] = X[i];
      return PETSC_TRUE;
    }
  }
  return PETSC_FALSE;
}

/* Polar decomposition F = R S with R a proper rotation, used by the co-rotational model: by
   Newton's iteration (PolarNewton) where det F is well away from 0, else R = U V^T from the SVD
   F = U Sigma V^T (through the eigen-decomposition of F^T F), where when det F <= 0 (inverted
   element) the smallest singular direction is flipped so that R stays a rotation (the
   "invertible FEM" convention). */
void FCMat3Polar(const PetscReal F[9], PetscReal R[9])
{
  if (PolarNewton(F, R)) return;
  {
    PetscReal C[9], w[3], V[9], U[9], sig[3];
    int       order[3] = {0, 1, 2};

    FCMat3MultTranspose(F, F, C);
    SymEig3(C, w, V);
    /* sort eigenvalues descending */
    for (int i = 0; i < 3; i++)
      for (int j = i + 1; j < 3; j++)
        if (w[order[j]] > w[order[i]]) {
          int t    = order[i];
          order[i] = order[j];
          order[j] = t;
        }
    {
      PetscReal Vs[9], ws[3];
      for (int j = 0; j < 3; j++) {
        ws[j] = w[order[j]];
        for (int i = 0; i < 3; i++) Vs[3 * i + j] = V[3 * i + order[j]];
      }
      for (int i = 0; i < 9; i++) V[i] = Vs[i];
      for (int j = 0; j < 3; j++) w[j] = ws[j];
    }
    if (FCMat3Det(V) < 0)
      for (int i = 0; i < 3; i++) V[3 * i + 2] = -V[3 * i + 2];
    for (int j = 0; j < 3; j++) sig[j] = PetscSqrtReal(PetscMax(w[j], 0.0));
    /* U columns u_j = F v_j / sigma_j for the well-conditioned ones, the rest completed */
    for (int j = 0; j < 2; j++) {
      PetscReal v[3] = {V[j], V[3 + j], V[6 + j]}, u[3], n;
      FCMat3Vec(F, v, u);
      n = PetscSqrtReal(FCDot(u, u));
      if (n > 1e-12 * PetscMax(sig[0], 1e-300)) {
        for (int i = 0; i < 3; i++) U[3 * i + j] = u[i] / n;
      } else { /* degenerate: any unit vector orthogonal to previous columns */
        PetscReal e[3] = {1, 0, 0};
        if (j == 1) {
          PetscReal u0[3] = {U[0], U[3], U[6]}, d;
          if (PetscAbsReal(u0[0]) > 0.9) {
            e[0] = 0;
            e[1] = 1;
          }
          d = FCDot(e, u0);
          for (int i = 0; i < 3; i++) e[i] -= d * u0[i];
          n = PetscSqrtReal(FCDot(e, e));
          for (int i = 0; i < 3; i++) e[i] /= n;
        }
        for (int i = 0; i < 3; i++) U[3 * i + j] = e[i];
      }
    }
    { /* Gram-Schmidt on the second column, third = first x second: det U = +1 */
      PetscReal u0[3] = {U[0], U[3], U[6]}, u1[3] = {U[1], U[4], U[7]}, u2[3], d = FCDot(u0, u1), n;
      for (int i = 0; i < 3; i++) u1[i] -= d * u0[i];
      n = PetscSqrtReal(FCDot(u1, u1));
      for (int i = 0; i < 3; i++) u1[i] /= n;
      FCCross(u0, u1, u2);
      for (int i = 0; i < 3; i++) {
        U[3 * i + 1] = u1[i];
        U[3 * i + 2] = u2[i];
      }
    }
    /* R = U V^T */
    for (int i = 0; i < 3; i++)
      for (int j = 0; j < 3; j++)
        R[3 * i + j] = U[3 * i] * V[3 * j] + U[3 * i + 1] * V[3 * j + 1] + U[3 * i + 2] * V[3 * j + 2];
  }
}

void FCCross(const PetscReal a[3], const PetscReal b[3], PetscReal c[3])
{
  PetscReal t[3] = {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
  c[0]           = t[0];
  c[1]           = t[1];
  c[2]           = t[2];
}

PetscReal FCDot(const PetscReal a[3], const PetscReal b[3])
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

void FCQuatFromAxisAngle(const PetscReal axis[3], PetscReal angle, PetscReal q[4])
{
  PetscReal n = PetscSqrtReal(FCDot(axis, axis)), s;
  if (n == 0.0 || angle == 0.0) {
    q[0] = 1;
    q[1] = q[2] = q[3] = 0;
    return;
  }
  s    = PetscSinReal(0.5 * angle) / n;
  q[0] = PetscCosReal(0.5 * angle);
  q[1] = s * axis[0];
  q[2] = s * axis[1];
  q[3] = s * axis[2];
}

void FCQuatMult(const PetscReal a[4], const PetscReal b[4], PetscReal c[4])
{
  PetscReal t[4];
  t[0] = a[0] * b[0] - a[1] * b[1] - a[2] * b[2] - a[3] * b[3];
  t[1] = a[0] * b[1] + a[1] * b[0] + a[2] * b[3] - a[3] * b[2];
  t[2] = a[0] * b[2] - a[1] * b[3] + a[2] * b[0] + a[3] * b[1];
  t[3] = a[0] * b[3] + a[1] * b[2] - a[2] * b[1] + a[3] * b[0];
  for (int i = 0; i < 4; i++) c[i] = t[i];
}

void FCQuatNormalize(PetscReal q[4])
{
  PetscReal n = PetscSqrtReal(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
  for (int i = 0; i < 4; i++) q[i] /= n;
  if (q[0] < 0)
    for (int i = 0; i < 4; i++) q[i] = -q[i]; /* one sign for output */
}

void FCQuatToMat3(const PetscReal q[4], PetscReal R[9])
{
  PetscReal w = q[0], x = q[1], y = q[2], z = q[3];
  R[0] = 1 - 2 * (y * y + z * z);
  R[1] = 2 * (x * y - w * z);
  R[2] = 2 * (x * z + w * y);
  R[3] = 2 * (x * y + w * z);
  R[4] = 1 - 2 * (x * x + z * z);
  R[5] = 2 * (y * z - w * x);
  R[6] = 2 * (x * z - w * y);
  R[7] = 2 * (y * z + w * x);
  R[8] = 1 - 2 * (x * x + y * y);
}

/* Exact rotation by the world-frame angular velocity over h: q_new = exp(h omega / 2) q */
void FCQuatIntegrate(const PetscReal q[4], const PetscReal omega[3], PetscReal h, PetscReal qn[4])
{
  PetscReal dq[4], n = PetscSqrtReal(FCDot(omega, omega));
  FCQuatFromAxisAngle(omega, n * h, dq);
  FCQuatMult(dq, q, qn);
  FCQuatNormalize(qn);
}
