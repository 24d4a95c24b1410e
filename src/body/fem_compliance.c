/* Compliance builders of an FE body, -compliance_type (eq. 17: W_b = J_b A_b^-1 J_b^T):
     dense        J_b^T solved with the factor of A in one MatMatSolve; X = A^-1 J_b^T is kept
                  for the correction (eq. 20)
     sparse       the same with J_b handed to MUMPS as sparse right-hand sides (1 rank)
     schur        MUMPS Schur complement of the augmented matrix [[0, J_b], [J_b^T, A]]
     inverse      the block of A^-1 on the contact DOFs from MUMPS (selected entries of the
                  inverse, ICNTL(30)), then J_S (A^-1)_SS J_S^T
     redundant    the same with a sequential factor of A on every rank, each computing 1/p of
                  the columns
     precomputed  columns of A_0^-1 restricted to the body's surface, computed once per surface
                  vertex (the first time it is in contact) and reused; A_0 is A at the
                  reference state. Co-rotational bodies warp them with the body's best-fit
                  rotation R (W_b = J R C_0 R^T J^T) and correct with the same operator.
   Every builder but dense corrects with one solve per step. */
#include "femimpl.h"

/* Frame direction a (0: n, 1: t1, 2: t2) of a contact, signed for the side of this body */
static void Direction(const FCContact *c, PetscInt side, PetscInt a, PetscReal e[3])
{
  const PetscReal *f = a == 0 ? c->n : (a == 1 ? c->t1 : c->t2);
  for (int i = 0; i < 3; i++) e[i] = (side == 0 ? 1.0 : -1.0) * f[i];
}

/* Numeric Cholesky factorization by MUMPS of a matrix this file owns (the Schur builder's augmented
   matrix, the redundant copies of A), checked: PETSc 3.18 records a MUMPS failure in the factor
   instead of raising it, and parallel MUMPS intermittently underestimates its workspace (INFOG(1) =
   -9, seen on 2 ranks: an unchecked failure gave an all-zero Schur complement). Out of memory is
   retried with ICNTL(14), the workspace margin in percent, doubled, up to 3 times. */
static PetscErrorCode CholeskyNumericChecked(FCBody body, Mat F, Mat K, const char what[])
{
  MatFactorInfo  info;
  MatFactorError err;

  PetscFunctionBegin;
  PetscCall(MatFactorInfoInitialize(&info));
  for (int attempt = 0;; attempt++) {
    PetscInt icntl14;
    PetscCall(MatCholeskyFactorNumeric(F, K, &info));
    PetscCall(MatFactorGetError(F, &err));
    if (err == MAT_FACTOR_NOERROR) break;
    PetscCall(MatMumpsGetIcntl(F, 14, &icntl14));
    PetscCheck(err == MAT_FACTOR_OUTMEMORY && attempt < 3, body->comm, PETSC_ERR_CONV_FAILED,
               "MUMPS factorization of %s of body '%s' failed (PETSc MatFactorError %d, ICNTL(14) = %" PetscInt_FMT ")",
               what, body->name, (int)err, icntl14);
    PetscCall(PetscInfo(F,
                        "MUMPS out of workspace in %s of body %s: ICNTL(14) %" PetscInt_FMT " -> %" PetscInt_FMT "\n",
                        what, body->name, icntl14, 2 * icntl14 + 20));
    PetscCall(MatMumpsSetIcntl(F, 14, 2 * icntl14 + 20));
    PetscCall(MatFactorClearError(F));
  }
  PetscFunctionReturn(0);
}

/* Compliance, MUMPS Schur builder: the augmented symmetric matrix K = [[0, J_b], [J_b^T, A]]
   (constraint rows first, so that the Schur indices live on rank 0) is factored with
   MatFactorSetSchurIS on the constraint rows; MUMPS returns S = -J_b A^-1 J_b^T, centralized on
   rank 0, which is broadcast. A is copied into K every call (the pattern changes with the
   contacts), and the correction then needs one solve with A's own factor. */
static PetscErrorCode SchurCompliance(FCBody body, PetscInt ncols, PetscReal *Wb)
{
  FEM          *fem = (FEM *)body->data;
  PetscMPIInt   rank;
  PetscInt      nloc, N, lo, hi, mloc;
  Mat           K, F, S;
  IS            is;
  MatFactorInfo info;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_rank(body->comm, &rank));
  PetscCall(VecGetLocalSize(fem->u, &nloc));
  PetscCall(VecGetSize(fem->u, &N));
  PetscCall(VecGetOwnershipRange(fem->u, &lo, &hi));
  mloc = nloc + (rank ? 0 : ncols);
  PetscCall(MatCreateAIJ(body->comm, mloc, mloc, N + ncols, N + ncols, 96, NULL, 96, NULL, &K));
  PetscCall(MatSetOption(K, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_FALSE));
  for (PetscInt r = lo; r < hi; r++) { /* A, shifted by ncols */
    PetscInt           nc;
    const PetscInt    *cols;
    const PetscScalar *vals;
    PetscInt           row = r + ncols, shifted[512];
    PetscCall(MatGetRow(fem->A, r, &nc, &cols, &vals));
    PetscCheck(nc <= 512, PETSC_COMM_SELF, PETSC_ERR_SUP, "Row of A with %" PetscInt_FMT " entries", nc);
    for (PetscInt k = 0; k < nc; k++) shifted[k] = cols[k] + ncols;
    PetscCall(MatSetValues(K, 1, &row, nc, shifted, vals, ADD_VALUES));
    PetscCall(MatRestoreRow(fem->A, r, &nc, &cols, &vals));
  }
  if (rank == 0)
    for (PetscInt i = 0; i < ncols; i++) PetscCall(MatSetValue(K, i, i, 0.0, ADD_VALUES)); /* structural diagonal */
  for (PetscInt q = 0; q < fem->njt; q++) {                                                /* J_b^T and J_b */
    PetscCall(MatSetValue(K, lo + fem->jtr[q] + ncols, fem->jtc[q], fem->jtv[q], ADD_VALUES));
    PetscCall(MatSetValue(K, fem->jtc[q], lo + fem->jtr[q] + ncols, fem->jtv[q], ADD_VALUES));
  }
  PetscCall(MatAssemblyBegin(K, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(K, MAT_FINAL_ASSEMBLY));
  PetscCall(MatSetOption(K, MAT_SYMMETRIC, PETSC_TRUE));
  PetscCall(MatGetFactor(K, MATSOLVERMUMPS, MAT_FACTOR_CHOLESKY, &F));
  PetscCall(ISCreateStride(PETSC_COMM_SELF, rank ? 0 : ncols, 0, 1, &is));
  PetscCall(MatFactorSetSchurIS(F, is));
  PetscCall(MatFactorInfoInitialize(&info));
  PetscCall(MatCholeskyFactorSymbolic(F, K, NULL, &info));
  PetscCall(CholeskyNumericChecked(body, F, K, "the augmented matrix [[0, J], [J^T, A]]"));
  PetscCall(MatFactorCreateSchurComplement(F, &S, NULL));
  if (rank == 0) {
    const PetscScalar *sa;
    PetscCall(MatDenseGetArrayRead(S, &sa));
    for (PetscInt i = 0; i < ncols; i++) /* column-major, symmetric */
      for (PetscInt j = 0; j < ncols; j++) Wb[i * ncols + j] = -PetscRealPart(sa[i + j * ncols]);
    PetscCall(MatDenseRestoreArrayRead(S, &sa));
  }
  PetscCallMPI(MPI_Bcast(Wb, (PetscMPIInt)(ncols * ncols), MPIU_REAL, 0, body->comm));
  PetscCall(MatDestroy(&S));
  PetscCall(MatDestroy(&F));
  PetscCall(MatDestroy(&K));
  PetscCall(ISDestroy(&is));
  PetscFunctionReturn(0);
}

