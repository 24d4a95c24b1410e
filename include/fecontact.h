/* fecontact: deformable (P1 finite element) and rigid bodies in frictional contact with the
   implicit constraint scheme of Zeng & Courtecuisse (2023). Public interface.

   One time step flows one way (docs/method.md, section 2):
     scene -> bodies (free motion, eq. 5) -> [collision -> contacts -> compliance -> scheme]
           -> bodies (correction, eq. 20, and integration, eq. 2) -> output                    */
#pragma once

#include <petscdmplex.h>
#include <petscksp.h>

#define FECONTACT_VERSION "0.1.0"

/* ---------------------------------------------------------------------------------------
   Package: type registries, log events, phase timers
   --------------------------------------------------------------------------------------- */
PETSC_EXTERN PetscErrorCode FCInitializePackage(void);
PETSC_EXTERN PetscClassId   FC_CLASSID; /* the package class: its log events */
PETSC_EXTERN PetscErrorCode FCFinalizePackage(void);

/* The phases of a time step. Each has one PetscLogEvent (named "FC<Name>") and a wall-clock
   accumulator that the scene writes to /steps/timing/<name> after every step. */
typedef enum {
  FC_PHASE_ASSEMBLY,      /* element loops: K, f_int, M (eq. 5)                  */
  FC_PHASE_FACTORIZATION, /* numeric (and symbolic) factorization of A           */
  FC_PHASE_FREE_MOTION,   /* right-hand side b and the solve A dv_free = b       */
  FC_PHASE_COLLISION,     /* discrete collision detection, contact set            */
  FC_PHASE_COMPLIANCE,    /* W = sum J A^-1 J^T (eq. 17)                           */
  FC_PHASE_CONTACT_SOLVE, /* projected Gauss-Seidel (eq. 19)                       */
  FC_PHASE_CORRECTION,    /* dv += h A^-1 J^T lambda (eq. 20)                      */
  FC_PHASE_REBUILD_W,     /* recursive schemes: W_k = C_k W_H C_k^T, or J_k A^-1 J_k^T */
  FC_PHASE_PROXIMITY,     /* recursive schemes: proximity update (eq. 31)         */
  FC_PHASE_INTEGRATION,   /* v += dv, q += h v (eq. 2)                            */
  FC_PHASE_OUTPUT,        /* HDF5 writes                                          */
  FC_PHASE_NUM
} FCPhase;
PETSC_EXTERN const char *const FCPhaseNames[];
PETSC_EXTERN PetscErrorCode    FCPhaseBegin(FCPhase);
PETSC_EXTERN PetscErrorCode    FCPhaseEnd(FCPhase);
PETSC_EXTERN PetscErrorCode    FCPhaseGetTimes(PetscReal[FC_PHASE_NUM]); /* seconds since last reset */
/* bytes by which the process' peak RSS grew while each phase ran, since the start */
PETSC_EXTERN PetscErrorCode FCPhaseGetMemoryGrowth(PetscReal[FC_PHASE_NUM]);
PETSC_EXTERN PetscErrorCode FCPhaseResetTimes(void);
PETSC_EXTERN PetscLogEvent  FC_EVENT_NEWTON; /* one Newton iteration of a recursive scheme */
/* the work a scheme does only when something changed: W summed from the bodies' parts and checked,
   W_k = C W_H C^T formed on the host (fast scheme; not counted when kept) */
PETSC_EXTERN PetscLogEvent FC_EVENT_COMPLIANCE_SUM, FC_EVENT_CONGRUENCE_WK;

/* ---------------------------------------------------------------------------------------
   Options helpers: every numeric option is checked for NaN/Inf and range, errors name it
   --------------------------------------------------------------------------------------- */
/* Inside PetscOptionsBegin/End: an integer in [min, max] (checked before conversion: never
   wrapped), an integer in PetscInt's range, a logical (no value or true/false/yes/no/on/off/1/0),
   a real that must be finite (and normal or 0), an array of exactly n such reals */
PETSC_EXTERN PetscErrorCode FCOptionsIntRange(PetscOptionItems *, const char opt[], const char text[], PetscInt min,
                                              PetscInt max, PetscInt *, PetscBool *);
PETSC_EXTERN PetscErrorCode FCOptionsInt(PetscOptionItems *, const char opt[], const char text[], PetscInt *,
                                         PetscBool *);
PETSC_EXTERN PetscErrorCode FCOptionsBool(PetscOptionItems *, const char opt[], const char text[], PetscBool *,
                                          PetscBool *);
