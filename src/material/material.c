/* Material registry: -<body>_material <type>. One file per model registers a constructor
   that fills the element force/stiffness and energy kernels. */
#include "../fcimpl.h"

PetscFunctionList FCMaterialList = NULL;

PetscErrorCode FCMaterialRegisterAll(void)
{
  PetscFunctionBegin;
  PetscCall(PetscFunctionListAdd(&FCMaterialList, "linear", FCMaterialCreate_Linear));
  PetscCall(PetscFunctionListAdd(&FCMaterialList, "corotational", FCMaterialCreate_Corotational));
  PetscFunctionReturn(0);
}

/* Lame parameters from Young's modulus E > 0 and Poisson's ratio -1 < nu < 1/2 */
PetscErrorCode FCMaterialCreate(const char type[], PetscReal young, PetscReal poisson, FCMaterial *mat)
{
  PetscErrorCode (*create)(FCMaterial) = NULL;
  FCMaterial m;

  PetscFunctionBegin;
  PetscCall(PetscFunctionListFind(FCMaterialList, type, &create));
  PetscCheck(create, PETSC_COMM_SELF, PETSC_ERR_ARG_UNKNOWN_TYPE,
             "Unknown material type '%s' (known: linear, corotational)", type);
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

PetscErrorCode FCMaterialDestroy(FCMaterial *mat)
{
  PetscFunctionBegin;
  PetscCall(PetscFree(*mat));
  PetscFunctionReturn(0);
}
