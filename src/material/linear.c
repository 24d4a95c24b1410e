/* Linear isotropic elasticity (small strain): f = K_e (x - X), constant stiffness, so the
   body's A = M + hB + h^2 K (eq. 5) is assembled and factored once per run. */
#include "../fcimpl.h"

static PetscErrorCode Element_Linear(FCMaterial m, const PetscReal x[12], const PetscReal X[12],
                                     const PetscReal Dminv[9], PetscReal vol, PetscReal f[12], PetscReal K[144])
{
  PetscReal G[12], Ke[144], u[12];

  PetscFunctionBegin;
  FCTetGradients(Dminv, G);
  FCTetStiffness(G, vol, m->lambda, m->mu, Ke);
  if (f) {
    for (int i = 0; i < 12; i++) u[i] = x[i] - X[i];
    for (int i = 0; i < 12; i++) {
      f[i] = 0.0;
      for (int j = 0; j < 12; j++) f[i] += Ke[12 * i + j] * u[j];
    }
  }
  if (K) PetscCall(PetscArraycpy(K, Ke, 144));
  PetscFunctionReturn(0);
}

/* The displacement gradient of x - X: H = F - I (constant over a P1 element) */
static void Gradient(const PetscReal x[12], const PetscReal Dminv[9], PetscReal H[9])
{
  FCMaterialDeformationGradient(x, Dminv, H);
  for (int i = 0; i < 3; i++) H[4 * i] -= 1.0;
}

/* 1/2 (x - X)^T K_e (x - X), from the strain it produces (FCMaterialHookeEnergy) */
static PetscErrorCode Energy_Linear(FCMaterial m, const PetscReal x[12], const PetscReal X[12],
                                    const PetscReal Dminv[9], PetscReal vol, PetscReal *E)
{
  PetscReal H[9];

  PetscFunctionBegin;
  (void)X;
  Gradient(x, Dminv, H);
  *E = FCMaterialHookeEnergy(m, H, vol);
  PetscFunctionReturn(0);
}

/* sigma of the small strain of x - X */
static PetscErrorCode Stress_Linear(FCMaterial m, const PetscReal x[12], const PetscReal X[12],
                                    const PetscReal Dminv[9], PetscReal sigma[9])
{
  PetscReal H[9];

  PetscFunctionBegin;
  (void)X;
  Gradient(x, Dminv, H);
  FCMaterialHooke(m, H, sigma);
  PetscFunctionReturn(0);
}

PetscErrorCode FCMaterialCreate_Linear(FCMaterial m)
{
  PetscFunctionBegin;
  m->linear  = PETSC_TRUE;
  m->element = Element_Linear;
  m->energy  = Energy_Linear;
  m->stress  = Stress_Linear;
  PetscFunctionReturn(0);
}
