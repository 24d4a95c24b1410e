/* libFuzzer target: the mesh reader. The input bytes are written to a scratch .msh file that is
   loaded as the mesh of an FE body (-fz_type fem: DMPlex gmsh reader, then fecontact's checks:
   3D, tetrahedra only, finite coordinates, positive volumes, boundary, mass properties,
   assembly and factorization, one free-motion step), and as the shape of a rigid body
   (-rz_shape mesh). Every error must come back as an error code: a crash, an abort or a
   sanitizer report is a finding.

   PETSc 3.18's own gmsh reader (DMPlexCreateGmsh) trusts the counts, tags and indices of the
   file and crashes on many malformed ones (docs/reliability.md); as libpetsc is not
   instrumented, it may also write out of bounds silently and corrupt this process. So every
   input is first read by PETSc alone in a forked child: an input that kills the child is not
   fecontact's finding; it is skipped (and kept in $FUZZ_PETSC_CRASHES when that is set). */
#include "fuzz_common.h"
#include <sanitizer/common_interface_defs.h>
#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>

static char mesh[PETSC_MAX_PATH_LEN + 32];

int LLVMFuzzerInitialize(int *argc, char ***argv)
{
  (void)argc;
  (void)argv;
  FuzzInitPETSc("fuzz_mesh");
  snprintf(mesh, sizeof(mesh), "%s/input.msh", fz_dir);
  return 0;
}

static PetscErrorCode LoadBody(const char name[], const char opts[], PetscBool step)
{
  FCBody         body = NULL;
  PetscErrorCode ierr;
  FCEnergy       E;

  PetscFunctionBegin;
  PetscCall(PetscOptionsClear(NULL));
  PetscCall(PetscOptionsInsertString(NULL, opts));
  ierr = FCBodyCreate(PETSC_COMM_WORLD, name, &body);
  if (!ierr) ierr = FCBodySetFromOptions(body);
  if (!ierr) ierr = FCBodySetUp(body);
  if (!ierr && step) ierr = FCBodyComputeFreeMotion(body, 0.0);
  if (!ierr && step) ierr = FCBodyIntegrate(body, 0.0);
  if (!ierr) ierr = FCBodyGetEnergy(body, &E);
  PetscCall(FCBodyDestroy(&body));
  PetscFunctionReturn(ierr);
}

static void ChildDeath(void)
{
  _exit(3);
}

/* 1 when PETSc's reader crashes (or is killed) on the mesh file, 0 when it reads it or returns
   an error */
static int ReaderCrashes(void)
{
  int   status;
  pid_t pid = fork();

  if (pid < 0) FuzzFail("fork", 1);
  if (pid == 0) { /* no crash report, no crash file from libFuzzer's handlers: just die */
    const int sigs[]  = {SIGSEGV, SIGBUS, SIGABRT, SIGFPE, SIGILL};
    DM        dm      = NULL;
    int       devnull = open("/dev/null", O_WRONLY);
    if (devnull >= 0) dup2(devnull, 2);
    for (size_t i = 0; i < sizeof(sigs) / sizeof(sigs[0]); i++) signal(sigs[i], SIG_DFL);
    __sanitizer_set_death_callback(ChildDeath);
    (void)DMPlexCreateFromFile(PETSC_COMM_SELF, mesh, "fuzz", PETSC_TRUE, &dm);
    _exit(0);
  }
  if (waitpid(pid, &status, 0) != pid) FuzzFail("waitpid", 1);
  return !(WIFEXITED(status) && WEXITSTATUS(status) == 0);
}

static void KeepPETScCrash(const uint8_t *data, size_t size)
{
  const char *dir = getenv("FUZZ_PETSC_CRASHES");
  char        path[PETSC_MAX_PATH_LEN];
  uint64_t    h = 1469598103934665603ULL; /* FNV-1a of the input names it */
  FILE       *fp;

  if (!dir || !dir[0]) return;
  for (size_t i = 0; i < size; i++) h = (h ^ data[i]) * 1099511628211ULL;
  snprintf(path, sizeof(path), "%s/petsc-reader-%016llx", dir, (unsigned long long)h);
  if ((fp = fopen(path, "wb"))) {
    fwrite(data, 1, size, fp);
    fclose(fp);
  }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
  FILE *fp = fopen(mesh, "wb");
  char  opts[2 * PETSC_MAX_PATH_LEN];

  if (!fp || fwrite(data, 1, size, fp) != size || fclose(fp)) FuzzFail("writing the mesh file", 1);
  if (ReaderCrashes()) {
    KeepPETScCrash(data, size);
    return -1;
  }
  snprintf(opts, sizeof(opts), "-fz_type fem -fz_dm_plex_filename %s -fz_young 1e5 -fz_density 100", mesh);
  (void)LoadBody("fz", opts, PETSC_TRUE);
  snprintf(opts, sizeof(opts), "-rz_type rigid -rz_shape mesh -rz_dm_plex_filename %s -rz_density 100", mesh);
  (void)LoadBody("rz", opts, PETSC_FALSE);
  if (PetscOptionsClear(NULL)) FuzzFail("PetscOptionsClear", 1);
  return 0;
}
