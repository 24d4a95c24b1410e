/* FE body, the factorization schedule of a co-rotational body (-<body>_factorization).

   every_step: A = M + h B + h^2 K(R) is assembled and factored at every step (fem_step.c): the free
   motion (eq. 5), W_b (eq. 17) and the correction (eq. 20) are exact for the step's linearization.

   reuse: A is factored now and then, and the steps between keep that factor F of A_0 (the A of
   the last factorization, at per-vertex rotations R_0):
     - the free motion is exact to -<body>_ksp_rtol: conjugate gradients on today's A, applied
       without assembling it (per cell, R K_e R^T x with R the cell's rotation now,
       FCMaterialRotatedApply; M by its matrix), preconditioned by the warped factor
           P^-1 = Q A_0^-1 Q^T,  Q = blockdiag(R_v R_0,v^T),
       R_v the rotation of vertex v now (the polar factor of the volume-weighted sum of its cells'
       rotations). Q A_0 Q^T is A_0 turned with the body, so a body that rotates keeps a good
       preconditioner (compliance warping, Mueller & Gross 2004; Courtecuisse et al. 2010);
     - the compliance and the correction take the same warped operator in place of A^-1:
           W_b = J Q A_0^-1 Q^T J^T,  dv += h Q A_0^-1 Q^T J^T lambda
       (the builder gets Q, FCComplianceSetWarp), so the contact forces solve the problem of that
       operator and the positions they give agree with W. This is the approximation: the
       compliance of the deformation since the last factorization is that of A_0 turned;
     - A is factored again at the step's state, before its solves, when the last step's contact
       correction, turned with the vertices since, leaves a relative residual above
       -<body>_refactor_residual in today's A (Predict: the warped compliance's error along the
       contacts' forces), when the largest vertex rotation since the last factorization,
       measured against the body's mean rotation since then (a rigid rotation is exact under the
       warp), passes -<body>_refactor_rotation, after a step whose CG took more than
       -<body>_refactor_iterations iterations, every -<body>_refactor_every steps (0: never for
       age), or at once when CG does not converge in -<body>_ksp_max_it iterations (the step then
       solves with the new factor). A contact outside the condensed builder's Schur block
       refactors A_0 (the builder's miss), which keeps Q.
   reuse needs the body's default solver (MUMPS Cholesky) and, in a contact pair, the condensed
   builder. every_step is the default: reuse's correction does not conserve momentum where Q
   varies, and its restarts are not exact (docs/accuracy.md, "Factorization schedule").
   The counts go to /steps/factorizations and /steps/krylov_iterations. */
#include "femimpl.h"
#include "../compliance/compliance.h"

/* The per-vertex rotations of the state: R_v = polar(sum over the vertex's cells of V R_cell), on
   the owned vertex blocks of the layout of u (column j of R_v in rcol[j]) */
static PetscErrorCode VertexRotations(FCBody body, PetscReal Rv[])
{
  FEM          *fem = (FEM *)body->data;
  FCMesh       *m   = &fem->mesh;
  PetscScalar  *l[3];
  const PetscScalar *g[3];
  PetscInt      n;

  PetscFunctionBegin;
  for (int j = 0; j < 3; j++) {
    PetscCall(VecZeroEntries(fem->rcolloc[j]));
    PetscCall(VecGetArray(fem->rcolloc[j], &l[j]));
  }
  for (PetscInt c = 0; c < m->cEnd - m->cStart; c++) {
    const PetscReal *R = &fem->Rcell[9 * c];
    PetscReal        V = PetscAbsReal(fem->vol[c]);
    for (int a = 0; a < 4; a++) {
      PetscInt v = m->cellVerts[4 * c + a] - m->vStart;
      if (fem->fixed[v]) continue;
      for (int j = 0; j < 3; j++)
        for (int i = 0; i < 3; i++) l[j][fem->ldof[v] + i] += V * R[3 * i + j];
    }
  }
  for (int j = 0; j < 3; j++) {
    PetscCall(VecRestoreArray(fem->rcolloc[j], &l[j]));
    PetscCall(VecZeroEntries(fem->rcol[j]));
    PetscCall(DMLocalToGlobal(m->dm, fem->rcolloc[j], ADD_VALUES, fem->rcol[j]));
    PetscCall(VecGetArrayRead(fem->rcol[j], &g[j]));
  }
  PetscCall(VecGetLocalSize(fem->u, &n));
  for (PetscInt b = 0; b < n / 3; b++) {
    PetscReal S[9];
    for (int i = 0; i < 3; i++)
      for (int j = 0; j < 3; j++) S[3 * i + j] = PetscRealPart(g[j][3 * b + i]);
    FCMat3Polar(S, &Rv[9 * b]);
  }
  for (int j = 0; j < 3; j++) PetscCall(VecRestoreArrayRead(fem->rcol[j], &g[j]));
  PetscFunctionReturn(0);
}

