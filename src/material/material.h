/* Materials (src/material/): one file per model, registered in FCMaterialList */
#pragma once

#include "../element/element.h"

struct _p_FCMaterial {
  char      type[FC_MAX_NAME];
  PetscReal young, poisson, lambda, mu;
  PetscBool linear; /* constant stiffness: K assembled and A factored once per run */
  /* Element internal force f (12) and tangent stiffness K (12x12) at current positions x,
     reference positions X. Either output may be NULL. */
  PetscErrorCode (*element)(FCMaterial, const PetscReal x[12], const PetscReal X[12], const PetscReal Dminv[9],
                            PetscReal vol, PetscReal f[12], PetscReal K[144]);
  /* Models whose tangent is R K_e R^T, K_e the element's linear stiffness (co-rotational; NULL
     for the others): the element rotation R (3x3, row-major) at positions x and, if f is not NULL,
     the internal force. With R kept per cell, FCMaterialRotatedApply forms K x without K */
  PetscErrorCode (*rotation)(FCMaterial, const PetscReal x[12], const PetscReal X[12], const PetscReal Dminv[9],
                             PetscReal vol, PetscReal f[12], PetscReal R[9]);
  /* Element elastic energy */
  PetscErrorCode (*energy)(FCMaterial, const PetscReal x[12], const PetscReal X[12], const PetscReal Dminv[9],
                           PetscReal vol, PetscReal *E);
  /* Element stress (3x3, row-major, Pa) of the model's linear law: sigma = lambda tr(eps) I + 2 mu eps with
     eps the small strain of the element (co-rotational: in the element's rotated frame, R^T F - I) */
  PetscErrorCode (*stress)(FCMaterial, const PetscReal x[12], const PetscReal X[12], const PetscReal Dminv[9],
                           PetscReal sigma[9]);
  /* Hyperelastic models (hyperelastic.c; NULL for the others): the strain-energy density W(F), the
     first Piola-Kirchhoff stress P(F) and its derivative dP along dF, F row-major with det F > 0 */
  PetscBool hyperelastic;
  PetscReal (*density)(FCMaterial, const PetscReal F[9]);
  void (*piola)(FCMaterial, const PetscReal F[9], PetscReal P[9]);
  void (*dpiola)(FCMaterial, const PetscReal F[9], const PetscReal dF[9], PetscReal dP[9]);
  PetscInt ninverted; /* cells met with det F <= 0 by the hyperelastic kernels (reset by their callers) */
};
PETSC_EXTERN PetscFunctionList FCMaterialList;
PETSC_INTERN PetscErrorCode    FCMaterialRegisterAll(void);
PETSC_INTERN PetscErrorCode    FCMaterialCreate(const char type[], PetscReal young, PetscReal poisson, FCMaterial *);
PETSC_INTERN void              FCMaterialHooke(FCMaterial, const PetscReal H[9], PetscReal sigma[9]);
PETSC_INTERN PetscReal         FCMaterialHookeEnergy(FCMaterial, const PetscReal H[9], PetscReal vol);
/* y (12) = R K_e R^T x (12) of one element, K_e the linear stiffness of its gradients (Dminv, vol):
   V sigma(H) g_a per vertex a, H = sum_b (R^T x_b) g_b^T, sigma = lambda tr(H) I + mu (H + H^T), the
   product FCTetStiffness' matrix gives, without forming it */
PETSC_INTERN void FCMaterialRotatedApply(FCMaterial, const PetscReal R[9], const PetscReal Dminv[9], PetscReal vol,
                                         const PetscReal x[12], PetscReal y[12]);
PETSC_INTERN void FCMaterialDeformationGradient(const PetscReal x[12], const PetscReal Dminv[9], PetscReal F[9]);
PETSC_INTERN PetscErrorCode FCMaterialDestroy(FCMaterial *);
/* A hyperelastic model's element, energy and stress kernels from its density, P and dP */
PETSC_INTERN void FCMaterialSetHyperelastic(FCMaterial);
