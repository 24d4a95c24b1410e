/* The generalized Jacobian of the Alart-Curnier function, H = A + B W (newton.c), and the solve of a
   Newton step H dr = -Phi. H has the block pattern of W plus its diagonal: contacts couple only
   through a body they share. A problem whose W has few nonzero blocks (rigid bodies, FCLIB's
   block-sparse problems) is factored as a sparse matrix, by MUMPS through PETSc with threshold
   pivoting; the pattern is the same at every Newton step of a solve, so its analysis is done once.
   A dense W (an FE body couples every contact on it) is factored by a dense LU with partial
   pivoting (LAPACK getrf). -contact_newton_lu auto|dense|sparse chooses (auto: sparse from
   FC_NEWTON_SPARSE_MIN_ROWS rows on, when W's nonzero blocks hold at most FC_NEWTON_SPARSE_FILL of
   its entries). */
#include "contactimpl.h"
#include <petscblaslapack.h>

#define FC_NEWTON_SPARSE_FILL 0.2
#define FC_NEWTON_SPARSE_MIN_ROWS 300 /* below, a dense LU costs less than MUMPS' set-up */

struct _n_FCNewtonJacobian {
  FCContactProblem p;
  PetscBool        sparse;
  PetscInt        *bptr, *bcol; /* H's block pattern: W's nonzero blocks and the diagonal, columns sorted */
  PetscInt        *wblk;        /* the block of W's block CSR for each pattern block (-1: none); dense W: unused */
  /* dense */
  PetscReal    *H; /* row-major n x n */
  PetscBLASInt *piv;
  /* sparse */
  Mat        Hs, F;
  Vec        b, x;
  PetscInt  *cols; /* the scalar columns of each contact's rows (its blocks' columns), from cptr */
  PetscInt  *cptr; /* per contact */
  PetscReal *hrow;
  PetscBool  analysed;
};

/* Row a of W's block (i, j) (d_j contiguous values), k = the pattern block */
static inline const PetscReal *WBlockRow(FCNewtonJacobian J, PetscInt i, PetscInt k, PetscInt a)
{
  FCContactProblem p = J->p;
  PetscInt         j = J->bcol[k];
  if (p->Wd) return FCContactProblemRow(p, p->off[i] + a) + p->off[j];
  return J->wblk[k] < 0 ? NULL : &p->val[p->boff[J->wblk[k]] + a * p->dim[j]];
}

/* The block pattern of H: W's nonzero blocks and every diagonal block */
static PetscErrorCode BlockPattern(FCNewtonJacobian J, PetscInt *nnz)
{
  FCContactProblem p  = J->p;
  PetscInt         nc = p->nc, nb = 0;

  PetscFunctionBegin;
  PetscCall(PetscMalloc1(nc + 1, &J->bptr));
  J->bptr[0] = 0;
  *nnz       = 0;
  if (p->Wd) { /* the nonzero blocks of the dense W, counted, then listed */
    for (PetscInt pass = 0; pass < 2; pass++) {
      nb = 0;
      for (PetscInt i = 0; i < nc; i++) {
        for (PetscInt j = 0; j < nc; j++) {
          PetscBool nz = i == j ? PETSC_TRUE : PETSC_FALSE;
          for (PetscInt a = 0; a < p->dim[i] && !nz; a++) {
            const PetscReal *w = FCContactProblemRow(p, p->off[i] + a) + p->off[j];
            for (PetscInt c = 0; c < p->dim[j]; c++)
              if (w[c] != 0.0) nz = PETSC_TRUE;
          }
          if (!nz) continue;
          if (pass)
            J->bcol[nb] = j;
          else
            *nnz += p->dim[i] * p->dim[j];
          nb++;
        }
        if (pass) J->bptr[i + 1] = nb;
      }
      if (!pass) PetscCall(PetscMalloc1(nb + 1, &J->bcol));
    }
    PetscFunctionReturn(0);
  }
  /* block CSR: its blocks, with the diagonal added where W has none */
  PetscCall(PetscMalloc2(p->rowptr[nc] + nc + 1, &J->bcol, p->rowptr[nc] + nc + 1, &J->wblk));
  for (PetscInt i = 0; i < nc; i++) {
    PetscBool diag = PETSC_FALSE;
    for (PetscInt b = p->rowptr[i]; b < p->rowptr[i + 1]; b++) {
      PetscInt j = p->col[b];
      if (!diag && j >= i) {
        if (j > i) J->bcol[nb] = i, J->wblk[nb] = -1, nb++;
        diag = PETSC_TRUE;
      }
      J->bcol[nb] = j, J->wblk[nb] = b, nb++;
    }
    if (!diag) J->bcol[nb] = i, J->wblk[nb] = -1, nb++;
    J->bptr[i + 1] = nb;
  }
  for (PetscInt i = 0; i < nc; i++)
    for (PetscInt k = J->bptr[i]; k < J->bptr[i + 1]; k++) *nnz += p->dim[i] * p->dim[J->bcol[k]];
  PetscFunctionReturn(0);
}

