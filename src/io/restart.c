/* The restart format, written and read here (docs/output.md, "Restart state"):

     /restart/slot0, /restart/slot1   two slots, written alternately at every output step (the
                                      older one each time), so that a run killed while writing one
                                      still has a complete state in the other; in each:
       step       scalar int64        the step the state belongs to; -1 while the slot is being
                                      written (it is written first as -1 and last as the step,
                                      each stage flushed before the next)
       time       scalar float64      its time
       step_control (3) float64       the requested time step, the sub-step in use and the sub-steps
                                      accepted since its last change (src/scene/stepcontrol.c)
       ncontacts  scalar int64        contacts of the step (the warm start of the next step)
       contacts   (>= ncontacts, FC_RESTART_CONTACT) float64, chunked and extendible (it only
                                      grows); its first ncontacts rows are this state's, one per
                                      contact: pair, rows, key (3), n, t1, t2 (3 each), force (3)
       <body>     one dataset per body: FCBodyGetStateLayout's `cols` values a row; one row per
                  vertex in the order of /bodies/<body>/mesh/reference (FE: u, v, V x 6), or a
                  single row (rigid, kinematic: x, q, v, w, 1 x 13)

   Writing (FCRestartWriter*, called by src/io/output.c on its open parallel file): every rank
   writes the rows of the vertices it owns, rank 0 the single rows and the contacts.
   Reading (-restart file.h5, FCRestartLoad): the newest complete slot of an earlier run's output
   is read into the bodies, the previous step's contacts (the warm start of the contact solver)
   and the step counter, so that the run continues as if it had not stopped. Every rank reads the
   file (read-only, serial HDF5) and takes its part; FE vertices are matched by their reference
   coordinates, so a file written on any number of ranks can be continued on any other. */
#include "ioimpl.h"
#include <math.h>

/* values of a contact record: pair, rows, key (3), n, t1, t2 (3 each), force (3) */
#define FC_RESTART_CONTACT 17

/* The record of a contact in /restart/slot0|1/contacts: what the next step's warm start reads
   (FCContactSetFind: pair and key; FCContactPreviousForce: frame and force) */
static void PackContact(const FCContact *c, double r[FC_RESTART_CONTACT])
{
  r[0] = c->pair;
  r[1] = c->dim;
  for (int d = 0; d < 3; d++) {
    r[2 + d]  = c->key[d];
    r[5 + d]  = c->n[d];
    r[8 + d]  = c->t1[d];
    r[11 + d] = c->t2[d];
    r[14 + d] = c->force[d];
  }
}

static void UnpackContact(const double r[FC_RESTART_CONTACT], FCContact *c)
{
  PetscMemzero(c, sizeof(*c));
  c->pair = (PetscInt)r[0];
  c->dim  = (PetscInt)r[1];
  for (int d = 0; d < 3; d++) {
    c->key[d]   = r[2 + d];
    c->n[d]     = r[5 + d];
    c->t1[d]    = r[8 + d];
    c->t2[d]    = r[11 + d];
    c->force[d] = r[14 + d];
  }
}

/* ---------------------------------------------------------------------------------------------
   Writing
   --------------------------------------------------------------------------------------------- */
struct _p_FCRestartWriter {
  PetscMPIInt rank;
  PetscInt    nbodies, nwritten;
  hid_t       slot[2], step[2], time[2], contacts[2], ncontacts[2], control[2], *body[2];
};

/* The rows of a body's state dataset and, on this rank, the first row and how many it writes */
static PetscErrorCode StateRows(FCBody b, PetscMPIInt rank, hsize_t *rows, hsize_t *cols, hsize_t *start,
                                hsize_t *count)
{
  const FCBodyVisual *vis;
  PetscInt            c;
  PetscBool           pervertex;

  PetscFunctionBegin;
  PetscCall(FCBodyGetStateLayout(b, &c, &pervertex));
  PetscCall(FCBodyGetVisual(b, &vis));
  *cols  = (hsize_t)c;
  *rows  = pervertex ? (hsize_t)vis->nv_global : 1;
  *start = pervertex ? (hsize_t)vis->vstart : 0;
  *count = pervertex ? (hsize_t)vis->nv : (rank ? 0 : 1);
  PetscFunctionReturn(0);
}

