/* FCContactProblem: the local frictional contact problem FC(W, q, mu) of eq. 18. W is kept dense
   as given (the compliance of a scene: row-major, symmetric, borrowed, no copy) or as a
   block-sparse matrix over contacts (blocks d_i x d_j, row-major) built from a scalar CSR matrix
   (FCLIB files, fclib.c). The solvers (pgs.c, newton.c) read W through the few functions below. */
#include "../fcimpl.h"
#include "contactimpl.h"
#include <petscblaslapack.h>

static PetscErrorCode ProblemAllocate(PetscInt nc, const PetscInt dim[], const PetscReal mu[], const PetscReal q[],
                                      FCContactProblem *prob)
{
  FCContactProblem p = NULL;

  PetscFunctionBegin;
  PetscCall(PetscNew(&p));
  p->nc = nc;
  PetscCall(PetscMalloc3(nc, &p->dim, nc + 1, &p->off, nc, &p->mu));
  p->off[0] = 0;
  for (PetscInt i = 0; i < nc; i++) {
    PetscCheck(dim[i] >= 1 && dim[i] <= 3, PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE,
               "Contact %" PetscInt_FMT " has %" PetscInt_FMT " rows: 1, 2 or 3 allowed", i, dim[i]);
    PetscCheck(mu[i] >= 0.0 && PetscIsNormalReal(mu[i] + 1.0), PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE,
               "Contact %" PetscInt_FMT ": friction coefficient %g must be >= 0", i, (double)mu[i]);
    p->dim[i]     = dim[i];
    p->mu[i]      = mu[i];
    p->off[i + 1] = p->off[i] + dim[i];
  }
  p->n       = p->off[nc];
  p->rowcomm = MPI_COMM_NULL; /* whole W */
  p->c1      = nc;
  p->whi     = p->n;
  PetscCall(PetscMalloc1(p->n, &p->q));
  PetscCall(PetscArraycpy(p->q, q, p->n));
  for (PetscInt k = 0; k < p->n; k++) p->qnorm += q[k] * q[k];
  p->qnorm = PetscSqrtReal(p->qnorm);
  *prob    = p;
  PetscFunctionReturn(0);
}

/* p->symmetric: W = W^T to round-off, every block W_ij against W_ji^T */
static PetscErrorCode CheckSymmetric(FCContactProblem p)
{
  PetscInt  nc = p->nc, nb = p->rowptr[nc];
  PetscReal wmax = 0.0, asym = 0.0;

  PetscFunctionBegin;
  for (PetscInt e = 0; e < p->boff[nb]; e++) wmax = PetscMax(wmax, PetscAbsReal(p->val[e]));
  for (PetscInt i = 0; i < nc; i++)
    for (PetscInt b = p->rowptr[i]; b < p->rowptr[i + 1]; b++) {
      PetscInt j = p->col[b], di = p->dim[i], dj = p->dim[j], bt;
      PetscCall(PetscFindInt(i, p->rowptr[j + 1] - p->rowptr[j], &p->col[p->rowptr[j]], &bt));
      if (bt >= 0) bt += p->rowptr[j];
      if (bt < 0) {
        asym = PETSC_MAX_REAL;
        continue;
      }
      for (PetscInt a = 0; a < di; a++)
        for (PetscInt c = 0; c < dj; c++)
          asym = PetscMax(asym, PetscAbsReal(p->val[p->boff[b] + a * dj + c] - p->val[p->boff[bt] + c * di + a]));
    }
  p->symmetric = asym <= 1e-12 * wmax ? PETSC_TRUE : PETSC_FALSE;
  PetscFunctionReturn(0);
}

static PetscErrorCode CreateBlocks(PetscInt, const PetscInt[], const PetscReal[], const PetscInt[], const PetscInt[],
                                   const PetscReal[], const PetscReal[], PetscBool, FCContactProblem *);

/* A non-symmetric W: W^T by blocks too, from W's CSR (rowptr, col, val); its rows are W's columns, which
   the sweeps add into u */
