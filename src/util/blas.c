/* dgemm_ with one column computed as dgemv_: the BLAS symbol itself, interposed, since MUMPS
   (and PETSc, ScaLAPACK, this code) call it by name.

   OpenBLAS 0.3.21 (Debian 12) packs both operands of every dgemm into its block buffers, a product
   with one column too; OpenBLAS forwards such products to gemv itself only from 0.3.27
   (GEMM_GEMV_FORWARD). MUMPS' solve with one right-hand side calls dgemm with n = 1 on every
   front (dmumps_solve_node_fwd / _bwd), and the packing (dgemm_oncopy, dgemm_otcopy) is then a
   large part of the solve (measured in docs/benchmarks.md, "One-column products"). Every other product goes to the next
   dgemm_ in the link order (the BLAS library), found by dlsym(RTLD_NEXT). MUMPS binds to this dgemm_ where
   libfecontact.so comes before the BLAS library in its lookup: the executable, and a Python process that loads the
   library globally before petsc4py loads MUMPS (python/fecontact/_lib.py).

   Option -blas_gemv_forward (read at package initialization, src/fecontact.c; its help string below and
   docs/options.md). */
#define _GNU_SOURCE
#include <dlfcn.h>
#include <stddef.h>
#include "../fcimpl.h"

typedef void (*GemmFn)(const char *, const char *, const int *, const int *, const int *, const double *,
                       const double *, const int *, const double *, const int *, const double *, double *, const int *,
                       size_t, size_t);
extern void dgemv_(const char *, const int *, const int *, const double *, const double *, const int *, const double *,
                   const int *, const double *, double *, const int *, size_t);

static PetscBool          forward = PETSC_TRUE;
static GemmFn             next_dgemm;
static unsigned long long nforwarded; /* products computed as dgemv, for -info at the end (a count
                                          only: not atomic, should a threaded caller race on it) */

/* C = alpha op(A) op(B) + beta C, op(A) m x k, op(B) k x n (Fortran BLAS, with gfortran's hidden
   lengths of the two character arguments) */
void dgemm_(const char *ta, const char *tb, const int *m, const int *n, const int *k, const double *alpha,
            const double *A, const int *lda, const double *B, const int *ldb, const double *beta, double *C,
            const int *ldc, size_t lta, size_t ltb)
{
  /* k > 0: dgemv returns at once for an empty A, where dgemm still scales C by beta */
  if (forward && *n == 1 && *m > 0 && *k > 0) {
    const int one = 1, incb = (*tb == 'N' || *tb == 'n') ? 1 : *ldb; /* op(B) = B(1, :)^T: stride ldb */
    if (*ta == 'N' || *ta == 'n')
      dgemv_("N", m, k, alpha, A, lda, B, &incb, beta, C, &one, 1);
    else
      dgemv_("T", k, m, alpha, A, lda, B, &incb, beta, C, &one, 1); /* A stored k x m */
    nforwarded++;
    return;
  }
  if (!next_dgemm) next_dgemm = (GemmFn)dlsym(RTLD_NEXT, "dgemm_");
  if (!next_dgemm) { /* no BLAS after this one: the link is broken, nothing to compute with */
    fprintf(stderr, "fecontact: error: no BLAS library dgemm_ after src/util/blas.c's (dlsym: %s)\n", dlerror());
    abort();
  }
  next_dgemm(ta, tb, m, n, k, alpha, A, lda, B, ldb, beta, C, ldc, lta, ltb);
}

PetscErrorCode FCBLASSetFromOptions(void)
{
  PetscFunctionBegin;
  PetscOptionsBegin(PETSC_COMM_WORLD, NULL, "BLAS", NULL);
  PetscCall(FCOptionsBool(PetscOptionsObject, "-blas_gemv_forward", "Compute dgemm with one column as dgemv", &forward,
                          NULL));
  PetscOptionsEnd();
  PetscFunctionReturn(0);
}

PetscErrorCode FCBLASView(void)
{
  PetscFunctionBegin;
  PetscCall(PetscInfo(NULL, "dgemm with one column computed as dgemv: %llu products (-blas_gemv_forward %s)\n",
                      nforwarded, forward ? "true" : "false"));
  PetscFunctionReturn(0);
}