/* Q = R_v R_0^T per owned block, the largest angle among them (every rank), and the surface
   vertices' Q on every rank for the compliance builder */
static PetscErrorCode UpdateWarp(FCBody body, const PetscReal Rv[])
{
  FEM      *fem = (FEM *)body->data;
  PetscInt  n, lo;
  PetscReal cmin = 1.0;

  PetscFunctionBegin;
  PetscCall(VecGetLocalSize(fem->u, &n));
  PetscCall(VecGetOwnershipRange(fem->u, &lo, NULL));
  PetscReal S[9] = {0}, Qm[9];
  for (PetscInt b = 0; b < n / 3; b++) {
    PetscReal *Q = &fem->dR[9 * b], R0T[9];
    FCMat3Transpose(&fem->Rv0[9 * b], R0T);
    FCMat3Mult(&Rv[9 * b], R0T, Q);
    for (int i = 0; i < 9; i++) S[i] += Q[i];
  }
  /* the angle that counts is each Q's against the body's mean rotation Qm: a rigid rotation turns
     A_0 into A exactly (Q A_0 Q^T), a rotation that varies over the body does not */
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, S, 9, MPIU_REAL, MPIU_SUM, body->comm));
  FCMat3Polar(S, Qm);
  for (PetscInt b = 0; b < n / 3; b++) {
    const PetscReal *Q = &fem->dR[9 * b];
    PetscReal        c = -0.5; /* cos of the angle of Q Qm^T: (tr(Q Qm^T) - 1) / 2 */
    for (int i = 0; i < 9; i++) c += 0.5 * Q[i] * Qm[i];
    cmin = PetscMin(cmin, c);
  }
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &cmin, 1, MPIU_REAL, MPIU_MIN, body->comm));
  fem->angle = PetscAcosReal(PetscMax(-1.0, PetscMin(1.0, cmin)));
  if (!fem->comp) PetscFunctionReturn(0);
  for (PetscInt i = 0; i < fem->nsurface; i++)
    PetscCall(PetscArraycpy(&fem->swbuf[9 * i], &fem->dR[9 * ((fem->surface[i] - lo) / 3)], 9));
  {
    PetscMPIInt size;
    PetscReal  *all;
    PetscCallMPI(MPI_Comm_size(body->comm, &size));
    PetscCall(PetscMalloc1(9 * fem->nsw + 1, &all));
    PetscCallMPI(MPI_Allgatherv(fem->swbuf, 9 * (PetscMPIInt)fem->nsurface, MPIU_REAL, all, fem->swcounts,
                                fem->swdispls, MPIU_REAL, body->comm));
    for (PetscInt i = 0; i < fem->nsw; i++) PetscCall(PetscArraycpy(&fem->swR[9 * i], &all[9 * fem->swperm[i]], 9));
    PetscCall(PetscFree(all));
  }
  PetscCall(FCComplianceSetWarp(fem->comp, fem->nsw, fem->swdof, fem->swR, n / 3, fem->dR));
  PetscFunctionReturn(0);
}

