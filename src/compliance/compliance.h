/* Compliance builders (src/compliance/): W_b = J_b A_b^-1 J_b^T of an FE body (eq. 17) and its
   correction dv += h A_b^-1 J_b^T lambda (eq. 20); one file per type, -compliance_type */
#pragma once

#include "../contact/contact.h"

#define FCCOMPLIANCEDENSE "dense"
#define FCCOMPLIANCESPARSE "sparse"
#define FCCOMPLIANCESCHUR "schur"
#define FCCOMPLIANCEINVERSE "inverse"
#define FCCOMPLIANCEREDUNDANT "redundant"
#define FCCOMPLIANCEPRECOMPUTED "precomputed"
#define FCCOMPLIANCECONDENSED "condensed"
/* What a builder gets from its FE body; it never calls the body back */
typedef struct {
  MPI_Comm        comm;
  const char     *name, *prefix; /* the body's, for messages */
  Vec             u;             /* layout of the rows of A (a global state vector)            */
  Mat             A;             /* A = M + h B + h^2 K, current with its factor              */
  KSP             ksp;           /* the factorization of A (preonly + Cholesky)               */
  PetscBool       linear;        /* A never changes                                           */
  PetscInt        nsurface;      /* first global DOF of the owned non-fixed boundary vertices */
  const PetscInt *surface;
} FCComplianceContext;
PETSC_EXTERN PetscFunctionList FCComplianceList;
PETSC_INTERN PetscErrorCode    FCComplianceRegisterAll(void);
PETSC_INTERN PetscErrorCode    FCComplianceCreate(const FCComplianceContext *, FCCompliance *);
PETSC_INTERN PetscErrorCode    FCComplianceSetType(FCCompliance, FCComplianceType);
PETSC_INTERN PetscErrorCode    FCComplianceSetFromOptions(FCCompliance); /* -compliance_type and the type's own */
/* Whether a KSP is an FE body's default solver, preonly + Cholesky by MUMPS */
PETSC_INTERN PetscErrorCode FCComplianceKSPIsMumps(KSP, PetscBool *);
PETSC_INTERN PetscErrorCode FCComplianceSetUp(FCCompliance);  /* at set-up, A at the reference state */
PETSC_INTERN PetscErrorCode FCComplianceFactor(FCCompliance); /* after every change of A            */
/* A builder that factors A itself (condensed) is the body's only factor: the body calls
   FCComplianceFactor instead of factoring and FCComplianceSolve for its solves */
PETSC_INTERN PetscBool      FCComplianceFactorsA(FCCompliance);
PETSC_INTERN PetscErrorCode FCComplianceSolve(FCCompliance, Vec b, Vec x);
/* a builder that warps a reference compliance needs the body's best-fit rotation before each Add */
PETSC_INTERN PetscBool FCComplianceUsesRotation(FCCompliance);
/* The builder keeps A at the start of the run (precomputed): it cannot follow a change of the time step */
PETSC_INTERN PetscBool      FCComplianceKeepsInitialA(FCCompliance);
PETSC_INTERN PetscErrorCode FCComplianceSetRotation(FCCompliance, const PetscReal R[9]);
/* A body that solves with the factor of an older A_0 (-<body>_factorization reuse) warps it: the
   builder takes Q A_0^-1 Q^T for A^-1 in W_b and in the correction, Q block-diagonal with a
   rotation per vertex: J_b Q in place of J_b (Q for every surface vertex of the body, nsurf of
   them by first global DOF, sorted, on every rank), and the correction's solve turned by Q on the
   owned vertex blocks (nowned, in the order of the layout of u). The arrays stay the caller's */
PETSC_INTERN PetscErrorCode FCComplianceSetWarp(FCCompliance, PetscInt nsurf, const PetscInt sdof[],
                                                const PetscReal sQ[], PetscInt nowned, const PetscReal oQ[]);
/* The right-hand side h J_b^T lambda (with a warp: (J_b Q)^T h lambda) of the last correction by one
   solve (NULL: none, or a builder with its own correction) */
PETSC_INTERN PetscErrorCode FCComplianceGetCorrectionRHS(FCCompliance, Vec *);
/* Factorizations the builder did on its own (a condensed miss), so far */
PETSC_INTERN PetscInt FCComplianceOwnFactorizations(FCCompliance);
/* W_b = J_b A^-1 J_b^T for the contacts touching body `self`, kept for the next Add: its rows that
   fall in this rank's rows of W (NULL: all); same: it is the last build's W_b on the same rows of W
   (a sum of the last builds still holds). Collective. */
PETSC_INTERN PetscErrorCode FCComplianceBuild(FCCompliance, PetscInt self, const FCContactSet *, const FCRows *,
                                              PetscBool *same);
/* W (this rank's rows, row-major; NULL rows: M x M) += J_b A^-1 J_b^T for the contacts touching
   body `self`: the W_b of the Build just before, with the same set and rows */
PETSC_INTERN PetscErrorCode FCComplianceAdd(FCCompliance, PetscInt self, const FCContactSet *, const FCRows *,
                                            PetscReal W[]);
/* Bytes this rank holds for the builder's W_b, and for Sigma / C and the factor (condensed; else 0)
   with the factor's largest rank */
PETSC_INTERN PetscErrorCode FCComplianceGetMemory(FCCompliance, PetscReal *wb, PetscReal *sigma, PetscReal *factor,
                                                  PetscReal *factormax);
/* a builder whose factorization depends on the contact DOFs (condensed) takes the contacts expected
   at its next factorization: whether it does, and the contacts */
PETSC_INTERN PetscBool      FCComplianceUsesExpectedContacts(FCCompliance);
PETSC_INTERN PetscErrorCode FCComplianceExpectContacts(FCCompliance, PetscInt self, const FCContactSet *);
/* dv += h A^-1 J_b^T lambda for the J_b of the last Add */
PETSC_INTERN PetscErrorCode FCComplianceCorrect(FCCompliance, PetscReal h, const PetscReal lambda[], Vec dv);
PETSC_INTERN PetscErrorCode FCComplianceDestroy(FCCompliance *);
