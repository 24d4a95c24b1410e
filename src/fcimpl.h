/* Private definitions shared by the implementation files of fecontact. */
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

/* ---------------------------------------------------------------------------------------
   P1 tetrahedron kernels (src/element/tet.c)
   --------------------------------------------------------------------------------------- */
/* Reference data of one tet: inverse edge matrix Dm^-1 (Dm = [X1-X0, X2-X0, X3-X0]) and volume */
PETSC_INTERN PetscErrorCode FCTetReference(const PetscReal X[12], PetscReal Dminv[9], PetscReal *vol);
/* Shape function gradients grad N_a (4 x 3) from Dm^-1 */
PETSC_INTERN void FCTetGradients(const PetscReal Dminv[9], PetscReal G[12]);
/* Linear isotropic element stiffness (12 x 12, row-major) */
PETSC_INTERN void FCTetStiffness(const PetscReal G[12], PetscReal vol, PetscReal lambda, PetscReal mu,
                                 PetscReal K[144]);
/* Mass of a tet, consistent (12 x 12) or lumped (diagonal, stored dense) */
PETSC_INTERN void FCTetMass(PetscReal rho, PetscReal vol, PetscBool lumped, PetscReal M[144]);

/* ---------------------------------------------------------------------------------------
   Materials (src/material/): one file per model, registered in FCMaterialList
   --------------------------------------------------------------------------------------- */
struct _p_FCMaterial {
  char      type[FC_MAX_NAME];
  PetscReal young, poisson, lambda, mu;
  PetscBool linear; /* constant stiffness: K assembled and A factored once per run */
  /* Element internal force f (12) and tangent stiffness K (12x12) at current positions x,
     reference positions X. Either output may be NULL. */
  PetscErrorCode (*element)(FCMaterial, const PetscReal x[12], const PetscReal X[12], const PetscReal Dminv[9],
                            PetscReal vol, PetscReal f[12], PetscReal K[144]);
  /* Element elastic energy */
  PetscErrorCode (*energy)(FCMaterial, const PetscReal x[12], const PetscReal X[12], const PetscReal Dminv[9],
                           PetscReal vol, PetscReal *E);
  /* Element stress (3x3, row-major, Pa) of the model's linear law: sigma = lambda tr(eps) I + 2 mu eps with
     eps the small strain of the element (co-rotational: in the element's rotated frame, R^T F - I) */
  PetscErrorCode (*stress)(FCMaterial, const PetscReal x[12], const PetscReal X[12], const PetscReal Dminv[9],
                           PetscReal sigma[9]);
};
PETSC_EXTERN PetscFunctionList FCMaterialList;
PETSC_INTERN PetscErrorCode    FCMaterialRegisterAll(void);
PETSC_INTERN PetscErrorCode    FCMaterialCreate(const char type[], PetscReal young, PetscReal poisson, FCMaterial *);
PETSC_INTERN void              FCMaterialHooke(FCMaterial, const PetscReal H[9], PetscReal sigma[9]);
PETSC_INTERN PetscReal         FCMaterialHookeEnergy(FCMaterial, const PetscReal H[9], PetscReal vol);
PETSC_INTERN void FCMaterialDeformationGradient(const PetscReal x[12], const PetscReal Dminv[9], PetscReal F[9]);
PETSC_INTERN PetscErrorCode FCMaterialDestroy(FCMaterial *);

/* ---------------------------------------------------------------------------------------
   Shapes (src/shape/): analytic geometry of rigid and kinematic bodies
   --------------------------------------------------------------------------------------- */
struct _p_FCShape {
  char      type[FC_MAX_NAME];
  PetscReal radius, half_extents[3], length, normal[3];
  PetscBool bounded;    /* a plane is not: it has no mass and can only be kinematic */
  PetscBool smooth;     /* no edges or corners (sphere, capsule): -contact_shape_points' kind of contact */
  PetscInt  ncore;      /* a rounded shape is the set of points within `radius` of its core, a point */
  PetscReal core[2][3]; /* (sphere, ncore 1) or a segment (capsule, cylinder: ncore 2), body frame */
  PetscBool flat;       /* ... cut by flat ends through the segment's ends (cylinder); 0 for others */
  void     *data;       /* shape-specific (the mesh of a mesh shape)               */
  PetscErrorCode (*setfromoptions)(PetscOptionItems *, FCShape, const char bodyname[]);
  PetscErrorCode (*setup)(FCShape, MPI_Comm, const char prefix[], const char bodyname[]);
  PetscErrorCode (*destroy)(FCShape);
  /* Volume, and inertia tensor per unit density about the centre, in the body frame */
  PetscErrorCode (*massproperties)(FCShape, PetscReal *volume, PetscReal J[9]);
  /* Signed distance of a body-frame point x to the surface (negative inside), the outward
     unit normal there and the closest surface point (body frame) */
  PetscErrorCode (*distance)(FCShape, const PetscReal x[3], PetscReal *d, PetscReal n[3], PetscReal cp[3]);
  /* Triangulated surface in the body frame for pictures: nv vertices, nt triangles */
  PetscErrorCode (*tessellate)(FCShape, PetscInt *nv, PetscReal **xyz, PetscInt *nt, PetscInt **tri);
};
PETSC_EXTERN PetscFunctionList FCShapeList;
PETSC_INTERN PetscErrorCode    FCShapeRegisterAll(void);
PETSC_INTERN PetscErrorCode FCShapeCreateFromOptions(MPI_Comm, const char prefix[], const char bodyname[], FCShape *);
PETSC_INTERN PetscErrorCode FCShapeDestroy(FCShape *);