static PetscErrorCode CreateTranspose(FCContactProblem p, const PetscInt rowptr[], const PetscInt col[],
                                      const PetscReal val[])
{
  PetscInt   n = p->n, nnz = rowptr[n], *trow, *tcol, *cnt;
  PetscReal *tval;

  PetscFunctionBegin;
  {
    PetscCall(PetscCalloc3(n + 1, &trow, nnz + 1, &tcol, n + 1, &cnt));
    PetscCall(PetscMalloc1(nnz + 1, &tval));
    for (PetscInt e = 0; e < nnz; e++) trow[col[e] + 1]++;
    for (PetscInt k = 0; k < n; k++) trow[k + 1] += trow[k];
    for (PetscInt k = 0; k < n; k++)
      for (PetscInt e = rowptr[k]; e < rowptr[k + 1]; e++) {
        PetscInt at = trow[col[e]] + cnt[col[e]]++;
        tcol[at]    = k;
        tval[at]    = val[e];
      }
    PetscCall(CreateBlocks(p->nc, p->dim, p->mu, trow, tcol, tval, p->q, PETSC_FALSE, &p->transpose));
    PetscCall(PetscFree3(trow, tcol, cnt));
    PetscCall(PetscFree(tval));
  }
  PetscFunctionReturn(0);
}

static PetscErrorCode CreateBlocks(PetscInt nc, const PetscInt dim[], const PetscReal mu[], const PetscInt rowptr[],
                                   const PetscInt col[], const PetscReal val[], const PetscReal q[],
                                   PetscBool transpose, FCContactProblem *prob)
{
  FCContactProblem p = NULL;
  PetscInt        *contactOf, *mark, nb = 0;

  PetscFunctionBegin;
  PetscCall(ProblemAllocate(nc, dim, mu, q, &p));
  PetscCall(PetscMalloc2(p->n, &contactOf, nc, &mark));
  for (PetscInt i = 0; i < nc; i++)
    for (PetscInt k = p->off[i]; k < p->off[i + 1]; k++) contactOf[k] = i;
  for (PetscInt i = 0; i < nc; i++) mark[i] = -1;
  /* block pattern: row i of contacts couples with contact j if any scalar entry does */
  PetscCall(PetscMalloc1(nc + 1, &p->rowptr));
  p->rowptr[0] = 0;
  for (PetscInt i = 0; i < nc; i++) {
    mark[i] = i; /* the diagonal block always exists */
    nb++;
    for (PetscInt k = p->off[i]; k < p->off[i + 1]; k++)
      for (PetscInt e = rowptr[k]; e < rowptr[k + 1]; e++) {
        PetscInt j = contactOf[col[e]];
        if (mark[j] != i) {
          mark[j] = i;
          nb++;
        }
      }
    p->rowptr[i + 1] = nb;
  }
  PetscCall(PetscMalloc3(nb, &p->col, nb + 1, &p->boff, nc, &p->diag));
  for (PetscInt i = 0; i < nc; i++) mark[i] = -1;
  {
    PetscInt b = 0;
    for (PetscInt i = 0; i < nc; i++) {
      mark[i]     = i;
      p->col[b++] = i;
      for (PetscInt k = p->off[i]; k < p->off[i + 1]; k++)
        for (PetscInt e = rowptr[k]; e < rowptr[k + 1]; e++) {
          PetscInt j = contactOf[col[e]];
          if (mark[j] != i) {
            mark[j]     = i;
            p->col[b++] = j;
          }
        }
      PetscCall(PetscSortInt(p->rowptr[i + 1] - p->rowptr[i], &p->col[p->rowptr[i]]));
    }
  }
  p->boff[0] = 0;
  for (PetscInt i = 0; i < nc; i++)
    for (PetscInt b = p->rowptr[i]; b < p->rowptr[i + 1]; b++) {
      p->boff[b + 1] = p->boff[b] + p->dim[i] * p->dim[p->col[b]];
      if (p->col[b] == i) p->diag[i] = b;
    }
  PetscCall(PetscCalloc1(p->boff[nb], &p->val));
  for (PetscInt i = 0; i < nc; i++)
    for (PetscInt k = p->off[i]; k < p->off[i + 1]; k++)
      for (PetscInt e = rowptr[k]; e < rowptr[k + 1]; e++) {
        PetscInt j = contactOf[col[e]], lo = p->rowptr[i], hi = p->rowptr[i + 1], b;
        while (hi - lo > 1) { /* binary search of block column j */
          PetscInt mid = (lo + hi) / 2;
          if (p->col[mid] <= j)
            lo = mid;
          else
            hi = mid;
        }
        b = lo;
        p->val[p->boff[b] + (k - p->off[i]) * p->dim[j] + (col[e] - p->off[j])] += val[e];
      }
  PetscCall(PetscFree2(contactOf, mark));
  PetscCall(CheckSymmetric(p));
  if (!p->symmetric && transpose) PetscCall(CreateTranspose(p, rowptr, col, val));
  *prob = p;
  PetscFunctionReturn(0);
}

