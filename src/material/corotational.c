/* Co-rotational linear elasticity (Felippa; Mueller & Gross 2004): the element rotation R is
   the rotational part of the polar decomposition of F = Ds Dm^-1. Elastic force
   f = R K_e (R^T x - X) and tangent K = R K_e R^T (the derivative of R is neglected, as in
   SOFA's TetrahedronFEMForceField). Rigid motions produce no force; A changes every step. */
#include "../fcimpl.h"

static PetscErrorCode Rotation(const PetscReal x[12], const PetscReal Dminv[9], PetscReal R[9])
{
  PetscReal F[9];

  PetscFunctionBegin;
  FCMaterialDeformationGradient(x, Dminv, F);
  FCMat3Polar(F, R);
  PetscFunctionReturn(0);
}

/* u_local = R^T x - X, expressed per vertex */
static void LocalDisplacement(const PetscReal R[9], const PetscReal x[12], const PetscReal X[12], PetscReal ul[12])
{
  for (int a = 0; a < 4; a++) {
    FCMat3TVec(R, &x[3 * a], &ul[3 * a]);
    for (int i = 0; i < 3; i++) ul[3 * a + i] -= X[3 * a + i];
  }
}

static PetscErrorCode Element_Corotational(FCMaterial m, const PetscReal x[12], const PetscReal X[12],
                                           const PetscReal Dminv[9], PetscReal vol, PetscReal f[12], PetscReal K[144])
{
  PetscReal R[9], G[12], Ke[144], ul[12], fl[12];

  PetscFunctionBegin;
  PetscCall(Rotation(x, Dminv, R));
  FCTetGradients(Dminv, G);
  FCTetStiffness(G, vol, m->lambda, m->mu, Ke);
  if (f) {
    LocalDisplacement(R, x, X, ul);
    for (int i = 0; i < 12; i++) {
      fl[i] = 0.0;
      for (int j = 0; j < 12; j++) fl[i] += Ke[12 * i + j] * ul[j];
    }
    for (int a = 0; a < 4; a++) FCMat3Vec(R, &fl[3 * a], &f[3 * a]);
  }
  if (K) { /* K_ab = R Ke_ab R^T, 3x3 block by block */
    for (int a = 0; a < 4; a++)
      for (int b = 0; b < 4; b++) {
        PetscReal B[9], T[9];
        for (int i = 0; i < 3; i++)
          for (int j = 0; j < 3; j++) B[3 * i + j] = Ke[(3 * a + i) * 12 + 3 * b + j];
        FCMat3Mult(R, B, T);
        for (int i = 0; i < 3; i++)
          for (int j = 0; j < 3; j++)
            K[(3 * a + i) * 12 + 3 * b + j] =
                T[3 * i] * R[3 * j] + T[3 * i + 1] * R[3 * j + 1] + T[3 * i + 2] * R[3 * j + 2];
      }
  }
  PetscFunctionReturn(0);
}

/* The rotation and, if f is not NULL, the internal force R K_e (R^T x - X) in the form of
   FCMaterialRotatedApply (no K_e formed) */
static PetscErrorCode Rotation_Corotational(FCMaterial m, const PetscReal x[12], const PetscReal X[12],
                                            const PetscReal Dminv[9], PetscReal vol, PetscReal f[12], PetscReal R[9])
{
  PetscReal Rx[12];

  PetscFunctionBegin;
  PetscCall(Rotation(x, Dminv, R));
  if (f) { /* R K_e (R^T x - X) = R K_e R^T (x - R X) */
    for (int a = 0; a < 4; a++) {
      FCMat3Vec(R, &X[3 * a], &Rx[3 * a]);
      for (int i = 0; i < 3; i++) Rx[3 * a + i] = x[3 * a + i] - Rx[3 * a + i];
    }
    FCMaterialRotatedApply(m, R, Dminv, vol, Rx, f);
  }
  PetscFunctionReturn(0);
}

/* The gradient of u_local = R^T x - X in the element's rotated frame: H = R^T F - I (constant over
   a P1 element), so a rigid motion has none */
static void RotatedGradient(const PetscReal x[12], const PetscReal Dminv[9], PetscReal H[9])
{
  PetscReal F[9], R[9];
  FCMaterialDeformationGradient(x, Dminv, F);
  FCMat3Polar(F, R);
  FCMat3MultTranspose(R, F, H);
  for (int i = 0; i < 3; i++) H[4 * i] -= 1.0;
}

/* 1/2 u_l^T K_e u_l, from the strain it produces (FCMaterialHookeEnergy: forming K_e cost as much as
   the polar decomposition, and this runs for every element at every step: the energy guard, the
   step's row) */
static PetscErrorCode Energy_Corotational(FCMaterial m, const PetscReal x[12], const PetscReal X[12],
                                          const PetscReal Dminv[9], PetscReal vol, PetscReal *E)
{
  PetscReal H[9];

  PetscFunctionBegin;
  (void)X;
  RotatedGradient(x, Dminv, H);
  *E = FCMaterialHookeEnergy(m, H, vol);
  PetscFunctionReturn(0);
}

/* sigma of the small strain in the element's rotated frame, expressed in that frame (its
   invariants, the von Mises stress among them, are those of R sigma R^T) */
static PetscErrorCode Stress_Corotational(FCMaterial m, const PetscReal x[12], const PetscReal X[12],
                                          const PetscReal Dminv[9], PetscReal sigma[9])
{
  PetscReal H[9];

  PetscFunctionBegin;
  (void)X;
  RotatedGradient(x, Dminv, H);
  FCMaterialHooke(m, H, sigma);
  PetscFunctionReturn(0);
}

PetscErrorCode FCMaterialCreate_Corotational(FCMaterial m)
{
  PetscFunctionBegin;
  m->linear   = PETSC_FALSE;
  m->element  = Element_Corotational;
  m->rotation = Rotation_Corotational;
  m->energy   = Energy_Corotational;
  m->stress   = Stress_Corotational;
  PetscFunctionReturn(0);
}
