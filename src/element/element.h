/* P1 tetrahedron kernels (src/element/tet.c) */
#pragma once

#include "../util/util.h"

/* Reference data of one tet: inverse edge matrix Dm^-1 (Dm = [X1-X0, X2-X0, X3-X0]) and volume */
PETSC_INTERN PetscErrorCode FCTetReference(const PetscReal X[12], PetscReal Dminv[9], PetscReal *vol);
/* Shape function gradients grad N_a (4 x 3) from Dm^-1 */
PETSC_INTERN void FCTetGradients(const PetscReal Dminv[9], PetscReal G[12]);
/* Linear isotropic element stiffness (12 x 12, row-major) */
PETSC_INTERN void FCTetStiffness(const PetscReal G[12], PetscReal vol, PetscReal lambda, PetscReal mu,
                                 PetscReal K[144]);
/* Mass of a tet, consistent (12 x 12) or lumped (diagonal, stored dense) */
PETSC_INTERN void FCTetMass(PetscReal rho, PetscReal vol, PetscBool lumped, PetscReal M[144]);
