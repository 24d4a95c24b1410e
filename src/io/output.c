/* HDF5 output of a run (schema in docs/output.md). Per-step rows are buffered and written,
   with the frame, at every output step; the file is flushed after each, so a run that stops
   keeps every completed output step readable. Parallel HDF5 (MPI-IO): each rank writes the
   positions of the vertices it owns; rank 0 writes the per-step rows. This file: the file, its
   header (attributes, /frames, /bodies), the frames, flush and close; the per-step records are in
   records.c, the restart state in restart.c (src/io/ioimpl.h). */
#include "ioimpl.h"
#include <time.h>

/* f.h5 -> f.xmf, other names get .xmf appended */
static PetscErrorCode FCOutputXdmfName(const char filename[], char xmf[], size_t n)
{
  size_t len;

  PetscFunctionBegin;
  PetscCall(PetscStrlen(filename, &len));
  PetscCall(PetscStrncpy(xmf, filename, n));
  if (len > 3 && len < n && !strcmp(filename + len - 3, ".h5")) xmf[len - 3] = 0;
  PetscCall(PetscStrlcat(xmf, ".xmf", n));
  PetscFunctionReturn(0);
}

PetscErrorCode FCOutputCreate(MPI_Comm comm, const char filename[], FCOutput *output)
{
  FCOutput out;
  hid_t    fapl;
  int      ok;

  PetscFunctionBegin;
  { /* no input of the run may be overwritten (src/util/inputs.c), nor its XDMF index */
    char xmf[PETSC_MAX_PATH_LEN];
    PetscCall(FCInputsCheckOutput(comm, filename, "-output_file"));
    PetscCall(FCOutputXdmfName(filename, xmf, sizeof(xmf)));
    PetscCall(FCInputsCheckOutput(comm, xmf, "the XDMF index of -output_file"));
    PetscCall(FCOutputsCheckLive(comm, filename)); /* nor the file of another live scene */
  }
  PetscCall(PetscNew(&out));
  out->comm = comm;
  PetscCallMPI(MPI_Comm_rank(comm, &out->rank));
  PetscCall(PetscStrncpy(out->filename, filename, sizeof(out->filename)));
  PetscCall(FCOutputXdmfName(filename, out->xdmfname, sizeof(out->xdmfname)));
  /* every write's failure is collective from now on (h5util.c); a device that takes no data
     (/dev/full) is found before HDF5 writes to it (reserve.c) */
  PetscCall(FCH5ContextSet(comm, filename));
  PetscCall(FCH5Reserve(comm, filename, -1, 4096, "the file"));
  fapl = H5Pcreate(H5P_FILE_ACCESS);
  H5Pset_fapl_mpio(fapl, comm, MPI_INFO_NULL);
  H5Pset_libver_bounds(fapl, H5F_LIBVER_V18, H5F_LIBVER_LATEST);
  { /* Metadata reaches the disk only at the flush that ends an output step. With the default cache,
       HDF5 evicts dirty metadata (a chunk index that names a chunk just allocated) whenever it
       likes; after a kill -9 the file could then index data beyond the end of file its superblock
       records ("addr overflow"), and a completed step would not read. No eviction, no automatic
       resizing, and the parallel sync threshold at its maximum keep the file on disk exactly as
       the last flush left it (a step's metadata is a few kB; the cache is emptied by each flush). */
    H5AC_cache_config_t mdc;
    mdc.version = H5AC__CURR_CACHE_CONFIG_VERSION;
    if (H5Pget_mdc_config(fapl, &mdc) >= 0) {
      mdc.evictions_enabled     = 0;
      mdc.incr_mode             = H5C_incr__off;
      mdc.flash_incr_mode       = H5C_flash_incr__off;
      mdc.decr_mode             = H5C_decr__off;
      mdc.dirty_bytes_threshold = 32 * 1024 * 1024; /* H5AC__MAX_DIRTY_BYTES_THRESHOLD */
      /* and rank 0 writes all of it: a flush has then put everything on disk when rank 0 returns
         from it (FCOutputFlush writes /complete after it) */
      mdc.metadata_write_strategy = H5AC_METADATA_WRITE_STRATEGY__PROCESS_0_ONLY;
      PetscCheck(H5Pset_mdc_config(fapl, &mdc) >= 0, comm, PETSC_ERR_LIB,
                 "HDF5 refused the metadata cache settings of '%s'", filename);
    }
  }
  H5Eset_auto2(H5E_DEFAULT, NULL, NULL); /* our own messages name the file */
  out->file = H5Fcreate(filename, H5F_ACC_TRUNC, H5P_DEFAULT, fapl);
  H5Pclose(fapl);
  ok = out->file >= 0;
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &ok, 1, MPI_INT, MPI_MIN, comm));
  if (!ok) {
    if (out->file >= 0) H5Fclose(out->file);
    PetscCall(FCH5ContextClear());
    PetscCall(PetscFree(out));
    SETERRQ(comm, PETSC_ERR_FILE_WRITE,
            "Cannot create output file '%s' (-output_file): check that its directory exists and is writable", filename);
  }
  PetscCall(FCOutputsAddLive(out, filename));
  *output = out;
  PetscFunctionReturn(0);
}

