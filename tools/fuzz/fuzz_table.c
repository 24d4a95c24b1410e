/* libFuzzer target: the tables of time (src/util/table.c). The input's first byte chooses the
   table's shape (the numbers of values per row that a trajectory, a displacement, a force or a
   pressure takes), the rest is the table's text: inline when it holds a ':' (as an option's
   value, of any length), else the text of a CSV file written to the scratch directory and read by
   path. The table is then evaluated at a few times. Every error must come back as an error code:
   a crash, an abort, a hang or a sanitizer report is a finding. Regions and the region=table pairs
   of the FE options are fuzzed through fuzz_options (its dictionary and seeds). */
#include "fuzz_common.h"
#include "util/util.h" /* FCTable (internal to the library, linked statically) */

int LLVMFuzzerInitialize(int *argc, char ***argv)
{
  (void)argc;
  (void)argv;
  FuzzInitPETSc("fuzz_table");
  return 0;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
  static const PetscInt shape[4][2] = {{3, 7}, {3, 3}, {1, 1}, {1, 16}}; /* trajectory, displacement, pressure, any */
  char                 *s, path[PETSC_MAX_PATH_LEN + 32];
  const char           *spec;
  FCTable               tab = NULL;
  PetscInt              k;

  if (size < 1 || size > 65536) return -1;
  k = data[0] % 4;
  s = malloc(size);
  memcpy(s, data + 1, size - 1);
  s[size - 1] = 0;
  spec        = s;
  if (!strchr(s, ':')) { /* a CSV file */
    FILE *fp;
    snprintf(path, sizeof(path), "%s/table.csv", fz_dir);
    fp = fopen(path, "wb");
    if (!fp) FuzzFail("fopen of the scratch table", 1);
    fwrite(s, 1, strlen(s), fp);
    fclose(fp);
    spec = path;
  }
  if (!FCTableCreate(PETSC_COMM_WORLD, spec, shape[k][0], shape[k][1], "fuzz table", &tab)) {
    PetscReal v[16], t[] = {-1e300, -1.0, 0.0, 0.5, 1.0, 1e300};
    PetscInt  n = FCTableColumns(tab);
    if (n < shape[k][0] || n > shape[k][1]) abort(); /* a table of another shape than asked for */
    for (size_t i = 0; i < sizeof(t) / sizeof(t[0]); i++) FCTableEval(tab, t[i], v);
    (void)FCTableMaxRate(tab, 0, n);
    if (FCTableDestroy(&tab)) FuzzFail("FCTableDestroy", 1);
  }
  free(s);
  return 0;
}
