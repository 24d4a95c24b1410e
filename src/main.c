/* fecontact: run a scene described by PETSc options.
     mpirun -n N fecontact -options_file input/<scene>.opts [overrides]          */
#include "fcimpl.h"
#include <unistd.h>

static const char help[] = "fecontact: deformable and rigid bodies in frictional contact (Zeng & Courtecuisse 2023).\n"
                           "Usage: mpirun -n N fecontact -options_file input/<scene>.opts [-option value ...]\n"
                           "Options are documented in docs/options.md; -help lists them with their values.\n";

/* Input errors are the user's, not the code's: one clear line, no traceback. Everything else
   goes to PETSc's traceback handler. */
static PetscErrorCode UserErrorHandler(MPI_Comm comm, int line, const char *fun, const char *file, PetscErrorCode n,
                                       PetscErrorType p, const char *mess, void *ctx)
{
  if (n == PETSC_ERR_USER_INPUT || n == PETSC_ERR_FILE_OPEN || n == PETSC_ERR_FILE_WRITE ||
      n == PETSC_ERR_ARG_UNKNOWN_TYPE || n == PETSC_ERR_SIG || n == PETSC_ERR_FP || n == PETSC_ERR_CONV_FAILED ||
      n == PETSC_ERR_MEM) {
    if (p == PETSC_ERROR_INITIAL) {
      PetscMPIInt rank = 0;
      if (comm != MPI_COMM_NULL) MPI_Comm_rank(comm, &rank);
      if (!rank) fprintf(stderr, "fecontact: error: %s\n", mess);
    }
    return n;
  }
  return PetscTraceBackErrorHandler(comm, line, fun, file, n, p, mess, ctx);
}

static PetscErrorCode RunScene(void)
{
  FCScene scene;

  PetscFunctionBegin;
  PetscCall(FCSceneCreate(PETSC_COMM_WORLD, &scene));
  PetscCall(FCSceneSetFromOptions(scene));
  PetscCall(FCSceneRun(scene));
  PetscCall(FCSceneDestroy(&scene));
  PetscFunctionReturn(0);
}

int main(int argc, char **argv)
{
  PetscErrorCode ierr;

  PetscCall(PetscInitialize(&argc, &argv, NULL, help));
  PetscCall(PetscPushErrorHandler(UserErrorHandler, NULL));
  ierr = RunScene();
  /* input errors, a diverging run (NaN/Inf state, failed factorization, contact solver: all
     decided collectively), a failed write of the output (collective) and SIGINT/SIGTERM are
     detected on every rank alike: finish cleanly with exit status 1, 2, 3 or 128 + signal; anything else may have
     happened on one rank only: abort them all */
  if (ierr == PETSC_ERR_USER_INPUT || ierr == PETSC_ERR_ARG_UNKNOWN_TYPE) {
    (void)PetscFinalize();
    return 1;
  }
  if (ierr == PETSC_ERR_FP || ierr == PETSC_ERR_CONV_FAILED || ierr == PETSC_ERR_MEM) {
    (void)PetscFinalize();
    return 2;
  }
  if (ierr == PETSC_ERR_FILE_WRITE) { /* a failed write of the output, made collective (src/io/h5util.c) */
    if (FCOutputFileLeftOpen()) {
      /* it failed inside HDF5: the file stays open as its last flush left it (HDF5 1.10 cannot
         close a file whose metadata it cannot write, and its clean-up inside MPI_Finalize would
         crash on it: src/io/output.c, FCOutputDestroy), so the ranks meet and leave without
         that clean-up */
      (void)MPI_Barrier(PETSC_COMM_WORLD);
      fflush(stdout);
      fflush(stderr);
      _exit(3);
    }
    (void)PetscFinalize();
    return 3;
  }
  if (ierr == PETSC_ERR_SIG) {
    int sig = FCSignalsCaught();
    (void)PetscFinalize();
    return 128 + sig;
  }
  if (ierr) PETSCABORT(PETSC_COMM_WORLD, ierr);
  PetscCall(PetscFinalize());
  return 0;
}
