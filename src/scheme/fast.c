/* Algorithm 3: recursive corrective motion with the fast update of the constraint matrices.
   Notation (../shared/design/DESIGN.md, section 2): per contact, d = p1 - p2 (world), F the
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
   dv = dv_free + h A^-1 H^T F. */
#include "../fcimpl.h"

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

PetscErrorCode FCSchemeFast(FCSchemeContext *ctx, FCSchemeStats *st)
{
  FCContactSet    *set = ctx->set, H = {0};
  PetscInt         nc = set->n, n3 = 3 * set->n, M = set->nrows, *dims;
  PetscReal       *WH, *dfree, *d0, *q, *qold, *mu, *lambda, change = 0.0;
  Mat              WHm, C = NULL, U = NULL, Ut = NULL, Wk = NULL;
  Vec              F, dvec, lam;
  FCContactProblem prob;
  PetscBool        conv;

  PetscFunctionBegin;
  FCSchemeStatsReset(set, st);
  if (!nc) PetscFunctionReturn(0);

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
  { /* W_H (3m)^2, U and U^T (M x 3m), W_k (M^2), replicated on every rank */
    PetscReal bytes = 8.0 * ((PetscReal)n3 * n3 + 2.0 * M * n3 + (PetscReal)M * M);
    PetscCheck(bytes <= ctx->memory_limit, ctx->comm, PETSC_ERR_MEM,
               "%" PetscInt_FMT " contacts: the fast scheme's dense W_H and W_k need %.3g GB per rank, above "
               "-contact_memory_limit %.3g GB; use -constraint_scheme explicit (W is %" PetscInt_FMT
               "^2), fewer contacts (-contact_distance, coarser surfaces), or raise the limit",
               nc, (double)(bytes / 1e9), (double)(ctx->memory_limit / 1e9), M);
  }
  PetscCall(MatCreate(PETSC_COMM_SELF, &WHm));
  PetscCall(MatSetSizes(WHm, n3, n3, n3, n3));
  PetscCall(MatSetType(WHm, ctx->wh_mat_type));
  PetscCall(MatSetUp(WHm));
  PetscCall(MatDenseGetArrayWrite(WHm, &WH)); /* symmetric: row/column-major alike */
  PetscCall(FCPhaseBegin(FC_PHASE_COMPLIANCE));
  PetscCall(FCSchemeCompliance(ctx->nbodies, ctx->bodies, &H, WH));
  PetscCall(FCPhaseEnd(FC_PHASE_COMPLIANCE));
  PetscCall(MatDenseRestoreArrayWrite(WHm, &WH));

  PetscCall(PetscMalloc6(n3, &dfree, n3, &d0, M, &q, M, &qold, nc, &mu, nc, &dims));
  PetscCall(PetscMalloc1(M, &lambda));
  /* first linearization: the frames of the collision detection, gaps at the start of the step */
  FCSchemeStartLinearization(set, dfree, d0, q, mu, dims);
  PetscCall(VecCreate(PETSC_COMM_SELF, &F));
  PetscCall(VecSetSizes(F, n3, n3));
  PetscCall(VecSetType(F, ctx->vec_type));
  PetscCall(VecDuplicate(F, &dvec));
  PetscCall(VecCreate(PETSC_COMM_SELF, &lam));
  PetscCall(VecSetSizes(lam, M, M));
  PetscCall(VecSetType(lam, ctx->vec_type));
  { /* warm start: the previous step's force of the same contact, in the world frame */
    PetscScalar *f;
    PetscCall(VecGetArray(F, &f));
    for (PetscInt k = 0; k < nc; k++) {
      PetscReal Fw[3];
      FCContactPreviousForce(ctx->previous, &set->c[k], Fw);
      for (int i = 0; i < 3; i++) f[3 * k + i] = Fw[i];
    }
    PetscCall(VecRestoreArray(F, &f));
  }
  PetscCall(MatCreate(PETSC_COMM_SELF, &C));
  PetscCall(MatSetSizes(C, M, n3, M, n3));
  PetscCall(MatSetType(C, ctx->frames_mat_type));
  PetscCall(MatSeqAIJSetPreallocation(C, 3, NULL));
  PetscCall(MatSetOption(C, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_FALSE));

  for (PetscInt it = 1; it <= ctx->newton_max_it; it++) {
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
    PetscCall(FCContactSolverSolve(ctx->solver, prob, lambda));
    PetscCall(FCContactSolverGetConvergence(ctx->solver, &sweeps, &st->residual, &conv));
    PetscCall(FCContactProblemDestroy(&prob));
    st->sweeps += sweeps;
    PetscCall(FCPhaseEnd(FC_PHASE_CONTACT_SOLVE));
    for (PetscInt k = 0; k < nc; k++) /* forces in the frames they were solved in */
      for (PetscInt a = 0; a < 3; a++) set->c[k].force[a] = a < set->c[k].dim ? lambda[set->c[k].row + a] : 0.0;
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
    if (it == ctx->newton_max_it) break;
    /* frames and right-hand side at the new proximity positions */
    PetscCall(PetscArraycpy(qold, q, M));
    {
      const PetscScalar *dv;
      PetscReal         *d;
      PetscCall(PetscMalloc1(n3, &d));
      PetscCall(VecGetArrayRead(dvec, &dv));
      for (PetscInt i = 0; i < n3; i++) d[i] = dfree[i] + PetscRealPart(dv[i]);
      PetscCall(VecRestoreArrayRead(dvec, &dv));
      PetscCall(FCSchemeLinearize(ctx, dfree, d0, d, q, &change));
      PetscCall(PetscFree(d));
    }
    if (FCSchemeConverged(ctx, M, q, qold, change)) break;
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
    for (PetscInt b = 0; b < ctx->nbodies; b++)
      if (ctx->bodies[b]->ops.applycorrection)
        PetscCall((*ctx->bodies[b]->ops.applycorrection)(ctx->bodies[b], b, &H, Fw));
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
