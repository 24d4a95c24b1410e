/* Compliance builder "schur": MUMPS' Schur complement of the augmented matrix
   [[0, J_b], [J_b^T, A]] on its constraint rows is -J_b A^-1 J_b^T (eq. 17). The correction is one
   solve with A's own factor (compliance.c). */
#include "complianceimpl.h"

/* The augmented symmetric matrix K = [[0, J_b], [J_b^T, A]]
   (constraint rows first, so that the Schur indices live on rank 0) is factored with
   MatFactorSetSchurIS on the constraint rows; MUMPS returns S = -J_b A^-1 J_b^T, centralized on
   rank 0, which is broadcast. A is copied into K every call (the pattern changes with the
   contacts), and the correction then needs one solve with A's own factor. */
static PetscErrorCode Build_Schur(FCCompliance comp, PetscInt self, const FCContactSet *set, PetscReal Wb[])
{
  PetscInt      ncols = comp->ncols;
  PetscMPIInt   rank;
  PetscInt      nloc, N, lo, hi, mloc;
  Mat           K, F, S;
  IS            is;
  MatFactorInfo info;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_rank(comp->ctx.comm, &rank));
  PetscCall(VecGetLocalSize(comp->ctx.u, &nloc));
  PetscCall(VecGetSize(comp->ctx.u, &N));
  PetscCall(VecGetOwnershipRange(comp->ctx.u, &lo, &hi));
  mloc = nloc + (rank ? 0 : ncols);
  PetscCall(MatCreateAIJ(comp->ctx.comm, mloc, mloc, N + ncols, N + ncols, 96, NULL, 96, NULL, &K));
  PetscCall(MatSetOption(K, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_FALSE));
  for (PetscInt r = lo; r < hi; r++) { /* A, shifted by ncols */
    PetscInt           nc;
    const PetscInt    *cols;
    const PetscScalar *vals;
    PetscInt           row = r + ncols, shifted[512];
    PetscCall(MatGetRow(comp->ctx.A, r, &nc, &cols, &vals));
    PetscCheck(nc <= 512, PETSC_COMM_SELF, PETSC_ERR_SUP, "Row of A with %" PetscInt_FMT " entries", nc);
    for (PetscInt k = 0; k < nc; k++) shifted[k] = cols[k] + ncols;
    PetscCall(MatSetValues(K, 1, &row, nc, shifted, vals, ADD_VALUES));
    PetscCall(MatRestoreRow(comp->ctx.A, r, &nc, &cols, &vals));
  }
  if (rank == 0)
    for (PetscInt i = 0; i < ncols; i++) PetscCall(MatSetValue(K, i, i, 0.0, ADD_VALUES)); /* structural diagonal */
  for (PetscInt q = 0; q < comp->njt; q++) {                                               /* J_b^T and J_b */
    PetscCall(MatSetValue(K, lo + comp->jtr[q] + ncols, comp->jtc[q], comp->jtv[q], ADD_VALUES));
    PetscCall(MatSetValue(K, comp->jtc[q], lo + comp->jtr[q] + ncols, comp->jtv[q], ADD_VALUES));
  }
  PetscCall(MatAssemblyBegin(K, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(K, MAT_FINAL_ASSEMBLY));
  PetscCall(MatSetOption(K, MAT_SYMMETRIC, PETSC_TRUE));
  PetscCall(MatGetFactor(K, MATSOLVERMUMPS, MAT_FACTOR_CHOLESKY, &F));
  PetscCall(ISCreateStride(PETSC_COMM_SELF, rank ? 0 : ncols, 0, 1, &is));
  PetscCall(MatFactorSetSchurIS(F, is));
  PetscCall(MatFactorInfoInitialize(&info));
  PetscCall(MatCholeskyFactorSymbolic(F, K, NULL, &info));
  PetscCall(FCMumpsCholeskyChecked(&F, K, is, "the augmented matrix [[0, J], [J^T, A]]", comp->ctx.name));
  PetscCall(MatFactorCreateSchurComplement(F, &S, NULL));
  if (rank == 0) {
    const PetscScalar *sa;
    PetscCall(MatDenseGetArrayRead(S, &sa));
    for (PetscInt i = 0; i < ncols; i++) /* column-major, symmetric */
      for (PetscInt j = 0; j < ncols; j++) Wb[i * ncols + j] = -PetscRealPart(sa[i + j * ncols]);
    PetscCall(MatDenseRestoreArrayRead(S, &sa));
  }
  PetscCallMPI(MPI_Bcast(Wb, (PetscMPIInt)(ncols * ncols), MPIU_REAL, 0, comp->ctx.comm));
  PetscCall(MatDestroy(&S));
  PetscCall(MatDestroy(&F));
  PetscCall(MatDestroy(&K));
  PetscCall(ISDestroy(&is));
  PetscFunctionReturn(0);
}

PetscErrorCode FCComplianceCreate_Schur(FCCompliance comp)
{
  PetscFunctionBegin;
  comp->ops.build = Build_Schur;
  PetscFunctionReturn(0);
}