/* Compliance, selected-inverse builders: W_b = J_S C J_S^T with C = (A^-1)_{SS} the block of the
   inverse on the DOFs S that the body's contacts touch, from MUMPS (ICNTL(30),
   MatMumpsGetInverse). MUMPS prunes its elimination tree to the paths of S, so the cost follows
   |S| and the tree, not |S| full solves.
     inverse    with the factor A already has (distributed): the entries come back on rank 0,
                which forms W_b;
     redundant  every rank keeps its own sequential factor of the whole A (PCREDUNDANT's idea:
                memory for parallelism) and computes the columns of C for its 1/p share of S;
                the partial W_b are summed. A linear A is factored once; a co-rotational one
                again whenever the body refactors A.
   The correction does one solve with the distributed factor. */

/* S (sorted DOFs that J_b touches, the same on every rank: contacts are replicated) and J_S by
   columns of S: for S index j, the rows a of J_b with J_b(a, S_j) != 0; from all the entries of
   J_b^T (fem->jtr + lo: global DOF) */
static PetscErrorCode ContactDofs(FEM *fem, PetscInt lo, PetscInt *ns_, PetscInt **S_, PetscInt **cptr_,
                                  PetscInt **crow_, PetscReal **cval_)
{
  PetscInt   n = fem->nje, ns = n, *S, *cptr, *crow, *cnt;
  PetscReal *cval;

  PetscFunctionBegin;
  PetscCall(PetscMalloc1(n + 1, &S));
  for (PetscInt q = 0; q < n; q++) S[q] = fem->jtr[q] + lo;
  PetscCall(PetscSortRemoveDupsInt(&ns, S));
  PetscCall(PetscCalloc1(ns + 1, &cptr));
  PetscCall(PetscCalloc1(ns + 1, &cnt));
  PetscCall(PetscMalloc1(n + 1, &crow));
  PetscCall(PetscMalloc1(n + 1, &cval));
  for (int pass = 0; pass < 2; pass++) { /* count, then fill */
    for (PetscInt q = 0; q < n; q++) {
      PetscInt at;
      PetscCall(PetscFindInt(fem->jtr[q] + lo, ns, S, &at));
      if (!pass)
        cptr[at + 1]++;
      else {
        PetscInt r = cptr[at] + cnt[at]++;
        crow[r]    = fem->jtc[q];
        cval[r]    = fem->jtv[q];
      }
    }
    if (!pass)
      for (PetscInt j = 0; j < ns; j++) cptr[j + 1] += cptr[j];
  }
  PetscCall(PetscFree(cnt));
  *ns_   = ns;
  *S_    = S;
  *cptr_ = cptr;
  *crow_ = crow;
  *cval_ = cval;
  PetscFunctionReturn(0);
}

/* Adds to Wb the part of J_S C J_S^T from the columns j0 <= j < j1 of C = (A^-1)_{SS}, computed
   with the factor F; a rank with j1 > j0 must hold every row of F (rank 0 of a distributed
   factor, or a sequential factor) */
