/* St Venant-Kirchhoff: linear elasticity's law on the Green-Lagrange strain E = (F^T F - I) / 2,
       W(F) = lambda/2 (tr E)^2 + mu E : E,   S = lambda tr(E) I + 2 mu E,   P = F S
       dP   = dF S + F dS,  dS = lambda tr(dE) I + 2 mu dE,  dE = sym(F^T dF)
   Objective and exact for large rotations, but it softens in compression: past a compression of
   about 42 % (uniaxial, nu = 0) its stress falls again and an element can be crushed through
   itself; neohookean is the model for compression. */
#include "../fcimpl.h"

static void Green(const PetscReal F[9], PetscReal E[9])
{
  FCMat3MultTranspose(F, F, E); /* F^T F */
  for (int k = 0; k < 9; k++) E[k] *= 0.5;
  for (int i = 0; i < 3; i++) E[4 * i] -= 0.5;
}

/* S = lambda tr(E) I + 2 mu E */
static void Hooke2(FCMaterial m, const PetscReal E[9], PetscReal S[9])
{
  PetscReal tr = E[0] + E[4] + E[8];
  for (int k = 0; k < 9; k++) S[k] = 2.0 * m->mu * E[k];
  for (int i = 0; i < 3; i++) S[4 * i] += m->lambda * tr;
}

static PetscReal Density_StVK(FCMaterial m, const PetscReal F[9])
{
  PetscReal E[9], tr, ee = 0.0;
  Green(F, E);
  tr = E[0] + E[4] + E[8];
  for (int k = 0; k < 9; k++) ee += E[k] * E[k];
  return 0.5 * m->lambda * tr * tr + m->mu * ee;
}

static void Piola_StVK(FCMaterial m, const PetscReal F[9], PetscReal P[9])
{
  PetscReal E[9], S[9];
  Green(F, E);
  Hooke2(m, E, S);
  FCMat3Mult(F, S, P);
}

static void DPiola_StVK(FCMaterial m, const PetscReal F[9], const PetscReal dF[9], PetscReal dP[9])
{
  PetscReal E[9], S[9], FtdF[9], dE[9], dS[9], a[9], b[9];
  Green(F, E);
  Hooke2(m, E, S);
  FCMat3MultTranspose(F, dF, FtdF);
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) dE[3 * i + j] = 0.5 * (FtdF[3 * i + j] + FtdF[3 * j + i]);
  Hooke2(m, dE, dS);
  FCMat3Mult(dF, S, a);
  FCMat3Mult(F, dS, b);
  for (int k = 0; k < 9; k++) dP[k] = a[k] + b[k];
}

PetscErrorCode FCMaterialCreate_StVK(FCMaterial m)
{
  PetscFunctionBegin;
  m->density = Density_StVK;
  m->piola   = Piola_StVK;
  m->dpiola  = DPiola_StVK;
  FCMaterialSetHyperelastic(m);
  PetscFunctionReturn(0);
}
