/* The files a run reads (options files, meshes, the restart file), recorded by identity (device
   and inode, taken when the file is read), and the check that no file the run writes is one of
   them: a hard link, a symbolic link or another spelling of an input's path is the same file, and
   creating the output would truncate it. The list is process-wide: FCSceneCreate empties it, the
   readers add to it (src/mesh/mesh.c, src/scene/scene.c), the writers check against it
   (src/io/output.c) before they create anything. */
#include "../fcimpl.h"
#include <sys/stat.h>

typedef struct {
  char  path[PETSC_MAX_PATH_LEN], what[256];
  dev_t dev;
  ino_t ino;
} FCInput;

static FCInput *inputs  = NULL;
static PetscInt ninputs = 0, maxinputs = 0;

PetscErrorCode FCInputsReset(void)
{
  PetscFunctionBegin;
  PetscCall(PetscFree(inputs));
  ninputs = maxinputs = 0;
  PetscFunctionReturn(0);
}

/* Records `path` (what: how the run came to read it, for messages) if it exists; a file met twice
   is kept once */
PetscErrorCode FCInputsAdd(const char path[], const char what[])
{
  struct stat st;

  PetscFunctionBegin;
  if (!path || !path[0] || stat(path, &st)) PetscFunctionReturn(0);
  for (PetscInt i = 0; i < ninputs; i++)
    if (inputs[i].dev == st.st_dev && inputs[i].ino == st.st_ino) PetscFunctionReturn(0);
  if (ninputs == maxinputs) {
    FCInput *tmp;
    maxinputs = PetscMax(16, 2 * maxinputs);
    PetscCall(PetscMalloc1(maxinputs, &tmp));
    if (ninputs) PetscCall(PetscArraycpy(tmp, inputs, ninputs));
    PetscCall(PetscFree(inputs));
    inputs = tmp;
  }
  PetscCall(PetscStrncpy(inputs[ninputs].path, path, sizeof(inputs[ninputs].path)));
  PetscCall(PetscStrncpy(inputs[ninputs].what, what, sizeof(inputs[ninputs].what)));
  inputs[ninputs].dev = st.st_dev;
  inputs[ninputs].ino = st.st_ino;
  ninputs++;
  PetscFunctionReturn(0);
}

/* An options file and the options files it names (-options_file inside it), to a depth of 8 */
static PetscErrorCode AddOptionsFile(const char path[], int depth)
{
  FILE *fp;
  char  word[PETSC_MAX_PATH_LEN], prev[32] = "";

  PetscFunctionBegin;
  PetscCall(FCInputsAdd(path, "options file (-options_file)"));
  if (depth >= 8 || !(fp = fopen(path, "r"))) PetscFunctionReturn(0);
  while (fscanf(fp, "%4095s", word) == 1) {
    if (!strcmp(prev, "-options_file")) PetscCall(AddOptionsFile(word, depth + 1));
    PetscCall(PetscStrncpy(prev, word, sizeof(prev)));
  }
  fclose(fp);
  PetscFunctionReturn(0);
}

/* The options files PETSc read: -options_file on the command line and in PETSC_OPTIONS (PETSc
   does not keep that option in its database), and the petscrc files it reads by default */
PetscErrorCode FCInputsAddOptionsFiles(void)
{
  int         argc = 0;
  char      **argv = NULL;
  const char *env = getenv("PETSC_OPTIONS"), *home = getenv("HOME");
  char        path[PETSC_MAX_PATH_LEN];

  PetscFunctionBegin;
  if (PetscGetArgs(&argc, &argv) == 0 && argv)
    for (int i = 1; i + 1 < argc; i++)
      if (!strcmp(argv[i], "-options_file") || !strcmp(argv[i], "-options_file_yaml"))
        PetscCall(AddOptionsFile(argv[i + 1], 0));
  if (env) {
    char     *copy, *tok, *save = NULL;
    PetscBool next = PETSC_FALSE;
    PetscCall(PetscStrallocpy(env, &copy));
    for (tok = strtok_r(copy, " \t\n", &save); tok; tok = strtok_r(NULL, " \t\n", &save)) {
      if (next) PetscCall(AddOptionsFile(tok, 0));
      next = !strcmp(tok, "-options_file") ? PETSC_TRUE : PETSC_FALSE;
    }
    PetscCall(PetscFree(copy));
  }
  PetscCall(FCInputsAdd("petscrc", "options file (petscrc, read by PETSc by default)"));
  PetscCall(FCInputsAdd(".petscrc", "options file (.petscrc, read by PETSc by default)"));
  if (home) {
    PetscCall(PetscSNPrintf(path, sizeof(path), "%s/.petscrc", home));
    PetscCall(FCInputsAdd(path, "options file (~/.petscrc, read by PETSc by default)"));
  }
  PetscFunctionReturn(0);
}

