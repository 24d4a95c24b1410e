/* Private data of an FE body, shared by its files:
     fem.c          options, set-up, destroy, type registration, accessors for tests and tools
     fem_step.c     element loops, A and its factorization, free motion (eq. 5), integration (eq. 2)
     fem_newton.c   the free motion by Newton's method (SNES) of a nonlinear body
     fem_nonlinear.c the nonlinear contact correction of a body with a Newton free motion
     fem_state.c    centroid, energies, visual positions and fields, restart state, NaN check
     fem_contact.c  contact points, surface triangles, proximity positions, the compliance builder
     fem_rotation.c the rotation of a free co-rotational body within a step
     fem_check.c    the checks of the derived quantities (mass, energies, M, K, A) at set-up
     fem_schedule.c when A is factored (-factorization), CG with the warped factor (femschedule.h)
     fem_warp.c     reuse without K: cell and vertex rotations, Q, the matrix-free A, the builder's table
     fem_bc.c       regions' constraints (fixed, prescribed, attached): options, set-up, poses, eq. 5's coupling
     fem_load.c     loads on regions
     fem_reaction.c the constrained regions' reactions
     fem_regions.c  what identifies the regions across runs (a restart's check) */
#pragma once
#include "bodyimpl.h"
#include <petscsnes.h>
#include "fembc.h"        /* constrained regions and loads */
#include "femnonlinear.h" /* the nonlinear correction */

#define FC_MAX_FIXED_BOXES 8 /* -<body>_fixed_box: boxes at most */

enum { FC_FACTORIZATION_EVERY_STEP, FC_FACTORIZATION_REUSE };
enum { FC_FREE_MOTION_LINEARIZED, FC_FREE_MOTION_NEWTON };