static PetscErrorCode AddInverseColumns(Mat F, PetscInt N, PetscInt ns, const PetscInt S[], const PetscInt cptr[],
                                        const PetscInt crow[], const PetscReal cval[], PetscInt j0, PetscInt j1,
                                        PetscInt block, PetscInt ncols, PetscReal *Wb)
{
  MPI_Comm    comm = PetscObjectComm((PetscObject)F);
  PetscMPIInt size;
  PetscInt    nloc = j1 > j0 ? N : 0, *nnz, icntl21, icntl27, icntl30;
  PetscReal  *T;
  Mat         Bt, Btseq, spRHS;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_size(comm, &size));
  /* row S_j of Bt lists the entries wanted in column S_j of A^-1 */
  PetscCall(MatCreateAIJ(comm, nloc, nloc, N, N, 0, NULL, 0, NULL, &Bt));
  PetscCall(PetscCalloc1(nloc + 1, &nnz));
  for (PetscInt j = j0; j < j1; j++) nnz[S[j]] = ns;
  PetscCall(MatSeqAIJSetPreallocation(Bt, 0, nnz));
  PetscCall(MatMPIAIJSetPreallocation(Bt, 0, nnz, 0, NULL));
  PetscCall(PetscFree(nnz));
  {
    PetscScalar *zero;
    PetscCall(PetscCalloc1(ns + 1, &zero));
    for (PetscInt j = j0; j < j1; j++) PetscCall(MatSetValues(Bt, 1, &S[j], ns, S, zero, INSERT_VALUES));
    PetscCall(PetscFree(zero));
  }
  PetscCall(MatAssemblyBegin(Bt, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(Bt, MAT_FINAL_ASSEMBLY));
  PetscCall(MatCreateTranspose(Bt, &spRHS));
  /* PETSc 3.18 leaves ICNTL(30) = 1 and ICNTL(21) = 0 (centralized solution) set after the call,
     which breaks the later solves with a distributed factor: restore both */
  PetscCall(MatMumpsGetIcntl(F, 21, &icntl21));
  PetscCall(MatMumpsGetIcntl(F, 27, &icntl27));
  PetscCall(MatMumpsGetIcntl(F, 30, &icntl30));
  PetscCall(MatMumpsSetIcntl(F, 27, block)); /* columns of A^-1 per block: -compliance_inverse_block */
  PetscCall(MatMumpsGetInverse(F, spRHS));
  PetscCall(MatMumpsSetIcntl(F, 21, icntl21));
  PetscCall(MatMumpsSetIcntl(F, 27, icntl27));
  PetscCall(MatMumpsSetIcntl(F, 30, icntl30));
  if (size > 1)
    PetscCall(MatMPIAIJGetSeqAIJ(Bt, &Btseq, NULL, NULL));
  else
    Btseq = Bt;
  /* per own column j: T = (J_S C)(:, j), then Wb(a, b) += T(a) J_S(b, j) */
  PetscCall(PetscMalloc1(ncols + 1, &T));
  for (PetscInt j = j0; j < j1; j++) {
    PetscInt           nc;
    const PetscInt    *cols;
    const PetscScalar *vals;
    PetscCall(MatGetRow(Btseq, S[j], &nc, &cols, &vals)); /* C(:, j), in the order of S */
    PetscCheck(nc == ns, PETSC_COMM_SELF, PETSC_ERR_LIB,
               "MUMPS returned %" PetscInt_FMT " of %" PetscInt_FMT " entries", nc, ns);
    PetscCall(PetscArrayzero(T, ncols));
    for (PetscInt i = 0; i < ns; i++)
      for (PetscInt q = cptr[i]; q < cptr[i + 1]; q++) T[crow[q]] += cval[q] * PetscRealPart(vals[i]);
    PetscCall(MatRestoreRow(Btseq, S[j], &nc, &cols, &vals));
    for (PetscInt q = cptr[j]; q < cptr[j + 1]; q++)
      for (PetscInt a = 0; a < ncols; a++) Wb[a * ncols + crow[q]] += T[a] * cval[q];
  }
  PetscCall(PetscFree(T));
  PetscCall(MatDestroy(&spRHS));
  PetscCall(MatDestroy(&Bt));
  PetscFunctionReturn(0);
}

/* Before the copies are factored: MUMPS' estimate of the memory of this rank's share of its copy
   (INFO(15), MB, in-core) against -compliance_redundant_memory_limit, so that a copy that would not
   fit stops with a clear error instead of an allocation failure or the kernel's OOM killer */
static PetscErrorCode CheckRedundantMemory(FCBody body)
{
  FEM      *fem = (FEM *)body->data;
  PetscInt  mb;
  PetscReal need, worst;

  PetscFunctionBegin;
  PetscCall(MatMumpsGetInfo(fem->Fr, 15, &mb));
  need = 1e6 * (PetscReal)mb;
  PetscCall(MPIU_Allreduce(&need, &worst, 1, MPIU_REAL, MPIU_MAX, body->comm));
  PetscCheck(worst <= fem->rmemory, body->comm, PETSC_ERR_MEM,
             "-compliance_type redundant: the copy of A of body '%s' needs about %.3g GB per rank to factor (MUMPS "
             "estimate), above -compliance_redundant_memory_limit %.3g GB; use fewer copies "
             "(-compliance_redundant_groups k), -compliance_type inverse, or raise the limit",
             body->name, (double)(worst / 1e9), (double)(fem->rmemory / 1e9));
  PetscFunctionReturn(0);
}

/* redundant: this rank's copy of A (on the rcomm of its group) and its factor, current with A's
   factor. rgroups = size (the default): a sequential copy per rank. */
static PetscErrorCode RedundantFactor(FCBody body, Mat *F)
{
  FEM          *fem = (FEM *)body->data;
  PetscMPIInt   size, rank;
  MatFactorInfo info;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_size(body->comm, &size));
  PetscCallMPI(MPI_Comm_rank(body->comm, &rank));
  if (!fem->rgroups) fem->rgroups = size;
  if (size == 1) { /* A's own factor is already sequential */
    PC pc;
    PetscCall(KSPGetPC(fem->ksp, &pc));
    PetscCall(PCFactorGetMatrix(pc, F));
    fem->group = 0;
    PetscFunctionReturn(0);
  }
  if (fem->rcomm == MPI_COMM_NULL) { /* contiguous groups of ranks */
    fem->group = (PetscInt)(((PetscInt64)rank * fem->rgroups) / size);
    PetscCallMPI(MPI_Comm_split(body->comm, (PetscMPIInt)fem->group, rank, &fem->rcomm));
  }
  if (!fem->Fr || fem->rfactor != fem->nfactor) {
    PetscCall(MatCreateRedundantMatrix(fem->A, fem->rgroups, fem->rcomm,
                                       fem->Ar ? MAT_REUSE_MATRIX : MAT_INITIAL_MATRIX, &fem->Ar));
    PetscCall(MatSetOption(fem->Ar, MAT_SYMMETRIC, PETSC_TRUE));
    PetscCall(MatFactorInfoInitialize(&info));
    if (!fem->Fr) { /* the pattern of A never changes: one analysis */
      PetscCall(MatGetFactor(fem->Ar, MATSOLVERMUMPS, MAT_FACTOR_CHOLESKY, &fem->Fr));
      PetscCall(MatCholeskyFactorSymbolic(fem->Fr, fem->Ar, NULL, &info));
      PetscCall(CheckRedundantMemory(body));
    }
    PetscCall(CholeskyNumericChecked(body, fem->Fr, fem->Ar, "the redundant copy of A"));
    fem->rfactor = fem->nfactor;
  }
  *F = fem->Fr;
  PetscFunctionReturn(0);
}

