/* A dense contact problem held by block rows over the ranks (FCContactProblemCreateDenseRows):
   each rank keeps only the rows of its block of contacts, the block the split sweeps give it
   (pgs_split.c), so W (M x M, the fast scheme's W_k) takes M^2 / p values per rank and is formed
   p ways (src/scheme/fast.c). What needs more than a rank's rows is collective here: u = W r + q
   (each rank its rows, then an MPI_Allgatherv), and W whole on rank 0 when rank 0 must go on alone
   (-pgs_ranks auto, split sweeps that would not converge) or write the problem (-pgs_dump_problem). */
#include "../fcimpl.h"
#include "contactimpl.h"
#include <petscblaslapack.h>

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