/* y = K(R) x, the cells' rotations of the step (Rcell) */
static PetscErrorCode KMultFree(FCBody body, Vec x, Vec y)
{
  FEM               *fem = (FEM *)body->data;
  FCMesh            *m   = &fem->mesh;
  const PetscScalar *xl;
  PetscScalar       *yl;

  PetscFunctionBegin;
  PetscCall(DMGlobalToLocal(m->dm, x, INSERT_VALUES, fem->vloc));
  PetscCall(VecZeroEntries(fem->dvloc));
  PetscCall(VecGetArrayRead(fem->vloc, &xl));
  PetscCall(VecGetArray(fem->dvloc, &yl));
  for (PetscInt c = 0; c < m->cEnd - m->cStart; c++) {
    PetscReal xe[12], ye[12];
    for (int a = 0; a < 4; a++) {
      PetscInt v = m->cellVerts[4 * c + a] - m->vStart;
      for (int d = 0; d < 3; d++) xe[3 * a + d] = fem->fixed[v] ? 0.0 : PetscRealPart(xl[fem->ldof[v] + d]);
    }
    FCMaterialRotatedApply(fem->mat, &fem->Rcell[9 * c], &fem->Dminv[9 * c], fem->vol[c], xe, ye);
    for (int a = 0; a < 4; a++) {
      PetscInt v = m->cellVerts[4 * c + a] - m->vStart;
      if (fem->fixed[v]) continue;
      for (int d = 0; d < 3; d++) yl[fem->ldof[v] + d] += ye[3 * a + d];
    }
  }
  PetscCall(VecRestoreArrayRead(fem->vloc, &xl));
  PetscCall(VecRestoreArray(fem->dvloc, &yl));
  PetscCall(VecZeroEntries(y));
  PetscCall(DMLocalToGlobal(m->dm, fem->dvloc, ADD_VALUES, y));
  PetscFunctionReturn(0);
}

/* y = K x with the step's K: the assembled one (every_step, linear) or the cells' rotations (reuse) */
PetscErrorCode FCFEMKMult(FCBody body, Vec x, Vec y)
{
  FEM *fem = (FEM *)body->data;

  PetscFunctionBegin;
  if (fem->factorization == FC_FACTORIZATION_REUSE) PetscCall(KMultFree(body, x, y));
  else PetscCall(MatMult(fem->K, x, y));
  PetscFunctionReturn(0);
}

/* Today's A x = (1 + h alpha) M x + (h beta + h^2) K x (quasi-static: h^2 K x), as FCFEMFormA forms it */
static PetscErrorCode AMult(Mat A, Vec x, Vec y)
{
  FCBody    body;
  FEM      *fem;
  PetscReal h;

  PetscFunctionBegin;
  PetscCall(MatShellGetContext(A, &body));
  fem = (FEM *)body->data;
  h   = body->h;
  PetscCall(KMultFree(body, x, y));
  if (body->quasistatic) PetscCall(VecScale(y, h * h));
  else {
    PetscCall(VecScale(y, h * fem->beta + h * h));
    PetscCall(MatMult(fem->M, x, fem->work));
    PetscCall(VecAXPY(y, 1.0 + h * fem->alpha, fem->work));
  }
  PetscFunctionReturn(0);
}

/* x (owned blocks) = Q x or Q^T x */
static PetscErrorCode Turn(FEM *fem, Vec x, PetscBool transpose)
{
  PetscScalar *a;
  PetscInt     n;

  PetscFunctionBegin;
  PetscCall(VecGetLocalSize(x, &n));
  PetscCall(VecGetArray(x, &a));
  for (PetscInt b = 0; b < n / 3; b++) {
    PetscReal y[3], z[3] = {PetscRealPart(a[3 * b]), PetscRealPart(a[3 * b + 1]), PetscRealPart(a[3 * b + 2])};
    if (transpose) FCMat3TVec(&fem->dR[9 * b], z, y);
    else FCMat3Vec(&fem->dR[9 * b], z, y);
    for (int d = 0; d < 3; d++) a[3 * b + d] = y[d];
  }
  PetscCall(VecRestoreArray(x, &a));
  PetscFunctionReturn(0);
}

