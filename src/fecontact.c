/* Package registration: type registries (bodies, materials, shapes, compliance builders, schemes,
   contact solvers), the METIS mesh partitioner (a PetscPartitioner type), log events, and the BLAS
   option (-blas_gemv_forward, src/util/blas.c). */
#include "fcimpl.h"

static PetscBool initialized = PETSC_FALSE;
PetscClassId     FC_CLASSID; /* the package: its log events */

PETSC_INTERN PetscErrorCode FCPhaseRegisterEvents(PetscClassId);

PetscErrorCode FCInitializePackage(void)
{
  PetscFunctionBegin;
  if (initialized) PetscFunctionReturn(0);
  initialized = PETSC_TRUE;
  PetscCall(PetscClassIdRegister("fecontact", &FC_CLASSID));
  PetscCall(FCPhaseRegisterEvents(FC_CLASSID));
  PetscCall(FCBodyRegisterAll());
  PetscCall(FCMaterialRegisterAll());
  PetscCall(FCShapeRegisterAll());
  PetscCall(FCSchemeRegisterAll());
  PetscCall(FCComplianceRegisterAll());
  PetscCall(FCContactSolverRegisterAll());
  PetscCall(FCPartitionerRegisterMetis());
  PetscCall(FCBLASSetFromOptions());
  PetscCall(PetscRegisterFinalize(FCFinalizePackage));
  PetscFunctionReturn(0);
}

PetscErrorCode FCFinalizePackage(void)
{
  PetscFunctionBegin;
  PetscCall(FCBLASView());
  PetscCall(PetscFunctionListDestroy(&FCBodyList));
  PetscCall(PetscFunctionListDestroy(&FCMaterialList));
  PetscCall(PetscFunctionListDestroy(&FCShapeList));
  PetscCall(PetscFunctionListDestroy(&FCSchemeList));
  PetscCall(PetscFunctionListDestroy(&FCComplianceList));
  PetscCall(PetscFunctionListDestroy(&FCContactSolverList));
  initialized = PETSC_FALSE;
  PetscFunctionReturn(0);
}
