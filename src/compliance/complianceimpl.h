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
  /* Wb (ncols x ncols, row-major, zeroed, to be complete on every rank) = J_b A^-1 J_b^T */
  PetscErrorCode (*build)(FCCompliance, PetscInt self, const FCContactSet *, PetscReal Wb[]);
  /* x = A^-1 b for the correction (default: a solve with the body's factor) ... */
  PetscErrorCode (*solve)(FCCompliance, Vec b, Vec x);
  /* ... or the whole correction dv += h A^-1 J_b^T lambda from what build kept */
  PetscErrorCode (*correct)(FCCompliance, PetscReal h, const PetscReal lambda[], Vec dv);
  PetscErrorCode (*reset)(FCCompliance); /* forget the step's columns */
  PetscErrorCode (*destroy)(FCCompliance);
} FCComplianceOps;

struct _p_FCCompliance {
  FCComplianceContext ctx;
  char                type[FC_MAX_NAME];
  FCComplianceOps     ops;
  void               *data;
  PetscBool           setupcalled, rotation;
  PetscReal           R[9]; /* the body's best-fit rotation (builders that set `rotation`) */
  /* J_b^T of the last Add, by entries: the first njt on owned DOFs, nje in all */
  PetscInt   ncols, *cols; /* columns, and the row of W of each                   */
  PetscInt   njt, nje;
  PetscInt  *jtr, *jtc; /* row (global DOF - first owned DOF), column            */
  PetscReal *jtv;
  Vec        rhs, work; /* the default correction's right-hand side and solution */
};

/* Frame direction a (0: n, 1: t1, 2: t2) of a contact, signed for side `side` (0 or 1) */
PETSC_INTERN void FCComplianceDirection(const FCContact *, PetscInt side, PetscInt a, PetscReal e[3]);
/* The factor of A (the body's KSP) */
PETSC_INTERN PetscErrorCode FCComplianceGetFactor(FCCompliance, Mat *F);
/* Numeric Cholesky by MUMPS of a matrix a builder owns, with its failure checked (see the file) */
PETSC_INTERN PetscErrorCode FCComplianceMumpsCholesky(FCCompliance, Mat F, Mat K, const char what[]);