/* A body held by nothing keeps the momentum of its free motion: A 1_d = M 1_d for a translation
   1_d (K annihilates it), so the exact x = A^-1 b has sum(M x)_d = sum(b)_d. CG stopped at its
   tolerance does not; x gets the translation velocity that restores it (no elastic force, and the
   positions move by what the tolerance left) */
static PetscErrorCode KeepMomentum(FCBody body, Vec b, Vec x)
{
  FEM               *fem = (FEM *)body->data;
  const PetscScalar *ba, *ma;
  PetscScalar       *xa;
  PetscReal          s[6] = {0};
  PetscInt           n;

  PetscFunctionBegin;
  if (fem->nfixed > 0) PetscFunctionReturn(0);
  PetscCall(MatMult(fem->M, x, fem->xres));
  PetscCall(VecGetLocalSize(x, &n));
  PetscCall(VecGetArrayRead(b, &ba));
  PetscCall(VecGetArrayRead(fem->xres, &ma));
  for (PetscInt i = 0; i < n; i++) {
    s[i % 3] += PetscRealPart(ba[i]);
    s[3 + i % 3] += PetscRealPart(ma[i]);
  }
  PetscCall(VecRestoreArrayRead(b, &ba));
  PetscCall(VecRestoreArrayRead(fem->xres, &ma));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, s, 6, MPIU_REAL, MPIU_SUM, body->comm));
  PetscCall(VecGetArray(x, &xa));
  for (PetscInt i = 0; i < n; i++) xa[i] += (s[i % 3] - s[3 + i % 3]) / fem->mass;
  PetscCall(VecRestoreArray(x, &xa));
  PetscFunctionReturn(0);
}

/* The preconditioner: z = Q A_0^-1 Q^T r with the last factor */
static PetscErrorCode WarpedSolve(PC pc, Vec r, Vec z)
{
  FCBody body;
  FEM   *fem;

  PetscFunctionBegin;
  PetscCall(PCShellGetContext(pc, &body));
  fem = (FEM *)body->data;
  PetscCall(VecCopy(r, fem->rw2));
  PetscCall(Turn(fem, fem->rw2, PETSC_TRUE));
  PetscCall(FCFEMSolveA(body, fem->rw2, z, "Preconditioner", fem->tnow));
  PetscCall(Turn(fem, z, PETSC_FALSE));
  PetscFunctionReturn(0);
}

/* What reuse needs: per-cell rotations, the vertex rotations and their reference, the surface
   table of the compliance builder, the matrix-free A and its CG. With every_step: nothing */
