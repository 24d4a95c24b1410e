/* Tables of time (docs/scenes.md, "Tables of time"): a time-dependent value given as rows
   t, v_1 ... v_n, piecewise linear in t, held at the first row's values before it and at the last
   row's after it. Written inline, "t0:v,v,v;t1:v,v,v" (any text with a ':'), or as a CSV file whose
   first line may be a header ("t,ux,uy,uz"); times strictly increasing, every number finite. The
   file is read on rank 0 and its text broadcast, so every rank holds the same table. */
#include "../fcimpl.h"
#include <errno.h>
#include <sys/stat.h>

struct _p_FCTable {
  PetscInt   nrow, ncol; /* ncol values per row besides t */
  PetscReal *t, *v;      /* nrow times, nrow x ncol values */
};

/* One number of a row, checked: finite, and the whole token */
static PetscErrorCode ParseNumber(MPI_Comm comm, const char what[], PetscInt row, const char *tok, PetscReal *x)
{
  char *end;

  PetscFunctionBegin;
  while (*tok == ' ' || *tok == '\t') tok++;
  errno = 0;
  *x    = strtod(tok, &end);
  while (*end == ' ' || *end == '\t' || *end == '\r') end++;
  PetscCheck(*tok && *tok != '\r', comm, PETSC_ERR_USER_INPUT, "%s, row %" PetscInt_FMT ": a cell is empty", what,
             row + 1);
  PetscCheck(end != tok && !*end, comm, PETSC_ERR_USER_INPUT, "%s, row %" PetscInt_FMT ": '%s' is not a number", what,
             row + 1, tok);
  PetscCheck(PetscIsNormalReal(*x) || *x == 0.0, comm, PETSC_ERR_USER_INPUT,
             "%s, row %" PetscInt_FMT ": '%s' is not a finite number", what, row + 1, tok);
  PetscFunctionReturn(0);
}

/* Rows from text: rows separated by rsep, t from the values by tsep (',' in a file, ':' inline),
   values by ','; lines that are empty or begin with '#' are skipped, and a first row that does not
   begin with a number is a header */
static PetscErrorCode ParseRows(MPI_Comm comm, const char what[], char *text, const char *rsep, char tsep,
                                PetscInt nmin, PetscInt nmax, FCTable tab)
{
  char    *row, *rs = NULL;
  PetscInt cap = 16, k = 0;

  PetscFunctionBegin;
  PetscCall(PetscMalloc2(cap, &tab->t, cap * nmax, &tab->v));
  tab->ncol = -1;
  for (row = strtok_r(text, rsep, &rs); row; row = strtok_r(NULL, rsep, &rs)) {
    char     *p = row, *vals, *tok, *vs;
    PetscInt  n = 0;
    PetscReal vv[16];
    while (*p == ' ' || *p == '\t' || *p == '\r') p++;
    if (!*p || *p == '#') continue;
    if (k == 0 && tsep == ',' && !((*p >= '0' && *p <= '9') || *p == '-' || *p == '+' || *p == '.')) continue;
    vals = strchr(p, tsep);
    PetscCheck(vals, comm, PETSC_ERR_USER_INPUT, "%s, row %" PetscInt_FMT ": '%s' has no '%c' after its time", what,
               k + 1, p, tsep);
    *vals++ = 0;
    if (k == cap) {
      PetscReal *t, *v;
      PetscCall(PetscMalloc2(2 * cap, &t, 2 * cap * nmax, &v));
      PetscCall(PetscArraycpy(t, tab->t, cap));
      PetscCall(PetscArraycpy(v, tab->v, cap * nmax));
      PetscCall(PetscFree2(tab->t, tab->v));
      tab->t = t;
      tab->v = v;
      cap *= 2;
    }
    PetscCall(ParseNumber(comm, what, k, p, &tab->t[k]));
    for (tok = vals; tok; tok = vs) { /* every cell, an empty one too (it would shift the columns) */
      vs = strchr(tok, ',');
      if (vs) *vs++ = 0;
      PetscCheck(n < nmax, comm, PETSC_ERR_USER_INPUT, "%s, row %" PetscInt_FMT ": more than %" PetscInt_FMT " values",
                 what, k + 1, nmax);
      PetscCall(ParseNumber(comm, what, k, tok, &vv[n++]));
    }
    PetscCheck(n >= nmin, comm, PETSC_ERR_USER_INPUT,
               "%s, row %" PetscInt_FMT ": %" PetscInt_FMT " values after the time, %" PetscInt_FMT "%s%" PetscInt_FMT
               " needed",
               what, k + 1, n, nmin, nmax > nmin ? " to " : "", nmax > nmin ? nmax : (PetscInt)0);
    PetscCheck(tab->ncol < 0 || n == tab->ncol, comm, PETSC_ERR_USER_INPUT,
               "%s, row %" PetscInt_FMT ": %" PetscInt_FMT " values, the rows before have %" PetscInt_FMT, what, k + 1,
               n, tab->ncol);
    tab->ncol = n;
    PetscCheck(k == 0 || tab->t[k] > tab->t[k - 1], comm, PETSC_ERR_USER_INPUT,
               "%s, row %" PetscInt_FMT ": time %g does not increase (row before: %g)", what, k + 1, (double)tab->t[k],
               (double)tab->t[k - 1]);
    for (PetscInt j = 0; j < n; j++) tab->v[k * nmax + j] = vv[j];
    k++;
  }
  PetscCheck(k > 0, comm, PETSC_ERR_USER_INPUT, "%s has no rows", what);
  tab->nrow = k;
  for (PetscInt r = 0; r < k; r++) /* packed to ncol per row */
    for (PetscInt j = 0; j < tab->ncol; j++) tab->v[r * tab->ncol + j] = tab->v[r * nmax + j];
  PetscFunctionReturn(0);
}

