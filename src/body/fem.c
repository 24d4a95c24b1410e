/* Deformable body: P1 tetrahedra, linear or co-rotational elasticity, lumped or consistent
   mass, Rayleigh damping B = alpha M + beta K, linearized backward Euler (eq. 5):
       A dv = b,  A = M + h B + h^2 K,  b = h (f_ext - f_int(q)) - h B v - h^2 K v,
   then v += dv, u += h v (eq. 2). Fixed vertices are constrained out of the section, so A is
   symmetric positive definite on the free DOFs and is factored by the body's KSP (default
   preonly + Cholesky + MUMPS). A linear material's A is assembled and factored once per run.

   Options (prefix <body>_):
     -<body>_dm_plex_filename f.msh   the mesh (required); every -<body>_dm_* option applies
     -<body>_material linear|corotational   (default linear)
     -<body>_young E                  Young's modulus, Pa (> 0, required)
     -<body>_poisson nu               Poisson's ratio (-1 < nu < 0.5, default 0.3)
     -<body>_density rho              kg/m^3 (> 0, required)
     -<body>_mass_type lumped|consistent   (default consistent)
     -<body>_rayleigh_mass alpha      damping alpha M (>= 0, default 0)
     -<body>_rayleigh_stiffness beta  damping beta K (>= 0, default 0)
     -<body>_fixed_box x0,y0,z0,x1,y1,z1   vertices inside (placed coordinates) are fixed
     -<body>_refactor_every k         co-rotational only: factor A every k steps (>= 1, default 1);
                                      between, K and f_int are current but A^-1 is the older
                                      factor's (a modified-Newton free motion, cheaper, less exact)
     -<body>_ksp_type, -<body>_pc_type, -<body>_pc_factor_mat_solver_type ...   the solver */
#include "femimpl.h"

static PetscErrorCode SetFromOptions_FEM(FCBody body)
{
  FEM      *fem = (FEM *)body->data;
  PetscBool set, setE, setRho;
  char      masstype[FC_MAX_NAME] = "consistent";

  PetscFunctionBegin;
  PetscOptionsBegin(body->comm, body->prefix, "FE body options", "FCBody");
  PetscCall(PetscOptionsFList("-material", "Material model", NULL, FCMaterialList, fem->material, fem->material,
                              sizeof(fem->material), &set));
  PetscCall(FCOptionsReal(PetscOptionsObject, "-young", "Young's modulus (Pa)", &fem->young, &setE));
  PetscCall(FCOptionsReal(PetscOptionsObject, "-poisson", "Poisson's ratio", &fem->poisson, NULL));
  PetscCall(FCOptionsReal(PetscOptionsObject, "-density", "Density (kg/m^3)", &body->density, &setRho));
  PetscCall(PetscOptionsString("-mass_type", "Mass matrix: consistent or lumped", NULL, masstype, masstype,
                               sizeof(masstype), NULL));
  PetscCall(FCOptionsReal(PetscOptionsObject, "-rayleigh_mass", "Rayleigh damping alpha (B = alpha M + beta K)",
                          &fem->alpha, NULL));
  PetscCall(FCOptionsReal(PetscOptionsObject, "-rayleigh_stiffness", "Rayleigh damping beta (B = alpha M + beta K)",
                          &fem->beta, NULL));
  PetscCall(FCOptionsRealArray(PetscOptionsObject, "-fixed_box",
                               "Fix the vertices inside xmin,ymin,zmin,xmax,ymax,zmax", 6, fem->fixed_box,
                               &fem->has_fixed_box));
  if (strcmp(fem->material, "linear")) /* a linear A never changes: nothing to refactor */
    PetscCall(FCOptionsInt(PetscOptionsObject, "-refactor_every", "Factor A every k steps (co-rotational)",
                           &fem->refactor_every, NULL));
  PetscOptionsEnd();
  PetscCheck(fem->refactor_every >= 1, body->comm, PETSC_ERR_USER_INPUT,
             "Option -%srefactor_every must be >= 1, got %" PetscInt_FMT, body->prefix, fem->refactor_every);
  PetscCheck(!strcmp(masstype, "consistent") || !strcmp(masstype, "lumped"), body->comm, PETSC_ERR_USER_INPUT,
             "Unknown mass type '%s' in -%smass_type (known: consistent, lumped)", masstype, body->prefix);
  fem->lumped = !strcmp(masstype, "lumped") ? PETSC_TRUE : PETSC_FALSE;
  {
    PetscErrorCode (*create)(FCMaterial) = NULL;
    PetscCall(PetscFunctionListFind(FCMaterialList, fem->material, &create));
    PetscCheck(create, body->comm, PETSC_ERR_USER_INPUT,
               "Unknown material '%s' in -%smaterial (known: linear, corotational)", fem->material, body->prefix);
  }
  PetscCheck(setE, body->comm, PETSC_ERR_USER_INPUT, "FE body '%s' needs -%syoung", body->name, body->prefix);
  PetscCheck(setRho, body->comm, PETSC_ERR_USER_INPUT, "FE body '%s' needs -%sdensity", body->name, body->prefix);
  PetscCall(FCCheckPositive(body->comm, body->prefix, "-young", fem->young));
  PetscCall(FCCheckPositive(body->comm, body->prefix, "-density", body->density));
  PetscCheck(fem->poisson > -1.0 && fem->poisson < 0.5, body->comm, PETSC_ERR_USER_INPUT,
             "Option -%spoisson must lie in (-1, 0.5), got %g", body->prefix, (double)fem->poisson);
  PetscCall(FCCheckNonNegative(body->comm, body->prefix, "-rayleigh_mass", fem->alpha));
  PetscCall(FCCheckNonNegative(body->comm, body->prefix, "-rayleigh_stiffness", fem->beta));
  if (fem->has_fixed_box)
    for (int d = 0; d < 3; d++)
      PetscCheck(fem->fixed_box[d] <= fem->fixed_box[3 + d], body->comm, PETSC_ERR_USER_INPUT,
                 "Option -%sfixed_box: min %d (%g) > max (%g)", body->prefix, d, (double)fem->fixed_box[d],
                 (double)fem->fixed_box[3 + d]);
  PetscFunctionReturn(0);
}

