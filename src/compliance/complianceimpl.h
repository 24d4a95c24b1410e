/* Private definitions of the compliance builders (src/compliance/). A builder type fills the ops
   of an FCCompliance in its create function and owns its data (comp->data). compliance.c does
   what every builder shares: J_b^T of the step by entries, the scatter of W_b into W, and the
   correction by one solve for builders that keep no A^-1 J_b^T. */
#pragma once
#include "../fcimpl.h"

typedef struct {
  PetscErrorCode (*setfromoptions)(FCCompliance, PetscOptionItems *);
  PetscErrorCode (*setup)(FCCompliance);  /* at set-up, A at the reference state       */
  PetscErrorCode (*factor)(FCCompliance); /* A was factored again                       */
  /* Wb (ncols x ncols, row-major, to be complete on every rank) = J_b A^-1 J_b^T. Wb is zeroed,
     unless the builder sets `keepswb`: then it holds the last build's W_b when comp->wb_valid,
     and a builder that knows it still holds leaves it and sets comp->kept */
  PetscErrorCode (*build)(FCCompliance, PetscInt self, const FCContactSet *, PetscReal Wb[]);
  /* bytes of Sigma / C and of the factor on this rank and on the largest (NULL: none) */
  PetscErrorCode (*memory)(FCCompliance, PetscReal *sigma, PetscReal *factor, PetscReal *factormax);
  /* x = A^-1 b for the correction (default: a solve with the body's factor) ... */
  PetscErrorCode (*solve)(FCCompliance, Vec b, Vec x);
  /* ... or the whole correction dv += h A^-1 J_b^T lambda from what build kept */
  PetscErrorCode (*correct)(FCCompliance, PetscReal h, const PetscReal lambda[], Vec dv);
  PetscErrorCode (*reset)(FCCompliance); /* forget the step's columns */
  /* J_b^T (jtr, ...) holds the contacts expected at the next factorization, not a step's: a
     builder whose factorization depends on the contact DOFs takes them (NULL: none does) */
  PetscErrorCode (*expect)(FCCompliance);
  PetscErrorCode (*destroy)(FCCompliance);
} FCComplianceOps;

struct _p_FCCompliance {
  FCComplianceContext ctx;
  char                type[FC_MAX_NAME];
  FCComplianceOps     ops;
  void               *data;
  PetscBool           setupcalled, rotation;
  PetscBool           factors; /* the builder factors A itself: the body's only factor (FCComplianceFactorsA) */
  PetscReal           R[9];    /* the body's best-fit rotation (builders that set `rotation`) */
  /* the warp of an older factor (FCComplianceSetWarp): NULL when A^-1 is the factor's */
  PetscInt         wnsurf, wnowned;
  const PetscInt  *wsdof;
  const PetscReal *wsQ, *woQ;
  PetscInt         nownfactor; /* factorizations the builder did on its own */
  /* J_b^T of the last Add, by entries: the first njt on owned DOFs, nje in all */
  PetscInt ncols, *cols; /* columns, and the row of W of each                   */
  /* W_b of the last build (FCComplianceBuild), added to W by FCComplianceAdd */
  PetscReal *Wb;
  PetscInt   wb_n;     /* its ncols */
  PetscInt   wa0, wa1; /* the rows of W_b kept: [wa0, wa1), those in this rank's rows of W (Wb is
                          (wa1 - wa0) x ncols) */
  PetscBool  windows;  /* ops.build fills only rows [wa0, wa1) (else it is given a whole W_b)    */
  PetscBool  wb_valid; /* it holds a complete W_b */
  PetscBool  keepswb;  /* the builder may keep it (ops.build) */
  PetscBool  kept;     /* the last build kept it: the W_b of the build before */
  PetscBool  pending;  /* built and not yet added (an Add needs a Build first) */
  PetscInt   njt, nje;
  PetscInt  *jtr, *jtc; /* row (global DOF - first owned DOF), column            */
  PetscReal *jtv;
  Vec        rhs, work; /* the default correction's right-hand side and solution */
};

