/* How fecontact reports an error (FCPushErrorHandler, include/fecontact.h). An input error, a
   diverging run or an interruption is the user's business, not the code's: one line on rank 0, no
   traceback. Everything else goes to PETSc's traceback handler. The first message of the last
   error (PETSC_ERROR_INITIAL: where it was raised) is kept, for a caller that reports it itself. */
#include "../fcimpl.h"

static char      last[1024];
static PetscBool printing = PETSC_TRUE; /* whether the handler below a step's (FCPushStepErrorHandler) prints */
static char      stepmode;              /* its context: the address marks the step's handler */

/* The failures that step control redoes with a smaller step (FCStepControl, src/scene/stepcontrol.c):
   a Newton free motion or a contact solve that did not converge, an element turned inside out, the
   energy guard (PETSC_ERR_CONV_FAILED), a state that is not finite (PETSC_ERR_FP) */
PetscBool FCErrorIsStepFailure(PetscErrorCode n)
{
  return n == PETSC_ERR_CONV_FAILED || n == PETSC_ERR_FP ? PETSC_TRUE : PETSC_FALSE;
}

/* The exit status of an error that every rank raises alike (docs/options.md, "Exit status"; the one
   table of them): 1 an input error, 2 a run that diverged or could not go on, 3 an output that could
   not be written, 128 + the signal an interruption; 0 for any other error, which may have happened on
   one rank only (the driver aborts every rank) */
int FCExitStatus(PetscErrorCode n)
{
  switch (n) {
  case PETSC_ERR_USER_INPUT:
  case PETSC_ERR_ARG_UNKNOWN_TYPE:
    return 1;
  case PETSC_ERR_FP:
  case PETSC_ERR_CONV_FAILED:
  case PETSC_ERR_MEM:
    return 2;
  case PETSC_ERR_FILE_WRITE:
    return 3;
  case PETSC_ERR_SIG:
    return 128 + FCSignalsCaught();
  default:
    return 0;
  }
}

/* Errors reported in one line: those of the table above, and a file that cannot be opened */
static PetscBool IsUserError(PetscErrorCode n)
{
  return FCExitStatus(n) || n == PETSC_ERR_FILE_OPEN ? PETSC_TRUE : PETSC_FALSE;
}

/* ctx: non-NULL, print (the handler pushed with print) */
static PetscErrorCode Handler(MPI_Comm comm, int line, const char *fun, const char *file, PetscErrorCode n,
                              PetscErrorType p, const char *mess, void *ctx)
{
  PetscBool printing = ctx ? PETSC_TRUE : PETSC_FALSE;

  if (ctx == (void *)&stepmode) printing = (PetscBool)(printing && !FCErrorIsStepFailure(n));
  if (p == PETSC_ERROR_INITIAL) {
    const char *text = mess;
    if (!text || !text[0]) (void)PetscErrorMessage(n, &text, NULL);
    (void)PetscStrncpy(last, text ? text : "", sizeof(last));
  }
  if (IsUserError(n)) {
    if (p == PETSC_ERROR_INITIAL && printing) {
      PetscMPIInt rank = 0;
      if (comm != MPI_COMM_NULL) MPI_Comm_rank(comm, &rank);
      if (!rank) fprintf(stderr, "fecontact: error: %s\n", mess);
    }
    return n;
  }
  if (!printing) return n;
  return PetscTraceBackErrorHandler(comm, line, fun, file, n, p, mess, ctx);
}

PetscErrorCode FCPushErrorHandler(PetscBool print)
{
  PetscFunctionBegin;
  last[0]  = 0; /* a message from before this handler is not this error's */
  printing = print;
  PetscCall(PetscPushErrorHandler(Handler, print ? (void *)last : NULL));
  PetscFunctionReturn(0);
}

/* Around a call whose step failure the scene redoes: such an error is kept (FCGetLastErrorMessage)
   and not printed; any other is handled as by the handler pushed before (printed or not). Popped
   with PetscPopErrorHandler */
PetscErrorCode FCPushStepErrorHandler(void)
{
  PetscFunctionBegin;
  last[0] = 0;
  PetscCall(PetscPushErrorHandler(Handler, printing ? (void *)&stepmode : NULL));
  PetscFunctionReturn(0);
}

const char *FCGetLastErrorMessage(void)
{
  return last;
}

/* After a call that may fail on some ranks only (a check of one rank's data, a file read on rank 0):
   every rank of comm learns it, so that none goes on alone into the next collective call while another
   has returned. ierr: this rank's result. A rank that failed returns its own error; one that did not
   raises the first failing rank's error (its class and message, which names that rank). Collective. */
PetscErrorCode FCErrorAgree(MPI_Comm comm, PetscErrorCode ierr)
{
  PetscMPIInt rank, size;
  int         first, code;
  char        msg[sizeof(last)];

  PetscFunctionBegin;
  if (comm == MPI_COMM_NULL || MPI_Comm_size(comm, &size) || size == 1 || MPI_Comm_rank(comm, &rank))
    PetscFunctionReturn(ierr);
  first = ierr ? rank : size;
  if (MPI_Allreduce(MPI_IN_PLACE, &first, 1, MPI_INT, MPI_MIN, comm)) PetscFunctionReturn(ierr ? ierr : PETSC_ERR_MPI);
  if (first == size) PetscFunctionReturn(0);
  code = (int)ierr;
  (void)PetscStrncpy(msg, last, sizeof(msg));
  if (rank == first && !msg[0]) {
    const char *text = NULL;
    (void)PetscErrorMessage(ierr, &text, NULL);
    (void)PetscStrncpy(msg, text ? text : "", sizeof(msg));
  }
  if (MPI_Bcast(&code, 1, MPI_INT, first, comm) || MPI_Bcast(msg, sizeof(msg), MPI_CHAR, first, comm))
    PetscFunctionReturn(ierr ? ierr : PETSC_ERR_MPI);
  if (ierr) PetscFunctionReturn(ierr);
  SETERRQ(comm, (PetscErrorCode)code, "%s (on rank %d)", msg, first);
}
