/* -restart file.h5: the state of the newest complete restart slot of an earlier run's output
   (src/io/output.c writes it at every output step) is read into the bodies, the previous step's
   contacts (the warm start of the contact solver) and the step counter, so that the run continues
   as if it had not stopped. Every rank reads the file (read-only, serial HDF5) and takes its part. */
#include "../fcimpl.h"
#include <hdf5.h>
#include <math.h>

/* The record of a contact in /restart/slot0|1/contacts: what the next step's warm start reads
   (FCContactSetFind: pair and key; FCContactPreviousForce: frame and force) */
void FCRestartPackContact(const FCContact *c, double r[FC_RESTART_CONTACT])
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
static PetscErrorCode MatchVertices(FCBody b, const char file[], hsize_t V, const double *ref, const double *state,
                                    double *mine)
{
  const FCBodyVisual *vis;
  VertexKey          *keys;
  double              lo[3] = {PETSC_MAX_REAL, PETSC_MAX_REAL, PETSC_MAX_REAL},
         hi[3] = {-PETSC_MAX_REAL, -PETSC_MAX_REAL, -PETSC_MAX_REAL}, scale = 0.0;

  PetscFunctionBegin;
  PetscCall(FCBodyGetVisual(b, &vis));
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
        b->name, (double)vis->reference[3 * i], (double)vis->reference[3 * i + 1], (double)vis->reference[3 * i + 2]);
    for (int c = 0; c < 6; c++) mine[6 * i + c] = state[6 * f->row + c];
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

PetscErrorCode FCRestartLoad(MPI_Comm comm, const char file[], PetscInt nbodies, FCBody bodies[],
                             FCContactSet *previous, PetscInt *step, PetscReal *t)
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
  for (PetscInt i = 0; i < nbodies; i++) {
    FCBody    b = bodies[i];
    PetscBool fem;
    hsize_t   rows, cols;
    double   *buf;
    PetscCall(PetscStrcmp(b->type, FCBODYFEM, &fem));
    rows = fem ? (hsize_t)b->visual.nv_global : 1;
    cols = fem ? 6 : 13;
    d    = H5Dopen2(g, b->name, H5P_DEFAULT);
    PetscCheck(d >= 0, comm, PETSC_ERR_USER_INPUT,
               "Restart file '%s' has no state of body '%s' (-restart needs the same scene)", file, b->name);
    PetscCall(PetscMalloc1(rows * cols, &buf));
    PetscCall(ReadAll(d, b->name, file, rows, cols, buf));
    H5Dclose(d);
    if (fem) {
      char    rpath[PETSC_MAX_PATH_LEN];
      double *ref, *mine;
      PetscCall(PetscSNPrintf(rpath, sizeof(rpath), "/bodies/%s/mesh/reference", b->name));
      d = H5Dopen2(f, rpath, H5P_DEFAULT);
      PetscCheck(d >= 0, comm, PETSC_ERR_USER_INPUT, "Restart file '%s' has no %s", file, rpath);
      PetscCall(PetscMalloc2(3 * rows, &ref, 6 * b->visual.nv + 1, &mine));
      PetscCall(ReadAll(d, rpath, file, rows, 3, ref));
      H5Dclose(d);
      PetscCall(MatchVertices(b, file, rows, ref, buf, mine));
      PetscCall((*b->ops.setstate)(b, mine));
      PetscCall(PetscFree2(ref, mine));
    } else
      PetscCall((*b->ops.setstate)(b, buf));
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
