/* FE body, operator and time step: the element loops (K, f_int, M), A = M + h B + h^2 K and its
   factorization, the free motion (eq. 5) and the integration (eq. 2). */
#include "femimpl.h"

/* Element loop: f (global, may be NULL) = f_int(u), K (may be NULL) = tangent stiffness. With
   -assembly coo the element matrices are written in place (Kcells) and summed by the map PETSc
   built at set-up (FCFEMCreateOperators), remote rows included, instead of inserting them one by
   one (MatSetValues: a search in the row per entry, a stash for the remote ones) */
PetscErrorCode FCFEMAssembleElastic(FCBody body, Vec u, Vec f, Mat K)
{
  PetscFunctionBegin;
  PetscCall(FCFEMAssembleElasticAt(body, u, FC_BC_NOW, f, K));
  PetscFunctionReturn(0);
}

PetscErrorCode FCFEMAssembleElasticAt(FCBody body, Vec u, int when, Vec f, Mat K)
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
  PetscBool coo = (PetscBool)(K && fem->Kcells);
  if (K && !coo) PetscCall(MatZeroEntries(K));
  for (PetscInt c = 0; c < m->cEnd - m->cStart; c++) {
    PetscReal  X[12], x[12], fe[12], Kv[144];
    PetscReal *Ke = coo ? &fem->Kcells[144 * c] : Kv;
    PetscInt   idx[12];
    FCFEMGatherElementAt(fem, c, ul, when, X, x);
    PetscCall((*fem->mat->element)(fem->mat, x, X, &fem->Dminv[9 * c], fem->vol[c], f ? fe : NULL, K ? Ke : NULL));
    if (f)
      for (int a = 0; a < 4; a++) {
        PetscInt v = m->cellVerts[4 * c + a] - m->vStart;
        if (fem->fixed[v]) continue;
        for (int d = 0; d < 3; d++) fl[fem->ldof[v] + d] += fe[3 * a + d];
      }
    if (K && !coo) {
      FCFEMElementIndices(fem, c, idx);
      PetscCall(MatSetValues(K, 12, idx, 12, idx, Ke, ADD_VALUES));
    }
  }
  PetscCall(VecRestoreArrayRead(fem->uloc, &ul));
  if (f) {
    PetscCall(VecRestoreArray(fem->floc, &fl));
    PetscCall(VecZeroEntries(f));
    PetscCall(DMLocalToGlobal(m->dm, fem->floc, ADD_VALUES, f));
  }
  if (coo)
    PetscCall(MatSetValuesCOO(K, fem->Kcells, INSERT_VALUES)); /* the sums replace K (assembled) */
  else if (K) {
    PetscCall(MatAssemblyBegin(K, MAT_FINAL_ASSEMBLY));
    PetscCall(MatAssemblyEnd(K, MAT_FINAL_ASSEMBLY));
  }
  fem->nassembly++;
  PetscCall(FCPhaseEnd(FC_PHASE_ASSEMBLY));
  PetscFunctionReturn(0);
}

/* A = (1 + h alpha) M + (h beta + h^2) K (quasi-static: h^2 K, the step's displacement h dv solving
   K h dv = h b / h); its factor is stale until FCFEMFactorA */
PetscErrorCode FCFEMFormA(FCBody body)
{
  FEM      *fem = (FEM *)body->data;
  PetscReal h   = body->h;

  PetscFunctionBegin;
  PetscCall(FCPhaseBegin(FC_PHASE_ASSEMBLY));
  PetscCall(MatCopy(fem->K, fem->A, SAME_NONZERO_PATTERN));
  PetscCall(MatScale(fem->A, h * fem->beta + h * h));
  if (body->quasistatic) {
    PetscCall(MatSetOption(fem->A, MAT_SPD, PETSC_TRUE));
    PetscCall(FCPhaseEnd(FC_PHASE_ASSEMBLY));
    fem->factored = PETSC_FALSE;
    PetscFunctionReturn(0);
  }
  /* SAME: K, M and A are duplicates of one filled pattern (FCFEMCreateOperators); SUBSET takes the
     row-by-row path of MatAXPY_Basic on MPIAIJ, a cost every step */
  PetscCall(MatAXPY(fem->A, 1.0 + h * fem->alpha, fem->M, SAME_NONZERO_PATTERN));
  PetscCall(MatSetOption(fem->A, MAT_SPD, PETSC_TRUE));
  PetscCall(FCPhaseEnd(FC_PHASE_ASSEMBLY));
  fem->factored = PETSC_FALSE;
  PetscFunctionReturn(0);
}

