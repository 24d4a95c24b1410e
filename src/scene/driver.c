/* The executable (src/main.c is main over it): PetscInitialize, a scene from the options,
   FCSceneRun, and the exit status of docs/options.md (FCExitStatus, src/util/errors.c). */
#include "../fcimpl.h"
#include <unistd.h>

static const char help[] = "fecontact: deformable and rigid bodies in frictional contact (Zeng & Courtecuisse 2023).\n"
                           "Usage: mpirun -n N fecontact -options_file input/<scene>.opts [-option value ...]\n"
                           "Options are documented in docs/options.md; -help lists them with their values.\n";

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

int FCMain(int argc, char **argv)
{
  PetscErrorCode ierr;
  int            status;

  if (FCSignalsBlock()) return 1; /* before MPI starts its threads (src/util/signals.c) */
  PetscCall(PetscInitialize(&argc, &argv, NULL, help));
  PetscCall(FCPushErrorHandler(PETSC_TRUE));
  ierr = RunScene();
  /* input errors, a diverging run (NaN/Inf state, failed factorization, contact solver: all
     decided collectively), a failed write of the output (collective) and SIGINT/SIGTERM are
     detected on every rank alike: finish cleanly with exit status 1, 2, 3 or 128 + signal; anything else may have
     happened on one rank only: abort them all */
  status = ierr ? FCExitStatus(ierr) : 0;
  if (status == 3 && FCOutputFileLeftOpen()) {
    /* a failed write inside HDF5: the file stays open as its last flush left it (HDF5 1.10 cannot
       close a file whose metadata it cannot write, and its clean-up inside MPI_Finalize would crash
       on it: src/io/output.c, FCOutputDestroy), so the ranks meet and leave without that clean-up */
    (void)MPI_Barrier(PETSC_COMM_WORLD);
    fflush(stdout);
    fflush(stderr);
    _exit(3);
  }
  if (status) {
    (void)PetscFinalize();
    return status;
  }
  if (ierr) PETSCABORT(PETSC_COMM_WORLD, ierr);
  PetscCall(PetscFinalize());
  return 0;
}