/* Called when A has been factored (in the factorization phase): the redundant copies follow */
PetscErrorCode FCFEMComplianceFactor(FCBody body)
{
  FEM *fem = (FEM *)body->data;
  Mat  F;

  PetscFunctionBegin;
  if (!strcmp(fem->compliance, "redundant")) PetscCall(RedundantFactor(body, &F));
  PetscFunctionReturn(0);
}

static PetscErrorCode InverseCompliance(FCBody body, PetscInt ncols, PetscReal *Wb)
{
  FEM        *fem = (FEM *)body->data;
  PetscMPIInt rank, size;
  PetscInt    N, lo, ns = 0, *S = NULL, *cptr = NULL, *crow = NULL, j0, j1;
  PetscReal  *cval = NULL;
  Mat         F;
  PC          pc;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_rank(body->comm, &rank));
  PetscCallMPI(MPI_Comm_size(body->comm, &size));
  PetscCall(VecGetSize(fem->u, &N));
  PetscCall(KSPGetPC(fem->ksp, &pc));
  PetscCall(PCFactorGetMatrix(pc, &F)); /* MUMPS: checked by FCBodyFEMSetComplianceType */
  PetscCall(VecGetOwnershipRange(fem->u, &lo, NULL));
  PetscCall(ContactDofs(fem, lo, &ns, &S, &cptr, &crow, &cval));
  if (!strcmp(fem->compliance, "redundant")) { /* the group's share of S, on rank 0 of its copy */
    PetscMPIInt grank = 0;
    PetscCall(RedundantFactor(body, &F));
    if (fem->rcomm != MPI_COMM_NULL) PetscCallMPI(MPI_Comm_rank(fem->rcomm, &grank));
    j0 = (ns * fem->group) / fem->rgroups;
    j1 = grank ? j0 : (ns * (fem->group + 1)) / fem->rgroups;
  } else { /* all of S on rank 0 of the distributed factor */
    j0 = 0;
    j1 = rank ? 0 : ns;
  }
  PetscCall(AddInverseColumns(F, N, ns, S, cptr, crow, cval, j0, j1, fem->iblock, ncols, Wb));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, Wb, ncols * ncols, MPIU_REAL, MPIU_SUM, body->comm));
  PetscCall(PetscFree(S));
  PetscCall(PetscFree(cptr));
  PetscCall(PetscFree(crow));
  PetscCall(PetscFree(cval));
  PetscFunctionReturn(0);
}

/* ---- precomputed builder ---- */

/* The surface (sorted first global DOFs of the non-fixed boundary vertices, on every rank) and,
   for a co-rotational body, a factor of A_0: called at set-up, while A is still A at q = 0 */
static PetscErrorCode PrecomputedSetUp(FCBody body)
{
  FEM        *fem = (FEM *)body->data;
  PetscMPIInt size, n = 0, *counts, *displs;
  PetscInt   *mine;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_size(body->comm, &size));
  PetscCall(PetscMalloc3(fem->nbv + 1, &mine, size, &counts, size + 1, &displs));
  for (PetscInt i = 0; i < fem->nbv; i++)
    if (fem->gdof[fem->bv[i]] >= 0) mine[n++] = fem->gdof[fem->bv[i]];
  PetscCallMPI(MPI_Allgather(&n, 1, MPI_INT, counts, 1, MPI_INT, body->comm));
  displs[0] = 0;
  for (PetscMPIInt r = 0; r < size; r++) displs[r + 1] = displs[r] + counts[r];
  fem->nsurf = displs[size];
  PetscCall(PetscMalloc2(fem->nsurf + 1, &fem->surf, fem->nsurf + 1, &fem->slot));
  PetscCallMPI(MPI_Allgatherv(mine, n, MPIU_INT, fem->surf, counts, displs, MPIU_INT, body->comm));
  PetscCall(PetscSortInt(fem->nsurf, fem->surf));
  for (PetscInt i = 0; i < fem->nsurf; i++) fem->slot[i] = -1;
  PetscCall(PetscFree3(mine, counts, displs));
  FCMat3Identity(fem->Rwarp);
  if (!fem->mat->linear) {
    PC pc;
    PetscCall(MatDuplicate(fem->A, MAT_COPY_VALUES, &fem->A0));
    PetscCall(KSPCreate(body->comm, &fem->ksp0));
    PetscCall(KSPSetOptionsPrefix(fem->ksp0, body->prefix));
    PetscCall(KSPSetType(fem->ksp0, KSPPREONLY));
    PetscCall(KSPGetPC(fem->ksp0, &pc));
    PetscCall(PCSetType(pc, PCCHOLESKY));
    PetscCall(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS));
    PetscCall(KSPSetFromOptions(fem->ksp0));
    PetscCall(KSPSetOperators(fem->ksp0, fem->A0, fem->A0));
    PetscCall(KSPSetUp(fem->ksp0));
  }
  PetscFunctionReturn(0);
}

/* Best-fit rotation of the body now (shape matching: the polar factor of
   sum (x - c)(X - C)^T over the vertices); identity for a linear material */