/* Step control changed h: A = M + h B + h^2 K with the new h. A linear body's A is formed again
   from its K; a nonlinear body's at its next step (its factorization schedule starts from a new
   factor). Either is factored at its next use */
PetscErrorCode FCFEMChangeTimeStep(FCBody body)
{
  FEM *fem = (FEM *)body->data;

  PetscFunctionBegin;
  PetscCheck(!fem->comp || !FCComplianceKeepsInitialA(fem->comp), body->comm, PETSC_ERR_SUP,
             "Step control would take body '%s' to a time step of %g s, which -compliance_type precomputed cannot "
             "follow (it keeps A of the first step); use another -compliance_type or -time_step_control off",
             body->name, (double)body->h);
  if (fem->mat->linear)
    PetscCall(FCFEMFormA(body));
  else {
    fem->Acurrent      = PETSC_FALSE;
    fem->refactor_next = PETSC_TRUE;
  }
  fem->factored = PETSC_FALSE;
  PetscFunctionReturn(0);
}

/* The factorization of A: by the compliance builder when it owns the body's factor (condensed:
   one factorization serves the solves and W_b), else by the body's KSP (then the builders that
   keep something of A are told) */
PetscErrorCode FCFEMFactorA(FCBody body)
{
  FEM *fem = (FEM *)body->data;

  PetscFunctionBegin;
  PetscCall(FCPhaseBegin(FC_PHASE_FACTORIZATION));
  if (fem->comp && FCComplianceFactorsA(fem->comp))
    PetscCall(FCComplianceFactor(fem->comp));
  else {
    PetscCall(KSPSetOperators(fem->ksp, fem->A, fem->A));
    PetscCall(KSPSetUp(fem->ksp));
    PetscCall(FCMumpsKSPChecked(fem->ksp, fem->A, "A", body->name)); /* PETSc records a failure, src/util/mumps.c */
    if (fem->comp) PetscCall(FCComplianceFactor(fem->comp));         /* builders that keep their own copy of A */
  }
  fem->nfactor++;
  fem->factor_age = 0;
  fem->factored   = PETSC_TRUE;
  PetscCall(FCPhaseEnd(FC_PHASE_FACTORIZATION));
  PetscFunctionReturn(0);
}

/* x = A^-1 b with the body's factor (current: the caller factors a stale A first, inside its own
   phase) */
PetscErrorCode FCFEMSolveA(FCBody body, Vec b, Vec x, const char what[], PetscReal t)
{
  FEM *fem = (FEM *)body->data;

  PetscFunctionBegin;
  PetscCheck(fem->factored, body->comm, PETSC_ERR_PLIB, "%s solve of body '%s' with a stale factor of A", what,
             body->name);
  if (fem->comp && FCComplianceFactorsA(fem->comp))
    PetscCall(FCComplianceSolve(fem->comp, b, x));
  else {
    KSPConvergedReason reason;
    PetscCall(KSPSolve(fem->ksp, b, x));
    PetscCall(KSPGetConvergedReason(fem->ksp, &reason));
    PetscCheck(reason >= 0, body->comm, PETSC_ERR_CONV_FAILED, "%s solve of body '%s' failed at t = %g: %s", what,
               body->name, (double)t, KSPConvergedReasons[reason]);
  }
  PetscFunctionReturn(0);
}

PetscErrorCode FCFEMAssembleMass(FCBody body)
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
    FCFEMElementIndices(fem, c, idx);
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
  body->mass = fem->mass;
  PetscCall(FCPhaseEnd(FC_PHASE_ASSEMBLY));
  PetscFunctionReturn(0);
}