/* Disk space to reserve (reserve.c) for the header (the meshes, the restart datasets) or for one
   output step before its size has been seen (a frame, a restart state), with room for the chunks
   of 256 rows that every row dataset allocates now and then */
static size_t ReserveBytes(PetscInt nbodies, FCBody bodies[], PetscBool header)
{
  size_t bytes = 262144 + 32768 * (size_t)nbodies;
  for (PetscInt i = 0; i < nbodies; i++) {
    const FCBodyVisual *vis;
    PetscInt            cols = 0;
    PetscBool           pervertex;
    if (FCBodyGetVisual(bodies[i], &vis) || FCBodyGetStateLayout(bodies[i], &cols, &pervertex)) continue;
    bytes += (size_t)vis->nv_global * (24 + 8 * (size_t)cols) * (header ? 4 : 2);
    if (header) bytes += (size_t)vis->nc_global * ((size_t)vis->nvpc + 2) * 8;
  }
  return bytes;
}

/* The file's attributes (the options, version, ranks, date, time step, steps, output period) and
   /complete = (last step, frames) safely on disk, written after each flush (FCOutputFlush): (-1, 0) until
   the first frame is */
static PetscErrorCode WriteAttributes(FCOutput out, PetscReal h, PetscInt nsteps, PetscInt every)
{
  char *opts;

  PetscFunctionBegin;
  PetscCall(PetscOptionsGetAll(NULL, &opts));
  PetscCall(FCH5AttrString(out->file, "options", opts));
  PetscCall(PetscFree(opts));
  PetscCall(FCH5AttrString(out->file, "fecontact_version", FECONTACT_VERSION));
  { /* the bodies in scene order: what /contacts/bodies indexes */
    char names[FC_MAX_BODIES * (FC_MAX_NAME + 1) + 1] = "";
    for (PetscInt i = 0; i < out->nbodies; i++) {
      PetscCall(PetscStrlcat(names, i ? "," : "", sizeof(names)));
      PetscCall(PetscStrlcat(names, FCBodyName(out->bodies[i]), sizeof(names)));
    }
    PetscCall(FCH5AttrString(out->file, "scene_bodies", names));
  }
  {
    PetscMPIInt size;
    char        date[64];
    time_t      now = time(NULL);
    PetscCallMPI(MPI_Comm_size(out->comm, &size));
    PetscCall(FCH5AttrInt(out->file, "mpi_ranks", size));
    strftime(date, sizeof(date), "%Y-%m-%dT%H:%M:%SZ", gmtime(&now));
    PetscCallMPI(MPI_Bcast(date, sizeof(date), MPI_CHAR, 0, out->comm));
    PetscCall(FCH5AttrString(out->file, "created", date));
  }
  {
    double hv    = h;
    hid_t  space = H5Screate(H5S_SCALAR),
          attr   = H5Acreate2(out->file, "time_step", H5T_NATIVE_DOUBLE, space, H5P_DEFAULT, H5P_DEFAULT);
    FCH5Check(H5Awrite(attr, H5T_NATIVE_DOUBLE, &hv), "time_step");
    H5Aclose(attr);
    H5Sclose(space);
    PetscCall(FCH5AttrInt(out->file, "time_steps", nsteps));
    PetscCall(FCH5AttrInt(out->file, "output_every", every));
  }
  {
    hsize_t   two[1]  = {2};
    hid_t     space   = H5Screate_simple(1, two, NULL);
    long long none[2] = {-1, 0};
    out->complete     = H5Dcreate2(out->file, "complete", H5T_STD_I64LE, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    H5Sclose(space);
    FCH5Check(out->complete < 0 ? -1 : 0, "complete");
    FCH5Check(H5Dwrite(out->complete, H5T_NATIVE_LLONG, H5S_ALL, H5S_ALL, H5P_DEFAULT, none), "complete");
    out->laststep = -1;
  }
  PetscFunctionReturn(0);
}

/* Body i's group: its type, initial centroid and rotation, the datasets of its records, its picture's
   mesh (cells, reference coordinates, and the partition: each cell's rank and index in the mesh as read) */
static PetscErrorCode WriteBodyHeader(FCOutput out, hid_t gb, PetscInt i, FCBody b)
{
  const FCBodyVisual *vis;
  const char         *name;
  FCBodyType          type;
  BodyOut            *bo = &out->bo[i];
  hid_t               gm;
  hsize_t             r3[1] = {3}, r4[1] = {4}, pv[2];
  PetscReal           c[3];
  long long          *cells;

  PetscFunctionBegin;
  PetscCall(FCBodyGetVisual(b, &vis));
  PetscCall(FCBodyGetName(b, &name));
  PetscCall(FCBodyGetType(b, &type));
  bo->group = H5Gcreate2(gb, name, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  PetscCall(FCH5AttrString(bo->group, "type", type));
  PetscCall(FCBodyGetCentroid(b, c));
  PetscCall(FCH5AttrReals(bo->group, "initial_centroid", 3, c));
  PetscCall(FCH5CreateRows(bo->group, "centroid", H5T_NATIVE_DOUBLE, 2, r3, 256, &bo->centroid));
  PetscCall(FCH5CreateRows(bo->group, "energy", H5T_NATIVE_DOUBLE, 2, r3, 256, &bo->energy));
  {
    PetscReal q[4];
    PetscBool has;
    PetscCall(FCBodyGetRotation(b, q, &has));
    if (has) {
      PetscCall(FCH5AttrReals(bo->group, "initial_rotation", 4, q));
      PetscCall(FCH5CreateRows(bo->group, "rotation", H5T_NATIVE_DOUBLE, 2, r4, 256, &bo->rotation));
    } else
      bo->rotation = -1;
  }
  {
    FCInverted inv;
    PetscBool  has;
    bo->inverted[0] = bo->inverted[1] = -1;
    PetscCall(FCBodyGetInverted(b, &inv, &has));
    if (has) { /* per step: the elements turned inside out and the smallest volume ratio J */
      hid_t gi = H5Gcreate2(bo->group, "inverted", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
      PetscCall(FCH5CreateRows(gi, "elements", H5T_NATIVE_LLONG, 1, NULL, 256, &bo->inverted[0]));
      PetscCall(FCH5CreateRows(gi, "min_volume_ratio", H5T_NATIVE_DOUBLE, 1, NULL, 256, &bo->inverted[1]));
      H5Gclose(gi);
    }
  }
  gm = H5Gcreate2(bo->group, "mesh", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  PetscCall(FCH5AttrString(gm, "cell_type", vis->nvpc == 4 ? "tetrahedron" : "triangle"));
  PetscCall(PetscMalloc1(vis->nc * vis->nvpc + 1, &cells));
  for (PetscInt k = 0; k < vis->nc * vis->nvpc; k++) cells[k] = vis->cells[k];
  PetscCall(FCH5WriteDistributed(gm, "cells", H5T_STD_I64LE, H5T_NATIVE_LLONG, vis->nc_global, vis->nvpc, vis->cstart,
                                 vis->nc, cells));
  PetscCall(PetscFree(cells));
  PetscCall(FCH5WriteDistributed(gm, "reference", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, vis->nv_global, 3, vis->vstart,
                                 vis->nv, vis->reference));
  if (vis->origin) { /* the partition: the rank of each cell and its index in the mesh as read, which
                        -<body>_partition_file replays (src/mesh/partreplay.c) */
    PetscMPIInt rank, size;
    PetscCallMPI(MPI_Comm_rank(out->comm, &rank));
    PetscCallMPI(MPI_Comm_size(out->comm, &size));
    PetscCall(PetscMalloc1(2 * vis->nc + 1, &cells));
    for (PetscInt k = 0; k < vis->nc; k++) {
      cells[k]           = rank;
      cells[vis->nc + k] = vis->origin[k];
    }
    PetscCall(FCH5WriteDistributed(gm, "rank", H5T_STD_I64LE, H5T_NATIVE_LLONG, vis->nc_global, 0, vis->cstart, vis->nc,
                                   cells));
    PetscCall(FCH5WriteDistributed(gm, "cell_origin", H5T_STD_I64LE, H5T_NATIVE_LLONG, vis->nc_global, 0, vis->cstart,
                                   vis->nc, cells + vis->nc));
    PetscCall(FCH5AttrInt(gm, "ranks", size));
    PetscCall(PetscFree(cells));
  }
  H5Gclose(gm);
  pv[0] = vis->nv_global;
  pv[1] = 3;
  PetscCall(FCH5CreateRows(bo->group, "positions", H5T_NATIVE_DOUBLE, 3, pv, 1, &bo->positions));
  { /* the reactions of the constrained regions, a row per step: force, moment about the region's centroid */
    const char **names;
    hsize_t      six[1] = {6};
    PetscCall(FCBodyGetReactions(b, &bo->nreact, &names, NULL));
    PetscCheck(bo->nreact <= FC_MAX_REACTIONS, out->comm, PETSC_ERR_SUP, "Body '%s': more than %d constrained regions",
               name, FC_MAX_REACTIONS);
    if (bo->nreact) {
      hid_t gr = H5Gcreate2(bo->group, "reactions", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
      PetscCall(FCH5AttrString(gr, "columns", "fx,fy,fz,mx,my,mz"));
      for (PetscInt k = 0; k < bo->nreact; k++)
        PetscCall(FCH5CreateRows(gr, names[k], H5T_NATIVE_DOUBLE, 2, six, 256, &bo->react[k]));
      H5Gclose(gr);
      PetscCall(PetscMalloc1(6 * bo->nreact * out->maxrows, &bo->rreact));
    }
  }
  { /* what identifies the regions (FCBodyGetRegions), for a restart's check (restartcheck.c) */
    PetscInt   n;
    char      *names;
    PetscReal *val;
    PetscCall(FCBodyGetRegions(b, &n, &names, &val));
    PetscCall(FCH5AttrString(bo->group, "regions", names));
    if (n) PetscCall(FCH5AttrReals(bo->group, "region_vertices", 4 * n, val));
    PetscCall(PetscFree(names));
    PetscCall(PetscFree(val));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode FCOutputWriteHeader(FCOutput out, PetscInt nbodies, FCBody bodies[], PetscReal h, PetscInt nsteps,
                                   PetscInt every, PetscBool contacts)
{
  hid_t gb, gf;

  PetscFunctionBegin;
  PetscCall(
      FCH5Reserve(out->comm, out->filename, out->file, ReserveBytes(nbodies, bodies, PETSC_TRUE), "the file's header"));
  out->nbodies = nbodies;
  out->bodies  = bodies;
  PetscCall(PetscCalloc1(nbodies, &out->bo));
  PetscCall(WriteAttributes(out, h, nsteps, every));
  PetscCall(FCOutputRecordsCreate(out, nbodies, bodies, contacts));
  gf = H5Gcreate2(out->file, "frames", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  PetscCall(FCH5CreateRows(gf, "time", H5T_NATIVE_DOUBLE, 1, NULL, 64, &out->ftime));
  PetscCall(FCH5CreateRows(gf, "step", H5T_NATIVE_LLONG, 1, NULL, 64, &out->fstep));
  H5Gclose(gf);

  gb = H5Gcreate2(out->file, "bodies", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  for (PetscInt i = 0; i < nbodies; i++) PetscCall(WriteBodyHeader(out, gb, i, bodies[i]));
  PetscCall(FCOutputFieldsCreate(out)); /* fields.c: the -output_fields datasets */
  H5Gclose(gb);
  PetscCall(FCRestartWriterCreate(out->comm, out->file, nbodies, bodies, &out->restart));
  PetscFunctionReturn(0);
}

PetscErrorCode FCOutputWriteFrame(FCOutput out, PetscInt step, PetscReal t, PetscInt nbodies, FCBody bodies[])
{
  double    tt = t;
  long long ss = step;

  PetscFunctionBegin;
  PetscCall(FCPhaseBegin(FC_PHASE_OUTPUT));
  /* the space of the output step (frame and restart state) first, while HDF5 holds nothing
     unwritten: the largest step so far with a margin, or an estimate (reserve.c) */
  PetscCall(FCH5Reserve(out->comm, out->filename, out->file,
                        PetscMax(out->growth + 262144, ReserveBytes(nbodies, bodies, PETSC_FALSE)),
                        "the next output step"));
  /* the order keeps a consistent prefix if a write fails: the step rows, the positions, then
     /frames/time and /frames/step (a frame exists once these hold it), then the flush; the
     restart state only after that (FCOutputWriteRestart) */
  PetscCall(FCOutputRecordsFlush(out));
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
  PetscCall(FCOutputFieldsWrite(out)); /* fields.c */
  PetscCall(FCH5AppendRows(out->rank, out->ftime, H5T_NATIVE_DOUBLE, 1, &tt));
  PetscCall(FCH5AppendRows(out->rank, out->fstep, H5T_NATIVE_LLONG, 1, &ss));
  PetscCall(FCXdmfAddFrame(out, t)); /* xdmf.c: the frame's views for the XDMF index */
  out->laststep = PetscMax(out->laststep, ss);
  if (out->nframes == out->maxframes) {
    double *f;
    out->maxframes = PetscMax(64, 2 * out->maxframes);
    PetscCall(PetscMalloc1(out->maxframes, &f));
    PetscCall(PetscArraycpy(f, out->frametimes, out->nframes));
    PetscCall(PetscFree(out->frametimes));
    out->frametimes = f;
  }
  out->frametimes[out->nframes++] = t;
  PetscCall(FCRestartWriterBegin(out->restart)); /* the restart slot's first stage, flushed with the frame */
  PetscCall(FCOutputFlush(out));
  PetscCall(FCPhaseEnd(FC_PHASE_OUTPUT));
  PetscFunctionReturn(0);
}

/* The XDMF index (rank 0), its failure made collective like an HDF5 write's */
static PetscErrorCode WriteXdmf(FCOutput out)
{
  PetscErrorCode ierr = 0;
  int            err  = 0;

  PetscFunctionBegin;
  if (out->rank == 0) {
    PetscCall(PetscPushErrorHandler(PetscReturnErrorHandler, NULL)); /* the agreed error below names it */
    errno = 0;
    ierr  = FCXdmfWrite(out);
    err   = errno;
    PetscCall(PetscPopErrorHandler());
  }
  PetscCall(FCH5AgreeClean(!ierr, err, "its XDMF index (.xmf)")); /* not HDF5's: the file can still be closed */
  out->xdmfwritten = out->nframes;
  PetscFunctionReturn(0);
}

/* Writes the buffered step rows, flushes the file; the XDMF index is rewritten whenever the
   number of frames has doubled (so the total cost stays linear in the number of frames) */
PetscErrorCode FCOutputFlush(FCOutput out)
{
  PetscFunctionBegin;
  PetscCall(FCOutputRecordsFlush(out));
  FCH5Check(H5Fflush(out->file, H5F_SCOPE_GLOBAL), "flush");
  /* only now, with everything up to that step on disk, the mark that says so: one raw write at a
     fixed place (no metadata), so after a crash or kill -9 a reader trusts the steps up to
     /complete and nothing beyond (a flush cut short may have put later metadata on disk: the
     index of a chunk allocated for the next frame, beyond the end of file the superblock records).
     Parallel HDF5 shares a flush's metadata writes among the ranks, and a rank may return from
     H5Fflush before another has written its share: the barrier makes every share written first
     (with rank 0 writing all metadata, FCOutputCreate, and this barrier, no rank's share can lag:
     a kill -9 under the sanitizers on 2 ranks once left the mark one step ahead of a dataset).
     The step and the frame count go in one write, so they always agree. */
  PetscCallMPI(MPI_Barrier(out->comm));
  {
    long long mark[2] = {out->laststep, (long long)out->nframes};
    FCH5Check(H5Dwrite(out->complete, H5T_NATIVE_LLONG, H5S_ALL, H5S_ALL, H5P_DEFAULT, mark), "complete");
  }
  if (out->nframes >= 2 * out->xdmfwritten || out->nframes == 1) PetscCall(WriteXdmf(out));
  PetscFunctionReturn(0);
}

/* /memory and /memory_phases (name): one row per rank (bytes; its columns named by the attribute
   `columns`, what they are by `units`), written again (replaced) by each call, e.g. at the end of a
   restarted run; collective */
PetscErrorCode FCOutputWriteMemory(FCOutput out, const char name[], const char units[], PetscInt ncols,
                                   const char *const names[], const PetscReal row[])
{
  PetscMPIInt size, rank;
  char        cols[256] = "";
  hid_t       d;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_size(out->comm, &size));
  PetscCallMPI(MPI_Comm_rank(out->comm, &rank));
  for (PetscInt i = 0; i < ncols; i++) {
    PetscCall(PetscStrlcat(cols, names[i], sizeof(cols)));
    if (i + 1 < ncols) PetscCall(PetscStrlcat(cols, ",", sizeof(cols)));
  }
  if (H5Lexists(out->file, name, H5P_DEFAULT) > 0) FCH5Check(H5Ldelete(out->file, name, H5P_DEFAULT), name);
  PetscCall(FCH5WriteDistributed(out->file, name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, (hsize_t)size, (hsize_t)ncols,
                                 (hsize_t)rank, 1, row));
  d = H5Dopen2(out->file, name, H5P_DEFAULT);
  FCH5Check(d, name);
  PetscCall(FCH5AttrString(d, "columns", cols));
  PetscCall(FCH5AttrString(d, "units", units));
  H5Dclose(d);
  FCH5Check(H5Fflush(out->file, H5F_SCOPE_GLOBAL), "flush");
  PetscFunctionReturn(0);
}

/* Writes what is buffered and closes the file. After a failed write nothing more is written.
   A failure outside HDF5 (disk space not reserved, the XDMF index) leaves nothing unwritten in
   HDF5, and the file is closed. After one inside HDF5 (FCH5FailedInside, on every rank alike) it
   is not even closed: HDF5 1.10 cannot close a file whose metadata it cannot write (H5Fclose fails
   half-way and leaves a dangling handle, which its clean-up at MPI_Finalize dereferences), so the
   file is left open as its last flush made it and the program exits without that clean-up
   (FCOutputFileLeftOpen, src/main.c). Returns the (collective) error of a final write that fails. */
PetscErrorCode FCOutputDestroy(FCOutput *output)
{
  FCOutput       out  = *output;
  PetscErrorCode ierr = 0;
  MPI_Comm       comm;
  char           msg[1024] = "";

  PetscFunctionBegin;
  if (!out) PetscFunctionReturn(0);
  comm = out->comm;
  PetscCall(FCOutputsRemoveLive(out));
  if (out->bo && !FCH5Failed()) {
    PetscCall(PetscPushErrorHandler(PetscReturnErrorHandler, NULL)); /* reported once, at the end */
    ierr = FCOutputFlush(out);
    if (!ierr && out->xdmfwritten != out->nframes) ierr = WriteXdmf(out);
    PetscCall(PetscPopErrorHandler());
  }
  if (out->bo) {
    if (!FCH5FailedInside()) {
      for (PetscInt i = 0; i < out->nbodies; i++) {
        H5Dclose(out->bo[i].centroid);
        H5Dclose(out->bo[i].energy);
        H5Dclose(out->bo[i].positions);
        if (out->bo[i].rotation >= 0) H5Dclose(out->bo[i].rotation);
        for (int k = 0; k < 2; k++)
          if (out->bo[i].inverted[k] >= 0) H5Dclose(out->bo[i].inverted[k]);
        for (PetscInt k = 0; k < out->bo[i].nreact; k++) H5Dclose(out->bo[i].react[k]);
        H5Gclose(out->bo[i].group);
      }
      H5Dclose(out->ftime);
      H5Dclose(out->fstep);
      H5Dclose(out->complete);
    }
    PetscCall(FCOutputFieldsDestroy(out)); /* these three close nothing after a failure inside HDF5 */
    PetscCall(FCXdmfDestroy(out));
    PetscCall(FCRestartWriterDestroy(&out->restart));
    PetscCall(FCOutputRecordsDestroy(out));
    PetscCall(PetscFree(out->bo));
  }
  PetscCall(PetscFree(out->frametimes));
  if (!FCH5FailedInside()) {
    PetscErrorCode cerr;
    PetscCall(PetscPushErrorHandler(PetscReturnErrorHandler, NULL));
    errno = 0;
    cerr  = H5Fclose(out->file) < 0 ? FCH5Agree(0, errno, "close") : FCH5Agree(1, 0, "close");
    PetscCall(PetscPopErrorHandler());
    if (!ierr) ierr = cerr;
    if (!FCH5FailedInside()) {
      PetscCall(FCH5Release(comm, out->filename));
      PetscCall(FCH5ContextClear());
    }
  }
  if (ierr) {
    char *specific = NULL;
    PetscCall(PetscErrorMessage(ierr, NULL, &specific));
    if (specific) PetscCall(PetscStrncpy(msg, specific, sizeof(msg)));
  }
  PetscCall(PetscFree(*output));
  PetscCheck(!ierr, comm, PETSC_ERR_FILE_WRITE, "%s", msg);
  PetscFunctionReturn(0);
}