PetscErrorCode FCNewtonJacobianCreate(FCContactProblem p, FCNewtonLU lu, FCNewtonJacobian *Jout)
{
  FCNewtonJacobian J;
  PetscInt         n = p->n, nnz;

  PetscFunctionBegin;
  PetscCall(PetscNew(&J));
  J->p = p;
  PetscCall(BlockPattern(J, &nnz));
  J->sparse = lu == FC_NEWTON_LU_SPARSE || (lu == FC_NEWTON_LU_AUTO && n >= FC_NEWTON_SPARSE_MIN_ROWS &&
                                            nnz <= FC_NEWTON_SPARSE_FILL * n * n)
                  ? PETSC_TRUE
                  : PETSC_FALSE;
  if (!J->sparse) {
    PetscCall(PetscMalloc2((size_t)n * n, &J->H, n, &J->piv));
  } else {
    PetscInt *rnnz;
    PetscCall(PetscMalloc1(n, &rnnz));
    PetscCall(PetscMalloc2(p->nc + 1, &J->cptr, n, &J->hrow));
    J->cptr[0] = 0;
    for (PetscInt i = 0; i < p->nc; i++) {
      PetscInt w = 0;
      for (PetscInt k = J->bptr[i]; k < J->bptr[i + 1]; k++) w += p->dim[J->bcol[k]];
      for (PetscInt a = 0; a < p->dim[i]; a++) rnnz[p->off[i] + a] = w;
      J->cptr[i + 1] = J->cptr[i] + w;
    }
    PetscCall(PetscMalloc1(J->cptr[p->nc] + 1, &J->cols));
    for (PetscInt i = 0; i < p->nc; i++) {
      PetscInt w = J->cptr[i];
      for (PetscInt k = J->bptr[i]; k < J->bptr[i + 1]; k++)
        for (PetscInt c = 0; c < p->dim[J->bcol[k]]; c++) J->cols[w++] = p->off[J->bcol[k]] + c;
    }
    PetscCall(MatCreateSeqAIJ(PETSC_COMM_SELF, n, n, 0, rnnz, &J->Hs));
    PetscCall(MatSetOption(J->Hs, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_TRUE));
    PetscCall(PetscFree(rnnz));
    PetscCall(VecCreateSeqWithArray(PETSC_COMM_SELF, 1, n, NULL, &J->b));
    PetscCall(VecCreateSeq(PETSC_COMM_SELF, n, &J->x));
  }
  PetscCall(PetscInfo(NULL,
                      "Newton Jacobian: %" PetscInt_FMT " rows, %" PetscInt_FMT " nonzeros (%.3g of n^2), %s LU\n", n,
                      nnz, n ? (double)nnz / ((double)n * n) : 0.0, J->sparse ? "sparse" : "dense"));
  *Jout = J;
  PetscFunctionReturn(0);
}

PetscErrorCode FCNewtonJacobianDestroy(FCNewtonJacobian *J)
{
  PetscFunctionBegin;
  if (!*J) PetscFunctionReturn(0);
  PetscCall(PetscFree((*J)->bptr));
  if ((*J)->p->Wd)
    PetscCall(PetscFree((*J)->bcol));
  else
    PetscCall(PetscFree2((*J)->bcol, (*J)->wblk));
  if ((*J)->sparse) {
    PetscCall(PetscFree2((*J)->cptr, (*J)->hrow));
    PetscCall(PetscFree((*J)->cols));
    PetscCall(MatDestroy(&(*J)->Hs));
    PetscCall(MatDestroy(&(*J)->F));
    PetscCall(VecDestroy(&(*J)->b));
    PetscCall(VecDestroy(&(*J)->x));
  } else
    PetscCall(PetscFree2((*J)->H, (*J)->piv));
  PetscCall(PetscFree(*J));
  PetscFunctionReturn(0);
}

/* Row k of contact i's rows of H = A + B W + reg I into h over the columns of the pattern blocks of row i
   (dense: h is the whole row, zeroed by the caller) */