PETSC_EXTERN PetscErrorCode FCOptionsReal(PetscOptionItems *, const char opt[], const char text[], PetscReal *,
                                          PetscBool *);
PETSC_EXTERN PetscErrorCode FCOptionsRealArray(PetscOptionItems *, const char opt[], const char text[], PetscInt n,
                                               PetscReal[], PetscBool *);
PETSC_EXTERN PetscErrorCode FCOptionsRealList(PetscOptionItems *, const char opt[], const char text[], PetscInt nmax,
                                              PetscReal[], PetscInt *n, PetscBool *);
/* Range checks whose error names the option with its prefix */
PETSC_EXTERN PetscErrorCode FCCheckPositive(MPI_Comm, const char prefix[], const char opt[], PetscReal);
PETSC_EXTERN PetscErrorCode FCCheckNonNegative(MPI_Comm, const char prefix[], const char opt[], PetscReal);
/* Every option given must have been read: a misspelt one is an error that names it */
PETSC_EXTERN PetscErrorCode FCOptionsCheckUnused(MPI_Comm);

/* ---------------------------------------------------------------------------------------
   Shapes of rigid and kinematic bodies (and their mass properties)
   --------------------------------------------------------------------------------------- */
typedef const char *FCShapeType;
#define FCSHAPEPLANE "plane"
#define FCSHAPESPHERE "sphere"
#define FCSHAPEBOX "box"
#define FCSHAPECAPSULE "capsule"
#define FCSHAPECYLINDER "cylinder"
#define FCSHAPEMESH "mesh"

/* ---------------------------------------------------------------------------------------
   Body: a deformable FE body, a rigid body or a kinematic (prescribed-motion) body
   --------------------------------------------------------------------------------------- */
typedef struct _p_FCBody *FCBody;
typedef const char       *FCBodyType;
#define FCBODYFEM "fem"
#define FCBODYRIGID "rigid"
#define FCBODYKINEMATIC "kinematic"

/* Energies of a body at its current state (joules) */
typedef struct {
  PetscReal kinetic, elastic, gravity;
} FCEnergy;

/* What the output needs to draw a body: owned vertices are a contiguous range
   [vstart, vstart + nv) of a global numbering; cells hold global vertex numbers. */
typedef struct {
  PetscInt   nv, vstart, nv_global; /* owned vertices */
  PetscInt   nc, cstart, nc_global; /* owned cells    */
  PetscInt   nvpc;                  /* 4: tetrahedra, 3: triangles */
  PetscInt  *cells;                 /* nc * nvpc global vertex numbers */
  PetscReal *reference;             /* nv * 3 reference (placed, t = 0) coordinates */
  PetscInt  *origin;                /* meshed bodies: nc, each cell's index in the mesh file; else NULL */
} FCBodyVisual;

PETSC_EXTERN PetscFunctionList FCBodyList;
PETSC_EXTERN PetscErrorCode    FCBodyRegister(const char[], PetscErrorCode (*)(FCBody));
PETSC_EXTERN PetscErrorCode    FCBodyCreate(MPI_Comm, const char name[], FCBody *);
PETSC_EXTERN PetscErrorCode    FCBodySetType(FCBody, FCBodyType);
PETSC_EXTERN PetscErrorCode    FCBodyGetType(FCBody, FCBodyType *);
PETSC_EXTERN PetscErrorCode    FCBodyGetName(FCBody, const char **);
PETSC_EXTERN PetscErrorCode    FCBodySetFromOptions(FCBody);
PETSC_EXTERN PetscErrorCode    FCBodySetTimeStep(FCBody, PetscReal);
PETSC_EXTERN PetscErrorCode    FCBodySetQuasiStatic(FCBody, PetscBool);
PETSC_EXTERN PetscErrorCode    FCBodySetSceneBodies(FCBody, PetscInt, FCBody[]);
PETSC_EXTERN PetscErrorCode    FCBodySetTime(FCBody, PetscReal);
PETSC_EXTERN PetscErrorCode    FCBodyGetPoseAt(FCBody, PetscReal, PetscReal[3], PetscReal[4]);
PETSC_EXTERN PetscErrorCode    FCBodySetGravity(FCBody, const PetscReal[3]);
PETSC_EXTERN PetscErrorCode    FCBodySetUp(FCBody);
PETSC_EXTERN PetscErrorCode    FCBodyComputeFreeMotion(FCBody, PetscReal t);
PETSC_EXTERN PetscErrorCode    FCBodyIntegrate(FCBody, PetscReal t);
PETSC_EXTERN PetscErrorCode    FCBodyGetCentroid(FCBody, PetscReal[3]);
PETSC_EXTERN PetscErrorCode    FCBodyGetRotation(FCBody, PetscReal[4], PetscBool *);
/* constrained regions (FE bodies) and their reactions of the last step: 6 values each, the force of
   the supports on the body and its moment about the region's centroid */