/* ---------------------------------------------------------------------------------------
   Tetrahedral mesh of a body (src/mesh/mesh.c): reading, validation, per-cell vertex lists
   --------------------------------------------------------------------------------------- */
typedef struct {
  DM         dm; /* DMPlex, distributed, interpolated                            */
  PetscInt   cStart, cEnd, vStart, vEnd;
  PetscInt  *cellVerts;                      /* (cEnd-cStart) x 4 local vertex points in closure order      */
  PetscReal *X;                              /* (vEnd-vStart) x 3 placed reference coordinates              */
  PetscBool *owned;                          /* (vEnd-vStart) vertex owned by this rank                      */
  IS         vertexNumbering, cellNumbering; /* global numbers (negative: not owned)      */
  PetscInt  *visVert;                        /* owned vertices (local index) in increasing global number    */
  PetscInt  *cellOrigin; /* (cEnd-cStart) each cell's index in the mesh as read, before distribution: the partition */
} FCMesh;
/* src/util/gather.c: n records of `size` bytes from every rank, concatenated in rank order on every
   rank (*all: total records, to be freed) */
PETSC_INTERN PetscErrorCode FCAllgatherRecords(MPI_Comm, PetscInt n, size_t size, const void *loc, PetscInt *total,
                                               void **all);
/* src/util/mumps.c: MUMPS factorizations checked by MUMPS' own INFOG(1); out of workspace retried on
   a new factor with ICNTL(14) doubled, 3 times (a builder's factor, a KSP's; the latter with any
   other solver checked by its PC's failure reason) */
PETSC_INTERN PetscErrorCode FCMumpsCholeskyChecked(Mat *F, Mat A, IS schur, const char what[], const char body[]);
PETSC_INTERN PetscErrorCode FCMumpsKSPChecked(KSP ksp, Mat A, const char what[], const char body[]);
/* src/mesh/partmetis.c: the PetscPartitioner type "metis" (METIS k-way on the gathered cell graph) */
#define FC_PARTITIONER_METIS "metis"
PETSC_INTERN PetscErrorCode FCPartitionerRegisterMetis(void);
/* -blas_gemv_forward: dgemm with one column as dgemv (src/util/blas.c) */
PETSC_INTERN PetscErrorCode FCBLASSetFromOptions(void);
PETSC_INTERN PetscErrorCode FCBLASView(void); /* -info: how many products it computed so */
/* The largest accepted magnitude of a mesh coordinate (m): a cell's volume, the cube of its size,
   stays finite with room to spare */
#define FC_MESH_MAX_COORDINATE 1e100
PETSC_INTERN PetscErrorCode FCMeshLoad(MPI_Comm, const char prefix[], const char bodyname[], FCMesh *);
/* src/mesh/partreplay.c: -<body>_partition_file, the partition recorded in an earlier run's output
   (/bodies/<body>/mesh/rank and cell_origin) set on the partitioner of the mesh as read (rank 0);
   nothing without the option */
PETSC_INTERN PetscErrorCode FCMeshPartitionReplay(DM serial, PetscPartitioner, const char prefix[],
                                                  const char bodyname[]);
PETSC_INTERN PetscErrorCode FCMeshTransform(FCMesh *, const PetscReal center[3], const PetscReal R[9],
                                            const PetscReal t[3]);
PETSC_INTERN PetscErrorCode FCMeshCheckCells(FCMesh *, const char bodyname[]);
PETSC_INTERN PetscErrorCode FCMeshComputeMassProperties(FCMesh *, PetscReal *volume, PetscReal centroid[3],
                                                        PetscReal J[9]);
