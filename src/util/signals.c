/* SIGINT and SIGTERM during a run: the handler only records the signal; the time loop checks it
   between steps (all ranks agree through one reduction), closes the output so that every
   completed step stays readable, and the run exits with status 128 + signal. A second signal
   while the step finishes falls back to the default action (a stuck run can still be killed). */
#include "../fcimpl.h"
#include <signal.h>

static volatile sig_atomic_t caught = 0;

static void Handler(int sig)
{
  if (caught) {
    signal(sig, SIG_DFL);
    raise(sig);
    return;
  }
  caught = sig;
}

PetscErrorCode FCSignalsInstall(void)
{
  struct sigaction sa;

  PetscFunctionBegin;
  memset(&sa, 0, sizeof(sa));
  sa.sa_handler = Handler;
  sa.sa_flags   = SA_RESTART; /* a system call the signal lands in (MPI, MUMPS, HDF5) resumes: the step finishes */
  sigemptyset(&sa.sa_mask);
  PetscCheck(sigaction(SIGINT, &sa, NULL) == 0 && sigaction(SIGTERM, &sa, NULL) == 0, PETSC_COMM_SELF, PETSC_ERR_SYS,
             "Cannot install the SIGINT/SIGTERM handler");
  PetscFunctionReturn(0);
}

/* The signal caught by any rank (0: none) */
PetscErrorCode FCSignalsPending(MPI_Comm comm, int *sig)
{
  PetscFunctionBegin;
  *sig = (int)caught;
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, sig, 1, MPI_INT, MPI_MAX, comm));
  PetscFunctionReturn(0);
}

int FCSignalsCaught(void)
{
  return (int)caught;
}
