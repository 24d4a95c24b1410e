/* A restart continues the scene that its file holds (docs/options.md, -restart): the options that
   define that scene must be those of the run that wrote the file (its "options" attribute). They
   are -scene_bodies, every option of a body (-<name>_...), -gravity and -time_integration, except those that
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

/* Whether key is an option that defines the scene: -scene_bodies, -gravity, -time_integration, or an
   option of a body that is not free to change. A key belongs to the body with the longest name that
   prefixes it ("pad_force_young" is pad_force's where bodies pad and pad_force exist) */
static PetscBool Defines(const char key[], PetscInt nbodies, FCBody bodies[])
{
  size_t best = 0;

  if (!strcmp(key, "scene_bodies") || !strcmp(key, "gravity") || !strcmp(key, "time_integration")) return PETSC_TRUE;
  for (PetscInt i = 0; i < nbodies; i++) {
    const char *name;
    size_t      l;
    if (FCBodyGetName(bodies[i], &name)) return PETSC_FALSE;
    l = strlen(name);
    if (l > best && !strncmp(key, name, l) && key[l] == '_') best = l;
  }
  if (!best) return PETSC_FALSE;
  for (size_t k = 0; k < sizeof(Free) / sizeof(Free[0]); k++)
    if (!strncmp(key + best + 1, Free[k], strlen(Free[k]))) return PETSC_FALSE;
  return PETSC_TRUE;
}

/* Attribute `name` of /bodies/<body> in the file f (rank 0): a string (len: its size, 0 when absent)
   or n doubles */
static PetscErrorCode ReadBodyAttr(hid_t f, const char body[], const char name[], char **str, double **val, size_t *n)
{
  char  path[PETSC_MAX_PATH_LEN];
  hid_t g, a, t;

  PetscFunctionBegin;
  *n = 0;
  PetscCall(PetscSNPrintf(path, sizeof(path), "/bodies/%s", body));
  if (H5Lexists(f, "bodies", H5P_DEFAULT) <= 0 || H5Lexists(f, path, H5P_DEFAULT) <= 0) PetscFunctionReturn(0);
  g = H5Gopen2(f, path, H5P_DEFAULT);
  if (g < 0) PetscFunctionReturn(0);
  if (H5Aexists(g, name) > 0 && (a = H5Aopen(g, name, H5P_DEFAULT)) >= 0) {
    if (str) {
      t  = H5Aget_type(a);
      *n = H5Tget_size(t);
      PetscCall(PetscCalloc1(*n + 1, str));
      if (H5Aread(a, t, *str) < 0) *n = 0;
      H5Tclose(t);
    } else {
      hid_t s = H5Aget_space(a);
      *n      = (size_t)H5Sget_simple_extent_npoints(s);
      H5Sclose(s);
      PetscCall(PetscCalloc1(*n + 1, val));
      if (H5Aread(a, H5T_NATIVE_DOUBLE, *val) < 0) *n = 0;
    }
    H5Aclose(a);
  }
  H5Gclose(g);
  PetscFunctionReturn(0);
}

/* The bodies' regions (FCBodyGetRegions) against those of the run that wrote the file: the same
   kinds and regions in the same order, each constraint on as many vertices with the same reference
   centroid (to 1e-9 of the body's size). A file without them (written before they were) is not
   checked. Collective; msg: the difference, "" when none */
static PetscErrorCode CheckRegions(MPI_Comm comm, const char file[], PetscInt nbodies, FCBody bodies[], char msg[],
                                   size_t len)
{
  PetscMPIInt rank;
  hid_t       f = -1;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  if (!rank) f = H5Fopen(file, H5F_ACC_RDONLY, H5P_DEFAULT);
  for (PetscInt i = 0; i < nbodies && !msg[0]; i++) {
    const char *name;
    char       *now, *old = NULL;
    PetscReal  *vnow;
    double     *vold = NULL;
    PetscInt    n;
    size_t      lold = 0, nold = 0;
    long        sizes[2];
    PetscCall(FCBodyGetName(bodies[i], &name));
    PetscCall(FCBodyGetRegions(bodies[i], &n, &now, &vnow));
    if (!rank && f >= 0) {
      PetscCall(ReadBodyAttr(f, name, "regions", &old, NULL, &lold));
      if (lold) PetscCall(ReadBodyAttr(f, name, "region_vertices", NULL, &vold, &nold));
    }
    sizes[0] = (long)lold;
    sizes[1] = (long)nold;
    PetscCallMPI(MPI_Bcast(sizes, 2, MPI_LONG, 0, comm));
    if (sizes[0]) {
      if (rank) PetscCall(PetscCalloc1(sizes[0] + 1, &old));
      if (rank) PetscCall(PetscCalloc1(sizes[1] + 1, &vold));
      PetscCallMPI(MPI_Bcast(old, (PetscMPIInt)sizes[0], MPI_CHAR, 0, comm));
      PetscCallMPI(MPI_Bcast(vold, (PetscMPIInt)sizes[1], MPI_DOUBLE, 0, comm));
      if (strcmp(old, now) || sizes[1] != 4 * n) {
        char *a = old, *b = now;
        for (char *p = a; *p; p++)
          if (*p == '\n') *p = p[1] ? ' ' : 0;
        for (char *p = b; *p; p++)
          if (*p == '\n') *p = p[1] ? ' ' : 0;
        PetscCall(PetscSNPrintf(msg, len, "body '%s' has the regions [%s] here but [%s] in the run that wrote it", name,
                                b, a));
      } else {
        PetscReal size = 0.0;
        for (PetscInt k = 0; k < n; k++)
          for (int d = 1; d < 4; d++) size = PetscMax(size, PetscAbsReal(vold[4 * k + d]));
        for (PetscInt k = 0; k < n && !msg[0]; k++) {
          PetscReal dx = 0.0;
          for (int d = 1; d < 4; d++) dx = PetscMax(dx, PetscAbsReal(vold[4 * k + d] - vnow[4 * k + d]));
          if (vold[4 * k] != vnow[4 * k] || dx > 1e-9 * PetscMax(size, 1e-300)) {
            char *line = now, *end;
            for (PetscInt j = 0; j < k; j++) line = strchr(line, '\n') + 1;
            if ((end = strchr(line, '\n'))) *end = 0;
            PetscCall(
                PetscSNPrintf(msg, len,
                              "body '%s', %s: %g vertices centred at (%g, %g, %g) here, %g at (%g, %g, %g) in the "
                              "run that wrote it",
                              name, line, (double)vnow[4 * k], (double)vnow[4 * k + 1], (double)vnow[4 * k + 2],
                              (double)vnow[4 * k + 3], (double)vold[4 * k], (double)vold[4 * k + 1],
                              (double)vold[4 * k + 2], (double)vold[4 * k + 3]));
          }
        }
      }
    }
    PetscCall(PetscFree(old));
    PetscCall(PetscFree(vold));
    PetscCall(PetscFree(now));
    PetscCall(PetscFree(vnow));
  }
  if (f >= 0) H5Fclose(f);
  PetscFunctionReturn(0);
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
  if (!msg[0]) PetscCall(CheckRegions(comm, file, nbodies, bodies, msg, sizeof(msg)));
  PetscCheck(
      !msg[0], comm, PETSC_ERR_USER_INPUT,
      "-restart %s: %s. A restart continues the scene that the file holds (bodies, meshes, materials, placement, "
      "velocities, constraints); its solver options and tables of time may change (docs/options.md)",
      file, msg);
  PetscFunctionReturn(0);
}
