/* Compressible Neo-Hookean (Bonet & Wood, Nonlinear Continuum Mechanics for Finite Element
   Analysis, 2nd ed., eq. 6.27-6.28):
       W(F) = mu/2 (tr(F^T F) - 3) - mu ln J + lambda/2 (ln J)^2,   J = det F
       P    = mu (F - F^-T) + lambda ln J F^-T
       dP   = mu dF + (mu - lambda ln J) F^-T dF^T F^-T + lambda tr(F^-1 dF) F^-T
   lambda and mu are the Lame parameters of -<body>_young and -<body>_poisson: at small strain the
   model is linear elasticity with them. W grows without bound as J -> 0 (an element resists being
   crushed to nothing) and is objective (W(Q F) = W(F) for a rotation Q). */
#include "../fcimpl.h"

static PetscReal Density_NeoHookean(FCMaterial m, const PetscReal F[9])
{
  PetscReal I1 = 0.0, lnJ = PetscLogReal(FCMat3Det(F));
  for (int k = 0; k < 9; k++) I1 += F[k] * F[k];
  return 0.5 * m->mu * (I1 - 3.0) - m->mu * lnJ + 0.5 * m->lambda * lnJ * lnJ;
}

/* F^-T (row-major) */
static void InverseTranspose(const PetscReal F[9], PetscReal FiT[9])
{
  PetscReal Fi[9];
  (void)FCMat3Inverse(F, Fi); /* det F > 0: the kernels of hyperelastic.c check it first */
  FCMat3Transpose(Fi, FiT);
}

static void Piola_NeoHookean(FCMaterial m, const PetscReal F[9], PetscReal P[9])
{
  PetscReal FiT[9], lnJ = PetscLogReal(FCMat3Det(F));
  InverseTranspose(F, FiT);
  for (int k = 0; k < 9; k++) P[k] = m->mu * (F[k] - FiT[k]) + m->lambda * lnJ * FiT[k];
}

static void DPiola_NeoHookean(FCMaterial m, const PetscReal F[9], const PetscReal dF[9], PetscReal dP[9])
{
  PetscReal FiT[9], T[9], U[9], tr = 0.0, lnJ = PetscLogReal(FCMat3Det(F));
  InverseTranspose(F, FiT);
  /* tr(F^-1 dF) = F^-T : dF; F^-T dF^T F^-T = (F^-1 dF F^-1)^T */
  for (int k = 0; k < 9; k++) tr += FiT[k] * dF[k];
  for (int i = 0; i < 3; i++) /* T = F^-T dF^T */
    for (int j = 0; j < 3; j++)
      T[3 * i + j] = FiT[3 * i] * dF[3 * j] + FiT[3 * i + 1] * dF[3 * j + 1] + FiT[3 * i + 2] * dF[3 * j + 2];
  FCMat3Mult(T, FiT, U);
  for (int k = 0; k < 9; k++) dP[k] = m->mu * dF[k] + (m->mu - m->lambda * lnJ) * U[k] + m->lambda * tr * FiT[k];
}

PetscErrorCode FCMaterialCreate_NeoHookean(FCMaterial m)
{
  PetscFunctionBegin;
  m->density = Density_NeoHookean;
  m->piola   = Piola_NeoHookean;
  m->dpiola  = DPiola_NeoHookean;
  FCMaterialSetHyperelastic(m);
  PetscFunctionReturn(0);
}
