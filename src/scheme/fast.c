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
   Distributed (-fast_distributed_contacts, on several ranks with split contact sweeps): each rank
   holds only the rows of W_H of its block of contacts (the block whose rows of W_k it forms and
   whose sweeps it runs), the builders form only those rows (FCRows), and the proximity update sums
   the ranks' W_H(rows, :)^T F(rows) (one reduction of 3 m values): no (3m)^2 array on any rank.
   Options (-fast_update, -fast_wk_rows, -fast_distributed_contacts, the matrix and vector types -wh_mat_type,
   -frames_mat_type, -contact_vec_type; -newton_max_it and -newton_tol in recursive.c): their help strings below and
   docs/options.md. */
#include "fastimpl.h"

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
    PetscCall(FCOptionsEList(PetscOptionsObject, "-fast_update",
                             "When the frames follow the forces: between contact solves, or after every sweep", when, 2,
                             &a, NULL));
    fast->sweep_update = a == 1 ? PETSC_TRUE : PETSC_FALSE;
  }
  PetscCall(PetscOptionsBool("-fast_wk_rows", "With split contact sweeps, each rank forms only its block rows of W_k",
                             NULL, fast->by_rows, &fast->by_rows, NULL));
  PetscCall(
      FCOptionsIntRange(PetscOptionsObject, "-fast_distributed_contacts",
                        "From this many contacts, with split contact sweeps on several ranks, each rank holds only "
                        "its block rows of W_H (0: always)",
                        0, PETSC_MAX_INT, &fast->dist_min, NULL));
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

/* Whether W_H is held by block rows: several ranks, host types, split sweeps, enough contacts */
static PetscBool Distributed(FCScheme scheme, const FCContactSet *set, PetscBool rows)
{
  Fast       *fast = (Fast *)scheme->data;
  PetscMPIInt size;

  if (MPI_Comm_size(scheme->comm, &size)) return PETSC_FALSE;
  return (PetscBool)(size > 1 && rows && fast->host && set->n >= fast->dist_min);
}

/* W_H (3m)^2 or its block rows, U and U^T (M x 3m; general types only), W_k (M^2, or the largest
   rank's block rows); collective */
static PetscErrorCode Memory_Fast(FCScheme scheme, const FCContactSet *set, PetscReal *bytes, const char **what)
{
  Fast     *fast = (Fast *)scheme->data;
  PetscReal n3 = 3.0 * set->n, M = set->nrows, Mb = M;
  PetscBool rows;
  PetscInt  c0, c1;

  PetscFunctionBegin;
  PetscReal nh = n3; /* W_H's columns held */
  PetscCall(RowBlock(scheme, set, &rows, &c0, &c1));
  if (rows) { /* the largest block of the ranks: every rank decides the same against the limit */
    PetscReal b[2];
    b[0] = (c1 < set->n ? set->c[c1].row : set->nrows) - (c0 < set->n ? set->c[c0].row : set->nrows);
    b[1] = 3.0 * (c1 - c0);
    PetscCall(MPIU_Allreduce(MPI_IN_PLACE, b, 2, MPIU_REAL, MPIU_MAX, scheme->comm));
    Mb = b[0];
    if (Distributed(scheme, set, rows)) nh = b[1];
  }
  *bytes = 8.0 * (n3 * nh + (fast->host ? 0.0 : 2.0 * M * n3) + M * Mb);
  *what  = rows ? (nh < n3 ? "this rank's rows of W_H and of W_k" : "dense W_H and this rank's rows of W_k")
                : "dense W_H and W_k";
  PetscFunctionReturn(0);
}

/* W_H once per step: the bodies' builders on the contacts in identity frames (fs->H), kept from the last step
   when every body's part is the last one (on the host); the W_k kept with it only if its rows still fit */
