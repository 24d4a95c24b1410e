/* What every package shares: limits, the registry helper, small dense kernels, gathers, checked
   MUMPS factorizations, the BLAS option, the inputs a run reads, signals and the progress line
   (src/util/). */
#pragma once

#include <fecontact.h>

#define FC_MAX_NAME 64
#define FC_MAX_BODIES 256 /* bodies of a scene, and contact pairs */

/* The create function of `type` in a registry; an unknown type is an error naming `option` and listing the
   registered types (src/util/registry.c). `what` names the kind of type ("body type") */
PETSC_INTERN PetscErrorCode FCRegistryFind(MPI_Comm, PetscFunctionList, const char what[], const char option[],
                                           const char type[], void (**create)(void));

/* ---------------------------------------------------------------------------------------
   Small dense kernels (src/util/linalg.c): 3-vectors, 3x3 matrices (row-major), quaternions
   --------------------------------------------------------------------------------------- */
PETSC_INTERN void           FCMat3Identity(PetscReal[9]);
PETSC_INTERN void           FCMat3Mult(const PetscReal[9], const PetscReal[9], PetscReal[9]);
PETSC_INTERN void           FCMat3MultTranspose(const PetscReal[9], const PetscReal[9], PetscReal[9]); /* A^T B */
PETSC_INTERN void           FCMat3Transpose(const PetscReal[9], PetscReal[9]);
PETSC_INTERN void           FCMat3Vec(const PetscReal[9], const PetscReal[3], PetscReal[3]);
PETSC_INTERN void           FCMat3TVec(const PetscReal[9], const PetscReal[3], PetscReal[3]);
PETSC_INTERN PetscReal      FCMat3Det(const PetscReal[9]);
PETSC_INTERN PetscErrorCode FCMat3Inverse(const PetscReal[9], PetscReal[9]);
PETSC_INTERN void           FCMat3Polar(const PetscReal F[9], PetscReal R[9]); /* F = R S, det R = +1 */
PETSC_INTERN void           FCCross(const PetscReal[3], const PetscReal[3], PetscReal[3]);
PETSC_INTERN PetscReal      FCDot(const PetscReal[3], const PetscReal[3]);
PETSC_INTERN void FCQuatFromAxisAngle(const PetscReal axis[3], PetscReal angle, PetscReal q[4]); /* q = (w,x,y,z) */
PETSC_INTERN void FCQuatMult(const PetscReal[4], const PetscReal[4], PetscReal[4]);
PETSC_INTERN void FCQuatNormalize(PetscReal[4]);
PETSC_INTERN void FCQuatToMat3(const PetscReal[4], PetscReal[9]);
PETSC_INTERN void FCQuatIntegrate(const PetscReal q[4], const PetscReal omega[3], PetscReal h, PetscReal qn[4]);

/* src/util/gather.c: n records of `size` bytes from every rank, concatenated in rank order on every
   rank (*all: total records, to be freed) */
PETSC_INTERN PetscErrorCode FCAllgatherRecords(MPI_Comm, PetscInt n, size_t size, const void *loc, PetscInt *total,
                                               void **all);
/* src/util/mumps.c: MUMPS factorizations checked by MUMPS' own INFOG(1); out of workspace retried on
   a new factor with ICNTL(14) doubled, 3 times (a builder's factor, a KSP's; the latter with any
   other solver checked by its PC's failure reason) */
PETSC_INTERN PetscErrorCode FCMumpsCholeskyChecked(Mat *F, Mat A, IS schur, const char what[], const char body[]);
PETSC_INTERN PetscErrorCode FCMumpsKSPChecked(KSP ksp, Mat A, const char what[], const char body[]);
/* -blas_gemv_forward: dgemm with one column as dgemv (src/util/blas.c) */
PETSC_INTERN PetscErrorCode FCBLASSetFromOptions(void);
PETSC_INTERN PetscErrorCode FCBLASView(void); /* -info: how many products it computed so */