/* Frame direction a (0: n, 1: t1, 2: t2) of a contact, signed for side `side` (0 or 1) */
PETSC_INTERN void FCComplianceDirection(const FCContact *, PetscInt side, PetscInt a, PetscReal e[3]);
/* S, the sorted global DOFs that J_b touches (the same on every rank: contacts are replicated),
   and J_S by columns of S: for S index j, the rows crow[cptr[j] .. cptr[j+1]) of J_b and their
   values (all five arrays to free) */
PETSC_INTERN PetscErrorCode FCComplianceContactDofs(FCCompliance, PetscInt *ns, PetscInt **S, PetscInt **cptr,
                                                    PetscInt **crow, PetscReal **cval);
/* W_b += the part of J_S C J_S^T from column j of C = (A^-1)_SS, given as C(:, j) in S order */
PETSC_INTERN void FCComplianceAddColumn(PetscInt ncols, PetscInt ns, const PetscInt cptr[], const PetscInt crow[],
                                        const PetscReal cval[], PetscInt j, const PetscScalar Ccol[], PetscReal T[],
                                        PetscReal Wb[]);
/* Rows [a0, a1) of W_b += J_T C J_T^T for a dense symmetric C: C(pos[i], pos[k]) is the entry of
   the contact DOFs T[i], T[k] (J_T by columns as FCComplianceContactDofs returns it, nt of them).
   C is column-major with leading dimension ldc, given whole (lcol NULL: column pos[k] at
   pos[k] ldc) or by some of its columns (column pos[k] at lcol[pos[k]] ldc, absent where
   lcol[pos[k]] < 0: the sum then holds only the terms of those columns). Wb holds rows a0 .. a1 - 1
   (ncols each); row by row, without the column loop's scattered writes */
PETSC_INTERN PetscErrorCode FCComplianceAddCongruence(PetscInt ncols, PetscInt a0, PetscInt a1, PetscInt nt,
                                                      const PetscInt cptr[], const PetscInt crow[],
                                                      const PetscReal cval[], const PetscInt pos[],
                                                      const PetscInt lcol[], PetscInt ldc, const PetscReal C[],
                                                      PetscReal Wb[]);
/* Whether the body's KSP is preonly + Cholesky by MUMPS (the default) */
PETSC_INTERN PetscErrorCode FCComplianceBodySolverIsMumps(FCCompliance, PetscBool *);
/* The factor of A (the body's KSP) */
PETSC_INTERN PetscErrorCode FCComplianceGetFactor(FCCompliance, Mat *F);

#ifndef FC_SPD_BLOCK
#define FC_SPD_BLOCK 64 /* ScaLAPACK block size (rows and columns) of Sigma and C */
#endif

/* Where C = Sigma^-1 is formed (spdinverse.c; -compliance_condensed_inverse) */
typedef enum {
  FC_SPD_INVERSE_HOST,
  FC_SPD_INVERSE_SCALAPACK,
  FC_SPD_INVERSE_COLUMNS,
  FC_SPD_INVERSE_DISTRIBUTED, /* Sigma from MUMPS and C kept distributed by block-cyclic columns */
  FC_SPD_INVERSE_AUTO         /* distributed on several ranks from a Schur block size on, else host */
} FCSPDInverseType;

/* One MUMPS Cholesky factorization of A with a set S of DOFs ordered last (METIS nested
   dissection before them), giving C = (A^-1)_SS on rank 0 besides the solves (schurfactor.c) */
typedef struct _FCSchurFactor *FCSchurFactor;
/* schurorder.c: perm (1-based, MUMPS' ICNTL(7) = 1) of the N DOFs: the interior vertex blocks of A's vertex-block graph
   (nb, gxadj, gadj) by nested dissection (balance: top levels balanced in the vertices next to S), then the ns DOFs S
   last in their order */
PETSC_INTERN PetscErrorCode FCSchurOrdering(const char name[], PetscInt nb, const PetscInt gxadj[],
                                            const PetscInt gadj[], PetscInt ns, const PetscInt S[], PetscInt N,
                                            PetscInt balance, PetscInt perm[]);