/* K, M and A share the pattern of the element couplings. The pattern is recorded by a
   MATPREALLOCATOR pass over the cells (DMCreateMatrix's adjacency-based preallocation costs
   more than a factorization on 10^5 DOFs), or with -assembly coo by the cells' (row, column)
   pairs given to MatSetPreallocationCOO (entries of fixed DOFs, -1, are ignored), which builds
   the map that sums the element matrices every step; K is assembled (zeros) before M and A copy
   its pattern. The matrix type follows -<body>_dm_mat_type. */
PetscErrorCode FCFEMCreateOperators(FCBody body)
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
  PetscCall(DMGetMatType(m->dm, &mtype));
  PetscCall(MatCreate(body->comm, &fem->K));
  PetscCall(MatSetSizes(fem->K, n, n, N, N));
  PetscCall(MatSetBlockSize(fem->K, 3));
  PetscCall(MatSetType(fem->K, mtype));
  if (fem->coo) {
    PetscInt   nc   = m->cEnd - m->cStart, *ci, *cj;
    PetscCount ncoo = 144 * (PetscCount)nc;
    PetscCall(PetscMalloc2(ncoo, &ci, ncoo, &cj));
    for (PetscInt c = 0; c < nc; c++) {
      PetscInt idx[12];
      FCFEMElementIndices(fem, c, idx);
      for (int a = 0; a < 12; a++)
        for (int b = 0; b < 12; b++) {
          ci[144 * c + 12 * a + b] = idx[a];
          cj[144 * c + 12 * a + b] = idx[b];
        }
    }
    PetscCall(MatSetPreallocationCOO(fem->K, ncoo, ci, cj));
    PetscCall(PetscFree2(ci, cj));
    PetscCall(PetscCalloc1(ncoo + 1, &fem->Kcells));
    PetscCall(MatSetValuesCOO(fem->K, fem->Kcells, INSERT_VALUES)); /* assembled: M and A copy the pattern */
  } else {
    PetscCall(MatCreate(body->comm, &P));
    PetscCall(MatSetType(P, MATPREALLOCATOR));
    PetscCall(MatSetSizes(P, n, n, N, N));
    PetscCall(MatSetUp(P));
    for (PetscInt c = 0; c < m->cEnd - m->cStart; c++) {
      PetscInt idx[12];
      FCFEMElementIndices(fem, c, idx);
      PetscCall(MatSetValues(P, 12, idx, 12, idx, zeros, INSERT_VALUES));
    }
    PetscCall(MatAssemblyBegin(P, MAT_FINAL_ASSEMBLY));
    PetscCall(MatAssemblyEnd(P, MAT_FINAL_ASSEMBLY));
    PetscCall(MatPreallocatorPreallocate(P, PETSC_TRUE, fem->K));
    PetscCall(MatDestroy(&P));
  }
  PetscCall(MatSetOption(fem->K, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_TRUE));
  PetscCall(MatDuplicate(fem->K, MAT_DO_NOT_COPY_VALUES, &fem->M));
  PetscCall(MatDuplicate(fem->K, MAT_DO_NOT_COPY_VALUES, &fem->A));
  PetscFunctionReturn(0);
}

/* Free motion, eq. 5: A dv_free = b = h (f_g - f_int) - M (h alpha v) - K ((h beta + h^2) v); a body
   that advances its rotation exactly takes it in the turning frame (fem_rotation.c). Quasi-static:
   no velocity carries over from the step before (v = 0), so b = h (f - f_int) and h dv is the
   step's displacement */
