/* The products of Algorithm 3 (eq. 28-31) on W_H, the compliance in the contacts' identity frames:
   W_k = C_k W_H C_k^T for the frames of iteration k, the proximity update d = d_free + h^2 W_H C_k^T
   lambda, and the forces between the world and the frames; with -fast_update sweep, the update after
   every sweep of the contact solver. */
#include "fastimpl.h"
#include <petscblaslapack.h>

/* C (rows x 3 nc, AIJ): the frame rows of every contact */
static PetscErrorCode AssembleFrames(const FCContactSet *set, Mat C)
{
  PetscFunctionBegin;
  PetscCall(MatZeroEntries(C));
  for (PetscInt k = 0; k < set->n; k++) {
    const FCContact *c       = &set->c[k];
    PetscInt         cols[3] = {3 * k, 3 * k + 1, 3 * k + 2};
    for (PetscInt a = 0; a < c->dim; a++) {
      const PetscReal *f   = a == 0 ? c->n : (a == 1 ? c->t1 : c->t2);
      PetscInt         row = c->row + a;
      PetscCall(MatSetValues(C, 1, &row, 3, cols, f, INSERT_VALUES));
    }
  }
  PetscCall(MatAssemblyBegin(C, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(C, MAT_FINAL_ASSEMBLY));
  PetscFunctionReturn(0);
}

/* W_k = C_k W_H C_k^T on the host, block by block: C_k is block diagonal (contact I's d_I frame
   rows act on its 3 columns), so W_k[I,J] = F_I W_H[I,J] F_J^T for the 3 x 3 blocks of W_H. One
   pass over W_H (read) and W_k (written), both column-major; the two general products below
   (MatMatMult, then a transpose) stream a dense matrix of this size five times. By rows: only the
   columns J of contacts [c0, c1), which are W_k's rows of those contacts (W_k is symmetric), M x
   (rhi - rlo), the layout of a problem by rows. */
static PetscErrorCode CongruenceHost(FastStep *fs)
{
  const FCContactSet *set = fs->set;
  const PetscScalar  *wh;
  PetscScalar        *wk;
  PetscInt            n3 = fs->n3, M = fs->M, off = fs->dist ? 3 * fs->c0 : 0; /* W_H's first column held */

  PetscFunctionBegin;
  if (!fs->Wk) PetscCall(MatCreateSeqDense(PETSC_COMM_SELF, M, fs->rhi - fs->rlo, NULL, &fs->Wk));
  PetscCall(MatDenseGetArrayRead(fs->WHm, &wh));
  PetscCall(MatDenseGetArrayWrite(fs->Wk, &wk));
  for (PetscInt kj = fs->c0; kj < fs->c1; kj++) {
    const FCContact *cj     = &set->c[kj];
    const PetscReal *fj[3]  = {cj->n, cj->t1, cj->t2};
    const PetscReal *col[3] = {wh + (3 * kj - off) * n3, wh + (3 * kj + 1 - off) * n3, wh + (3 * kj + 2 - off) * n3};
    PetscScalar     *out[3];
    for (PetscInt b = 0; b < cj->dim; b++) out[b] = wk + (cj->row + b - fs->rlo) * M;
    for (PetscInt ki = 0; ki < fs->nc; ki++) {
      const FCContact *ci    = &set->c[ki];
      const PetscReal *fi[3] = {ci->n, ci->t1, ci->t2};
      PetscReal        p[3][3]; /* p[b][i] = (W_H[ki,kj] F_kj^T)_ib */
      for (PetscInt b = 0; b < cj->dim; b++)
        for (int i = 0; i < 3; i++)
          p[b][i] = col[0][3 * ki + i] * fj[b][0] + col[1][3 * ki + i] * fj[b][1] + col[2][3 * ki + i] * fj[b][2];
      for (PetscInt b = 0; b < cj->dim; b++)
        for (PetscInt a = 0; a < ci->dim; a++)
          out[b][ci->row + a] = fi[a][0] * p[b][0] + fi[a][1] * p[b][1] + fi[a][2] * p[b][2];
    }
  }
  PetscCall(MatDenseRestoreArrayWrite(fs->Wk, &wk));
  PetscCall(MatDenseRestoreArrayRead(fs->WHm, &wh));
  { /* per block pair: 5 flops for each of the 3 d_J entries of p, 5 for each of the d_I d_J outputs */
    PetscLogDouble rows = (PetscLogDouble)(fs->rhi - fs->rlo), cols = (PetscLogDouble)M;
    PetscCall(PetscLogFlops(5.0 * rows * (3.0 * fs->nc + cols)));
  }
  PetscFunctionReturn(0);
}

/* The normal compliance of every contact, n^T W_H[k,k] n: W_k's diagonal by the arithmetic of
   CongruenceHost, for a W_k that holds only this rank's rows (from a W_H held by rows, this rank's
   contacts', summed over the ranks) */
PetscErrorCode FCFastNormalComplianceFromWH(FastStep *fs, const PetscScalar *wh)
{
  FCContactSet *set = fs->set;
  PetscInt      n3 = fs->n3, k0 = fs->dist ? fs->c0 : 0, k1 = fs->dist ? fs->c1 : fs->nc, off = 3 * k0;
  PetscReal    *w = NULL;

  PetscFunctionBegin;
  if (fs->dist) PetscCall(PetscCalloc1(fs->nc + 1, &w));
  for (PetscInt k = k0; k < k1; k++) {
    FCContact       *c      = &set->c[k];
    const PetscReal *col[3] = {wh + (3 * k - off) * n3, wh + (3 * k + 1 - off) * n3, wh + (3 * k + 2 - off) * n3};
    PetscReal        p[3];
    for (int i = 0; i < 3; i++)
      p[i] = col[0][3 * k + i] * c->n[0] + col[1][3 * k + i] * c->n[1] + col[2][3 * k + i] * c->n[2];
    c->wnn = c->n[0] * p[0] + c->n[1] * p[1] + c->n[2] * p[2];
    if (w) w[k] = c->wnn;
  }
  if (fs->dist) {
    PetscCallMPI(MPIU_Allreduce(MPI_IN_PLACE, w, fs->nc, MPIU_REAL, MPIU_SUM, fs->scheme->comm));
    for (PetscInt k = 0; k < fs->nc; k++) set->c[k].wnn = w[k];
    PetscCall(PetscFree(w));
  }
  PetscFunctionReturn(0);
}

/* Whether W_k was formed from the current W_H with the frames of the set (the host's kept W_k);
   else records them for the W_k about to be formed */
static PetscErrorCode SameFrames(Fast *fast, const FCContactSet *set, PetscBool *same)
{
  PetscInt nc = set->n;

  PetscFunctionBegin;
  *same = (PetscBool)(fast->wk_state == fast->wh_state && fast->wk_nc == nc);
  for (PetscInt k = 0; k < nc && *same; k++) {
    const FCContact *c = &set->c[k];
    *same              = (PetscBool)(fast->wk_rows[2 * k] == c->row && fast->wk_rows[2 * k + 1] == c->dim);
    for (int i = 0; i < 3 && *same; i++)
      *same = (PetscBool)(fast->wk_frames[9 * k + i] == c->n[i] && fast->wk_frames[9 * k + 3 + i] == c->t1[i] &&
                          fast->wk_frames[9 * k + 6 + i] == c->t2[i]);
  }
  if (*same) PetscFunctionReturn(0);
  if (fast->wk_nc != nc) {
    PetscCall(PetscFree2(fast->wk_rows, fast->wk_frames));
    PetscCall(PetscMalloc2(2 * nc + 1, &fast->wk_rows, 9 * nc + 1, &fast->wk_frames));
    fast->wk_nc = nc;
  }
  for (PetscInt k = 0; k < nc; k++) {
    const FCContact *c       = &set->c[k];
    fast->wk_rows[2 * k]     = c->row;
    fast->wk_rows[2 * k + 1] = c->dim;
    for (int i = 0; i < 3; i++) {
      fast->wk_frames[9 * k + i]     = c->n[i];
      fast->wk_frames[9 * k + 3 + i] = c->t1[i];
      fast->wk_frames[9 * k + 6 + i] = c->t2[i];
    }
  }
  fast->wk_state = fast->wh_state;
  PetscFunctionReturn(0);
}

/* W_k = C_k W_H C_k^T for the frames of the contact set: blockwise on the host (the default types;
   not at all when neither W_H nor the frames changed since the last one, as for a linear body on a
   kinematic plane: the frames stay those of the plane), else U = C W_H (AIJ x dense), W_k = C U^T,
   on the types of -wh_mat_type and -frames_mat_type */
PetscErrorCode FCFastRebuildW(FastStep *fs)
{
  PetscFunctionBegin;
  PetscCall(AssembleFrames(fs->set, fs->C));
  if (fs->host) {
    Fast     *fast = (Fast *)fs->scheme->data;
    PetscBool same;
    PetscCall(SameFrames(fast, fs->set, &same));
    if (same && fs->Wk) PetscFunctionReturn(0);
    PetscCall(PetscLogEventBegin(FC_EVENT_CONGRUENCE_WK, 0, 0, 0, 0));
    PetscCall(CongruenceHost(fs));
    PetscCall(PetscLogEventEnd(FC_EVENT_CONGRUENCE_WK, 0, 0, 0, 0));
    PetscFunctionReturn(0);
  }
  PetscCall(MatMatMult(fs->C, fs->WHm, fs->U ? MAT_REUSE_MATRIX : MAT_INITIAL_MATRIX, PETSC_DEFAULT, &fs->U));
  PetscCall(MatTranspose(fs->U, fs->Ut ? MAT_REUSE_MATRIX : MAT_INITIAL_MATRIX, &fs->Ut));
  PetscCall(MatMatMult(fs->C, fs->Ut, fs->Wk ? MAT_REUSE_MATRIX : MAT_INITIAL_MATRIX, PETSC_DEFAULT, &fs->Wk));
  PetscFunctionReturn(0);
}

/* F = C_k^T lambda and the proximity update d = d_free + h^2 W_H F (eq. 31) */
PetscErrorCode FCFastProximityUpdate(FastStep *fs, const PetscReal lambda[])
{
  PetscScalar       *l;
  const PetscScalar *dv;

  PetscFunctionBegin;
  PetscCall(VecGetArray(fs->lam, &l));
  for (PetscInt r = 0; r < fs->M; r++) l[r] = lambda[r];
  PetscCall(VecRestoreArray(fs->lam, &l));
  PetscCall(MatMultTranspose(fs->C, fs->lam, fs->F));
  if (fs->dist) { /* W_H F = sum over the ranks of W_H(:, own) F(own), W_H(:, own) = W_H(own, :)^T */
    const PetscScalar *f, *wh;
    PetscScalar       *d;
    PetscBLASInt       n, m, one = 1;
    PetscScalar        alpha = 1.0, beta = 0.0;
    PetscCall(PetscBLASIntCast(fs->n3, &n));
    PetscCall(PetscBLASIntCast(3 * (fs->c1 - fs->c0), &m));
    PetscCall(VecGetArrayRead(fs->F, &f));
    PetscCall(VecGetArrayWrite(fs->dvec, &d));
    PetscCall(MatDenseGetArrayRead(fs->WHm, &wh));
    if (m)
      PetscCallBLAS("BLASgemv", BLASgemv_("N", &n, &m, &alpha, wh, &n, f + 3 * fs->c0, &one, &beta, d, &one));
    else
      for (PetscInt i = 0; i < fs->n3; i++) d[i] = 0.0;
    PetscCall(MatDenseRestoreArrayRead(fs->WHm, &wh));
    PetscCall(VecRestoreArrayRead(fs->F, &f));
    PetscCallMPI(MPIU_Allreduce(MPI_IN_PLACE, d, (PetscMPIInt)fs->n3, MPIU_SCALAR, MPIU_SUM, fs->scheme->comm));
    PetscCall(VecRestoreArrayWrite(fs->dvec, &d));
  } else
    PetscCall(MatMult(fs->WHm, fs->F, fs->dvec));
  PetscCall(VecGetArrayRead(fs->dvec, &dv));
  for (PetscInt i = 0; i < fs->n3; i++) fs->d[i] = fs->dfree[i] + PetscRealPart(dv[i]);
  PetscCall(VecRestoreArrayRead(fs->dvec, &dv));
  PetscFunctionReturn(0);
}

/* lambda = C_k F: the world forces in the current frames */
PetscErrorCode FCFastForcesInFrames(FastStep *fs, PetscReal lambda[])
{
  const PetscScalar *l;

  PetscFunctionBegin;
  PetscCall(MatMult(fs->C, fs->F, fs->lam));
  PetscCall(VecGetArrayRead(fs->lam, &l));
  for (PetscInt r = 0; r < fs->M; r++) lambda[r] = PetscRealPart(l[r]);
  PetscCall(VecRestoreArrayRead(fs->lam, &l));
  PetscFunctionReturn(0);
}

/* -fast_update sweep: after every sweep of the contact solver, the proximity update and the
   re-linearization at the sweep's forces; when the frames moved, W_k is rebuilt in place (the
   problem reads W_k's array) and the forces are carried to the new frames (the paper's closing
   remark: the fast update is cheap enough to refresh the directions inside the solve) */
PetscErrorCode FCFastUpdateAfterSweep(void *ctx, FCContactProblem prob, PetscReal r[], PetscBool *changed)
{
  FastStep *fs = (FastStep *)ctx;
  PetscReal change, dq = 0.0, qs = 0.0;

  PetscFunctionBegin;
  *changed = PETSC_FALSE;
  PetscCall(FCFastProximityUpdate(fs, r));
  PetscCall(PetscArraycpy(fs->qold, fs->q, fs->M));
  PetscCall(FCSchemeLinearize(fs->scheme, fs->set, fs->dfree, fs->d0, fs->d, fs->q, &change));
  for (PetscInt k = 0; k < fs->M; k++) {
    dq = PetscMax(dq, PetscAbsReal(fs->q[k] - fs->qold[k]));
    qs = PetscMax(qs, PetscAbsReal(fs->q[k]));
  }
  if (change == 0.0 && dq <= PETSC_MACHINE_EPSILON * qs) PetscFunctionReturn(0);
  if (change > 0.0) {
    const PetscScalar *w;
    PetscCall(FCFastRebuildW(fs));
    PetscCall(MatDenseGetArrayRead(fs->Wk, &w)); /* the same array: MAT_REUSE_MATRIX */
    FCContactSetNormalCompliance(fs->set, w);
    PetscCall(MatDenseRestoreArrayRead(fs->Wk, &w));
    PetscCall(FCFastForcesInFrames(fs, r));
    fs->rebuilds++;
  }
  PetscCall(FCContactProblemSetRHS(prob, fs->q));
  *changed = PETSC_TRUE;
  PetscFunctionReturn(0);
}
