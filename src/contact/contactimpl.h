/* Private structures of the contact problem and solvers. */
#pragma once
#include "../fcimpl.h"

struct _p_FCContactProblem {
  PetscInt   nc, n;     /* contacts, rows                                  */
  PetscInt  *dim, *off; /* rows per contact (1..3), first row (off[nc] = n) */
  PetscReal *mu, *q;
  PetscInt  *rowptr, *col; /* block CSR over contacts, columns sorted         */
  PetscInt  *boff, *diag;  /* value offset of each block, diagonal block of each row */
  PetscReal *val;          /* blocks d_i x d_j, row-major                      */
};

/* Projection on the Coulomb cone {||x_T|| <= mu x_n} (d = 2, 3) or on R+ (d = 1) */
PETSC_INTERN void FCContactProjectCone(PetscInt d, PetscReal mu, const PetscReal x[], PetscReal p[]);
/* ||e||^2 of the natural map of one contact (see FCContactProblemResidual) */
PETSC_INTERN PetscReal FCContactNaturalMapError2(PetscInt dim, PetscReal mu, const PetscReal r[], const PetscReal u[]);
