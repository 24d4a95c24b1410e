/* Option helpers: numeric options are checked for NaN/Inf, subnormals and exact arity, integers
   against their range before conversion, logical options for their accepted words; errors name
   the full option, and options nobody read are reported (a misspelt option is an error,
   never a silent default). */
#include "../fcimpl.h"
#include <errno.h>
#include <float.h>

static const char *PrefixOf(PetscOptionItems *obj)
{
  return obj->prefix ? obj->prefix : "";
}

/* The raw text of an option must be n comma-separated numbers (integers when integer): PETSc's
   own parse error would not name the option. */
static PetscErrorCode CheckNumbers(PetscOptionItems *obj, const char opt[], PetscBool integer)
{
  const char *value;
  char       *buf, *tok, *save = NULL;
  PetscBool   set;

  PetscFunctionBegin;
  PetscCall(PetscOptionsFindPair(obj->options, obj->prefix, opt, &value, &set));
  if (!set) PetscFunctionReturn(0);
  PetscCheck(value && value[0], obj->comm, PETSC_ERR_USER_INPUT, "Option -%s%s needs a value", PrefixOf(obj), opt + 1);
  PetscCall(PetscStrallocpy(value, &buf)); /* the whole text, whatever its length */
  for (tok = strtok_r(buf, ",", &save); tok; tok = strtok_r(NULL, ",", &save)) {
    char     *end;
    PetscBool ok;
    while (*tok == ' ') tok++;
    if (integer)
      (void)strtoll(tok, &end, 10);
    else
      (void)strtod(tok, &end);
    while (*end == ' ') end++;
    ok = (PetscBool)(end != tok && *end == 0);
    if (!ok) {
      char shown[256];
      PetscCall(PetscStrncpy(shown, tok, sizeof(shown)));
      PetscCall(PetscFree(buf));
      SETERRQ(obj->comm, PETSC_ERR_USER_INPUT, "Option -%s%s: '%s' is not %s", PrefixOf(obj), opt + 1, shown,
              integer ? "an integer" : "a number");
    }
  }
  PetscCall(PetscFree(buf));
  PetscFunctionReturn(0);
}

/* A string option of any length (PETSc's own copy into a fixed buffer would cut a long value
   silently): PetscOptionsString registers it for -help, and its whole value is then taken from
   the options database. *value is NULL or an earlier value, which is freed (PetscOptionsBegin
   may run its block more than once) */
PetscErrorCode FCOptionsStringAlloc(PetscOptionItems *PetscOptionsObject, const char opt[], const char text[],
                                    char **value, PetscBool *set)
{
  char        scratch[2];
  const char *v = NULL;
  PetscBool   flg;

  PetscFunctionBegin;
  FCValidPointer(PetscOptionsObject, 1);
  FCValidPointer(opt, 2);
  FCValidPointer(text, 3);
  FCValidPointer(value, 4);
  PetscCall(PetscOptionsString(opt, text, NULL, "", scratch, sizeof(scratch), NULL));
  PetscCall(PetscOptionsFindPair(PetscOptionsObject->options, PetscOptionsObject->prefix, opt, &v, &flg));
  PetscCall(PetscFree(*value));
  PetscCall(PetscStrallocpy(flg && v ? v : "", value));
  if (set) *set = flg;
  PetscFunctionReturn(0);
}

/* The one helper behind every integer option: the text is parsed as a 64-bit integer and checked
   against [min, max] (within PetscInt's range) before it is converted, so that a value past the
   range is an error that names the option and the range, never a wrapped value */
PetscErrorCode FCOptionsIntRange(PetscOptionItems *PetscOptionsObject, const char opt[], const char text[],
                                 PetscInt min, PetscInt max, PetscInt *v, PetscBool *set)
{
  const char *buf;
  char       *end;
  PetscBool   flg;
  long long   x;

  PetscFunctionBegin;
  FCValidPointer(PetscOptionsObject, 1);
  FCValidPointer(opt, 2);
  FCValidPointer(text, 3);
  FCValidPointer(v, 6);
  min = PetscMax(min, PETSC_MIN_INT);
  max = PetscMin(max, PETSC_MAX_INT);
  PetscCall(CheckNumbers(PetscOptionsObject, opt, PETSC_TRUE));
  PetscCall(PetscOptionsFindPair(PetscOptionsObject->options, PetscOptionsObject->prefix, opt, &buf, &flg));
  if (flg && buf) {
    errno = 0;
    x     = strtoll(buf, &end, 10);
    PetscCheck(errno != ERANGE && x >= (long long)min && x <= (long long)max, PetscOptionsObject->comm,
               PETSC_ERR_USER_INPUT,
               "Option -%s%s must be an integer in [%" PetscInt_FMT ", %" PetscInt_FMT "], got %s",
               PrefixOf(PetscOptionsObject), opt + 1, min, max, buf);
  }
  PetscCall(PetscOptionsInt(opt, text, NULL, *v, v, set));
  PetscFunctionReturn(0);
}

