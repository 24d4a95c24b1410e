/* Material registry: -<body>_material <type>. One file per model registers a constructor
   that fills the element force/stiffness and energy kernels. */
#include "../fcimpl.h"

PetscFunctionList FCMaterialList = NULL;

/* The built-in models: a new model is one file with its create function, declared and registered here */
PETSC_INTERN PetscErrorCode FCMaterialCreate_Linear(FCMaterial);
PETSC_INTERN PetscErrorCode FCMaterialCreate_Corotational(FCMaterial);
PETSC_INTERN PetscErrorCode FCMaterialCreate_NeoHookean(FCMaterial);
PETSC_INTERN PetscErrorCode FCMaterialCreate_StVK(FCMaterial);

PetscErrorCode FCMaterialRegister(const char name[], PetscErrorCode (*create)(FCMaterial))
{
  PetscFunctionBegin;
  FCValidPointer(name, 1);
  FCValidPointer(create, 2);
  PetscCall(PetscFunctionListAdd(&FCMaterialList, name, create));
  PetscFunctionReturn(0);
}

PetscErrorCode FCMaterialRegisterAll(void)
{
  PetscFunctionBegin;
  PetscCall(FCMaterialRegister("linear", FCMaterialCreate_Linear));
  PetscCall(FCMaterialRegister("corotational", FCMaterialCreate_Corotational));
  PetscCall(FCMaterialRegister("neohookean", FCMaterialCreate_NeoHookean));
  PetscCall(FCMaterialRegister("stvk", FCMaterialCreate_StVK));
  PetscFunctionReturn(0);
}

/* Lame parameters from Young's modulus E > 0 and Poisson's ratio -1 < nu < 1/2 */
PetscErrorCode FCMaterialCreate(const char type[], PetscReal young, PetscReal poisson, FCMaterial *mat)
{
  PetscErrorCode (*create)(FCMaterial) = NULL;
  FCMaterial m;

  PetscFunctionBegin;
  PetscCall(FCRegistryFind(PETSC_COMM_SELF, FCMaterialList, "material", "-<body>_material", type,
                           (void (**)(void)) & create));
  PetscCall(PetscNew(&m));
  PetscCall(PetscStrncpy(m->type, type, sizeof(m->type)));
  m->young   = young;
  m->poisson = poisson;
  m->lambda  = young * poisson / ((1.0 + poisson) * (1.0 - 2.0 * poisson));
  m->mu      = young / (2.0 * (1.0 + poisson));
  PetscCall((*create)(m));
  *mat = m;
  PetscFunctionReturn(0);
}

/* Hooke's law on the displacement gradient H: sigma = lambda tr(eps) I + 2 mu eps, eps = (H + H^T) / 2 */
void FCMaterialHooke(FCMaterial m, const PetscReal H[9], PetscReal sigma[9])
{
  PetscReal tr = H[0] + H[4] + H[8];
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++)
      sigma[3 * i + j] = m->mu * (H[3 * i + j] + H[3 * j + i]) + (i == j ? m->lambda * tr : 0.0);
}

/* The strain energy of a P1 element of volume vol whose displacement gradient is H (constant over
   it): vol/2 sigma(H) : H, equal to 1/2 u^T K_e u for the nodal displacements u that produce H,
   without forming K_e */
PetscReal FCMaterialHookeEnergy(FCMaterial m, const PetscReal H[9], PetscReal vol)
{
  PetscReal sigma[9], e = 0.0;
  FCMaterialHooke(m, H, sigma);
  for (int k = 0; k < 9; k++) e += sigma[k] * H[k];
  return 0.5 * vol * e;
}

/* Deformation gradient of a P1 tetrahedron: F = Ds Dm^-1, Ds the edge vectors x_a - x_0 as columns */
void FCMaterialDeformationGradient(const PetscReal x[12], const PetscReal Dminv[9], PetscReal F[9])
{
  PetscReal Ds[9];
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) Ds[3 * i + j] = x[3 * (j + 1) + i] - x[i];
  FCMat3Mult(Ds, Dminv, F);
}

void FCMaterialRotatedApply(FCMaterial m, const PetscReal R[9], const PetscReal Dminv[9], PetscReal vol,
                            const PetscReal x[12], PetscReal y[12])
{
  PetscReal G[12], H[9] = {0}, S[9], xl[3], fl[3], V = PetscAbsReal(vol), tr;

  FCTetGradients(Dminv, G);
  for (int b = 0; b < 4; b++) {
    const PetscReal *xb = &x[3 * b];
    for (int i = 0; i < 3; i++) xl[i] = R[i] * xb[0] + R[3 + i] * xb[1] + R[6 + i] * xb[2]; /* R^T x_b */
    for (int i = 0; i < 3; i++)
      for (int j = 0; j < 3; j++) H[3 * i + j] += xl[i] * G[3 * b + j];
  }
  tr = H[0] + H[4] + H[8];
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++)
      S[3 * i + j] = V * (m->mu * (H[3 * i + j] + H[3 * j + i]) + (i == j ? m->lambda * tr : 0.0));
  for (int a = 0; a < 4; a++) {
    const PetscReal *g = &G[3 * a];
    for (int i = 0; i < 3; i++) fl[i] = S[3 * i] * g[0] + S[3 * i + 1] * g[1] + S[3 * i + 2] * g[2];
    for (int i = 0; i < 3; i++) y[3 * a + i] = R[3 * i] * fl[0] + R[3 * i + 1] * fl[1] + R[3 * i + 2] * fl[2];
  }
}

PetscErrorCode FCMaterialDestroy(FCMaterial *mat)
{
  PetscFunctionBegin;
  PetscCall(PetscFree(*mat));
  PetscFunctionReturn(0);
}
