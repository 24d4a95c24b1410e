/* fecontact: the frictional contact problem and its solvers, on their own (FCLIB problems, tools/).
   Included by fecontact.h. */
#pragma once

#include <petscsys.h>

/* ---------------------------------------------------------------------------------------
   Frictional contact problem FC(W, q, mu) in local coordinates (eq. 18): find r with
   u = W r + q, each contact's r in the Coulomb cone {||r_T|| <= mu r_n}, the modified velocity
   u + mu ||u_T|| e_N in the dual cone, orthogonal to r. Contacts have 1 (frictionless normal),
   2 (2D: normal + one tangent) or 3 (normal + two tangents) rows, ordered [n t1 t2].
   --------------------------------------------------------------------------------------- */
typedef struct _p_FCContactProblem *FCContactProblem;
/* Dense W: n x n, row-major, symmetric, used in place (no copy): it must outlive the problem */
PETSC_EXTERN PetscErrorCode FCContactProblemCreateDense(PetscInt nc, const PetscInt dim[], const PetscReal mu[],
                                                        const PetscReal W[], const PetscReal q[], FCContactProblem *);
/* Dense W held by block rows over comm: this rank passes only the rows of its contacts [c0, c1)
   (rows off[c0] .. off[c1] - 1, n values each, row-major; used in place), the block that
   FCContactSolverRowBlock gives it; the blocks tile the rows in rank order. Only a solver that
   splits its sweeps over comm takes it (src/contact/problem_rows.c) */
PETSC_EXTERN PetscErrorCode FCContactProblemCreateDenseRows(MPI_Comm comm, PetscInt nc, const PetscInt dim[],
                                                            const PetscReal mu[], PetscInt c0, PetscInt c1,
                                                            const PetscReal Wrows[], const PetscReal q[],
                                                            FCContactProblem *);
PETSC_EXTERN PetscErrorCode FCContactProblemCreateCSR(PetscInt nc, const PetscInt dim[], const PetscReal mu[],
                                                      const PetscInt rowptr[], const PetscInt col[],
                                                      const PetscReal val[], const PetscReal q[], FCContactProblem *);
/* mask[i]: contact i is dormant, a nearly redundant constraint the solver adds only where the
   solution without it leaves its normal gap below -depth (borrowed: kept alive by the caller,
   updated by FCContactSolverSolve with the contacts it woke) */
PETSC_EXTERN PetscErrorCode FCContactProblemSetDormant(FCContactProblem, PetscBool mask[], PetscReal depth);
PETSC_EXTERN PetscErrorCode FCContactProblemLoadFCLIB(const char path[], FCContactProblem *);
PETSC_EXTERN PetscErrorCode FCContactProblemWriteFCLIB(FCContactProblem, const char path[]);
/* W as a dense n x n row-major array (to be freed with PetscFree; the caller then makes a dense
   problem of it with FCContactProblemCreateDense, e.g. tools/fclib_solve -dense) */
PETSC_EXTERN PetscErrorCode FCContactProblemGetDenseW(FCContactProblem, PetscReal **W);
PETSC_EXTERN PetscErrorCode FCContactProblemGetSizes(FCContactProblem, PetscInt *ncontacts, PetscInt *nrows);
PETSC_EXTERN PetscErrorCode FCContactProblemGetFriction(FCContactProblem, PetscReal mu[]); /* per contact */
/* New right-hand side q (n values); a dense W borrowed by the problem may change in place too */
PETSC_EXTERN PetscErrorCode FCContactProblemSetRHS(FCContactProblem, const PetscReal q[]);
PETSC_EXTERN PetscErrorCode FCContactProblemVelocity(FCContactProblem, const PetscReal r[], PetscReal u[]);
/* Natural-map residual e_i = r_i - Proj_K(r_i - (u_i + mu ||u_T|| e_N)); returns sqrt(sum ||e_i||^2)
   (absolute) and that divided by max(||q||, eps) (relative, the normalization of Siconos 4.4) */
PETSC_EXTERN PetscErrorCode FCContactProblemResidual(FCContactProblem, const PetscReal r[], PetscReal *abs,
                                                     PetscReal *rel);
PETSC_EXTERN PetscErrorCode FCContactProblemDestroy(FCContactProblem *);

/* Exact solution of one contact's problem (W 3x3 or smaller, row-major): open, stick, or slip
   found by a root search on the slip direction; returns the local residual reached */
PETSC_EXTERN PetscErrorCode FCContactLocalSolve(PetscInt dim, const PetscReal W[], const PetscReal q[], PetscReal mu,
                                                PetscReal r[], PetscReal *residual);

typedef struct _p_FCContactSolver *FCContactSolver;
typedef const char                *FCContactSolverType;
#define FCCONTACTSOLVERAUTO "auto"
#define FCCONTACTSOLVERPGS "pgs"
#define FCCONTACTSOLVERNEWTON "newton"
/* A contact solver type (-contact_solver): one file whose create function sets the solve on one
   rank (src/contact/contactimpl.h), and this call */
PETSC_EXTERN PetscErrorCode FCContactSolverRegister(const char[], PetscErrorCode (*)(FCContactSolver));
PETSC_EXTERN PetscErrorCode FCContactSolverCreate(MPI_Comm, FCContactSolver *);
PETSC_EXTERN PetscErrorCode FCContactSolverSetFromOptions(FCContactSolver);
PETSC_EXTERN PetscErrorCode FCContactSolverSetTolerances(FCContactSolver, PetscReal tol, PetscInt max_it);
/* Called after every sweep with the iterate r: it may change the problem (FCContactProblemSetRHS,
   the entries of a borrowed dense W) and r (e.g. the same forces in new frames), and says so in
   *changed; the solver then recomputes W r + q and restarts its acceleration. NULL: none. */
typedef PetscErrorCode (*FCContactSolverUpdateFn)(void *ctx, FCContactProblem, PetscReal r[], PetscBool *changed);
PETSC_EXTERN PetscErrorCode FCContactSolverSetUpdate(FCContactSolver, FCContactSolverUpdateFn, void *ctx);
/* Whether the solver splits the sweeps of a dense problem of these contacts over its ranks
   (-pgs_ranks split, or auto at that size), and then this rank's block of contacts [c0, c1): the
   rows a problem by rows (FCContactProblemCreateDenseRows) must give it */
PETSC_EXTERN PetscErrorCode FCContactSolverRowBlock(FCContactSolver, PetscInt nc, const PetscInt dim[],
                                                    PetscBool *split, PetscInt *c0, PetscInt *c1);
/* r: warm start on input, solution on output */
PETSC_EXTERN PetscErrorCode FCContactSolverSolve(FCContactSolver, FCContactProblem, PetscReal r[]);
PETSC_EXTERN PetscErrorCode FCContactSolverGetConvergence(FCContactSolver, PetscInt *sweeps, PetscReal *residual,
                                                          PetscBool *converged);
PETSC_EXTERN PetscErrorCode FCContactSolverDestroy(FCContactSolver *);