static PetscErrorCode WarpRotation(FCBody body)
{
  FEM               *fem   = (FEM *)body->data;
  FCMesh            *m     = &fem->mesh;
  PetscReal          s[16] = {0}, A[9]; /* sum X, sum x, count, sum x X^T */
  const PetscScalar *u;
  PetscInt           lo;

  PetscFunctionBegin;
  FCMat3Identity(fem->Rwarp);
  if (fem->mat->linear) PetscFunctionReturn(0);
  PetscCall(VecGetOwnershipRange(fem->u, &lo, NULL));
  PetscCall(VecGetArrayRead(fem->u, &u));
  for (PetscInt v = 0; v < m->vEnd - m->vStart; v++) {
    PetscReal X[3], x[3];
    if (!m->owned[v]) continue;
    for (int d = 0; d < 3; d++) {
      X[d] = m->X[3 * v + d];
      x[d] = X[d] + (fem->fixed[v] ? 0.0 : PetscRealPart(u[fem->gdof[v] - lo + d]));
      s[d] += X[d];
      s[3 + d] += x[d];
    }
    s[6] += 1.0;
    for (int i = 0; i < 3; i++)
      for (int j = 0; j < 3; j++) s[7 + 3 * i + j] += x[i] * X[j];
  }
  PetscCall(VecRestoreArrayRead(fem->u, &u));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, s, 16, MPIU_REAL, MPIU_SUM, body->comm));
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) A[3 * i + j] = s[7 + 3 * i + j] - s[3 + i] * s[j] / s[6];
  FCMat3Polar(A, fem->Rwarp);
  PetscFunctionReturn(0);
}

/* Factor of A_0: ksp0 (co-rotational) or the body's own (linear: A never changes) */
static PetscErrorCode ReferenceSolver(FEM *fem, KSP *ksp)
{
  PetscFunctionBegin;
  *ksp = fem->ksp0 ? fem->ksp0 : fem->ksp;
  PetscFunctionReturn(0);
}

/* W_b(i, j) = sum over the vertices a of column i and b of column j of
   w_a w_b (R^T e_i)^T C_0[a, b] (R^T e_j); columns of C_0 missing from the cache are solved for
   first, all at once (3 right-hand sides per new surface vertex) */
static PetscErrorCode PrecomputedCompliance(FCBody body, PetscInt self, const FCContactSet *set, PetscInt ncols,
                                            PetscReal *Wb)
{
  FEM       *fem = (FEM *)body->data;
  PetscInt  *si, nnew = 0, *newv, ns3 = 3 * fem->nsurf;
  PetscReal *co, Rt[9];

  PetscFunctionBegin;
  PetscCall(WarpRotation(body));
  FCMat3Transpose(fem->Rwarp, Rt);
  /* per column: up to 3 (surface vertex, coefficient 3-vector) */
  PetscCall(PetscMalloc3(3 * ncols, &si, 9 * ncols, &co, 3 * ncols, &newv));
  {
    PetscInt col = 0;
    for (PetscInt k = 0; k < set->n; k++)
      for (PetscInt s = 0; s < 2; s++) {
        const FCContact *c = &set->c[k];
        if (c->body[s] != self) continue;
        for (PetscInt a = 0; a < c->dim; a++, col++) {
          PetscReal e[3], er[3];
          Direction(c, s, a, e);
          FCMat3Vec(Rt, e, er);
          for (PetscInt vtx = 0; vtx < 3; vtx++) {
            PetscInt g = vtx < c->prox[s].nv ? c->prox[s].gdof[vtx] : -1, idx = -1;
            if (g >= 0) PetscCall(PetscFindInt(g, fem->nsurf, fem->surf, &idx));
            PetscCheck(g < 0 || idx >= 0, PETSC_COMM_SELF, PETSC_ERR_PLIB,
                       "Contact point of body '%s' is not on its surface", body->name);
            si[3 * col + vtx] = idx;
            for (int d = 0; d < 3; d++) co[9 * col + 3 * vtx + d] = idx >= 0 ? c->prox[s].w[vtx] * er[d] : 0.0;
            if (idx >= 0 && fem->slot[idx] == -1) {
              fem->slot[idx] = -2; /* queued */
              newv[nnew++]   = idx;
            }
          }
        }
      }
  }
  if (nnew) { /* C_0 columns of the new vertices: A_0^-1 [e_g e_g+1 e_g+2], kept on the surface rows */
    KSP                ksp;
    PC                 pc;
    Mat                F, B, X;
    PetscInt           nloc, N, lo;
    PetscScalar       *b;
    const PetscScalar *x;
    PetscReal         *cols;
    PetscCall(ReferenceSolver(fem, &ksp));
    PetscCall(KSPGetPC(ksp, &pc));
    PetscCall(PCFactorGetMatrix(pc, &F));
    PetscCall(VecGetLocalSize(fem->u, &nloc));
    PetscCall(VecGetSize(fem->u, &N));
    PetscCall(VecGetOwnershipRange(fem->u, &lo, NULL));
    PetscCall(MatCreateDense(body->comm, nloc, PETSC_DECIDE, N, 3 * nnew, NULL, &B));
    PetscCall(MatDenseGetArray(B, &b));
    PetscCall(PetscArrayzero(b, nloc * 3 * nnew));
    for (PetscInt j = 0; j < nnew; j++) {
      PetscInt g = fem->surf[newv[j]];
      if (g >= lo && g < lo + nloc)
        for (int d = 0; d < 3; d++) b[(g - lo + d) + nloc * (3 * j + d)] = 1.0;
    }
    PetscCall(MatDenseRestoreArray(B, &b));
    PetscCall(MatDuplicate(B, MAT_DO_NOT_COPY_VALUES, &X));
    PetscCall(MatMatSolve(F, B, X));
    if (fem->ncached + nnew > fem->maxcached) {
      PetscReal *grown;
      fem->maxcached = PetscMax(2 * fem->maxcached, fem->ncached + nnew);
      PetscCall(PetscMalloc1(9 * fem->nsurf * fem->maxcached, &grown));
      if (fem->ncached) PetscCall(PetscArraycpy(grown, fem->cache, 9 * fem->nsurf * fem->ncached));
      PetscCall(PetscFree(fem->cache));
      fem->cache = grown;
    }
    cols = &fem->cache[9 * fem->nsurf * fem->ncached];
    PetscCall(PetscArrayzero(cols, 9 * fem->nsurf * nnew));
    PetscCall(MatDenseGetArrayRead(X, &x));
    for (PetscInt sv = 0; sv < fem->nsurf; sv++) {
      PetscInt g = fem->surf[sv];
      if (g < lo || g >= lo + nloc) continue;
      for (PetscInt c = 0; c < 3 * nnew; c++)
        for (int d = 0; d < 3; d++) cols[(3 * sv + d) + ns3 * c] = PetscRealPart(x[(g - lo + d) + nloc * c]);
    }
    PetscCall(MatDenseRestoreArrayRead(X, &x));
    PetscCall(MPIU_Allreduce(MPI_IN_PLACE, cols, 9 * fem->nsurf * nnew, MPIU_REAL, MPIU_SUM, body->comm));
    for (PetscInt j = 0; j < nnew; j++) fem->slot[newv[j]] = fem->ncached + j;
    fem->ncached += nnew;
    PetscCall(MatDestroy(&B));
    PetscCall(MatDestroy(&X));
  }
  for (PetscInt i = 0; i < ncols; i++)
    for (PetscInt j = 0; j < ncols; j++) {
      PetscReal w = 0.0;
      for (int va = 0; va < 3; va++) {
        if (si[3 * i + va] < 0) continue;
        for (int vb = 0; vb < 3; vb++) {
          const PetscReal *C;
          if (si[3 * j + vb] < 0) continue;
          C = &fem->cache[9 * fem->nsurf * fem->slot[si[3 * j + vb]] + 3 * si[3 * i + va]];
          for (int d = 0; d < 3; d++)
            for (int e = 0; e < 3; e++) w += co[9 * i + 3 * va + d] * C[d + ns3 * e] * co[9 * j + 3 * vb + e];
        }
      }
      Wb[i * ncols + j] = w;
    }
  PetscCall(PetscFree3(si, co, newv));
  PetscFunctionReturn(0);
}

