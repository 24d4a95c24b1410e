/* What FCSchurFactor (schurfactor.c) hands MUMPS and its ordering: A's upper triangle by the
   owned rows (distributed triples) and the vertex-block graph of A gathered on the host */
#include "schurfactorimpl.h"

/* The owned rows' upper triangle (c >= r), in MatGetRow order: the pattern at create, the values
   at each factorization (A's pattern never changes) */
PetscErrorCode FCSchurFactorTriples(FCSchurFactor f, Mat A, PetscBool values)
{
  PetscInt k = 0;

  PetscFunctionBegin;
  for (PetscInt r = f->lo; r < f->hi; r++) {
    PetscInt           nc;
    const PetscInt    *cols;
    const PetscScalar *vals;
    PetscCall(MatGetRow(A, r, &nc, &cols, &vals));
    for (PetscInt j = 0; j < nc; j++) {
      if (cols[j] < r) continue;
      if (values)
        f->val[k] = PetscRealPart(vals[j]);
      else if (f->irn) {
        f->irn[k] = (MUMPS_INT)(r + 1);
        f->jcn[k] = (MUMPS_INT)(cols[j] + 1);
      }
      k++;
    }
    PetscCall(MatRestoreRow(A, r, &nc, &cols, &vals));
  }
  if (!values && !f->irn) {
    f->nnz = k;
    PetscCall(PetscMalloc3(k + 1, &f->irn, k + 1, &f->jcn, k + 1, &f->val));
    PetscCall(FCSchurFactorTriples(f, A, PETSC_FALSE));
  }
  PetscFunctionReturn(0);
}

/* The vertex-block graph of A, gathered on the host (the ordering is computed there) */
PetscErrorCode FCSchurFactorGatherGraph(FCSchurFactor f, Mat A)
{
  PetscInt     nbl = (f->hi - f->lo) / 3, *cnt, *nbr, nnbr = 0, cap = 1, *allcnt = NULL;
  PetscMPIInt *rc = NULL, *rd = NULL, *ec = NULL, *ed = NULL, mc, me;

  PetscFunctionBegin;
  for (PetscInt b = 0; b < nbl; b++) { /* room: the entries of the first row of each block */
    PetscInt nc;
    PetscCall(MatGetRow(A, f->lo + 3 * b, &nc, NULL, NULL));
    cap += nc;
    PetscCall(MatRestoreRow(A, f->lo + 3 * b, &nc, NULL, NULL));
  }
  PetscCall(PetscMalloc2(nbl + 1, &cnt, cap, &nbr));
  for (PetscInt b = 0; b < nbl; b++) {
    PetscInt        nc, r = f->lo + 3 * b, start = nnbr;
    const PetscInt *cols;
    PetscCall(MatGetRow(A, r, &nc, &cols, NULL));
    for (PetscInt j = 0; j < nc; j++) { /* cols sorted: a block's columns are consecutive */
      PetscInt cb = cols[j] / 3;
      if (cb == r / 3 || (nnbr > start && nbr[nnbr - 1] == cb)) continue;
      nbr[nnbr++] = cb;
    }
    PetscCall(MatRestoreRow(A, r, &nc, &cols, NULL));
    cnt[b] = nnbr - start;
  }
  mc = (PetscMPIInt)nbl;
  me = (PetscMPIInt)nnbr;
  if (!f->rank) PetscCall(PetscMalloc4(f->size, &rc, f->size + 1, &rd, f->size, &ec, f->size + 1, &ed));
  PetscCallMPI(MPI_Gather(&mc, 1, MPI_INT, rc, 1, MPI_INT, 0, f->comm));
  PetscCallMPI(MPI_Gather(&me, 1, MPI_INT, ec, 1, MPI_INT, 0, f->comm));
  if (!f->rank) {
    rd[0] = ed[0] = 0;
    for (PetscMPIInt r = 0; r < f->size; r++) {
      rd[r + 1] = rd[r] + rc[r];
      ed[r + 1] = ed[r] + ec[r];
    }
    f->nb = rd[f->size];
    PetscCall(PetscMalloc1(f->nb + 1, &allcnt));
    PetscCall(PetscMalloc2(f->nb + 1, &f->xadj, ed[f->size] + 1, &f->adj));
  }
  PetscCallMPI(MPI_Gatherv(cnt, mc, MPIU_INT, allcnt, rc, rd, MPIU_INT, 0, f->comm));
  PetscCallMPI(MPI_Gatherv(nbr, me, MPIU_INT, f->adj, ec, ed, MPIU_INT, 0, f->comm));
  if (!f->rank) {
    f->xadj[0] = 0;
    for (PetscInt b = 0; b < f->nb; b++) f->xadj[b + 1] = f->xadj[b] + allcnt[b];
    PetscCall(PetscFree(allcnt));
    PetscCall(PetscFree4(rc, rd, ec, ed));
  }
  PetscCall(PetscFree2(cnt, nbr));
  PetscFunctionReturn(0);
}