/* Element positions: reference X and current x = X + u (fixed vertices do not move) */
static void GatherElement(FEM *fem, PetscInt c, const PetscScalar *uloc, PetscReal X[12], PetscReal x[12])
{
  FCMesh *m = &fem->mesh;
  for (int a = 0; a < 4; a++) {
    PetscInt v = m->cellVerts[4 * c + a] - m->vStart;
    for (int d = 0; d < 3; d++) {
      X[3 * a + d] = m->X[3 * v + d];
      x[3 * a + d] = X[3 * a + d] + (fem->fixed[v] || !uloc ? 0.0 : PetscRealPart(uloc[fem->ldof[v] + d]));
    }
  }
}

static void ElementIndices(FEM *fem, PetscInt c, PetscInt idx[12])
{
  FCMesh *m = &fem->mesh;
  for (int a = 0; a < 4; a++) {
    PetscInt v = m->cellVerts[4 * c + a] - m->vStart;
    for (int d = 0; d < 3; d++) idx[3 * a + d] = fem->gdof[v] < 0 ? -1 : fem->gdof[v] + d;
  }
}

/* Element loop: f (global, may be NULL) = f_int(u), K (may be NULL) = tangent stiffness */
static PetscErrorCode AssembleElastic(FCBody body, Vec u, Vec f, Mat K)
{
  FEM               *fem = (FEM *)body->data;
  FCMesh            *m   = &fem->mesh;
  const PetscScalar *ul;
  PetscScalar       *fl = NULL;

  PetscFunctionBegin;
  PetscCall(FCPhaseBegin(FC_PHASE_ASSEMBLY));
  PetscCall(DMGlobalToLocal(m->dm, u, INSERT_VALUES, fem->uloc));
  PetscCall(VecGetArrayRead(fem->uloc, &ul));
  if (f) {
    PetscCall(VecZeroEntries(fem->floc));
    PetscCall(VecGetArray(fem->floc, &fl));
  }
  if (K) PetscCall(MatZeroEntries(K));
  for (PetscInt c = 0; c < m->cEnd - m->cStart; c++) {
    PetscReal X[12], x[12], fe[12], Ke[144];
    PetscInt  idx[12];
    GatherElement(fem, c, ul, X, x);
    PetscCall((*fem->mat->element)(fem->mat, x, X, &fem->Dminv[9 * c], fem->vol[c], f ? fe : NULL, K ? Ke : NULL));
    if (f)
      for (int a = 0; a < 4; a++) {
        PetscInt v = m->cellVerts[4 * c + a] - m->vStart;
        if (fem->fixed[v]) continue;
        for (int d = 0; d < 3; d++) fl[fem->ldof[v] + d] += fe[3 * a + d];
      }
    if (K) {
      ElementIndices(fem, c, idx);
      PetscCall(MatSetValues(K, 12, idx, 12, idx, Ke, ADD_VALUES));
    }
  }
  PetscCall(VecRestoreArrayRead(fem->uloc, &ul));
  if (f) {
    PetscCall(VecRestoreArray(fem->floc, &fl));
    PetscCall(VecZeroEntries(f));
    PetscCall(DMLocalToGlobal(m->dm, fem->floc, ADD_VALUES, f));
  }
  if (K) {
    PetscCall(MatAssemblyBegin(K, MAT_FINAL_ASSEMBLY));
    PetscCall(MatAssemblyEnd(K, MAT_FINAL_ASSEMBLY));
  }
  fem->nassembly++;
  PetscCall(FCPhaseEnd(FC_PHASE_ASSEMBLY));
  PetscFunctionReturn(0);
}

/* A = (1 + h alpha) M + (h beta + h^2) K, then its factorization */
static PetscErrorCode FormAndFactorA(FCBody body)
{
  FEM      *fem = (FEM *)body->data;
  PetscReal h   = body->h;

  PetscFunctionBegin;
  PetscCall(FCPhaseBegin(FC_PHASE_ASSEMBLY));
  PetscCall(MatCopy(fem->K, fem->A, SAME_NONZERO_PATTERN));
  PetscCall(MatScale(fem->A, h * fem->beta + h * h));
  PetscCall(MatAXPY(fem->A, 1.0 + h * fem->alpha, fem->M, SUBSET_NONZERO_PATTERN));
  PetscCall(MatSetOption(fem->A, MAT_SPD, PETSC_TRUE));
  PetscCall(FCPhaseEnd(FC_PHASE_ASSEMBLY));
  PetscCall(FCPhaseBegin(FC_PHASE_FACTORIZATION));
  PetscCall(KSPSetOperators(fem->ksp, fem->A, fem->A));
  PetscCall(KSPSetUp(fem->ksp));
  {
    PC             pc;
    PCFailedReason reason;
    PetscCall(KSPGetPC(fem->ksp, &pc));
    PetscCall(PCGetFailedReason(pc, &reason));
    PetscCheck(reason == PC_NOERROR, body->comm, PETSC_ERR_CONV_FAILED,
               "Factorization of A for body '%s' failed: %s (out of memory with MUMPS, which underestimates its "
               "workspace now and then on several ranks: raise the margin, -%smat_mumps_icntl_14 50)",
               body->name, PCFailedReasons[reason], body->prefix);
  }
  fem->nfactor++;
  fem->factor_age = 0;
  PetscCall(FCFEMComplianceFactor(body)); /* builders that keep their own factor of A */
  PetscCall(FCPhaseEnd(FC_PHASE_FACTORIZATION));
  fem->Acurrent = PETSC_TRUE;
  PetscFunctionReturn(0);
}