PetscErrorCode FCContactProblemCreateCSR(PetscInt nc, const PetscInt dim[], const PetscReal mu[],
                                         const PetscInt rowptr[], const PetscInt col[], const PetscReal val[],
                                         const PetscReal q[], FCContactProblem *prob)
{
  PetscFunctionBegin;
  PetscCall(CreateBlocks(nc, dim, mu, rowptr, col, val, q, PETSC_TRUE, prob));
  PetscFunctionReturn(0);
}

/* W (n x n, row-major, symmetric) is used in place: it must outlive the problem */
PetscErrorCode FCContactProblemCreateDense(PetscInt nc, const PetscInt dim[], const PetscReal mu[], const PetscReal W[],
                                           const PetscReal q[], FCContactProblem *prob)
{
  PetscFunctionBegin;
  PetscCall(ProblemAllocate(nc, dim, mu, q, prob));
  (*prob)->Wd        = W;
  (*prob)->symmetric = PETSC_TRUE;
  PetscFunctionReturn(0);
}

void FCContactProblemDiagonalBlock(FCContactProblem p, PetscInt i, PetscReal Wii[9])
{
  PetscInt d = p->dim[i], o = p->off[i];
  if (p->Wd) { /* by rows: one of this rank's contacts */
    for (PetscInt a = 0; a < d; a++)
      for (PetscInt b = 0; b < d; b++) Wii[a * d + b] = FCContactProblemRow(p, o + a)[o + b];
  } else
    for (PetscInt a = 0; a < d * d; a++) Wii[a] = p->val[p->boff[p->diag[i]] + a];
}

/* u += x a + y b + z c: the inner loop of a sweep, the only place where W is read, once per sweep.
   Unrolled by 4 for the vectorizer; on x86-64 with GCC, also compiled for x86-64-v3 (AVX2, FMA) and
   chosen at run time (function multiversioning), since the portable build targets SSE2 only. The
   clone is named by the ISA level, not "arch=haswell": GCC dispatches an arch= clone on the CPU
   model, so a CPU it does not name (an AMD EPYC with AVX2 and FMA) runs the SSE2 default, while
   x86-64-v3 is dispatched on the features (GCC >= 12) */
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__) && __GNUC__ >= 12
__attribute__((target_clones("arch=x86-64-v3", "default")))
#endif
void
FCContactAddRows3(PetscInt n, const PetscReal *restrict a, const PetscReal *restrict b, const PetscReal *restrict c, PetscReal x,
         PetscReal y, PetscReal z, PetscReal *restrict u)
{
  PetscInt k = 0;
  for (; k + 4 <= n; k += 4) {
    u[k] += x * a[k] + y * b[k] + z * c[k];
    u[k + 1] += x * a[k + 1] + y * b[k + 1] + z * c[k + 1];
    u[k + 2] += x * a[k + 2] + y * b[k + 2] + z * c[k + 2];
    u[k + 3] += x * a[k + 3] + y * b[k + 3] + z * c[k + 3];
  }
  for (; k < n; k++) u[k] += x * a[k] + y * b[k] + z * c[k];
}

/* Column i of W (the d_i rows of contact i when W is symmetric, else of W^T) scaled into u, in one pass */
void FCContactProblemAddColumns(FCContactProblem p, PetscInt i, const PetscReal delta[], PetscReal u[])
{
  PetscInt d = p->dim[i], o = p->off[i], n = p->n;
  if (p->Wd) {
    const PetscReal *a = FCContactProblemRow(p, o); /* by rows: one of this rank's contacts */
    if (d == 3)
      FCContactAddRows3(n, a, a + n, a + 2 * n, delta[0], delta[1], delta[2], u);
    else
      for (PetscInt e = 0; e < d; e++) FCContactAddRows3(n, a + e * n, a + e * n, a + e * n, delta[e], 0.0, 0.0, u);
    return;
  }
  if (p->transpose) p = p->transpose;                          /* W^T's row i is W's column i */
  for (PetscInt b = p->rowptr[i]; b < p->rowptr[i + 1]; b++) { /* u_j += W_ji delta = W_ij^T delta */
    PetscInt         j = p->col[b], dj = p->dim[j];
    const PetscReal *B = &p->val[p->boff[b]];
    for (PetscInt c = 0; c < dj; c++) {
      PetscReal acc = 0.0;
      for (PetscInt a = 0; a < d; a++) acc += B[a * dj + c] * delta[a];
      u[p->off[j] + c] += acc;
    }
  }
}