PETSC_INTERN PetscErrorCode FCMeshCreateVisual(FCMesh *, FCBodyVisual *);
PETSC_INTERN PetscErrorCode FCMeshGetBoundary(FCMesh *, PetscInt *nbv, PetscInt **bv, PetscInt *ntri, PetscInt **triv);
PETSC_INTERN PetscErrorCode FCMeshDestroy(FCMesh *);

/* ---------------------------------------------------------------------------------------
   Contacts of one step (src/contact/contactset.c). A proximity point is a linear map of a
   body's DOFs (eq. 6): barycentric weights on FE vertices, or a body-frame point of a rigid or
   kinematic body. Contacts are replicated on every rank, in a partition-independent order.
   --------------------------------------------------------------------------------------- */
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
  PetscReal nb[3]; /* FC_SIDE_RIGID_TRIANGLE: the normal in side 2's body frame             */
  PetscReal wnn;   /* normal diagonal entry of the step's W (m/N): scales the end measures  */
  PetscReal n_end[3], d_end[3]; /* end of the step: normal on the real geometry, d = p1 - p2 (world)  */
  PetscReal p_end[3];           /* end of the step: the side-1 proximity point (world)                */
  PetscBool dormant;            /* a redundant contact kept out of the solve unless the solution violates it */
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

/* ---------------------------------------------------------------------------------------
   Body
   --------------------------------------------------------------------------------------- */
/* Fields of a body's picture written at output frames (-output_fields, src/io/fields.c): point
   fields have 3 values per visual vertex, cell fields 1 value per visual cell */
typedef enum {
  FC_FIELD_DISPLACEMENT,   /* point: x - X (m)                                               */
  FC_FIELD_VELOCITY,       /* point: dx/dt (m/s)                                             */
  FC_FIELD_VON_MISES,      /* cell, FE: von Mises stress of the material's linear stress (Pa) */
  FC_FIELD_ENERGY_DENSITY, /* cell, FE: elastic energy / reference volume (J/m^3 = Pa)        */
  FC_FIELD_NUM
} FCVisualField;
PETSC_INTERN const char *const FCVisualFieldNames[FC_FIELD_NUM];
PETSC_INTERN PetscBool         FCVisualFieldIsCell(FCVisualField);

typedef struct {
  PetscErrorCode (*setfromoptions)(FCBody);
  PetscErrorCode (*setup)(FCBody);
  PetscErrorCode (*freemotion)(FCBody, PetscReal t);
  PetscErrorCode (*integrate)(FCBody, PetscReal t);
  PetscErrorCode (*getcentroid)(FCBody, PetscReal[3]);
  PetscErrorCode (*getrotation)(FCBody, PetscReal[4], PetscBool *);
  PetscErrorCode (*getenergy)(FCBody, FCEnergy *);
  PetscErrorCode (*getvisualpositions)(FCBody, PetscReal[]);
  /* a field of the picture (FCVisualField): per owned visual vertex (3 values) or per owned visual
     cell (1 value), in the visual order; *has = PETSC_FALSE when the type has no such field */
  PetscErrorCode (*getvisualfield)(FCBody, FCVisualField, PetscReal[], PetscBool *has);
  PetscErrorCode (*checkstate)(FCBody, PetscInt);
  /* restart: FE bodies 6 values (u, v) per owned vertex in the visual order; rigid and kinematic
     bodies 13 values (x, q, v, w), the same on every rank */
  PetscErrorCode (*getstate)(FCBody, PetscReal[]);
  PetscErrorCode (*setstate)(FCBody, const PetscReal[]);
  PetscErrorCode (*destroy)(FCBody);
  /* contact: candidate points of this body (owned FE boundary vertices, or points of a rigid
     shape), each with its proximity map, start and free-motion positions */
  PetscErrorCode (*contactpoints)(FCBody, PetscInt *n, FCProximity **prox, PetscReal **x0, PetscReal **xfree,
                                  PetscReal **key);
  /* world position of a proximity point: at the start of the step, after free motion, now */
  PetscErrorCode (*proximityposition)(FCBody, const FCProximity *, PetscInt when, PetscReal x[3]);
  /* W += J_b A_b^-1 J_b^T for the contacts touching this body (W: nrows x nrows, replicated) */
  PetscErrorCode (*addcompliance)(FCBody, PetscInt self, const FCContactSet *, PetscReal W[]);
  /* optional: builds that W_b for the next addcompliance and tells whether it is the last one, on
     the same rows of W (NULL: a body that adds something is never known to be unchanged; one that
     has it is always called before addcompliance, by FCSchemeCompliance) */
  PetscErrorCode (*buildcompliance)(FCBody, PetscInt self, const FCContactSet *, PetscBool *same);
  /* signed distance of a world point to this body's shape now: outward normal (world) and the
     closest point (body frame) */
  PetscErrorCode (*shapedistance)(FCBody, const PetscReal x[3], PetscReal *d, PetscReal n[3], PetscReal cpb[3]);
  /* the same against the shape at its pose after the free motion (end of the step for a kinematic body) */
  PetscErrorCode (*shapedistancefree)(FCBody, const PetscReal x[3], PetscReal *d, PetscReal n[3], PetscReal cpb[3]);
  /* FE: the boundary triangles this rank holds (start and free positions of this step) */
  PetscErrorCode (*surfacetriangles)(FCBody, PetscInt *n, FCSurfaceTriangle **);
  /* rigid and kinematic: a world point or direction in the body frame, at the pose now (start of
     the step during detection) or after the free motion (when = FC_AT_NOW, FC_AT_FREE) */
  PetscErrorCode (*tobody)(FCBody, PetscInt when, const PetscReal x[3], PetscBool direction, PetscReal r[3]);
  /* the rotation of the body frame over the step (start to free motion): its angle and the
     body-frame point it turns about (rigid and kinematic bodies; none: no rotation) */
  PetscErrorCode (*steprotation)(FCBody, PetscReal *theta, PetscReal center[3]);
  /* add w x (current position) of the vertices of a proximity point this rank owns (FE), or
     the point on rank 0 (rigid, kinematic) */
  PetscErrorCode (*partialposition)(FCBody, const FCProximity *, PetscReal x[3]);
  /* a body named in a contact pair: what its response needs (FE: the compliance builder) */
  PetscErrorCode (*setupcontact)(FCBody);
  /* recursive schemes: keep dv_free, go back to it, and add w x of a proximity point at the
     trial state q + h (v + dv) (owned FE vertices; rigid on rank 0) */
  PetscErrorCode (*savefree)(FCBody);
  PetscErrorCode (*restorefree)(FCBody);
  PetscErrorCode (*trialposition)(FCBody, const FCProximity *, PetscReal x[3]);
  /* dv += h A_b^-1 J_b^T lambda */
  PetscErrorCode (*applycorrection)(FCBody, PetscInt self, const FCContactSet *, const PetscReal lambda[]);
  /* the contacts a proximity query at the start of a run expects, before the body's first
     factorization: a body whose factorization depends on its contact DOFs prepares for them
     (set by the body at contact set-up, with `expects`) */
  PetscErrorCode (*expectcontacts)(FCBody, PetscInt self, const FCContactSet *);
} FCBodyOps;
enum { FC_AT_START, FC_AT_FREE, FC_AT_NOW };