static PetscErrorCode AssembleMass(FCBody body)
{
  FEM         *fem = (FEM *)body->data;
  FCMesh      *m   = &fem->mesh;
  Vec          mloc;
  PetscScalar *ml;

  PetscFunctionBegin;
  PetscCall(FCPhaseBegin(FC_PHASE_ASSEMBLY));
  PetscCall(MatZeroEntries(fem->M));
  PetscCall(DMGetLocalVector(m->dm, &mloc));
  PetscCall(VecZeroEntries(mloc));
  PetscCall(VecGetArray(mloc, &ml));
  fem->mass = 0.0;
  for (PetscInt c = 0; c < m->cEnd - m->cStart; c++) {
    PetscReal Me[144];
    PetscInt  idx[12];
    FCTetMass(body->density, fem->vol[c], fem->lumped, Me);
    ElementIndices(fem, c, idx);
    PetscCall(MatSetValues(fem->M, 12, idx, 12, idx, Me, ADD_VALUES));
    fem->mass += body->density * fem->vol[c];
    /* gravity: the load of a P1 element on each vertex is rho V / 4 g, whatever the mass matrix */
    for (int a = 0; a < 4; a++) {
      PetscInt v = m->cellVerts[4 * c + a] - m->vStart;
      if (fem->fixed[v]) continue;
      for (int d = 0; d < 3; d++) ml[fem->ldof[v] + d] += body->density * fem->vol[c] / 4.0 * body->gravity[d];
    }
  }
  PetscCall(VecRestoreArray(mloc, &ml));
  PetscCall(VecZeroEntries(fem->fgrav));
  PetscCall(DMLocalToGlobal(m->dm, mloc, ADD_VALUES, fem->fgrav));
  PetscCall(DMRestoreLocalVector(m->dm, &mloc));
  PetscCall(MatAssemblyBegin(fem->M, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(fem->M, MAT_FINAL_ASSEMBLY));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &fem->mass, 1, MPIU_REAL, MPIU_SUM, body->comm));
  PetscCall(FCPhaseEnd(FC_PHASE_ASSEMBLY));
  PetscFunctionReturn(0);
}

/* K, M and A share the pattern of the element couplings. The pattern is recorded by a
   MATPREALLOCATOR pass over the cells (DMCreateMatrix's adjacency-based preallocation costs
   more than a factorization on 10^5 DOFs); the matrix type follows -<body>_dm_mat_type. */