PetscErrorCode FCContactProblemGetDenseW(FCContactProblem p, PetscReal **W)
{
  PetscFunctionBegin;
  PetscCheck(p->rowcomm == MPI_COMM_NULL, PETSC_COMM_SELF, PETSC_ERR_SUP,
             "A contact problem held by block rows has no whole W here (FCContactProblemGatherWhole)");
  PetscCall(PetscCalloc1(p->n * p->n + 1, W));
  if (p->Wd)
    PetscCall(PetscArraycpy(*W, p->Wd, p->n * p->n));
  else
    for (PetscInt i = 0; i < p->nc; i++)
      for (PetscInt b = p->rowptr[i]; b < p->rowptr[i + 1]; b++) {
        PetscInt j = p->col[b], di = p->dim[i], dj = p->dim[j];
        for (PetscInt a = 0; a < di; a++)
          for (PetscInt c = 0; c < dj; c++)
            (*W)[(p->off[i] + a) * p->n + p->off[j] + c] = p->val[p->boff[b] + a * dj + c];
      }
  PetscFunctionReturn(0);
}

PetscErrorCode FCContactProblemGetSizes(FCContactProblem p, PetscInt *nc, PetscInt *n)
{
  PetscFunctionBegin;
  if (nc) *nc = p->nc;
  if (n) *n = p->n;
  PetscFunctionReturn(0);
}

static PetscErrorCode MultAdd(FCContactProblem, const PetscReal[], PetscReal[]);

/* u = W r + q (dense: one BLAS gemv) */
PetscErrorCode FCContactProblemVelocity(FCContactProblem p, const PetscReal r[], PetscReal u[])
{
  PetscFunctionBegin;
  if (p->rowcomm != MPI_COMM_NULL) {
    PetscCall(FCContactProblemVelocityRows(p, r, u));
    PetscFunctionReturn(0);
  }
  PetscCall(PetscArraycpy(u, p->q, p->n));
  PetscCall(MultAdd(p, r, u));
  PetscFunctionReturn(0);
}

PetscErrorCode FCContactProblemMult(FCContactProblem p, const PetscReal x[], PetscReal y[])
{
  PetscFunctionBegin;
  PetscCheck(p->rowcomm == MPI_COMM_NULL, PETSC_COMM_SELF, PETSC_ERR_SUP,
             "A contact problem held by block rows has no whole W here (FCContactProblemGatherWhole)");
  PetscCall(PetscArrayzero(y, p->n));
  PetscCall(MultAdd(p, x, y));
  PetscFunctionReturn(0);
}

/* u += W r, W whole on this rank */
static PetscErrorCode MultAdd(FCContactProblem p, const PetscReal r[], PetscReal u[])
{
  PetscFunctionBegin;
  if (p->Wd) { /* row-major W is W^T column-major: u += (W^T)^T r */
    PetscBLASInt n, one = 1;
    PetscScalar  alpha = 1.0, beta = 1.0;
    PetscCall(PetscBLASIntCast(p->n, &n));
    if (n) PetscCallBLAS("BLASgemv", BLASgemv_("T", &n, &n, &alpha, p->Wd, &n, r, &one, &beta, u, &one));
    PetscFunctionReturn(0);
  }
  for (PetscInt i = 0; i < p->nc; i++) {
    PetscInt di = p->dim[i];
    for (PetscInt b = p->rowptr[i]; b < p->rowptr[i + 1]; b++) {
      PetscInt         j = p->col[b], dj = p->dim[j];
      const PetscReal *B = &p->val[p->boff[b]];
      for (PetscInt a = 0; a < di; a++)
        for (PetscInt c = 0; c < dj; c++) u[p->off[i] + a] += B[a * dj + c] * r[p->off[j] + c];
    }
  }
  PetscFunctionReturn(0);
}

PetscErrorCode FCContactProblemSetRHS(FCContactProblem p, const PetscReal q[])
{
  PetscFunctionBegin;
  PetscCall(PetscArraycpy(p->q, q, p->n));
  p->qnorm = 0.0;
  for (PetscInt k = 0; k < p->n; k++) p->qnorm += q[k] * q[k];
  p->qnorm = PetscSqrtReal(p->qnorm);
  PetscFunctionReturn(0);
}