static PetscErrorCode BuildWH(FastStep *fs)
{
  FCScheme   scheme = fs->scheme;
  Fast      *fast   = (Fast *)scheme->data;
  PetscInt   nc = fs->nc, n3 = fs->n3, M = fs->M, nh = fs->dist ? 3 * (fs->c1 - fs->c0) : n3;
  PetscReal *WH;
  FCRows     rows = {3 * fs->c0, 3 * fs->c1};

  PetscFunctionBegin;
  PetscCall(FCContactSetCopy(fs->set, &fs->H));
  for (PetscInt k = 0; k < nc; k++) {
    FCContact *c = &fs->H.c[k];
    for (int i = 0; i < 3; i++) c->n[i] = c->t1[i] = c->t2[i] = 0.0;
    c->n[0] = c->t1[1] = c->t2[2] = 1.0;
    c->dim                        = 3;
    c->row                        = 3 * k;
  }
  fs->H.nrows = n3;
  if (!fast->WH || fast->wh_n3 != n3 || fast->wh_c0 != (fs->dist ? fs->c0 : 0) ||
      fast->wh_c1 != (fs->dist ? fs->c1 : nc)) {
    PetscCall(MatDestroy(&fast->WH));
    PetscCall(MatDestroy(&fast->Wk));
    PetscCall(MatCreate(PETSC_COMM_SELF, &fast->WH));
    PetscCall(MatSetSizes(fast->WH, n3, nh, n3, nh));
    PetscCall(MatSetType(fast->WH, fast->wh_mat_type));
    PetscCall(MatSetUp(fast->WH));
    fast->wh_n3    = n3;
    fast->wh_c0    = fs->dist ? fs->c0 : 0;
    fast->wh_c1    = fs->dist ? fs->c1 : nc;
    fast->wh_valid = PETSC_FALSE;
  }
  fs->WHm = fast->WH;
  if (fast->Wk) { /* M x M, or M x its block rows: the rows of the frames (3 per contact with friction, else 1) */
    PetscInt m, mb;
    PetscCall(MatGetSize(fast->Wk, &m, &mb));
    if (m != M || mb != fs->rhi - fs->rlo || fast->wk_c0 != fs->c0 || fast->wk_c1 != fs->c1) {
      PetscCall(MatDestroy(&fast->Wk));
      fast->wk_state = -1;
    }
  }
  if (fast->host) fs->Wk = fast->Wk; /* formed again by RebuildW when W_H or the frames changed */
  {                                  /* W_H: kept when every body's part is the last one (on the host) */
    PetscBool kept = (PetscBool)(fast->host && fast->wh_valid);
    fast->wh_valid = PETSC_FALSE;
    PetscCall(MatDenseGetArrayWrite(fs->WHm, &WH)); /* symmetric: row/column-major alike */
    PetscCall(FCPhaseBegin(FC_PHASE_COMPLIANCE));
    PetscCall(FCSchemeCompliance(scheme, &fs->H, fs->dist ? &rows : NULL, WH, &kept));
    PetscCall(FCPhaseEnd(FC_PHASE_COMPLIANCE));
    PetscCall(MatDenseRestoreArrayWrite(fs->WHm, &WH));
    fast->wh_valid = PETSC_TRUE;
    if (!kept) fast->wh_state++;
  }
  PetscFunctionReturn(0);
}

/* The first linearization (the frames of the collision detection, the gaps at the start of the step), the
   vectors, the warm start (the previous step's world force of the same contact) and the frames' matrix */