static PetscErrorCode CreateOperators(FCBody body)
{
  FEM        *fem = (FEM *)body->data;
  FCMesh     *m   = &fem->mesh;
  Mat         P;
  PetscInt    n, N;
  MatType     mtype;
  PetscScalar zeros[144] = {0};

  PetscFunctionBegin;
  PetscCall(VecGetLocalSize(fem->u, &n));
  PetscCall(VecGetSize(fem->u, &N));
  PetscCall(MatCreate(body->comm, &P));
  PetscCall(MatSetType(P, MATPREALLOCATOR));
  PetscCall(MatSetSizes(P, n, n, N, N));
  PetscCall(MatSetUp(P));
  for (PetscInt c = 0; c < m->cEnd - m->cStart; c++) {
    PetscInt idx[12];
    ElementIndices(fem, c, idx);
    PetscCall(MatSetValues(P, 12, idx, 12, idx, zeros, INSERT_VALUES));
  }
  PetscCall(MatAssemblyBegin(P, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(P, MAT_FINAL_ASSEMBLY));
  PetscCall(DMGetMatType(m->dm, &mtype));
  PetscCall(MatCreate(body->comm, &fem->K));
  PetscCall(MatSetSizes(fem->K, n, n, N, N));
  PetscCall(MatSetBlockSize(fem->K, 3));
  PetscCall(MatSetType(fem->K, mtype));
  PetscCall(MatPreallocatorPreallocate(P, PETSC_TRUE, fem->K));
  PetscCall(MatDestroy(&P));
  PetscCall(MatSetOption(fem->K, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_TRUE));
  PetscCall(MatDuplicate(fem->K, MAT_DO_NOT_COPY_VALUES, &fem->M));
  PetscCall(MatDuplicate(fem->K, MAT_DO_NOT_COPY_VALUES, &fem->A));
  PetscFunctionReturn(0);
}

static PetscBool InBox(const PetscReal box[6], const PetscReal x[3])
{
  for (int d = 0; d < 3; d++)
    if (x[d] < box[d] || x[d] > box[3 + d]) return PETSC_FALSE;
  return PETSC_TRUE;
}

static PetscErrorCode SetUp_FEM(FCBody body)
{
  FEM         *fem = (FEM *)body->data;
  FCMesh      *m   = &fem->mesh;
  PetscSection s, gs;
  PetscInt     nv, nc, nfixed = 0;
  PetscReal    R[9], c0[3], V, J[9];

  PetscFunctionBegin;
  PetscCall(FCMeshLoad(body->comm, body->prefix, body->name, m));
  nv = m->vEnd - m->vStart;
  nc = m->cEnd - m->cStart;
  PetscCall(FCMeshCheckCells(m, body->name));
  PetscCall(FCMaterialCreate(fem->material, fem->young, fem->poisson, &fem->mat));

  /* placement: rotate about the centre (default: the mesh centroid), then translate */
  PetscCall(FCMeshComputeMassProperties(m, &V, c0, J));
  if (!body->center_set)
    for (int d = 0; d < 3; d++) body->center[d] = c0[d];
  FCBodyPlacementRotation(body, R);
  PetscCall(FCMeshTransform(m, body->center, R, body->translate));
  for (int d = 0; d < 3; d++) body->center[d] += body->translate[d];

  /* section: 3 DOFs per vertex, fixed vertices constrained out */
  PetscCall(PetscMalloc3(nv, &fem->ldof, nv, &fem->gdof, nv, &fem->fixed));
  PetscCall(PetscSectionCreate(body->comm, &s));
  PetscCall(PetscSectionSetNumFields(s, 1));
  PetscCall(PetscSectionSetFieldName(s, 0, "displacement"));
  PetscCall(PetscSectionSetFieldComponents(s, 0, 3));
  /* chart from 0: PETSc 3.18's PetscSectionSetConstraintIndices() indexes by point, not by
     point - pStart, and rejects valid indices when the chart does not start at 0 */
  PetscCall(PetscSectionSetChart(s, 0, m->vEnd));
  for (PetscInt v = 0; v < nv; v++) {
    fem->fixed[v] = fem->has_fixed_box && InBox(fem->fixed_box, &m->X[3 * v]) ? PETSC_TRUE : PETSC_FALSE;
    PetscCall(PetscSectionSetDof(s, m->vStart + v, 3));
    PetscCall(PetscSectionSetFieldDof(s, m->vStart + v, 0, 3));
    if (fem->fixed[v]) {
      PetscCall(PetscSectionSetConstraintDof(s, m->vStart + v, 3));
      PetscCall(PetscSectionSetFieldConstraintDof(s, m->vStart + v, 0, 3));
      if (m->owned[v]) nfixed++;
    }
  }
  PetscCall(PetscSectionSetUp(s));
  for (PetscInt v = 0; v < nv; v++)
    if (fem->fixed[v]) {
      const PetscInt all[3] = {0, 1, 2};
      PetscCall(PetscSectionSetConstraintIndices(s, m->vStart + v, all));
      PetscCall(PetscSectionSetFieldConstraintIndices(s, m->vStart + v, 0, all));
    }
  PetscCall(DMSetLocalSection(m->dm, s));
  PetscCall(PetscSectionDestroy(&s));
  PetscCall(DMGetGlobalSection(m->dm, &gs));
  PetscCall(DMGetLocalSection(m->dm, &s));
  for (PetscInt v = 0; v < nv; v++) {
    PetscInt off, goff, gd;
    PetscCall(PetscSectionGetOffset(s, m->vStart + v, &off));
    PetscCall(PetscSectionGetOffset(gs, m->vStart + v, &goff));
    PetscCall(PetscSectionGetDof(gs, m->vStart + v, &gd));
    if (gd < 0) goff = -(goff + 1);
    fem->ldof[v] = off;
    fem->gdof[v] = fem->fixed[v] ? -1 : goff;
  }
  PetscCall(MPIU_Allreduce(&nfixed, &fem->nfixed, 1, MPIU_INT, MPI_SUM, body->comm));

  /* reference data of the cells */
  PetscCall(PetscMalloc2(9 * nc, &fem->Dminv, nc, &fem->vol));
  for (PetscInt c = 0; c < nc; c++) {
    PetscReal X[12], x[12];
    GatherElement(fem, c, NULL, X, x);
    PetscCall(FCTetReference(X, &fem->Dminv[9 * c], &fem->vol[c]));
  }

  /* state, work vectors, operators */
  PetscCall(DMCreateGlobalVector(m->dm, &fem->u));
  PetscCall(PetscObjectSetName((PetscObject)fem->u, "displacement"));
  PetscCall(VecDuplicate(fem->u, &fem->v));
  PetscCall(VecDuplicate(fem->u, &fem->dv));
  PetscCall(VecDuplicate(fem->u, &fem->b));
  PetscCall(VecDuplicate(fem->u, &fem->fint));
  PetscCall(VecDuplicate(fem->u, &fem->fgrav));
  PetscCall(VecDuplicate(fem->u, &fem->work));
  PetscCall(DMCreateLocalVector(m->dm, &fem->uloc));
  PetscCall(VecDuplicate(fem->uloc, &fem->floc));
  PetscCall(VecZeroEntries(fem->uloc));
  PetscCall(CreateOperators(body));
  PetscCall(PetscObjectSetName((PetscObject)fem->A, "A"));
  {
    PetscInt nglobal;
    PetscCall(VecGetSize(fem->u, &nglobal));
    PetscCheck(nglobal > 0, body->comm, PETSC_ERR_USER_INPUT,
               "Every vertex of body '%s' is fixed by -%sfixed_box: nothing to simulate", body->name, body->prefix);
  }

  /* initial velocity v = v0 + omega x (X - c) on the free vertices */
  {
    PetscScalar *va;
    PetscInt     lo;
    PetscCall(VecGetOwnershipRange(fem->v, &lo, NULL));
    PetscCall(VecGetArray(fem->v, &va));
    for (PetscInt v = 0; v < nv; v++) {
      PetscReal r[3], w[3];
      if (!m->owned[v] || fem->fixed[v]) continue;
      for (int d = 0; d < 3; d++) r[d] = m->X[3 * v + d] - body->center[d];
      FCCross(body->angular_velocity, r, w);
      for (int d = 0; d < 3; d++) va[fem->gdof[v] - lo + d] = body->velocity[d] + w[d];
    }
    PetscCall(VecRestoreArray(fem->v, &va));
  }

  /* solver: preonly + Cholesky (MUMPS) unless the options say otherwise */
  PetscCall(KSPCreate(body->comm, &fem->ksp));
  PetscCall(KSPSetOptionsPrefix(fem->ksp, body->prefix));
  PetscCall(KSPSetType(fem->ksp, KSPPREONLY));
  {
    PC pc;
    PetscCall(KSPGetPC(fem->ksp, &pc));
    PetscCall(PCSetType(pc, PCCHOLESKY));
    PetscCall(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS));
  }
  PetscCall(KSPSetFromOptions(fem->ksp));

  PetscCall(AssembleMass(body));
  PetscCall(AssembleElastic(body, fem->u, fem->fint, fem->K));
  PetscCall(FormAndFactorA(body));
  PetscCall(FCMeshCreateVisual(m, &body->visual));
  PetscCall(FCBodyFEMGetReferenceCoordinates(body, &fem->Xg));
  /* boundary: owned vertices (candidate contact points) and outward triangles (mesh.c) */
  PetscCall(FCMeshGetBoundary(m, &fem->nbv, &fem->bv, &fem->ntri, &fem->triv));
  PetscCall(PetscMalloc1(fem->ntri + 1, &fem->tri));
  PetscCall(DMCreateLocalVector(m->dm, &fem->vloc));
  PetscCall(VecDuplicate(fem->vloc, &fem->dvloc));
  PetscCall(PetscMalloc4(3 * fem->nbv + 1, &fem->bx0, 3 * fem->nbv + 1, &fem->bxf, 3 * fem->nbv + 1, &fem->bkey,
                         fem->nbv + 1, &fem->bprox));
  PetscFunctionReturn(0);
}

/* Owned boundary vertices: positions at the start of the step and after the free motion
   x_free = X + u + h (v + dv_free) */
