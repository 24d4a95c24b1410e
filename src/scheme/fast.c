/* Algorithm 3: recursive corrective motion with the fast update of the constraint matrices.
   Notation (docs/method.md, section 2): per contact, d = p1 - p2 (world), F the
   world force on side 1, H the proximity maps (constant in the step), so that
       d(F) = d_free + h^2 W_H F,   W_H = sum_b H_b A_b^-1 H_b^T      (eq. 28, 31)
   W_H is built once per step by the bodies' compliance builders applied to the contact set in
   identity frames (3 rows x, y, z per contact). Newton iteration k:
       frames C_k from the proximity positions p_k (eq. 26)
       W_k = C_k W_H C_k^T                          MatMatMult (AIJ x dense), twice
       PGS on delta = q_k + W_k lambda, warm-started from C_k F_{k-1}; F_k = C_k^T lambda
       d_{k+1} = d_free + h^2 W_H F_k              MatMult (eq. 31)
   The normal of a contact against a kinematic shape is re-evaluated at p1 against the shape at
   its end-of-step pose, and so is its gap: q_n = gap(p1_k) - n_k . (d_k - d_free). Against FE
   triangles and rigid shapes the start-of-step normal is kept (their surfaces move with DOFs that
   the proximity points do not carry). The loop stops when frames and right-hand sides change by
   less than -newton_tol (0: always -newton_max_it). One correction per body at the end:
   dv = dv_free + h A^-1 H^T F.
   Options (besides -newton_max_it and -newton_tol, recursive.c):
     -fast_update newton|sweep   when the frames follow the forces: between contact solves, as the
                                 paper (default), or also after every sweep of the contact solver
                                 (beyond the paper: its closing remark; docs/accuracy.md measures it)
     the types of W_H (dense), the frames C (sparse) and the force vectors, host by default; on a
     GPU build -wh_mat_type seqdensecuda -frames_mat_type seqaijcusparse -contact_vec_type seqcuda
     (docs/gpu.md)
     -fast_wk_rows <bool>        where the contact solver splits its sweeps over the ranks
                                 (-pgs_ranks split, or auto from -pgs_split_min_rows rows), each
                                 rank forms and keeps only the block rows of W_k its sweeps read
                                 (M^2 / p values, formed p ways; src/contact/problem_rows.c);
                                 default true, host types only; false (and -fast_update sweep,
                                 whose solver does not split): W_k whole on every rank */
#include "schemeimpl.h"

typedef struct {
  char      wh_mat_type[FC_MAX_NAME], frames_mat_type[FC_MAX_NAME], vec_type[FC_MAX_NAME];
  PetscBool sweep_update; /* -fast_update sweep */
  PetscBool host;         /* W_H seqdense and C seqaij (the default types): W_k by CongruenceHost */
  PetscBool by_rows;      /* -fast_wk_rows */
  /* W_H and W_k kept from step to step, and what they were built from: W_H is built again only when
     a body's part changed (FCSchemeCompliance), W_k only when W_H or the frames did (on the host) */
  Mat        WH, Wk;
  PetscInt   wh_n3;        /* W_H's size: 3 x the contacts (h, in W_H, is fixed at set-up) */
  PetscBool  wh_valid;     /* it holds the last build, complete and checked */
  PetscInt   wh_state;     /* counts the builds of W_H that changed it */
  PetscInt   wk_state;     /* the W_H state W_k was formed from (-1: none) */
  PetscInt   wk_c0, wk_c1; /* the contacts whose rows W_k holds (all: 0, nc) */
  PetscInt   wk_nc;        /* the frames W_k was formed with: per contact its row, dim and n, t1, t2 */
  PetscInt  *wk_rows;
  PetscReal *wk_frames;
} Fast;

/* A matrix (ismat) or vector type given by an option is known to this PETSc build: a CUDA type in
   a host build is an input error at set-up, not at the first contact */