/* An integer option in PetscInt's whole range (callers that need a narrower one check it after, or
   call FCOptionsIntRange) */
PetscErrorCode FCOptionsInt(PetscOptionItems *PetscOptionsObject, const char opt[], const char text[], PetscInt *v,
                            PetscBool *set)
{
  PetscFunctionBegin;
  FCValidPointer(PetscOptionsObject, 1);
  FCValidPointer(opt, 2);
  FCValidPointer(text, 3);
  FCValidPointer(v, 4);
  PetscCall(FCOptionsIntRange(PetscOptionsObject, opt, text, PETSC_MIN_INT, PETSC_MAX_INT, v, set));
  PetscFunctionReturn(0);
}

/* A logical option: no value, or one of the words PETSc accepts; PETSc's own parse error would
   neither name the option nor say what is accepted */
PetscErrorCode FCOptionsBool(PetscOptionItems *PetscOptionsObject, const char opt[], const char text[], PetscBool *v,
                             PetscBool *set)
{
  static const char *words[] = {"1", "0", "true", "false", "yes", "no", "on", "off", NULL};
  char               buf[256];
  PetscBool          flg, ok = PETSC_FALSE;

  PetscFunctionBegin;
  FCValidPointer(PetscOptionsObject, 1);
  FCValidPointer(opt, 2);
  FCValidPointer(text, 3);
  FCValidPointer(v, 4);
  PetscCall(
      PetscOptionsGetString(PetscOptionsObject->options, PetscOptionsObject->prefix, opt, buf, sizeof(buf), &flg));
  if (flg && buf[0]) {
    for (int i = 0; words[i] && !ok; i++) PetscCall(PetscStrcasecmp(buf, words[i], &ok));
    PetscCheck(ok, PetscOptionsObject->comm, PETSC_ERR_USER_INPUT,
               "Option -%s%s takes no value or one of true, false, yes, no, on, off, 1, 0; got '%s'",
               PrefixOf(PetscOptionsObject), opt + 1, buf);
  }
  PetscCall(PetscOptionsBool(opt, text, NULL, *v, v, set));
  PetscFunctionReturn(0);
}

/* A choice among words: PETSc's own error on another word is a traceback that does not say what is
   accepted. The value is the index of the word in list (compared as PETSc does, ignoring case) */
PetscErrorCode FCOptionsEList(PetscOptionItems *PetscOptionsObject, const char opt[], const char text[],
                              const char *const list[], PetscInt n, PetscInt *v, PetscBool *set)
{
  char      buf[256], known[1024] = "";
  PetscBool flg, ok               = PETSC_FALSE;

  PetscFunctionBegin;
  FCValidPointer(PetscOptionsObject, 1);
  FCValidPointer(opt, 2);
  FCValidPointer(text, 3);
  FCValidPointer(list, 4);
  FCValidPointer(v, 6);
  PetscCall(
      PetscOptionsGetString(PetscOptionsObject->options, PetscOptionsObject->prefix, opt, buf, sizeof(buf), &flg));
  if (flg) {
    for (PetscInt i = 0; i < n && !ok; i++) PetscCall(PetscStrcasecmp(buf, list[i], &ok));
    for (PetscInt i = 0; i < n; i++) {
      PetscCall(PetscStrlcat(known, i ? (i == n - 1 ? " or " : ", ") : "", sizeof(known)));
      PetscCall(PetscStrlcat(known, list[i], sizeof(known)));
    }
    PetscCheck(ok, PetscOptionsObject->comm, PETSC_ERR_USER_INPUT, "Option -%s%s takes %s%s; got '%s'",
               PrefixOf(PetscOptionsObject), opt + 1, n > 1 ? "one of " : "", known, buf);
  }
  PetscCall(PetscOptionsEList(opt, text, NULL, list, n, list[*v], v, set));
  PetscFunctionReturn(0);
}

