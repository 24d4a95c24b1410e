/* Private definitions of the constraint schemes (src/scheme/). A scheme type fills the ops of an
   FCScheme in its create function and reads its own options; scheme.c does what every scheme
   shares: the memory check, the contact solver, the W assembly and its check, the residual check. */
#pragma once
#include "../fcimpl.h"

typedef struct {
  PetscErrorCode (*setfromoptions)(FCScheme, PetscOptionItems *);
  /* bytes of the dense contact matrices one step of this contact set needs per rank, and what
     they are (for the error message) */
  PetscErrorCode (*memory)(FCScheme, const FCContactSet *, PetscReal *bytes, const char **what);
  /* forces and corrected motions of a non-empty contact set; stats were reset by the caller */
  PetscErrorCode (*solve)(FCScheme, FCContactSet *, const FCContactSet *previous, FCSchemeStats *);
  /* bytes this rank holds from step to step: W_H and W_k (fast) */
  PetscErrorCode (*held)(FCScheme, PetscReal *wh, PetscReal *wk);
  PetscErrorCode (*destroy)(FCScheme);
} FCSchemeOps;

struct _p_FCScheme {
  MPI_Comm        comm;
  char            type[FC_MAX_NAME];
  FCSchemeOps     ops;
  void           *data;
  PetscInt        nbodies;
  FCBody         *bodies;
  FCContactSolver solver;
  PetscReal       memory_limit;  /* -contact_memory_limit: bytes per rank */
  PetscReal       fail_residual; /* -pgs_fail_residual */
  /* recursive schemes (standard, fast): -newton_max_it, -newton_tol (recursive.c) */
  PetscInt  newton_max_it;
  PetscReal newton_tol;
};

/* W = h^2 sum_b J_b A_b^-1 J_b^T of a contact set in its frames (identity frames give W_H),
   checked to be a compliance (scheme.c). kept (NULL: no): on entry, W holds the W of the last call,
   for a set with the same rows (h is fixed at set-up); on return, whether W was left as it was because
   every body's part is the one it added last (a linear body on the same contacts: condensed.c) */
PETSC_INTERN PetscErrorCode FCSchemeCompliance(FCScheme, const FCContactSet *, const FCRows *, PetscReal W[],
                                               PetscBool *kept);
/* The contact solver on prob (the set's linearization), with the set's dormant contacts; the ones
   the solver wakes stay awake in the set for the rest of the step */
PETSC_INTERN PetscErrorCode FCSchemeContactSolve(FCScheme, FCContactSet *, FCContactProblem, PetscReal lambda[]);
/* dv_b += h A_b^-1 J_b^T lambda for every body (the J_b of the last FCSchemeCompliance) */
PETSC_INTERN PetscErrorCode FCSchemeCorrect(FCScheme, const FCContactSet *, const PetscReal lambda[]);

/* Shared by the recursive schemes (recursive.c) */
PETSC_INTERN PetscErrorCode FCSchemeRecursiveSetFromOptions(FCScheme, PetscOptionItems *);
PETSC_INTERN void FCSchemeStartLinearization(const FCContactSet *, PetscReal dfree[], PetscReal d0[], PetscReal q[],
                                             PetscReal mu[], PetscInt dims[]);
PETSC_INTERN PetscErrorCode FCSchemeLinearize(FCScheme, FCContactSet *, const PetscReal dfree[], const PetscReal d0[],
                                              const PetscReal d[], PetscReal q[], PetscReal *frame_change);
PETSC_INTERN PetscBool      FCSchemeConverged(FCScheme, PetscInt M, const PetscReal q[], const PetscReal qold[],
                                              PetscReal frame_change);