static PetscErrorCode CheckType(MPI_Comm comm, PetscBool ismat, const char type[], const char option[])
{
  Mat       A = NULL;
  Vec       v = NULL;
  PetscBool ok;

  PetscFunctionBegin;
  if (ismat) {
    PetscCall(MatCreate(PETSC_COMM_SELF, &A));
    PetscCall(MatSetSizes(A, 1, 1, 1, 1));
  } else {
    PetscCall(VecCreate(PETSC_COMM_SELF, &v));
    PetscCall(VecSetSizes(v, 1, 1));
  }
  PetscCall(PetscPushErrorHandler(PetscReturnErrorHandler, NULL));
  ok = (ismat ? MatSetType(A, type) : VecSetType(v, type)) ? PETSC_FALSE : PETSC_TRUE;
  PetscCall(PetscPopErrorHandler());
  PetscCall(MatDestroy(&A));
  PetscCall(VecDestroy(&v));
  PetscCheck(ok, comm, PETSC_ERR_USER_INPUT, "Unknown %s type '%s' in %s (in this PETSc build)",
             ismat ? "matrix" : "vector", type, option);
  PetscFunctionReturn(0);
}

static PetscErrorCode SetFromOptions_Fast(FCScheme scheme, PetscOptionItems *PetscOptionsObject)
{
  Fast *fast = (Fast *)scheme->data;

  PetscFunctionBegin;
  PetscCall(FCSchemeRecursiveSetFromOptions(scheme, PetscOptionsObject));
  PetscCall(PetscOptionsString("-wh_mat_type", "Matrix type of W_H (fast scheme)", NULL, fast->wh_mat_type,
                               fast->wh_mat_type, sizeof(fast->wh_mat_type), NULL));
  PetscCall(PetscOptionsString("-frames_mat_type", "Matrix type of the contact frames C (fast scheme)", NULL,
                               fast->frames_mat_type, fast->frames_mat_type, sizeof(fast->frames_mat_type), NULL));
  PetscCall(PetscOptionsString("-contact_vec_type", "Vector type of the contact forces (fast scheme)", NULL,
                               fast->vec_type, fast->vec_type, sizeof(fast->vec_type), NULL));
  {
    const char *when[] = {"newton", "sweep"};
    PetscInt    a      = fast->sweep_update ? 1 : 0;
    PetscCall(PetscOptionsEList("-fast_update",
                                "When the frames follow the forces: between contact solves, or after every sweep", NULL,
                                when, 2, when[a], &a, NULL));
    fast->sweep_update = a == 1 ? PETSC_TRUE : PETSC_FALSE;
  }
  PetscCall(PetscOptionsBool("-fast_wk_rows", "With split contact sweeps, each rank forms only its block rows of W_k",
                             NULL, fast->by_rows, &fast->by_rows, NULL));
  PetscCall(CheckType(scheme->comm, PETSC_TRUE, fast->wh_mat_type, "-wh_mat_type"));
  PetscCall(CheckType(scheme->comm, PETSC_TRUE, fast->frames_mat_type, "-frames_mat_type"));
  PetscCall(CheckType(scheme->comm, PETSC_FALSE, fast->vec_type, "-contact_vec_type"));
  {
    PetscBool dense, aij;
    PetscCall(PetscStrcmp(fast->wh_mat_type, MATSEQDENSE, &dense));
    PetscCall(PetscStrcmp(fast->frames_mat_type, MATSEQAIJ, &aij));
    fast->host = (PetscBool)(dense && aij);
  }
  PetscFunctionReturn(0);
}

/* The contacts whose rows of W_k this rank forms: its block when the contact solver splits the
   sweeps (and -fast_wk_rows, host types, no -fast_update sweep), else all */
static PetscErrorCode RowBlock(FCScheme scheme, const FCContactSet *set, PetscBool *rows, PetscInt *c0, PetscInt *c1)
{
  Fast     *fast = (Fast *)scheme->data;
  PetscInt *dims;

  PetscFunctionBegin;
  *rows = PETSC_FALSE;
  *c0   = 0;
  *c1   = set->n;
  /* -fast_update sweep: the solver calls back after every sweep, so it does not split (solver.c) */
  if (!fast->host || !fast->by_rows || fast->sweep_update) PetscFunctionReturn(0);
  PetscCall(PetscMalloc1(set->n + 1, &dims));
  for (PetscInt k = 0; k < set->n; k++) {
    PetscCheck(set->c[k].row == (k ? set->c[k - 1].row + set->c[k - 1].dim : 0), PETSC_COMM_SELF, PETSC_ERR_PLIB,
               "Contact %" PetscInt_FMT "'s rows do not follow the previous contact's", k);
    dims[k] = set->c[k].dim;
  }
  PetscCall(FCContactSolverRowBlock(scheme->solver, set->n, dims, rows, c0, c1));
  PetscCall(PetscFree(dims));
  PetscFunctionReturn(0);
}

/* W_H (3m)^2, U and U^T (M x 3m; general types only), W_k (M^2, or the largest rank's block rows);
   collective */