/* distributed_inverse: C = Sigma^-1 by ScaLAPACK over the ranks, else LAPACK on rank 0;
   balance: top levels of the nested dissection bisected in balance of the vertices next to S */
PETSC_INTERN PetscErrorCode FCSchurFactorCreate(Mat A, const char name[], FCSPDInverseType inverse, PetscInt balance,
                                                PetscInt distmin, FCSchurFactor *);
/* rank 0: sorted DOFs, whole vertex blocks (the other ranks' arguments are ignored); collective */
PETSC_INTERN PetscErrorCode FCSchurFactorSetSchur(FCSchurFactor, PetscInt ns, const PetscInt S[]);
PETSC_INTERN PetscErrorCode FCSchurFactorFactor(FCSchurFactor, Mat A);
PETSC_INTERN PetscErrorCode FCSchurFactorSolve(FCSchurFactor, Vec b, Vec x);
/* rank 0: S and C (ns x ns, column-major) of the current factorization */
PETSC_INTERN PetscErrorCode FCSchurFactorGetInverse(FCSchurFactor, PetscInt *ns, const PetscInt **S,
                                                    const PetscReal **C);
/* every rank: whether C is distributed, S, and this rank's ns x nloc block-cyclic columns of C */
PETSC_INTERN PetscErrorCode FCSchurFactorGetLocalInverse(FCSchurFactor, PetscBool *dist, PetscInt *ns,
                                                         const PetscInt **S, PetscInt *nb, PetscInt *nloc,
                                                         const PetscReal **C);
/* bytes: this rank's Sigma / C, MUMPS' factorization memory on this rank and on the largest one */
PETSC_INTERN PetscErrorCode FCSchurFactorGetMemory(FCSchurFactor, PetscReal *sigma, PetscReal *factor,
                                                   PetscReal *factormax);
PETSC_INTERN PetscErrorCode FCSchurFactorGetGraph(FCSchurFactor, PetscInt *nb, const PetscInt **xadj,
                                                  const PetscInt **adj);
PETSC_INTERN PetscErrorCode FCSchurFactorGetCounts(FCSchurFactor, PetscInt *nanalysis, PetscInt *nfactor);
PETSC_INTERN PetscErrorCode FCSchurFactorDestroy(FCSchurFactor *);

/* C = Sigma^-1 of a dense SPD matrix held by rank 0 of comm: LAPACK there, or ScaLAPACK over
   every rank of comm (spdinverse.c) */
typedef struct _FCSPDInverse *FCSPDInverse;
PETSC_INTERN PetscErrorCode   FCSPDInverseCreate(MPI_Comm, const char name[], FCSPDInverseType, FCSPDInverse *);
/* rank 0: a = the upper triangle of Sigma (column-major ns x ns) in, the whole C out; collective */
PETSC_INTERN PetscErrorCode FCSPDInverseApply(FCSPDInverse, PetscInt ns, PetscReal a[]);
/* every rank: its block-cyclic columns (1 x p grid, blocks of nb, ns rows, lld ns) of Sigma (lower triangle at
   least) in, of the whole C out; collective */
PETSC_INTERN PetscErrorCode FCSPDInverseApplyLocal(FCSPDInverse, PetscInt ns, PetscInt nb, PetscReal loc[]);
/* the columns of an n x n matrix that a rank holds on the 1 x p grid: how many, and the global
   index of local column jl */
PETSC_INTERN PetscInt FCSPDLocalColumns(PetscInt n, PetscInt nb, PetscMPIInt rank, PetscMPIInt size);
PETSC_INTERN PetscInt FCSPDGlobalColumn(PetscInt jl, PetscInt nb, PetscMPIInt rank, PetscMPIInt size);
/* the block size of a distributed n x n matrix on size ranks: FC_SPD_BLOCK, smaller where n is
   small, so that the ranks' columns stay even (at least 4 blocks a rank) */
PETSC_INTERN PetscInt       FCSPDBlock(PetscInt n, PetscMPIInt size);
PETSC_INTERN PetscErrorCode FCSPDInverseDestroy(FCSPDInverse *);