static PetscErrorCode ContactPoints_FEM(FCBody body, PetscInt *n, FCProximity **prox, PetscReal **x0, PetscReal **xf,
                                        PetscReal **key)
{
  FEM               *fem = (FEM *)body->data;
  FCMesh            *m   = &fem->mesh;
  const PetscScalar *u, *v, *dv;
  PetscInt           lo;

  PetscFunctionBegin;
  PetscCall(VecGetOwnershipRange(fem->u, &lo, NULL));
  PetscCall(VecGetArrayRead(fem->u, &u));
  PetscCall(VecGetArrayRead(fem->v, &v));
  PetscCall(VecGetArrayRead(fem->dv, &dv));
  for (PetscInt i = 0; i < fem->nbv; i++) {
    PetscInt     vtx = fem->bv[i], g = fem->gdof[vtx];
    FCProximity *p = &fem->bprox[i];
    PetscCall(PetscMemzero(p, sizeof(*p)));
    p->nv      = 1;
    p->gdof[0] = g;
    p->w[0]    = 1.0;
    for (int d = 0; d < 3; d++) {
      PetscReal X          = m->X[3 * vtx + d];
      p->r[d]              = X;
      p->X[0][d]           = X;
      fem->bkey[3 * i + d] = X;
      fem->bx0[3 * i + d]  = X + (g < 0 ? 0.0 : PetscRealPart(u[g - lo + d]));
      fem->bxf[3 * i + d] =
          fem->bx0[3 * i + d] + (g < 0 ? 0.0 : body->h * PetscRealPart(v[g - lo + d] + dv[g - lo + d]));
    }
  }
  PetscCall(VecRestoreArrayRead(fem->u, &u));
  PetscCall(VecRestoreArrayRead(fem->v, &v));
  PetscCall(VecRestoreArrayRead(fem->dv, &dv));
  *n    = fem->nbv;
  *prox = fem->bprox;
  *x0   = fem->bx0;
  *xf   = fem->bxf;
  *key  = fem->bkey;
  PetscFunctionReturn(0);
}

/* Boundary triangles held by this rank with their positions at the start of the step and
   after the free motion (ghost vertices included, through the local vectors) */
static PetscErrorCode SurfaceTriangles_FEM(FCBody body, PetscInt *n, FCSurfaceTriangle **tri)
{
  FEM               *fem = (FEM *)body->data;
  FCMesh            *m   = &fem->mesh;
  const PetscScalar *u, *v, *dv;

  PetscFunctionBegin;
  PetscCall(DMGlobalToLocal(m->dm, fem->u, INSERT_VALUES, fem->uloc));
  PetscCall(DMGlobalToLocal(m->dm, fem->v, INSERT_VALUES, fem->vloc));
  PetscCall(DMGlobalToLocal(m->dm, fem->dv, INSERT_VALUES, fem->dvloc));
  PetscCall(VecGetArrayRead(fem->uloc, &u));
  PetscCall(VecGetArrayRead(fem->vloc, &v));
  PetscCall(VecGetArrayRead(fem->dvloc, &dv));
  for (PetscInt t = 0; t < fem->ntri; t++) {
    FCSurfaceTriangle *T = &fem->tri[t];
    for (int a = 0; a < 3; a++) {
      PetscInt vtx = fem->triv[3 * t + a], o = fem->ldof[vtx];
      T->gdof[a] = fem->gdof[vtx];
      for (int d = 0; d < 3; d++) {
        PetscReal X = m->X[3 * vtx + d], uu = fem->fixed[vtx] ? 0.0 : PetscRealPart(u[o + d]);
        T->X[a][d]  = X;
        T->x0[a][d] = X + uu;
        T->xf[a][d] = T->x0[a][d] + (fem->fixed[vtx] ? 0.0 : body->h * PetscRealPart(v[o + d] + dv[o + d]));
      }
    }
  }
  PetscCall(VecRestoreArrayRead(fem->uloc, &u));
  PetscCall(VecRestoreArrayRead(fem->vloc, &v));
  PetscCall(VecRestoreArrayRead(fem->dvloc, &dv));
  *n   = fem->ntri;
  *tri = fem->tri;
  PetscFunctionReturn(0);
}

/* x += sum of w_k x_k over the vertices of p: owned vertices at the current state X + u, or at
   the trial state X + u + h (v + dv); fixed vertices (never moving, X kept in the proximity) are
   added by rank 0 only, so that a sum over the ranks counts every vertex once */
static PetscErrorCode AddVertexPositions(FCBody body, const FCProximity *p, PetscBool trial, PetscReal x[3])
{
  FEM               *fem = (FEM *)body->data;
  const PetscScalar *u, *X, *v = NULL, *dv = NULL;
  PetscInt           lo, hi;
  PetscMPIInt        rank;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_rank(body->comm, &rank));
  PetscCall(VecGetOwnershipRange(fem->u, &lo, &hi));
  PetscCall(VecGetArrayRead(fem->u, &u));
  PetscCall(VecGetArrayRead(fem->Xg, &X));
  if (trial) {
    PetscCall(VecGetArrayRead(fem->v, &v));
    PetscCall(VecGetArrayRead(fem->dv, &dv));
  }
  for (PetscInt k = 0; k < p->nv; k++) {
    PetscInt g = p->gdof[k];
    if (g < 0) {
      if (!rank)
        for (int d = 0; d < 3; d++) x[d] += p->w[k] * p->X[k][d];
      continue;
    }
    if (g < lo || g >= hi) continue;
    for (int d = 0; d < 3; d++)
      x[d] += p->w[k] *
              PetscRealPart(X[g - lo + d] + u[g - lo + d] + (trial ? body->h * (v[g - lo + d] + dv[g - lo + d]) : 0.0));
  }
  PetscCall(VecRestoreArrayRead(fem->u, &u));
  PetscCall(VecRestoreArrayRead(fem->Xg, &X));
  if (trial) {
    PetscCall(VecRestoreArrayRead(fem->v, &v));
    PetscCall(VecRestoreArrayRead(fem->dv, &dv));
  }
  PetscFunctionReturn(0);
}

static PetscErrorCode PartialPosition_FEM(FCBody body, const FCProximity *p, PetscReal x[3])
{
  PetscFunctionBegin;
  PetscCall(AddVertexPositions(body, p, PETSC_FALSE, x));
  PetscFunctionReturn(0);
}

/* G(q) at the trial state of a recursive scheme */
static PetscErrorCode TrialPosition_FEM(FCBody body, const FCProximity *p, PetscReal x[3])
{
  PetscFunctionBegin;
  PetscCall(AddVertexPositions(body, p, PETSC_TRUE, x));
  PetscFunctionReturn(0);
}