PetscErrorCode FCContactProblemGetFriction(FCContactProblem p, PetscReal mu[])
{
  PetscFunctionBegin;
  PetscCall(PetscArraycpy(mu, p->mu, p->nc));
  PetscFunctionReturn(0);
}

PetscReal FCContactProblemResidualFromVelocity(FCContactProblem p, const PetscReal r[], const PetscReal u[])
{
  PetscReal sum = 0.0;
  for (PetscInt i = 0; i < p->nc; i++)
    if (!p->dormant || !p->dormant[i])
      sum += FCContactNaturalMapError2(p->dim[i], p->mu[i], &r[p->off[i]], &u[p->off[i]]);
  return PetscSqrtReal(sum) / PetscMax(p->qnorm, PETSC_MACHINE_EPSILON);
}

PetscErrorCode FCContactProblemResidual(FCContactProblem p, const PetscReal r[], PetscReal *abs, PetscReal *rel)
{
  PetscReal *u, rr;

  PetscFunctionBegin;
  PetscCall(PetscMalloc1(p->n, &u));
  PetscCall(FCContactProblemVelocity(p, r, u));
  rr = FCContactProblemResidualFromVelocity(p, r, u);
  PetscCall(PetscFree(u));
  if (abs) *abs = rr * PetscMax(p->qnorm, PETSC_MACHINE_EPSILON);
  if (rel) *rel = rr;
  PetscFunctionReturn(0);
}

/* Dormant contacts (mask[i], borrowed: the caller keeps it alive and reads back the contacts the
   solver woke): nearly redundant constraints that the solver adds only where the solution without
   them leaves their normal gap below -depth (solver.c, SolveLazy). u is a displacement here (q holds
   the gaps), so depth is a length. */
PetscErrorCode FCContactProblemSetDormant(FCContactProblem p, PetscBool mask[], PetscReal depth)
{
  PetscFunctionBegin;
  PetscCheck(depth >= 0.0, PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE,
             "The wake depth of dormant contacts must be >= 0, got %g", (double)depth);
  p->dormant = mask;
  p->wake    = depth;
  PetscFunctionReturn(0);
}

PetscErrorCode FCContactProblemDestroy(FCContactProblem *prob)
{
  FCContactProblem p = *prob;

  PetscFunctionBegin;
  if (!p) PetscFunctionReturn(0);
  PetscCall(PetscFree3(p->dim, p->off, p->mu));
  PetscCall(PetscFree(p->q));
  PetscCall(PetscFree(p->rowptr));
  PetscCall(PetscFree3(p->col, p->boff, p->diag));
  PetscCall(PetscFree(p->val));
  PetscCall(PetscFree2(p->rcounts, p->rdispls));
  PetscCall(FCContactProblemDestroy(&p->transpose));
  PetscCall(PetscFree(*prob));
  PetscFunctionReturn(0);
}

/* ---- A dense problem held by block rows over the ranks (FCContactProblemCreateDenseRows):
   each rank keeps only the rows of its block of contacts, the block the split sweeps give it
   (pgs_split.c), so W (M x M, the fast scheme's W_k) takes M^2 / p values per rank and is formed
   p ways (src/scheme/fast.c). What needs more than a rank's rows is collective here: u = W r + q
   (each rank its rows, then an MPI_Allgatherv), and W whole on rank 0 when rank 0 must go on alone
   (-pgs_ranks auto, split sweeps that would not converge) or write the problem (-pgs_dump_problem). */
static const PetscReal NoRows = 0.0;

