/* bench_spdinverse: the inverse of a dense SPD matrix held by rank 0 (the condensed builder's
   Sigma^-1, src/compliance/spdinverse.c), LAPACK on rank 0 against ScaLAPACK over every rank and
   against the host's Cholesky factor with the ranks' blocks of columns of its inverse ("columns"),
   for matrices of n rows; run it on the ranks to compare (mpirun -n 2 build/bench_spdinverse).
     bench_spdinverse [-sizes 500,1000,1500,2000,3000] [-repeat 3]
   Prints per n the best of the repeats of each, their ratios to the host, the floor (the host time
   divided by the number of ranks) and ||Sigma C - I||_max of each result. */
/* times the condensed builder's inverse of Sigma, private to the compliance package */
#include "../src/compliance/complianceimpl.h"
#include <petscblaslapack.h>

/* Sigma = B B^T / n + I for B with entries in [-1, 1] (a fixed sequence): SPD, well conditioned */
static PetscErrorCode Fill(PetscInt n, PetscReal s[])
{
  PetscReal   *b, alpha = 1.0 / n, beta = 0.0;
  PetscBLASInt bn;
  unsigned     x = 12345u;

  PetscFunctionBegin;
  PetscCall(PetscBLASIntCast(n, &bn));
  PetscCall(PetscMalloc1(n * n, &b));
  for (PetscInt k = 0; k < n * n; k++) {
    x    = 1664525u * x + 1013904223u;
    b[k] = 2.0 * (x >> 8) / 16777216.0 - 1.0;
  }
  PetscCallBLAS("BLASgemm", BLASgemm_("N", "T", &bn, &bn, &bn, &alpha, b, &bn, b, &bn, &beta, s, &bn));
  for (PetscInt i = 0; i < n; i++) s[i + i * n] += 1.0;
  PetscCall(PetscFree(b));
  PetscFunctionReturn(0);
}

/* *e = max |Sigma C - I| */
static PetscErrorCode Error(PetscInt n, const PetscReal s[], const PetscReal c[], PetscReal *e)
{
  PetscReal   *p, one = 1.0, zero = 0.0;
  PetscBLASInt bn;

  PetscFunctionBegin;
  PetscCall(PetscBLASIntCast(n, &bn));
  PetscCall(PetscMalloc1(n * n, &p));
  PetscCallBLAS("BLASgemm",
                BLASgemm_("N", "N", &bn, &bn, &bn, &one, (PetscReal *)s, &bn, (PetscReal *)c, &bn, &zero, p, &bn));
  *e = 0.0;
  for (PetscInt j = 0; j < n; j++)
    for (PetscInt i = 0; i < n; i++) *e = PetscMax(*e, PetscAbsReal(p[i + j * n] - (i == j ? 1.0 : 0.0)));
  PetscCall(PetscFree(p));
  PetscFunctionReturn(0);
}

int main(int argc, char **argv)
{
  PetscInt     sizes[8] = {500, 1000, 1500, 2000, 3000}, nsz = 8, repeat = 3;
  PetscBool    set;
  PetscMPIInt  rank, size;
  FCSPDInverse inv[3];

  PetscCall(PetscInitialize(&argc, &argv, NULL, NULL));
  PetscCall(PetscOptionsGetIntArray(NULL, NULL, "-sizes", sizes, &nsz, &set));
  if (!set) nsz = 5;
  PetscCall(PetscOptionsGetInt(NULL, NULL, "-repeat", &repeat, NULL));
  PetscCallMPI(MPI_Comm_rank(PETSC_COMM_WORLD, &rank));
  PetscCallMPI(MPI_Comm_size(PETSC_COMM_WORLD, &size));
  PetscCall(FCSPDInverseCreate(PETSC_COMM_WORLD, "bench", FC_SPD_INVERSE_HOST, &inv[0]));
  PetscCall(FCSPDInverseCreate(PETSC_COMM_WORLD, "bench", FC_SPD_INVERSE_SCALAPACK, &inv[1]));
  PetscCall(FCSPDInverseCreate(PETSC_COMM_WORLD, "bench", FC_SPD_INVERSE_COLUMNS, &inv[2]));
  PetscCall(PetscPrintf(PETSC_COMM_WORLD,
                        "%d ranks, best of %" PetscInt_FMT
                        "\n\n| n | host LAPACK (s) | ScaLAPACK (s) | columns (s) | ScaLAPACK / host | columns / host | "
                        "floor host / ranks (s) | error host | error ScaLAPACK | error columns |\n"
                        "|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n",
                        (int)size, repeat));
  for (PetscInt s = 0; s < nsz; s++) {
    PetscInt   n   = sizes[s];
    PetscReal *sig = NULL, *a = NULL, best[3] = {PETSC_MAX_REAL, PETSC_MAX_REAL, PETSC_MAX_REAL}, err[3] = {0, 0, 0};
    if (!rank) {
      PetscCall(PetscMalloc2(n * n, &sig, n * n, &a));
      PetscCall(Fill(n, sig));
    }
    for (int k = 0; k < 3; k++)
      for (PetscInt r = 0; r < repeat; r++) {
        PetscLogDouble t0, t1;
        if (!rank) PetscCall(PetscArraycpy(a, sig, n * n));
        PetscCallMPI(MPI_Barrier(PETSC_COMM_WORLD));
        PetscCall(PetscTime(&t0));
        PetscCall(FCSPDInverseApply(inv[k], n, a));
        PetscCall(PetscTime(&t1));
        best[k] = PetscMin(best[k], t1 - t0);
        if (!rank && r == 0) PetscCall(Error(n, sig, a, &err[k]));
      }
    PetscCallMPI(MPI_Bcast(best, 3, MPIU_REAL, 0, PETSC_COMM_WORLD));
    PetscCall(PetscPrintf(
        PETSC_COMM_WORLD, "| %" PetscInt_FMT " | %.4f | %.4f | %.4f | %.2f | %.2f | %.4f | %.1e | %.1e | %.1e |\n", n,
        (double)best[0], (double)best[1], (double)best[2], (double)(best[1] / best[0]), (double)(best[2] / best[0]),
        (double)(best[0] / size), (double)err[0], (double)err[1], (double)err[2]));
    if (!rank) PetscCall(PetscFree2(sig, a));
  }
  PetscCall(FCSPDInverseDestroy(&inv[0]));
  PetscCall(FCSPDInverseDestroy(&inv[1]));
  PetscCall(FCSPDInverseDestroy(&inv[2]));
  PetscCall(PetscFinalize());
  return 0;
}
