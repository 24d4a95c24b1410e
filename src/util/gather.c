/* Records of any fixed size (contacts, surface triangles), concatenated on every rank in rank
   order: the one all-gather the replicated phases use. */
#include "../fcimpl.h"

PetscErrorCode FCAllgatherRecords(MPI_Comm comm, PetscInt n, size_t size, const void *loc, PetscInt *total, void **all)
{
  PetscMPIInt nranks, nloc = (PetscMPIInt)n, *counts, *displs, sum = 0, bytes = (PetscMPIInt)size;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_size(comm, &nranks));
  PetscCall(PetscMalloc2(nranks, &counts, nranks, &displs));
  PetscCallMPI(MPI_Allgather(&nloc, 1, MPI_INT, counts, 1, MPI_INT, comm));
  for (PetscMPIInt r = 0; r < nranks; r++) {
    displs[r] = sum * bytes;
    sum += counts[r];
    counts[r] *= bytes;
  }
  PetscCall(PetscMalloc((size_t)sum * size + size, all));
  PetscCallMPI(MPI_Allgatherv(loc, nloc * bytes, MPI_BYTE, *all, counts, displs, MPI_BYTE, comm));
  PetscCall(PetscFree2(counts, displs));
  *total = sum;
  PetscFunctionReturn(0);
}