static void HRow(FCNewtonJacobian J, PetscInt i, PetscInt k, const PetscReal A[], const PetscReal B[], PetscReal reg,
                 PetscReal h[], PetscBool dense)
{
  FCContactProblem p = J->p;
  PetscInt         d = p->dim[i], w = 0;

  for (PetscInt kb = J->bptr[i]; kb < J->bptr[i + 1]; kb++) {
    PetscInt   j = J->bcol[kb], dj = p->dim[j];
    PetscReal *hj = dense ? &h[p->off[j]] : &h[w];
    if (!dense)
      for (PetscInt c = 0; c < dj; c++) hj[c] = 0.0;
    for (PetscInt a = 0; a < d; a++) {
      PetscReal        b  = B[9 * i + k * d + a];
      const PetscReal *wr = b != 0.0 ? WBlockRow(J, i, kb, a) : NULL;
      if (wr)
        for (PetscInt c = 0; c < dj; c++) hj[c] += b * wr[c];
    }
    if (j == i) {
      for (PetscInt a = 0; a < d; a++) hj[a] += A[9 * i + k * d + a];
      hj[k] += reg;
    }
    w += dj;
  }
}

/* Solve H dr = rhs in place (rhs: -Phi in, dr out), H = A + B W + reg I with A, B per contact d x d (9 each,
   row-major); *ok = PETSC_FALSE where H is singular (rhs then undefined) */
PetscErrorCode FCNewtonJacobianSolve(FCNewtonJacobian J, const PetscReal A[], const PetscReal B[], PetscReal reg,
                                     PetscReal rhs[], PetscBool *ok)
{
  FCContactProblem p = J->p;
  PetscInt         n = p->n;

  PetscFunctionBegin;
  *ok = PETSC_TRUE;
  if (!J->sparse) {
    PetscBLASInt bn, one = 1, info;
    PetscCall(PetscBLASIntCast(n, &bn));
    PetscCall(PetscArrayzero(J->H, (size_t)n * n));
    for (PetscInt i = 0; i < p->nc; i++)
      for (PetscInt k = 0; k < p->dim[i]; k++) HRow(J, i, k, A, B, reg, &J->H[(size_t)(p->off[i] + k) * n], PETSC_TRUE);
    /* row-major H is H^T column-major: solve with getrs "T" */
    PetscCallBLAS("LAPACKgetrf", LAPACKgetrf_(&bn, &bn, J->H, &bn, J->piv, &info));
    if (info == 0) PetscCallBLAS("LAPACKgetrs", LAPACKgetrs_("T", &bn, &one, J->H, &bn, J->piv, rhs, &bn, &info));
    *ok = info == 0 ? PETSC_TRUE : PETSC_FALSE;
    PetscFunctionReturn(0);
  }
  for (PetscInt i = 0; i < p->nc; i++)
    for (PetscInt k = 0; k < p->dim[i]; k++) {
      PetscInt row = p->off[i] + k;
      HRow(J, i, k, A, B, reg, J->hrow, PETSC_FALSE);
      PetscCall(
          MatSetValues(J->Hs, 1, &row, J->cptr[i + 1] - J->cptr[i], &J->cols[J->cptr[i]], J->hrow, INSERT_VALUES));
    }
  PetscCall(MatAssemblyBegin(J->Hs, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(J->Hs, MAT_FINAL_ASSEMBLY));
  {
    MatFactorInfo  info;
    MatFactorError err;
    PetscCall(MatFactorInfoInitialize(&info));
    if (!J->analysed) {
      IS rp, cp;
      PetscCall(MatGetFactor(J->Hs, MATSOLVERMUMPS, MAT_FACTOR_LU, &J->F));
      PetscCall(MatMumpsSetIcntl(J->F, 4, 0));  /* no MUMPS output */
      PetscCall(MatMumpsSetIcntl(J->F, 24, 1)); /* a null pivot (redundant contacts) is detected, not fatal */
      PetscCall(MatGetOrdering(J->Hs, MATORDERINGNATURAL, &rp, &cp));
      PetscCall(MatLUFactorSymbolic(J->F, J->Hs, rp, cp, &info));
      PetscCall(ISDestroy(&rp));
      PetscCall(ISDestroy(&cp));
      J->analysed = PETSC_TRUE;
    }
    PetscCall(MatLUFactorNumeric(J->F, J->Hs, &info));
    PetscCall(MatFactorGetError(J->F, &err));
    if (err != MAT_FACTOR_NOERROR) {
      *ok = PETSC_FALSE;
      PetscCall(MatFactorClearError(J->F));
      PetscFunctionReturn(0);
    }
  }
  PetscCall(VecPlaceArray(J->b, rhs));
  PetscCall(MatSolve(J->F, J->b, J->x));
  PetscCall(VecResetArray(J->b));
  {
    const PetscReal *x;
    PetscCall(VecGetArrayRead(J->x, &x));
    PetscCall(PetscArraycpy(rhs, x, n));
    PetscCall(VecRestoreArrayRead(J->x, &x));
  }
  PetscFunctionReturn(0);
}
