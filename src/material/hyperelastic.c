/* The element kernels of a hyperelastic model, from its strain-energy density W(F), its first
   Piola-Kirchhoff stress P = dW/dF and the directional derivative dP = (d^2 W / dF^2) : dF (the
   model's file gives the three; FCMaterialSetHyperelastic installs these kernels). For a P1
   tetrahedron F = sum_a x_a g_a^T is constant over the cell, with g_a the reference gradient of
   the shape function of vertex a, and
       E   = V W(F)
       f_a = V P g_a                                   (internal force, dE/dx_a)
       K_(ai)(bk) = V sum_J dP[e_k g_b^T]_iJ g_aJ      (consistent tangent, d f_a,i / d x_b,k)
       sigma = J^-1 P F^T                              (Cauchy stress, for the von Mises field)
   V the reference volume. A cell with J = det F <= 0 has no energy the model can give (its log J or
   its stiffening is undefined): the kernels return a zero force and stiffness there and count it
   in m->ninverted, so that a Newton iterate that reaches one is cut back (fem_newton.c) and a step
   that ends with one stops with the located error of the inverted-element check (fem_state.c). */
#include "../fcimpl.h"

static PetscBool Inverted(FCMaterial m, const PetscReal F[9])
{
  if (FCMat3Det(F) > 0.0) return PETSC_FALSE;
  m->ninverted++;
  return PETSC_TRUE;
}

static PetscErrorCode Element_Hyperelastic(FCMaterial m, const PetscReal x[12], const PetscReal X[12],
                                           const PetscReal Dminv[9], PetscReal vol, PetscReal f[12], PetscReal K[144])
{
  PetscReal F[9], G[12], P[9], V = PetscAbsReal(vol);

  PetscFunctionBegin;
  (void)X;
  FCMaterialDeformationGradient(x, Dminv, F);
  if (Inverted(m, F)) {
    if (f) PetscCall(PetscArrayzero(f, 12));
    if (K) PetscCall(PetscArrayzero(K, 144));
    PetscFunctionReturn(0);
  }
  FCTetGradients(Dminv, G);
  if (f) {
    (*m->piola)(m, F, P);
    for (int a = 0; a < 4; a++)
      for (int i = 0; i < 3; i++)
        f[3 * a + i] = V * (P[3 * i] * G[3 * a] + P[3 * i + 1] * G[3 * a + 1] + P[3 * i + 2] * G[3 * a + 2]);
  }
  if (K)
    for (int b = 0; b < 4; b++)
      for (int k = 0; k < 3; k++) {
        PetscReal dF[9] = {0}, dP[9];
        for (int L = 0; L < 3; L++) dF[3 * k + L] = G[3 * b + L];
        (*m->dpiola)(m, F, dF, dP);
        for (int a = 0; a < 4; a++)
          for (int i = 0; i < 3; i++)
            K[(3 * a + i) * 12 + 3 * b + k] =
                V * (dP[3 * i] * G[3 * a] + dP[3 * i + 1] * G[3 * a + 1] + dP[3 * i + 2] * G[3 * a + 2]);
      }
  PetscFunctionReturn(0);
}

static PetscErrorCode Energy_Hyperelastic(FCMaterial m, const PetscReal x[12], const PetscReal X[12],
                                          const PetscReal Dminv[9], PetscReal vol, PetscReal *E)
{
  PetscReal F[9];

  PetscFunctionBegin;
  (void)X;
  FCMaterialDeformationGradient(x, Dminv, F);
  *E = Inverted(m, F) ? 0.0 : PetscAbsReal(vol) * (*m->density)(m, F);
  PetscFunctionReturn(0);
}

/* sigma = J^-1 P F^T */
static PetscErrorCode Stress_Hyperelastic(FCMaterial m, const PetscReal x[12], const PetscReal X[12],
                                          const PetscReal Dminv[9], PetscReal sigma[9])
{
  PetscReal F[9], P[9], J;

  PetscFunctionBegin;
  (void)X;
  FCMaterialDeformationGradient(x, Dminv, F);
  if (Inverted(m, F)) {
    PetscCall(PetscArrayzero(sigma, 9));
    PetscFunctionReturn(0);
  }
  J = FCMat3Det(F);
  (*m->piola)(m, F, P);
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++)
      sigma[3 * i + j] = (P[3 * i] * F[3 * j] + P[3 * i + 1] * F[3 * j + 1] + P[3 * i + 2] * F[3 * j + 2]) / J;
  PetscFunctionReturn(0);
}

void FCMaterialSetHyperelastic(FCMaterial m)
{
  m->linear       = PETSC_FALSE;
  m->hyperelastic = PETSC_TRUE;
  m->element      = Element_Hyperelastic;
  m->energy       = Energy_Hyperelastic;
  m->stress       = Stress_Hyperelastic;
}