typedef struct {
  FCMesh     mesh;
  FCMaterial mat;
  char       material[FC_MAX_NAME];
  PetscReal  young, poisson, alpha, beta;
  PetscBool  lumped, has_fixed_box;
  PetscReal  fixed_box[6 * FC_MAX_FIXED_BOXES + 1]; /* nfixed_box boxes, 6 numbers each */
  PetscInt   nfixed_box;
  PetscBool  allow_inverted; /* -inverted allow: no stop at an element turned inside out */
  FCInverted inverted;       /* the elements turned inside out at the last check (CheckState_FEM) */
  PetscInt   nfixed;         /* global number of fixed vertices */
  PetscInt  *ldof;           /* per local vertex: offset in the local vector */
  PetscInt  *gdof;           /* per local vertex: first global DOF, -1 when fixed */
  PetscBool *fixed;          /* per local vertex: constrained (fixed or prescribed) */
  /* boundary conditions and loads (fem_bc.c) */
  char           *bcspec[6]; /* -fixed, -displacement, -force, -traction, -pressure, -attach as given (allocated) */
  PetscInt        ncons, nload;
  FCFEMConstraint cons[FC_MAX_REGIONS];
  FCFEMLoad       load[FC_MAX_REGIONS];
  PetscInt       *creg;              /* per local vertex: its constraint, -1 when free */
  PetscInt        nccell, *ccell;    /* the cells with a constrained vertex */
  PetscBool       moving;            /* some constraint moves */
  Vec             fload;             /* the loads at the end of the step */
  PetscReal      *fcons;             /* per local vertex, 3: this rank's share of the loads at the end of the step on
                                        constrained vertices (their supports take them: the reactions) */
  Vec         varea;                 /* per DOF: a third of the boundary faces' area at the vertex (contact_pressure) */
  const char *rname[FC_MAX_REGIONS]; /* the constraints' regions and reactions, for the output */
  PetscReal   rval[6 * FC_MAX_REGIONS];
  PetscReal   extwork;     /* magnitude of the work of the prescribed motions and loads so far (energy guard) */
  PetscReal  *Dminv, *vol; /* per cell */
  Mat         M, K, A;
  Vec         u, v, dv, b, fint, fgrav, work, uloc, floc;
  KSP         ksp;
  PetscInt    nassembly, nfactor;
  PetscBool   Acurrent;   /* K and f_int belong to the current state */
  PetscBool   factored;   /* the factor of A is that of the current A */
  PetscInt    factor_age; /* steps since A was last factored */
  /* the factorization schedule (fem_schedule.c, fem_warp.c; docs/method.md "When A is factored") */
  PetscInt     factorization;                                            /* FC_FACTORIZATION_EVERY_STEP or _REUSE */
  PetscReal    ksp_rtol, refactor_rotation, refactor_residual;           /* reuse: CG's tolerance, the triggers */
  PetscInt     ksp_max_it, refactor_iterations, refactor_every, nkrylov; /* ... and CG iterations so far */
  PetscBool    refactor_next, fresh, hasprev; /* factor at the next step; A factored this step; xprev holds */
  PetscReal    angle, tnow;                   /* the largest vertex rotation since the last factorization */
  Vec          state;                         /* where this step's A is linearized (u or the turned state) */
  PetscReal   *Rcell, *Rv0, *dR;              /* per cell its rotation; per owned vertex block R_0 and Q */
  PetscReal   *Rvnow, *Rvprev;                /* per owned vertex block its rotation now, at the last correction */
  Vec          rcol[3], rcolloc[3];           /* the vertex rotations' sums */
  Vec          rw2, xlast, xres, xcorr;       /* work; the last free motion (CG's first guess); the correction */
  Vec          xprev, rprev;                  /* the last correction and its right-hand side h J^T lambda */
  Mat          Aop;                           /* today's A, matrix-free */
  KSP          kspk;                          /* CG on Aop, preconditioned by the warped factor */
  PetscInt     nsw, *swdof, *swperm;          /* the surface vertices of every rank (first DOFs, sorted) */
  PetscReal   *swR, *swbuf, *swall;           /* their Q; this rank's; every rank's, gathered */
  PetscMPIInt *swcounts, *swdispls;
  PetscBool    coo; /* -assembly coo: K summed by MatSetValuesCOO from Kcells */
  /* the Newton free motion (fem_newton.c) */
  PetscInt         free_motion; /* -free_motion: FC_FREE_MOTION_LINEARIZED or _NEWTON (-1: the material's default) */
  SNES             snes;        /* its iterations, on the body's KSP */
  Vec              nw, nf, nbc, nr; /* the iterate's state at t + h, f_int there, b_c, the residual */
  PetscBool        jacobian;        /* A formed and factored at an iterate of this step */
  PetscInt         nnewton;         /* Newton iterations so far */
  PetscInt         correction;      /* -correction: 0 linear, 1 nonlinear */
  FCFEMNonlinear   nl;              /* the nonlinear correction's state (NULL: linear) */
  PetscReal        penalty;         /* -correction_penalty */
  PetscReal       *Kcells;          /* coo: the element matrices, 144 per cell, in cell order */
  PetscReal        mass;
  FCEnergy         energy;             /* the last energy computed (GetEnergy_FEM) ... */
  PetscObjectState energy_u, energy_v; /* ... for these states of u and v (0: none yet) */
  /* contact */
  PetscInt           nbv, *bv; /* owned boundary vertices (local vertex indices)             */
  PetscInt           nsurface; /* ... their first global DOF, the non-fixed ones             */
  PetscInt          *surface;
  Vec                Xg;               /* placed reference coordinates, layout of u                  */
  PetscReal         *bx0, *bxf, *bkey; /* contact point buffers                                      */
  FCProximity       *bprox;
  PetscInt           ntri; /* local boundary faces: vertices (local indices, outward order) */
  PetscInt          *triv;
  FCSurfaceTriangle *tri;
  Vec                vloc, dvloc;
  Vec                dvfree;   /* recursive schemes: dv_free kept while corrections are tried */
  FCCompliance       comp;     /* W_b and the correction (-compliance_type); bodies in a contact pair */
  PetscBool          Rcurrent; /* comp has the best-fit rotation of the current u (set once per step) */
  /* the rotation within a step (fem_rotation.c) */
  PetscBool rotation_exact;  /* -rotation exact (co-rotational bodies without fixed vertices) */
  PetscBool shifted;         /* this step's positions include shift (set by the free motion)  */
  Vec       rr, shift, uhat; /* r, delta, u + (Q - I) r                                       */
  Vec       rvt, rw, rcf;    /* v~, v - omega x r, the centrifugal force                      */
} FEM;

static inline PetscReal FCFEMConstrainedU(const FEM *fem, PetscInt k, const PetscReal X[3], int when, int d)
{
  return k < 0 ? 0.0 : FCFEMConstraintU(&fem->cons[k], X, when, d);
}
/* Its velocity over the step (before: over the step before) */
static inline PetscReal FCFEMConstrainedV(const FEM *fem, PetscInt k, const PetscReal X[3], PetscBool before,
                                          PetscReal h, int d)
{
  return before ? (FCFEMConstrainedU(fem, k, X, FC_BC_NOW, d) - FCFEMConstrainedU(fem, k, X, FC_BC_BEFORE, d)) / h
                : (FCFEMConstrainedU(fem, k, X, FC_BC_END, d) - FCFEMConstrainedU(fem, k, X, FC_BC_NOW, d)) / h;
}
/* Component d of the displacement now of local vertex v: its constraint's, or from the local vector
   ul (FCFEMLocalU), or for an owned vertex from the owned rows of a global vector whose first row is
   lo (FCFEMOwnedU) */
