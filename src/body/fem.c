/* Deformable body: P1 tetrahedra, linear or co-rotational elasticity, lumped or consistent
   mass, Rayleigh damping B = alpha M + beta K, linearized backward Euler (eq. 5):
       A dv = b,  A = M + h B + h^2 K,  b = h (f_ext - f_int(q)) - h B v - h^2 K v,
   then v += dv, u += h v (eq. 2). Fixed vertices are constrained out of the section, so A is
   symmetric positive definite on the free DOFs and is factored by the body's KSP (default
   preonly + Cholesky + MUMPS). A linear material's A is assembled and factored once per run.

   Options (prefix <body>_): -dm_plex_filename and every -dm_* option, -material, -young, -poisson,
   -density, -mass_type, -rayleigh_mass, -rayleigh_stiffness, -fixed_box, -inverted, and for a
   co-rotational body -factorization (and with reuse -ksp_rtol, -ksp_max_it, -refactor_rotation,
   -refactor_iterations, -refactor_every), -rotation, -assembly; the solver's -ksp_*, -pc_*: each
   described by its help string below and in docs/options.md. */
#include "femimpl.h"

static PetscErrorCode SetFromOptions_FEM(FCBody body)
{
  FEM        *fem = (FEM *)body->data;
  PetscBool   set, setE, setRho;
  const char *mass[] = {"consistent", "lumped"};
  PetscInt    lumped = fem->lumped ? 1 : 0;

  PetscFunctionBegin;
  PetscOptionsBegin(body->comm, body->prefix, "FE body options", "FCBody");
  PetscCall(PetscOptionsFList("-material", "Material model", NULL, FCMaterialList, fem->material, fem->material,
                              sizeof(fem->material), &set));
  PetscCall(FCOptionsReal(PetscOptionsObject, "-young", "Young's modulus (Pa)", &fem->young, &setE));
  PetscCall(FCOptionsReal(PetscOptionsObject, "-poisson", "Poisson's ratio", &fem->poisson, NULL));
  PetscCall(FCOptionsReal(PetscOptionsObject, "-density", "Density (kg/m^3)", &body->density, &setRho));
  PetscCall(
      FCOptionsEList(PetscOptionsObject, "-mass_type", "Mass matrix: consistent or lumped", mass, 2, &lumped, NULL));
  fem->lumped = lumped == 1 ? PETSC_TRUE : PETSC_FALSE;
  PetscCall(FCOptionsReal(PetscOptionsObject, "-rayleigh_mass", "Rayleigh damping alpha (B = alpha M + beta K)",
                          &fem->alpha, NULL));
  PetscCall(FCOptionsReal(PetscOptionsObject, "-rayleigh_stiffness", "Rayleigh damping beta (B = alpha M + beta K)",
                          &fem->beta, NULL));
  {
    PetscInt n = 0;
    PetscCall(FCOptionsRealList(PetscOptionsObject, "-fixed_box",
                                "Fix the vertices inside xmin,ymin,zmin,xmax,ymax,zmax (one or more boxes)",
                                6 * FC_MAX_FIXED_BOXES + 1, fem->fixed_box, &n, &fem->has_fixed_box));
    PetscCheck(
        !fem->has_fixed_box || (n > 0 && n % 6 == 0 && n <= 6 * FC_MAX_FIXED_BOXES), body->comm, PETSC_ERR_USER_INPUT,
        "Option -%sfixed_box needs 6 comma-separated numbers per box (xmin,ymin,zmin,xmax,ymax,zmax), at most %d "
        "boxes; got %" PetscInt_FMT " numbers",
        body->prefix, FC_MAX_FIXED_BOXES, n);
    fem->nfixed_box = n / 6;
  }
  PetscCall(FCFEMBCSetFromOptions(PetscOptionsObject, body));
  PetscCall(FCFEMNewtonSetFromOptions(PetscOptionsObject, body));
  PetscCall(FCFEMNonlinearSetFromOptions(PetscOptionsObject, body));
  { /* the default by material: a co-rotational element turned inside out gets a force that turns it
       back (the invertible-FE rotation of FCMat3Polar); a hyperelastic energy has no value there, and
       linear elasticity no force against it */
    const char *inv[] = {"error", "allow"};
    PetscInt    a     = strcmp(fem->material, "corotational") ? 0 : 1;
    PetscCall(FCOptionsEList(PetscOptionsObject, "-inverted",
                             "An element turned inside out (J = det F <= 0) at the end of a step: error (stop) or "
                             "allow (run on); default allow for corotational, error for the other materials",
                             inv, 2, &a, NULL));
    fem->allow_inverted = a == 1 ? PETSC_TRUE : PETSC_FALSE;
  }
  PetscCall(FCFEMScheduleSetFromOptions(PetscOptionsObject, body));
  if (strcmp(fem->material, "linear")) { /* a linear A never changes: nothing to refactor or re-sum */
    const char *how[] = {"values", "coo"}, *rot[] = {"linear", "exact"};
    PetscInt    a = fem->coo ? 1 : 0, r = fem->rotation_exact ? 1 : 0;
    PetscCall(FCOptionsEList(PetscOptionsObject, "-assembly", "How K is summed every step (co-rotational)", how, 2, &a,
                             NULL));
    fem->coo = a == 1 ? PETSC_TRUE : PETSC_FALSE;
    if (!strcmp(fem->material, "corotational")) { /* a hyperelastic body's Newton step turns exactly */
      PetscCall(FCOptionsEList(PetscOptionsObject, "-rotation",
                               "The rotation within a step: exact or linear (co-rotational)", rot, 2, &r, NULL));
      fem->rotation_exact = r == 1 ? PETSC_TRUE : PETSC_FALSE;
    } else
      fem->rotation_exact = PETSC_FALSE;
  } else {
    fem->coo            = PETSC_FALSE;
    fem->rotation_exact = PETSC_FALSE;
    fem->factorization  = FC_FACTORIZATION_EVERY_STEP; /* factored once: nothing to schedule */
  }
  PetscOptionsEnd();
  {
    PetscErrorCode (*create)(FCMaterial) = NULL;
    char option[FC_MAX_NAME + 12];
    PetscCall(PetscSNPrintf(option, sizeof(option), "-%smaterial", body->prefix));
    PetscCall(
        FCRegistryFind(body->comm, FCMaterialList, "material", option, fem->material, (void (**)(void)) & create));
  }
  PetscCheck(setE, body->comm, PETSC_ERR_USER_INPUT, "FE body '%s' needs -%syoung", body->name, body->prefix);
  PetscCheck(setRho, body->comm, PETSC_ERR_USER_INPUT, "FE body '%s' needs -%sdensity", body->name, body->prefix);
  PetscCall(FCCheckPositive(body->comm, body->prefix, "-young", fem->young));
  PetscCall(FCCheckPositive(body->comm, body->prefix, "-density", body->density));
  PetscCheck(fem->poisson > -1.0 && fem->poisson < 0.5, body->comm, PETSC_ERR_USER_INPUT,
             "Option -%spoisson must lie in (-1, 0.5), got %g", body->prefix, (double)fem->poisson);
  PetscCall(FCCheckNonNegative(body->comm, body->prefix, "-rayleigh_mass", fem->alpha));
  PetscCall(FCCheckNonNegative(body->comm, body->prefix, "-rayleigh_stiffness", fem->beta));
  for (PetscInt b = 0; b < fem->nfixed_box; b++)
    for (int d = 0; d < 3; d++)
      PetscCheck(fem->fixed_box[6 * b + d] <= fem->fixed_box[6 * b + 3 + d], body->comm, PETSC_ERR_USER_INPUT,
                 "Option -%sfixed_box, box %" PetscInt_FMT ": min %d (%g) > max (%g)", body->prefix, b, d,
                 (double)fem->fixed_box[6 * b + d], (double)fem->fixed_box[6 * b + 3 + d]);
  PetscFunctionReturn(0);
}