PetscErrorCode FreeMotion_FEM(FCBody body, PetscReal t)
{
  FEM      *fem = (FEM *)body->data;
  PetscReal h   = body->h;
  PetscBool rotate;
  Vec       vb, vk; /* the velocities that B and h^2 K act on */

  PetscFunctionBegin;
  PetscCall(FCFEMBCBeginStep(body, t));
  if (body->quasistatic) PetscCall(VecZeroEntries(fem->v));
  if (fem->free_motion == FC_FREE_MOTION_NEWTON) {
    PetscCall(FCFEMNewtonFreeMotion(body, t));
    PetscFunctionReturn(0);
  }
  rotate = FCFEMRotationActive(fem);
  if (rotate) {
    PetscCall(FCPhaseBegin(FC_PHASE_FREE_MOTION));
    PetscCall(FCFEMRotationPredict(body));
    PetscCall(FCPhaseEnd(FC_PHASE_FREE_MOTION));
  }
  if (!fem->Acurrent || (rotate && !fem->factored)) { /* co-rotational: the operator at q_t (turned; the first
                                                         step's too), factored on the schedule */
    PetscCall(FCFEMScheduleOperator(body, rotate ? fem->uhat : fem->u));
    fem->Acurrent = PETSC_TRUE;
  }
  if (!fem->factored) PetscCall(FCFEMFactorA(body)); /* the first step: factored at first use */
  PetscCall(FCPhaseBegin(FC_PHASE_FREE_MOTION));
  vb = rotate ? fem->rvt : fem->v;
  vk = rotate ? fem->rw : fem->v;
  if (fem->mat->linear) PetscCall(MatMult(fem->K, fem->u, fem->fint)); /* f_int = K u */
  if (body->gravity[0] != 0.0 || body->gravity[1] != 0.0 || body->gravity[2] != 0.0)
    PetscCall(VecAXPBYPCZ(fem->b, h, -h, 0.0, fem->fgrav, fem->fint));
  else { /* no gravity work without gravity */
    PetscCall(VecCopy(fem->fint, fem->b));
    PetscCall(VecScale(fem->b, -h));
  }
  if (rotate) PetscCall(VecAXPY(fem->b, h, fem->rcf));
  if (fem->alpha != 0.0) {
    PetscCall(MatMult(fem->M, vb, fem->work));
    PetscCall(VecAXPY(fem->b, -h * fem->alpha, fem->work));
  }
  if (vb == vk) {
    PetscCall(FCFEMKMult(body, fem->v, fem->work));
    PetscCall(VecAXPY(fem->b, -(h * fem->beta + h * h), fem->work));
  } else {
    if (fem->beta != 0.0) {
      PetscCall(FCFEMKMult(body, vb, fem->work));
      PetscCall(VecAXPY(fem->b, -h * fem->beta, fem->work));
    }
    PetscCall(FCFEMKMult(body, vk, fem->work));
    PetscCall(VecAXPY(fem->b, -h * h, fem->work));
  }
  PetscCall(FCFEMBCAddRHS(body, fem->b, PETSC_TRUE));
  PetscCall(FCFEMScheduleSolve(body, fem->b, fem->dv, t));
  if (rotate) { /* dv = D + v~ - v_t */
    PetscCall(VecAXPY(fem->dv, 1.0, fem->rvt));
    PetscCall(VecAXPY(fem->dv, -1.0, fem->v));
  }
  PetscCall(FCPhaseEnd(FC_PHASE_FREE_MOTION));
  PetscFunctionReturn(0);
}

/* eq. 2: v_{t+h} = v_t + dv, u_{t+h} = u_t + h v_{t+h} (+ delta, fem_rotation.c) */
PetscErrorCode Integrate_FEM(FCBody body, PetscReal t)
{
  FEM *fem = (FEM *)body->data;

  PetscFunctionBegin;
  PetscCall(VecAXPY(fem->v, 1.0, fem->dv));
  PetscCall(VecAXPY(fem->u, body->h, fem->v));
  if (fem->shifted) PetscCall(VecAXPY(fem->u, 1.0, fem->shift));
  fem->shifted = PETSC_FALSE;
  if (!fem->mat->linear) fem->Acurrent = PETSC_FALSE;
  fem->Rcurrent = PETSC_FALSE;
  fem->factor_age++;
  PetscCall(FCFEMBCEndStep(body));
  PetscFunctionReturn(0);
}
