/* Memory per rank (docs/output.md, /memory; the run summary's table): for each rank, the largest
   over the steps of its peak resident memory and of the contact data it holds, each counted where
   it is allocated: W_H and W_k (the fast scheme), W_b and Sigma / C (the bodies' compliance
   builders) and the factorization of A (MUMPS' own count, INFO(22), condensed builder). Updated
   after every step (local, no communication), gathered at the end of the run. */
#include "scene.h"
#include "../scheme/scheme.h"
#include "../io/io.h"
#include <sys/resource.h>

const char *const FCMemoryNames[FC_MEMORY_NUM] = {"peak_rss", "W_H", "W_k", "W_b", "Sigma", "factor", "contact_data"};

PetscErrorCode FCMemoryUpdate(FCScheme scheme, PetscInt nbodies, FCBody bodies[], PetscReal peak[FC_MEMORY_NUM])
{
  struct rusage ru;
  PetscReal     m[FC_MEMORY_NUM] = {0};

  PetscFunctionBegin;
  if (!getrusage(RUSAGE_SELF, &ru)) m[0] = 1024.0 * (PetscReal)ru.ru_maxrss; /* kB on Linux */
  if (scheme) PetscCall(FCSchemeGetHeldMemory(scheme, &m[1], &m[2]));
  for (PetscInt b = 0; b < nbodies; b++) {
    PetscReal bytes[3];
    PetscCall(FCBodyGetContactMemory(bodies[b], bytes));
    m[3] += bytes[0];
    m[4] += bytes[1];
    m[5] += bytes[2];
  }
  m[6] = m[1] + m[2] + m[3] + m[4];
  for (int i = 0; i < FC_MEMORY_NUM; i++) peak[i] = PetscMax(peak[i], m[i]);
  PetscFunctionReturn(0);
}

/* Rank 0 prints every rank's row of n values (MB) under a title and the column names */
static PetscErrorCode PrintRows(MPI_Comm comm, const char title[], int n, const char *const names[],
                                const PetscReal row[])
{
  PetscMPIInt size, rank;
  PetscReal  *all = NULL;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_size(comm, &size));
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  if (!rank) PetscCall(PetscMalloc1(n * size, &all));
  PetscCallMPI(MPI_Gather(row, n, MPIU_REAL, all, n, MPIU_REAL, 0, comm));
  PetscCall(PetscPrintf(comm, "  %s:", title));
  for (int i = 0; i < n; i++) PetscCall(PetscPrintf(comm, " %s", names[i]));
  PetscCall(PetscPrintf(comm, "\n"));
  for (PetscMPIInt r = 0; r < size && !rank; r++) {
    PetscCall(PetscPrintf(PETSC_COMM_SELF, "    rank %d:", (int)r));
    for (int i = 0; i < n; i++) PetscCall(PetscPrintf(PETSC_COMM_SELF, " %.1f", (double)(all[n * r + i] / 1048576.0)));
    PetscCall(PetscPrintf(PETSC_COMM_SELF, "\n"));
  }
  PetscCall(PetscFree(all));
  PetscFunctionReturn(0);
}

/* The ranks' rows (MB) printed by rank 0 (print), and written to /memory and /memory_phases (out;
   NULL: not). The phases' row: the growth of the peak RSS while each phase ran, the first column
   (set_up) what it grew outside them (set-up, mesh, operators, the run's own bookkeeping): the
   columns sum to the peak RSS, and the largest says which phase set it */
PetscErrorCode FCMemoryReport(MPI_Comm comm, const PetscReal peak_in[FC_MEMORY_NUM], PetscBool print, FCOutput out)
{
  const char   *names[FC_PHASE_NUM + 1];
  PetscReal     grown[FC_PHASE_NUM + 1], sum = 0.0, peak[FC_MEMORY_NUM];
  struct rusage ru;

  PetscFunctionBegin;
  /* the peak RSS now: the last step's output came after the step's update */
  for (int i = 0; i < FC_MEMORY_NUM; i++) peak[i] = peak_in[i];
  if (!getrusage(RUSAGE_SELF, &ru)) peak[0] = PetscMax(peak[0], 1024.0 * (PetscReal)ru.ru_maxrss);
  names[0] = "set_up";
  PetscCall(FCPhaseGetMemoryGrowth(&grown[1]));
  for (int p = 0; p < FC_PHASE_NUM; p++) {
    names[p + 1] = FCPhaseNames[p];
    sum += grown[p + 1];
  }
  grown[0] = peak[0] - sum;
  if (out) {
    PetscCall(FCOutputWriteMemory(out, "memory", "bytes; per rank, the largest over the steps of the run",
                                  FC_MEMORY_NUM, FCMemoryNames, peak));
    PetscCall(FCOutputWriteMemory(out, "memory_phases",
                                  "bytes; per rank, how much the peak RSS grew while each phase ran (set_up: outside "
                                  "the phases); the row sums to /memory's peak_rss",
                                  FC_PHASE_NUM + 1, names, grown));
  }
  if (!print) PetscFunctionReturn(0);
  PetscCall(PrintRows(comm, "memory per rank (MB, largest over the steps)", FC_MEMORY_NUM, FCMemoryNames, peak));
  PetscCall(PrintRows(comm, "peak RSS growth per phase (MB)", FC_PHASE_NUM + 1, names, grown));
  PetscFunctionReturn(0);
}