/* The DOF section: 3 DOFs per vertex, the vertices of -<name>_fixed_box constrained out; each vertex's
   local and global DOF (-1: fixed) */
static PetscErrorCode SetUpSection(FCBody body)
{
  FEM         *fem = (FEM *)body->data;
  FCMesh      *m   = &fem->mesh;
  PetscSection s, gs;
  PetscInt     nv = m->vEnd - m->vStart, nfixed = 0;

  PetscFunctionBegin;
  PetscCall(PetscMalloc3(nv, &fem->ldof, nv, &fem->gdof, nv, &fem->fixed));
  PetscCall(FCFEMBCSetUpConstraints(body)); /* fixed[]; first: an error in a region leaves no section to free */
  PetscCall(PetscSectionCreate(body->comm, &s));
  PetscCall(PetscSectionSetNumFields(s, 1));
  PetscCall(PetscSectionSetFieldName(s, 0, "displacement"));
  PetscCall(PetscSectionSetFieldComponents(s, 0, 3));
  /* chart from 0: PETSc 3.18's PetscSectionSetConstraintIndices() indexes by point, not by
     point - pStart, and rejects valid indices when the chart does not start at 0 */
  PetscCall(PetscSectionSetChart(s, 0, m->vEnd));
  for (PetscInt v = 0; v < nv; v++) {
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
    fem->gdof[v] = !fem->fixed[v] ? goff : fem->cons[fem->creg[v]].moves ? -2 - fem->creg[v] : -1;
  }
  PetscCall(MPIU_Allreduce(&nfixed, &fem->nfixed, 1, MPIU_INT, MPI_SUM, body->comm));

  PetscFunctionReturn(0);
}