struct _p_FCBody {
  MPI_Comm  comm;
  PetscBool deformable;       /* set by the type: DOFs at mesh vertices, a surface that deforms (fem) */
  PetscBool prescribed;       /* set by the type: motion given, takes no force (kinematic)           */
  PetscInt  state_cols;       /* set by the type: restart values per row ...                     */
  PetscBool state_per_vertex; /* ... one row per visual vertex (else one row, on rank 0)          */
  char      name[FC_MAX_NAME];
  char      prefix[FC_MAX_NAME + 1]; /* "<name>_" */
  char      type[FC_MAX_NAME];
  FCBodyOps ops;
  void     *data;
  PetscBool setupcalled;
  PetscBool expects; /* its first factorization depends on its contacts: FCBodyExpectContacts before the free motion */
  PetscReal h, gravity[3];
  /* placement and initial motion, common to every type */
  PetscReal    translate[3], rotate[4], center[3], velocity[3], angular_velocity[3];
  PetscBool    center_set;
  PetscReal    density;
  PetscReal    mass; /* set by the type at set-up (fem, rigid); 0: kinematic */
  FCBodyVisual visual;
  FCShape      shape; /* rigid and kinematic bodies: their shape (owned by the pose) */
};

/* What a body is, and what code outside src/body/ may ask of it (src/body/body_ops.c): no other
   file reads body->ops or compares body type names. */
PETSC_INTERN PetscBool FCBodyIsDeformable(FCBody);    /* FE: vertex DOFs, a deforming surface     */
PETSC_INTERN PetscBool FCBodyIsPrescribed(FCBody);    /* kinematic: given motion, takes no force  */
PETSC_INTERN PetscBool FCBodyHasShape(FCBody);        /* a signed distance (rigid, kinematic)     */
PETSC_INTERN PetscBool FCBodyHasBoundedShape(FCBody); /* ... of a closed shape (not a plane)      */
PETSC_INTERN PetscBool FCBodyHasShapeCore(FCBody);    /* ... rounded, with a core (sphere, capsule, cylinder) */
/* the core of a rounded shape (FCShape: a point or a segment, body frame), its radius and whether
   its ends are flat (cylinder); *ncore 0 for a body without one */
