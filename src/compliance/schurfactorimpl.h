/* The data of an FCSchurFactor (schurfactor.c: factorization, Schur block, solves; schurinput.c:
   MUMPS' input and the vertex graph of A) */
#pragma once
#include "complianceimpl.h"
#include <dmumps_c.h>

#define ICNTL(i) icntl[(i)-1]
#define INFOG(i) infog[(i)-1]
#define INFO(i) info[(i)-1]

struct _FCSchurFactor {
  MPI_Comm       comm; /* a duplicate of A's: MUMPS messages stay apart from PETSc's */
  PetscMPIInt    rank, size;
  char           name[FC_MAX_NAME];
  DMUMPS_STRUC_C id;
  PetscInt       N, lo, hi;
  PetscInt       nnz; /* upper-triangle entries of the owned rows */
  MUMPS_INT     *irn, *jcn;
  PetscReal     *val;
  /* host only */
  PetscInt     nb, *xadj, *adj; /* vertex-block graph of A (without self loops) */
  PetscInt     ns, *S;          /* Schur DOFs (sorted) of the current analysis */
  PetscInt     nsnext, *Snext;  /* requested by FCSchurFactorSetSchur */
  MUMPS_INT   *perm, *list;
  PetscReal   *sigma, *red, *work; /* Sigma from MUMPS, inverted in place into C = (A^-1)_SS; reduced rhs; C red */
  Vec          bseq;
  VecScatter   tohost;
  PetscBool    analysed, factored;
  FCSPDInverse inv;
  PetscInt     nanalysis, nfactor;
  PetscInt     balance; /* top levels of the dissection balanced in the vertices next to S (Dissect) */
  /* distributed Sigma and C (every rank): this analysis uses them, and when they are asked for */
  FCSPDInverseType type;
  PetscInt         distmin;
  PetscBool        dist;
  PetscInt         cnb, nloc, *Sall; /* block size and local columns of C; S on every rank */
  PetscReal       *loc, *rl, *yl;    /* ns x nloc (lld ns); r_S at the local columns; C_loc r_l */
};

/* The owned rows' upper triangle of A (values: only the values, A's pattern being fixed) */
PETSC_INTERN PetscErrorCode FCSchurFactorTriples(FCSchurFactor, Mat A, PetscBool values);
/* The vertex-block graph of A, gathered on the host */
PETSC_INTERN PetscErrorCode FCSchurFactorGatherGraph(FCSchurFactor, Mat A);