/* The state, work vectors and operators, and the initial velocity v = v0 + omega x (X - c) of the free
   vertices */
static PetscErrorCode SetUpState(FCBody body)
{
  FEM     *fem = (FEM *)body->data;
  FCMesh  *m   = &fem->mesh;
  PetscInt nv  = m->vEnd - m->vStart;

  PetscFunctionBegin;
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
  PetscCall(FCFEMCreateOperators(body));
  PetscCall(PetscObjectSetName((PetscObject)fem->A, "A"));
  {
    PetscInt nglobal;
    PetscCall(VecGetSize(fem->u, &nglobal));
    PetscCheck(
        nglobal > 0, body->comm, PETSC_ERR_USER_INPUT,
        "Every vertex of body '%s' is constrained (-%sfixed_box, -%sfixed, -%sdisplacement): nothing to simulate",
        body->name, body->prefix, body->prefix, body->prefix);
  }

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

  PetscFunctionReturn(0);
}

/* The body's solver: preonly + Cholesky (MUMPS) unless its options say otherwise */
static PetscErrorCode SetUpSolver(FCBody body)
{
  FEM *fem = (FEM *)body->data;

  PetscFunctionBegin;
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

  PetscFunctionReturn(0);
}

static PetscErrorCode SetUp_FEM(FCBody body)
{
  FEM      *fem = (FEM *)body->data;
  FCMesh   *m   = &fem->mesh;
  PetscInt  nc;
  PetscReal R[9], c0[3], V, J[9];

  PetscFunctionBegin;
  PetscCall(FCMeshLoad(body->comm, body->prefix, body->name, m));
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

  PetscCall(SetUpSection(body));
  if (body->quasistatic) { /* -time_integration static */
    PetscCheck(
        fem->alpha == 0.0 && fem->beta == 0.0, body->comm, PETSC_ERR_USER_INPUT,
        "-time_integration static has no damping: body '%s' cannot take -%srayleigh_mass or -%srayleigh_stiffness",
        body->name, body->prefix, body->prefix);
    PetscCheck(fem->nfixed > 0, body->comm, PETSC_ERR_USER_INPUT,
               "-time_integration static: body '%s' has no fixed or prescribed vertex (-%sfixed, -%sdisplacement), so "
               "nothing holds it in equilibrium (its stiffness is singular)",
               body->name, body->prefix, body->prefix);
  }

  /* reference data of the cells */
  PetscCall(PetscMalloc2(9 * nc, &fem->Dminv, nc, &fem->vol));
  for (PetscInt c = 0; c < nc; c++) {
    PetscReal X[12], x[12];
    FCFEMGatherElement(fem, c, NULL, X, x);
    PetscCall(FCTetReference(X, &fem->Dminv[9 * c], &fem->vol[c]));
  }

  PetscCall(SetUpState(body));
  PetscCall(FCFEMBCSetUp(body));
  PetscCall(SetUpSolver(body));
  PetscCall(FCFEMAssembleMass(body));
  PetscCall(FCFEMAssembleElastic(body, fem->u, fem->fint, fem->K));
  PetscCall(FCFEMFormA(body)); /* factored at first use: by the KSP or by the compliance builder */
  PetscCall(FCFEMCheckDerived(body));
  fem->Acurrent = PETSC_TRUE;
  PetscCall(FCFEMScheduleSetUp(body));  /* reuse: the first step takes its operator at its state */
  PetscCall(FCFEMNewtonSetUp(body));    /* -free_motion newton: its SNES */
  PetscCall(FCFEMNonlinearSetUp(body)); /* -correction nonlinear */
  PetscCall(FCMeshCreateVisual(m, &body->visual));
  PetscCall(FCBodyFEMGetReferenceCoordinates(body, &fem->Xg));
  /* boundary: owned vertices (candidate contact points) and outward triangles (src/mesh/boundary.c) */
  PetscCall(FCMeshGetBoundary(m, &fem->nbv, &fem->bv, &fem->ntri, &fem->triv));
  PetscCall(PetscMalloc1(fem->nbv + 1, &fem->surface));
  for (PetscInt i = 0; i < fem->nbv; i++)
    if (fem->gdof[fem->bv[i]] >= 0) fem->surface[fem->nsurface++] = fem->gdof[fem->bv[i]];
  PetscCall(PetscMalloc1(fem->ntri + 1, &fem->tri));
  PetscCall(DMCreateLocalVector(m->dm, &fem->vloc));
  PetscCall(VecDuplicate(fem->vloc, &fem->dvloc));
  PetscCall(PetscMalloc4(3 * fem->nbv + 1, &fem->bx0, 3 * fem->nbv + 1, &fem->bxf, 3 * fem->nbv + 1, &fem->bkey,
                         fem->nbv + 1, &fem->bprox));
  PetscFunctionReturn(0);
}

