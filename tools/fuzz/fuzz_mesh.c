/* libFuzzer target: the mesh reader. The input bytes are written to a scratch .msh file that is
   loaded as the mesh of an FE body (-fz_type fem: DMPlex gmsh reader, then fecontact's checks:
   3D, tetrahedra only, finite coordinates, positive volumes, boundary, mass properties,
   assembly and factorization, one free-motion step), and as the shape of a rigid body
   (-rz_shape mesh). Every error must come back as an error code: a crash, an abort or a
   sanitizer report is a finding.

   PETSc 3.18's own gmsh reader (DMPlexCreateGmsh) trusts the counts, tags and indices of the
   file and crashes on many malformed ones (docs/reliability.md); as libpetsc is not
   instrumented, it may also write out of bounds silently and corrupt this process. So every
   input is first loaded in a forked child: an input on which the child dies inside PETSc's
   reader is not fecontact's finding; it is skipped (and kept in $FUZZ_PETSC_CRASHES when that
   is set), and so is one for which the child takes hundreds of MB (a huge count in the file). */
#include "fuzz_common.h"
#include <sanitizer/common_interface_defs.h>
#include <fcntl.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>

static char mesh[PETSC_MAX_PATH_LEN + 32];
#define FUZZ_CHILD_SECONDS 20

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

/* A child that runs past its time (PETSc's reader loops forever on some files) prints where it
   is, as a sanitizer report would, and dies */
static void ChildTimeout(int sig)
{
  (void)sig;
  fprintf(stderr, "fuzz_mesh: the child ran past %d s, at:\n", FUZZ_CHILD_SECONDS);
  __sanitizer_print_stack_trace();
  _exit(4);
}

/* Both loads of an input: an FE body and a rigid body shaped by the mesh */
static void LoadBoth(void)
{
  char opts[2 * PETSC_MAX_PATH_LEN];

  snprintf(opts, sizeof(opts), "-fz_type fem -fz_dm_plex_filename %s -fz_young 1e5 -fz_density 100", mesh);
  (void)LoadBody("fz", opts, PETSC_TRUE);
  snprintf(opts, sizeof(opts), "-rz_type rigid -rz_shape mesh -rz_dm_plex_filename %s -rz_density 100", mesh);
  (void)LoadBody("rz", opts, PETSC_FALSE);
  if (PetscOptionsClear(NULL)) FuzzFail("PetscOptionsClear", 1);
}

/* A frame of fecontact's own code: its source file is in this repository (" /repo/src/x.c:12:3";
   the fuzz build has debug information), as opposed to a module path ("(/repo/build-fuzz/...+0x")
   of a frame without one: PETSc's, MPI's, libc's or the sanitizer's interceptors (__isoc99_fscanf,
   read ...). Modules alone cannot tell them apart: with libc's debug symbols (libc6-dbg) a libc
   frame names a glibc source file, not "libc.so". */
static int IsOwnFrame(const char *line)
{
  const char *p = strstr(line, " " FC_SOURCE_DIR);
  return p && !strstr(line, "ChildTimeout");
}

/* The child's sanitizer report (a crash, or the stack of ChildTimeout) shows PETSc's gmsh reader
   at fault: a frame of DMPlexCreateGmsh... in libpetsc, with no frame of fecontact's own code
   above it */
static int CrashInPETScReader(const char *report)
{
  FILE *fp = fopen(report, "r");
  char  line[4096];
  int   ok = 0;

  if (!fp) return 0;
  while (fgets(line, sizeof(line), fp)) {
    const char *p = line;
    while (*p == ' ') p++;
    if (*p != '#') continue;
    if (IsOwnFrame(line)) break;
    if (strstr(line, "Gmsh") && strstr(line, "libpetsc")) {
      ok = 1;
      break;
    }
  }
  fclose(fp);
  return ok;
}

/* Runs both loads first in a forked child, whose heap is the same as this process's, so that it
   meets what this process would: 1 when PETSc's reader crashes there or runs past 20 s (a
   stack through DMPlexCreateGmsh with only PETSc above it), or needs more than 768 MB
   beyond this process's own memory (a count in the file that it trusts: the run would end on
   libFuzzer's memory limit); 0 when the child finished. A child that dies anywhere else (in
   fecontact) returns 0 too: the loads then run here and the crash is libFuzzer's to report. */
static int ReaderCrashes(void)
{
  int           status;
  struct rusage self, child;
  pid_t         pid;
  char          report[PETSC_MAX_PATH_LEN + 32];

  snprintf(report, sizeof(report), "%s/child-report.txt", fz_dir);
  getrusage(RUSAGE_SELF, &self);
  pid = fork();
  if (pid < 0) FuzzFail("fork", 1);
  if (pid == 0) { /* a sanitizer report goes to the report file, no crash file from libFuzzer */
    int fd = open(report, O_WRONLY | O_CREAT | O_TRUNC, 0600);
    if (fd >= 0) dup2(fd, 2);
    signal(SIGABRT, SIG_DFL);
    signal(SIGILL, SIG_DFL);
    signal(SIGALRM, ChildTimeout);
    alarm(FUZZ_CHILD_SECONDS);
    __sanitizer_set_death_callback(ChildDeath);
    LoadBoth();
    _exit(0);
  }
  if (wait4(pid, &status, 0, &child) != pid) FuzzFail("wait4", 1);
  if (getenv("FUZZ_DEBUG"))
    fprintf(stderr, "fuzz_mesh: child status %d, max rss %ld kB (this process %ld kB)\n", status, child.ru_maxrss,
            self.ru_maxrss);
  if (child.ru_maxrss > self.ru_maxrss + 768 * 1024) return 1; /* kB */
  if (WIFEXITED(status) && WEXITSTATUS(status) == 0) return 0;
  return CrashInPETScReader(report);
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

  if (!fp || fwrite(data, 1, size, fp) != size || fclose(fp)) FuzzFail("writing the mesh file", 1);
  if (ReaderCrashes()) {
    KeepPETScCrash(data, size);
    return -1;
  }
  LoadBoth();
  return 0;
}
