/* Private structures of the contact problem and solvers. */
#pragma once
#include "../fcimpl.h"

/* The contact solver's settings and last convergence (solver.c: options, placement; pgs.c: the sweeps;
   newton.c: the Newton driver) */
struct _p_FCContactSolver {
  MPI_Comm                comm;
  PetscReal               tol, residual, omega, proximal;
  PetscInt                max_it, sweeps;
  PetscBool               converged, nncg;
  PetscInt                placement;                /* PGSPlacement (-pgs_ranks) */
  PetscReal               split_damping;            /* -pgs_split_damping */
  PetscInt                split_min_rows;           /* -pgs_split_min_rows (auto) */
  PetscInt                split_max_it;             /* -pgs_split_max_it (auto): then root from there */
  char                    dump[PETSC_MAX_PATH_LEN]; /* -pgs_dump_problem */
  PetscInt                dump_rows;
  PetscBool               dumped, dump_unconverged; /* -pgs_dump_unconverged: the first unconverged problem */
  FCContactSolverUpdateFn update;                   /* after every sweep (FCContactSolverSetUpdate) */
  void                   *updatectx;
  char                    type[FC_MAX_NAME];                               /* -contact_solver (solver.c's registry) */
  PetscErrorCode (*solve)(FCContactSolver, FCContactProblem, PetscReal[]); /* the type's solve on this rank */
  PetscBool splits;                                                        /* its sweeps may be split (-pgs_ranks) */
  PetscBool newton;        /* it takes Newton steps (-contact_newton_*) */
  PetscInt  newton_max_it; /* -contact_newton_max_it */
  PetscBool giveup;        /* the sweeps stop once their rate says max_it will not do (auto) */
  PetscInt  newton_lu;     /* -contact_newton_lu (FCNewtonLU) */
};

/* newton_jacobian.c: the generalized Jacobian H = A + B W of a Newton step and its factorization */
typedef enum { FC_NEWTON_LU_AUTO, FC_NEWTON_LU_DENSE, FC_NEWTON_LU_SPARSE } FCNewtonLU;
typedef struct _n_FCNewtonJacobian *FCNewtonJacobian;
PETSC_INTERN PetscErrorCode         FCNewtonJacobianCreate(FCContactProblem, FCNewtonLU, FCNewtonJacobian *);
/* Solve (A + B W + reg I) dr = rhs in place; *ok false where the factorization failed */
PETSC_INTERN PetscErrorCode FCNewtonJacobianSolve(FCNewtonJacobian, const PetscReal A[], const PetscReal B[],
                                                  PetscReal reg, PetscReal rhs[], PetscBool *ok);
PETSC_INTERN PetscErrorCode FCNewtonJacobianDestroy(FCNewtonJacobian *);

struct _p_FCContactProblem {
  PetscInt   nc, n;     /* contacts, rows                                  */
  PetscInt  *dim, *off; /* rows per contact (1..3), first row (off[nc] = n) */
  PetscReal *mu, *q;
  PetscInt  *rowptr, *col; /* block CSR over contacts, columns sorted         */
  PetscInt  *boff, *diag;  /* value offset of each block, diagonal block of each row */
  PetscReal *val;          /* blocks d_i x d_j, row-major                      */
  /* dense W (FCContactProblemCreateDense): n x n, row-major, borrowed from the caller, which keeps
     it alive while the problem exists; then the block CSR arrays above are NULL */
  const PetscReal *Wd;
  /* dense W by block rows (FCContactProblemCreateDenseRows, problem.c): Wd holds only the rows
     [wlo, whi), those of contacts [c0, c1), this rank's block of rowcomm; whole W: MPI_COMM_NULL,
     rows [0, n) */
  MPI_Comm         rowcomm;
  PetscInt         c0, c1, wlo, whi;
  PetscMPIInt     *rcounts, *rdispls; /* every rank's rows (by rows) */
  PetscBool        symmetric;         /* W = W^T to round-off: its rows serve as its columns (dense: assumed) */
  FCContactProblem transpose;         /* a non-symmetric block-sparse W: W^T by blocks (its rows are W's columns) */
  PetscReal        qnorm;             /* ||q||, the residual's normalization */
  PetscBool       *dormant;           /* borrowed (FCContactProblemSetDormant): contacts the sweeps skip, r_i = 0 */
  PetscReal        wake;              /* a dormant contact wakes when its normal gap u_n < -wake */
};

/* Row k of a dense W (held by this rank) */
static inline const PetscReal *FCContactProblemRow(FCContactProblem p, PetscInt k)
{
  return p->Wd + (k - p->wlo) * p->n;
}
/* The blocks of contacts the split sweeps give the ranks: contiguous, about n / size rows each;
   cfirst[b] is block b's first contact, cfirst[size] = nc (pgs_split.c) */
PETSC_INTERN void FCContactSplitBlocks(PetscInt nc, const PetscInt off[], PetscMPIInt size, PetscInt cfirst[]);
/* u = W r + q of a problem by rows: each rank its rows, then every row on every rank (collective) */
PETSC_INTERN PetscErrorCode FCContactProblemVelocityRows(FCContactProblem, const PetscReal r[], PetscReal u[]);
/* A problem by rows gathered whole on rank 0 of its rowcomm (collective): *whole and its W (to be
   freed by the caller) on rank 0, NULL elsewhere; the whole one shares q, mu and the dormant mask */
