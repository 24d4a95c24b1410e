/* Shared set-up of the libFuzzer targets (tools/fuzz/): PETSc is initialized once, without
   libFuzzer's arguments and without PETSc's signal handler (AddressSanitizer reports crashes);
   every PETSc error comes back as an error code (PetscReturnErrorHandler), never an abort. */
#pragma once

#include <fecontact.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

/* A scratch directory for the files a target writes (mesh inputs, HDF5 outputs) */
static char fz_dir[PETSC_MAX_PATH_LEN];

static void FuzzFail(const char *what, PetscErrorCode ierr)
{
  fprintf(stderr, "fuzz harness: %s failed (PETSc error %d)\n", what, (int)ierr);
  abort();
}

static void FuzzInitPETSc(const char *name)
{
  static char  arg0[64], arg1[] = "-no_signal_handler";
  static char *args[] = {arg0, arg1, NULL};
  static int   nargs  = 2;
  char       **argv   = args;
  const char  *tmp    = getenv("TMPDIR");

  /* the fuzzer classifies crashes of PETSc's gmsh reader itself (fuzz_mesh forks a child): the
     run-time guard of src/mesh/read.c, which turns them into an exit, is off here */
  setenv("FECONTACT_NO_READER_GUARD", "1", 1);

  snprintf(arg0, sizeof(arg0), "%s", name);
  snprintf(fz_dir, sizeof(fz_dir), "%s/%s.%d", tmp && tmp[0] ? tmp : "/tmp", name, (int)getpid());
  if (mkdir(fz_dir, 0700) && access(fz_dir, W_OK)) FuzzFail("mkdir of the scratch directory", 1);
  if (PetscInitialize(&nargs, &argv, NULL, NULL)) FuzzFail("PetscInitialize", 1);
  if (PetscPushErrorHandler(PetscReturnErrorHandler, NULL)) FuzzFail("PetscPushErrorHandler", 1);
  if (FCInitializePackage()) FuzzFail("FCInitializePackage", 1);
}
