/* HDF5 output of a run (schema in docs/output.md). Per-step rows are buffered and written,
   with the frame, at every output step; the file is flushed after each, so a run that stops
   keeps every completed output step readable. Parallel HDF5 (MPI-IO): each rank writes the
   positions of the vertices it owns; rank 0 writes the per-step rows. */
#include "../fcimpl.h"
#include <hdf5.h>
#include <time.h>

#define FC_MAX_BODIES 256

typedef struct {
  hid_t group, centroid, rotation, energy, positions;
} BodyOut;

struct _p_FCOutput {
  MPI_Comm    comm;
  PetscMPIInt rank;
  char        filename[PETSC_MAX_PATH_LEN], xdmfname[PETSC_MAX_PATH_LEN];
  hid_t       file, time, step, energy, denergy, timing[FC_PHASE_NUM], ftime, fstep;
  PetscInt    nbodies;
  FCBody     *bodies;
  BodyOut    *bo;
  /* rows buffered since the last flush (rank 0) */
  PetscInt  nrows, maxrows;
  double   *rtime, *renergy, *rtiming, *rbody; /* rbody: per row, per body: centroid 3, quaternion 4, energy 3 */
  PetscInt *rstep;
  double    elast; /* total energy of the last recorded step (initial energy before step 1) */
  PetscInt  nframes, xdmfwritten;
  /* contacts (scenes with contact pairs only) */
  PetscBool contacts;
  hid_t     c_offset, c_bodies, c_point, c_normal, c_force, c_gap, c_gapend, c_state;
  hid_t     s_contacts, s_rows, s_sweeps, s_residual, s_maxpen, s_newton, s_violation, s_rmspen, s_compl, s_cone;
  long long ctotal;             /* contacts recorded so far */
  PetscInt  nc, maxc, ns, maxs; /* buffered contact records and per-step rows */
  struct {
    long long bodies[2], state;
    double    point[3], normal[3], force[3], gap, gap_end;
  } * cbuf;
  struct {
    long long         contacts, rows, sweeps, offset, newton;
    double            residual;
    FCContactMeasures m;
  } * sbuf;
  double  *frametimes;
  PetscInt maxframes;
  /* restart state (docs/output.md): two slots written alternately, the step last, so that a run
     killed while writing one still has the other */
  hid_t    xslot[2], xstep[2], xtime[2], xcontacts[2], xncontacts[2], *xbody[2];
  PetscInt nrestart;
};

#define FCH5Check(call, msg)                                                                                           \
  do {                                                                                                                 \
    if ((call) < 0) SETERRQ(PETSC_COMM_SELF, PETSC_ERR_LIB, "HDF5 failed: %s", msg);                                   \
  } while (0)

/* An extendible dataset of rows of shape dims[1..rank-1], chunked by row */
static PetscErrorCode CreateRows(hid_t loc, const char name[], hid_t type, int rank, const hsize_t rowdims[],
                                 hsize_t chunkrows, hid_t *dset)
{
  hsize_t dims[3] = {0, 0, 0}, maxdims[3] = {H5S_UNLIMITED, 0, 0}, chunk[3] = {chunkrows, 0, 0};
  hid_t   space, plist;

  PetscFunctionBegin;
  for (int i = 1; i < rank; i++) dims[i] = maxdims[i] = chunk[i] = rowdims[i - 1];
  space = H5Screate_simple(rank, dims, maxdims);
  plist = H5Pcreate(H5P_DATASET_CREATE);
  FCH5Check(H5Pset_chunk(plist, rank, chunk), "chunk");
  *dset = H5Dcreate2(loc, name, type, space, H5P_DEFAULT, plist, H5P_DEFAULT);
  FCH5Check(*dset, name);
  H5Pclose(plist);
  H5Sclose(space);
  PetscFunctionReturn(0);
}

/* Append n rows (collective extend); rank 0 writes data, the others take part with nothing */
static PetscErrorCode AppendRows(FCOutput out, hid_t dset, hid_t memtype, hsize_t n, const void *data)
{
  hid_t   fspace, mspace;
  int     rank;
  hsize_t dims[3], start[3] = {0, 0, 0}, count[3];

  PetscFunctionBegin;
  if (!n) PetscFunctionReturn(0);
  fspace = H5Dget_space(dset);
  rank   = H5Sget_simple_extent_ndims(fspace);
  H5Sget_simple_extent_dims(fspace, dims, NULL);
  H5Sclose(fspace);
  start[0] = dims[0];
  dims[0] += n;
  FCH5Check(H5Dset_extent(dset, dims), "extend");
  fspace = H5Dget_space(dset);
  for (int i = 0; i < rank; i++) count[i] = i ? dims[i] : n;
  if (out->rank == 0) {
    H5Sselect_hyperslab(fspace, H5S_SELECT_SET, start, NULL, count, NULL);
    mspace = H5Screate_simple(rank, count, NULL);
  } else {
    H5Sselect_none(fspace);
    mspace = H5Screate(H5S_NULL);
    H5Sselect_none(mspace);
  }
  FCH5Check(H5Dwrite(dset, memtype, mspace, fspace, H5P_DEFAULT, data), "write rows");
  H5Sclose(mspace);
  H5Sclose(fspace);
  PetscFunctionReturn(0);
}