/* A real value must be finite and, unless 0, normal: a subnormal (below 2.2e-308 in magnitude)
   has lost precision and makes every quantity derived from it meaningless. entry < 0: a scalar */
static PetscErrorCode CheckReal(PetscOptionItems *obj, const char opt[], PetscInt entry, PetscReal v)
{
  char where[64] = "";

  PetscFunctionBegin;
  if (PetscIsNormalReal(v) || v == 0.0) PetscFunctionReturn(0);
  if (entry >= 0) PetscCall(PetscSNPrintf(where, sizeof(where), ": entry %" PetscInt_FMT, entry));
  PetscCheck(!PetscIsInfOrNanReal(v), obj->comm, PETSC_ERR_USER_INPUT, "Option -%s%s%s must be a finite number, got %g",
             PrefixOf(obj), opt + 1, where, (double)v);
  SETERRQ(obj->comm, PETSC_ERR_USER_INPUT,
          "Option -%s%s%s: %g is subnormal (a magnitude below %g, the smallest normal double, has lost its "
          "precision); give 0 or a magnitude in [%g, %g]",
          PrefixOf(obj), opt + 1, where, (double)v, DBL_MIN, DBL_MIN, (double)PETSC_MAX_REAL);
}

PetscErrorCode FCOptionsReal(PetscOptionItems *PetscOptionsObject, const char opt[], const char text[], PetscReal *v,
                             PetscBool *set)
{
  PetscBool flg = PETSC_FALSE;

  PetscFunctionBegin;
  FCValidPointer(PetscOptionsObject, 1);
  FCValidPointer(opt, 2);
  FCValidPointer(text, 3);
  FCValidPointer(v, 4);
  PetscCall(CheckNumbers(PetscOptionsObject, opt, PETSC_FALSE));
  PetscCall(PetscOptionsReal(opt, text, NULL, *v, v, &flg));
  if (flg) PetscCall(CheckReal(PetscOptionsObject, opt, -1, *v));
  if (set) *set = flg;
  PetscFunctionReturn(0);
}

PetscErrorCode FCOptionsRealArray(PetscOptionItems *PetscOptionsObject, const char opt[], const char text[], PetscInt n,
                                  PetscReal v[], PetscBool *set)
{
  PetscInt  got = n;
  PetscBool flg = PETSC_FALSE;
  PetscReal tmp[16];

  PetscFunctionBegin;
  FCValidPointer(PetscOptionsObject, 1);
  FCValidPointer(opt, 2);
  FCValidPointer(text, 3);
  FCValidPointer(v, 5);
  PetscCheck(n <= 15, PETSC_COMM_SELF, PETSC_ERR_PLIB, "Array option too long");
  got = 16;
  PetscCall(CheckNumbers(PetscOptionsObject, opt, PETSC_FALSE));
  PetscCall(PetscArraycpy(tmp, v, n));
  PetscCall(PetscOptionsRealArray(opt, text, NULL, tmp, &got, &flg));
  if (flg) {
    PetscCheck(got == n, PetscOptionsObject->comm, PETSC_ERR_USER_INPUT,
               "Option -%s%s needs %" PetscInt_FMT " comma-separated numbers, got %" PetscInt_FMT,
               PrefixOf(PetscOptionsObject), opt + 1, n, got);
    for (PetscInt i = 0; i < n; i++) PetscCall(CheckReal(PetscOptionsObject, opt, i, tmp[i]));
    PetscCall(PetscArraycpy(v, tmp, n));
  }
  if (set) *set = flg;
  PetscFunctionReturn(0);
}

/* A list of 1 to nmax finite numbers; n returns how many were given */
PetscErrorCode FCOptionsRealList(PetscOptionItems *PetscOptionsObject, const char opt[], const char text[],
                                 PetscInt nmax, PetscReal v[], PetscInt *n, PetscBool *set)
{
  PetscBool flg = PETSC_FALSE;

  PetscFunctionBegin;
  FCValidPointer(PetscOptionsObject, 1);
  FCValidPointer(opt, 2);
  FCValidPointer(text, 3);
  FCValidPointer(v, 5);
  FCValidPointer(n, 6);
  PetscCall(CheckNumbers(PetscOptionsObject, opt, PETSC_FALSE));
  *n = nmax;
  PetscCall(PetscOptionsRealArray(opt, text, NULL, v, n, &flg));
  for (PetscInt i = 0; flg && i < *n; i++) PetscCall(CheckReal(PetscOptionsObject, opt, i, v[i]));
  if (set) *set = flg;
  PetscFunctionReturn(0);
}