static PetscErrorCode SaveFree_FEM(FCBody body)
{
  FEM *fem = (FEM *)body->data;
  PetscFunctionBegin;
  if (!fem->dvfree) PetscCall(VecDuplicate(fem->dv, &fem->dvfree));
  PetscCall(VecCopy(fem->dv, fem->dvfree));
  PetscFunctionReturn(0);
}

static PetscErrorCode RestoreFree_FEM(FCBody body)
{
  FEM *fem = (FEM *)body->data;
  PetscFunctionBegin;
  PetscCall(VecCopy(fem->dvfree, fem->dv));
  PetscFunctionReturn(0);
}

/* Current position of a proximity point whose vertices this rank owns */
static PetscErrorCode ProximityPosition_FEM(FCBody body, const FCProximity *p, PetscInt when, PetscReal x[3])
{
  FEM               *fem = (FEM *)body->data;
  const PetscScalar *u, *X;
  PetscInt           lo, hi;

  PetscFunctionBegin;
  PetscCheck(when == FC_AT_NOW, body->comm, PETSC_ERR_SUP,
             "FE proximity positions are evaluated at the current state only");
  PetscCall(VecGetOwnershipRange(fem->u, &lo, &hi));
  PetscCall(VecGetArrayRead(fem->u, &u));
  PetscCall(VecGetArrayRead(fem->Xg, &X));
  for (int d = 0; d < 3; d++) x[d] = 0.0;
  for (PetscInt k = 0; k < p->nv; k++) {
    PetscInt g = p->gdof[k];
    if (g < 0) { /* fixed vertex: it stays at its reference position */
      for (int d = 0; d < 3; d++) x[d] += p->w[k] * p->X[k][d];
      continue;
    }
    PetscCheck(g >= lo && g < hi, PETSC_COMM_SELF, PETSC_ERR_PLIB, "Proximity vertex not owned by this rank");
    for (int d = 0; d < 3; d++) x[d] += p->w[k] * PetscRealPart(X[g - lo + d] + u[g - lo + d]);
  }
  PetscCall(VecRestoreArrayRead(fem->u, &u));
  PetscCall(VecRestoreArrayRead(fem->Xg, &X));
  PetscFunctionReturn(0);
}

/* Free motion, eq. 5: A dv_free = b = h (f_g - f_int) - M (h alpha v) - K ((h beta + h^2) v) */
static PetscErrorCode FreeMotion_FEM(FCBody body, PetscReal t)
{
  FEM      *fem = (FEM *)body->data;
  PetscReal h   = body->h;

  PetscFunctionBegin;
  if (!fem->Acurrent) { /* co-rotational: K and f_int at q_t; A too every refactor_every steps */
    PetscCall(AssembleElastic(body, fem->u, fem->fint, fem->K));
    if (fem->factor_age >= fem->refactor_every) PetscCall(FormAndFactorA(body));
    fem->Acurrent = PETSC_TRUE;
  }
  PetscCall(FCPhaseBegin(FC_PHASE_FREE_MOTION));
  if (fem->mat->linear) PetscCall(MatMult(fem->K, fem->u, fem->fint)); /* f_int = K u */
  if (body->gravity[0] != 0.0 || body->gravity[1] != 0.0 || body->gravity[2] != 0.0)
    PetscCall(VecAXPBYPCZ(fem->b, h, -h, 0.0, fem->fgrav, fem->fint));
  else { /* no gravity work without gravity */
    PetscCall(VecCopy(fem->fint, fem->b));
    PetscCall(VecScale(fem->b, -h));
  }
  if (fem->alpha != 0.0) {
    PetscCall(MatMult(fem->M, fem->v, fem->work));
    PetscCall(VecAXPY(fem->b, -h * fem->alpha, fem->work));
  }
  PetscCall(MatMult(fem->K, fem->v, fem->work));
  PetscCall(VecAXPY(fem->b, -(h * fem->beta + h * h), fem->work));
  PetscCall(KSPSolve(fem->ksp, fem->b, fem->dv));
  {
    KSPConvergedReason reason;
    PetscCall(KSPGetConvergedReason(fem->ksp, &reason));
    PetscCheck(reason >= 0, body->comm, PETSC_ERR_CONV_FAILED, "Free-motion solve of body '%s' failed at t = %g: %s",
               body->name, (double)t, KSPConvergedReasons[reason]);
  }
  PetscCall(FCPhaseEnd(FC_PHASE_FREE_MOTION));
  PetscFunctionReturn(0);
}

/* eq. 2: v_{t+h} = v_t + dv, u_{t+h} = u_t + h v_{t+h} */
static PetscErrorCode Integrate_FEM(FCBody body, PetscReal t)
{
  FEM *fem = (FEM *)body->data;

  PetscFunctionBegin;
  PetscCall(VecAXPY(fem->v, 1.0, fem->dv));
  PetscCall(VecAXPY(fem->u, body->h, fem->v));
  if (!fem->mat->linear) fem->Acurrent = PETSC_FALSE;
  fem->factor_age++;
  PetscFunctionReturn(0);
}

/* Mass-weighted centroid: for P1, int x dV over a tet is V times the mean of its vertices */
static PetscErrorCode GetCentroid_FEM(FCBody body, PetscReal c[3])
{
  FEM               *fem = (FEM *)body->data;
  FCMesh            *m   = &fem->mesh;
  const PetscScalar *ul;
  PetscReal          acc[4] = {0, 0, 0, 0};

  PetscFunctionBegin;
  PetscCall(DMGlobalToLocal(m->dm, fem->u, INSERT_VALUES, fem->uloc));
  PetscCall(VecGetArrayRead(fem->uloc, &ul));
  for (PetscInt e = 0; e < m->cEnd - m->cStart; e++) {
    PetscReal X[12], x[12];
    GatherElement(fem, e, ul, X, x);
    acc[3] += fem->vol[e];
    for (int d = 0; d < 3; d++) acc[d] += fem->vol[e] * 0.25 * (x[d] + x[3 + d] + x[6 + d] + x[9 + d]);
  }
  PetscCall(VecRestoreArrayRead(fem->uloc, &ul));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, acc, 4, MPIU_REAL, MPIU_SUM, body->comm));
  for (int d = 0; d < 3; d++) c[d] = acc[d] / acc[3];
  PetscFunctionReturn(0);
}

