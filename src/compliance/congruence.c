/* The products the selected-inverse builders (inverse.c, condensed.c) share: J_S by columns of the
   contact DOFs S, and W_b = J_S C J_S^T from a dense C = (A^-1)_SS, by columns of C or by rows of
   W_b (whole, or this rank's rows from some columns of C) */
#include "complianceimpl.h"

/* S (sorted DOFs that J_b touches, the same on every rank: contacts are replicated) and J_S by
   columns of S: for S index j, the rows a of J_b with J_b(a, S_j) != 0; from all the entries of
   J_b^T (comp->jtr + lo: global DOF) */
PetscErrorCode FCComplianceContactDofs(FCCompliance comp, PetscInt *ns_, PetscInt **S_, PetscInt **cptr_,
                                       PetscInt **crow_, PetscReal **cval_)
{
  PetscInt   n = comp->nje, ns = n, *S, *cptr, *crow, *cnt, lo;
  PetscReal *cval;

  PetscFunctionBegin;
  PetscCall(VecGetOwnershipRange(comp->ctx.u, &lo, NULL));
  PetscCall(PetscMalloc1(n + 1, &S));
  for (PetscInt q = 0; q < n; q++) S[q] = comp->jtr[q] + lo;
  PetscCall(PetscSortRemoveDupsInt(&ns, S));
  PetscCall(PetscCalloc1(ns + 1, &cptr));
  PetscCall(PetscCalloc1(ns + 1, &cnt));
  PetscCall(PetscMalloc1(n + 1, &crow));
  PetscCall(PetscMalloc1(n + 1, &cval));
  for (int pass = 0; pass < 2; pass++) { /* count, then fill */
    for (PetscInt q = 0; q < n; q++) {
      PetscInt at;
      PetscCall(PetscFindInt(comp->jtr[q] + lo, ns, S, &at));
      if (!pass)
        cptr[at + 1]++;
      else {
        PetscInt r = cptr[at] + cnt[at]++;
        crow[r]    = comp->jtc[q];
        cval[r]    = comp->jtv[q];
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

/* W_b += the part of J_S C J_S^T from column j of C = (A^-1)_SS (Ccol: C(:, j) in the order of
   S): T = (J_S C)(:, j), then W_b(b, a) += T(a) J_S(b, j); T is ncols of work. W_b is symmetric,
   so the term of (a, b) goes to (b, a): a row of W_b, contiguous, where the column took a stride of
   ncols per entry */
void FCComplianceAddColumn(PetscInt ncols, PetscInt ns, const PetscInt cptr[], const PetscInt crow[],
                           const PetscReal cval[], PetscInt j, const PetscScalar Ccol[], PetscReal T[], PetscReal Wb[])
{
  for (PetscInt a = 0; a < ncols; a++) T[a] = 0.0;
  for (PetscInt i = 0; i < ns; i++)
    for (PetscInt q = cptr[i]; q < cptr[i + 1]; q++) T[crow[q]] += cval[q] * PetscRealPart(Ccol[i]);
  for (PetscInt q = cptr[j]; q < cptr[j + 1]; q++) {
    PetscReal *row = Wb + crow[q] * ncols, v = cval[q];
    for (PetscInt a = 0; a < ncols; a++) row[a] += T[a] * v;
  }
}

/* Row a of W_b = J_T C J_T^T is (J_T C)(a, :) J_T^T: the row q = (J_T C)(a, :) combines the columns
   of C (C symmetric: a column is a row) that row a of J_T touches, 1 to 9 of them, one pass of nt
   each; then W_b(a, b) = sum over row b of J_T of q at its columns. J_T by rows comes from its
   columns by one transposition. Per row, 2 passes of nt and ncols over data that stays in cache,
   where FCComplianceAddColumn cleared and scattered into a work vector of ncols for every column
   of C */
PetscErrorCode FCComplianceAddCongruence(PetscInt ncols, PetscInt a0, PetscInt a1, PetscInt nt, const PetscInt cptr[],
                                         const PetscInt crow[], const PetscReal cval[], const PetscInt pos[],
                                         const PetscInt lcol[], PetscInt ldc, const PetscReal C[], PetscReal Wb[])
{
  PetscInt  *rptr, *rcol, *fill, nnz = cptr[nt];
  PetscReal *rval, *q;

  PetscFunctionBegin;
  PetscCall(PetscCalloc3(ncols + 1, &rptr, nnz + 1, &rcol, ncols + 1, &fill));
  PetscCall(PetscMalloc2(nnz + 1, &rval, nt + 1, &q));
  for (PetscInt k = 0; k < nnz; k++) rptr[crow[k] + 1]++;
  for (PetscInt a = 0; a < ncols; a++) rptr[a + 1] += rptr[a];
  for (PetscInt i = 0; i < nt; i++) /* J_T by rows: the T index of each entry, and its value */
    for (PetscInt k = cptr[i]; k < cptr[i + 1]; k++) {
      PetscInt at = rptr[crow[k]] + fill[crow[k]]++;
      rcol[at]    = i;
      rval[at]    = cval[k];
    }
  for (PetscInt a = a0; a < a1; a++) {
    PetscReal *w   = Wb + (a - a0) * ncols;
    PetscBool  any = PETSC_FALSE;
    if (rptr[a] == rptr[a + 1]) continue;
    for (PetscInt i = 0; i < nt; i++) q[i] = 0.0;
    for (PetscInt k = rptr[a]; k < rptr[a + 1]; k++) { /* q += J_T(a, t) C(:, t) */
      PetscInt         col = lcol ? lcol[pos[rcol[k]]] : pos[rcol[k]];
      const PetscReal *c, v = rval[k];
      if (col < 0) continue; /* not among the columns given */
      c   = C + col * ldc;
      any = PETSC_TRUE;
      for (PetscInt i = 0; i < nt; i++) q[i] += v * c[pos[i]];
    }
    if (!any) continue;
    for (PetscInt b = 0; b < ncols; b++) { /* W_b(a, b) += q . J_T(b, :) */
      PetscReal sum = 0.0;
      for (PetscInt k = rptr[b]; k < rptr[b + 1]; k++) sum += rval[k] * q[rcol[k]];
      w[b] += sum;
    }
  }
  PetscCall(PetscFree3(rptr, rcol, fill));
  PetscCall(PetscFree2(rval, q));
  PetscFunctionReturn(0);
}