/* v = R v (or R^T v) on every vertex block of a global vector */
static PetscErrorCode RotateBlocks(FEM *fem, Vec v, PetscBool transpose)
{
  PetscScalar *a;
  PetscInt     n;

  PetscFunctionBegin;
  if (fem->mat->linear) PetscFunctionReturn(0);
  PetscCall(VecGetLocalSize(v, &n));
  PetscCall(VecGetArray(v, &a));
  for (PetscInt i = 0; i < n; i += 3) {
    PetscReal x[3] = {PetscRealPart(a[i]), PetscRealPart(a[i + 1]), PetscRealPart(a[i + 2])}, y[3];
    if (transpose)
      FCMat3TVec(fem->Rwarp, x, y);
    else
      FCMat3Vec(fem->Rwarp, x, y);
    for (int d = 0; d < 3; d++) a[i + d] = y[d];
  }
  PetscCall(VecRestoreArray(v, &a));
  PetscFunctionReturn(0);
}

/* Forgets the step's contact columns: J_b^T, A^-1 J_b^T and their rows of W */
PetscErrorCode FCFEMComplianceReset(FCBody body)
{
  FEM *fem = (FEM *)body->data;

  PetscFunctionBegin;
  PetscCall(MatDestroy(&fem->JT));
  PetscCall(MatDestroy(&fem->X));
  PetscCall(PetscFree(fem->cols));
  PetscCall(PetscFree3(fem->jtr, fem->jtc, fem->jtv));
  fem->ncols = fem->njt = fem->nje = 0;
  PetscFunctionReturn(0);
}

PetscErrorCode FCFEMComplianceDestroy(FCBody body)
{
  FEM *fem = (FEM *)body->data;

  PetscFunctionBegin;
  PetscCall(KSPDestroy(&fem->ksp0));
  PetscCall(MatDestroy(&fem->A0));
  PetscCall(PetscFree2(fem->surf, fem->slot));
  PetscCall(PetscFree(fem->cache));
  PetscCall(MatDestroy(&fem->Fr));
  PetscCall(MatDestroy(&fem->Ar));
  if (fem->rcomm != MPI_COMM_NULL) PetscCallMPI(MPI_Comm_free(&fem->rcomm));
  PetscCall(FCFEMComplianceReset(body));
  PetscFunctionReturn(0);
}

/* Compliance, "dense multi-RHS" builder: J_b^T (dense, n_b x m_b) is solved with the factor of
   A in one MatMatSolve, X = A^-1 J_b^T is kept for the correction, and
   W_b = J_b X accumulates only the rows of J_b that are non-zero (3 per vertex). */