/* The body's factorizations of A (a condensed builder's misses included), CG and Newton iterations */
static PetscErrorCode GetSolverCounts_FEM(FCBody body, PetscInt *nfactor, PetscInt *nkrylov, PetscInt *nnewton)
{
  FEM *fem = (FEM *)body->data;

  PetscFunctionBegin;
  *nfactor = fem->nfactor + (fem->comp ? FCComplianceOwnFactorizations(fem->comp) : 0);
  *nkrylov = fem->nkrylov;
  *nnewton = fem->nnewton;
  PetscFunctionReturn(0);
}

static PetscErrorCode GetContactMemory_FEM(FCBody body, PetscReal bytes[3])
{
  FEM      *fem = (FEM *)body->data;
  PetscReal fmax;

  PetscFunctionBegin;
  if (fem->comp) PetscCall(FCComplianceGetMemory(fem->comp, &bytes[0], &bytes[1], &bytes[2], &fmax));
  PetscFunctionReturn(0);
}

static PetscErrorCode Destroy_FEM(FCBody body)
{
  FEM *fem = (FEM *)body->data;

  PetscFunctionBegin;
  PetscCall(FCFEMNewtonDestroy(body));
  PetscCall(FCFEMNonlinearDestroy(body));
  PetscCall(KSPDestroy(&fem->ksp));
  PetscCall(FCFEMScheduleDestroy(body));
  PetscCall(FCComplianceDestroy(&fem->comp));
  PetscCall(PetscFree(fem->surface));
  PetscCall(MatDestroy(&fem->M));
  PetscCall(MatDestroy(&fem->K));
  PetscCall(MatDestroy(&fem->A));
  PetscCall(PetscFree(fem->Kcells));
  PetscCall(VecDestroy(&fem->u));
  PetscCall(VecDestroy(&fem->v));
  PetscCall(VecDestroy(&fem->dv));
  PetscCall(VecDestroy(&fem->b));
  PetscCall(VecDestroy(&fem->fint));
  PetscCall(VecDestroy(&fem->fgrav));
  PetscCall(VecDestroy(&fem->work));
  PetscCall(VecDestroy(&fem->rr));
  PetscCall(VecDestroy(&fem->shift));
  PetscCall(VecDestroy(&fem->uhat));
  PetscCall(VecDestroy(&fem->rvt));
  PetscCall(VecDestroy(&fem->rw));
  PetscCall(VecDestroy(&fem->rcf));
  PetscCall(VecDestroy(&fem->uloc));
  PetscCall(VecDestroy(&fem->floc));
  PetscCall(PetscFree3(fem->ldof, fem->gdof, fem->fixed));
  PetscCall(FCFEMBCDestroy(body));
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
  fem->poisson                 = 0.3;
  fem->factorization           = FC_FACTORIZATION_EVERY_STEP; /* exact; reuse's trade: docs/accuracy.md */
  fem->ksp_rtol                = 1e-8;
  fem->ksp_max_it              = 50;
  fem->refactor_rotation       = 0.2;
  fem->refactor_iterations     = 8;
  fem->refactor_every          = 0;
  fem->refactor_residual       = 0.003;
  fem->coo                     = PETSC_TRUE; /* co-rotational; a linear K is summed once, by values */
  fem->rotation_exact          = PETSC_TRUE; /* co-rotational without fixed vertices */
  fem->correction              = -1;         /* -correction: nonlinear for a Newton free motion */
  fem->penalty                 = 1.0;
  fem->free_motion             = -1;  /* newton for a hyperelastic material, else linearized */
  fem->inverted.min_J          = 1.0; /* the reference state, before any step */
  body->deformable             = PETSC_TRUE;
  body->state_cols             = 6; /* u, v */
  body->state_per_vertex       = PETSC_TRUE;
  body->data                   = fem;
  body->ops.setfromoptions     = SetFromOptions_FEM;
  body->ops.setup              = SetUp_FEM;
  body->ops.freemotion         = FreeMotion_FEM;
  body->ops.integrate          = Integrate_FEM;
  body->ops.getcentroid        = GetCentroid_FEM;
  body->ops.getenergy          = GetEnergy_FEM;
  body->ops.getvisualpositions = GetVisualPositions_FEM;
  body->ops.getvisualfield     = GetVisualField_FEM;
  body->ops.checkstate         = CheckState_FEM;
  body->ops.getstate           = GetState_FEM;
  body->ops.setstate           = SetState_FEM;
  body->ops.destroy            = Destroy_FEM;
  body->ops.contactpoints      = ContactPoints_FEM;
  body->ops.proximityposition  = ProximityPosition_FEM;
  body->ops.setupcontact       = SetUpContact_FEM;
  body->ops.addcompliance      = AddCompliance_FEM;
  body->ops.buildcompliance    = BuildCompliance_FEM;
  body->ops.applycorrection    = ApplyCorrection_FEM;
  body->ops.expectcontacts     = ExpectContacts_FEM;
  body->ops.surfacetriangles   = SurfaceTriangles_FEM;
  body->ops.partialposition    = PartialPosition_FEM;
  body->ops.savefree           = SaveFree_FEM;
  body->ops.restorefree        = RestoreFree_FEM;
  body->ops.trialposition      = TrialPosition_FEM;
  body->ops.getreactions       = GetReactions_FEM;
  body->ops.getregions         = GetRegions_FEM;
  body->ops.settime            = FCFEMBCPoses;
  body->ops.changetimestep     = FCFEMChangeTimeStep;
  body->ops.getexternalwork    = GetExternalWork_FEM;
  body->ops.getsolvercounts    = GetSolverCounts_FEM;
  body->ops.getcontactmemory   = GetContactMemory_FEM;
  body->ops.getinverted        = GetInverted_FEM;
  body->ops.settle             = FCFEMNonlinearSettle;
  body->ops.relinearize        = FCFEMNonlinearRelinearize;
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
  FCValidPointer(body, 1);
  FCValidPointer(dm, 2);
  PetscCall(FCFEMGet(body, &fem));
  *dm = fem->mesh.dm;
  PetscFunctionReturn(0);
}