/* Refuses (collectively) to write `path` when it is one of the inputs or exists as a FIFO, a
   directory or a socket; what: the output, as the
   message names it (e.g. "-output_file") */
PetscErrorCode FCInputsCheckOutput(MPI_Comm comm, const char path[], const char what[])
{
  struct stat st;
  PetscInt    clash = -1, special = 0;

  PetscFunctionBegin;
  if (!stat(path, &st)) {
    for (PetscInt i = 0; i < ninputs && clash < 0; i++)
      if (inputs[i].dev == st.st_dev && inputs[i].ino == st.st_ino) clash = i;
    /* a FIFO would block the writer until someone reads it; a device is written (/dev/full fails
       there, exit status 3) */
    special = S_ISFIFO(st.st_mode) || S_ISDIR(st.st_mode) || S_ISSOCK(st.st_mode) ? 1 : 0;
  }
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &clash, 1, MPIU_INT, MPI_MAX, comm));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &special, 1, MPIU_INT, MPI_MAX, comm));
  PetscCheck(!special, comm, PETSC_ERR_USER_INPUT,
             "%s '%s' exists and is a FIFO, a directory or a socket: the output is written to a regular file, "
             "created or overwritten",
             what, path);
  PetscCheck(clash < 0, comm, PETSC_ERR_USER_INPUT,
             "%s '%s' is the same file as '%s', the %s this run reads (same device and inode: a hard or symbolic "
             "link counts); writing it would destroy the input: choose another output file name",
             what, path, inputs[clash].path, inputs[clash].what);
  PetscFunctionReturn(0);
}

/* The output files of this process' live scenes, by identity, each with the output that writes it:
   a second scene may not write a file another one is writing (two writers of one file leave a file
   that neither wrote, and that reads without a warning). Unlike the inputs, the list outlives
   FCSceneCreate: an entry is removed when its output is destroyed. */
typedef struct {
  const void *owner;
  char        path[PETSC_MAX_PATH_LEN];
  dev_t       dev;
  ino_t       ino;
} FCLiveOutput;

static FCLiveOutput *outputs  = NULL;
static PetscInt      noutputs = 0, maxoutputs = 0;

/* Refuses (collectively) to write `path` when a live output of this process writes it */
PetscErrorCode FCOutputsCheckLive(MPI_Comm comm, const char path[])
{
  struct stat st;
  PetscInt    clash = -1;

  PetscFunctionBegin;
  if (!stat(path, &st))
    for (PetscInt i = 0; i < noutputs && clash < 0; i++)
      if (outputs[i].dev == st.st_dev && outputs[i].ino == st.st_ino) clash = i;
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &clash, 1, MPIU_INT, MPI_MAX, comm));
  PetscCheck(clash < 0, comm, PETSC_ERR_USER_INPUT,
             "-output_file '%s' is the file '%s' that another live scene of this program writes (same device and "
             "inode): destroy that scene first, or choose another output file name",
             path, outputs[clash].path);
  PetscFunctionReturn(0);
}

/* Records `path`, just created by `owner`, as a live output (nothing if it cannot be found) */
PetscErrorCode FCOutputsAddLive(const void *owner, const char path[])
{
  struct stat st;

  PetscFunctionBegin;
  if (stat(path, &st)) PetscFunctionReturn(0);
  if (noutputs == maxoutputs) {
    FCLiveOutput *tmp;
    maxoutputs = PetscMax(4, 2 * maxoutputs);
    PetscCall(PetscMalloc1(maxoutputs, &tmp));
    if (noutputs) PetscCall(PetscArraycpy(tmp, outputs, noutputs));
    PetscCall(PetscFree(outputs));
    outputs = tmp;
  }
  outputs[noutputs].owner = owner;
  PetscCall(PetscStrncpy(outputs[noutputs].path, path, sizeof(outputs[noutputs].path)));
  outputs[noutputs].dev = st.st_dev;
  outputs[noutputs].ino = st.st_ino;
  noutputs++;
  PetscFunctionReturn(0);
}

/* Forgets the live output of `owner` (its file closed); the list freed when it is empty */
PetscErrorCode FCOutputsRemoveLive(const void *owner)
{
  PetscFunctionBegin;
  for (PetscInt i = 0; i < noutputs; i++)
    if (outputs[i].owner == owner) outputs[i--] = outputs[--noutputs];
  if (!noutputs) {
    PetscCall(PetscFree(outputs));
    maxoutputs = 0;
  }
  PetscFunctionReturn(0);
}