PetscErrorCode FCFEMScheduleSetUp(FCBody body)
{
  FEM     *fem = (FEM *)body->data;
  FCMesh  *m   = &fem->mesh;
  PetscInt n, N, nc = m->cEnd - m->cStart;
  PC       pc;

  PetscFunctionBegin;
  if (fem->factorization != FC_FACTORIZATION_REUSE) PetscFunctionReturn(0);
  { /* the preconditioner is the body's factor: its solver must be one (preonly + Cholesky + MUMPS) */
    KSPType       kt;
    MatSolverType st;
    PetscBool     preonly, cholesky, mumps = PETSC_FALSE;
    PetscCall(KSPGetType(fem->ksp, &kt));
    PetscCall(KSPGetPC(fem->ksp, &pc));
    PetscCall(PetscStrcmp(kt, KSPPREONLY, &preonly));
    PetscCall(PetscObjectTypeCompare((PetscObject)pc, PCCHOLESKY, &cholesky));
    if (preonly && cholesky) {
      PetscCall(PCFactorGetMatSolverType(pc, &st));
      PetscCall(PetscStrcmp(st, MATSOLVERMUMPS, &mumps));
    }
    PetscCheck(mumps, body->comm, PETSC_ERR_USER_INPUT,
               "-%sfactorization reuse preconditions with the body's factorization of A, but the options of its solver "
               "(-%sksp_type, -%spc_type, -%spc_factor_mat_solver_type) ask for another solver than MUMPS Cholesky: "
               "drop them, or use -%sfactorization every_step",
               body->prefix, body->prefix, body->prefix, body->prefix, body->prefix);
  }
  fem->Acurrent = PETSC_FALSE; /* the first step takes its operator (and first factor) at its state */
  fem->factored = PETSC_FALSE;
  PetscCall(VecGetLocalSize(fem->u, &n));
  PetscCall(VecGetSize(fem->u, &N));
  PetscCall(PetscMalloc5(9 * nc + 1, &fem->Rcell, 3 * n + 1, &fem->Rv0, 3 * n + 1, &fem->dR, 3 * n + 1, &fem->Rvnow,
                         3 * n + 1, &fem->Rvprev));
  for (PetscInt b = 0; b < n / 3; b++) {
    FCMat3Identity(&fem->Rv0[9 * b]);
    FCMat3Identity(&fem->dR[9 * b]);
  }
  for (int j = 0; j < 3; j++) {
    PetscCall(VecDuplicate(fem->u, &fem->rcol[j]));
    PetscCall(DMCreateLocalVector(m->dm, &fem->rcolloc[j]));
  }
  PetscCall(VecDuplicate(fem->u, &fem->rw2));
  PetscCall(VecDuplicate(fem->u, &fem->xlast));
  PetscCall(VecDuplicate(fem->u, &fem->xres));
  PetscCall(VecDuplicate(fem->u, &fem->xcorr));
  PetscCall(VecDuplicate(fem->u, &fem->xprev));
  PetscCall(VecDuplicate(fem->u, &fem->rprev));
  PetscCall(MatCreateShell(body->comm, n, n, N, N, body, &fem->Aop));
  PetscCall(MatShellSetOperation(fem->Aop, MATOP_MULT, (void (*)(void))AMult));
  PetscCall(KSPCreate(body->comm, &fem->kspk));
  PetscCall(KSPSetType(fem->kspk, KSPCG));
  PetscCall(KSPSetOperators(fem->kspk, fem->Aop, fem->Aop));
  PetscCall(KSPSetNormType(fem->kspk, KSP_NORM_UNPRECONDITIONED));
  PetscCall(KSPSetInitialGuessNonzero(fem->kspk, PETSC_TRUE));
  PetscCall(KSPSetTolerances(fem->kspk, fem->ksp_rtol, PETSC_DEFAULT, PETSC_DEFAULT, fem->ksp_max_it));
  PetscCall(KSPGetPC(fem->kspk, &pc));
  PetscCall(PCSetType(pc, PCSHELL));
  PetscCall(PCShellSetContext(pc, body));
  PetscCall(PCShellSetApply(pc, WarpedSolve));
  PetscCall(PCShellSetName(pc, "warped factor of the last A"));
  PetscFunctionReturn(0);
}

/* The surface table of the compliance builder (after the builder exists): every rank's owned
   surface DOFs, sorted, and where each comes from in the gathered order */
