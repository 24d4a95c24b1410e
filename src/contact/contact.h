/* Contacts of one step (src/contact/contactset.c, measures.c). A proximity point is a linear map of
   a body's DOFs (eq. 6): barycentric weights on FE vertices, or a body-frame point of a rigid or
   kinematic body. Contacts are replicated on every rank, in a partition-independent order. */
#pragma once

#include "../util/util.h"

typedef struct {
  PetscInt  nv;      /* FE: vertices (1..3: a vertex, an edge, a triangle); 0 for rigid and kinematic bodies */
  PetscInt  gdof[3]; /* FE: first global DOF of each vertex, -1 when fixed     */
  PetscReal w[3];    /* FE: barycentric weights                                */
  PetscReal r[3];    /* rigid/kinematic: body-frame point                      */
  PetscReal X[3][3]; /* FE: reference positions of the vertices (fixed ones never move) */
} FCProximity;

typedef struct {
  PetscInt    pair, body[2]; /* scene body indices; the normal points from side 2 to side 1 */
  FCProximity prox[2];
  PetscReal   key[3];                /* reference position on side 1: sorts contacts independently of the partition */
  PetscReal   n[3], t1[3], t2[3];    /* frame at the start of the step */
  PetscReal   p0[2][3], pfree[2][3]; /* proximity positions at the start and after free motion */
  PetscReal   gap0, mu, gap_end;
  PetscReal   slack; /* penetration the step may leave: what a start inside the other body exceeds
                        -contact_separation_speed x h by (0 for a contact that starts outside) */
  PetscReal qcurv;   /* an FE point against a rounded rigid shape (shapepoints.c): the shape's exact gap there after
                        the free motion minus n . d_free, which the shape's point, turning with it, misses by
                        r (1 - cos theta) (a rolling ball would sink by that each step); 0 otherwise */
  PetscInt  dim, row, owner; /* rows (1 frictionless, 3), first row, detecting rank */
  PetscReal force[3];        /* lambda in the [n t1 t2] frame (force units)      */
  PetscInt  state;           /* 0 open, 1 stick, 2 slip */
  PetscInt  side2; /* what side 2 is: FC_SIDE_SHAPE, FC_SIDE_FE_TRIANGLE, FC_SIDE_RIGID_TRIANGLE, FC_SIDE_FE_EDGE */
  PetscReal nb[3]; /* the normal in a body frame: side 2's (FC_SIDE_RIGID_TRIANGLE), side 1's (face1) */
  PetscBool face1; /* a rigid shape's point against an FE triangle face to face: the normal is side 1's face's */
  PetscReal wnn;   /* normal diagonal entry of the step's W (m/N): scales the end measures  */
  PetscReal n_end[3], d_end[3]; /* end of the step: normal on the real geometry, d = p1 - p2 (world)  */
  PetscReal p_end[3];           /* end of the step: the side-1 proximity point (world)                */
  PetscBool dormant;            /* a redundant contact kept out of the solve unless the solution violates it */
  PetscBool swept; /* from beyond the alarm distance against a shape travelling over half its size: it may pass */
} FCContact;
/* FC_SIDE_FE_EDGE: an edge-edge contact between two FE bodies (prox[0] and prox[1] each an edge,
   nv = 2; the normal is the cross product of the two edges). An FE edge against an edge of a
   rigid mesh is an FC_SIDE_RIGID_TRIANGLE contact: a point and a normal fixed in the mesh's frame. */
enum { FC_SIDE_SHAPE, FC_SIDE_FE_TRIANGLE, FC_SIDE_RIGID_TRIANGLE, FC_SIDE_FE_EDGE };

typedef struct {
  PetscInt   n, max, nrows;
  FCContact *c;
  PetscReal  dormant_depth; /* the depth at which a dormant contact wakes (FCCollisionDetect) */
} FCContactSet;

/* The rows [r0, r1) of a contact compliance (W, W_H) that a rank holds when it is distributed by
   block rows: row-major, (r1 - r0) x nrows, entry (i, j) at [(i - r0) nrows + j]. NULL: whole */