/* A table of nmin to nmax (at most 16) values per time from spec; what names its option in errors */
/* FCTableCreate into tab, with the text it reads (*text, freed by the caller, also after an error) */
static PetscErrorCode TableFill(MPI_Comm comm, const char spec[], PetscInt nmin, PetscInt nmax, const char what[],
                                FCTable tab, char **textp)
{
  char *text = NULL;

  PetscFunctionBegin;
  if (strchr(spec, ':')) {
    PetscCall(PetscStrallocpy(spec, &text));
    *textp = text;
    PetscCall(ParseRows(comm, what, text, ";", ':', nmin, nmax, tab));
  } else { /* a file */
    long        len = -1;
    PetscMPIInt rank;
    PetscCallMPI(MPI_Comm_rank(comm, &rank));
    text = NULL;
    if (!rank) {
      struct stat st;
      /* a regular file only: a FIFO would block the read, a directory has no text */
      FILE *fp = !stat(spec, &st) && S_ISREG(st.st_mode) ? fopen(spec, "rb") : NULL;
      if (!fp && !stat(spec, &st) && !S_ISREG(st.st_mode)) len = -2;
      if (fp && !fseek(fp, 0, SEEK_END) && (len = ftell(fp)) >= 0 && !fseek(fp, 0, SEEK_SET)) {
        PetscCall(PetscMalloc1(len + 1, &text));
        *textp = text;
        if ((long)fread(text, 1, len, fp) != len)
          len = -1;
        else
          text[len] = 0;
      } else if (len != -2)
        len = -1;
      if (fp) fclose(fp);
    }
    PetscCallMPI(MPI_Bcast(&len, 1, MPI_LONG, 0, comm));
    PetscCheck(len != -2, comm, PETSC_ERR_USER_INPUT, "%s: the table file '%s' is not a regular file", what, spec);
    PetscCheck(len >= 0, comm, PETSC_ERR_USER_INPUT,
               "%s: cannot read the table file '%s' (inline tables are written t0:v,v;t1:v,v)", what, spec);
    if (rank) PetscCall(PetscMalloc1(len + 1, &text));
    if (rank) *textp = text;
    PetscCallMPI(MPI_Bcast(text, (PetscMPIInt)len + 1, MPI_CHAR, 0, comm));
    {
      char w[512];
      PetscCall(PetscSNPrintf(w, sizeof(w), "table of %s", what));
      PetscCall(FCInputsAdd(spec, w));
      PetscCall(PetscSNPrintf(w, sizeof(w), "%s (file '%s')", what, spec));
      PetscCall(ParseRows(comm, w, text, "\n", ',', nmin, nmax, tab));
    }
  }
  PetscFunctionReturn(0);
}