PetscErrorCode FCFEMScheduleSetUpContact(FCBody body)
{
  FEM        *fem = (FEM *)body->data;
  PetscMPIInt size, n = (PetscMPIInt)fem->nsurface, *counts, *displs;

  PetscFunctionBegin;
  if (fem->factorization != FC_FACTORIZATION_REUSE || fem->swdof) PetscFunctionReturn(0);
  PetscCheck(FCComplianceFactorsA(fem->comp), body->comm, PETSC_ERR_USER_INPUT,
             "-%sfactorization reuse warps the compliance of the condensed builder: body '%s' needs "
             "-compliance_type condensed (the default)",
             body->prefix, body->name);
  PetscCallMPI(MPI_Comm_size(body->comm, &size));
  PetscCall(PetscMalloc2(size, &counts, size + 1, &displs));
  PetscCallMPI(MPI_Allgather(&n, 1, MPI_INT, counts, 1, MPI_INT, body->comm));
  displs[0] = 0;
  for (PetscMPIInt r = 0; r < size; r++) displs[r + 1] = displs[r] + counts[r];
  fem->nsw = displs[size];
  PetscCall(PetscMalloc4(fem->nsw + 1, &fem->swdof, fem->nsw + 1, &fem->swperm, 9 * fem->nsw + 1, &fem->swR,
                         9 * fem->nsurface + 1, &fem->swbuf));
  PetscCallMPI(
      MPI_Allgatherv(fem->surface, n, MPIU_INT, fem->swdof, counts, displs, MPIU_INT, body->comm));
  for (PetscInt i = 0; i < fem->nsw; i++) fem->swperm[i] = i;
  PetscCall(PetscSortIntWithArray(fem->nsw, fem->swdof, fem->swperm));
  PetscCall(PetscMalloc2(size, &fem->swcounts, size, &fem->swdispls));
  for (PetscMPIInt r = 0; r < size; r++) {
    fem->swcounts[r] = 9 * counts[r];
    fem->swdispls[r] = 9 * displs[r];
  }
  PetscCall(PetscFree2(counts, displs));
  PetscFunctionReturn(0);
}

static PetscErrorCode Predict(FCBody, PetscReal *);

/* Factor A at the state (K assembled there), which becomes A_0: Q = I */
static PetscErrorCode Refactor(FCBody body, const PetscReal Rv[])
{
  FEM     *fem = (FEM *)body->data;
  PetscInt n;

  PetscFunctionBegin;
  PetscCall(FCFEMAssembleElastic(body, fem->state, NULL, fem->K));
  PetscCall(FCFEMFormA(body));
  PetscCall(FCFEMFactorA(body));
  PetscCall(VecGetLocalSize(fem->u, &n));
  PetscCall(PetscArraycpy(fem->Rv0, Rv, 3 * n));
  PetscCall(UpdateWarp(body, Rv));
  fem->refactor_next = PETSC_FALSE;
  fem->fresh         = PETSC_TRUE;
  fem->hasprev       = PETSC_FALSE;
  PetscFunctionReturn(0);
}

/* The operator of the step at `state` (u, or the turned state): every_step assembles K and f_int
   and factors A; reuse computes the cells' rotations and f_int, the vertex rotations since the last
   factorization, and factors A when one of the triggers says so */
PetscErrorCode FCFEMScheduleOperator(FCBody body, Vec state)
{
  FEM               *fem = (FEM *)body->data;
  FCMesh            *m   = &fem->mesh;
  const PetscScalar *ul;
  PetscScalar       *fl;
  PetscReal         *Rv, res = 0.0;
  PetscBool          due;

  PetscFunctionBegin;
  fem->state = state;
  fem->fresh = PETSC_FALSE;
  if (fem->factorization != FC_FACTORIZATION_REUSE) {
    PetscCall(FCFEMAssembleElastic(body, state, fem->fint, fem->K));
    PetscCall(FCFEMFormA(body));
    PetscCall(FCFEMFactorA(body));
    fem->fresh = PETSC_TRUE;
    PetscFunctionReturn(0);
  }
  PetscCall(FCPhaseBegin(FC_PHASE_ASSEMBLY));
  PetscCall(DMGlobalToLocal(m->dm, state, INSERT_VALUES, fem->uloc));
  PetscCall(VecGetArrayRead(fem->uloc, &ul));
  PetscCall(VecZeroEntries(fem->floc));
  PetscCall(VecGetArray(fem->floc, &fl));
  for (PetscInt c = 0; c < m->cEnd - m->cStart; c++) {
    PetscReal X[12], x[12], fe[12];
    FCFEMGatherElement(fem, c, ul, X, x);
    PetscCall((*fem->mat->rotation)(fem->mat, x, X, &fem->Dminv[9 * c], fem->vol[c], fe, &fem->Rcell[9 * c]));
    for (int a = 0; a < 4; a++) {
      PetscInt v = m->cellVerts[4 * c + a] - m->vStart;
      if (fem->fixed[v]) continue;
      for (int d = 0; d < 3; d++) fl[fem->ldof[v] + d] += fe[3 * a + d];
    }
  }
  PetscCall(VecRestoreArrayRead(fem->uloc, &ul));
  PetscCall(VecRestoreArray(fem->floc, &fl));
  PetscCall(VecZeroEntries(fem->fint));
  PetscCall(DMLocalToGlobal(m->dm, fem->floc, ADD_VALUES, fem->fint));
  Rv = fem->Rvnow;
  PetscCall(VertexRotations(body, Rv));
  PetscCall(UpdateWarp(body, Rv));
  PetscCall(Predict(body, &res));
  PetscCall(FCPhaseEnd(FC_PHASE_ASSEMBLY));
  due = (PetscBool)(!fem->factored || fem->refactor_next || fem->angle > fem->refactor_rotation ||
                    res > fem->refactor_residual || (fem->refactor_every > 0 && fem->factor_age >= fem->refactor_every));
  if (due) {
    PetscCall(PetscInfo(NULL,
                        "body %s: factoring A (rotation since the last factorization %g rad, residual of the last "
                        "correction %g, age %" PetscInt_FMT ", CG iterations above the limit: %s)\n",
                        body->name, (double)fem->angle, (double)res, fem->factor_age, PetscBools[fem->refactor_next]));
    PetscCall(Refactor(body, Rv));
  }
  PetscFunctionReturn(0);
}