PETSC_INTERN void FCBodyGetShapeCore(FCBody, PetscInt *ncore, PetscReal core[2][3], PetscReal *radius, PetscBool *flat);
PETSC_INTERN PetscBool FCBodyHasSmoothShape(FCBody);      /* ... without edges (sphere, capsule)      */
PETSC_INTERN PetscBool FCBodyHasSurfaceTriangles(FCBody); /* FE bodies and mesh shapes           */
PETSC_INTERN PetscBool FCBodyIsBox(FCBody);               /* a rigid or kinematic box              */
PETSC_INTERN void      FCBodyGetBoxHalfExtents(FCBody, PetscReal h[3]);
PETSC_INTERN PetscReal FCBodyGetMass(FCBody); /* after set-up; 0 for kinematic bodies */
/* Restart state: `cols` values per visual vertex (pervertex, distributed like the visual) or one
   row of `cols` values on rank 0 */
PETSC_INTERN PetscErrorCode FCBodyGetStateLayout(FCBody, PetscInt *cols, PetscBool *pervertex);
PETSC_INTERN PetscErrorCode FCBodyGetState(FCBody, PetscReal[]);
/* A field of the body's picture (see FCBodyOps.getvisualfield); *has = PETSC_FALSE when the body has none */
PETSC_INTERN PetscErrorCode FCBodyGetVisualField(FCBody, FCVisualField, PetscReal[], PetscBool *has);
PETSC_INTERN PetscErrorCode FCBodySetState(FCBody, const PetscReal[]);
/* Contact geometry (see FCBodyOps for the meaning of each) */
PETSC_INTERN PetscErrorCode FCBodyGetContactPoints(FCBody, PetscInt *n, FCProximity **prox, PetscReal **x0,
                                                   PetscReal **xfree, PetscReal **key);
PETSC_INTERN PetscErrorCode FCBodyGetSurfaceTriangles(FCBody, PetscInt *n, FCSurfaceTriangle **);
PETSC_INTERN PetscErrorCode FCBodyProximityPosition(FCBody, const FCProximity *, PetscInt when, PetscReal x[3]);
/* when: FC_AT_NOW (the shape's pose now) or FC_AT_FREE (after the free motion) */
PETSC_INTERN PetscErrorCode FCBodyShapeDistance(FCBody, PetscInt when, const PetscReal x[3], PetscReal *d,
                                                PetscReal n[3], PetscReal cpb[3]);
/* when: FC_AT_NOW (the pose now) or FC_AT_FREE (after the free motion) */
/* The angle the body frame turns by over the step and the body-frame point it turns about (0 for
   bodies that do not rotate rigidly): continuous detection bounds the arc a point follows in it */
PETSC_INTERN PetscErrorCode FCBodyStepRotation(FCBody, PetscReal *theta, PetscReal center[3]);
PETSC_INTERN PetscErrorCode FCBodyToBodyFrame(FCBody, PetscInt when, const PetscReal x[3], PetscBool direction,
                                              PetscReal r[3]);
/* signed distance of a body-frame point to the body's shape: outward normal and closest point, body frame */
PETSC_INTERN PetscErrorCode FCBodyShapeDistanceLocal(FCBody, const PetscReal r[3], PetscReal *d, PetscReal n[3],
                                                     PetscReal cp[3]);
PETSC_INTERN PetscErrorCode FCBodyAddPartialPosition(FCBody, const FCProximity *, PetscReal x[3]);
/* Contact response */
PETSC_INTERN PetscErrorCode FCBodySetUpContact(FCBody); /* a body named in a contact pair, after FCBodySetUp */
PETSC_INTERN PetscErrorCode FCBodyAddCompliance(FCBody, PetscInt self, const FCContactSet *, PetscReal W[]);
/* before FCBodyAddCompliance with the same set: whether the body's part of W is the one it added
   last (on the same rows): a W summed from the bodies' last parts still holds when every one is */
PETSC_INTERN PetscErrorCode FCBodyBuildCompliance(FCBody, PetscInt self, const FCContactSet *, PetscBool *same);
/* before the first free motion of a run: whether the body's factorization depends on its contacts,
   and the contacts a proximity query at the start positions gives it */
PETSC_INTERN PetscBool      FCBodyExpectsContacts(FCBody);
PETSC_INTERN PetscErrorCode FCBodyExpectContacts(FCBody, PetscInt self, const FCContactSet *);
PETSC_INTERN PetscErrorCode FCBodyApplyCorrection(FCBody, PetscInt self, const FCContactSet *,
                                                  const PetscReal lambda[]);