/* Kinetic 1/2 v^T M v, elastic (sum of element energies), gravity -m g . x_centroid */
static PetscErrorCode GetEnergy_FEM(FCBody body, FCEnergy *E)
{
  FEM               *fem = (FEM *)body->data;
  FCMesh            *m   = &fem->mesh;
  const PetscScalar *ul;
  PetscReal          c[3];
  PetscScalar        vMv;

  PetscFunctionBegin;
  PetscCall(MatMult(fem->M, fem->v, fem->work));
  PetscCall(VecDot(fem->v, fem->work, &vMv));
  E->kinetic = 0.5 * PetscRealPart(vMv);
  E->elastic = 0.0;
  PetscCall(DMGlobalToLocal(m->dm, fem->u, INSERT_VALUES, fem->uloc));
  PetscCall(VecGetArrayRead(fem->uloc, &ul));
  for (PetscInt e = 0; e < m->cEnd - m->cStart; e++) {
    PetscReal X[12], x[12], Ee;
    GatherElement(fem, e, ul, X, x);
    PetscCall((*fem->mat->energy)(fem->mat, x, X, &fem->Dminv[9 * e], fem->vol[e], &Ee));
    E->elastic += Ee;
  }
  PetscCall(VecRestoreArrayRead(fem->uloc, &ul));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &E->elastic, 1, MPIU_REAL, MPIU_SUM, body->comm));
  PetscCall(GetCentroid_FEM(body, c));
  E->gravity = -fem->mass * FCDot(body->gravity, c);
  PetscFunctionReturn(0);
}

static PetscErrorCode GetVisualPositions_FEM(FCBody body, PetscReal x[])
{
  FEM               *fem = (FEM *)body->data;
  FCMesh            *m   = &fem->mesh;
  const PetscScalar *ul;

  PetscFunctionBegin;
  PetscCall(DMGlobalToLocal(m->dm, fem->u, INSERT_VALUES, fem->uloc));
  PetscCall(VecGetArrayRead(fem->uloc, &ul));
  for (PetscInt i = 0; i < body->visual.nv; i++) {
    PetscInt v = m->visVert[i];
    for (int d = 0; d < 3; d++)
      x[3 * i + d] = m->X[3 * v + d] + (fem->fixed[v] ? 0.0 : PetscRealPart(ul[fem->ldof[v] + d]));
  }
  PetscCall(VecRestoreArrayRead(fem->uloc, &ul));
  PetscFunctionReturn(0);
}

/* Restart state: per owned vertex in the visual (global) order, u and v (0 on fixed vertices) */
static PetscErrorCode GetState_FEM(FCBody body, PetscReal s[])
{
  FEM               *fem = (FEM *)body->data;
  FCMesh            *m   = &fem->mesh;
  const PetscScalar *u, *v;
  PetscInt           lo;

  PetscFunctionBegin;
  PetscCall(VecGetOwnershipRange(fem->u, &lo, NULL));
  PetscCall(VecGetArrayRead(fem->u, &u));
  PetscCall(VecGetArrayRead(fem->v, &v));
  for (PetscInt i = 0; i < body->visual.nv; i++) {
    PetscInt vx = m->visVert[i];
    for (int d = 0; d < 3; d++) {
      s[6 * i + d]     = fem->fixed[vx] ? 0.0 : PetscRealPart(u[fem->gdof[vx] - lo + d]);
      s[6 * i + 3 + d] = fem->fixed[vx] ? 0.0 : PetscRealPart(v[fem->gdof[vx] - lo + d]);
    }
  }
  PetscCall(VecRestoreArrayRead(fem->u, &u));
  PetscCall(VecRestoreArrayRead(fem->v, &v));
  PetscFunctionReturn(0);
}

/* The state of a restart: A of a co-rotational body is reassembled and factored at the next step,
   as it would have been (-refactor_every 1; with k > 1 the factor's age restarts) */
static PetscErrorCode SetState_FEM(FCBody body, const PetscReal s[])
{
  FEM         *fem = (FEM *)body->data;
  FCMesh      *m   = &fem->mesh;
  PetscScalar *u, *v;
  PetscInt     lo;

  PetscFunctionBegin;
  PetscCall(VecGetOwnershipRange(fem->u, &lo, NULL));
  PetscCall(VecGetArray(fem->u, &u));
  PetscCall(VecGetArray(fem->v, &v));
  for (PetscInt i = 0; i < body->visual.nv; i++) {
    PetscInt vx = m->visVert[i];
    if (fem->fixed[vx]) continue;
    for (int d = 0; d < 3; d++) {
      u[fem->gdof[vx] - lo + d] = s[6 * i + d];
      v[fem->gdof[vx] - lo + d] = s[6 * i + 3 + d];
    }
  }
  PetscCall(VecRestoreArray(fem->u, &u));
  PetscCall(VecRestoreArray(fem->v, &v));
  if (!fem->mat->linear) {
    fem->Acurrent   = PETSC_FALSE;
    fem->factor_age = fem->refactor_every;
  }
  PetscFunctionReturn(0);
}

static PetscErrorCode CheckState_FEM(FCBody body, PetscInt step)
{
  FEM      *fem = (FEM *)body->data;
  PetscReal nu, nv;

  PetscFunctionBegin;
  PetscCall(VecNorm(fem->u, NORM_INFINITY, &nu));
  PetscCall(VecNorm(fem->v, NORM_INFINITY, &nv));
  PetscCheck(!PetscIsInfOrNanReal(nu) && !PetscIsInfOrNanReal(nv), body->comm, PETSC_ERR_FP,
             "Body '%s' diverged at step %" PetscInt_FMT
             ": its displacement or velocity is NaN or Inf (time step too large?)",
             body->name, step);
  PetscFunctionReturn(0);
}

