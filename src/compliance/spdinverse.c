/* FCSPDInverse: C = Sigma^-1 for the dense SPD Schur complement that MUMPS leaves on rank 0 (the
   host) of a body's communicator (schurfactor.c), either

     host       LAPACK potrf + potri on the host alone, the other ranks idle; or
     scalapack  the host's array redistributed block-cyclically over a 1 x p BLACS grid of all
                the ranks (pdgemr2d), ScaLAPACK pdpotrf + pdpotri there, C gathered back to the
                host: ns^3 flops shared, 2 ns^2 values moved; or
     columns    the Cholesky factor on the host (Sigma = U^T U, ns^3/3 flops), broadcast; each rank
                forms a block of columns J of X = U^-1 and its share X(:, J) X(:, J)^T of
                C = X X^T; the shares are summed on the host (MPI_Reduce): the 2 ns^3/3 flops of
                potri split over the ranks, 2 ns^2 values moved. The blocks are balanced by the
                cost of a column of X, which grows like j^2 (the block of the last columns is the
                narrowest).

   Both take Sigma's upper triangle (column-major, ns x ns, on the host) and leave the whole
   symmetric C in the same array. The distributed Schur complement (FCSPDInverseApplyLocal) never
   comes to the host: MUMPS leaves each rank its block-cyclic columns of Sigma on the same 1 x p
   grid, ScaLAPACK inverts them in place and each rank keeps its columns of C. host is the default
   (-compliance_condensed_inverse): where rank 1 comes late from its share of MUMPS' factorization, a split does not pay
   (docs/scaling.md). */
#include "complianceimpl.h"
#include <petscblaslapack.h>

/* BLACS and ScaLAPACK (libscalapack-openmpi; Debian ships no header for them) */
extern int  Csys2blacs_handle(MPI_Comm);
extern void Cfree_blacs_system_handle(int);
extern void Cblacs_gridinit(int *ctxt, const char *order, int nprow, int npcol);
extern void Cblacs_gridinfo(int ctxt, int *nprow, int *npcol, int *myrow, int *mycol);
extern void Cblacs_gridexit(int ctxt);
extern int  numroc_(const int *n, const int *nb, const int *iproc, const int *isrcproc, const int *nprocs);
extern void descinit_(int *desc, const int *m, const int *n, const int *mb, const int *nb, const int *irsrc,
                      const int *icsrc, const int *ictxt, const int *lld, int *info);
extern void Cpdgemr2d(int m, int n, double *a, int ia, int ja, int *desca, double *b, int ib, int jb, int *descb,
                      int gcontext);
extern void pdpotrf_(const char *uplo, const int *n, double *a, const int *ia, const int *ja, const int *desca,
                     int *info);
extern void dtrtri_(const char *uplo, const char *diag, const int *n, double *a, const int *lda, int *info);
extern void dlauum_(const char *uplo, const int *n, double *a, const int *lda, int *info);
extern void dtrmm_(const char *side, const char *uplo, const char *transa, const char *diag, const int *m, const int *n,
                   const double *alpha, const double *a, const int *lda, double *b, const int *ldb);
extern void pdtran_(const int *m, const int *n, const double *alpha, const double *a, const int *ia, const int *ja,
                    const int *desca, const double *beta, double *c, const int *ic, const int *jc, const int *descc);
extern void pdpotri_(const char *uplo, const int *n, double *a, const int *ia, const int *ja, const int *desca,
                     int *info);

struct _FCSPDInverse {
  MPI_Comm    comm;
  PetscMPIInt rank, size;
  char        name[FC_MAX_NAME];
  PetscBool   distributed; /* scalapack */
  PetscBool   columns;     /* columns */
  PetscBool   grid;        /* the BLACS grids exist (scalapack, distributed, auto on several ranks) */
  int         sys;         /* BLACS handle of comm */
  int         ctxt_all;    /* 1 x size grid */
  int         ctxt_host;   /* 1 x 1 grid on the host (-1 elsewhere) */
  int         mycol;
  PetscInt    nalloc;
  PetscReal  *loc; /* this rank's block-cyclic columns (ns x nloc) */
};

