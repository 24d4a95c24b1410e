/* Private data of an FE body (src/body/fem.c), shared with its compliance builders
   (src/body/fem_compliance.c). */
#pragma once
#include "../fcimpl.h"

typedef struct {
  FCMesh     mesh;
  FCMaterial mat;
  char       material[FC_MAX_NAME];
  PetscReal  young, poisson, alpha, beta;
  PetscBool  lumped, has_fixed_box;
  PetscReal  fixed_box[6];
  PetscInt   nfixed;      /* global number of fixed vertices */
  PetscInt  *ldof;        /* per local vertex: offset in the local vector */
  PetscInt  *gdof;        /* per local vertex: first global DOF, -1 when fixed */
  PetscBool *fixed;       /* per local vertex */
  PetscReal *Dminv, *vol; /* per cell */
  Mat        M, K, A;
  Vec        u, v, dv, b, fint, fgrav, work, uloc, floc;
  KSP        ksp;
  PetscInt   nassembly, nfactor;
  PetscBool  Acurrent;       /* K and f_int belong to the current state */
  PetscInt   refactor_every; /* co-rotational: factor A every k steps, reuse the older factor between */
  PetscInt   factor_age;     /* steps since A was last factored */
  PetscReal  mass;
  /* contact */
  PetscInt           nbv, *bv;  /* owned boundary vertices (local vertex indices)          */
  Vec                Xg;        /* placed reference coordinates, layout of u               */
  Mat                JT, X;     /* dense and sparse builders: J_b^T and A^-1 J_b^T (dense) */
  PetscInt           njt, nje;  /* J_b^T by entries: the first njt on owned DOFs, nje in all */
  PetscInt          *jtr, *jtc; /* row (global DOF - first owned DOF), column                */
  PetscReal         *jtv;
  PetscInt           ncols, *cols;     /* global constraint row of each column of JT and X        */
  PetscReal         *bx0, *bxf, *bkey; /* contact point buffers                                   */
  FCProximity       *bprox;
  char               compliance[FC_MAX_NAME]; /* builder of A^-1 J^T: dense or sparse right-hand sides */
  PetscInt           ntri;                    /* local boundary faces: vertices (local indices, outward order) */
  PetscInt          *triv;
  FCSurfaceTriangle *tri;
  Vec                vloc, dvloc;
  Vec                dvfree; /* recursive schemes: dv_free kept while corrections are tried */
  /* precomputed compliance: C_0 = A_0^-1 restricted to the surface DOFs, per surface vertex */
  KSP        ksp0; /* co-rotational: factor of A_0 (reference state); linear: NULL (ksp) */
  Mat        A0;
  PetscInt   nsurf; /* non-fixed boundary vertices of the whole body */
  PetscInt  *surf;  /* their first global DOF, sorted (replicated)    */
  PetscInt  *slot;  /* per surface vertex: its cached columns, or -1   */
  PetscReal *cache; /* slot j: 3 nsurf x 3, column-major              */
  PetscInt   ncached, maxcached;
  PetscReal  Rwarp[9]; /* best-fit rotation of the body at the start of the step */
  /* redundant compliance: rgroups copies of A (one per group of ranks) and their factors */
  Mat       Ar, Fr;
  PetscInt  rfactor;        /* nfactor when Fr was factored */
  PetscInt  rgroups, group; /* copies, and the one this rank belongs to */
  PetscReal rmemory;        /* bytes per rank a copy's factorization may take */
  PetscInt  iblock;         /* MUMPS ICNTL(27) for the entries of A^-1 */
  MPI_Comm  rcomm;          /* the ranks of this copy */
} FEM;

/* Compliance builders (-compliance_type, src/body/fem_compliance.c) */
PETSC_INTERN PetscErrorCode FCFEMAddCompliance(FCBody, PetscInt self, const FCContactSet *, PetscReal W[]);
PETSC_INTERN PetscErrorCode FCFEMApplyCorrection(FCBody, PetscInt self, const FCContactSet *, const PetscReal lambda[]);
PETSC_INTERN PetscErrorCode FCFEMComplianceDestroy(FCBody);
PETSC_INTERN PetscErrorCode FCFEMComplianceReset(FCBody);
PETSC_INTERN PetscErrorCode FCFEMComplianceFactor(FCBody); /* after A is factored */
PETSC_INTERN PetscErrorCode FCFEMGet(FCBody, FEM **);      /* checks that the body is an FE body */