/* A fixed-size dataset (rows x cols) written by ranges: each rank its [start, start + n) rows */
static PetscErrorCode WriteDistributed(hid_t loc, const char name[], hid_t filetype, hid_t memtype, hsize_t rows,
                                       hsize_t cols, hsize_t start, hsize_t n, const void *data)
{
  hsize_t dims[2] = {rows, cols}, s[2] = {start, 0}, c[2] = {n, cols};
  hid_t   fspace = H5Screate_simple(2, dims, NULL), dset, mspace;

  PetscFunctionBegin;
  dset = H5Dcreate2(loc, name, filetype, fspace, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  FCH5Check(dset, name);
  if (n) {
    H5Sselect_hyperslab(fspace, H5S_SELECT_SET, s, NULL, c, NULL);
    mspace = H5Screate_simple(2, c, NULL);
  } else {
    H5Sselect_none(fspace);
    mspace = H5Screate(H5S_NULL);
  }
  FCH5Check(H5Dwrite(dset, memtype, mspace, fspace, H5P_DEFAULT, data), name);
  H5Sclose(mspace);
  H5Sclose(fspace);
  H5Dclose(dset);
  PetscFunctionReturn(0);
}

static PetscErrorCode AttrString(hid_t loc, const char name[], const char value[])
{
  hid_t type = H5Tcopy(H5T_C_S1), space = H5Screate(H5S_SCALAR), attr;

  PetscFunctionBegin;
  H5Tset_size(type, strlen(value) + 1);
  attr = H5Acreate2(loc, name, type, space, H5P_DEFAULT, H5P_DEFAULT);
  FCH5Check(attr, name);
  FCH5Check(H5Awrite(attr, type, value), name);
  H5Aclose(attr);
  H5Sclose(space);
  H5Tclose(type);
  PetscFunctionReturn(0);
}

static PetscErrorCode AttrReals(hid_t loc, const char name[], hsize_t n, const double v[])
{
  hid_t space = H5Screate_simple(1, &n, NULL), attr;

  PetscFunctionBegin;
  attr = H5Acreate2(loc, name, H5T_NATIVE_DOUBLE, space, H5P_DEFAULT, H5P_DEFAULT);
  FCH5Check(attr, name);
  FCH5Check(H5Awrite(attr, H5T_NATIVE_DOUBLE, v), name);
  H5Aclose(attr);
  H5Sclose(space);
  PetscFunctionReturn(0);
}

static PetscErrorCode AttrInt(hid_t loc, const char name[], long long v)
{
  hid_t space = H5Screate(H5S_SCALAR), attr;

  PetscFunctionBegin;
  attr = H5Acreate2(loc, name, H5T_NATIVE_LLONG, space, H5P_DEFAULT, H5P_DEFAULT);
  FCH5Check(attr, name);
  FCH5Check(H5Awrite(attr, H5T_NATIVE_LLONG, &v), name);
  H5Aclose(attr);
  H5Sclose(space);
  PetscFunctionReturn(0);
}

PetscErrorCode FCOutputCreate(MPI_Comm comm, const char filename[], FCOutput *output)
{
  FCOutput out;
  hid_t    fapl;
  size_t   len;
  int      ok;

  PetscFunctionBegin;
  PetscCall(PetscNew(&out));
  out->comm = comm;
  PetscCallMPI(MPI_Comm_rank(comm, &out->rank));
  PetscCall(PetscStrncpy(out->filename, filename, sizeof(out->filename)));
  PetscCall(PetscStrlen(filename, &len));
  PetscCall(PetscStrncpy(out->xdmfname, filename, sizeof(out->xdmfname)));
  if (len > 3 && !strcmp(filename + len - 3, ".h5")) out->xdmfname[len - 3] = 0;
  PetscCall(PetscStrlcat(out->xdmfname, ".xmf", sizeof(out->xdmfname)));
  fapl = H5Pcreate(H5P_FILE_ACCESS);
  H5Pset_fapl_mpio(fapl, comm, MPI_INFO_NULL);
  H5Pset_libver_bounds(fapl, H5F_LIBVER_V18, H5F_LIBVER_LATEST);
  H5Eset_auto2(H5E_DEFAULT, NULL, NULL); /* our own messages name the file */
  out->file = H5Fcreate(filename, H5F_ACC_TRUNC, H5P_DEFAULT, fapl);
  H5Pclose(fapl);
  ok = out->file >= 0;
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &ok, 1, MPI_INT, MPI_MIN, comm));
  if (!ok) {
    if (out->file >= 0) H5Fclose(out->file);
    PetscCall(PetscFree(out));
    SETERRQ(comm, PETSC_ERR_FILE_OPEN,
            "Cannot create output file '%s' (-output_file): check that its directory exists and is writable", filename);
  }
  *output = out;
  PetscFunctionReturn(0);
}

/* /restart/slot0 and slot1: per body a dataset of its state (FE: V x 6, u and v per vertex in the
   order of mesh/reference; rigid, kinematic: 13 values x, q, v, w), the previous step's contacts
   (warm start of the solver) and the step they belong to (-1: being written) */