PetscErrorCode FCContactProblemCreateDenseRows(MPI_Comm comm, PetscInt nc, const PetscInt dim[], const PetscReal mu[],
                                               PetscInt c0, PetscInt c1, const PetscReal Wrows[], const PetscReal q[],
                                               FCContactProblem *prob)
{
  FCContactProblem p;
  PetscMPIInt      size, rank;
  PetscInt         range[2], *ranges;

  PetscFunctionBegin;
  PetscCheck(0 <= c0 && c0 <= c1 && c1 <= nc, PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE,
             "Block of contacts [%" PetscInt_FMT ", %" PetscInt_FMT ") outside [0, %" PetscInt_FMT ")", c0, c1, nc);
  /* a rank with no contacts in its block may pass no rows (NULL): Wd still marks the problem dense */
  PetscCall(FCContactProblemCreateDense(nc, dim, mu, c1 > c0 ? Wrows : &NoRows, q, &p));
  PetscCallMPI(MPI_Comm_size(comm, &size));
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  p->rowcomm = comm;
  p->c0      = c0;
  p->c1      = c1;
  p->wlo     = p->off[c0];
  p->whi     = p->off[c1];
  range[0]   = p->wlo;
  range[1]   = p->whi;
  PetscCall(PetscMalloc1(2 * size, &ranges));
  PetscCallMPI(MPI_Allgather(range, 2, MPIU_INT, ranges, 2, MPIU_INT, comm));
  PetscCall(PetscMalloc2(size, &p->rcounts, size, &p->rdispls));
  for (PetscMPIInt b = 0; b < size; b++) { /* the blocks tile the rows in rank order */
    PetscCheck(ranges[2 * b] == (b ? ranges[2 * b - 1] : 0) && (b < size - 1 || ranges[2 * b + 1] == p->n),
               PETSC_COMM_SELF, PETSC_ERR_ARG_WRONG,
               "The row blocks of a contact problem must tile its %" PetscInt_FMT
               " rows in rank order: rank %d holds [%" PetscInt_FMT ", %" PetscInt_FMT ")",
               p->n, (int)b, ranges[2 * b], ranges[2 * b + 1]);
    PetscCall(PetscMPIIntCast(ranges[2 * b + 1] - ranges[2 * b], &p->rcounts[b]));
    PetscCall(PetscMPIIntCast(ranges[2 * b], &p->rdispls[b]));
  }
  PetscCall(PetscFree(ranges));
  *prob = p;
  PetscFunctionReturn(0);
}

PetscErrorCode FCContactProblemVelocityRows(FCContactProblem p, const PetscReal r[], PetscReal u[])
{
  PetscBLASInt n, nb, one = 1;
  PetscReal    alpha = 1.0, beta = 1.0;

  PetscFunctionBegin;
  PetscCall(PetscBLASIntCast(p->n, &n));
  PetscCall(PetscBLASIntCast(p->whi - p->wlo, &nb));
  PetscCall(PetscArraycpy(u + p->wlo, p->q + p->wlo, nb));
  if (nb && n) /* the rows, row-major: W_rows^T column-major */
    PetscCallBLAS("BLASgemv", BLASgemv_("T", &n, &nb, &alpha, p->Wd, &n, r, &one, &beta, u + p->wlo, &one));
  PetscCallMPI(MPI_Allgatherv(MPI_IN_PLACE, 0, MPI_DATATYPE_NULL, u, p->rcounts, p->rdispls, MPIU_REAL, p->rowcomm));
  PetscFunctionReturn(0);
}

PetscErrorCode FCContactProblemGatherWhole(FCContactProblem p, PetscReal **W, FCContactProblem *whole)
{
  PetscMPIInt size, rank, mine, *counts = NULL, *displs = NULL;
  PetscReal  *Wall = NULL;

  PetscFunctionBegin;
  *W     = NULL;
  *whole = NULL;
  PetscCallMPI(MPI_Comm_size(p->rowcomm, &size));
  PetscCallMPI(MPI_Comm_rank(p->rowcomm, &rank));
  PetscCall(PetscMPIIntCast((p->whi - p->wlo) * p->n, &mine));
  if (!rank) {
    PetscCall(PetscMalloc1(p->n * p->n + 1, &Wall));
    PetscCall(PetscMalloc2(size, &counts, size, &displs));
    for (PetscMPIInt b = 0; b < size; b++) {
      PetscCall(PetscMPIIntCast((PetscInt)p->rcounts[b] * p->n, &counts[b]));
      PetscCall(PetscMPIIntCast((PetscInt)p->rdispls[b] * p->n, &displs[b]));
    }
  }
  PetscCallMPI(MPI_Gatherv(p->Wd, mine, MPIU_REAL, Wall, counts, displs, MPIU_REAL, 0, p->rowcomm));
  if (!rank) {
    PetscCall(FCContactProblemCreateDense(p->nc, p->dim, p->mu, Wall, p->q, whole));
    (*whole)->dormant = p->dormant;
    (*whole)->wake    = p->wake;
    *W                = Wall;
    PetscCall(PetscFree2(counts, displs));
  }
  PetscFunctionReturn(0);
}
