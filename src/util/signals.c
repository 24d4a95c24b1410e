/* SIGINT and SIGTERM during a run: the signal is only recorded; the time loop checks it between
   steps (all ranks agree through one reduction), closes the output so that every completed step
   stays readable, and the run exits with status 128 + signal. A second signal while the step
   finishes falls back to the default action (a stuck run can still be killed).
   The executable blocks both signals in every thread before MPI starts its own (FCSignalsBlock) and
   takes them in a thread of its own (sigwait): a library that installs its own handler for a while
   never gets them. METIS does (GKlib turns SIGTERM into its error return, and from another thread,
   such as MPI's progress thread, its handler's longjmp would crash the process), and MUMPS orders
   with METIS. A program that calls the library itself (Python) gets a plain handler instead. */
#include "../fcimpl.h"
#include <signal.h>
#include <pthread.h>

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

static PetscBool             blocked = PETSC_FALSE;
static volatile sig_atomic_t running = 0; /* FCSignalsInstall was called: a run takes them */

static void *Wait(void *arg)
{
  sigset_t set;
  int      sig;

  (void)arg;
  sigemptyset(&set);
  sigaddset(&set, SIGINT);
  sigaddset(&set, SIGTERM);
  for (;;) {
    if (sigwait(&set, &sig)) continue;
    if (running && !caught) {
      caught = sig;
      continue;
    }
    /* before a run, or the second: the default action, here (a signal raised in this thread is
       this thread's) */
    signal(sig, SIG_DFL);
    pthread_sigmask(SIG_UNBLOCK, &set, NULL);
    raise(sig);
  }
  return NULL;
}

/* Before MPI and every library start their threads, which inherit the mask: SIGINT and SIGTERM
   blocked in all of them and taken by one thread, which records them once a run has begun
   (FCSignalsInstall) and before that ends the process as they would */
PetscErrorCode FCSignalsBlock(void)
{
  sigset_t       set;
  pthread_t      th;
  pthread_attr_t attr;

  sigemptyset(&set);
  sigaddset(&set, SIGINT);
  sigaddset(&set, SIGTERM);
  if (pthread_sigmask(SIG_BLOCK, &set, NULL)) return PETSC_ERR_SYS;
  pthread_attr_init(&attr);
  pthread_attr_setdetachstate(&attr, PTHREAD_CREATE_DETACHED);
  if (pthread_create(&th, &attr, Wait, NULL)) {
    pthread_sigmask(SIG_UNBLOCK, &set, NULL);
    return PETSC_ERR_SYS;
  }
  pthread_attr_destroy(&attr);
  blocked = PETSC_TRUE;
  return 0;
}

PetscErrorCode FCSignalsInstall(void)
{
  struct sigaction sa;

  PetscFunctionBegin;
  if (blocked) { /* the executable's thread takes them from now on */
    running = 1;
    PetscFunctionReturn(0);
  }
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