PetscErrorCode FCSPDInverseCreate(MPI_Comm comm, const char name[], FCSPDInverseType type, FCSPDInverse *inv)
{
  FCSPDInverse v;

  PetscFunctionBegin;
  PetscCall(PetscNew(&v));
  v->comm = comm;
  PetscCallMPI(MPI_Comm_rank(comm, &v->rank));
  PetscCallMPI(MPI_Comm_size(comm, &v->size));
  PetscCall(PetscStrncpy(v->name, name, sizeof(v->name)));
  v->distributed = (PetscBool)(type == FC_SPD_INVERSE_SCALAPACK && v->size > 1);
  v->grid        = (PetscBool)(v->size > 1 && type != FC_SPD_INVERSE_HOST && type != FC_SPD_INVERSE_COLUMNS);
  v->columns     = (PetscBool)(type == FC_SPD_INVERSE_COLUMNS && v->size > 1);
  if (v->grid) {
    int nprow, npcol, myrow;
    v->sys      = Csys2blacs_handle(comm);
    v->ctxt_all = v->sys;
    Cblacs_gridinit(&v->ctxt_all, "R", 1, (int)v->size);
    v->ctxt_host = v->sys;
    Cblacs_gridinit(&v->ctxt_host, "R", 1, 1); /* the first process of comm: the host */
    Cblacs_gridinfo(v->ctxt_all, &nprow, &npcol, &myrow, &v->mycol);
    PetscCheck(nprow == 1 && npcol == v->size && v->mycol == v->rank, comm, PETSC_ERR_LIB,
               "BLACS grid of body '%s': %d x %d, column %d on rank %d (expected 1 x %d in rank order)", name, nprow,
               npcol, v->mycol, (int)v->rank, (int)v->size);
  }
  *inv = v;
  PetscFunctionReturn(0);
}

/* Room for this rank's block-cyclic columns of an ns x ns matrix (ns rows by nloc columns) */
static PetscErrorCode Reserve(FCSPDInverse v, int n)
{
  int nb = FC_SPD_BLOCK, zero = 0, nloc, size = (int)v->size;

  PetscFunctionBegin;
  nloc = numroc_(&n, &nb, &v->mycol, &zero, &size);
  if (v->nalloc < (PetscInt)n * nloc + 1) {
    PetscCall(PetscFree(v->loc));
    v->nalloc = (PetscInt)n * nloc + 1;
    PetscCall(PetscMalloc1(v->nalloc, &v->loc));
  }
  PetscFunctionReturn(0);
}

/* First column of each rank's block (cut[0 .. size]): the cost of the columns up to j grows like
   j^3, so cut[r] = n (r / size)^(1/3) */
static void ColumnCuts(int n, PetscMPIInt size, int cut[])
{
  for (PetscMPIInt r = 0; r <= size; r++) cut[r] = (int)PetscFloorReal(n * PetscCbrtReal((PetscReal)r / size) + 0.5);
  cut[0]    = 0;
  cut[size] = n;
}

/* columns: U (upper, n x n, lda n) on every rank; this rank adds X(:, J) X(:, J)^T to c (upper
   triangle, n x n, zero on entry) for its columns J = [j0, j1) of X = U^-1:
     X(J, J)  = U(J, J)^-1                       (trtri)
     X(0:j0, J) = -U(0:j0, 0:j0)^-1 U(0:j0, J) X(J, J)   (trmm, trsm)
   and the product in three parts, the diagonal block by lauum */
