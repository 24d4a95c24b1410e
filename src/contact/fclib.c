/* FCLIB files (the library's local-problem layout: W as a scalar CSR, q, mu,
   the dimension): FCContactProblemLoadFCLIB reads one into a block-sparse problem (tools/fclib_solve,
   the tests), FCContactProblemWriteFCLIB writes any problem (-pgs_dump_problem). */
#include "contactimpl.h"
#include <hdf5.h>

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

static PetscErrorCode WriteArray(hid_t g, const char name[], hid_t type, hsize_t n, const void *v)
{
  hid_t s = H5Screate_simple(1, &n, NULL), d = H5Dcreate2(g, name, type, s, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);

  PetscFunctionBegin;
  PetscCheck(d >= 0 && H5Dwrite(d, type == H5T_STD_I64LE ? H5T_NATIVE_LLONG : H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL,
                                H5P_DEFAULT, v) >= 0,
             PETSC_COMM_SELF, PETSC_ERR_FILE_WRITE, "Cannot write FCLIB dataset %s", name);
  H5Dclose(d);
  H5Sclose(s);
  PetscFunctionReturn(0);
}

/* The problem in the FCLIB local layout that FCContactProblemLoadFCLIB reads (W in CSR, nz = -2),
   for tools/bench_pgs and Siconos; every contact must have the same number of rows */
PetscErrorCode FCContactProblemWriteFCLIB(FCContactProblem p, const char path[])
{
  hid_t      f, g, w, v;
  long long *rowptr, *col, one[1];
  PetscReal *val;
  PetscInt   nnz = 0, e = 0, n = p->n;

  PetscFunctionBegin;
  PetscCheck(p->rowcomm == MPI_COMM_NULL, PETSC_COMM_SELF, PETSC_ERR_SUP,
             "A contact problem held by block rows is written from its whole W (FCContactProblemGatherWhole)");
  for (PetscInt i = 0; i < p->nc; i++)
    PetscCheck(p->dim[i] == p->dim[0], PETSC_COMM_SELF, PETSC_ERR_SUP,
               "FCLIB needs the same rows for every contact: contact %" PetscInt_FMT " has %" PetscInt_FMT
               ", contact 0 %" PetscInt_FMT,
               i, p->dim[i], p->dim[0]);
  if (p->Wd)
    nnz = n * n;
  else
    for (PetscInt i = 0; i < p->nc; i++)
      for (PetscInt b = p->rowptr[i]; b < p->rowptr[i + 1]; b++) nnz += p->dim[i] * p->dim[p->col[b]];
  PetscCall(PetscMalloc3(n + 1, &rowptr, nnz + 1, &col, nnz + 1, &val));
  rowptr[0] = 0;
  for (PetscInt i = 0; i < p->nc; i++)
    for (PetscInt a = 0; a < p->dim[i]; a++) {
      if (p->Wd)
        for (PetscInt k = 0; k < n; k++, e++) {
          col[e] = k;
          val[e] = p->Wd[(p->off[i] + a) * n + k];
        }
      else
        for (PetscInt b = p->rowptr[i]; b < p->rowptr[i + 1]; b++) {
          PetscInt j = p->col[b], dj = p->dim[j];
          for (PetscInt c = 0; c < dj; c++, e++) {
            col[e] = p->off[j] + c;
            val[e] = p->val[p->boff[b] + a * dj + c];
          }
        }
      rowptr[p->off[i] + a + 1] = e;
    }
  f = H5Fcreate(path, H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  PetscCheck(f >= 0, PETSC_COMM_SELF, PETSC_ERR_FILE_OPEN, "Cannot create FCLIB file '%s'", path);
  g      = H5Gcreate2(f, "/fclib_local", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  w      = H5Gcreate2(g, "W", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  v      = H5Gcreate2(g, "vectors", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  one[0] = n;
  PetscCall(WriteArray(w, "m", H5T_STD_I64LE, 1, one));
  PetscCall(WriteArray(w, "n", H5T_STD_I64LE, 1, one));
  one[0] = -2;
  PetscCall(WriteArray(w, "nz", H5T_STD_I64LE, 1, one));
  PetscCall(WriteArray(w, "p", H5T_STD_I64LE, n + 1, rowptr));
  PetscCall(WriteArray(w, "i", H5T_STD_I64LE, nnz, col));
  PetscCall(WriteArray(w, "x", H5T_IEEE_F64LE, nnz, val));
  PetscCall(WriteArray(v, "q", H5T_IEEE_F64LE, n, p->q));
  PetscCall(WriteArray(v, "mu", H5T_IEEE_F64LE, p->nc, p->mu));
  one[0] = p->nc ? p->dim[0] : 3;
  PetscCall(WriteArray(g, "spacedim", H5T_STD_I64LE, 1, one));
  H5Gclose(v);
  H5Gclose(w);
  H5Gclose(g);
  H5Fclose(f);
  PetscCall(PetscFree3(rowptr, col, val));
  PetscFunctionReturn(0);
}