PetscErrorCode FCTableCreate(MPI_Comm comm, const char spec[], PetscInt nmin, PetscInt nmax, const char what[],
                             FCTable *table)
{
  FCTable        tab;
  char          *text = NULL;
  PetscErrorCode ierr;

  PetscFunctionBegin;
  PetscCheck(nmax <= 16 && nmin >= 1 && nmin <= nmax, comm, PETSC_ERR_PLIB,
             "table of %" PetscInt_FMT "..%" PetscInt_FMT " values", nmin, nmax);
  PetscCall(PetscNew(&tab));
  ierr = TableFill(comm, spec, nmin, nmax, what, tab, &text); /* a wrong table frees what it had read */
  PetscCall(PetscFree(text));
  if (ierr) {
    PetscCall(FCTableDestroy(&tab));
    PetscCall(ierr);
  }
  *table = tab;
  PetscFunctionReturn(0);
}

PetscInt FCTableColumns(FCTable tab)
{
  return tab->ncol;
}

/* The rows' values (nrow rows of FCTableColumns each), for checks of their meaning */
const PetscReal *FCTableValues(FCTable tab, PetscInt *nrow)
{
  *nrow = tab->nrow;
  return tab->v;
}

/* The rows around time t and where t lies between them, s in [0, 1] (outside the table: the
   first or last row twice) */
void FCTableBracket(FCTable tab, PetscReal t, const PetscReal **a, const PetscReal **b, PetscReal *s)
{
  PetscInt n = tab->nrow, c = tab->ncol, lo = 0, hi = n - 1;
  if (t <= tab->t[0] || n == 1 || t >= tab->t[n - 1]) {
    *a = *b = &tab->v[(t <= tab->t[0] || n == 1 ? 0 : n - 1) * c];
    *s      = 0.0;
    return;
  }
  while (hi - lo > 1) { /* t[lo] < t <= t[hi] */
    PetscInt mid = (lo + hi) / 2;
    if (tab->t[mid] < t)
      lo = mid;
    else
      hi = mid;
  }
  *a = &tab->v[lo * c];
  *b = &tab->v[hi * c];
  *s = (t - tab->t[lo]) / (tab->t[hi] - tab->t[lo]);
}

/* The values at time t: linear between rows, constant outside them */
void FCTableEval(FCTable tab, PetscReal t, PetscReal v[])
{
  const PetscReal *a, *b;
  PetscReal        s;
  FCTableBracket(tab, t, &a, &b, &s);
  for (PetscInt j = 0; j < tab->ncol; j++) v[j] = (1.0 - s) * a[j] + s * b[j];
}

/* The largest rate of change over the rows of the columns [j0, j1) (their norm per unit time) */
PetscReal FCTableMaxRate(FCTable tab, PetscInt j0, PetscInt j1)
{
  PetscReal r = 0.0;
  for (PetscInt k = 1; k < tab->nrow; k++) {
    PetscReal d2 = 0.0;
    for (PetscInt j = j0; j < j1; j++) d2 += PetscSqr(tab->v[k * tab->ncol + j] - tab->v[(k - 1) * tab->ncol + j]);
    r = PetscMax(r, PetscSqrtReal(d2) / (tab->t[k] - tab->t[k - 1]));
  }
  return r;
}

PetscErrorCode FCTableDestroy(FCTable *tab)
{
  PetscFunctionBegin;
  if (!*tab) PetscFunctionReturn(0);
  PetscCall(PetscFree2((*tab)->t, (*tab)->v));
  PetscCall(PetscFree(*tab));
  PetscFunctionReturn(0);
}
