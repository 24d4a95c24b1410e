/* HDF5 helpers of the output files (src/io/ioimpl.h): extendible row datasets, distributed
   fixed-size datasets, attributes. */
#include "ioimpl.h"
#include <sys/statvfs.h>

/* ---------------------------------------------------------------------------------------------
   Collective errors of the output file
   --------------------------------------------------------------------------------------------- */
static struct {
  PetscBool active, failed, inside; /* inside: the failure was inside HDF5 */
  MPI_Comm  comm;
  char      file[PETSC_MAX_PATH_LEN];
} ctx;

PetscErrorCode FCH5ContextSet(MPI_Comm comm, const char filename[])
{
  PetscFunctionBegin;
  ctx.active = PETSC_TRUE;
  ctx.failed = ctx.inside = PETSC_FALSE;
  ctx.comm                = comm;
  PetscCall(PetscStrncpy(ctx.file, filename, sizeof(ctx.file)));
  PetscFunctionReturn(0);
}

PetscErrorCode FCH5ContextClear(void)
{
  PetscFunctionBegin;
  ctx.active = ctx.failed = ctx.inside = PETSC_FALSE;
  PetscFunctionReturn(0);
}

PetscBool FCH5Failed(void)
{
  return ctx.active && ctx.failed ? PETSC_TRUE : PETSC_FALSE;
}

PetscBool FCH5FailedInside(void)
{
  return ctx.active && ctx.failed && ctx.inside ? PETSC_TRUE : PETSC_FALSE;
}

PetscBool FCOutputFileLeftOpen(void)
{
  return FCH5FailedInside();
}

/* The innermost (most specific) description of HDF5's error stack, and whether any record of
   it says that the device is full (MPI-IO's error strings do, when errno is lost on the way) */
typedef struct {
  char      inner[256];
  PetscBool nospace;
} StackInfo;

static herr_t ReadStack(unsigned n, const H5E_error2_t *e, void *ctxp)
{
  StackInfo *info = (StackInfo *)ctxp;
  if (n == 0 && e->desc) snprintf(info->inner, sizeof(info->inner), "HDF5 %s(): %s", e->func_name, e->desc);
  if (e->desc && (strstr(e->desc, "No space") || strstr(e->desc, "no space") || strstr(e->desc, "NO_SPACE") ||
                  strstr(e->desc, "quota")))
    info->nospace = PETSC_TRUE;
  return 0;
}

static PetscErrorCode Agree(int ok, int err, const char what[], PetscBool inside)
{
  char        cause[256] = "";
  PetscMPIInt rank       = 0, first;
  int         fail[2];

  PetscFunctionBegin;
  if (!ok) {
    StackInfo info = {"", PETSC_FALSE};
    H5Ewalk2(H5E_DEFAULT, H5E_WALK_UPWARD, ReadStack, &info);
    /* MPI-IO may report a short write without errno: then the file system's free space tells */
    if (!info.nospace && ctx.active && err != ENOSPC) {
      struct statvfs fs;
      if (!statvfs(ctx.file, &fs) && (double)fs.f_bavail * fs.f_frsize < 65536.0) info.nospace = PETSC_TRUE;
    }
    if (err == ENOSPC || err == EDQUOT || info.nospace)
      PetscCall(PetscSNPrintf(cause, sizeof(cause), "no space left on device"));
    else if (err)
      PetscCall(PetscSNPrintf(cause, sizeof(cause), "%s", strerror(err)));
    else
      PetscCall(PetscSNPrintf(cause, sizeof(cause), "%s", info.inner[0] ? info.inner : "HDF5 reports no cause"));
  }
  if (!ctx.active) {
    PetscCheck(ok, PETSC_COMM_SELF, PETSC_ERR_FILE_WRITE, "HDF5 failed: %s (%s)", what, cause);
    PetscFunctionReturn(0);
  }
  PetscCallMPI(MPI_Comm_rank(ctx.comm, &rank));
  fail[0] = ok ? 0 : 1;
  fail[1] = ok ? PETSC_MPI_INT_MAX : rank;
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &fail[0], 1, MPI_INT, MPI_MAX, ctx.comm));
  if (!fail[0]) PetscFunctionReturn(0);
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &fail[1], 1, MPI_INT, MPI_MIN, ctx.comm));
  first = fail[1]; /* the cause as the first failing rank saw it */
  PetscCallMPI(MPI_Bcast(cause, sizeof(cause), MPI_CHAR, first, ctx.comm));
  ctx.failed = PETSC_TRUE;
  ctx.inside = inside;
  SETERRQ(ctx.comm, PETSC_ERR_FILE_WRITE, "Cannot write the output file '%s' (-output_file): %s (%s, rank %d)",
          ctx.file, cause, what, first);
}

PetscErrorCode FCH5Agree(int ok, int err, const char what[])
{
  return Agree(ok, err, what, PETSC_TRUE);
}

PetscErrorCode FCH5AgreeClean(int ok, int err, const char what[])
{
  return Agree(ok, err, what, PETSC_FALSE);
}

PetscErrorCode FCH5CreateRows(hid_t loc, const char name[], hid_t type, int rank, const hsize_t rowdims[],
                              hsize_t chunkrows, hid_t *dset)
{
  hsize_t dims[3] = {0, 0, 0}, maxdims[3] = {H5S_UNLIMITED, 0, 0}, chunk[3] = {chunkrows, 0, 0};
  hid_t   space, plist;

  PetscFunctionBegin;
  for (int i = 1; i < rank; i++) dims[i] = maxdims[i] = chunk[i] = rowdims[i - 1];
  space = H5Screate_simple(rank, dims, maxdims);
  plist = H5Pcreate(H5P_DATASET_CREATE);
  FCH5Check(H5Pset_chunk(plist, rank, chunk), "chunk");
  /* every row is written: no fill values, so that extending writes nothing (in parallel HDF5 the
     fill is a collective write inside H5Dset_extent, whose failure on one rank hangs the others) */
  FCH5Check(H5Pset_fill_time(plist, H5D_FILL_TIME_NEVER), "fill time");
  *dset = H5Dcreate2(loc, name, type, space, H5P_DEFAULT, plist, H5P_DEFAULT);
  FCH5Check(*dset, name);
  H5Pclose(plist);
  H5Sclose(space);
  PetscFunctionReturn(0);
}

PetscErrorCode FCH5AppendRows(PetscMPIInt myrank, hid_t dset, hid_t memtype, hsize_t n, const void *data)
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
  if (myrank == 0) {
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

PetscErrorCode FCH5WriteDistributed(hid_t loc, const char name[], hid_t filetype, hid_t memtype, hsize_t rows,
                                    hsize_t cols, hsize_t start, hsize_t n, const void *data)
{
  hsize_t dims[2] = {rows, cols}, s[2] = {start, 0}, c[2] = {n, cols};
  int     rank   = cols ? 2 : 1; /* cols 0: a list (rows,) */
  hid_t   fspace = H5Screate_simple(rank, dims, NULL), dset, mspace;

  PetscFunctionBegin;
  dset = H5Dcreate2(loc, name, filetype, fspace, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  FCH5Check(dset, name);
  if (n) {
    H5Sselect_hyperslab(fspace, H5S_SELECT_SET, s, NULL, c, NULL);
    mspace = H5Screate_simple(rank, c, NULL);
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

PetscErrorCode FCH5AttrString(hid_t loc, const char name[], const char value[])
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

PetscErrorCode FCH5AttrReals(hid_t loc, const char name[], hsize_t n, const double v[])
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

PetscErrorCode FCH5AttrInt(hid_t loc, const char name[], long long v)
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