static PetscErrorCode SetUpStep(FastStep *fs, const FCContactSet *previous)
{
  FCScheme scheme = fs->scheme;
  Fast    *fast   = (Fast *)scheme->data;
  PetscInt nc = fs->nc, n3 = fs->n3, M = fs->M;

  PetscFunctionBegin;
  PetscCall(PetscMalloc6(n3, &fs->dfree, n3, &fs->d0, M, &fs->q, M, &fs->qold, nc, &fs->mu, nc, &fs->dims));
  PetscCall(PetscMalloc2(M, &fs->lambda, n3, &fs->d));
  /* first linearization: the frames of the collision detection, gaps at the start of the step */
  FCSchemeStartLinearization(fs->set, fs->dfree, fs->d0, fs->q, fs->mu, fs->dims);
  PetscCall(VecCreate(PETSC_COMM_SELF, &fs->F));
  PetscCall(VecSetSizes(fs->F, n3, n3));
  PetscCall(VecSetType(fs->F, fast->vec_type));
  PetscCall(VecDuplicate(fs->F, &fs->dvec));
  PetscCall(VecCreate(PETSC_COMM_SELF, &fs->lam));
  PetscCall(VecSetSizes(fs->lam, M, M));
  PetscCall(VecSetType(fs->lam, fast->vec_type));
  { /* warm start: the previous step's force of the same contact, in the world frame */
    PetscScalar *f;
    PetscCall(VecGetArray(fs->F, &f));
    for (PetscInt k = 0; k < nc; k++) {
      PetscReal Fw[3];
      FCContactPreviousForce(previous, &fs->set->c[k], Fw);
      for (int i = 0; i < 3; i++) f[3 * k + i] = Fw[i];
    }
    PetscCall(VecRestoreArray(fs->F, &f));
  }
  PetscCall(MatCreate(PETSC_COMM_SELF, &fs->C));
  PetscCall(MatSetSizes(fs->C, M, n3, M, n3));
  PetscCall(MatSetType(fs->C, fast->frames_mat_type));
  PetscCall(MatSeqAIJSetPreallocation(fs->C, 3, NULL));
  PetscCall(MatSetOption(fs->C, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_FALSE));
  if (fast->sweep_update) PetscCall(FCContactSolverSetUpdate(scheme->solver, FCFastUpdateAfterSweep, fs));
  PetscFunctionReturn(0);
}

/* One Newton iteration's contact problem, FC(W_k, q_k, mu), solved from C_k F_{k-1}: W_k whole, or the
   rows of this rank's contacts when the solver splits them */
static PetscErrorCode SolveInFrames(FastStep *fs, FCSchemeStats *st)
{
  FCScheme           scheme = fs->scheme;
  PetscInt           nc     = fs->nc, sweeps;
  PetscReal         *lambda = fs->lambda;
  const PetscScalar *w;
  FCContactProblem   prob;
  PetscBool          conv;

  PetscFunctionBegin;
  PetscCall(FCFastForcesInFrames(fs, lambda));
  PetscCall(MatDenseGetArrayRead(fs->Wk, &w)); /* symmetric: column-major = row-major */
  if (fs->rows) {
    const PetscScalar *wh;
    PetscCall(FCContactProblemCreateDenseRows(scheme->comm, nc, fs->dims, fs->mu, fs->c0, fs->c1, w, fs->q, &prob));
    PetscCall(MatDenseGetArrayRead(fs->WHm, &wh));
    PetscCall(FCFastNormalComplianceFromWH(fs, wh));
    PetscCall(MatDenseRestoreArrayRead(fs->WHm, &wh));
  } else {
    PetscCall(FCContactProblemCreateDense(nc, fs->dims, fs->mu, w, fs->q, &prob));
    FCContactSetNormalCompliance(fs->set, w);
  }
  PetscCall(FCSchemeContactSolve(scheme, fs->set, prob, lambda));
  PetscCall(FCContactSolverGetConvergence(scheme->solver, &sweeps, &st->residual, &conv));
  PetscCall(FCContactProblemDestroy(&prob));
  PetscCall(MatDenseRestoreArrayRead(fs->Wk, &w));
  st->sweeps += sweeps;
  PetscFunctionReturn(0);
}