/* The files a run reads, by identity, and the check that an output is none of them
   (src/util/inputs.c) */
PETSC_INTERN PetscErrorCode FCInputsReset(void);
PETSC_INTERN PetscErrorCode FCInputsAdd(const char path[], const char what[]);
PETSC_INTERN PetscErrorCode FCInputsAddOptionsFiles(void);
PETSC_INTERN PetscErrorCode FCInputsCheckOutput(MPI_Comm, const char path[], const char what[]);
/* The output files of the live scenes, by identity: no two write one file (src/util/inputs.c) */
PETSC_INTERN PetscErrorCode FCOutputsCheckLive(MPI_Comm, const char path[]);
PETSC_INTERN PetscErrorCode FCOutputsAddLive(const void *owner, const char path[]);
PETSC_INTERN PetscErrorCode FCOutputsRemoveLive(const void *owner);

/* SIGINT/SIGTERM: recorded by a handler, acted on between steps (src/util/signals.c) */
PETSC_INTERN PetscErrorCode FCSignalsBlock(void);
PETSC_INTERN PetscErrorCode FCSignalsInstall(void);
PETSC_INTERN PetscErrorCode FCSignalsPending(MPI_Comm, int *sig);
PETSC_INTERN int            FCSignalsCaught(void);

/* Progress line on rank 0 (src/util/progress.c) */
typedef struct {
  PetscLogDouble start, last;
  PetscBool      quiet;
  PetscInt       warned; /* steps with a warning so far */
} FCProgress;
PETSC_INTERN PetscErrorCode FCProgressStart(FCProgress *, PetscBool quiet);
/* warning: what the step's end found wrong ("" when nothing); the first 10 such steps get their line
   whatever the time since the last one, each such line ends with the warning */
PETSC_INTERN PetscErrorCode FCProgressUpdate(FCProgress *, MPI_Comm, PetscInt step, PetscInt nsteps, PetscReal t,
                                             const char warning[]);

/* Tables of time (src/util/table.c): rows t, v_1..v_n, piecewise linear, constant outside them */
typedef struct _p_FCTable  *FCTable;
PETSC_INTERN PetscErrorCode FCTableCreate(MPI_Comm, const char spec[], PetscInt nmin, PetscInt nmax, const char what[],
                                          FCTable *);
PETSC_INTERN PetscInt       FCTableColumns(FCTable);
PETSC_INTERN const PetscReal *FCTableValues(FCTable, PetscInt *nrow);
PETSC_INTERN void             FCTableEval(FCTable, PetscReal t, PetscReal v[]);
PETSC_INTERN void      FCTableBracket(FCTable, PetscReal t, const PetscReal **a, const PetscReal **b, PetscReal *s);
PETSC_INTERN PetscReal FCTableMaxRate(FCTable, PetscInt j0, PetscInt j1);
PETSC_INTERN PetscErrorCode FCTableDestroy(FCTable *);

/* Errors a scene's step control redoes, and the handler around the calls that raise them (src/util/errors.c) */
PETSC_INTERN PetscBool      FCErrorIsStepFailure(PetscErrorCode);
PETSC_INTERN int            FCExitStatus(PetscErrorCode);
PETSC_INTERN PetscErrorCode FCPushStepErrorHandler(void);
PETSC_INTERN PetscErrorCode FCErrorAgree(MPI_Comm, PetscErrorCode);
/* A pointer argument of a public function (include/fecontact.h) that may not be NULL: an error naming the
   function and the argument rather than a crash (PETSc's PetscValidPointer checks nothing in an optimized
   build) */
#define FCValidPointer(p, arg)                                                                                         \
  PetscCheck((p) != NULL, PETSC_COMM_SELF, PETSC_ERR_ARG_NULL, "%s: argument %d (%s) is NULL", PETSC_FUNCTION_NAME,    \
             (int)(arg), #p)