PetscErrorCode FCCheckPositive(MPI_Comm comm, const char prefix[], const char opt[], PetscReal v)
{
  PetscFunctionBegin;
  FCValidPointer(opt, 3);
  PetscCheck(v > 0.0, comm, PETSC_ERR_USER_INPUT, "Option -%s%s must be > 0, got %g", prefix ? prefix : "", opt + 1,
             (double)v);
  PetscFunctionReturn(0);
}

PetscErrorCode FCCheckNonNegative(MPI_Comm comm, const char prefix[], const char opt[], PetscReal v)
{
  PetscFunctionBegin;
  FCValidPointer(opt, 3);
  PetscCheck(v >= 0.0, comm, PETSC_ERR_USER_INPUT, "Option -%s%s must be >= 0, got %g", prefix ? prefix : "", opt + 1,
             (double)v);
  PetscFunctionReturn(0);
}

/* PETSc's own run-time options that are legitimately read after set-up (viewers at solve or
   exit, logging, debugging): never reported. */
static PetscBool IsPetscRuntimeOption(const char name[])
{
  static const char *exact[]  = {"log",
                                 "info",
                                 "malloc",
                                 "malloc_debug",
                                 "malloc_dump",
                                 "malloc_view",
                                 "help",
                                 "version",
                                 "fp_trap",
                                 "no_signal_handler",
                                 "history",
                                 "checkstack",
                                 "objects_dump",
                                 "memory_view",
                                 "skip_petscrc",
                                 "start_in_debugger",
                                 "debugger",
                                 "stop_for_debugger",
                                 "display",
                                 "use_gpu_aware_mpi",
                                 "fecontact_allow_unknown_options",
                                 NULL};
  static const char *starts[] = {
      "options_", "log_", "info_", "malloc_", "on_error_", "viewer_", "device_", "cuda_", "check_pointer_intensity",
      NULL};
  size_t len = strlen(name);
  for (int i = 0; exact[i]; i++)
    if (!strcmp(name, exact[i])) return PETSC_TRUE;
  for (int i = 0; starts[i]; i++)
    if (!strncmp(name, starts[i], strlen(starts[i]))) return PETSC_TRUE;
  /* MUMPS' options (-[<body>_]mat_mumps_icntl_14, ...) are read when a factor is set up, at its
     first use, after this check: the error messages of a failed factorization name them */
  if (strstr(name, "mat_mumps_")) return PETSC_TRUE;
  /* viewers and reports read when a solve finishes: -xxx_view, -xxx_view_*, -xxx_converged_reason */
  if ((len >= 5 && !strcmp(name + len - 5, "_view")) || strstr(name, "_view_") ||
      (len >= 16 && !strcmp(name + len - 16, "converged_reason")))
    return PETSC_TRUE;
  return PETSC_FALSE;
}

PetscErrorCode FCOptionsCheckUnused(MPI_Comm comm)
{
  PetscInt  n;
  char    **names, **values;
  PetscBool allow = PETSC_FALSE;

  PetscFunctionBegin;
  PetscCall(PetscOptionsGetBool(NULL, NULL, "-fecontact_allow_unknown_options", &allow, NULL));
  PetscCall(PetscOptionsLeftGet(NULL, &n, &names, &values));
  for (PetscInt i = 0; i < n; i++) {
    if (IsPetscRuntimeOption(names[i])) continue;
    if (allow) {
      PetscCall(PetscPrintf(comm, "fecontact: warning: option -%s was never used\n", names[i]));
      continue;
    }
    {
      char msg[PETSC_MAX_PATH_LEN];
      PetscCall(PetscSNPrintf(msg, sizeof(msg), "%s", names[i]));
      PetscCall(PetscOptionsLeftRestore(NULL, &n, &names, &values));
      SETERRQ(comm, PETSC_ERR_USER_INPUT,
              "Unknown or unused option -%s (misspelt, for a body not in -scene_bodies, or an option of a "
              "-constraint_scheme or -compliance_type not chosen? see docs/options.md; "
              "-fecontact_allow_unknown_options turns this into a warning)",
              msg);
    }
  }
  PetscCall(PetscOptionsLeftRestore(NULL, &n, &names, &values));
  PetscFunctionReturn(0);
}