static inline PetscReal FCFEMLocalUAt(const FEM *fem, PetscInt v, const PetscScalar *ul, int when, int d)
{
  return fem->fixed[v] ? FCFEMConstrainedU(fem, fem->creg[v], &fem->mesh.X[3 * v], when, d)
                       : PetscRealPart(ul[fem->ldof[v] + d]);
}
static inline PetscReal FCFEMLocalU(const FEM *fem, PetscInt v, const PetscScalar *ul, int d)
{
  return FCFEMLocalUAt(fem, v, ul, FC_BC_NOW, d);
}
static inline PetscReal FCFEMOwnedU(const FEM *fem, PetscInt v, const PetscScalar *u, PetscInt lo, int d)
{
  return fem->fixed[v] ? FCFEMConstrainedU(fem, fem->creg[v], &fem->mesh.X[3 * v], FC_BC_NOW, d)
                       : PetscRealPart(u[fem->gdof[v] - lo + d]);
}
/* The global DOF of a constrained vertex of a moving constraint k encodes k: -2 - k (fixed: -1) */
static inline PetscInt FCFEMConstrainedOfDof(PetscInt g)
{
  return g <= -2 ? -2 - g : -1;
}

/* Element positions: reference X and current x = X + u (constrained vertices at their prescribed
   displacement at when: FC_BC_NOW, or FC_BC_END for the Newton iterates); uloc NULL: X */
static inline void FCFEMGatherElementAt(FEM *fem, PetscInt c, const PetscScalar *uloc, int when, PetscReal X[12],
                                        PetscReal x[12])
{
  FCMesh *m = &fem->mesh;
  for (int a = 0; a < 4; a++) {
    PetscInt v = m->cellVerts[4 * c + a] - m->vStart;
    for (int d = 0; d < 3; d++) {
      X[3 * a + d] = m->X[3 * v + d];
      x[3 * a + d] = X[3 * a + d] + (uloc ? FCFEMLocalUAt(fem, v, uloc, when, d) : 0.0);
    }
  }
}
static inline void FCFEMGatherElement(FEM *fem, PetscInt c, const PetscScalar *uloc, PetscReal X[12], PetscReal x[12])
{
  FCFEMGatherElementAt(fem, c, uloc, FC_BC_NOW, X, x);
}

/* Global DOFs of a cell's 12 unknowns, -1 on fixed vertices */
static inline void FCFEMElementIndices(FEM *fem, PetscInt c, PetscInt idx[12])
{
  FCMesh *m = &fem->mesh;
  for (int a = 0; a < 4; a++) {
    PetscInt v = m->cellVerts[4 * c + a] - m->vStart;
    for (int d = 0; d < 3; d++) idx[3 * a + d] = fem->gdof[v] < 0 ? -1 : fem->gdof[v] + d;
  }
}

PETSC_INTERN PetscErrorCode FCFEMGet(FCBody, FEM **); /* checks that the body is an FE body */

/* fem_check.c: after M, K and A are assembled */
PETSC_INTERN PetscErrorCode FCFEMCheckDerived(FCBody);
/* fem_step.c */
PETSC_INTERN PetscErrorCode FCFEMCreateOperators(FCBody);
PETSC_INTERN PetscErrorCode FCFEMAssembleMass(FCBody);
PETSC_INTERN PetscErrorCode FCFEMAssembleElastic(FCBody, Vec u, Vec f, Mat K); /* f, K may be NULL */
/* ... with the constrained vertices where they are at when (FC_BC_NOW, FC_BC_END) */
PETSC_INTERN PetscErrorCode FCFEMAssembleElasticAt(FCBody, Vec u, int when, Vec f, Mat K);
PETSC_INTERN PetscErrorCode FCFEMFormA(FCBody);          /* A from M and K; its factor becomes stale */
PETSC_INTERN PetscErrorCode FCFEMChangeTimeStep(FCBody); /* body->h changed after set-up */
PETSC_INTERN PetscErrorCode FCFEMFactorA(FCBody);        /* by the builder that owns it, or the KSP */
PETSC_INTERN PetscErrorCode FCFEMSolveA(FCBody, Vec b, Vec x, const char what[], PetscReal t);
PETSC_INTERN PetscErrorCode FreeMotion_FEM(FCBody, PetscReal);
PETSC_INTERN PetscErrorCode Integrate_FEM(FCBody, PetscReal);
#include "femschedule.h" /* fem_schedule.c, fem_warp.c */
/* fem_bc.c */
PETSC_INTERN PetscErrorCode FCFEMBCSetFromOptions(PetscOptionItems *, FCBody);
PETSC_INTERN PetscErrorCode FCFEMBCSetUpConstraints(FCBody); /* fixed[], creg[] before the section */
PETSC_INTERN PetscErrorCode FCFEMBCSetUp(FCBody);            /* loads and the constrained cells, after it */
PETSC_INTERN PetscErrorCode FCFEMBCPoses(FCBody, PetscReal t);
PETSC_INTERN PetscErrorCode FCFEMSplitPairs(FCBody, const char option[], const char spec[], PetscInt *n,
                                            char reg[][256], char *tab[]);