static PetscErrorCode ColumnsShare(FCSPDInverse v, int n, const PetscReal u[], int j0, int j1, PetscReal c[])
{
  int        m = j1 - j0, info = 0;
  PetscReal *xjj, *b = NULL, one = 1.0, mone = -1.0;

  PetscFunctionBegin;
  if (!m) PetscFunctionReturn(0);
  PetscCall(PetscCalloc1((size_t)m * m, &xjj));
  for (int j = 0; j < m; j++)
    for (int i = 0; i <= j; i++) xjj[i + j * m] = u[(j0 + i) + (j0 + j) * (size_t)n];
  dtrtri_("U", "N", &m, xjj, &m, &info);
  PetscCheck(info == 0, PETSC_COMM_SELF, PETSC_ERR_LIB, "LAPACK trtri on the Cholesky factor of body '%s': %d", v->name,
             info);
  if (j0) {
    PetscBLASInt bj0, bm;
    PetscCall(PetscMalloc1((size_t)j0 * m, &b));
    for (int j = 0; j < m; j++) PetscCall(PetscArraycpy(b + (size_t)j * j0, u + (size_t)(j0 + j) * n, j0));
    dtrmm_("R", "U", "N", "N", &j0, &m, &mone, xjj, &m, b, &j0); /* -U(0:j0, J) X(J, J) */
    PetscCall(PetscBLASIntCast(j0, &bj0));
    PetscCall(PetscBLASIntCast(m, &bm));
    { /* b = U(0:j0, 0:j0)^-1 b: X(0:j0, J) */
      PetscBLASInt bn = (PetscBLASInt)n;
      PetscCallBLAS("BLAStrsm", BLAStrsm_("L", "U", "N", "N", &bj0, &bm, &one, u, &bn, b, &bj0));
      /* c(0:j0, 0:j0) += b b^T; c(0:j0, J) += b X(J, J)^T (X(J, J) upper, its lower part zero) */
      PetscCallBLAS("BLASsyrk", BLASsyrk_("U", "N", &bj0, &bm, &one, b, &bj0, &one, c, &bn));
      PetscCallBLAS("BLASgemm",
                    BLASgemm_("N", "T", &bj0, &bm, &bm, &one, b, &bj0, xjj, &bm, &one, c + (size_t)j0 * n, &bn));
    }
    PetscCall(PetscFree(b));
  }
  dlauum_("U", &m, xjj, &m, &info); /* X(J, J) X(J, J)^T, upper */
  PetscCheck(info == 0, PETSC_COMM_SELF, PETSC_ERR_LIB, "LAPACK lauum on the Schur complement of body '%s': %d",
             v->name, info);
  for (int j = 0; j < m; j++)
    for (int i = 0; i <= j; i++) c[(j0 + i) + (size_t)(j0 + j) * n] += xjj[i + j * m];
  PetscCall(PetscFree(xjj));
  PetscFunctionReturn(0);
}

/* The host's a (ns x ns, column-major, upper triangle of Sigma) becomes C = Sigma^-1 (whole).
   Collective. */