PETSC_INTERN PetscErrorCode FCBodySaveFreeMotion(FCBody);
PETSC_INTERN PetscErrorCode FCBodyRestoreFreeMotion(FCBody);
PETSC_INTERN PetscErrorCode FCBodyAddTrialPosition(FCBody, const FCProximity *, PetscReal x[3]);

PETSC_INTERN PetscErrorCode FCBodyRegisterAll(void);
/* Reads the placement options of a body: -<name>_translate, _rotate, _center, _velocity,
   _angular_velocity. */
PETSC_INTERN PetscErrorCode FCBodyReadPlacement(FCBody);
/* Rotation matrix of -<name>_rotate */
PETSC_INTERN void           FCBodyPlacementRotation(FCBody, PetscReal R[9]);
PETSC_INTERN PetscErrorCode FCBodyVisualFromShape(FCBody, FCShape);
PETSC_INTERN PetscErrorCode FCBodyVisualDestroy(FCBodyVisual *);

/* ---------------------------------------------------------------------------------------
   Compliance builders (src/compliance/): W_b = J_b A_b^-1 J_b^T of an FE body (eq. 17) and its
   correction dv += h A_b^-1 J_b^T lambda (eq. 20); one file per type, -compliance_type
   --------------------------------------------------------------------------------------- */
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
PETSC_INTERN PetscErrorCode    FCComplianceSetUp(FCCompliance);          /* at set-up, A at the reference state */
PETSC_INTERN PetscErrorCode    FCComplianceFactor(FCCompliance);         /* after every change of A            */
/* A builder that factors A itself (condensed) is the body's only factor: the body calls
   FCComplianceFactor instead of factoring and FCComplianceSolve for its solves */
PETSC_INTERN PetscBool      FCComplianceFactorsA(FCCompliance);
PETSC_INTERN PetscErrorCode FCComplianceSolve(FCCompliance, Vec b, Vec x);
/* a builder that warps a reference compliance needs the body's best-fit rotation before each Add */
PETSC_INTERN PetscBool      FCComplianceUsesRotation(FCCompliance);
PETSC_INTERN PetscErrorCode FCComplianceSetRotation(FCCompliance, const PetscReal R[9]);
/* W_b = J_b A^-1 J_b^T for the contacts touching body `self`, kept for the next Add; same: it is the
   last build's W_b on the same rows of W (a sum of the last builds still holds) */
PETSC_INTERN PetscErrorCode FCComplianceBuild(FCCompliance, PetscInt self, const FCContactSet *, PetscBool *same);
/* W (M x M, row-major, replicated) += J_b A^-1 J_b^T for the contacts touching body `self`: the W_b
   of the Build just before, with the same set */
PETSC_INTERN PetscErrorCode FCComplianceAdd(FCCompliance, PetscInt self, const FCContactSet *, PetscReal W[]);
/* a builder whose factorization depends on the contact DOFs (condensed) takes the contacts expected
   at its next factorization: whether it does, and the contacts */
PETSC_INTERN PetscBool      FCComplianceUsesExpectedContacts(FCCompliance);
PETSC_INTERN PetscErrorCode FCComplianceExpectContacts(FCCompliance, PetscInt self, const FCContactSet *);
/* dv += h A^-1 J_b^T lambda for the J_b of the last Add */
PETSC_INTERN PetscErrorCode FCComplianceCorrect(FCCompliance, PetscReal h, const PetscReal lambda[], Vec dv);
PETSC_INTERN PetscErrorCode FCComplianceDestroy(FCCompliance *);

/* ---------------------------------------------------------------------------------------
   Output (src/io/): one HDF5 file per run, an XDMF file beside it for ParaView
   --------------------------------------------------------------------------------------- */
typedef struct _p_FCOutput *FCOutput;
PETSC_INTERN PetscErrorCode FCOutputCreate(MPI_Comm, const char filename[], FCOutput *);
struct _FCContactSetView; /* defined with the schemes below */
PETSC_INTERN PetscErrorCode FCOutputWriteHeader(FCOutput, PetscInt nbodies, FCBody[], PetscReal h, PetscInt nsteps,
                                                PetscInt every, PetscBool contacts);
/* The contacts of the step just recorded (only in scenes with contact pairs) */
PETSC_INTERN PetscErrorCode FCOutputRecordContacts(FCOutput, const struct _FCContactSetView *);
PETSC_INTERN PetscErrorCode FCOutputRecordStep(FCOutput, PetscInt step, PetscReal t,
                                               const PetscReal timing[FC_PHASE_NUM], PetscReal wall, PetscInt nbodies,
                                               FCBody[]);
