/* FE body, what the reuse schedule (fem_schedule.c) computes without K: the cells' rotations and
   f_int at the step's state, the matrix-free K x and A x, the vertex rotations R_v, their turn
   since the last factorization Q = R_v R_0,v^T (and its largest angle against the body's mean),
   Q applied to a vector, and the table of the surface vertices' Q that the compliance builder
   warps J with (FCComplianceSetWarp). */
#include "femimpl.h"
#include "../compliance/compliance.h"

/* The per-vertex rotations of the state: R_v = polar(sum over the vertex's cells of V R_cell), on
   the owned vertex blocks of the layout of u (column j of R_v in rcol[j]) */
PetscErrorCode FCFEMWarpVertexRotations(FCBody body, PetscReal Rv[])
{
  FEM               *fem = (FEM *)body->data;
  FCMesh            *m   = &fem->mesh;
  PetscScalar       *l[3];
  const PetscScalar *g[3];
  PetscInt           n;

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
PetscErrorCode FCFEMWarpUpdate(FCBody body, const PetscReal Rv[])
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
  PetscCallMPI(MPI_Allgatherv(fem->swbuf, 9 * (PetscMPIInt)fem->nsurface, MPIU_REAL, fem->swall, fem->swcounts,
                              fem->swdispls, MPIU_REAL, body->comm));
  for (PetscInt i = 0; i < fem->nsw; i++)
    PetscCall(PetscArraycpy(&fem->swR[9 * i], &fem->swall[9 * fem->swperm[i]], 9));
  PetscCall(FCComplianceSetWarp(fem->comp, fem->nsw, fem->swdof, fem->swR, n / 3, fem->dR));
  PetscFunctionReturn(0);
}

/* fl (local vector) += fe, a cell's 12 values, on its unconstrained vertices */
static inline void AddCell(const FEM *fem, PetscInt c, const PetscReal fe[12], PetscScalar fl[])
{
  const FCMesh *m = &fem->mesh;
  for (int a = 0; a < 4; a++) {
    PetscInt v = m->cellVerts[4 * c + a] - m->vStart;
    if (fem->fixed[v]) continue;
    for (int d = 0; d < 3; d++) fl[fem->ldof[v] + d] += fe[3 * a + d];
  }
}

/* The cells' rotations at `state` (Rcell) and f_int there, R K_e (R^T x - X) per cell without
   forming K_e (FCMaterialRotatedApply); then the vertex rotations (Rvnow) and Q */
PetscErrorCode FCFEMWarpAtState(FCBody body, Vec state)
{
  FEM               *fem = (FEM *)body->data;
  FCMesh            *m   = &fem->mesh;
  const PetscScalar *ul;
  PetscScalar       *fl;

  PetscFunctionBegin;
  PetscCall(DMGlobalToLocal(m->dm, state, INSERT_VALUES, fem->uloc));
  PetscCall(VecGetArrayRead(fem->uloc, &ul));
  PetscCall(VecZeroEntries(fem->floc));
  PetscCall(VecGetArray(fem->floc, &fl));
  for (PetscInt c = 0; c < m->cEnd - m->cStart; c++) {
    PetscReal X[12], x[12], fe[12];
    FCFEMGatherElement(fem, c, ul, X, x);
    PetscCall((*fem->mat->rotation)(fem->mat, x, X, &fem->Dminv[9 * c], fem->vol[c], fe, &fem->Rcell[9 * c]));
    AddCell(fem, c, fe, fl);
  }
  PetscCall(VecRestoreArrayRead(fem->uloc, &ul));
  PetscCall(VecRestoreArray(fem->floc, &fl));
  PetscCall(VecZeroEntries(fem->fint));
  PetscCall(DMLocalToGlobal(m->dm, fem->floc, ADD_VALUES, fem->fint));
  PetscCall(FCFEMWarpVertexRotations(body, fem->Rvnow));
  PetscCall(FCFEMWarpUpdate(body, fem->Rvnow));
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
    AddCell(fem, c, ye, yl);
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
  if (fem->factorization == FC_FACTORIZATION_REUSE)
    PetscCall(KMultFree(body, x, y));
  else
    PetscCall(MatMult(fem->K, x, y));
  PetscFunctionReturn(0);
}

/* Today's A x = (1 + h alpha) M x + (h beta + h^2) K x (quasi-static: h^2 K x), as FCFEMFormA forms it */
PetscErrorCode FCFEMWarpAMult(Mat A, Vec x, Vec y)
{
  FCBody    body;
  FEM      *fem;
  PetscReal h;

  PetscFunctionBegin;
  PetscCall(MatShellGetContext(A, &body));
  fem = (FEM *)body->data;
  h   = body->h;
  PetscCall(KMultFree(body, x, y));
  if (body->quasistatic)
    PetscCall(VecScale(y, h * h));
  else {
    PetscCall(VecScale(y, h * fem->beta + h * h));
    PetscCall(MatMult(fem->M, x, fem->work));
    PetscCall(VecAXPY(y, 1.0 + h * fem->alpha, fem->work));
  }
  PetscFunctionReturn(0);
}

/* x (owned vertex blocks) = R_b x_b, or R_b^T x_b, with one 3x3 rotation per block (Q: fem->dR) */
PetscErrorCode FCFEMWarpTurn(const PetscReal R[], Vec x, PetscBool transpose)
{
  PetscScalar *a;
  PetscInt     n;

  PetscFunctionBegin;
  PetscCall(VecGetLocalSize(x, &n));
  PetscCall(VecGetArray(x, &a));
  for (PetscInt b = 0; b < n / 3; b++) {
    PetscReal y[3], z[3] = {PetscRealPart(a[3 * b]), PetscRealPart(a[3 * b + 1]), PetscRealPart(a[3 * b + 2])};
    if (transpose)
      FCMat3TVec(&R[9 * b], z, y);
    else
      FCMat3Vec(&R[9 * b], z, y);
    for (int d = 0; d < 3; d++) a[3 * b + d] = y[d];
  }
  PetscCall(VecRestoreArray(x, &a));
  PetscFunctionReturn(0);
}

/* The surface table of the compliance builder (after the builder exists): every rank's owned
   surface DOFs, sorted, and where each comes from in the gathered order */
PetscErrorCode FCFEMWarpSetUpContact(FCBody body)
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
  PetscCall(PetscMalloc5(fem->nsw + 1, &fem->swdof, fem->nsw + 1, &fem->swperm, 9 * fem->nsw + 1, &fem->swR,
                         9 * fem->nsurface + 1, &fem->swbuf, 9 * fem->nsw + 1, &fem->swall));
  PetscCallMPI(MPI_Allgatherv(fem->surface, n, MPIU_INT, fem->swdof, counts, displs, MPIU_INT, body->comm));
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
