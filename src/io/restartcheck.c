/* A restart continues the scene that its file holds (docs/options.md, -restart): the options that
   define that scene must be those of the run that wrote the file (its "options" attribute). They
   are every option of a body (-<name>_...), -gravity and -time_integration, except those that
   say how the scene is solved or written (the body's solver, partition, factorization schedule,
   checks) and the tables of time (a trajectory, a prescribed displacement, a load), which may
   continue with new rows: the new table's values from the restart time on are used. A change is an
   error naming the option, both values and the file. */
#include "ioimpl.h"

/* Suffixes (after "<name>_") of body options that may differ at a restart */
static const char *Free[] = {"ksp_",     "pc_",           "mat_",          "petscpartitioner_", "partition_file",
                             "dm_view",  "dm_plex_check", "dm_distribute", "refactor_",         "factorization",
                             "assembly", "inverted",      "trajectory",    "displacement",      "force",
                             "traction", "pressure",      "compliance_",   "dm_mat_type",       "dm_vec_type",
                             "snes_"};

/* The value of key in an options string "-a v -b -c w" (NULL: absent; "" : no value) */
static const char *Find(char *const keys[], char *const vals[], PetscInt n, const char key[])
{
  for (PetscInt i = 0; i < n; i++)
    if (!strcmp(keys[i], key)) return vals[i];
  return NULL;
}

/* Splits an options string in place into keys (without '-') and values */
static void Split(char *s, char *keys[], char *vals[], PetscInt max, PetscInt *n)
{
  char *tok, *save = NULL;
  *n = 0;
  for (tok = strtok_r(s, " ", &save); tok; tok = strtok_r(NULL, " ", &save)) {
    PetscBool key =
        (PetscBool)(tok[0] == '-' && ((tok[1] >= 'a' && tok[1] <= 'z') || (tok[1] >= 'A' && tok[1] <= 'Z')));
    if (key && *n < max) {
      keys[*n] = tok + 1;
      vals[*n] = tok + strlen(tok); /* "" until a value follows */
      (*n)++;
    } else if (!key && *n) {
      if (*vals[*n - 1])
        tok[-1] = ' '; /* a value of several words: join them back */
      else
        vals[*n - 1] = tok;
    }
  }
}

static PetscBool Defines(const char key[], PetscInt nbodies, FCBody bodies[])
{
  if (!strcmp(key, "gravity") || !strcmp(key, "time_integration")) return PETSC_TRUE;
  for (PetscInt i = 0; i < nbodies; i++) {
    const char *name;
    size_t      l;
    if (FCBodyGetName(bodies[i], &name)) return PETSC_FALSE;
    l = strlen(name);
    if (!strncmp(key, name, l) && key[l] == '_') {
      for (size_t k = 0; k < sizeof(Free) / sizeof(Free[0]); k++)
        if (!strncmp(key + l + 1, Free[k], strlen(Free[k]))) return PETSC_FALSE;
      return PETSC_TRUE;
    }
  }
  return PETSC_FALSE;
}

PetscErrorCode FCRestartCheckScene(MPI_Comm comm, const char file[], PetscInt nbodies, FCBody bodies[])
{
  char       *old = NULL, *now, *ko[1024], *vo[1024], *kn[1024], *vn[1024], msg[1024] = "";
  PetscInt    no, nn;
  long        len = 0;
  PetscMPIInt rank;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  if (!rank) { /* the file's options (FCRestartLoad has checked that it opens) */
    hid_t f = H5Fopen(file, H5F_ACC_RDONLY, H5P_DEFAULT), a = -1, t;
    if (f >= 0 && H5Aexists(f, "options") > 0 && (a = H5Aopen(f, "options", H5P_DEFAULT)) >= 0) {
      t   = H5Aget_type(a);
      len = (long)H5Tget_size(t);
      PetscCall(PetscCalloc1(len + 1, &old));
      if (H5Aread(a, t, old) < 0) len = 0;
      H5Tclose(t);
    }
    if (a >= 0) H5Aclose(a);
    if (f >= 0) H5Fclose(f);
  }
  PetscCallMPI(MPI_Bcast(&len, 1, MPI_LONG, 0, comm));
  if (!len) { /* a file without its options: nothing to compare */
    PetscCall(PetscFree(old));
    PetscFunctionReturn(0);
  }
  if (rank) PetscCall(PetscCalloc1(len + 1, &old));
  PetscCallMPI(MPI_Bcast(old, (PetscMPIInt)len + 1, MPI_CHAR, 0, comm));
  PetscCall(PetscOptionsGetAll(NULL, &now));
  Split(old, ko, vo, 1024, &no);
  Split(now, kn, vn, 1024, &nn);
  for (int pass = 0; pass < 2 && !msg[0]; pass++) { /* this run's options, then the file's */
    char *const *k = pass ? ko : kn, *const *v = pass ? vo : vn;
    PetscInt     n = pass ? no : nn;
    for (PetscInt i = 0; i < n && !msg[0]; i++) {
      const char *other = pass ? Find(kn, vn, nn, k[i]) : Find(ko, vo, no, k[i]);
      if (!Defines(k[i], nbodies, bodies) || (other && !strcmp(other, v[i]))) continue;
      if (!other)
        PetscCall(PetscSNPrintf(msg, sizeof(msg), "option -%s is %s in %s", k[i],
                                pass ? "not given here but given" : "given here but not", "the run that wrote it"));
      else
        PetscCall(PetscSNPrintf(msg, sizeof(msg), "option -%s is '%s' here but '%s' in the run that wrote it", k[i],
                                v[i], other));
    }
  }
  PetscCall(PetscFree(old));
  PetscCall(PetscFree(now));
  PetscCheck(
      !msg[0], comm, PETSC_ERR_USER_INPUT,
      "-restart %s: %s. A restart continues the scene that the file holds (bodies, meshes, materials, placement, "
      "velocities, constraints); its solver options and tables of time may change (docs/options.md)",
      file, msg);
  PetscFunctionReturn(0);
}