PetscErrorCode FCSPDInverseApply(FCSPDInverse v, PetscInt ns, PetscReal a[])
{
  PetscFunctionBegin;
  if (!ns) PetscFunctionReturn(0);
  if (v->columns) {
    int        n, info = 0, *cut;
    PetscReal *u, *c;
    PetscCall(PetscMPIIntCast(ns, &n));
    PetscCall(PetscMalloc1(v->size + 1, &cut));
    PetscCall(PetscCalloc1((size_t)n * n, &c));
    u = a;
    if (v->rank) PetscCall(PetscMalloc1((size_t)n * n, &u));
    if (!v->rank) {
      PetscBLASInt bn, binfo;
      PetscCall(PetscBLASIntCast(ns, &bn));
      PetscCallBLAS("LAPACKpotrf", LAPACKpotrf_("U", &bn, a, &bn, &binfo));
      info = (int)binfo;
    }
    PetscCallMPI(MPI_Bcast(&info, 1, MPI_INT, 0, v->comm)); /* one verdict */
    if (info) { /* a failed step (step control tries a smaller one): nothing left allocated */
      if (v->rank) PetscCall(PetscFree(u));
      PetscCall(PetscFree(c));
      PetscCall(PetscFree(cut));
    }
    PetscCheck(info == 0, v->comm, PETSC_ERR_CONV_FAILED,
               "The Schur complement of A of body '%s' on its %d contact DOFs is not positive definite (LAPACK "
               "potrf info %d)",
               v->name, n, info);
    PetscCallMPI(MPI_Bcast(u, n * n, MPIU_REAL, 0, v->comm));
    ColumnCuts(n, v->size, cut);
    PetscCall(ColumnsShare(v, n, u, cut[v->rank], cut[v->rank + 1], c));
    PetscCallMPI(MPI_Reduce(v->rank ? c : MPI_IN_PLACE, c, n * n, MPIU_REAL, MPIU_SUM, 0, v->comm));
    if (!v->rank)
      PetscCall(PetscArraycpy(a, c, (size_t)n * n));
    else
      PetscCall(PetscFree(u));
    PetscCall(PetscFree(c));
    PetscCall(PetscFree(cut));
  } else if (!v->distributed) {
    if (!v->rank) {
      PetscBLASInt n, info;
      PetscCall(PetscBLASIntCast(ns, &n));
      PetscCallBLAS("LAPACKpotrf", LAPACKpotrf_("U", &n, a, &n, &info));
      PetscCheck(info == 0, PETSC_COMM_SELF, PETSC_ERR_CONV_FAILED,
                 "The Schur complement of A of body '%s' on its %" PetscInt_FMT
                 " contact DOFs is not positive definite (LAPACK potrf info %d)",
                 v->name, ns, (int)info);
      PetscCallBLAS("LAPACKpotri", LAPACKpotri_("U", &n, a, &n, &info));
      PetscCheck(info == 0, PETSC_COMM_SELF, PETSC_ERR_LIB, "LAPACK potri on the Schur complement of body '%s': %d",
                 v->name, (int)info);
    }
  } else {
    int n, nb = FC_SPD_BLOCK, zero = 0, one = 1, info = 0, dh[9], dc[9], lldc;
    PetscCall(PetscMPIIntCast(ns, &n));
    PetscCall(Reserve(v, n));
    lldc = n; /* one row of processes: every rank holds all n rows of its columns */
    descinit_(dc, &n, &n, &nb, &nb, &zero, &zero, &v->ctxt_all, &lldc, &info);
    PetscCheck(info == 0, PETSC_COMM_SELF, PETSC_ERR_LIB, "ScaLAPACK descinit (grid) for body '%s': %d", v->name, info);
    if (!v->rank) {
      descinit_(dh, &n, &n, &n, &n, &zero, &zero, &v->ctxt_host, &lldc, &info);
      PetscCheck(info == 0, PETSC_COMM_SELF, PETSC_ERR_LIB, "ScaLAPACK descinit (host) for body '%s': %d", v->name,
                 info);
    } else
      dh[1] = -1; /* not in the host grid */
    Cpdgemr2d(n, n, a, 1, 1, dh, v->loc, 1, 1, dc, v->ctxt_all);
    pdpotrf_("U", &n, v->loc, &one, &one, dc, &info);
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &info, 1, MPI_INT, MPI_MAX, v->comm)); /* one verdict */
    PetscCheck(info == 0, v->comm, PETSC_ERR_CONV_FAILED,
               "The Schur complement of A of body '%s' on its %d contact DOFs is not positive definite (ScaLAPACK "
               "pdpotrf info %d)",
               v->name, n, info);
    pdpotri_("U", &n, v->loc, &one, &one, dc, &info);
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &info, 1, MPI_INT, MPI_MAX, v->comm));
    PetscCheck(info == 0, v->comm, PETSC_ERR_LIB, "ScaLAPACK pdpotri on the Schur complement of body '%s': %d", v->name,
               info);
    Cpdgemr2d(n, n, v->loc, 1, 1, dc, a, 1, 1, dh, v->ctxt_all);
  }
  if (!v->rank) /* the lower triangle from the upper, by tiles (a column read across rows strides ns) */
    for (PetscInt j0 = 0; j0 < ns; j0 += 32)
      for (PetscInt i0 = j0; i0 < ns; i0 += 32)
        for (PetscInt j = j0; j < PetscMin(j0 + 32, ns); j++)
          for (PetscInt i = PetscMax(i0, j + 1); i < PetscMin(i0 + 32, ns); i++) a[i + j * ns] = a[j + i * ns];
  PetscFunctionReturn(0);
}

/* Local columns of an n x n matrix block-cyclic over the 1 x size grid: how many, and the global
   index of local column jl */
PetscInt FCSPDBlock(PetscInt n, PetscMPIInt size)
{
  PetscInt nb = (n + 4 * size - 1) / (4 * size); /* at least 4 blocks a rank: columns even within a block */
  return PetscMax(1, PetscMin(FC_SPD_BLOCK, nb));
}

PetscInt FCSPDLocalColumns(PetscInt n, PetscInt nbl, PetscMPIInt rank, PetscMPIInt size)
{
  int nn = (int)n, nb = (int)nbl, zero = 0, r = (int)rank, p = (int)size;
  return (PetscInt)numroc_(&nn, &nb, &r, &zero, &p);
}

PetscInt FCSPDGlobalColumn(PetscInt jl, PetscInt nb, PetscMPIInt rank, PetscMPIInt size)
{
  return ((jl / nb) * size + rank) * nb + jl % nb;
}