/* x = A^-1 b for the free motion: with the factor of this step's A, one solve; else CG to
   ksp_rtol, and a factorization now if it does not converge */
PetscErrorCode FCFEMScheduleSolve(FCBody body, Vec b, Vec x, PetscReal t)
{
  FEM               *fem = (FEM *)body->data;
  KSPConvergedReason reason;
  PetscInt           its;

  PetscFunctionBegin;
  fem->tnow = t;
  if (fem->fresh || fem->factorization != FC_FACTORIZATION_REUSE) {
    PetscCall(FCFEMSolveA(body, b, x, "Free-motion", t));
    if (fem->xlast) PetscCall(VecCopy(x, fem->xlast));
    PetscFunctionReturn(0);
  }
  PetscCall(VecCopy(fem->xlast, x)); /* the last step's solution: the free motion changes little from step to step */
  PetscCall(KSPSolve(fem->kspk, b, x));
  PetscCall(KeepMomentum(body, b, x));
  PetscCall(VecCopy(x, fem->xlast));
  PetscCall(KSPGetConvergedReason(fem->kspk, &reason));
  PetscCall(KSPGetIterationNumber(fem->kspk, &its));
  fem->nkrylov += its;
  if (its > fem->refactor_iterations) fem->refactor_next = PETSC_TRUE;
  if (reason < 0) { /* the old factor is too far from A: a new one, and a direct solve */
    PetscCall(PetscInfo(NULL, "body %s: CG with the old factor did not converge (%s, %" PetscInt_FMT " iterations): refactoring\n",
                        body->name, KSPConvergedReasons[reason], its));
    PetscCall(Refactor(body, fem->Rvnow));
    PetscCall(FCFEMSolveA(body, b, x, "Free-motion", t));
  }
  PetscFunctionReturn(0);
}

/* The contact correction x = h Q A_0^-1 Q^T J^T lambda (the warped operator's), before dv += x: x
   and its right-hand side h J^T lambda kept, with the vertex rotations of the step, for the check
   of the next step (Predict). Its momentum is the warped operator's: not restored, since a
   translation added to x would move the contacts off the gaps W was solved for */
PetscErrorCode FCFEMScheduleKeepCorrection(FCBody body, Vec x)
{
  FEM     *fem = (FEM *)body->data;
  Vec      rhs;
  PetscInt n;

  PetscFunctionBegin;
  if (fem->factorization != FC_FACTORIZATION_REUSE || !fem->comp) PetscFunctionReturn(0);
  PetscCall(FCComplianceGetCorrectionRHS(fem->comp, &rhs)); /* (J Q)^T h lambda = Q^T J^T h lambda */
  if (!rhs) PetscFunctionReturn(0);
  PetscCall(VecCopy(rhs, fem->rprev));
  PetscCall(Turn(fem, fem->rprev, PETSC_FALSE));
  PetscCall(VecCopy(x, fem->xprev));
  PetscCall(VecGetLocalSize(fem->u, &n));
  PetscCall(PetscArraycpy(fem->Rvprev, fem->Rvnow, 3 * n));
  fem->hasprev = PETSC_TRUE;
  PetscFunctionReturn(0);
}

