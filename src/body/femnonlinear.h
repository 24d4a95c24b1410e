/* FE body, the nonlinear contact correction (fem_nonlinear.c, -<body>_correction nonlinear): its
   state is private to that file */
#pragma once
#include "bodyimpl.h"

typedef struct _FCFEMNonlinear *FCFEMNonlinear;

PETSC_INTERN PetscErrorCode FCFEMNonlinearSetFromOptions(PetscOptionItems *, FCBody);
PETSC_INTERN PetscErrorCode FCFEMNonlinearSetUp(FCBody); /* after FCFEMNewtonSetUp */
PETSC_INTERN PetscErrorCode FCFEMNonlinearDestroy(FCBody);
/* the free motion: its load b_c += h f_c, and after it dv_free = dv_load - h A^-1 f_c */
PETSC_INTERN PetscErrorCode FCFEMNonlinearAddLoad(FCBody, Vec bc);
PETSC_INTERN PetscErrorCode FCFEMNonlinearUnload(FCBody);
PETSC_INTERN PetscBool      FCFEMNonlinearLoaded(FCBody);
/* after the scheme: the equilibrium with the set's forces (held: what the springs still carry,
   relative), and the free motion linearized at it for the scheme to solve again */
PETSC_INTERN PetscErrorCode FCFEMNonlinearSettle(FCBody, const FCContactSet *, PetscReal t, PetscReal *held);
PETSC_INTERN PetscErrorCode FCFEMNonlinearRelinearize(FCBody);
/* the springs in the Newton residual F (at the end state w) and its Jacobian A */
PETSC_INTERN PetscErrorCode FCFEMNonlinearAddSpringForce(FCBody, Vec w, Vec F);
PETSC_INTERN PetscErrorCode FCFEMNonlinearAddSpringStiffness(FCBody, Mat A);
/* restart and step control: f_c and the sticking vertices (4 columns after u and v) */
PETSC_INTERN PetscErrorCode FCFEMNonlinearGetState(FCBody, PetscInt cols, PetscReal[]);
PETSC_INTERN PetscErrorCode FCFEMNonlinearSetState(FCBody, PetscInt cols, const PetscReal[]);
