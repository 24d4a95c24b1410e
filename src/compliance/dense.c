/* Compliance builders "dense" and "sparse" (multiple right-hand sides): J_b^T (n_b x m_b) is
   solved with the factor of A in one solve, X = A^-1 J_b^T is kept for the correction (eq. 20),
   and W_b = J_b X accumulates only the rows of J_b that are non-zero (3 per vertex).
     dense   J_b^T as a dense matrix, MatMatSolve
     sparse  J_b handed to MUMPS as sparse right-hand sides (MatMatTransposeSolve; 1 rank) */
#include "complianceimpl.h"

typedef struct {
  PetscBool sparse;
  Mat       JT, X; /* J_b^T and A^-1 J_b^T (dense, the layout of A's rows) */
} Dense;

static PetscErrorCode Reset_Dense(FCCompliance comp)
{
  Dense *dn = (Dense *)comp->data;

  PetscFunctionBegin;
  PetscCall(MatDestroy(&dn->JT));
  PetscCall(MatDestroy(&dn->X));
  PetscFunctionReturn(0);
}

static PetscErrorCode Destroy_Dense(FCCompliance comp)
{
  PetscFunctionBegin;
  PetscCall(Reset_Dense(comp));
  PetscCall(PetscFree(comp->data));
  PetscFunctionReturn(0);
}

/* MatMatTransposeSolve with MUMPS (PETSc 3.18.5, MUMPS 5.5) returned a wrong A^-1 J^T on 2 ranks
   in our tests (contact forces diverged from the dense builder): sparse is refused there */
static PetscErrorCode SetUp_Sparse(FCCompliance comp)
{
  PetscMPIInt size;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_size(comp->ctx.comm, &size));
  PetscCheck(size == 1, comp->ctx.comm, PETSC_ERR_USER_INPUT,
             "-compliance_type sparse is available on one MPI rank only (PETSc 3.18's parallel MUMPS sparse "
             "right-hand sides gave wrong results); use -compliance_type dense");
  PetscFunctionReturn(0);
}

static PetscErrorCode Build_Dense(FCCompliance comp, PetscInt self, const FCContactSet *set, PetscReal Wb[])
{
  Dense             *dn = (Dense *)comp->data;
  PetscInt           nloc, N, lo, ncols = comp->ncols;
  PetscScalar       *jt;
  const PetscScalar *x;
  Mat                F;

  PetscFunctionBegin;
  PetscCall(VecGetLocalSize(comp->ctx.u, &nloc));
  PetscCall(VecGetSize(comp->ctx.u, &N));
  PetscCall(VecGetOwnershipRange(comp->ctx.u, &lo, NULL));
  PetscCall(MatCreateDense(comp->ctx.comm, nloc, PETSC_DECIDE, N, ncols, NULL, &dn->JT));
  PetscCall(MatDenseGetArray(dn->JT, &jt));
  PetscCall(PetscArrayzero(jt, nloc * ncols));
  for (PetscInt q = 0; q < comp->njt; q++) jt[comp->jtr[q] + comp->jtc[q] * nloc] += comp->jtv[q];
  PetscCall(MatDenseRestoreArray(dn->JT, &jt));
  PetscCall(MatDuplicate(dn->JT, MAT_DO_NOT_COPY_VALUES, &dn->X));
  PetscCall(FCComplianceGetFactor(comp, &F));
  if (dn->sparse) {
    /* J_b (ncols x N, at most 9 entries a row); MUMPS takes sparse right-hand sides centralized on
       the host: rank 0 owns every row */
    Mat         Bt;
    PetscMPIInt rank;
    PetscCallMPI(MPI_Comm_rank(comp->ctx.comm, &rank));
    PetscCall(MatCreateAIJ(comp->ctx.comm, rank ? 0 : ncols, nloc, ncols, N, 9, NULL, 9, NULL, &Bt));
    PetscCall(MatSetOption(Bt, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_FALSE));
    for (PetscInt q = 0; q < comp->njt; q++)
      PetscCall(MatSetValue(Bt, comp->jtc[q], lo + comp->jtr[q], comp->jtv[q], ADD_VALUES));
    PetscCall(MatAssemblyBegin(Bt, MAT_FINAL_ASSEMBLY));
    PetscCall(MatAssemblyEnd(Bt, MAT_FINAL_ASSEMBLY));
    PetscCall(MatMatTransposeSolve(F, Bt, dn->X));
    PetscCall(MatDestroy(&Bt));
  } else
    PetscCall(MatMatSolve(F, dn->JT, dn->X));
  /* W_b(i, j) = sum over the non-zero rows r of column i of J^T: JT(r, i) X(r, j) */
  PetscCall(MatDenseGetArrayRead(dn->X, &x));
  for (PetscInt q = 0; q < comp->njt; q++)
    for (PetscInt c2 = 0; c2 < ncols; c2++)
      Wb[comp->jtc[q] * ncols + c2] += comp->jtv[q] * PetscRealPart(x[comp->jtr[q] + c2 * nloc]);
  PetscCall(MatDenseRestoreArrayRead(dn->X, &x));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, Wb, ncols * ncols, MPIU_REAL, MPIU_SUM, comp->ctx.comm));
  PetscFunctionReturn(0);
}

/* eq. 20: dv = dv_free + h A^-1 J_b^T lambda = dv_free + h X lambda_b */
static PetscErrorCode Correct_Dense(FCCompliance comp, PetscReal h, const PetscReal lambda[], Vec dv)
{
  Dense             *dn = (Dense *)comp->data;
  const PetscScalar *x;
  PetscScalar       *a;
  PetscInt           nloc;

  PetscFunctionBegin;
  PetscCall(VecGetLocalSize(dv, &nloc));
  PetscCall(MatDenseGetArrayRead(dn->X, &x));
  PetscCall(VecGetArray(dv, &a));
  for (PetscInt i = 0; i < comp->ncols; i++) {
    PetscReal l = h * lambda[comp->cols[i]];
    if (l == 0.0) continue;
    for (PetscInt r = 0; r < nloc; r++) a[r] += l * x[r + i * nloc];
  }
  PetscCall(VecRestoreArray(dv, &a));
  PetscCall(MatDenseRestoreArrayRead(dn->X, &x));
  PetscFunctionReturn(0);
}

static PetscErrorCode Create(FCCompliance comp, PetscBool sparse)
{
  Dense *dn;

  PetscFunctionBegin;
  PetscCall(PetscNew(&dn));
  dn->sparse        = sparse;
  comp->data        = dn;
  comp->ops.setup   = sparse ? SetUp_Sparse : NULL;
  comp->ops.build   = Build_Dense;
  comp->ops.correct = Correct_Dense;
  comp->ops.reset   = Reset_Dense;
  comp->ops.destroy = Destroy_Dense;
  PetscFunctionReturn(0);
}

PetscErrorCode FCComplianceCreate_Dense(FCCompliance comp)
{
  PetscFunctionBegin;
  PetscCall(Create(comp, PETSC_FALSE));
  PetscFunctionReturn(0);
}

PetscErrorCode FCComplianceCreate_Sparse(FCCompliance comp)
{
  PetscFunctionBegin;
  PetscCall(Create(comp, PETSC_TRUE));
  PetscFunctionReturn(0);
}
