/* FCContactProblem: the local frictional contact problem FC(W, q, mu) of eq. 18, with W stored
   as a block-sparse matrix over contacts (blocks d_i x d_j, row-major). Dense W (from the
   compliance of a scene) and scalar CSR W (FCLIB files) are both turned into this form. */
#include "../fcimpl.h"
#include "contactimpl.h"
#include <hdf5.h>

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
  p->n = p->off[nc];
  PetscCall(PetscMalloc1(p->n, &p->q));
  PetscCall(PetscArraycpy(p->q, q, p->n));
  *prob = p;
  PetscFunctionReturn(0);
}

PetscErrorCode FCContactProblemCreateCSR(PetscInt nc, const PetscInt dim[], const PetscReal mu[],
                                         const PetscInt rowptr[], const PetscInt col[], const PetscReal val[],
                                         const PetscReal q[], FCContactProblem *prob)
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
  *prob = p;
  PetscFunctionReturn(0);
}

PetscErrorCode FCContactProblemCreateDense(PetscInt nc, const PetscInt dim[], const PetscReal mu[], const PetscReal W[],
                                           const PetscReal q[], FCContactProblem *prob)
{
  PetscInt *rowptr, *col, n = 0;

  PetscFunctionBegin;
  for (PetscInt i = 0; i < nc; i++) n += dim[i];
  PetscCall(PetscMalloc2(n + 1, &rowptr, n * n + 1, &col));
  for (PetscInt k = 0; k <= n; k++) rowptr[k] = k * n;
  for (PetscInt k = 0; k < n * n; k++) col[k] = k % n;
  PetscCall(FCContactProblemCreateCSR(nc, dim, mu, rowptr, col, W, q, prob));
  PetscCall(PetscFree2(rowptr, col));
  PetscFunctionReturn(0);
}

PetscErrorCode FCContactProblemGetSizes(FCContactProblem p, PetscInt *nc, PetscInt *n)
{
  PetscFunctionBegin;
  if (nc) *nc = p->nc;
  if (n) *n = p->n;
  PetscFunctionReturn(0);
}

/* u = W r + q */
PetscErrorCode FCContactProblemVelocity(FCContactProblem p, const PetscReal r[], PetscReal u[])
{
  PetscFunctionBegin;
  for (PetscInt i = 0; i < p->nc; i++) {
    PetscInt di = p->dim[i];
    for (PetscInt a = 0; a < di; a++) u[p->off[i] + a] = p->q[p->off[i] + a];
    for (PetscInt b = p->rowptr[i]; b < p->rowptr[i + 1]; b++) {
      PetscInt         j = p->col[b], dj = p->dim[j];
      const PetscReal *B = &p->val[p->boff[b]];
      for (PetscInt a = 0; a < di; a++)
        for (PetscInt c = 0; c < dj; c++) u[p->off[i] + a] += B[a * dj + c] * r[p->off[j] + c];
    }
  }
  PetscFunctionReturn(0);
}

PetscErrorCode FCContactProblemResidual(FCContactProblem p, const PetscReal r[], PetscReal *abs, PetscReal *rel)
{
  PetscReal *u, sum = 0.0, nq = 0.0;

  PetscFunctionBegin;
  PetscCall(PetscMalloc1(p->n, &u));
  PetscCall(FCContactProblemVelocity(p, r, u));
  for (PetscInt i = 0; i < p->nc; i++)
    sum += FCContactNaturalMapError2(p->dim[i], p->mu[i], &r[p->off[i]], &u[p->off[i]]);
  for (PetscInt k = 0; k < p->n; k++) nq += p->q[k] * p->q[k];
  PetscCall(PetscFree(u));
  if (abs) *abs = PetscSqrtReal(sum);
  if (rel) *rel = PetscSqrtReal(sum) / PetscMax(PetscSqrtReal(nq), PETSC_MACHINE_EPSILON);
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
  PetscCall(PetscFree(*prob));
  PetscFunctionReturn(0);
}

/* ---- FCLIB local problems: /fclib_local/W/{m,n,nz,p,i,x} (nz = -2 CSR, -1 CSC, >= 0
   triplet), /fclib_local/vectors/{q,mu}, /fclib_local/spacedim ---- */
static PetscErrorCode ReadInts(hid_t f, const char path[], PetscInt *n, PetscInt **v)
{
  hid_t      d = H5Dopen2(f, path, H5P_DEFAULT), s;
  hssize_t   m;
  long long *tmp;

  PetscFunctionBegin;
  PetscCheck(d >= 0, PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED, "FCLIB file has no dataset %s", path);
  s = H5Dget_space(d);
  m = H5Sget_simple_extent_npoints(s);
  PetscCall(PetscMalloc1(m + 1, &tmp));
  PetscCall(PetscMalloc1(m + 1, v));
  PetscCheck(H5Dread(d, H5T_NATIVE_LLONG, H5S_ALL, H5S_ALL, H5P_DEFAULT, tmp) >= 0, PETSC_COMM_SELF,
             PETSC_ERR_FILE_READ, "Cannot read %s", path);
  for (hssize_t k = 0; k < m; k++) (*v)[k] = (PetscInt)tmp[k];
  PetscCall(PetscFree(tmp));
  *n = (PetscInt)m;
  H5Sclose(s);
  H5Dclose(d);
  PetscFunctionReturn(0);
}