PetscErrorCode FCBodyFEMGetState(FCBody body, Vec *u, Vec *v)
{
  FEM *fem = NULL;
  PetscFunctionBegin;
  FCValidPointer(body, 1);
  PetscCall(FCFEMGet(body, &fem));
  if (u) *u = fem->u;
  if (v) *v = fem->v;
  PetscFunctionReturn(0);
}

PetscErrorCode FCBodyFEMComputeElasticForce(FCBody body, Vec u, Vec f)
{
  FEM *fem = NULL;
  PetscFunctionBegin;
  FCValidPointer(body, 1);
  FCValidPointer(u, 2);
  FCValidPointer(f, 3);
  PetscCall(FCFEMGet(body, &fem));
  PetscCall(FCFEMAssembleElastic(body, u, f, NULL));
  PetscFunctionReturn(0);
}

/* Placed reference coordinates in the layout of the global state vectors */
PetscErrorCode FCBodyFEMGetReferenceCoordinates(FCBody body, Vec *X)
{
  FEM         *fem;
  PetscScalar *xa;
  PetscInt     lo;

  PetscFunctionBegin;
  FCValidPointer(body, 1);
  FCValidPointer(X, 2);
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
  FCValidPointer(body, 1);
  PetscCall(FCFEMGet(body, &fem));
  if (nassembly) *nassembly = fem->nassembly;
  if (nfactorization) *nfactorization = fem->nfactor;
  PetscFunctionReturn(0);
}
