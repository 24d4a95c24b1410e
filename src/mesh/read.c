/* Reading a body's mesh file: the checks before PETSc's gmsh reader sees the file (it exists, is a
   regular file, and has no unterminated $Comments section, on which the reader would not return),
   and a guard that turns a memory fault inside the reader into an error naming the file. The mesh
   is read on rank 0 and not distributed (mesh.c distributes it with the body's partitioner). */
#include "../fcimpl.h"
#include <sys/stat.h>
#include <signal.h>
#include <unistd.h>

/* PETSc 3.18's gmsh reader trusts a file's counts and indices and can crash on a malformed one
   (tools/fuzz/petsc-gmsh-crashes, docs/reliability.md). While it reads, a memory fault ends the
   run with a line naming the file instead of a crash report: the message is prepared before, and
   the handler only writes it and exits (async-signal-safe). */
static char             reader_message[2 * PETSC_MAX_PATH_LEN];
static size_t           reader_message_len;
static struct sigaction reader_saved[3];
static const int        reader_signals[3] = {SIGSEGV, SIGBUS, SIGFPE};

static void ReaderFault(int sig)
{
  (void)sig;
  if (write(STDERR_FILENO, reader_message, reader_message_len) < 0) _exit(1);
  _exit(1);
}

static void ReaderGuard(PetscBool on, const char fname[], const char prefix[], const char bodyname[])
{
  if (getenv("FECONTACT_NO_READER_GUARD")) return; /* the fuzzers watch the reader's crashes themselves */
  if (on) {
    struct sigaction sa;
    snprintf(reader_message, sizeof(reader_message),
             "fecontact: error: cannot read mesh file '%s' (-%sdm_plex_filename) of body '%s': PETSc's gmsh reader "
             "hit a memory fault on it, the file is malformed (open it in gmsh to see where)\n",
             fname, prefix, bodyname);
    reader_message_len = strlen(reader_message);
    memset(&sa, 0, sizeof(sa));
    sa.sa_handler = ReaderFault;
    sigemptyset(&sa.sa_mask);
    for (int i = 0; i < 3; i++) sigaction(reader_signals[i], &sa, &reader_saved[i]);
  } else
    for (int i = 0; i < 3; i++) sigaction(reader_signals[i], &reader_saved[i], NULL);
}

/* PETSc 3.18's gmsh reader loops forever, at the end of the file, on a $Comments section that
   has no $EndComments (its GmshReadSection; tools/fuzz/petsc-gmsh-crashes/v22_comments_unterminated.msh):
   1 when the file has a "$Comments" with no "$EndComments" after it. One pass over the bytes; '$'
   starts both words and occurs nowhere else in them, so a mismatch restarts at '$' or at 0. */
static int UnterminatedComments(FILE *fp)
{
  static const char open[] = "$Comments", close[] = "$EndComments";
  char              buf[1 << 16];
  size_t            n, io = 0, ic = 0;
  int               inside = 0;

  while ((n = fread(buf, 1, sizeof(buf), fp)) > 0) {
    for (size_t k = 0; k < n; k++) {
      const char c = buf[k];
      io           = c == open[io] ? io + 1 : (c == '$');
      ic           = c == close[ic] ? ic + 1 : (c == '$');
      if (io == sizeof(open) - 1) inside = 1, io = 0;
      if (ic == sizeof(close) - 1) inside = 0, ic = 0;
    }
  }
  return inside;
}

/* On several ranks PETSc's reader reads the file on rank 0 while the other ranks wait for what it
   sends them: a file it fails on (truncated, malformed) would leave them waiting for ever. Rank 0
   first reads it alone (not interpolated), and every rank learns the outcome: a file the reader
   rejects is then an input error on every rank, naming it. On 1 rank nothing waits: no trial read. */
static PetscErrorCode TrialRead(MPI_Comm comm, const char fname[], const char prefix[], const char bodyname[])
{
  PetscMPIInt rank, size;
  int         ierr     = 0;
  char        msg[512] = "";

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_size(comm, &size));
  if (size == 1) PetscFunctionReturn(0);
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  if (!rank) {
    DM trial = NULL;
    ReaderGuard(PETSC_TRUE, fname, prefix, bodyname);
    ierr = (int)DMPlexCreateGmshFromFile(PETSC_COMM_SELF, fname, PETSC_FALSE, &trial);
    ReaderGuard(PETSC_FALSE, fname, prefix, bodyname);
    if (ierr) (void)PetscStrncpy(msg, FCGetLastErrorMessage(), sizeof(msg));
    (void)DMDestroy(&trial);
  }
  PetscCallMPI(MPI_Bcast(&ierr, 1, MPI_INT, 0, comm));
  PetscCallMPI(MPI_Bcast(msg, sizeof(msg), MPI_CHAR, 0, comm));
  PetscCheck(!ierr, comm, PETSC_ERR_USER_INPUT,
             "Cannot read mesh file '%s' (-%sdm_plex_filename) of body '%s': not a valid or complete gmsh file "
             "(PETSc's gmsh reader: %s)",
             fname, prefix, bodyname, msg[0] ? msg : "no message");
  PetscFunctionReturn(0);
}

