/* libFuzzer target: the scene option parser. The input is an options string (as in a scene
   file: "-scene_bodies a,b -a_type fem ..."), inserted into PETSc's database with
   PetscOptionsInsertString; the scene is then created, set from options and set up, and up to
   two steps are run. Every error must come back as an error code: a crash, an abort or a
   sanitizer report is a finding.

   Inputs are skipped (not executed, not kept in the corpus) when they would only exercise
   PETSc's own machinery or run unboundedly long, not fecontact's parser:
     - options that read or write other files, print help, start debuggers, change PETSc's
       error or malloc handling, trap floating point or log (options_file, yaml, help, debugger,
       on_error, malloc, fp_trap, log, info, history, _view, monitor, dump);
     - mesh refinement and extrusion (refine, extrude): meshes grow without bound;
     - MUMPS control parameters (mat_mumps): MUMPS is not ours;
     - an iteration count over 1000 (any option whose name holds max_it); -pgs_max_it is 200
       unless the input sets it, and -time_step_min -time_step / 2 (one cut of step control at
       most: a scene that fails its steps, each redone down to h / 1024, runs for minutes);
     - a mesh file (..._filename) larger than 800 kB (the Table 1 meshes: minutes per step).
   The output file is always redirected to a scratch directory.

   Built with FUZZ_OPTION_PAIRS (tools/fuzz/fuzz_option_pairs.c), the input is instead what the
   Python module makes of an option dict (python/fecontact/scene.py, _option_pairs): one option a
   line, its name, then a tab and its value, each value inserted whole with PetscOptionsSetValue
   (spaces, ';' and any other bytes included). */
#include "fuzz_common.h"
#include <sys/stat.h>

static const char *deny[] = {"options_file", "yaml",   "help",     "debugger",  "on_error",     "malloc",
                             "fp_trap",      "log",    "info",     "history",   "_view",        "monitor",
                             "dump",         "refine", "extrude",  "mat_mumps", "version",      "checkstack",
                             "objects",      "signal", "stop_for", "display",   "skip_petscrc", NULL};

int LLVMFuzzerInitialize(int *argc, char ***argv)
{
  (void)argc;
  (void)argv;
  FuzzInitPETSc("fuzz_options");
  return 0;
}

/* After insertion: reject long iteration counts and big meshes */
static PetscBool TooExpensive(void)
{
  PetscInt  n;
  char    **names, **values;
  PetscBool bad = PETSC_FALSE;

  if (PetscOptionsLeftGet(NULL, &n, &names, &values)) return PETSC_TRUE;
  for (PetscInt i = 0; i < n && !bad; i++) {
    if (!values[i]) continue;
    if (strstr(names[i], "max_it") && strtod(values[i], NULL) > 1000) bad = PETSC_TRUE;
    if (strstr(names[i], "filename")) {
      struct stat st;
      if (!stat(values[i], &st) && st.st_size > 800 * 1024) bad = PETSC_TRUE;
    }
  }
  (void)PetscOptionsLeftRestore(NULL, &n, &names, &values);
  return bad;
}

static PetscErrorCode RunScene(void)
{
  FCScene        scene = NULL;
  PetscErrorCode ierr;

  PetscFunctionBegin;
  ierr = FCSceneCreate(PETSC_COMM_WORLD, &scene);
  if (!ierr) ierr = FCSceneSetFromOptions(scene);
  if (!ierr) ierr = FCSceneSetUp(scene);
  for (int k = 0; k < 2 && !ierr; k++) ierr = FCSceneStep(scene);
  /* a scene must be destroyable whatever step failed */
  PetscCall(FCSceneDestroy(&scene));
  PetscFunctionReturn(ierr);
}

/* The input into the options database: a command line's text, or (FUZZ_OPTION_PAIRS) name<TAB>value
   lines, each a name ("-" prepended when missing, as the Python module does) and its whole value */
static PetscErrorCode Insert(char *s)
{
#if defined(FUZZ_OPTION_PAIRS)
  char *save = NULL;

  for (char *line = strtok_r(s, "\n", &save); line; line = strtok_r(NULL, "\n", &save)) {
    char          *tab = strchr(line, '\t'), name[256];
    PetscErrorCode ierr;
    if (tab) *tab = 0;
    if (!line[0]) continue;
    snprintf(name, sizeof(name), "%s%s", line[0] == '-' ? "" : "-", line);
    ierr = PetscOptionsSetValue(NULL, name, tab ? tab + 1 : NULL);
    if (ierr) return ierr;
  }
  return 0;
#else
  return PetscOptionsInsertString(NULL, s);
#endif
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
  char          *s, out[PETSC_MAX_PATH_LEN + 32];
  PetscErrorCode ierr;

  if (size > 4096) return -1;
  s = malloc(size + 1);
  memcpy(s, data, size);
  s[size] = 0;
  for (int i = 0; deny[i]; i++)
    if (strstr(s, deny[i])) {
      free(s);
      return -1;
    }
  if (PetscOptionsClear(NULL)) FuzzFail("PetscOptionsClear", 1);
  ierr = Insert(s);
  free(s);
  if (!ierr && TooExpensive()) {
    (void)PetscOptionsClear(NULL);
    return -1;
  }
  snprintf(out, sizeof(out), "%s/out.h5", fz_dir);
  if (!ierr) ierr = PetscOptionsSetValue(NULL, "-output_file", out);
  if (!ierr) { /* bodies thrust into each other make PGS run all its (default 1000) sweeps */
    PetscBool has;
    ierr = PetscOptionsHasName(NULL, NULL, "-pgs_max_it", &has);
    if (!ierr && !has) ierr = PetscOptionsSetValue(NULL, "-pgs_max_it", "200");
  }
  if (!ierr) { /* step control: one cut at most */
    PetscBool has, set;
    PetscReal h = 0.0;
    ierr        = PetscOptionsHasName(NULL, NULL, "-time_step_min", &has);
    if (!ierr && !has) ierr = PetscOptionsGetReal(NULL, NULL, "-time_step", &h, &set);
    if (!ierr && !has && set && h > 0.0 && PetscIsNormalReal(h)) {
      char v[64];
      snprintf(v, sizeof(v), "%.17g", (double)(h / 2.0));
      ierr = PetscOptionsSetValue(NULL, "-time_step_min", v);
    }
  }
  if (!ierr) (void)RunScene(); /* errors are expected; crashes are not */
  if (PetscOptionsClear(NULL)) FuzzFail("PetscOptionsClear", 1);
  return 0;
}