typedef struct {
  PetscInt r0, r1;
} FCRows;
PETSC_INTERN PetscErrorCode FCContactSetAdd(FCContactSet *, const FCContact *);
PETSC_INTERN PetscErrorCode FCContactSetGather(FCContactSet *, MPI_Comm);
PETSC_INTERN PetscErrorCode FCContactSetFinalize(FCContactSet *); /* frames, rows */
PETSC_INTERN PetscErrorCode FCContactSetReset(FCContactSet *);
PETSC_INTERN PetscErrorCode FCContactSetDestroy(FCContactSet *);
PETSC_INTERN PetscErrorCode FCContactSetCopy(const FCContactSet *, FCContactSet *);
/* The contact of set with the same pair and side-1 point as c, or NULL */
PETSC_INTERN const FCContact *FCContactSetFind(const FCContactSet *, const FCContact *c);

/* A boundary triangle of an FE body, outward-oriented, with its vertices' first global DOF
   (-1: fixed), reference, start-of-step and free-motion positions */
typedef struct {
  PetscInt  gdof[3];
  PetscReal X[3][3], x0[3][3], xf[3][3];
} FCSurfaceTriangle;

/* Spatial hash of triangles (src/collision/collision.c), also used by the benchmark tool */
typedef struct _FCSurface   FCSurface;
PETSC_EXTERN PetscErrorCode FCSurfaceCreate(PetscInt n, FCSurfaceTriangle *tri, PetscReal distance, FCSurface **);
PETSC_EXTERN void           FCSurfaceClosest(const FCSurface *, const PetscReal x[3], PetscInt *tri, PetscReal w[3],
                                             PetscReal cp[3], PetscReal *dist2);
PETSC_EXTERN PetscErrorCode FCSurfaceDestroy(FCSurface **);

/* Contact-set helpers of the schemes (src/contact/contactset.c) */
PETSC_INTERN void FCContactSetUpdateStates(FCContactSet *); /* 0 open, 1 stick, 2 slip from the forces */
/* World force of the same contact (pair, side-1 point) in the previous step, 0 if it is new */
PETSC_INTERN void FCContactPreviousForce(const FCContactSet *previous, const FCContact *, PetscReal F[3]);
/* The warm start of every scheme: the previous step's world force of each contact, projected on
   this step's frame (lambda: M rows) */
PETSC_INTERN void FCContactSetWarmStart(const FCContactSet *set, const FCContactSet *previous, PetscReal lambda[]);
/* c->force of every contact from lambda (rows in the contact frames) */
PETSC_INTERN void FCContactSetStoreForces(FCContactSet *, const PetscReal lambda[]);
/* The set's dormant contacts as a mask for FCContactProblemSetDormant (NULL when none), and back:
   the contacts the solver woke stay awake for the rest of the step */
PETSC_INTERN PetscErrorCode FCContactSetDormantMask(const FCContactSet *, PetscBool **mask, PetscReal *depth);
PETSC_INTERN PetscErrorCode FCContactSetDormantRestore(FCContactSet *, PetscBool **mask);
/* Tangents completing a normal: the frame C_i = [n t1 t2] */
PETSC_INTERN void FCContactFrame(const PetscReal n[3], PetscReal t1[3], PetscReal t2[3]);
/* A contact's force on side 1 in world axes: lambda_n n + lambda_t1 t1 + lambda_t2 t2 */
PETSC_INTERN void FCContactForceWorld(const FCContact *, PetscReal F[3]);

/* End-of-step accuracy measures of a contact set (src/contact/measures.c, docs/output.md) */
typedef struct {
  PetscReal max_penetration, rms_penetration, violation, complementarity, cone_violation;
  PetscReal max_complementarity; /* the largest contact's natural-map error (m) */
  PetscInt  beyond;         /* contacts beyond the end-of-step check's tolerances (cone_tol, complementarity_tol) */
  PetscInt  intersections;  /* points inside another body (FCCollisionCountIntersections) */
  PetscInt  crossings;      /* features that went through another body's surface over the step (crossing.c) */
  PetscReal crossing_depth; /* how far the deepest of them ended behind that surface (m) */
} FCContactMeasures;
/* The measures, and the contacts whose cone excess (relative to the step's largest contact force)
   is above cone_tol or whose natural-map error is above complementarity_tol (m) */
PETSC_INTERN void FCContactSetMeasure(const FCContactSet *, PetscReal cone_tol, PetscReal complementarity_tol,
                                      FCContactMeasures *);
/* wnn of every contact: the normal diagonal entry of W (row-major M x M, in the contacts' frames) */
PETSC_INTERN void FCContactSetNormalCompliance(FCContactSet *, const PetscReal W[]);

/* the contact solver types (src/contact/solver.c) */
PETSC_EXTERN PetscFunctionList FCContactSolverList;
PETSC_INTERN PetscErrorCode    FCContactSolverRegisterAll(void);