PetscErrorCode FCMeshRead(MPI_Comm comm, const char prefix[], const char bodyname[], FCMesh *mesh,
                          char fname[PETSC_MAX_PATH_LEN], PetscBool *distribute)
{
  PetscBool   set;
  PetscMPIInt rank;
  PetscInt    readable = 1, comments = 0;

  PetscFunctionBegin;
  *distribute = PETSC_TRUE;
  PetscCall(PetscOptionsGetString(NULL, prefix, "-dm_plex_filename", fname, PETSC_MAX_PATH_LEN, &set));
  PetscCheck(set, comm, PETSC_ERR_USER_INPUT, "Body '%s' needs a mesh: -%sdm_plex_filename <file.msh>", bodyname,
             prefix);
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  if (rank == 0) {
    struct stat st;
    FILE       *fp = NULL;
    if (stat(fname, &st) || !S_ISREG(st.st_mode) || !(fp = fopen(fname, "rb"))) readable = 0;
    if (fp) {
      comments = UnterminatedComments(fp);
      fclose(fp);
    }
  }
  {
    PetscInt flags[2] = {readable, comments};
    PetscCallMPI(MPI_Bcast(flags, 2, MPIU_INT, 0, comm));
    readable = flags[0];
    comments = flags[1];
  }
  PetscCheck(readable, comm, PETSC_ERR_USER_INPUT,
             "Cannot open mesh file '%s' given by -%sdm_plex_filename for body '%s'", fname, prefix, bodyname);
  PetscCheck(!comments, comm, PETSC_ERR_USER_INPUT,
             "Cannot read mesh file '%s' (-%sdm_plex_filename) of body '%s': a $Comments section has no $EndComments "
             "(the file is truncated or malformed; PETSc's gmsh reader would not return on it)",
             fname, prefix, bodyname);
  { /* an input: no output may overwrite it (src/util/inputs.c) */
    char what[256];
    PetscCall(PetscSNPrintf(what, sizeof(what), "mesh of body '%s' (-%sdm_plex_filename)", bodyname, prefix));
    PetscCall(FCInputsAdd(fname, what));
  }

  PetscCall(DMCreate(comm, &mesh->dm));
  PetscCall(DMSetType(mesh->dm, DMPLEX));
  PetscCall(PetscObjectSetName((PetscObject)mesh->dm, bodyname));
  PetscCall(DMSetOptionsPrefix(mesh->dm, prefix));
  {
    /* reads (on rank 0), interpolates, refines. Not distributed here: the reader replaces the DM's data, and
       with it the partitioner, by a default one that never sees the body's options; the mesh is
       distributed below, by a partitioner that does (-<body>_dm_distribute, read here, is
       restored after the read) */
    PetscErrorCode ierr;
    char           opt[FC_MAX_NAME + 32];
    PetscBool      regions;
    PetscCall(PetscOptionsGetBool(NULL, prefix, "-dm_distribute", distribute, NULL));
    /* one label per physical group, named after it (regions, src/mesh/region.c) */
    /* (PETSc 3.18's reader reads them without the DM's prefix; mark_vertices makes the labels of
       Physical Point groups, and marks the vertices of the others too) */
    PetscCall(PetscOptionsHasName(NULL, NULL, "-dm_plex_gmsh_use_regions", &regions));
    if (!regions) PetscCall(PetscOptionsSetValue(NULL, "-dm_plex_gmsh_use_regions", "1"));
    PetscCall(PetscOptionsHasName(NULL, NULL, "-dm_plex_gmsh_mark_vertices", &regions));
    if (!regions) PetscCall(PetscOptionsSetValue(NULL, "-dm_plex_gmsh_mark_vertices", "1"));
    PetscCall(PetscSNPrintf(opt, sizeof(opt), "-%sdm_distribute", prefix));
    PetscCall(PetscOptionsSetValue(NULL, opt, "0"));
    PetscCall(TrialRead(comm, fname, prefix, bodyname));
    ReaderGuard(PETSC_TRUE, fname, prefix, bodyname);
    ierr = DMSetFromOptions(mesh->dm);
    ReaderGuard(PETSC_FALSE, fname, prefix, bodyname);
    PetscCall(PetscOptionsSetValue(NULL, opt, *distribute ? "1" : "0"));
    /* an input error naming the file and the option, with the reader's message (on several ranks the
       trial read has caught such a file on every rank already) */
    PetscCheck(!ierr, comm, PETSC_ERR_USER_INPUT,
               "Cannot read mesh file '%s' (-%sdm_plex_filename) of body '%s': not a valid or complete gmsh file "
               "(PETSc's gmsh reader: %s)",
               fname, prefix, bodyname, FCGetLastErrorMessage()[0] ? FCGetLastErrorMessage() : "no message");
  }
  PetscFunctionReturn(0);
}