/* Creates /restart/slot0|1 with every dataset, both slots incomplete (step -1) */
PetscErrorCode FCRestartWriterCreate(MPI_Comm comm, hid_t file, PetscInt nbodies, FCBody bodies[],
                                     FCRestartWriter *writer)
{
  FCRestartWriter w;
  hid_t           g;

  PetscFunctionBegin;
  PetscCall(PetscNew(&w));
  PetscCallMPI(MPI_Comm_rank(comm, &w->rank));
  w->nbodies = nbodies;
  g          = H5Gcreate2(file, "restart", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  FCH5Check(g, "restart");
  for (int k = 0; k < 2; k++) {
    char      name[16];
    hsize_t   cdims[1] = {FC_RESTART_CONTACT};
    long long none     = -1;
    hid_t     sp       = H5Screate(H5S_SCALAR);
    PetscCall(PetscSNPrintf(name, sizeof(name), "slot%d", k));
    w->slot[k]      = H5Gcreate2(g, name, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    w->step[k]      = H5Dcreate2(w->slot[k], "step", H5T_STD_I64LE, sp, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    w->time[k]      = H5Dcreate2(w->slot[k], "time", H5T_IEEE_F64LE, sp, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    w->ncontacts[k] = H5Dcreate2(w->slot[k], "ncontacts", H5T_STD_I64LE, sp, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    H5Sclose(sp);
    {
      hsize_t three = 3;
      sp            = H5Screate_simple(1, &three, NULL);
      w->control[k] = H5Dcreate2(w->slot[k], "step_control", H5T_IEEE_F64LE, sp, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
      H5Sclose(sp);
    }
    FCH5Check(H5Dwrite(w->step[k], H5T_NATIVE_LLONG, H5S_ALL, H5S_ALL, H5P_DEFAULT, &none), "restart step");
    PetscCall(FCH5CreateRows(w->slot[k], "contacts", H5T_NATIVE_DOUBLE, 2, cdims, 256, &w->contacts[k]));
    PetscCall(PetscMalloc1(nbodies, &w->body[k]));
    for (PetscInt i = 0; i < nbodies; i++) {
      const char *bname;
      hsize_t     dims[2], start, count;
      hid_t       space;
      PetscCall(FCBodyGetName(bodies[i], &bname));
      PetscCall(StateRows(bodies[i], w->rank, &dims[0], &dims[1], &start, &count));
      space         = H5Screate_simple(2, dims, NULL);
      w->body[k][i] = H5Dcreate2(w->slot[k], bname, H5T_IEEE_F64LE, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
      FCH5Check(w->body[k][i], "restart body state");
      H5Sclose(space);
    }
  }
  H5Gclose(g);
  *writer = w;
  PetscFunctionReturn(0);
}

/* Marks the slot the next state goes to as incomplete (step -1); flushed with the frame before
   that state is written (src/io/output.c) */
PetscErrorCode FCRestartWriterBegin(FCRestartWriter w)
{
  long long none = -1;

  PetscFunctionBegin;
  FCH5Check(H5Dwrite(w->step[w->nwritten % 2], H5T_NATIVE_LLONG, H5S_ALL, H5S_ALL, H5P_DEFAULT, &none), "restart step");
  PetscFunctionReturn(0);
}

/* The state at the end of step `step` into the older slot: the step as -1, the bodies, the
   previous contacts, the time, and the step last (collective) */
PetscErrorCode FCRestartWriterWrite(FCRestartWriter w, PetscInt step, PetscReal t, const PetscReal control[3],
                                    PetscInt nbodies, FCBody bodies[], const FCContactSet *previous)
{
  PetscInt  k = w->nwritten++ % 2, nc = previous ? previous->n : 0;
  long long st      = step;
  double    tt      = t, *buf;
  hsize_t   dims[2] = {(hsize_t)nc, FC_RESTART_CONTACT};

  PetscFunctionBegin;
  /* each of the three stages is flushed before the next: HDF5 writes what a flush holds in no
     set order, so a slot marked complete on disk never holds a half-written state. The first
     stage, the step as -1, was written by FCRestartWriterBegin and flushed with the frame */
  for (PetscInt i = 0; i < nbodies; i++) {
    hid_t   fspace = H5Dget_space(w->body[k][i]), mspace;
    hsize_t rows, start[2] = {0, 0}, count[2];
    PetscCall(StateRows(bodies[i], w->rank, &rows, &count[1], &start[0], &count[0]));
    /* a single-row state is reported on every rank, written by rank 0 */
    PetscCall(PetscMalloc1((count[0] ? count[0] : 1) * count[1], &buf));
    PetscCall(FCBodyGetState(bodies[i], buf));
    if (count[0]) {
      H5Sselect_hyperslab(fspace, H5S_SELECT_SET, start, NULL, count, NULL);
      mspace = H5Screate_simple(2, count, NULL);
    } else {
      H5Sselect_none(fspace);
      mspace = H5Screate(H5S_NULL);
    }
    FCH5Check(H5Dwrite(w->body[k][i], H5T_NATIVE_DOUBLE, mspace, fspace, H5P_DEFAULT, buf), "restart state");
    H5Sclose(mspace);
    H5Sclose(fspace);
    PetscCall(PetscFree(buf));
  }
  { /* the dataset only grows (shrinking a chunked dataset in parallel HDF5 1.10 broke a later
       flush); its first ncontacts rows are this state's */
    hid_t   space = H5Dget_space(w->contacts[k]);
    hsize_t cur[2];
    H5Sget_simple_extent_dims(space, cur, NULL);
    H5Sclose(space);
    if (cur[0] < dims[0]) FCH5Check(H5Dset_extent(w->contacts[k], dims), "restart contacts");
  }
  PetscCall(PetscMalloc1(FC_RESTART_CONTACT * nc + 1, &buf));
  for (PetscInt j = 0; j < nc; j++) PackContact(&previous->c[j], &buf[FC_RESTART_CONTACT * j]);
  if (nc) {
    hid_t fspace = H5Dget_space(w->contacts[k]), mspace;
    if (w->rank == 0) {
      hsize_t start[2] = {0, 0};
      H5Sselect_hyperslab(fspace, H5S_SELECT_SET, start, NULL, dims, NULL);
      mspace = H5Screate_simple(2, dims, NULL);
    } else {
      H5Sselect_none(fspace);
      mspace = H5Screate(H5S_NULL);
    }
    FCH5Check(H5Dwrite(w->contacts[k], H5T_NATIVE_DOUBLE, mspace, fspace, H5P_DEFAULT, buf), "restart contacts");
    H5Sclose(mspace);
    H5Sclose(fspace);
  }
  PetscCall(PetscFree(buf));
  {
    long long n = nc;
    FCH5Check(H5Dwrite(w->ncontacts[k], H5T_NATIVE_LLONG, H5S_ALL, H5S_ALL, H5P_DEFAULT, &n), "restart ncontacts");
  }
  FCH5Check(H5Dwrite(w->time[k], H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, &tt), "restart time");
  {
    double cv[3] = {control[0], control[1], control[2]};
    FCH5Check(H5Dwrite(w->control[k], H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, cv), "restart step control");
  }
  FCH5Check(H5Fflush(w->slot[k], H5F_SCOPE_GLOBAL), "flush of the restart state");
  FCH5Check(H5Dwrite(w->step[k], H5T_NATIVE_LLONG, H5S_ALL, H5S_ALL, H5P_DEFAULT, &st), "restart step");
  PetscFunctionReturn(0);
}

/* The restart state (restart.c), written after the frame of the same step has been written and
   flushed, then flushed itself: the newest complete restart slot is never ahead of the frames and
   step rows, whatever write fails */
PetscErrorCode FCOutputWriteRestart(FCOutput out, PetscInt step, PetscReal t, const PetscReal control[3],
                                    PetscInt nbodies, FCBody bodies[], const FCContactSet *previous)
{
  PetscFunctionBegin;
  PetscCall(FCPhaseBegin(FC_PHASE_OUTPUT));
  PetscCall(FCRestartWriterWrite(out->restart, step, t, control, nbodies, bodies, previous));
  FCH5Check(H5Fflush(out->file, H5F_SCOPE_GLOBAL), "flush of the restart state");
  if (out->rank == 0) { /* the growth of HDF5's allocation over one output step: the next reservation
                           (the file itself is longer, by what is reserved: reserve.c) */
    haddr_t eoa  = 0;
    size_t  size = H5Fget_eoa(out->file, &eoa) >= 0 ? (size_t)eoa : 0;
    if (out->lastsize && size > out->lastsize) out->growth = PetscMax(out->growth, size - out->lastsize);
    out->lastsize = size;
  }
  PetscCall(FCPhaseEnd(FC_PHASE_OUTPUT));
  PetscFunctionReturn(0);
}

PetscErrorCode FCRestartWriterDestroy(FCRestartWriter *writer)
{
  FCRestartWriter w = *writer;

  PetscFunctionBegin;
  if (!w) PetscFunctionReturn(0);
  for (int k = 0; k < 2; k++) {
    if (!FCH5FailedInside()) { /* after a failed write nothing is closed (output.c, FCOutputDestroy) */
      for (PetscInt i = 0; i < w->nbodies; i++) H5Dclose(w->body[k][i]);
      H5Dclose(w->step[k]);
      H5Dclose(w->time[k]);
      H5Dclose(w->control[k]);
      H5Dclose(w->contacts[k]);
      H5Dclose(w->ncontacts[k]);
      H5Gclose(w->slot[k]);
    }
    PetscCall(PetscFree(w->body[k]));
  }
  PetscCall(PetscFree(*writer));
  PetscFunctionReturn(0);
}

/* ---------------------------------------------------------------------------------------------
   Reading
   --------------------------------------------------------------------------------------------- */
static PetscErrorCode ReadAll(hid_t d, const char what[], const char file[], hsize_t rows, hsize_t cols, double *buf)
{
  hid_t   space   = H5Dget_space(d);
  hsize_t dims[2] = {0, 0};
  int     nd      = H5Sget_simple_extent_dims(space, dims, NULL);

  PetscFunctionBegin;
  H5Sclose(space);
  PetscCheck(
      nd == 2 && dims[0] == rows && dims[1] == cols, PETSC_COMM_SELF, PETSC_ERR_USER_INPUT,
      "Restart file '%s': %s has shape (%llu, %llu), this scene needs (%llu, %llu) (-restart needs the same scene)",
      file, what, (unsigned long long)dims[0], (unsigned long long)dims[1], (unsigned long long)rows,
      (unsigned long long)cols);
  PetscCheck(H5Dread(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, buf) >= 0, PETSC_COMM_SELF,
             PETSC_ERR_FILE_READ, "Restart file '%s': cannot read %s", file, what);
  PetscFunctionReturn(0);
}

/* Vertices are matched by their reference coordinates, rounded to 1e-9 of the body's size: the
   global vertex numbering depends on the partition, which may differ between the two runs */
typedef struct {
  long long key[3];
  PetscInt  row;
} VertexKey;

static int CompareVertexKey(const void *a, const void *b)
{
  const VertexKey *x = (const VertexKey *)a, *y = (const VertexKey *)b;
  for (int d = 0; d < 3; d++)
    if (x->key[d] != y->key[d]) return x->key[d] < y->key[d] ? -1 : 1;
  return 0;
}

static void MakeKey(const double X[3], double scale, VertexKey *k)
{
  for (int d = 0; d < 3; d++) k->key[d] = llround(X[d] / scale);
}

/* The state rows (file order) of this rank's vertices (visual order) */
static PetscErrorCode MatchVertices(FCBody b, const char file[], hsize_t V, hsize_t cols, const double *ref,
                                    const double *state, double *mine)
{
  const FCBodyVisual *vis;
  const char         *name;
  VertexKey          *keys;
  double              lo[3] = {PETSC_MAX_REAL, PETSC_MAX_REAL, PETSC_MAX_REAL},
         hi[3] = {-PETSC_MAX_REAL, -PETSC_MAX_REAL, -PETSC_MAX_REAL}, scale = 0.0;

  PetscFunctionBegin;
  PetscCall(FCBodyGetVisual(b, &vis));
  PetscCall(FCBodyGetName(b, &name));
  for (hsize_t r = 0; r < V; r++)
    for (int d = 0; d < 3; d++) {
      lo[d] = PetscMin(lo[d], ref[3 * r + d]);
      hi[d] = PetscMax(hi[d], ref[3 * r + d]);
    }
  for (int d = 0; d < 3; d++) scale = PetscMax(scale, hi[d] - lo[d]);
  scale = 1e-9 * PetscMax(scale, PETSC_SMALL);
  PetscCall(PetscMalloc1(V, &keys));
  for (hsize_t r = 0; r < V; r++) {
    MakeKey(&ref[3 * r], scale, &keys[r]);
    keys[r].row = (PetscInt)r;
  }
  qsort(keys, V, sizeof(VertexKey), CompareVertexKey);
  for (PetscInt i = 0; i < vis->nv; i++) {
    VertexKey k, *f;
    MakeKey(&vis->reference[3 * i], scale, &k);
    f = (VertexKey *)bsearch(&k, keys, V, sizeof(VertexKey), CompareVertexKey);
    PetscCheck(
        f, PETSC_COMM_SELF, PETSC_ERR_USER_INPUT,
        "Restart file '%s': body '%s' has no vertex at (%g, %g, %g) (-restart needs the same mesh and placement)", file,
        name, (double)vis->reference[3 * i], (double)vis->reference[3 * i + 1], (double)vis->reference[3 * i + 2]);
    for (hsize_t c = 0; c < cols; c++) mine[cols * i + c] = state[cols * f->row + c];
  }
  PetscCall(PetscFree(keys));
  PetscFunctionReturn(0);
}

static PetscErrorCode SlotStep(hid_t f, int k, long long *step)
{
  char  path[32];
  hid_t d;

  PetscFunctionBegin;
  *step = -1;
  PetscCall(PetscSNPrintf(path, sizeof(path), "/restart/slot%d/step", k));
  d = H5Dopen2(f, path, H5P_DEFAULT);
  if (d >= 0) {
    if (H5Dread(d, H5T_NATIVE_LLONG, H5S_ALL, H5S_ALL, H5P_DEFAULT, step) < 0) *step = -1;
    H5Dclose(d);
  }
  PetscFunctionReturn(0);
}

/* The step control's state of a slot (none in a file written without step control: zeros, the requested step) */
static PetscErrorCode ReadStepControl(MPI_Comm comm, const char file[], const char path[], hid_t g,
                                      PetscReal control[3])
{
  double cv[3] = {0.0, 0.0, 0.0};

  PetscFunctionBegin;
  if (H5Lexists(g, "step_control", H5P_DEFAULT) > 0) {
    hid_t d = H5Dopen2(g, "step_control", H5P_DEFAULT);
    PetscCheck(d >= 0 && H5Dread(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, cv) >= 0, comm,
               PETSC_ERR_FILE_READ, "Restart file '%s': cannot read %s/step_control", file, path);
    H5Dclose(d);
  }
  for (int i = 0; i < 3; i++) control[i] = cv[i];
  PetscFunctionReturn(0);
}

PetscErrorCode FCRestartLoad(MPI_Comm comm, const char file[], PetscInt nbodies, FCBody bodies[],
                             FCContactSet *previous, PetscInt *step, PetscReal *t, PetscReal control[3])
{
  hid_t     f, g, d;
  long long s0, s1, st;
  int       k;
  char      path[32];
  double    tt;
  int       ok;

  PetscFunctionBegin;
  H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
  f  = H5Fopen(file, H5F_ACC_RDONLY, H5P_DEFAULT);
  ok = f >= 0;
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &ok, 1, MPI_INT, MPI_MIN, comm));
  PetscCheck(ok, comm, PETSC_ERR_USER_INPUT, "Cannot open the restart file '%s' (-restart)", file);
  PetscCall(SlotStep(f, 0, &s0));
  PetscCall(SlotStep(f, 1, &s1));
  PetscCheck(
      s0 >= 0 || s1 >= 0, comm, PETSC_ERR_USER_INPUT,
      "Restart file '%s' holds no complete restart state (/restart/slot0|1; written by fecontact at every output "
      "step)",
      file);
  k  = s1 > s0 ? 1 : 0;
  st = k ? s1 : s0;
  PetscCall(PetscSNPrintf(path, sizeof(path), "/restart/slot%d", k));
  g = H5Gopen2(f, path, H5P_DEFAULT);
  d = H5Dopen2(g, "time", H5P_DEFAULT);
  PetscCheck(d >= 0 && H5Dread(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, &tt) >= 0, comm,
             PETSC_ERR_FILE_READ, "Restart file '%s': cannot read %s/time", file, path);
  H5Dclose(d);
  PetscCall(ReadStepControl(comm, file, path, g, control));
  for (PetscInt i = 0; i < nbodies; i++) {
    FCBody              b = bodies[i];
    const FCBodyVisual *vis;
    const char         *name;
    PetscInt            c;
    PetscBool           pervertex;
    hsize_t             rows, cols;
    double             *buf;
    PetscCall(FCBodyGetStateLayout(b, &c, &pervertex));
    PetscCall(FCBodyGetVisual(b, &vis));
    PetscCall(FCBodyGetName(b, &name));
    rows = pervertex ? (hsize_t)vis->nv_global : 1;
    cols = (hsize_t)c;
    d    = H5Dopen2(g, name, H5P_DEFAULT);
    PetscCheck(d >= 0, comm, PETSC_ERR_USER_INPUT,
               "Restart file '%s' has no state of body '%s' (-restart needs the same scene)", file, name);
    PetscCall(PetscMalloc1(rows * cols, &buf));
    PetscCall(ReadAll(d, name, file, rows, cols, buf));
    H5Dclose(d);
    if (pervertex) {
      char    rpath[PETSC_MAX_PATH_LEN];
      double *ref, *mine;
      PetscCall(PetscSNPrintf(rpath, sizeof(rpath), "/bodies/%s/mesh/reference", name));
      d = H5Dopen2(f, rpath, H5P_DEFAULT);
      PetscCheck(d >= 0, comm, PETSC_ERR_USER_INPUT, "Restart file '%s' has no %s", file, rpath);
      PetscCall(PetscMalloc2(3 * rows, &ref, cols * vis->nv + 1, &mine));
      PetscCall(ReadAll(d, rpath, file, rows, 3, ref));
      H5Dclose(d);
      PetscCall(MatchVertices(b, file, rows, cols, ref, buf, mine));
      PetscCall(FCBodySetState(b, mine));
      PetscCall(PetscFree2(ref, mine));
    } else
      PetscCall(FCBodySetState(b, buf));
    PetscCall(PetscFree(buf));
  }
  { /* the previous step's contacts: the warm start of the contact solver */
    hid_t     space;
    hsize_t   dims[2] = {0, 0};
    double   *buf;
    long long n = 0;
    d           = H5Dopen2(g, "ncontacts", H5P_DEFAULT);
    PetscCheck(d >= 0 && H5Dread(d, H5T_NATIVE_LLONG, H5S_ALL, H5S_ALL, H5P_DEFAULT, &n) >= 0, comm,
               PETSC_ERR_FILE_READ, "Restart file '%s': cannot read %s/ncontacts", file, path);
    H5Dclose(d);
    d = H5Dopen2(g, "contacts", H5P_DEFAULT);
    PetscCheck(d >= 0, comm, PETSC_ERR_FILE_READ, "Restart file '%s': no %s/contacts", file, path);
    space = H5Dget_space(d);
    H5Sget_simple_extent_dims(space, dims, NULL);
    H5Sclose(space);
    PetscCheck((hsize_t)n <= dims[0], comm, PETSC_ERR_FILE_READ,
               "Restart file '%s': %s/contacts is shorter than ncontacts", file, path);
    PetscCall(PetscMalloc1(dims[0] * FC_RESTART_CONTACT + 1, &buf));
    if (dims[0]) PetscCall(ReadAll(d, "contacts", file, dims[0], FC_RESTART_CONTACT, buf));
    H5Dclose(d);
    dims[0] = (hsize_t)n;
    PetscCall(FCContactSetReset(previous));
    for (hsize_t j = 0; j < dims[0]; j++) {
      FCContact c;
      UnpackContact(&buf[FC_RESTART_CONTACT * j], &c);
      PetscCall(FCContactSetAdd(previous, &c));
    }
    PetscCall(PetscFree(buf));
  }
  H5Gclose(g);
  H5Fclose(f);
  *step = (PetscInt)st;
  *t    = tt;
  PetscFunctionReturn(0);
}