/* Rows of the transpose's panel (FCSPDInverseApplyLocal): a scratch of 1/16 of this rank's columns,
   at least one block high, so that the transient memory stays small beside C's columns */
static PetscInt PanelRows(PetscInt ns, PetscInt nbl)
{
  return PetscMin(ns, PetscMax(nbl, (ns + 15) / 16));
}

/* This rank's block-cyclic columns of Sigma (n rows, lld n; the lower triangle at least) become its
   columns of the whole symmetric C = Sigma^-1: pdpotrf and pdpotri on the lower triangle, then the
   upper one from the transpose, one panel of rows at a time (pdtran of L's columns [r0, r0 + h)
   into an h x n scratch on the same 1 x p grid). Collective. */
PetscErrorCode FCSPDInverseApplyLocal(FCSPDInverse v, PetscInt ns, PetscInt nbl, PetscReal loc[])
{
  int        n, nb = (int)nbl, zero = 0, one = 1, info = 0, dc[9], lld;
  PetscInt   nloc, hmax;
  PetscReal *t, dzero = 0.0, done = 1.0;

  PetscFunctionBegin;
  if (!ns) PetscFunctionReturn(0);
  PetscCheck(v->grid, v->comm, PETSC_ERR_PLIB, "Body '%s': a distributed inverse without a BLACS grid", v->name);
  PetscCall(PetscMPIIntCast(ns, &n));
  lld = n;
  descinit_(dc, &n, &n, &nb, &nb, &zero, &zero, &v->ctxt_all, &lld, &info);
  PetscCheck(info == 0, PETSC_COMM_SELF, PETSC_ERR_LIB, "ScaLAPACK descinit (grid) for body '%s': %d", v->name, info);
  pdpotrf_("L", &n, loc, &one, &one, dc, &info);
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &info, 1, MPI_INT, MPI_MAX, v->comm)); /* one verdict */
  PetscCheck(info == 0, v->comm, PETSC_ERR_CONV_FAILED,
             "The Schur complement of A of body '%s' on its %d contact DOFs is not positive definite (ScaLAPACK "
             "pdpotrf info %d)",
             v->name, n, info);
  pdpotri_("L", &n, loc, &one, &one, dc, &info);
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &info, 1, MPI_INT, MPI_MAX, v->comm));
  PetscCheck(info == 0, v->comm, PETSC_ERR_LIB, "ScaLAPACK pdpotri on the Schur complement of body '%s': %d", v->name,
             info);
  nloc = FCSPDLocalColumns(ns, nbl, v->rank, v->size);
  hmax = PanelRows(ns, nbl);
  PetscCall(PetscMalloc1((size_t)hmax * nloc + 1, &t));
  for (PetscInt r0 = 0; r0 < ns; r0 += hmax) {
    int h = (int)PetscMin(hmax, ns - r0), ja = (int)r0 + 1, dt[9];

    descinit_(dt, &h, &n, &h, &nb, &zero, &zero, &v->ctxt_all, &h, &info);
    PetscCheck(info == 0, PETSC_COMM_SELF, PETSC_ERR_LIB, "ScaLAPACK descinit (panel) for body '%s': %d", v->name,
               info);
    pdtran_(&h, &n, &done, loc, &one, &ja, dc, &dzero, t, &one, &one, dt); /* t = L(:, r0:r0+h)^T */
    for (PetscInt jl = 0; jl < nloc; jl++) {
      PetscInt j = FCSPDGlobalColumn(jl, nbl, v->rank, v->size);
      for (PetscInt i = r0; i < PetscMin(j, r0 + h); i++)
        loc[i + jl * ns] = t[(i - r0) + jl * h]; /* C's upper triangle */
    }
  }
  PetscCall(PetscFree(t));
  PetscFunctionReturn(0);
}

PetscErrorCode FCSPDInverseDestroy(FCSPDInverse *inv)
{
  FCSPDInverse v = *inv;

  PetscFunctionBegin;
  if (!v) PetscFunctionReturn(0);
  if (v->grid) {
    if (!v->rank) Cblacs_gridexit(v->ctxt_host);
    Cblacs_gridexit(v->ctxt_all);
    Cfree_blacs_system_handle(v->sys);
  }
  PetscCall(PetscFree(v->loc));
  PetscCall(PetscFree(v));
  *inv = NULL;
  PetscFunctionReturn(0);
}