/* Before the step's solves, whether the warped factor still answers the last step's contact forces:
   x and r = h J^T lambda of the last correction, turned with each vertex since (R_v R_v,last^T), and
   the relative residual ||A x - r|| / ||r|| in today's A (one matrix-free product). It measures the
   warped compliance's error along the forces of the contacts, and the change of A since they were
   computed; above -refactor_residual, A is factored now, before the contacts need it */
static PetscErrorCode Predict(FCBody body, PetscReal *res)
{
  FEM         *fem = (FEM *)body->data;
  PetscScalar *xa, *ra;
  PetscInt     n;
  PetscReal    nr, nb;

  PetscFunctionBegin;
  *res = 0.0;
  if (!fem->hasprev) PetscFunctionReturn(0);
  fem->hasprev = PETSC_FALSE;
  PetscCall(VecGetLocalSize(fem->u, &n));
  PetscCall(VecGetArray(fem->xprev, &xa));
  PetscCall(VecGetArray(fem->rprev, &ra));
  for (PetscInt b = 0; b < n / 3; b++) {
    PetscReal PT[9], T[9], y[3], z[3];
    FCMat3Transpose(&fem->Rvprev[9 * b], PT);
    FCMat3Mult(&fem->Rvnow[9 * b], PT, T);
    for (int d = 0; d < 3; d++) z[d] = PetscRealPart(xa[3 * b + d]);
    FCMat3Vec(T, z, y);
    for (int d = 0; d < 3; d++) xa[3 * b + d] = y[d];
    for (int d = 0; d < 3; d++) z[d] = PetscRealPart(ra[3 * b + d]);
    FCMat3Vec(T, z, y);
    for (int d = 0; d < 3; d++) ra[3 * b + d] = y[d];
  }
  PetscCall(VecRestoreArray(fem->xprev, &xa));
  PetscCall(VecRestoreArray(fem->rprev, &ra));
  PetscCall(VecNorm(fem->rprev, NORM_2, &nb));
  if (nb == 0.0) PetscFunctionReturn(0);
  PetscCall(MatMult(fem->Aop, fem->xprev, fem->xres));
  PetscCall(VecAXPY(fem->xres, -1.0, fem->rprev));
  PetscCall(VecNorm(fem->xres, NORM_2, &nr));
  *res = nr / nb;
  PetscFunctionReturn(0);
}

PetscErrorCode FCFEMScheduleDestroy(FCBody body)
{
  FEM *fem = (FEM *)body->data;

  PetscFunctionBegin;
  PetscCall(PetscFree5(fem->Rcell, fem->Rv0, fem->dR, fem->Rvnow, fem->Rvprev));
  for (int j = 0; j < 3; j++) {
    PetscCall(VecDestroy(&fem->rcol[j]));
    PetscCall(VecDestroy(&fem->rcolloc[j]));
  }
  PetscCall(VecDestroy(&fem->rw2));
  PetscCall(VecDestroy(&fem->xlast));
  PetscCall(VecDestroy(&fem->xres));
  PetscCall(VecDestroy(&fem->xcorr));
  PetscCall(VecDestroy(&fem->xprev));
  PetscCall(VecDestroy(&fem->rprev));
  PetscCall(MatDestroy(&fem->Aop));
  PetscCall(KSPDestroy(&fem->kspk));
  PetscCall(PetscFree4(fem->swdof, fem->swperm, fem->swR, fem->swbuf));
  PetscCall(PetscFree2(fem->swcounts, fem->swdispls));
  PetscFunctionReturn(0);
}
