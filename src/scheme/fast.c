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
   Options (besides -newton_max_it and -newton_tol, recursive.c): the types of W_H (dense), the
   frames C (sparse) and the force vectors, host by default; on a GPU build
     -wh_mat_type seqdensecuda -frames_mat_type seqaijcusparse -contact_vec_type seqcuda (docs/gpu.md) */
#include "schemeimpl.h"

typedef struct {
  char wh_mat_type[FC_MAX_NAME], frames_mat_type[FC_MAX_NAME], vec_type[FC_MAX_NAME];
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
  PetscCall(CheckType(scheme->comm, PETSC_TRUE, fast->wh_mat_type, "-wh_mat_type"));
  PetscCall(CheckType(scheme->comm, PETSC_TRUE, fast->frames_mat_type, "-frames_mat_type"));
  PetscCall(CheckType(scheme->comm, PETSC_FALSE, fast->vec_type, "-contact_vec_type"));
  PetscFunctionReturn(0);
}

/* W_H (3m)^2, U and U^T (M x 3m), W_k (M^2), replicated on every rank */
static PetscErrorCode Memory_Fast(FCScheme scheme, const FCContactSet *set, PetscReal *bytes, const char **what)
{
  PetscReal n3 = 3.0 * set->n, M = set->nrows;

  PetscFunctionBegin;
  *bytes = 8.0 * (n3 * n3 + 2.0 * M * n3 + M * M);
  *what  = "dense W_H and W_k";
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

static PetscErrorCode Solve_Fast(FCScheme scheme, FCContactSet *set, const FCContactSet *previous, FCSchemeStats *st)
{
  Fast            *fast = (Fast *)scheme->data;
  FCContactSet     H    = {0};
  PetscInt         nc = set->n, n3 = 3 * set->n, M = set->nrows, *dims;
  PetscReal       *WH, *dfree, *d0, *q, *qold, *mu, *lambda, change = 0.0;
  Mat              WHm, C = NULL, U = NULL, Ut = NULL, Wk = NULL;
  Vec              F, dvec, lam;
  FCContactProblem prob;
  PetscBool        conv;

  PetscFunctionBegin;
  /* W_H once per step: the bodies' builders on the contacts in identity frames */
  PetscCall(FCContactSetCopy(set, &H));
  for (PetscInt k = 0; k < nc; k++) {
    FCContact *c = &H.c[k];
    for (int i = 0; i < 3; i++) c->n[i] = c->t1[i] = c->t2[i] = 0.0;
    c->n[0] = c->t1[1] = c->t2[2] = 1.0;
    c->dim                        = 3;
    c->row                        = 3 * k;
  }
  H.nrows = n3;
  PetscCall(MatCreate(PETSC_COMM_SELF, &WHm));
  PetscCall(MatSetSizes(WHm, n3, n3, n3, n3));
  PetscCall(MatSetType(WHm, fast->wh_mat_type));
  PetscCall(MatSetUp(WHm));
  PetscCall(MatDenseGetArrayWrite(WHm, &WH)); /* symmetric: row/column-major alike */
  PetscCall(FCPhaseBegin(FC_PHASE_COMPLIANCE));
  PetscCall(FCSchemeCompliance(scheme, &H, WH));
  PetscCall(FCPhaseEnd(FC_PHASE_COMPLIANCE));
  PetscCall(MatDenseRestoreArrayWrite(WHm, &WH));

  PetscCall(PetscMalloc6(n3, &dfree, n3, &d0, M, &q, M, &qold, nc, &mu, nc, &dims));
  PetscCall(PetscMalloc1(M, &lambda));
  /* first linearization: the frames of the collision detection, gaps at the start of the step */
  FCSchemeStartLinearization(set, dfree, d0, q, mu, dims);
  PetscCall(VecCreate(PETSC_COMM_SELF, &F));
  PetscCall(VecSetSizes(F, n3, n3));
  PetscCall(VecSetType(F, fast->vec_type));
  PetscCall(VecDuplicate(F, &dvec));
  PetscCall(VecCreate(PETSC_COMM_SELF, &lam));
  PetscCall(VecSetSizes(lam, M, M));
  PetscCall(VecSetType(lam, fast->vec_type));
  { /* warm start: the previous step's force of the same contact, in the world frame */
    PetscScalar *f;
    PetscCall(VecGetArray(F, &f));
    for (PetscInt k = 0; k < nc; k++) {
      PetscReal Fw[3];
      FCContactPreviousForce(previous, &set->c[k], Fw);
      for (int i = 0; i < 3; i++) f[3 * k + i] = Fw[i];
    }
    PetscCall(VecRestoreArray(F, &f));
  }
  PetscCall(MatCreate(PETSC_COMM_SELF, &C));
  PetscCall(MatSetSizes(C, M, n3, M, n3));
  PetscCall(MatSetType(C, fast->frames_mat_type));
  PetscCall(MatSeqAIJSetPreallocation(C, 3, NULL));
  PetscCall(MatSetOption(C, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_FALSE));

  for (PetscInt it = 1; it <= scheme->newton_max_it; it++) {
    const PetscScalar *w;
    PetscInt           sweeps;
    PetscCall(PetscLogEventBegin(FC_EVENT_NEWTON, 0, 0, 0, 0));
    /* W_k = C_k W_H C_k^T: U = C W_H (AIJ x dense), W_k = C U^T */
    PetscCall(FCPhaseBegin(FC_PHASE_REBUILD_W));
    PetscCall(AssembleFrames(set, C));
    if (!U)
      PetscCall(MatMatMult(C, WHm, MAT_INITIAL_MATRIX, PETSC_DEFAULT, &U));
    else
      PetscCall(MatMatMult(C, WHm, MAT_REUSE_MATRIX, PETSC_DEFAULT, &U));
    PetscCall(MatDestroy(&Ut));
    PetscCall(MatTranspose(U, MAT_INITIAL_MATRIX, &Ut));
    if (!Wk)
      PetscCall(MatMatMult(C, Ut, MAT_INITIAL_MATRIX, PETSC_DEFAULT, &Wk));
    else
      PetscCall(MatMatMult(C, Ut, MAT_REUSE_MATRIX, PETSC_DEFAULT, &Wk));
    PetscCall(FCPhaseEnd(FC_PHASE_REBUILD_W));
    /* PGS on the total force, warm-started from C_k F_{k-1} */
    PetscCall(FCPhaseBegin(FC_PHASE_CONTACT_SOLVE));
    PetscCall(MatMult(C, F, lam));
    {
      const PetscScalar *l;
      PetscCall(VecGetArrayRead(lam, &l));
      for (PetscInt r = 0; r < M; r++) lambda[r] = PetscRealPart(l[r]);
      PetscCall(VecRestoreArrayRead(lam, &l));
    }
    PetscCall(MatDenseGetArrayRead(Wk, &w)); /* symmetric */
    PetscCall(FCContactProblemCreateDense(nc, dims, mu, w, q, &prob));
    FCContactSetNormalCompliance(set, w);
    PetscCall(MatDenseRestoreArrayRead(Wk, &w));
    PetscCall(FCContactSolverSolve(scheme->solver, prob, lambda));
    PetscCall(FCContactSolverGetConvergence(scheme->solver, &sweeps, &st->residual, &conv));
    PetscCall(FCContactProblemDestroy(&prob));
    st->sweeps += sweeps;
    PetscCall(FCPhaseEnd(FC_PHASE_CONTACT_SOLVE));
    FCContactSetStoreForces(set, lambda); /* in the frames they were solved in */
    /* F_k = C_k^T lambda; proximity update d = d_free + h^2 W_H F_k (eq. 31) */
    PetscCall(FCPhaseBegin(FC_PHASE_PROXIMITY));
    {
      PetscScalar *l;
      PetscCall(VecGetArray(lam, &l));
      for (PetscInt r = 0; r < M; r++) l[r] = lambda[r];
      PetscCall(VecRestoreArray(lam, &l));
    }
    PetscCall(MatMultTranspose(C, lam, F));
    PetscCall(MatMult(WHm, F, dvec));
    PetscCall(FCPhaseEnd(FC_PHASE_PROXIMITY));
    st->newton = it;
    PetscCall(PetscLogEventEnd(FC_EVENT_NEWTON, 0, 0, 0, 0));
    if (it == scheme->newton_max_it) break;
    /* frames and right-hand side at the new proximity positions */
    PetscCall(PetscArraycpy(qold, q, M));
    {
      const PetscScalar *dv;
      PetscReal         *d;
      PetscCall(PetscMalloc1(n3, &d));
      PetscCall(VecGetArrayRead(dvec, &dv));
      for (PetscInt i = 0; i < n3; i++) d[i] = dfree[i] + PetscRealPart(dv[i]);
      PetscCall(VecRestoreArrayRead(dvec, &dv));
      PetscCall(FCSchemeLinearize(scheme, set, dfree, d0, d, q, &change));
      PetscCall(PetscFree(d));
    }
    if (FCSchemeConverged(scheme, M, q, qold, change)) break;
  }
  FCContactSetUpdateStates(set);
  /* one correction per body: dv = dv_free + h A^-1 H^T F (identity frames: lambda = F) */
  PetscCall(FCPhaseBegin(FC_PHASE_CORRECTION));
  {
    const PetscScalar *f;
    PetscReal         *Fw;
    PetscCall(PetscMalloc1(n3, &Fw));
    PetscCall(VecGetArrayRead(F, &f));
    for (PetscInt i = 0; i < n3; i++) Fw[i] = PetscRealPart(f[i]);
    PetscCall(VecRestoreArrayRead(F, &f));
    PetscCall(FCSchemeCorrect(scheme, &H, Fw));
    PetscCall(PetscFree(Fw));
  }
  PetscCall(FCPhaseEnd(FC_PHASE_CORRECTION));
  PetscCall(MatDestroy(&C));
  PetscCall(MatDestroy(&U));
  PetscCall(MatDestroy(&Ut));
  PetscCall(MatDestroy(&Wk));
  PetscCall(MatDestroy(&WHm));
  PetscCall(VecDestroy(&F));
  PetscCall(VecDestroy(&dvec));
  PetscCall(VecDestroy(&lam));
  PetscCall(PetscFree6(dfree, d0, q, qold, mu, dims));
  PetscCall(PetscFree(lambda));
  PetscCall(FCContactSetDestroy(&H));
  PetscFunctionReturn(0);
}

static PetscErrorCode Destroy_Fast(FCScheme scheme)
{
  PetscFunctionBegin;
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
  scheme->data               = fast;
  scheme->ops.setfromoptions = SetFromOptions_Fast;
  scheme->ops.memory         = Memory_Fast;
  scheme->ops.solve          = Solve_Fast;
  scheme->ops.destroy        = Destroy_Fast;
  PetscFunctionReturn(0);
}