static PetscErrorCode CreateRestart(FCOutput out, PetscInt nbodies, FCBody bodies[])
{
  hid_t g = H5Gcreate2(out->file, "restart", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);

  PetscFunctionBegin;
  for (int k = 0; k < 2; k++) {
    char      name[16];
    hsize_t   cdims[1] = {FC_RESTART_CONTACT};
    long long none     = -1;
    hid_t     sp       = H5Screate(H5S_SCALAR);
    PetscCall(PetscSNPrintf(name, sizeof(name), "slot%d", k));
    out->xslot[k] = H5Gcreate2(g, name, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    out->xstep[k] = H5Dcreate2(out->xslot[k], "step", H5T_STD_I64LE, sp, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    out->xtime[k] = H5Dcreate2(out->xslot[k], "time", H5T_IEEE_F64LE, sp, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    out->xncontacts[k] =
        H5Dcreate2(out->xslot[k], "ncontacts", H5T_STD_I64LE, sp, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    H5Sclose(sp);
    FCH5Check(H5Dwrite(out->xstep[k], H5T_NATIVE_LLONG, H5S_ALL, H5S_ALL, H5P_DEFAULT, &none), "restart step");
    PetscCall(CreateRows(out->xslot[k], "contacts", H5T_NATIVE_DOUBLE, 2, cdims, 256, &out->xcontacts[k]));
    PetscCall(PetscMalloc1(nbodies, &out->xbody[k]));
    for (PetscInt i = 0; i < nbodies; i++) {
      PetscBool fem;
      hsize_t   dims[2];
      hid_t     space;
      PetscCall(PetscStrcmp(bodies[i]->type, FCBODYFEM, &fem));
      dims[0] = fem ? (hsize_t)bodies[i]->visual.nv_global : 1;
      dims[1] = fem ? 6 : 13;
      space   = H5Screate_simple(2, dims, NULL);
      out->xbody[k][i] =
          H5Dcreate2(out->xslot[k], bodies[i]->name, H5T_IEEE_F64LE, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
      FCH5Check(out->xbody[k][i], "restart body state");
      H5Sclose(space);
    }
  }
  H5Gclose(g);
  PetscFunctionReturn(0);
}

/* The state at the end of step `step` (before the frame's flush): bodies, previous contacts, and
   the step, written last */
PetscErrorCode FCOutputWriteRestart(FCOutput out, PetscInt step, PetscReal t, PetscInt nbodies, FCBody bodies[],
                                    const FCContactSet *previous)
{
  PetscInt  k = out->nrestart++ % 2, nc = previous ? previous->n : 0;
  long long none = -1, st = step;
  double    tt      = t, *buf;
  hsize_t   dims[2] = {(hsize_t)nc, FC_RESTART_CONTACT};

  PetscFunctionBegin;
  FCH5Check(H5Dwrite(out->xstep[k], H5T_NATIVE_LLONG, H5S_ALL, H5S_ALL, H5P_DEFAULT, &none), "restart step");
  for (PetscInt i = 0; i < nbodies; i++) {
    PetscBool fem;
    hid_t     fspace   = H5Dget_space(out->xbody[k][i]), mspace;
    hsize_t   start[2] = {0, 0}, count[2];
    PetscCall(PetscStrcmp(bodies[i]->type, FCBODYFEM, &fem));
    count[0] = fem ? (hsize_t)bodies[i]->visual.nv : (out->rank ? 0 : 1);
    count[1] = fem ? 6 : 13;
    start[0] = fem ? (hsize_t)bodies[i]->visual.vstart : 0;
    PetscCall(PetscMalloc1(count[0] * count[1] + 13, &buf));
    PetscCall((*bodies[i]->ops.getstate)(bodies[i], buf));
    if (count[0]) {
      H5Sselect_hyperslab(fspace, H5S_SELECT_SET, start, NULL, count, NULL);
      mspace = H5Screate_simple(2, count, NULL);
    } else {
      H5Sselect_none(fspace);
      mspace = H5Screate(H5S_NULL);
    }
    FCH5Check(H5Dwrite(out->xbody[k][i], H5T_NATIVE_DOUBLE, mspace, fspace, H5P_DEFAULT, buf), "restart state");
    H5Sclose(mspace);
    H5Sclose(fspace);
    PetscCall(PetscFree(buf));
  }
  { /* the dataset only grows (shrinking a chunked dataset in parallel HDF5 1.10 broke a later
       flush); its first ncontacts rows are this state's */
    hid_t   space = H5Dget_space(out->xcontacts[k]);
    hsize_t cur[2];
    H5Sget_simple_extent_dims(space, cur, NULL);
    H5Sclose(space);
    if (cur[0] < dims[0]) FCH5Check(H5Dset_extent(out->xcontacts[k], dims), "restart contacts");
  }
  PetscCall(PetscMalloc1(FC_RESTART_CONTACT * nc + 1, &buf));
  for (PetscInt j = 0; j < nc; j++) { FCRestartPackContact(&previous->c[j], &buf[FC_RESTART_CONTACT * j]); }
  if (nc) {
    hid_t fspace = H5Dget_space(out->xcontacts[k]), mspace;
    if (out->rank == 0) {
      hsize_t start[2] = {0, 0};
      H5Sselect_hyperslab(fspace, H5S_SELECT_SET, start, NULL, dims, NULL);
      mspace = H5Screate_simple(2, dims, NULL);
    } else {
      H5Sselect_none(fspace);
      mspace = H5Screate(H5S_NULL);
    }
    FCH5Check(H5Dwrite(out->xcontacts[k], H5T_NATIVE_DOUBLE, mspace, fspace, H5P_DEFAULT, buf), "restart contacts");
    H5Sclose(mspace);
    H5Sclose(fspace);
  }
  PetscCall(PetscFree(buf));
  {
    long long n = nc;
    FCH5Check(H5Dwrite(out->xncontacts[k], H5T_NATIVE_LLONG, H5S_ALL, H5S_ALL, H5P_DEFAULT, &n), "restart ncontacts");
  }
  FCH5Check(H5Dwrite(out->xtime[k], H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, &tt), "restart time");
  FCH5Check(H5Dwrite(out->xstep[k], H5T_NATIVE_LLONG, H5S_ALL, H5S_ALL, H5P_DEFAULT, &st), "restart step");
  PetscFunctionReturn(0);
}

PetscErrorCode FCOutputWriteHeader(FCOutput out, PetscInt nbodies, FCBody bodies[], PetscReal h, PetscInt nsteps,
                                   PetscInt every, PetscBool contacts)
{
  hid_t  g, gt, gb, gf;
  char  *opts;
  size_t nrow;

  PetscFunctionBegin;
  out->nbodies = nbodies;
  out->bodies  = bodies;
  PetscCall(PetscCalloc1(nbodies, &out->bo));
  PetscCall(PetscOptionsGetAll(NULL, &opts));
  PetscCall(AttrString(out->file, "options", opts));
  PetscCall(PetscFree(opts));
  PetscCall(AttrString(out->file, "fecontact_version", FECONTACT_VERSION));
  {
    PetscMPIInt size;
    char        date[64];
    time_t      now = time(NULL);
    PetscCallMPI(MPI_Comm_size(out->comm, &size));
    PetscCall(AttrInt(out->file, "mpi_ranks", size));
    strftime(date, sizeof(date), "%Y-%m-%dT%H:%M:%SZ", gmtime(&now));
    PetscCallMPI(MPI_Bcast(date, sizeof(date), MPI_CHAR, 0, out->comm));
    PetscCall(AttrString(out->file, "created", date));
  }
  {
    double hv    = h;
    hid_t  space = H5Screate(H5S_SCALAR),
          attr   = H5Acreate2(out->file, "time_step", H5T_NATIVE_DOUBLE, space, H5P_DEFAULT, H5P_DEFAULT);
    FCH5Check(H5Awrite(attr, H5T_NATIVE_DOUBLE, &hv), "time_step");
    H5Aclose(attr);
    H5Sclose(space);
    PetscCall(AttrInt(out->file, "time_steps", nsteps));
    PetscCall(AttrInt(out->file, "output_every", every));
  }
  out->elast = 0.0; /* the total energy at t = 0: the reference of /steps/energy_change */
  for (PetscInt i = 0; i < nbodies; i++) {
    FCEnergy E;
    PetscCall(FCBodyGetEnergy(bodies[i], &E));
    out->elast += E.kinetic + E.elastic + E.gravity;
  }
  {
    PetscReal e0 = out->elast;
    PetscCall(AttrReals(out->file, "initial_energy", 1, &e0));
  }
  g = H5Gcreate2(out->file, "steps", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  PetscCall(CreateRows(g, "time", H5T_NATIVE_DOUBLE, 1, NULL, 256, &out->time));
  PetscCall(CreateRows(g, "step", H5T_NATIVE_LLONG, 1, NULL, 256, &out->step));
  PetscCall(CreateRows(g, "energy", H5T_NATIVE_DOUBLE, 1, NULL, 256, &out->energy));
  PetscCall(CreateRows(g, "energy_change", H5T_NATIVE_DOUBLE, 1, NULL, 256, &out->denergy));
  gt = H5Gcreate2(g, "timing", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  for (int p = 0; p < FC_PHASE_NUM; p++)
    PetscCall(CreateRows(gt, FCPhaseNames[p], H5T_NATIVE_DOUBLE, 1, NULL, 256, &out->timing[p]));
  H5Gclose(gt);
  H5Gclose(g);
  if (contacts) {
    hid_t gc         = H5Gcreate2(out->file, "contacts", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
          gs         = H5Gopen2(out->file, "steps", H5P_DEFAULT);
    hsize_t   two[1] = {2}, three[1] = {3};
    long long zero = 0;
    out->contacts  = PETSC_TRUE;
    PetscCall(CreateRows(gc, "offset", H5T_NATIVE_LLONG, 1, NULL, 256, &out->c_offset));
    PetscCall(CreateRows(gc, "bodies", H5T_NATIVE_LLONG, 2, two, 1024, &out->c_bodies));
    PetscCall(CreateRows(gc, "point", H5T_NATIVE_DOUBLE, 2, three, 1024, &out->c_point));
    PetscCall(CreateRows(gc, "normal", H5T_NATIVE_DOUBLE, 2, three, 1024, &out->c_normal));
    PetscCall(CreateRows(gc, "force", H5T_NATIVE_DOUBLE, 2, three, 1024, &out->c_force));
    PetscCall(CreateRows(gc, "gap", H5T_NATIVE_DOUBLE, 1, NULL, 1024, &out->c_gap));
    PetscCall(CreateRows(gc, "gap_end", H5T_NATIVE_DOUBLE, 1, NULL, 1024, &out->c_gapend));
    PetscCall(CreateRows(gc, "state", H5T_NATIVE_LLONG, 1, NULL, 1024, &out->c_state));
    PetscCall(CreateRows(gs, "contacts", H5T_NATIVE_LLONG, 1, NULL, 256, &out->s_contacts));
    PetscCall(CreateRows(gs, "constraint_rows", H5T_NATIVE_LLONG, 1, NULL, 256, &out->s_rows));
    PetscCall(CreateRows(gs, "pgs_iterations", H5T_NATIVE_LLONG, 1, NULL, 256, &out->s_sweeps));
    PetscCall(CreateRows(gs, "residual", H5T_NATIVE_DOUBLE, 1, NULL, 256, &out->s_residual));
    PetscCall(CreateRows(gs, "max_penetration", H5T_NATIVE_DOUBLE, 1, NULL, 256, &out->s_maxpen));
    PetscCall(CreateRows(gs, "newton_iterations", H5T_NATIVE_LLONG, 1, NULL, 256, &out->s_newton));
    PetscCall(CreateRows(gs, "violation", H5T_NATIVE_DOUBLE, 1, NULL, 256, &out->s_violation));
    PetscCall(CreateRows(gs, "rms_penetration", H5T_NATIVE_DOUBLE, 1, NULL, 256, &out->s_rmspen));
    PetscCall(CreateRows(gs, "complementarity", H5T_NATIVE_DOUBLE, 1, NULL, 256, &out->s_compl));
    PetscCall(CreateRows(gs, "cone_violation", H5T_NATIVE_DOUBLE, 1, NULL, 256, &out->s_cone));
    PetscCall(AppendRows(out, out->c_offset, H5T_NATIVE_LLONG, 1, &zero));
    H5Gclose(gs);
    H5Gclose(gc);
  }
  gf = H5Gcreate2(out->file, "frames", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  PetscCall(CreateRows(gf, "time", H5T_NATIVE_DOUBLE, 1, NULL, 64, &out->ftime));
  PetscCall(CreateRows(gf, "step", H5T_NATIVE_LLONG, 1, NULL, 64, &out->fstep));
  H5Gclose(gf);

  gb = H5Gcreate2(out->file, "bodies", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  for (PetscInt i = 0; i < nbodies; i++) {
    FCBody              b = bodies[i];
    const FCBodyVisual *vis;
    BodyOut            *bo = &out->bo[i];
    hid_t               gm;
    hsize_t             r3[1] = {3}, r4[1] = {4}, pv[2];
    PetscReal           c[3];
    long long          *cells;

    PetscCall(FCBodyGetVisual(b, &vis));
    bo->group = H5Gcreate2(gb, b->name, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    PetscCall(AttrString(bo->group, "type", b->type));
    PetscCall(FCBodyGetCentroid(b, c));
    PetscCall(AttrReals(bo->group, "initial_centroid", 3, c));
    PetscCall(CreateRows(bo->group, "centroid", H5T_NATIVE_DOUBLE, 2, r3, 256, &bo->centroid));
    PetscCall(CreateRows(bo->group, "energy", H5T_NATIVE_DOUBLE, 2, r3, 256, &bo->energy));
    {
      PetscReal q[4];
      PetscBool has;
      PetscCall(FCBodyGetRotation(b, q, &has));
      if (has) {
        PetscCall(AttrReals(bo->group, "initial_rotation", 4, q));
        PetscCall(CreateRows(bo->group, "rotation", H5T_NATIVE_DOUBLE, 2, r4, 256, &bo->rotation));
      } else
        bo->rotation = -1;
    }
    gm = H5Gcreate2(bo->group, "mesh", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    PetscCall(AttrString(gm, "cell_type", vis->nvpc == 4 ? "tetrahedron" : "triangle"));
    PetscCall(PetscMalloc1(vis->nc * vis->nvpc + 1, &cells));
    for (PetscInt k = 0; k < vis->nc * vis->nvpc; k++) cells[k] = vis->cells[k];
    PetscCall(WriteDistributed(gm, "cells", H5T_STD_I64LE, H5T_NATIVE_LLONG, vis->nc_global, vis->nvpc, vis->cstart,
                               vis->nc, cells));
    PetscCall(PetscFree(cells));
    PetscCall(WriteDistributed(gm, "reference", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, vis->nv_global, 3, vis->vstart,
                               vis->nv, vis->reference));
    H5Gclose(gm);
    pv[0] = vis->nv_global;
    pv[1] = 3;
    PetscCall(CreateRows(bo->group, "positions", H5T_NATIVE_DOUBLE, 3, pv, 1, &bo->positions));
  }
  H5Gclose(gb);
  PetscCall(CreateRestart(out, nbodies, bodies));
  nrow         = 64;
  out->maxrows = (PetscInt)nrow;
  PetscCall(PetscMalloc5(nrow, &out->rtime, nrow, &out->renergy, nrow * FC_PHASE_NUM, &out->rtiming,
                         nrow * nbodies * 10 + 1, &out->rbody, nrow, &out->rstep));
  PetscFunctionReturn(0);
}

/* One row per completed step (buffered until the next flush) */
PetscErrorCode FCOutputRecordStep(FCOutput out, PetscInt step, PetscReal t, const PetscReal timing[FC_PHASE_NUM],
                                  PetscInt nbodies, FCBody bodies[])
{
  PetscInt r    = out->nrows;
  double   etot = 0.0;

  PetscFunctionBegin;
  if (r == out->maxrows) {
    double   *a, *b, *c, *d;
    PetscInt *e, n = 2 * out->maxrows;
    PetscCall(PetscMalloc5(n, &a, n, &b, n * FC_PHASE_NUM, &c, n * nbodies * 10 + 1, &d, n, &e));
    PetscCall(PetscArraycpy(a, out->rtime, r));
    PetscCall(PetscArraycpy(b, out->renergy, r));
    PetscCall(PetscArraycpy(c, out->rtiming, r * FC_PHASE_NUM));
    PetscCall(PetscArraycpy(d, out->rbody, r * nbodies * 10));
    PetscCall(PetscArraycpy(e, out->rstep, r));
    PetscCall(PetscFree5(out->rtime, out->renergy, out->rtiming, out->rbody, out->rstep));
    out->rtime   = a;
    out->renergy = b;
    out->rtiming = c;
    out->rbody   = d;
    out->rstep   = e;
    out->maxrows = n;
  }
  out->rtime[r] = t;
  out->rstep[r] = step;
  for (int p = 0; p < FC_PHASE_NUM; p++) out->rtiming[r * FC_PHASE_NUM + p] = timing[p];
  for (PetscInt i = 0; i < nbodies; i++) {
    double   *row = &out->rbody[(r * nbodies + i) * 10];
    FCEnergy  E;
    PetscBool has;
    PetscCall(FCBodyGetCentroid(bodies[i], row));
    PetscCall(FCBodyGetRotation(bodies[i], row + 3, &has));
    PetscCall(FCBodyGetEnergy(bodies[i], &E));
    row[7] = E.kinetic;
    row[8] = E.elastic;
    row[9] = E.gravity;
    etot += E.kinetic + E.elastic + E.gravity;
  }
  out->renergy[r] = etot;
  out->nrows++;
  PetscFunctionReturn(0);
}

PetscErrorCode FCOutputRecordContacts(FCOutput out, const struct _FCContactSetView *v)
{
  const FCContactSet *set = v->set;

  PetscFunctionBegin;
  if (out->ns == out->maxs) {
    void *tmp;
    out->maxs = PetscMax(64, 2 * out->maxs);
    PetscCall(PetscMalloc(out->maxs * sizeof(*out->sbuf), &tmp));
    if (out->ns) PetscCall(PetscMemcpy(tmp, out->sbuf, out->ns * sizeof(*out->sbuf)));
    PetscCall(PetscFree(out->sbuf));
    out->sbuf = tmp;
  }
  if (out->nc + set->n > out->maxc) {
    void *tmp;
    out->maxc = PetscMax(2 * out->maxc, out->nc + set->n + 256);
    PetscCall(PetscMalloc(out->maxc * sizeof(*out->cbuf), &tmp));
    if (out->nc) PetscCall(PetscMemcpy(tmp, out->cbuf, out->nc * sizeof(*out->cbuf)));
    PetscCall(PetscFree(out->cbuf));
    out->cbuf = tmp;
  }
  for (PetscInt k = 0; k < set->n; k++) {
    const FCContact *c           = &set->c[k];
    out->cbuf[out->nc].bodies[0] = c->body[0];
    out->cbuf[out->nc].bodies[1] = c->body[1];
    out->cbuf[out->nc].state     = c->state;
    for (int i = 0; i < 3; i++) {
      out->cbuf[out->nc].point[i]  = c->p0[0][i];
      out->cbuf[out->nc].normal[i] = c->n[i];
      out->cbuf[out->nc].force[i]  = c->force[i];
    }
    out->cbuf[out->nc].gap     = c->gap0;
    out->cbuf[out->nc].gap_end = c->gap_end;
    out->nc++;
  }
  out->ctotal += set->n;
  out->sbuf[out->ns].contacts = set->n;
  out->sbuf[out->ns].rows     = v->stats->rows;
  out->sbuf[out->ns].sweeps   = v->stats->sweeps;
  out->sbuf[out->ns].residual = v->stats->residual;
  out->sbuf[out->ns].m        = *v->measures;
  out->sbuf[out->ns].newton   = v->stats->newton;
  out->sbuf[out->ns].offset   = out->ctotal;
  out->ns++;
  PetscFunctionReturn(0);
}

static PetscErrorCode FlushContacts(FCOutput out)
{
  PetscInt   n = out->nc, m = out->ns;
  double    *d;
  long long *l;

  PetscFunctionBegin;
  if (!out->contacts) PetscFunctionReturn(0);
  PetscCall(PetscMalloc2(3 * n + 3 * m + 1, &d, 2 * n + 2 * m + 1, &l));
  for (PetscInt k = 0; k < n; k++)
    for (int i = 0; i < 2; i++) l[2 * k + i] = out->cbuf[k].bodies[i];
  PetscCall(AppendRows(out, out->c_bodies, H5T_NATIVE_LLONG, n, l));
  for (PetscInt k = 0; k < n; k++)
    for (int i = 0; i < 3; i++) d[3 * k + i] = out->cbuf[k].point[i];
  PetscCall(AppendRows(out, out->c_point, H5T_NATIVE_DOUBLE, n, d));
  for (PetscInt k = 0; k < n; k++)
    for (int i = 0; i < 3; i++) d[3 * k + i] = out->cbuf[k].normal[i];
  PetscCall(AppendRows(out, out->c_normal, H5T_NATIVE_DOUBLE, n, d));
  for (PetscInt k = 0; k < n; k++)
    for (int i = 0; i < 3; i++) d[3 * k + i] = out->cbuf[k].force[i];
  PetscCall(AppendRows(out, out->c_force, H5T_NATIVE_DOUBLE, n, d));
  for (PetscInt k = 0; k < n; k++) d[k] = out->cbuf[k].gap;
  PetscCall(AppendRows(out, out->c_gap, H5T_NATIVE_DOUBLE, n, d));
  for (PetscInt k = 0; k < n; k++) d[k] = out->cbuf[k].gap_end;
  PetscCall(AppendRows(out, out->c_gapend, H5T_NATIVE_DOUBLE, n, d));
  for (PetscInt k = 0; k < n; k++) l[k] = out->cbuf[k].state;
  PetscCall(AppendRows(out, out->c_state, H5T_NATIVE_LLONG, n, l));
  for (PetscInt k = 0; k < m; k++) l[k] = out->sbuf[k].offset;
  PetscCall(AppendRows(out, out->c_offset, H5T_NATIVE_LLONG, m, l));
  for (PetscInt k = 0; k < m; k++) l[k] = out->sbuf[k].contacts;
  PetscCall(AppendRows(out, out->s_contacts, H5T_NATIVE_LLONG, m, l));
  for (PetscInt k = 0; k < m; k++) l[k] = out->sbuf[k].rows;
  PetscCall(AppendRows(out, out->s_rows, H5T_NATIVE_LLONG, m, l));
  for (PetscInt k = 0; k < m; k++) l[k] = out->sbuf[k].sweeps;
  PetscCall(AppendRows(out, out->s_sweeps, H5T_NATIVE_LLONG, m, l));
  for (PetscInt k = 0; k < m; k++) d[k] = out->sbuf[k].residual;
  PetscCall(AppendRows(out, out->s_residual, H5T_NATIVE_DOUBLE, m, d));
  for (PetscInt k = 0; k < m; k++) d[k] = out->sbuf[k].m.max_penetration;
  PetscCall(AppendRows(out, out->s_maxpen, H5T_NATIVE_DOUBLE, m, d));
  for (PetscInt k = 0; k < m; k++) l[k] = out->sbuf[k].newton;
  PetscCall(AppendRows(out, out->s_newton, H5T_NATIVE_LLONG, m, l));
  for (PetscInt k = 0; k < m; k++) d[k] = out->sbuf[k].m.violation;
  PetscCall(AppendRows(out, out->s_violation, H5T_NATIVE_DOUBLE, m, d));
  for (PetscInt k = 0; k < m; k++) d[k] = out->sbuf[k].m.rms_penetration;
  PetscCall(AppendRows(out, out->s_rmspen, H5T_NATIVE_DOUBLE, m, d));
  for (PetscInt k = 0; k < m; k++) d[k] = out->sbuf[k].m.complementarity;
  PetscCall(AppendRows(out, out->s_compl, H5T_NATIVE_DOUBLE, m, d));
  for (PetscInt k = 0; k < m; k++) d[k] = out->sbuf[k].m.cone_violation;
  PetscCall(AppendRows(out, out->s_cone, H5T_NATIVE_DOUBLE, m, d));
  PetscCall(PetscFree2(d, l));
  out->nc = out->ns = 0;
  PetscFunctionReturn(0);
}

PetscErrorCode FCOutputWriteFrame(FCOutput out, PetscInt step, PetscReal t, PetscInt nbodies, FCBody bodies[])
{
  double    tt = t;
  long long ss = step;

  PetscFunctionBegin;
  PetscCall(FCPhaseBegin(FC_PHASE_OUTPUT));
  for (PetscInt i = 0; i < nbodies; i++) {
    const FCBodyVisual *vis;
    PetscReal          *x;
    hid_t               fspace, mspace;
    hsize_t             dims[3], start[3] = {0, 0, 0}, count[3];
    PetscCall(FCBodyGetVisual(bodies[i], &vis));
    PetscCall(PetscMalloc1(3 * vis->nv + 1, &x));
    PetscCall(FCBodyGetVisualPositions(bodies[i], x));
    fspace = H5Dget_space(out->bo[i].positions);
    H5Sget_simple_extent_dims(fspace, dims, NULL);
    H5Sclose(fspace);
    start[0] = dims[0];
    start[1] = vis->vstart;
    dims[0] += 1;
    FCH5Check(H5Dset_extent(out->bo[i].positions, dims), "extend positions");
    fspace   = H5Dget_space(out->bo[i].positions);
    count[0] = 1;
    count[1] = vis->nv;
    count[2] = 3;
    if (vis->nv) {
      H5Sselect_hyperslab(fspace, H5S_SELECT_SET, start, NULL, count, NULL);
      mspace = H5Screate_simple(3, count, NULL);
    } else {
      H5Sselect_none(fspace);
      mspace = H5Screate(H5S_NULL);
    }
    FCH5Check(H5Dwrite(out->bo[i].positions, H5T_NATIVE_DOUBLE, mspace, fspace, H5P_DEFAULT, x), "write positions");
    H5Sclose(mspace);
    H5Sclose(fspace);
    PetscCall(PetscFree(x));
  }
  PetscCall(AppendRows(out, out->ftime, H5T_NATIVE_DOUBLE, 1, &tt));
  PetscCall(AppendRows(out, out->fstep, H5T_NATIVE_LLONG, 1, &ss));
  if (out->nframes == out->maxframes) {
    double *f;
    out->maxframes = PetscMax(64, 2 * out->maxframes);
    PetscCall(PetscMalloc1(out->maxframes, &f));
    PetscCall(PetscArraycpy(f, out->frametimes, out->nframes));
    PetscCall(PetscFree(out->frametimes));
    out->frametimes = f;
  }
  out->frametimes[out->nframes++] = t;
  PetscCall(FCOutputFlush(out));
  PetscCall(FCPhaseEnd(FC_PHASE_OUTPUT));
  PetscFunctionReturn(0);
}

/* Writes the buffered step rows, flushes the file; the XDMF index is rewritten whenever the
   number of frames has doubled (so the total cost stays linear in the number of frames) */
PetscErrorCode FCOutputFlush(FCOutput out)
{
  PetscInt n = out->nrows, nb = out->nbodies;
  double  *tmp;

  PetscFunctionBegin;
  if (n) {
    long long *steps;
    PetscCall(PetscMalloc2(n * 4 + 1, &tmp, n, &steps));
    for (PetscInt r = 0; r < n; r++) steps[r] = out->rstep[r];
    PetscCall(AppendRows(out, out->time, H5T_NATIVE_DOUBLE, n, out->rtime));
    PetscCall(AppendRows(out, out->step, H5T_NATIVE_LLONG, n, steps));
    PetscCall(AppendRows(out, out->energy, H5T_NATIVE_DOUBLE, n, out->renergy));
    for (PetscInt r = 0; r < n; r++) { /* energy change over each step: a scheme adding energy shows here */
      tmp[r]     = out->renergy[r] - out->elast;
      out->elast = out->renergy[r];
    }
    PetscCall(AppendRows(out, out->denergy, H5T_NATIVE_DOUBLE, n, tmp));
    for (int p = 0; p < FC_PHASE_NUM; p++) {
      for (PetscInt r = 0; r < n; r++) tmp[r] = out->rtiming[r * FC_PHASE_NUM + p];
      PetscCall(AppendRows(out, out->timing[p], H5T_NATIVE_DOUBLE, n, tmp));
    }
    for (PetscInt i = 0; i < nb; i++) {
      for (PetscInt r = 0; r < n; r++)
        for (int k = 0; k < 3; k++) tmp[3 * r + k] = out->rbody[(r * nb + i) * 10 + k];
      PetscCall(AppendRows(out, out->bo[i].centroid, H5T_NATIVE_DOUBLE, n, tmp));
      for (PetscInt r = 0; r < n; r++)
        for (int k = 0; k < 3; k++) tmp[3 * r + k] = out->rbody[(r * nb + i) * 10 + 7 + k];
      PetscCall(AppendRows(out, out->bo[i].energy, H5T_NATIVE_DOUBLE, n, tmp));
      if (out->bo[i].rotation >= 0) {
        for (PetscInt r = 0; r < n; r++)
          for (int k = 0; k < 4; k++) tmp[4 * r + k] = out->rbody[(r * nb + i) * 10 + 3 + k];
        PetscCall(AppendRows(out, out->bo[i].rotation, H5T_NATIVE_DOUBLE, n, tmp));
      }
    }
    PetscCall(PetscFree2(tmp, steps));
    out->nrows = 0;
  }
  PetscCall(FlushContacts(out));
  FCH5Check(H5Fflush(out->file, H5F_SCOPE_GLOBAL), "flush");
  if (out->nframes >= 2 * out->xdmfwritten || out->nframes == 1) {
    if (out->rank == 0)
      PetscCall(FCXdmfWrite(out->filename, out->xdmfname, out->nbodies, out->bodies, out->nframes, out->frametimes));
    out->xdmfwritten = out->nframes;
  }
  PetscFunctionReturn(0);
}

PetscErrorCode FCOutputDestroy(FCOutput *output)
{
  FCOutput out = *output;

  PetscFunctionBegin;
  if (!out) PetscFunctionReturn(0);
  if (out->bo) {
    PetscCall(FCOutputFlush(out));
    if (out->rank == 0 && out->xdmfwritten != out->nframes)
      PetscCall(FCXdmfWrite(out->filename, out->xdmfname, out->nbodies, out->bodies, out->nframes, out->frametimes));
    for (PetscInt i = 0; i < out->nbodies; i++) {
      H5Dclose(out->bo[i].centroid);
      H5Dclose(out->bo[i].energy);
      H5Dclose(out->bo[i].positions);
      if (out->bo[i].rotation >= 0) H5Dclose(out->bo[i].rotation);
      H5Gclose(out->bo[i].group);
    }
    H5Dclose(out->time);
    H5Dclose(out->step);
    H5Dclose(out->energy);
    H5Dclose(out->denergy);
    for (int p = 0; p < FC_PHASE_NUM; p++) H5Dclose(out->timing[p]);
    H5Dclose(out->ftime);
    H5Dclose(out->fstep);
    for (int k = 0; k < 2; k++) {
      for (PetscInt i = 0; i < out->nbodies; i++) H5Dclose(out->xbody[k][i]);
      PetscCall(PetscFree(out->xbody[k]));
      H5Dclose(out->xstep[k]);
      H5Dclose(out->xtime[k]);
      H5Dclose(out->xcontacts[k]);
      H5Dclose(out->xncontacts[k]);
      H5Gclose(out->xslot[k]);
    }
    if (out->contacts) {
      hid_t ds[] = {out->c_offset, out->c_bodies, out->c_point,     out->c_normal, out->c_force,  out->c_gap,
                    out->c_gapend, out->c_state,  out->s_contacts,  out->s_rows,   out->s_sweeps, out->s_residual,
                    out->s_maxpen, out->s_newton, out->s_violation, out->s_rmspen, out->s_compl,  out->s_cone};
      for (size_t i = 0; i < sizeof(ds) / sizeof(ds[0]); i++) H5Dclose(ds[i]);
    }
    PetscCall(PetscFree(out->cbuf));
    PetscCall(PetscFree(out->sbuf));
    PetscCall(PetscFree(out->bo));
    PetscCall(PetscFree5(out->rtime, out->renergy, out->rtiming, out->rbody, out->rstep));
  }
  PetscCall(PetscFree(out->frametimes));
  H5Fclose(out->file);
  PetscCall(PetscFree(*output));
  PetscFunctionReturn(0);
}
