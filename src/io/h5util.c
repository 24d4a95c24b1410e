/* HDF5 helpers of the output files (src/io/ioimpl.h): extendible row datasets, distributed
   fixed-size datasets, attributes. */
#include "ioimpl.h"

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