PetscErrorCode FCFEMAddCompliance(FCBody body, PetscInt self, const FCContactSet *set, PetscReal W[])
{
  FEM               *fem = (FEM *)body->data;
  PetscInt           nloc, N, lo, M = set->nrows, ncols = 0, n = 0;
  PetscScalar       *jt;
  const PetscScalar *x;
  Mat                F;
  PC                 pc;
  PetscReal         *Wb;

  PetscFunctionBegin;
  PetscCall(FCFEMComplianceReset(body));
  PetscCheck(strcmp(fem->compliance, "none"), body->comm, PETSC_ERR_PLIB,
             "Body '%s' has contacts but no compliance type", body->name);
  for (PetscInt k = 0; k < set->n; k++)
    for (PetscInt s = 0; s < 2; s++)
      if (set->c[k].body[s] == self) {
        ncols += set->c[k].dim;
        n += set->c[k].dim * 3 * set->c[k].prox[s].nv;
      }
  if (!ncols) PetscFunctionReturn(0);
  PetscCall(PetscMalloc1(ncols, &fem->cols));
  PetscCall(PetscMalloc3(n, &fem->jtr, n, &fem->jtc, n, &fem->jtv));
  PetscCall(VecGetLocalSize(fem->u, &nloc));
  PetscCall(VecGetSize(fem->u, &N));
  PetscCall(VecGetOwnershipRange(fem->u, &lo, NULL));
  /* J_b^T by entries, at most 9 per column (3 vertices x 3 components): the owned DOFs' first (pass
     0, fem->njt of them), then the others' (pass 1, fem->nje in all; the selected-inverse builders
     need every entry, on every rank) */
  for (int pass = 0; pass < 2; pass++) {
    if (pass) fem->njt = fem->nje;
    ncols = 0;
    for (PetscInt k = 0; k < set->n; k++)
      for (PetscInt s = 0; s < 2; s++) {
        const FCContact *c = &set->c[k];
        if (c->body[s] != self) continue;
        for (PetscInt a = 0; a < c->dim; a++, ncols++) {
          PetscReal e[3];
          fem->cols[ncols] = c->row + a;
          Direction(c, s, a, e);
          for (PetscInt vtx = 0; vtx < c->prox[s].nv; vtx++) {
            PetscInt g = c->prox[s].gdof[vtx];
            if (g < 0 || (g >= lo && g < lo + nloc) == (pass == 1)) continue; /* fixed, or the other pass's */
            for (int d = 0; d < 3; d++, fem->nje++) {
              fem->jtr[fem->nje] = g - lo + d;
              fem->jtc[fem->nje] = ncols;
              fem->jtv[fem->nje] = c->prox[s].w[vtx] * e[d];
            }
          }
        }
      }
  }
  fem->ncols = ncols;
  if (!strcmp(fem->compliance, "schur") || !strcmp(fem->compliance, "inverse") ||
      !strcmp(fem->compliance, "redundant") || !strcmp(fem->compliance, "precomputed")) {
    PetscCall(PetscCalloc1(ncols * ncols, &Wb));
    if (!strcmp(fem->compliance, "schur"))
      PetscCall(SchurCompliance(body, ncols, Wb));
    else if (!strcmp(fem->compliance, "inverse") || !strcmp(fem->compliance, "redundant"))
      PetscCall(InverseCompliance(body, ncols, Wb));
    else
      PetscCall(PrecomputedCompliance(body, self, set, ncols, Wb));
    for (PetscInt i = 0; i < ncols; i++)
      for (PetscInt j = 0; j < ncols; j++) W[fem->cols[i] * M + fem->cols[j]] += Wb[i * ncols + j];
    PetscCall(PetscFree(Wb));
    PetscFunctionReturn(0);
  }
  /* dense and sparse: J_b^T as a dense matrix, the right-hand sides of MatMatSolve */
  PetscCall(MatCreateDense(body->comm, nloc, PETSC_DECIDE, N, ncols, NULL, &fem->JT));
  PetscCall(MatDenseGetArray(fem->JT, &jt));
  PetscCall(PetscArrayzero(jt, nloc * ncols));
  for (PetscInt q = 0; q < fem->njt; q++) jt[fem->jtr[q] + fem->jtc[q] * nloc] += fem->jtv[q];
  PetscCall(MatDenseRestoreArray(fem->JT, &jt));
  PetscCall(MatDuplicate(fem->JT, MAT_DO_NOT_COPY_VALUES, &fem->X));
  PetscCall(KSPGetPC(fem->ksp, &pc));
  PetscCall(PCFactorGetMatrix(pc, &F));
  if (!strcmp(fem->compliance, "sparse")) {
    /* sparse right-hand sides: J_b (ncols x N, at most 9 entries a row) handed to MUMPS as is */
    Mat         Bt;
    PetscMPIInt rank;
    PetscCallMPI(MPI_Comm_rank(body->comm, &rank));
    /* MUMPS takes sparse right-hand sides centralized on the host: rank 0 owns every row */
    PetscCall(MatCreateAIJ(body->comm, rank ? 0 : ncols, nloc, ncols, N, 9, NULL, 9, NULL, &Bt));
    PetscCall(MatSetOption(Bt, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_FALSE));
    for (PetscInt q = 0; q < fem->njt; q++)
      PetscCall(MatSetValue(Bt, fem->jtc[q], lo + fem->jtr[q], fem->jtv[q], ADD_VALUES));
    PetscCall(MatAssemblyBegin(Bt, MAT_FINAL_ASSEMBLY));
    PetscCall(MatAssemblyEnd(Bt, MAT_FINAL_ASSEMBLY));
    PetscCall(MatMatTransposeSolve(F, Bt, fem->X));
    PetscCall(MatDestroy(&Bt));
  } else
    PetscCall(MatMatSolve(F, fem->JT, fem->X));
  /* W_b(i, j) = sum over the non-zero rows r of column i of J^T: JT(r, i) X(r, j) */
  PetscCall(PetscCalloc1(ncols * ncols, &Wb));
  PetscCall(MatDenseGetArrayRead(fem->X, &x));
  for (PetscInt q = 0; q < fem->njt; q++)
    for (PetscInt c2 = 0; c2 < ncols; c2++)
      Wb[fem->jtc[q] * ncols + c2] += fem->jtv[q] * PetscRealPart(x[fem->jtr[q] + c2 * nloc]);
  PetscCall(MatDenseRestoreArrayRead(fem->X, &x));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, Wb, ncols * ncols, MPIU_REAL, MPIU_SUM, body->comm));
  for (PetscInt i = 0; i < ncols; i++)
    for (PetscInt j = 0; j < ncols; j++) W[fem->cols[i] * M + fem->cols[j]] += Wb[i * ncols + j];
  PetscCall(PetscFree(Wb));
  PetscFunctionReturn(0);
}

