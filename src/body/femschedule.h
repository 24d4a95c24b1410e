/* The factorization schedule of an FE body (-<body>_factorization): fem_schedule.c decides when A
   is factored and solves with the last factor, fem_warp.c computes what reuse needs without K
   (docs/method.md, "When A is factored"). Included by femimpl.h after the FEM struct. */
#pragma once

/* fem_schedule.c */
PETSC_INTERN PetscErrorCode FCFEMScheduleSetFromOptions(PetscOptionItems *, FCBody);
PETSC_INTERN PetscErrorCode FCFEMScheduleSetUp(FCBody);
PETSC_INTERN PetscErrorCode FCFEMScheduleOperator(FCBody, Vec state);
PETSC_INTERN PetscErrorCode FCFEMScheduleSolve(FCBody, Vec b, Vec x, PetscReal t);
PETSC_INTERN PetscErrorCode FCFEMScheduleKeepCorrection(FCBody, Vec x);
PETSC_INTERN PetscErrorCode FCFEMScheduleDestroy(FCBody);
/* fem_warp.c */
PETSC_INTERN PetscErrorCode FCFEMKMult(FCBody, Vec x, Vec y);
PETSC_INTERN PetscErrorCode FCFEMWarpAtState(FCBody, Vec state);
PETSC_INTERN PetscErrorCode FCFEMWarpVertexRotations(FCBody, PetscReal Rv[]);
PETSC_INTERN PetscErrorCode FCFEMWarpUpdate(FCBody, const PetscReal Rv[]);
PETSC_INTERN PetscErrorCode FCFEMWarpTurn(const PetscReal R[], Vec x, PetscBool transpose);
PETSC_INTERN PetscErrorCode FCFEMWarpAMult(Mat, Vec x, Vec y);
PETSC_INTERN PetscErrorCode FCFEMWarpSetUpContact(FCBody); /* the surface table of the builder's warp */