/* One correction per body from the total force, and what the step leaves: W_k kept with W_H (host) */
static PetscErrorCode FinishStep(FastStep *fs)
{
  FCScheme scheme = fs->scheme;
  Fast    *fast   = (Fast *)scheme->data;
  PetscInt n3     = fs->n3;

  PetscFunctionBegin;
  /* one correction per body: dv = dv_free + h A^-1 H^T F (identity frames: lambda = F) */
  PetscCall(FCPhaseBegin(FC_PHASE_CORRECTION));
  {
    const PetscScalar *f;
    PetscReal         *Fw;
    PetscCall(PetscMalloc1(n3, &Fw));
    PetscCall(VecGetArrayRead(fs->F, &f));
    for (PetscInt i = 0; i < n3; i++) Fw[i] = PetscRealPart(f[i]);
    PetscCall(VecRestoreArrayRead(fs->F, &f));
    PetscCall(FCSchemeCorrect(scheme, &fs->H, Fw));
    PetscCall(PetscFree(Fw));
  }
  PetscCall(FCPhaseEnd(FC_PHASE_CORRECTION));
  PetscCall(MatDestroy(&fs->C));
  PetscCall(MatDestroy(&fs->U));
  PetscCall(MatDestroy(&fs->Ut));
  if (fast->host) { /* kept with W_H */
    fast->Wk    = fs->Wk;
    fast->wk_c0 = fs->c0;
    fast->wk_c1 = fs->c1;
  } else
    PetscCall(MatDestroy(&fs->Wk));
  PetscCall(VecDestroy(&fs->F));
  PetscCall(VecDestroy(&fs->dvec));
  PetscCall(VecDestroy(&fs->lam));
  PetscCall(PetscFree6(fs->dfree, fs->d0, fs->q, fs->qold, fs->mu, fs->dims));
  PetscCall(PetscFree2(fs->lambda, fs->d));
  PetscCall(FCContactSetDestroy(&fs->H));
  PetscFunctionReturn(0);
}

/* Algorithm 3 for one step: W_H, then Newton iterations of (re-form W_k, solve, proximity update,
   re-linearize) until the frames and right-hand sides settle, then one correction per body */
static PetscErrorCode Solve_Fast(FCScheme scheme, FCContactSet *set, const FCContactSet *previous, FCSchemeStats *st)
{
  Fast     *fast = (Fast *)scheme->data;
  FastStep  fs   = {0};
  PetscInt  nc = set->n, M = set->nrows;
  PetscReal change = 0.0;

  PetscFunctionBegin;
  fs.scheme = scheme;
  fs.set    = set;
  fs.nc     = nc;
  fs.n3     = 3 * nc;
  fs.M      = M;
  fs.host   = fast->host;
  PetscCall(RowBlock(scheme, set, &fs.rows, &fs.c0, &fs.c1));
  fs.dist = Distributed(scheme, set, fs.rows);
  fs.rlo  = fs.c0 < nc ? set->c[fs.c0].row : M;
  fs.rhi  = fs.c1 < nc ? set->c[fs.c1].row : M;
  PetscCall(BuildWH(&fs));
  PetscCall(SetUpStep(&fs, previous));
  for (PetscInt it = 1; it <= scheme->newton_max_it; it++) {
    PetscCall(PetscLogEventBegin(FC_EVENT_NEWTON, 0, 0, 0, 0));
    PetscCall(FCPhaseBegin(FC_PHASE_REBUILD_W));
    PetscCall(FCFastRebuildW(&fs));
    PetscCall(FCPhaseEnd(FC_PHASE_REBUILD_W));
    PetscCall(FCPhaseBegin(FC_PHASE_CONTACT_SOLVE));
    PetscCall(SolveInFrames(&fs, st));
    PetscCall(FCPhaseEnd(FC_PHASE_CONTACT_SOLVE));
    FCContactSetStoreForces(set, fs.lambda); /* in the frames they were solved in */
    PetscCall(FCPhaseBegin(FC_PHASE_PROXIMITY));
    PetscCall(FCFastProximityUpdate(&fs, fs.lambda));
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
  PetscCall(FinishStep(&fs));
  PetscFunctionReturn(0);
}

static PetscErrorCode Held_Fast(FCScheme scheme, PetscReal *wh, PetscReal *wk)
{
  Fast    *fast = (Fast *)scheme->data;
  PetscInt m, n;

  PetscFunctionBegin;
  if (fast->WH) {
    PetscCall(MatGetSize(fast->WH, &m, &n));
    *wh = 8.0 * m * n;
  }
  if (fast->Wk) {
    PetscCall(MatGetSize(fast->Wk, &m, &n));
    *wk = 8.0 * m * n;
  }
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
  fast->dist_min             = 1000;
  fast->wk_state             = -1;
  scheme->data               = fast;
  scheme->ops.setfromoptions = SetFromOptions_Fast;
  scheme->ops.memory         = Memory_Fast;
  scheme->ops.solve          = Solve_Fast;
  scheme->ops.held           = Held_Fast;
  scheme->ops.destroy        = Destroy_Fast;
  PetscFunctionReturn(0);
}
