/* FCSPDInverse: C = Sigma^-1 for the dense SPD Schur complement that MUMPS leaves on rank 0 (the
   host) of a body's communicator (schurfactor.c), either

     host       LAPACK potrf + potri on the host alone, the other ranks idle; or
     scalapack  the host's array redistributed block-cyclically over a 1 x p BLACS grid of all
                the ranks (pdgemr2d), ScaLAPACK pdpotrf + pdpotri there, C gathered back to the
                host: ns^3 flops shared, 2 ns^2 values moved.

   Both take Sigma's upper triangle (column-major, ns x ns, on the host) and leave the whole
   symmetric C in the same array. host is the default (-compliance_condensed_inverse): on this
   VM's 2 ranks scalapack was no faster from 600 to 4800 rows, and slower in the solver (issue
   16; both measured in docs/scaling.md). */
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
extern void pdpotri_(const char *uplo, const int *n, double *a, const int *ia, const int *ja, const int *desca,
                     int *info);

#ifndef FC_SPD_BLOCK
#define FC_SPD_BLOCK 64 /* ScaLAPACK block size (rows and columns) */
#endif

struct _FCSPDInverse {
  MPI_Comm    comm;
  PetscMPIInt rank, size;
  char        name[FC_MAX_NAME];
  PetscBool   distributed;
  int         sys;       /* BLACS handle of comm */
  int         ctxt_all;  /* 1 x size grid */
  int         ctxt_host; /* 1 x 1 grid on the host (-1 elsewhere) */
  int         mycol;
  PetscInt    nalloc;
  PetscReal  *loc; /* this rank's block-cyclic columns (ns x nloc) */
};

PetscErrorCode FCSPDInverseCreate(MPI_Comm comm, const char name[], PetscBool distributed, FCSPDInverse *inv)
{
  FCSPDInverse v;

  PetscFunctionBegin;
  PetscCall(PetscNew(&v));
  v->comm = comm;
  PetscCallMPI(MPI_Comm_rank(comm, &v->rank));
  PetscCallMPI(MPI_Comm_size(comm, &v->size));
  PetscCall(PetscStrncpy(v->name, name, sizeof(v->name)));
  v->distributed = (PetscBool)(distributed && v->size > 1);
  if (v->distributed) {
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

/* The host's a (ns x ns, column-major, upper triangle of Sigma) becomes C = Sigma^-1 (whole).
   Collective. */
PetscErrorCode FCSPDInverseApply(FCSPDInverse v, PetscInt ns, PetscReal a[])
{
  PetscFunctionBegin;
  if (!ns) PetscFunctionReturn(0);
  if (!v->distributed) {
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
  if (!v->rank) /* the lower triangle from the upper */
    for (PetscInt j = 0; j < ns; j++)
      for (PetscInt i = j + 1; i < ns; i++) a[i + j * ns] = a[j + i * ns];
  PetscFunctionReturn(0);
}

PetscErrorCode FCSPDInverseDestroy(FCSPDInverse *inv)
{
  FCSPDInverse v = *inv;

  PetscFunctionBegin;
  if (!v) PetscFunctionReturn(0);
  if (v->distributed) {
    if (!v->rank) Cblacs_gridexit(v->ctxt_host);
    Cblacs_gridexit(v->ctxt_all);
    Cfree_blacs_system_handle(v->sys);
  }
  PetscCall(PetscFree(v->loc));
  PetscCall(PetscFree(v));
  *inv = NULL;
  PetscFunctionReturn(0);
}