PETSC_INTERN PetscErrorCode FCOutputWriteFrame(FCOutput, PetscInt step, PetscReal t, PetscInt nbodies, FCBody[]);
PETSC_INTERN PetscErrorCode FCOutputFlush(FCOutput);
/* The restart state of the end of `step` (/restart, written before the frame's flush); the
   restart format is written and read in src/io/restart.c */
PETSC_INTERN PetscErrorCode FCOutputWriteRestart(FCOutput, PetscInt step, PetscReal t, PetscInt nbodies, FCBody[],
                                                 const FCContactSet *previous);
/* Reads the newest complete restart state of a file into the bodies, previous contacts, step, t */
PETSC_INTERN PetscErrorCode FCRestartLoad(MPI_Comm, const char file[], PetscInt nbodies, FCBody[],
                                          FCContactSet *previous, PetscInt *step, PetscReal *t);
PETSC_INTERN PetscErrorCode FCOutputDestroy(FCOutput *);
PETSC_INTERN PetscErrorCode FCXdmfWrite(FCOutput);
/* -output_fields: the list of field names (FCVisualFieldNames, or "none") as a bit mask, 1 << field;
   an unknown name is an error naming the option */
PETSC_INTERN PetscErrorCode FCOutputFieldsParse(MPI_Comm, const char list[], PetscInt *mask);
PETSC_INTERN PetscErrorCode FCOutputSetFields(FCOutput, PetscInt mask); /* before FCOutputWriteHeader */
/* After a write that failed inside HDF5 the output file cannot be closed: the program must then
   leave without HDF5's clean-up in MPI_Finalize (src/main.c; src/io/output.c, FCOutputDestroy) */
PETSC_INTERN PetscBool FCOutputFileLeftOpen(void);

/* ---------------------------------------------------------------------------------------
   Contact pairs, collision detection (src/collision/) and the constraint schemes (src/scheme/)
   --------------------------------------------------------------------------------------- */
typedef struct {
  PetscInt n;
  PetscInt (*body)[2]; /* scene body indices */
  PetscReal *mu;
  PetscReal  distance;      /* alarm distance */
  PetscInt   passes;        /* FE-FE and FE-mesh pairs: 2 both ways, 1 first body's vertices only */
  PetscReal  pass2_drop;    /* -contact_fe_pass2_drop: drop 2nd-pass vertices held by the 1st pass (< 0: off) */
  PetscReal  pass2_dormant; /* -contact_fe_pass2_dormant: such contacts dormant instead (< 0: off) */
  PetscReal  dormant_depth; /* -contact_dormant_depth: a dormant contact wakes when left deeper than this (m) */
  PetscBool  facing;        /* -contact_facing: a vertex lands only on triangles that face its own surface */
  PetscBool  continuous;    /* -contact_detection continuous (default) or discrete */
  PetscBool  edges;         /* -contact_edge_edge: edge-edge contacts of meshed pairs (default) */
  PetscBool  shape_points;  /* -contact_shape_points: a bounded shape's points against an FE surface too */
  PetscBool  rounded_exact; /* -contact_rounded_surface exact: a sphere's or capsule's nearest FE surface points */
  PetscReal
      separation_speed; /* -contact_separation_speed: bodies that start inside each other part at most this fast */
  PetscReal intersection_depth;   /* a point deeper than this inside another body is an intersection */
  PetscBool fail_on_intersection; /* -contact_fail_on_intersection: stop the run at the first one */
} FCContactPairs;
/* Discrete collision detection at the start of the step (after the free motion has been
   computed, so that every contact also carries its free-motion positions) */
PETSC_INTERN PetscErrorCode FCCollisionDetect(MPI_Comm, PetscInt nbodies, FCBody bodies[], const FCContactPairs *,
                                              FCContactSet *);
/* Gap, normal and d = p1 - p2 of every contact at the end of the step, on the real geometry */
PETSC_INTERN PetscErrorCode FCCollisionEndGaps(MPI_Comm, PetscInt nbodies, FCBody bodies[], FCContactSet *);
/* The points inside another body at the end of the step (src/collision/intersection.c), the same
   on every rank */
PETSC_INTERN PetscErrorCode FCCollisionCountIntersections(MPI_Comm, PetscInt nbodies, FCBody bodies[],
                                                          const FCContactPairs *, PetscInt *count);

typedef struct {
  PetscInt  contacts, rows, sweeps;
  PetscReal residual;
  PetscInt  newton; /* Newton iterations (recursive schemes; 1 for explicit) */
} FCSchemeStats;

/* FCScheme: a constraint scheme (src/scheme/), -constraint_scheme explicit|standard|fast. It owns
   the contact solver and, per step, turns the contact set into forces and corrected motions. */
