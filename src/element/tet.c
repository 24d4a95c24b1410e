/* P1 tetrahedron kernels. Reference data Dm = [X1-X0, X2-X0, X3-X0] (columns), the
   deformation gradient of an element is F = Ds Dm^-1 with Ds built the same way from the
   current positions. DOFs of an element are ordered [x0 y0 z0 x1 ... z3]. */
#include "../fcimpl.h"

static void EdgeMatrix(const PetscReal X[12], PetscReal D[9])
{
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) D[3 * i + j] = X[3 * (j + 1) + i] - X[i];
}

/* vol is the signed volume det(Dm)/6; the caller decides what a sign means */
PetscErrorCode FCTetReference(const PetscReal X[12], PetscReal Dminv[9], PetscReal *vol)
{
  PetscReal D[9], d;

  PetscFunctionBegin;
  EdgeMatrix(X, D);
  d    = FCMat3Det(D);
  *vol = d / 6.0;
  if (d == 0.0) {
    for (int i = 0; i < 9; i++) Dminv[i] = 0.0;
    PetscFunctionReturn(0);
  }
  PetscCall(FCMat3Inverse(D, Dminv));
  PetscFunctionReturn(0);
}

/* grad N_{a} for a = 1..3 are the rows of Dm^-1; grad N_0 = -(sum of them) */
void FCTetGradients(const PetscReal Dminv[9], PetscReal G[12])
{
  for (int j = 0; j < 3; j++) {
    G[j] = -(Dminv[j] + Dminv[3 + j] + Dminv[6 + j]);
    for (int a = 1; a < 4; a++) G[3 * a + j] = Dminv[3 * (a - 1) + j];
  }
}

/* K_{ai,bj} = V (lambda g_ai g_bj + mu g_aj g_bi + mu delta_ij g_a . g_b) */
void FCTetStiffness(const PetscReal G[12], PetscReal vol, PetscReal lambda, PetscReal mu, PetscReal K[144])
{
  PetscReal V = PetscAbsReal(vol);
  for (int a = 0; a < 4; a++)
    for (int b = 0; b < 4; b++) {
      PetscReal gg = G[3 * a] * G[3 * b] + G[3 * a + 1] * G[3 * b + 1] + G[3 * a + 2] * G[3 * b + 2];
      for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
          K[(3 * a + i) * 12 + 3 * b + j] =
              V * (lambda * G[3 * a + i] * G[3 * b + j] + mu * G[3 * a + j] * G[3 * b + i] + (i == j ? mu * gg : 0.0));
    }
}

/* Consistent: M_ab = rho V (1 + delta_ab) / 20 I3. Lumped: rho V / 4 on the diagonal. */
void FCTetMass(PetscReal rho, PetscReal vol, PetscBool lumped, PetscReal M[144])
{
  PetscReal V = PetscAbsReal(vol);
  for (int i = 0; i < 144; i++) M[i] = 0.0;
  for (int a = 0; a < 4; a++)
    for (int b = 0; b < 4; b++) {
      PetscReal m = lumped ? (a == b ? rho * V / 4.0 : 0.0) : rho * V * (a == b ? 2.0 : 1.0) / 20.0;
      for (int i = 0; i < 3; i++) M[(3 * a + i) * 12 + 3 * b + i] = m;
    }
}