static PetscErrorCode Destroy_FEM(FCBody body)
{
  FEM *fem = (FEM *)body->data;

  PetscFunctionBegin;
  PetscCall(KSPDestroy(&fem->ksp));
  PetscCall(FCFEMComplianceDestroy(body));
  PetscCall(MatDestroy(&fem->M));
  PetscCall(MatDestroy(&fem->K));
  PetscCall(MatDestroy(&fem->A));
  PetscCall(VecDestroy(&fem->u));
  PetscCall(VecDestroy(&fem->v));
  PetscCall(VecDestroy(&fem->dv));
  PetscCall(VecDestroy(&fem->b));
  PetscCall(VecDestroy(&fem->fint));
  PetscCall(VecDestroy(&fem->fgrav));
  PetscCall(VecDestroy(&fem->work));
  PetscCall(VecDestroy(&fem->uloc));
  PetscCall(VecDestroy(&fem->floc));
  PetscCall(PetscFree3(fem->ldof, fem->gdof, fem->fixed));
  PetscCall(PetscFree2(fem->Dminv, fem->vol));
  PetscCall(PetscFree(fem->bv));
  PetscCall(PetscFree(fem->triv));
  PetscCall(PetscFree(fem->tri));
  PetscCall(VecDestroy(&fem->vloc));
  PetscCall(VecDestroy(&fem->dvloc));
  PetscCall(VecDestroy(&fem->dvfree));
  PetscCall(PetscFree4(fem->bx0, fem->bxf, fem->bkey, fem->bprox));
  PetscCall(VecDestroy(&fem->Xg));
  PetscCall(FCMaterialDestroy(&fem->mat));
  PetscCall(FCMeshDestroy(&fem->mesh));
  PetscCall(PetscFree(body->data));
  PetscFunctionReturn(0);
}

PetscErrorCode FCBodyCreate_FEM(FCBody body)
{
  FEM *fem = NULL;

  PetscFunctionBegin;
  PetscCall(PetscNew(&fem));
  PetscCall(PetscStrncpy(fem->material, "linear", sizeof(fem->material)));
  PetscCall(PetscStrncpy(fem->compliance, "none", sizeof(fem->compliance))); /* set by the scene for paired bodies */
  fem->poisson                 = 0.3;
  fem->refactor_every          = 1;
  fem->rcomm                   = MPI_COMM_NULL;
  fem->rmemory                 = PETSC_MAX_REAL;
  fem->iblock                  = 256;
  body->data                   = fem;
  body->ops.setfromoptions     = SetFromOptions_FEM;
  body->ops.setup              = SetUp_FEM;
  body->ops.freemotion         = FreeMotion_FEM;
  body->ops.integrate          = Integrate_FEM;
  body->ops.getcentroid        = GetCentroid_FEM;
  body->ops.getenergy          = GetEnergy_FEM;
  body->ops.getvisualpositions = GetVisualPositions_FEM;
  body->ops.checkstate         = CheckState_FEM;
  body->ops.getstate           = GetState_FEM;
  body->ops.setstate           = SetState_FEM;
  body->ops.destroy            = Destroy_FEM;
  body->ops.contactpoints      = ContactPoints_FEM;
  body->ops.proximityposition  = ProximityPosition_FEM;
  body->ops.addcompliance      = FCFEMAddCompliance;
  body->ops.applycorrection    = FCFEMApplyCorrection;
  body->ops.surfacetriangles   = SurfaceTriangles_FEM;
  body->ops.partialposition    = PartialPosition_FEM;
  body->ops.savefree           = SaveFree_FEM;
  body->ops.restorefree        = RestoreFree_FEM;
  body->ops.trialposition      = TrialPosition_FEM;
  PetscFunctionReturn(0);
}

/* ---- accessors for tests and tools ---- */
PetscErrorCode FCFEMGet(FCBody body, FEM **fem)
{
  PetscBool isfem;

  PetscFunctionBegin;
  PetscCall(PetscStrcmp(body->type, FCBODYFEM, &isfem));
  PetscCheck(isfem, body->comm, PETSC_ERR_ARG_WRONG, "Body '%s' is not an FE body", body->name);
  *fem = (FEM *)body->data;
  PetscFunctionReturn(0);
}

PetscErrorCode FCBodyFEMGetDM(FCBody body, DM *dm)
{
  FEM *fem = NULL;
  PetscFunctionBegin;
  PetscCall(FCFEMGet(body, &fem));
  *dm = fem->mesh.dm;
  PetscFunctionReturn(0);
}

PetscErrorCode FCBodyFEMGetState(FCBody body, Vec *u, Vec *v)
{
  FEM *fem = NULL;
  PetscFunctionBegin;
  PetscCall(FCFEMGet(body, &fem));
  if (u) *u = fem->u;
  if (v) *v = fem->v;
  PetscFunctionReturn(0);
}

PetscErrorCode FCBodyFEMComputeElasticForce(FCBody body, Vec u, Vec f)
{
  FEM *fem = NULL;
  PetscFunctionBegin;
  PetscCall(FCFEMGet(body, &fem));
  PetscCall(AssembleElastic(body, u, f, NULL));
  PetscFunctionReturn(0);
}

/* Placed reference coordinates in the layout of the global state vectors */
PetscErrorCode FCBodyFEMGetReferenceCoordinates(FCBody body, Vec *X)
{
  FEM         *fem;
  PetscScalar *xa;
  PetscInt     lo;

  PetscFunctionBegin;
  PetscCall(FCFEMGet(body, &fem));
  PetscCall(VecDuplicate(fem->u, X));
  PetscCall(VecGetOwnershipRange(*X, &lo, NULL));
  PetscCall(VecGetArray(*X, &xa));
  for (PetscInt v = 0; v < fem->mesh.vEnd - fem->mesh.vStart; v++)
    if (fem->mesh.owned[v] && !fem->fixed[v])
      for (int d = 0; d < 3; d++) xa[fem->gdof[v] - lo + d] = fem->mesh.X[3 * v + d];
  PetscCall(VecRestoreArray(*X, &xa));
  PetscFunctionReturn(0);
}

PetscErrorCode FCBodyFEMGetCounters(FCBody body, PetscInt *nassembly, PetscInt *nfactorization)
{
  FEM *fem = NULL;
  PetscFunctionBegin;
  PetscCall(FCFEMGet(body, &fem));
  if (nassembly) *nassembly = fem->nassembly;
  if (nfactorization) *nfactorization = fem->nfactor;
  PetscFunctionReturn(0);
}