PETSC_EXTERN PetscErrorCode FCBodyGetExternalWork(FCBody, PetscReal *);
PETSC_EXTERN PetscErrorCode FCBodyGetReactions(FCBody, PetscInt *n, const char ***names, const PetscReal **values);
/* The factorizations of the body's A, the Krylov iterations of its solves and the Newton iterations of
   its free motions so far (0 for bodies without) */
PETSC_EXTERN PetscErrorCode FCBodyGetSolverCounts(FCBody, PetscInt *nfactor, PetscInt *nkrylov, PetscInt *nnewton);
PETSC_EXTERN PetscErrorCode FCBodyGetEnergy(FCBody, FCEnergy *);
PETSC_EXTERN PetscErrorCode FCBodyGetVisual(FCBody, const FCBodyVisual **);
PETSC_EXTERN PetscErrorCode FCBodyGetVisualPositions(FCBody, PetscReal[]);
PETSC_EXTERN PetscErrorCode FCBodyCheckState(FCBody, PetscInt step);
PETSC_EXTERN PetscErrorCode FCBodyDestroy(FCBody *);

/* FE body specifics, for tests and tools: the DMPlex with the displacement section, the
   displacement u and velocity v (global vectors), the elastic force f_int(u) (global). */
PETSC_EXTERN PetscErrorCode FCBodyFEMGetDM(FCBody, DM *);
PETSC_EXTERN PetscErrorCode FCBodyFEMGetState(FCBody, Vec *u, Vec *v);
PETSC_EXTERN PetscErrorCode FCBodyFEMComputeElasticForce(FCBody, Vec u, Vec f);
PETSC_EXTERN PetscErrorCode FCBodyFEMGetReferenceCoordinates(FCBody, Vec *);
PETSC_EXTERN PetscErrorCode FCBodyFEMGetCounters(FCBody, PetscInt *nassembly, PetscInt *nfactorization);

/* ---------------------------------------------------------------------------------------
   Extending fecontact: a new body type, shape, material, compliance builder or constraint
   scheme is one file with its create function (which fills the type's private structure,
   src/<package>/) and one Register call, before the scene reads its options; the type is then
   chosen by its option (-<body>_type, -<body>_shape, -<body>_material, -compliance_type,
   -constraint_scheme) like the built-in ones. docs/architecture.md shows each.
   --------------------------------------------------------------------------------------- */
typedef struct _p_FCShape      *FCShape;
typedef struct _p_FCMaterial   *FCMaterial;
typedef struct _p_FCCompliance *FCCompliance;
typedef const char             *FCComplianceType;
typedef struct _p_FCScheme     *FCScheme;
typedef const char             *FCSchemeType;
PETSC_EXTERN PetscErrorCode     FCShapeRegister(const char[], PetscErrorCode (*)(FCShape));
PETSC_EXTERN PetscErrorCode     FCMaterialRegister(const char[], PetscErrorCode (*)(FCMaterial));
PETSC_EXTERN PetscErrorCode     FCComplianceRegister(const char[], PetscErrorCode (*)(FCCompliance));
PETSC_EXTERN PetscErrorCode     FCSchemeRegister(const char[], PetscErrorCode (*)(FCScheme));

/* ---------------------------------------------------------------------------------------
   Scene: the bodies, the time loop, the output
   --------------------------------------------------------------------------------------- */
typedef struct _p_FCScene *FCScene;

PETSC_EXTERN PetscErrorCode FCSceneCreate(MPI_Comm, FCScene *);
PETSC_EXTERN PetscErrorCode FCSceneSetFromOptions(FCScene);
PETSC_EXTERN PetscErrorCode FCSceneSetUp(FCScene);
PETSC_EXTERN PetscErrorCode FCSceneRun(FCScene);
PETSC_EXTERN PetscErrorCode FCSceneStep(FCScene);
PETSC_EXTERN PetscErrorCode FCSceneGetBody(FCScene, const char[], FCBody *);
PETSC_EXTERN PetscErrorCode FCSceneDestroy(FCScene *);

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