static PetscErrorCode ReadReals(hid_t f, const char path[], PetscInt *n, PetscReal **v)
{
  hid_t    d = H5Dopen2(f, path, H5P_DEFAULT), s;
  hssize_t m;

  PetscFunctionBegin;
  PetscCheck(d >= 0, PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED, "FCLIB file has no dataset %s", path);
  s = H5Dget_space(d);
  m = H5Sget_simple_extent_npoints(s);
  PetscCall(PetscMalloc1(m + 1, v));
  PetscCheck(H5Dread(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, *v) >= 0, PETSC_COMM_SELF,
             PETSC_ERR_FILE_READ, "Cannot read %s", path);
  *n = (PetscInt)m;
  H5Sclose(s);
  H5Dclose(d);
  PetscFunctionReturn(0);
}

PetscErrorCode FCContactProblemLoadFCLIB(const char path[], FCContactProblem *prob)
{
  hid_t      f;
  PetscInt   n1, *m, *nn, *nz, *pp, *ii, np, ni, nx, nq, nmu, *sd, *dim, *rowptr, *col, nc, n, nnz;
  PetscReal *x, *q, *mu, *val;

  PetscFunctionBegin;
  H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
  f = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT);
  PetscCheck(f >= 0, PETSC_COMM_SELF, PETSC_ERR_USER_INPUT, "Cannot open FCLIB file '%s'", path);
  PetscCall(ReadInts(f, "/fclib_local/W/m", &n1, &m));
  PetscCall(ReadInts(f, "/fclib_local/W/n", &n1, &nn));
  PetscCall(ReadInts(f, "/fclib_local/W/nz", &n1, &nz));
  PetscCall(ReadInts(f, "/fclib_local/W/p", &np, &pp));
  PetscCall(ReadInts(f, "/fclib_local/W/i", &ni, &ii));
  PetscCall(ReadReals(f, "/fclib_local/W/x", &nx, &x));
  PetscCall(ReadReals(f, "/fclib_local/vectors/q", &nq, &q));
  PetscCall(ReadReals(f, "/fclib_local/vectors/mu", &nmu, &mu));
  PetscCall(ReadInts(f, "/fclib_local/spacedim", &n1, &sd));
  H5Fclose(f);
  n  = m[0];
  nc = nmu;
  PetscCheck(m[0] == nn[0] && nq == n && n == nc * sd[0], PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED,
             "FCLIB file '%s': inconsistent sizes (m %" PetscInt_FMT ", n %" PetscInt_FMT ", q %" PetscInt_FMT
             ", contacts %" PetscInt_FMT ", dim %" PetscInt_FMT ")",
             path, m[0], nn[0], nq, nc, sd[0]);
  /* to CSR */
  PetscCall(PetscCalloc1(n + 1, &rowptr));
  if (nz[0] == -2) {
    nnz = pp[n];
    PetscCall(PetscMalloc2(nnz + 1, &col, nnz + 1, &val));
    for (PetscInt k = 0; k <= n; k++) rowptr[k] = pp[k];
    for (PetscInt e = 0; e < nnz; e++) {
      col[e] = ii[e];
      val[e] = x[e];
    }
  } else { /* CSC (p: column pointers, i: rows) or triplet (i: rows, p: columns) */
    PetscInt *cnt, *rows, *cols;
    nnz = nz[0] == -1 ? pp[n] : nz[0];
    PetscCall(PetscMalloc3(nnz + 1, &rows, nnz + 1, &cols, n + 1, &cnt));
    for (PetscInt e = 0; e < nnz; e++) rows[e] = ii[e];
    if (nz[0] == -1) {
      for (PetscInt c = 0; c < n; c++)
        for (PetscInt e = pp[c]; e < pp[c + 1]; e++) cols[e] = c;
    } else
      for (PetscInt e = 0; e < nnz; e++) cols[e] = pp[e];
    PetscCall(PetscMalloc2(nnz + 1, &col, nnz + 1, &val));
    for (PetscInt e = 0; e < nnz; e++) rowptr[rows[e] + 1]++;
    for (PetscInt k = 0; k < n; k++) rowptr[k + 1] += rowptr[k];
    for (PetscInt k = 0; k <= n; k++) cnt[k] = rowptr[k];
    for (PetscInt e = 0; e < nnz; e++) {
      col[cnt[rows[e]]]   = cols[e];
      val[cnt[rows[e]]++] = x[e];
    }
    PetscCall(PetscFree3(rows, cols, cnt));
  }
  PetscCall(PetscMalloc1(nc, &dim));
  for (PetscInt i = 0; i < nc; i++) dim[i] = sd[0];
  PetscCall(FCContactProblemCreateCSR(nc, dim, mu, rowptr, col, val, q, prob));
  PetscCall(PetscFree(dim));
  PetscCall(PetscFree2(col, val));
  PetscCall(PetscFree(rowptr));
  PetscCall(PetscFree(m));
  PetscCall(PetscFree(nn));
  PetscCall(PetscFree(nz));
  PetscCall(PetscFree(pp));
  PetscCall(PetscFree(ii));
  PetscCall(PetscFree(x));
  PetscCall(PetscFree(q));
  PetscCall(PetscFree(mu));
  PetscCall(PetscFree(sd));
  PetscFunctionReturn(0);
}