/* eq. 20: dv = dv_free + h A^-1 J_b^T lambda = dv_free + h X lambda_b */
PetscErrorCode FCFEMApplyCorrection(FCBody body, PetscInt self, const FCContactSet *set, const PetscReal lambda[])
{
  FEM               *fem = (FEM *)body->data;
  const PetscScalar *x;
  PetscScalar       *dv;
  PetscInt           nloc;

  PetscFunctionBegin;
  if (!fem->ncols) PetscFunctionReturn(0);
  if (!fem->X) { /* Schur builder: dv += h A^-1 (J_b^T lambda_b), one solve with A's factor;
                    precomputed: the operator of its W, h R A_0^-1 R^T J_b^T lambda_b */
    Vec          rhs;
    PetscScalar *r;
    PetscCall(VecDuplicate(fem->u, &rhs)); /* J_b^T (h lambda_b), from the owned entries */
    PetscCall(VecGetArray(rhs, &r));
    for (PetscInt q = 0; q < fem->njt; q++) r[fem->jtr[q]] += fem->jtv[q] * body->h * lambda[fem->cols[fem->jtc[q]]];
    PetscCall(VecRestoreArray(rhs, &r));
    if (fem->surf) {
      KSP ksp;
      PetscCall(ReferenceSolver(fem, &ksp));
      PetscCall(RotateBlocks(fem, rhs, PETSC_TRUE));
      PetscCall(KSPSolve(ksp, rhs, fem->work));
      PetscCall(RotateBlocks(fem, fem->work, PETSC_FALSE));
    } else
      PetscCall(KSPSolve(fem->ksp, rhs, fem->work));
    PetscCall(VecAXPY(fem->dv, 1.0, fem->work));
    PetscCall(VecDestroy(&rhs));
    PetscFunctionReturn(0);
  }
  PetscCall(VecGetLocalSize(fem->u, &nloc));
  PetscCall(MatDenseGetArrayRead(fem->X, &x));
  PetscCall(VecGetArray(fem->dv, &dv));
  for (PetscInt i = 0; i < fem->ncols; i++) {
    PetscReal l = body->h * lambda[fem->cols[i]];
    if (l == 0.0) continue;
    for (PetscInt r = 0; r < nloc; r++) dv[r] += l * x[r + i * nloc];
  }
  PetscCall(VecRestoreArray(fem->dv, &dv));
  PetscCall(MatDenseRestoreArrayRead(fem->X, &x));
  PetscFunctionReturn(0);
}

/* The selected-inverse builders' settings (before FCBodyFEMSetComplianceType; the scene reads them
   from -compliance_inverse_block, -compliance_redundant_groups, -compliance_redundant_memory_limit):
   MUMPS' ICNTL(27) while it computes the entries of A^-1, the number of copies of A the redundant
   builder keeps, and the bytes per rank a copy's factorization may take */
PetscErrorCode FCBodyFEMSetInverseOptions(FCBody body, PetscInt block, PetscInt groups, PetscReal memory_limit)
{
  FEM        *fem = NULL;
  PetscMPIInt size;

  PetscFunctionBegin;
  PetscCall(FCFEMGet(body, &fem));
  PetscCallMPI(MPI_Comm_size(body->comm, &size));
  PetscCheck(groups >= 1 && groups <= size, body->comm, PETSC_ERR_ARG_OUTOFRANGE,
             "Redundant groups %" PetscInt_FMT " for body '%s' not in [1, %d]", groups, body->name, size);
  PetscCheck(!fem->Fr, body->comm, PETSC_ERR_ARG_WRONGSTATE, "Redundant groups of body '%s' set after its copies",
             body->name);
  PetscCheck(memory_limit > 0, body->comm, PETSC_ERR_ARG_OUTOFRANGE, "Redundant memory limit %g for body '%s' not > 0",
             (double)memory_limit, body->name);
  PetscCheck(block != 0, body->comm, PETSC_ERR_ARG_OUTOFRANGE, "Inverse block 0 for body '%s'", body->name);
  fem->iblock  = block;
  fem->rgroups = groups;
  fem->rmemory = memory_limit;
  PetscFunctionReturn(0);
}

/* -compliance_type of the scene: how A^-1 J^T is computed for the compliance (eq. 17) */
PetscErrorCode FCBodyFEMSetComplianceType(FCBody body, const char type[])
{
  FEM *fem = NULL;
  PetscFunctionBegin;
  PetscCall(FCFEMGet(body, &fem));
  {
    static const char *const known[] = {"dense", "sparse", "schur", "inverse", "redundant", "precomputed"};
    PetscBool                found   = PETSC_FALSE;
    for (size_t k = 0; k < sizeof(known) / sizeof(known[0]); k++) found = found || !strcmp(type, known[k]);
    PetscCheck(found, body->comm, PETSC_ERR_USER_INPUT,
               "Unknown compliance type '%s' in -compliance_type (known: dense, sparse, schur, inverse, redundant, "
               "precomputed)",
               type);
  }
  if (!strcmp(type, "sparse")) {
    PetscMPIInt size;
    PetscCallMPI(MPI_Comm_size(body->comm, &size));
    /* MatMatTransposeSolve with MUMPS (PETSc 3.18.5, MUMPS 5.5) returned a wrong A^-1 J^T on
       2 ranks in our tests (contact forces diverged from the dense builder): refuse it there */
    PetscCheck(size == 1, body->comm, PETSC_ERR_USER_INPUT,
               "-compliance_type sparse is available on one MPI rank only (PETSc 3.18's parallel MUMPS sparse "
               "right-hand sides gave wrong results); use -compliance_type dense");
  }
  PetscCall(PetscStrncpy(fem->compliance, type, sizeof(fem->compliance)));
  if (!strcmp(type, "precomputed")) PetscCall(PrecomputedSetUp(body)); /* A is still A_0 */
  if (!strcmp(type, "inverse") || !strcmp(type, "redundant")) {        /* MUMPS' selected inverse entries */
    PC            pc;
    Mat           F;
    MatSolverType stype;
    PetscBool     mumps;
    PetscCall(KSPGetPC(fem->ksp, &pc));
    PetscCall(PCFactorGetMatrix(pc, &F));
    PetscCall(MatFactorGetSolverType(F, &stype));
    PetscCall(PetscStrcmp(stype, MATSOLVERMUMPS, &mumps));
    PetscCheck(mumps, body->comm, PETSC_ERR_USER_INPUT,
               "-compliance_type %s needs MUMPS as the factorization of body '%s' (it has '%s' from "
               "-%spc_factor_mat_solver_type): use MUMPS or -compliance_type dense",
               type, body->name, stype, body->prefix);
  }
  if (!strcmp(type, "redundant")) PetscCall(FCFEMComplianceFactor(body)); /* the copies of A, at set-up */
  PetscFunctionReturn(0);
}