static PetscErrorCode Memory_Fast(FCScheme scheme, const FCContactSet *set, PetscReal *bytes, const char **what)
{
  Fast     *fast = (Fast *)scheme->data;
  PetscReal n3 = 3.0 * set->n, M = set->nrows, Mb = M;
  PetscBool rows;
  PetscInt  c0, c1;

  PetscFunctionBegin;
  PetscCall(RowBlock(scheme, set, &rows, &c0, &c1));
  if (rows) { /* the largest block of the ranks: every rank decides the same against the limit */
    Mb = (c1 < set->n ? set->c[c1].row : set->nrows) - (c0 < set->n ? set->c[c0].row : set->nrows);
    PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &Mb, 1, MPIU_REAL, MPIU_MAX, scheme->comm));
  }
  *bytes = 8.0 * (n3 * n3 + (fast->host ? 0.0 : 2.0 * M * n3) + M * Mb);
  *what  = rows ? "dense W_H and this rank's rows of W_k" : "dense W_H and W_k";
  PetscFunctionReturn(0);
}

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

/* What one step of the scheme works on */
typedef struct {
  FCScheme      scheme;
  FCContactSet *set, H; /* the contacts, and the same in identity frames (W_H's rows) */
  PetscInt      nc, n3, M;
  Mat           WHm, C, U, Ut, Wk;
  Vec           F, dvec, lam; /* world forces, W_H F, forces in the frames */
  PetscReal    *dfree, *d0, *q, *qold, *d;
  PetscInt      rebuilds; /* W_k rebuilt inside the contact solver (-fast_update sweep) */
  PetscBool     host;     /* W_H dense and C AIJ on the host: W_k by CongruenceHost */
  PetscBool     rows;     /* W_k holds the rows [rlo, rhi) of contacts [c0, c1) only (RowBlock) */
  PetscInt      c0, c1, rlo, rhi;
} FastStep;

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
  PetscInt            n3 = fs->n3, M = fs->M;

  PetscFunctionBegin;
  if (!fs->Wk) PetscCall(MatCreateSeqDense(PETSC_COMM_SELF, M, fs->rhi - fs->rlo, NULL, &fs->Wk));
  PetscCall(MatDenseGetArrayRead(fs->WHm, &wh));
  PetscCall(MatDenseGetArrayWrite(fs->Wk, &wk));
  for (PetscInt kj = fs->c0; kj < fs->c1; kj++) {
    const FCContact *cj     = &set->c[kj];
    const PetscReal *fj[3]  = {cj->n, cj->t1, cj->t2};
    const PetscReal *col[3] = {wh + (3 * kj) * n3, wh + (3 * kj + 1) * n3, wh + (3 * kj + 2) * n3};
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
   CongruenceHost, for a W_k that holds only this rank's rows */
static void NormalComplianceFromWH(FastStep *fs, const PetscScalar *wh)
{
  FCContactSet *set = fs->set;
  PetscInt      n3  = fs->n3;
  for (PetscInt k = 0; k < fs->nc; k++) {
    FCContact       *c      = &set->c[k];
    const PetscReal *col[3] = {wh + (3 * k) * n3, wh + (3 * k + 1) * n3, wh + (3 * k + 2) * n3};
    PetscReal        p[3];
    for (int i = 0; i < 3; i++)
      p[i] = col[0][3 * k + i] * c->n[0] + col[1][3 * k + i] * c->n[1] + col[2][3 * k + i] * c->n[2];
    c->wnn = c->n[0] * p[0] + c->n[1] * p[1] + c->n[2] * p[2];
  }
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
static PetscErrorCode RebuildW(FastStep *fs)
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
static PetscErrorCode ProximityUpdate(FastStep *fs, const PetscReal lambda[])
{
  PetscScalar       *l;
  const PetscScalar *dv;

  PetscFunctionBegin;
  PetscCall(VecGetArray(fs->lam, &l));
  for (PetscInt r = 0; r < fs->M; r++) l[r] = lambda[r];
  PetscCall(VecRestoreArray(fs->lam, &l));
  PetscCall(MatMultTranspose(fs->C, fs->lam, fs->F));
  PetscCall(MatMult(fs->WHm, fs->F, fs->dvec));
  PetscCall(VecGetArrayRead(fs->dvec, &dv));
  for (PetscInt i = 0; i < fs->n3; i++) fs->d[i] = fs->dfree[i] + PetscRealPart(dv[i]);
  PetscCall(VecRestoreArrayRead(fs->dvec, &dv));
  PetscFunctionReturn(0);
}

/* lambda = C_k F: the world forces in the current frames */
static PetscErrorCode ForcesInFrames(FastStep *fs, PetscReal lambda[])
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
static PetscErrorCode UpdateAfterSweep(void *ctx, FCContactProblem prob, PetscReal r[], PetscBool *changed)
{
  FastStep *fs = (FastStep *)ctx;
  PetscReal change, dq = 0.0, qs = 0.0;

  PetscFunctionBegin;
  *changed = PETSC_FALSE;
  PetscCall(ProximityUpdate(fs, r));
  PetscCall(PetscArraycpy(fs->qold, fs->q, fs->M));
  PetscCall(FCSchemeLinearize(fs->scheme, fs->set, fs->dfree, fs->d0, fs->d, fs->q, &change));
  for (PetscInt k = 0; k < fs->M; k++) {
    dq = PetscMax(dq, PetscAbsReal(fs->q[k] - fs->qold[k]));
    qs = PetscMax(qs, PetscAbsReal(fs->q[k]));
  }
  if (change == 0.0 && dq <= PETSC_MACHINE_EPSILON * qs) PetscFunctionReturn(0);
  if (change > 0.0) {
    const PetscScalar *w;
    PetscCall(RebuildW(fs));
    PetscCall(MatDenseGetArrayRead(fs->Wk, &w)); /* the same array: MAT_REUSE_MATRIX */
    FCContactSetNormalCompliance(fs->set, w);
    PetscCall(MatDenseRestoreArrayRead(fs->Wk, &w));
    PetscCall(ForcesInFrames(fs, r));
    fs->rebuilds++;
  }
  PetscCall(FCContactProblemSetRHS(prob, fs->q));
  *changed = PETSC_TRUE;
  PetscFunctionReturn(0);
}

static PetscErrorCode Solve_Fast(FCScheme scheme, FCContactSet *set, const FCContactSet *previous, FCSchemeStats *st)
{
  Fast            *fast = (Fast *)scheme->data;
  FastStep         fs   = {0};
  PetscInt         nc = set->n, n3 = 3 * set->n, M = set->nrows, *dims;
  PetscReal       *WH, *mu, *lambda, change = 0.0;
  FCContactProblem prob;
  PetscBool        conv;

  PetscFunctionBegin;
  fs.scheme = scheme;
  fs.set    = set;
  fs.nc     = nc;
  fs.n3     = n3;
  fs.M      = M;
  fs.host   = fast->host;
  PetscCall(RowBlock(scheme, set, &fs.rows, &fs.c0, &fs.c1));
  fs.rlo = fs.c0 < nc ? set->c[fs.c0].row : M;
  fs.rhi = fs.c1 < nc ? set->c[fs.c1].row : M;
  /* W_H once per step: the bodies' builders on the contacts in identity frames */
  PetscCall(FCContactSetCopy(set, &fs.H));
  for (PetscInt k = 0; k < nc; k++) {
    FCContact *c = &fs.H.c[k];
    for (int i = 0; i < 3; i++) c->n[i] = c->t1[i] = c->t2[i] = 0.0;
    c->n[0] = c->t1[1] = c->t2[2] = 1.0;
    c->dim                        = 3;
    c->row                        = 3 * k;
  }
  fs.H.nrows = n3;
  if (!fast->WH || fast->wh_n3 != n3) {
    PetscCall(MatDestroy(&fast->WH));
    PetscCall(MatDestroy(&fast->Wk));
    PetscCall(MatCreate(PETSC_COMM_SELF, &fast->WH));
    PetscCall(MatSetSizes(fast->WH, n3, n3, n3, n3));
    PetscCall(MatSetType(fast->WH, fast->wh_mat_type));
    PetscCall(MatSetUp(fast->WH));
    fast->wh_n3    = n3;
    fast->wh_valid = PETSC_FALSE;
  }
  fs.WHm = fast->WH;
  if (fast->Wk) { /* M x M, or M x its block rows: the rows of the frames (3 per contact with friction, else 1) */
    PetscInt m, mb;
    PetscCall(MatGetSize(fast->Wk, &m, &mb));
    if (m != M || mb != fs.rhi - fs.rlo || fast->wk_c0 != fs.c0 || fast->wk_c1 != fs.c1) {
      PetscCall(MatDestroy(&fast->Wk));
      fast->wk_state = -1;
    }
  }
  if (fast->host) fs.Wk = fast->Wk; /* formed again by RebuildW when W_H or the frames changed */
  {                                 /* W_H: kept when every body's part is the last one (on the host) */
    PetscBool kept = (PetscBool)(fast->host && fast->wh_valid);
    fast->wh_valid = PETSC_FALSE;
    PetscCall(MatDenseGetArrayWrite(fs.WHm, &WH)); /* symmetric: row/column-major alike */
    PetscCall(FCPhaseBegin(FC_PHASE_COMPLIANCE));
    PetscCall(FCSchemeCompliance(scheme, &fs.H, WH, &kept));
    PetscCall(FCPhaseEnd(FC_PHASE_COMPLIANCE));
    PetscCall(MatDenseRestoreArrayWrite(fs.WHm, &WH));
    fast->wh_valid = PETSC_TRUE;
    if (!kept) fast->wh_state++;
  }

  PetscCall(PetscMalloc6(n3, &fs.dfree, n3, &fs.d0, M, &fs.q, M, &fs.qold, nc, &mu, nc, &dims));
  PetscCall(PetscMalloc2(M, &lambda, n3, &fs.d));
  /* first linearization: the frames of the collision detection, gaps at the start of the step */
  FCSchemeStartLinearization(set, fs.dfree, fs.d0, fs.q, mu, dims);
  PetscCall(VecCreate(PETSC_COMM_SELF, &fs.F));
  PetscCall(VecSetSizes(fs.F, n3, n3));
  PetscCall(VecSetType(fs.F, fast->vec_type));
  PetscCall(VecDuplicate(fs.F, &fs.dvec));
  PetscCall(VecCreate(PETSC_COMM_SELF, &fs.lam));
  PetscCall(VecSetSizes(fs.lam, M, M));
  PetscCall(VecSetType(fs.lam, fast->vec_type));
  { /* warm start: the previous step's force of the same contact, in the world frame */
    PetscScalar *f;
    PetscCall(VecGetArray(fs.F, &f));
    for (PetscInt k = 0; k < nc; k++) {
      PetscReal Fw[3];
      FCContactPreviousForce(previous, &set->c[k], Fw);
      for (int i = 0; i < 3; i++) f[3 * k + i] = Fw[i];
    }
    PetscCall(VecRestoreArray(fs.F, &f));
  }
  PetscCall(MatCreate(PETSC_COMM_SELF, &fs.C));
  PetscCall(MatSetSizes(fs.C, M, n3, M, n3));
  PetscCall(MatSetType(fs.C, fast->frames_mat_type));
  PetscCall(MatSeqAIJSetPreallocation(fs.C, 3, NULL));
  PetscCall(MatSetOption(fs.C, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_FALSE));
  if (fast->sweep_update) PetscCall(FCContactSolverSetUpdate(scheme->solver, UpdateAfterSweep, &fs));

  for (PetscInt it = 1; it <= scheme->newton_max_it; it++) {
    const PetscScalar *w;
    PetscInt           sweeps;
    PetscCall(PetscLogEventBegin(FC_EVENT_NEWTON, 0, 0, 0, 0));
    PetscCall(FCPhaseBegin(FC_PHASE_REBUILD_W));
    PetscCall(RebuildW(&fs));
    PetscCall(FCPhaseEnd(FC_PHASE_REBUILD_W));
    /* PGS on the total force, warm-started from C_k F_{k-1} */
    PetscCall(FCPhaseBegin(FC_PHASE_CONTACT_SOLVE));
    PetscCall(ForcesInFrames(&fs, lambda));
    PetscCall(MatDenseGetArrayRead(fs.Wk, &w)); /* symmetric: column-major = row-major */
    if (fs.rows) {
      const PetscScalar *wh;
      PetscCall(FCContactProblemCreateDenseRows(scheme->comm, nc, dims, mu, fs.c0, fs.c1, w, fs.q, &prob));
      PetscCall(MatDenseGetArrayRead(fs.WHm, &wh));
      NormalComplianceFromWH(&fs, wh);
      PetscCall(MatDenseRestoreArrayRead(fs.WHm, &wh));
    } else {
      PetscCall(FCContactProblemCreateDense(nc, dims, mu, w, fs.q, &prob));
      FCContactSetNormalCompliance(set, w);
    }
    PetscCall(FCSchemeContactSolve(scheme, set, prob, lambda));
    PetscCall(FCContactSolverGetConvergence(scheme->solver, &sweeps, &st->residual, &conv));
    PetscCall(FCContactProblemDestroy(&prob));
    PetscCall(MatDenseRestoreArrayRead(fs.Wk, &w));
    st->sweeps += sweeps;
    PetscCall(FCPhaseEnd(FC_PHASE_CONTACT_SOLVE));
    FCContactSetStoreForces(set, lambda); /* in the frames they were solved in */
    PetscCall(FCPhaseBegin(FC_PHASE_PROXIMITY));
    PetscCall(ProximityUpdate(&fs, lambda));
    PetscCall(FCPhaseEnd(FC_PHASE_PROXIMITY));
    st->newton = it;
    PetscCall(PetscLogEventEnd(FC_EVENT_NEWTON, 0, 0, 0, 0));
    if (it == scheme->newton_max_it) break;
    /* frames and right-hand side at the new proximity positions */
    PetscCall(PetscArraycpy(fs.qold, fs.q, M));
    PetscCall(FCSchemeLinearize(scheme, set, fs.dfree, fs.d0, fs.d, fs.q, &change));
    if (FCSchemeConverged(scheme, M, fs.q, fs.qold, change)) break;
  }
  if (fast->sweep_update) PetscCall(FCContactSolverSetUpdate(scheme->solver, NULL, NULL));
  FCContactSetUpdateStates(set);
  /* one correction per body: dv = dv_free + h A^-1 H^T F (identity frames: lambda = F) */
  PetscCall(FCPhaseBegin(FC_PHASE_CORRECTION));
  {
    const PetscScalar *f;
    PetscReal         *Fw;
    PetscCall(PetscMalloc1(n3, &Fw));
    PetscCall(VecGetArrayRead(fs.F, &f));
    for (PetscInt i = 0; i < n3; i++) Fw[i] = PetscRealPart(f[i]);
    PetscCall(VecRestoreArrayRead(fs.F, &f));
    PetscCall(FCSchemeCorrect(scheme, &fs.H, Fw));
    PetscCall(PetscFree(Fw));
  }
  PetscCall(FCPhaseEnd(FC_PHASE_CORRECTION));
  PetscCall(MatDestroy(&fs.C));
  PetscCall(MatDestroy(&fs.U));
  PetscCall(MatDestroy(&fs.Ut));
  if (fast->host) { /* kept with W_H */
    fast->Wk    = fs.Wk;
    fast->wk_c0 = fs.c0;
    fast->wk_c1 = fs.c1;
  } else
    PetscCall(MatDestroy(&fs.Wk));
  PetscCall(VecDestroy(&fs.F));
  PetscCall(VecDestroy(&fs.dvec));
  PetscCall(VecDestroy(&fs.lam));
  PetscCall(PetscFree6(fs.dfree, fs.d0, fs.q, fs.qold, mu, dims));
  PetscCall(PetscFree2(lambda, fs.d));
  PetscCall(FCContactSetDestroy(&fs.H));
  PetscFunctionReturn(0);
}

static PetscErrorCode Destroy_Fast(FCScheme scheme)
{
  Fast *fast = (Fast *)scheme->data;

  PetscFunctionBegin;
  PetscCall(MatDestroy(&fast->WH));
  PetscCall(MatDestroy(&fast->Wk));
  PetscCall(PetscFree2(fast->wk_rows, fast->wk_frames));
  PetscCall(PetscFree(scheme->data));
  PetscFunctionReturn(0);
}

PetscErrorCode FCSchemeCreate_Fast(FCScheme scheme)
{
  Fast *fast;

  PetscFunctionBegin;
  PetscCall(PetscNew(&fast));
  PetscCall(PetscStrncpy(fast->wh_mat_type, MATSEQDENSE, sizeof(fast->wh_mat_type)));
  PetscCall(PetscStrncpy(fast->frames_mat_type, MATSEQAIJ, sizeof(fast->frames_mat_type)));
  PetscCall(PetscStrncpy(fast->vec_type, VECSEQ, sizeof(fast->vec_type)));
  fast->host                 = PETSC_TRUE; /* the default types above */
  fast->by_rows              = PETSC_TRUE;
  fast->wk_state             = -1;
  scheme->data               = fast;
  scheme->ops.setfromoptions = SetFromOptions_Fast;
  scheme->ops.memory         = Memory_Fast;
  scheme->ops.solve          = Solve_Fast;
  scheme->ops.destroy        = Destroy_Fast;
  PetscFunctionReturn(0);
}