#define FCSCHEMEEXPLICIT "explicit"
#define FCSCHEMESTANDARD "standard"
#define FCSCHEMEFAST "fast"
PETSC_EXTERN PetscFunctionList FCSchemeList;
PETSC_INTERN PetscErrorCode    FCSchemeRegisterAll(void);
/* the contact solver types (src/contact/solver.c) */
PETSC_EXTERN PetscFunctionList FCContactSolverList;
PETSC_INTERN PetscErrorCode    FCContactSolverRegisterAll(void);
PETSC_INTERN PetscErrorCode    FCSchemeCreate(MPI_Comm, PetscInt nbodies, FCBody bodies[], FCScheme *);
PETSC_INTERN PetscErrorCode    FCSchemeSetType(FCScheme, FCSchemeType);
PETSC_INTERN PetscErrorCode    FCSchemeSetFromOptions(FCScheme);
/* One step's contacts: forces (set->c[k].force, state) and the bodies' corrected dv; `step`
   names the step in errors (a contact problem left unsolved stops the run, -pgs_fail_residual) */
PETSC_INTERN PetscErrorCode FCSchemeSolve(FCScheme, PetscInt step, FCContactSet *, const FCContactSet *previous,
                                          FCSchemeStats *);
PETSC_INTERN PetscErrorCode FCSchemeDestroy(FCScheme *);

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

/* End-of-step accuracy measures of a contact set (src/contact/measures.c, docs/output.md) */
typedef struct {
  PetscReal max_penetration, rms_penetration, violation, complementarity, cone_violation;
  PetscInt  intersections; /* points inside another body (FCCollisionCountIntersections) */
} FCContactMeasures;
PETSC_INTERN void FCContactSetMeasure(const FCContactSet *, FCContactMeasures *);
/* wnn of every contact: the normal diagonal entry of W (row-major M x M, in the contacts' frames) */
PETSC_INTERN void FCContactSetNormalCompliance(FCContactSet *, const PetscReal W[]);

struct _FCContactSetView {
  const FCContactSet      *set;
  const FCSchemeStats     *stats;
  const FCContactMeasures *measures;
};

/* The guard on the total energy of the scene (src/scene/energy.c): -energy_growth_limit */
typedef struct {
  PetscReal limit; /* stop when the energy grows by more than limit * scale (0: never) */
  PetscReal E0;    /* total energy at set-up (or at the restart point) */
  PetscReal scale; /* the energy the scene may receive (J) */
  PetscReal Eb0[FC_MAX_BODIES];
  PetscBool reported; /* stops once */
} FCEnergyGuard;
PETSC_INTERN PetscErrorCode FCEnergyGuardSetFromOptions(FCEnergyGuard *, MPI_Comm);
/* speed: the largest speed of separation the contact response may give (0: no contact pairs) */
PETSC_INTERN PetscErrorCode FCEnergyGuardSetUp(FCEnergyGuard *, MPI_Comm, PetscInt nbodies, FCBody[], PetscReal h,
                                               PetscInt nsteps, PetscReal speed);
PETSC_INTERN PetscErrorCode FCEnergyGuardCheck(FCEnergyGuard *, MPI_Comm, PetscInt nbodies, FCBody[], PetscInt step,
                                               PetscReal t, PetscReal h);

/* The files a run reads, by identity, and the check that an output is none of them
   (src/util/inputs.c) */
PETSC_INTERN PetscErrorCode FCInputsReset(void);
PETSC_INTERN PetscErrorCode FCInputsAdd(const char path[], const char what[]);
PETSC_INTERN PetscErrorCode FCInputsAddOptionsFiles(void);
PETSC_INTERN PetscErrorCode FCInputsCheckOutput(MPI_Comm, const char path[], const char what[]);

/* SIGINT/SIGTERM: recorded by a handler, acted on between steps (src/util/signals.c) */
PETSC_INTERN PetscErrorCode FCSignalsInstall(void);
PETSC_INTERN PetscErrorCode FCSignalsPending(MPI_Comm, int *sig);
PETSC_INTERN int            FCSignalsCaught(void);

/* Progress line on rank 0 (src/util/progress.c) */
typedef struct {
  PetscLogDouble start, last;
  PetscBool      quiet;
  PetscInt       warned; /* steps with intersections so far */
} FCProgress;
PETSC_INTERN PetscErrorCode FCProgressStart(FCProgress *, PetscBool quiet);
/* intersections: points inside another body at the end of the step; when not 0 the line is printed
   whatever the time since the last one, with a warning */
PETSC_INTERN PetscErrorCode FCProgressUpdate(FCProgress *, MPI_Comm, PetscInt step, PetscInt nsteps, PetscReal t,
                                             PetscInt intersections);
