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
PETSC_EXTERN PetscErrorCode FCOptionsEList(PetscOptionItems *, const char opt[], const char text[],
                                           const char *const list[], PetscInt n, PetscInt *, PetscBool *);
PETSC_EXTERN PetscErrorCode FCOptionsReal(PetscOptionItems *, const char opt[], const char text[], PetscReal *,
                                          PetscBool *);
PETSC_EXTERN PetscErrorCode FCOptionsRealArray(PetscOptionItems *, const char opt[], const char text[], PetscInt n,
                                               PetscReal[], PetscBool *);
PETSC_EXTERN PetscErrorCode FCOptionsRealList(PetscOptionItems *, const char opt[], const char text[], PetscInt nmax,
                                              PetscReal[], PetscInt *n, PetscBool *);
/* A string option of any length: *value (NULL or an earlier value, freed) is allocated (PetscFree),
   "" when the option is not given */
PETSC_EXTERN PetscErrorCode FCOptionsStringAlloc(PetscOptionItems *, const char opt[], const char text[], char **value,
                                                 PetscBool *);
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
/* FE bodies: the elements turned inside out (volume ratio J = det F <= 0) at the end of the last
   step and the smallest J of the body's elements then, the same on every rank; *has is PETSC_FALSE
   for the other types (nothing filled) */
typedef struct {
  PetscInt  count; /* elements with J <= 0 */
  PetscReal min_J; /* the smallest J of the body's elements (1 before the first step) */
} FCInverted;
PETSC_EXTERN PetscErrorCode FCBodyGetInverted(FCBody, FCInverted *, PetscBool *has);
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

/* A program that drives a scene itself (examples/c/, the Python module, python/): create it from
   the options database (the options of a run of the executable), set it up, then step it; between
   two steps it may read the time, the bodies' state and the contacts of the last step, and steer
   its kinematic bodies. FCSceneStep sets the scene up at its first call and refuses a step beyond
   -time_steps; FCSceneFinish, after the last step, prints the summary and writes the memory report
   as the end of FCSceneRun does. FCSceneCreate, SetFromOptions, SetUp, Step, Run and Finish fail on
   every rank when one rank fails (the first failing rank's error and message on the others).
   Every function of this header checks its pointer and handle arguments: a NULL one that is not
   documented as optional is an error (PETSC_ERR_ARG_NULL) naming the function and the argument. */
PETSC_EXTERN PetscErrorCode FCSceneFinish(FCScene);
PETSC_EXTERN PetscErrorCode FCSceneGetTime(FCScene, PetscReal *t, PetscInt *step);
PETSC_EXTERN PetscErrorCode FCSceneGetTimeStep(FCScene, PetscReal *h, PetscInt *nsteps);
PETSC_EXTERN PetscErrorCode FCSceneGetNumBodies(FCScene, PetscInt *);
PETSC_EXTERN PetscErrorCode FCSceneGetBodyByIndex(FCScene, PetscInt, FCBody *); /* in -scene_bodies order */
/* A contact of the last step: its two bodies (scene indices; the force acts on body[0], its
   opposite on body[1]), the point of body[0] and the normal (out of body[1]) at the start of the
   step, the force on body[0] in the contact frame (normal, t1, t2) and in world axes, the gaps at
   the start and at the end of the step, its state (0 open, 1 stick, 2 slip): /contacts of the
   output (docs/output.md). Every rank has every contact. */
typedef struct {
  PetscInt  body[2];
  PetscReal point[3], normal[3], force[3], force_world[3], gap, gap_end;
  PetscInt  state;
} FCContactInfo;
/* *n contacts; info NULL: only their number, else info[0 .. n) (the caller's, *n long) filled */
PETSC_EXTERN PetscErrorCode FCSceneGetContacts(FCScene, PetscInt *n, FCContactInfo info[]);
/* A kinematic body steered from the program: SetKinematicPose, the pose (centre, unit quaternion
   body to world) it reaches at the end of the next step, moving there at constant velocity and
   angular velocity over that step, then held; SetKinematicVelocity, a constant velocity and
   angular velocity (about its centre) from the next step on. Either replaces the motion its
   options gave. */
PETSC_EXTERN PetscErrorCode FCBodySetKinematicPose(FCBody, const PetscReal x[3], const PetscReal q[4]);
PETSC_EXTERN PetscErrorCode FCBodySetKinematicVelocity(FCBody, const PetscReal v[3], const PetscReal w[3]);
/* A rigid or kinematic body's velocity and angular velocity (world) over the last step */
PETSC_EXTERN PetscErrorCode FCBodyGetVelocity(FCBody, PetscReal v[3], PetscReal w[3]);
/* The positions (or velocities) of the body's picture's vertices: FE, its mesh's vertices; rigid and
   kinematic, its shape's tessellation. gathered: all of them on every rank, in the output's order
   (else this rank's, the range of FCBodyVisual); x NULL: only their number */
PETSC_EXTERN PetscErrorCode FCBodyGetPositions(FCBody, PetscBool gathered, PetscInt *n, PetscReal x[]);
PETSC_EXTERN PetscErrorCode FCBodyGetVelocities(FCBody, PetscBool gathered, PetscInt *n, PetscReal v[]);

/* Errors as the executable reports them: an input error (a wrong option or input file, a
   diverging run, an interruption) is one line "fecontact: error: <message>" on rank 0 (print), not
   a traceback; other errors go to PETSc's traceback handler. Either way the first message of the
   last error is kept for a caller that reports it itself (the Python module raises it). */
PETSC_EXTERN PetscErrorCode FCPushErrorHandler(PetscBool print);
PETSC_EXTERN const char    *FCGetLastErrorMessage(void);
/* The executable: PetscInitialize, a scene from the options, FCSceneRun, and the exit status of
   docs/output.md (0 done, 1 input error, 2 diverged, 3 output failed, 128 + n signal n) */
PETSC_EXTERN int FCMain(int argc, char **argv);

#include "fecontactsolver.h"