PETSC_INTERN PetscErrorCode FCContactProblemGatherWhole(FCContactProblem, PetscReal **W, FCContactProblem *whole);

/* The relative natural-map residual of r given u = W r + q (no product with W) */
PETSC_INTERN PetscReal FCContactProblemResidualFromVelocity(FCContactProblem, const PetscReal r[], const PetscReal u[]);
/* u += W[:, rows of contact i] delta (d_i values): the change of u when r_i changes by delta (the
   rows of contact i in W when W is symmetric, in W^T otherwise) */
PETSC_INTERN void FCContactProblemAddColumns(FCContactProblem, PetscInt i, const PetscReal delta[], PetscReal u[]);
/* u += x a + y b + z c over n entries (the vectorized inner loop of a sweep, problem.c) */
PETSC_INTERN void FCContactAddRows3(PetscInt n, const PetscReal *restrict a, const PetscReal *restrict b,
                                    const PetscReal *restrict c, PetscReal x, PetscReal y, PetscReal z,
                                    PetscReal *restrict u);
/* One contact's step of a sweep (pgs.c, shared by the replicated and the split sweeps): the local
   problem (W_ii, u_i - W_ii r_i) with u_i = ui (its d_i rows of u = q + W r), proximal damping and
   relaxation; r_i updated in place, delta = its change, changed = whether it moved */
PETSC_INTERN PetscErrorCode FCContactLocalUpdate(FCContactProblem, PetscInt i, const PetscReal ui[], PetscReal omega,
                                                 PetscReal proximal, PetscReal r[], PetscReal delta[],
                                                 PetscBool *changed);
/* The diagonal block W_ii (d_i x d_i, row-major) */
PETSC_INTERN void FCContactProblemDiagonalBlock(FCContactProblem, PetscInt i, PetscReal Wii[9]);

/* FCContactLocalSolve with the slip direction bracketed on a grid only (no Newton): the reference
   the tests hold the fast local solve against */
PETSC_INTERN PetscErrorCode FCContactLocalSolveReference(PetscInt d, const PetscReal W[], const PetscReal q[],
                                                         PetscReal mu, PetscReal r[], PetscReal *residual);
/* Projection on the Coulomb cone {||x_T|| <= mu x_n} (d = 2, 3) or on R+ (d = 1) */
PETSC_INTERN void FCContactProjectCone(PetscInt d, PetscReal mu, const PetscReal x[], PetscReal p[]);
/* ||e||^2 of the natural map of one contact (see FCContactProblemResidual) */
PETSC_INTERN PetscReal FCContactNaturalMapError2(PetscInt dim, PetscReal mu, const PetscReal r[], const PetscReal u[]);

/* pgs.c: the sweeps (NNCG unless -pgs_acceleration none) on this rank, up to s->max_it */
PETSC_INTERN PetscErrorCode FCContactSolverSweeps(FCContactSolver, FCContactProblem, PetscReal[]);
/* newton.c: -contact_solver newton on this rank, rounds of sweeps then Newton steps */
PETSC_INTERN PetscErrorCode FCContactSolverNewton(FCContactSolver, FCContactProblem, PetscReal[]);
/* newton.c: -contact_solver auto on this rank: the sweeps, and FCContactSolverNewton from their iterate when their
   rate says they will not converge within max_it */
PETSC_INTERN PetscErrorCode FCContactSolverAuto(FCContactSolver, FCContactProblem, PetscReal[]);
/* newton.c: nonsmooth Newton on the Alart-Curnier function of a whole problem, on this rank, with the Jacobian J of the
   caller (FCNewtonJacobianCreate on the same problem); r in:
   the warm start, out: the forces; its = Newton steps taken, residual as FCContactProblemResidual */
PETSC_INTERN PetscErrorCode FCContactSolveNewton(FCContactProblem, FCNewtonJacobian, PetscReal tol, PetscInt max_it,
                                                 PetscReal r[], PetscInt *its, PetscReal *residual);
/* y = W x (a whole W on this rank) */
PETSC_INTERN PetscErrorCode FCContactProblemMult(FCContactProblem, const PetscReal x[], PetscReal y[]);
/* pgs_split.c: the sweeps split over the ranks of comm (-pgs_ranks split), dense W only; r in:
   the warm start (the same on every rank), out: the forces (the same on every rank). With
   giveup, the sweeps stop early, unconverged, once their rate of convergence says they would not
   reach tol within max_it (-pgs_ranks auto then goes on on rank 0) */
PETSC_INTERN PetscErrorCode FCContactSolveSplit(MPI_Comm, FCContactProblem, PetscReal tol, PetscInt max_it,
                                                PetscReal omega, PetscReal proximal, PetscReal damping,
                                                PetscBool giveup, PetscReal r[], PetscInt *sweeps, PetscReal *residual);