PETSC_INTERN PetscErrorCode FCFEMBCBeginStep(FCBody, PetscReal t);
/* b += the loads and the prescribed motion's coupling: its inertia, and with stiffness its elastic
   coupling too (the Newton free motion takes the latter from f_int at the prescribed positions) */
PETSC_INTERN PetscErrorCode FCFEMBCAddRHS(FCBody, Vec b, PetscBool stiffness);
/* fem_newton.c */
PETSC_INTERN PetscErrorCode FCFEMNewtonSetFromOptions(PetscOptionItems *, FCBody);
PETSC_INTERN PetscErrorCode FCFEMNewtonSetUp(FCBody); /* after the solver and A */
PETSC_INTERN PetscErrorCode FCFEMNewtonFreeMotion(FCBody, PetscReal t);
PETSC_INTERN PetscErrorCode FCFEMNewtonSolve(FCBody, Vec again, SNESConvergedReason *, PetscInt *its);
PETSC_INTERN PetscErrorCode FCFEMNewtonDestroy(FCBody);
PETSC_INTERN PetscErrorCode FCFEMBCDestroy(FCBody);
/* fem_load.c */
PETSC_INTERN PetscErrorCode FCFEMLoadsSetUp(FCBody);
PETSC_INTERN PetscErrorCode FCFEMLoadsAt(FCBody, PetscReal t);
/* fem_reaction.c */
PETSC_INTERN PetscErrorCode FCFEMBCEndStep(FCBody);
PETSC_INTERN PetscErrorCode GetExternalWork_FEM(FCBody, PetscReal *);
PETSC_INTERN PetscErrorCode GetReactions_FEM(FCBody, PetscInt *, const char ***, const PetscReal **);
PETSC_INTERN PetscErrorCode GetRegions_FEM(FCBody, PetscInt *, char **, PetscReal **); /* fem_regions.c */
/* fem_rotation.c */
PETSC_INTERN PetscBool      FCFEMRotationActive(FEM *);
PETSC_INTERN PetscErrorCode FCFEMRotationPredict(FCBody);
/* fem_state.c */
PETSC_INTERN PetscErrorCode GetCentroid_FEM(FCBody, PetscReal[3]);
PETSC_INTERN PetscErrorCode GetEnergy_FEM(FCBody, FCEnergy *);
PETSC_INTERN PetscErrorCode GetVisualPositions_FEM(FCBody, PetscReal[]);
PETSC_INTERN PetscErrorCode GetVisualField_FEM(FCBody, FCVisualField, PetscReal[], PetscBool *);
PETSC_INTERN PetscErrorCode FCFEMContactPressure(FCBody, PetscReal[]);
PETSC_INTERN PetscErrorCode GetState_FEM(FCBody, PetscReal[]);
PETSC_INTERN PetscErrorCode SetState_FEM(FCBody, const PetscReal[]);
PETSC_INTERN PetscErrorCode CheckState_FEM(FCBody, PetscInt);
PETSC_INTERN PetscErrorCode GetInverted_FEM(FCBody, FCInverted *, PetscBool *);
/* fem_contact.c */
PETSC_INTERN PetscErrorCode ContactPoints_FEM(FCBody, PetscInt *, FCProximity **, PetscReal **, PetscReal **,
                                              PetscReal **);
PETSC_INTERN PetscErrorCode SurfaceTriangles_FEM(FCBody, PetscInt *, FCSurfaceTriangle **);
PETSC_INTERN PetscErrorCode PartialPosition_FEM(FCBody, const FCProximity *, PetscReal[3]);
PETSC_INTERN PetscErrorCode TrialPosition_FEM(FCBody, const FCProximity *, PetscReal[3]);
PETSC_INTERN PetscErrorCode SaveFree_FEM(FCBody);
PETSC_INTERN PetscErrorCode RestoreFree_FEM(FCBody);
PETSC_INTERN PetscErrorCode ProximityPosition_FEM(FCBody, const FCProximity *, PetscInt, PetscReal[3]);
PETSC_INTERN PetscErrorCode SetUpContact_FEM(FCBody);
PETSC_INTERN PetscErrorCode AddCompliance_FEM(FCBody, PetscInt, const FCContactSet *, const FCRows *, PetscReal[]);
PETSC_INTERN PetscErrorCode BuildCompliance_FEM(FCBody, PetscInt, const FCContactSet *, const FCRows *, PetscBool *);
PETSC_INTERN PetscErrorCode ApplyCorrection_FEM(FCBody, PetscInt, const FCContactSet *, const PetscReal[]);
PETSC_INTERN PetscErrorCode ExpectContacts_FEM(FCBody, PetscInt, const FCContactSet *);
