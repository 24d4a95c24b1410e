/* The replay of a recorded partition: -<body>_partition_file <run.h5> distributes the body's mesh
   exactly as in the run that wrote run.h5, whose /bodies/<body>/mesh/rank and cell_origin hold,
   for every cell, the rank that held it and its index in the mesh as read (docs/output.md). A
   parallel run that differs from another (a partition that exposes a bug, ptscotch's partitions,
   which vary from run to run) can so be run again on the same cells per rank. The partition is set
   on PETSc's shell partitioner; the mesh must be the one of that run (same file, same refinement)
   and the number of ranks the same. */
#include "../fcimpl.h"
#include <hdf5.h>
#include <sys/stat.h>

/* Rank 0 reads the two datasets of body `bodyname` from `file` into rank[] and origin[] (n each,
   to be freed); a message in `why` (empty if fine) and *ranks, the attribute of the run's size */
static PetscErrorCode ReadRecorded(const char file[], const char bodyname[], PetscInt *n, PetscInt **rank,
                                   PetscInt **origin, PetscInt *ranks, char why[], size_t len)
{
  struct stat st;
  hid_t       f, d[2] = {-1, -1}, g = -1;
  const char *names[2] = {"rank", "cell_origin"};
  char        path[PETSC_MAX_PATH_LEN];
  long long   nranks = -1;

  PetscFunctionBegin;
  why[0] = 0;
  *n     = 0;
  *rank = *origin = NULL;
  if (stat(file, &st) || !S_ISREG(st.st_mode)) {
    PetscCall(PetscSNPrintf(why, len, "cannot open it"));
    PetscFunctionReturn(0);
  }
  H5E_BEGIN_TRY
  {
    f = H5Fopen(file, H5F_ACC_RDONLY, H5P_DEFAULT);
  }
  H5E_END_TRY;
  if (f < 0) {
    PetscCall(PetscSNPrintf(why, len, "not an HDF5 file"));
    PetscFunctionReturn(0);
  }
  PetscCall(PetscSNPrintf(path, sizeof(path), "/bodies/%s/mesh", bodyname));
  H5E_BEGIN_TRY
  {
    g = H5Gopen2(f, path, H5P_DEFAULT);
    for (int k = 0; k < 2 && g >= 0; k++) d[k] = H5Dopen2(g, names[k], H5P_DEFAULT);
    if (g >= 0 && H5Aexists(g, "ranks") > 0) {
      hid_t a = H5Aopen(g, "ranks", H5P_DEFAULT);
      if (a >= 0 && H5Aread(a, H5T_NATIVE_LLONG, &nranks) < 0) nranks = -1;
      if (a >= 0) H5Aclose(a);
    }
  }
  H5E_END_TRY;
  if (d[0] < 0 || d[1] < 0 || nranks < 1) {
    PetscCall(PetscSNPrintf(why, len,
                            "it has no recorded partition of body '%s' (%s/rank, cell_origin and its attribute ranks)",
                            bodyname, path));
  } else {
    hsize_t dims[2][2] = {{0, 0}, {0, 0}};
    for (int k = 0; k < 2; k++) {
      hid_t sp = H5Dget_space(d[k]);
      if (H5Sget_simple_extent_ndims(sp) != 1)
        dims[k][0] = (hsize_t)-1;
      else
        H5Sget_simple_extent_dims(sp, dims[k], NULL);
      H5Sclose(sp);
    }
    if (dims[0][0] != dims[1][0] || dims[0][0] == (hsize_t)-1) {
      PetscCall(PetscSNPrintf(why, len, "its %s/rank and cell_origin are not two lists of the same length", path));
    } else {
      long long *buf;
      *n = (PetscInt)dims[0][0];
      PetscCall(PetscMalloc1(2 * (*n) + 1, &buf));
      PetscCall(PetscMalloc2(*n + 1, rank, *n + 1, origin));
      if (H5Dread(d[0], H5T_NATIVE_LLONG, H5S_ALL, H5S_ALL, H5P_DEFAULT, buf) < 0 ||
          H5Dread(d[1], H5T_NATIVE_LLONG, H5S_ALL, H5S_ALL, H5P_DEFAULT, buf + *n) < 0)
        PetscCall(PetscSNPrintf(why, len, "its %s/rank or cell_origin cannot be read", path));
      for (PetscInt i = 0; i < *n; i++) {
        (*rank)[i]   = (PetscInt)buf[i];
        (*origin)[i] = (PetscInt)buf[*n + i];
      }
      PetscCall(PetscFree(buf));
    }
  }
  for (int k = 0; k < 2; k++)
    if (d[k] >= 0) H5Dclose(d[k]);
  if (g >= 0) H5Gclose(g);
  H5Fclose(f);
  *ranks = (PetscInt)nranks;
  PetscFunctionReturn(0);
}

PetscErrorCode FCMeshPartitionReplay(DM serial, PetscPartitioner part, const char prefix[], const char bodyname[])
{
  char        file[PETSC_MAX_PATH_LEN], why[PETSC_MAX_PATH_LEN + 256] = "";
  PetscBool   set, typed;
  MPI_Comm    comm = PetscObjectComm((PetscObject)serial);
  PetscMPIInt rank, size;
  PetscInt    cStart, cEnd, nc, n = 0, ranks = 0, *rk = NULL, *origin = NULL, *sizes, *points = NULL;

  PetscFunctionBegin;
  PetscCall(PetscOptionsGetString(NULL, prefix, "-partition_file", file, sizeof(file), &set));
  if (!set) PetscFunctionReturn(0);
  PetscCall(PetscOptionsHasName(NULL, prefix, "-petscpartitioner_type", &typed));
  PetscCheck(!typed, comm, PETSC_ERR_USER_INPUT,
             "Body '%s': -%spartition_file replays a recorded partition, -%spetscpartitioner_type would choose "
             "another: give one of them",
             bodyname, prefix, prefix);
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCallMPI(MPI_Comm_size(comm, &size));
  PetscCall(DMPlexGetHeightStratum(serial, 0, &cStart, &cEnd));
  nc = cEnd - cStart; /* all on rank 0: the mesh is read there */
  PetscCall(PetscCalloc1(size, &sizes));
  if (!rank) {
    PetscCall(ReadRecorded(file, bodyname, &n, &rk, &origin, &ranks, why, sizeof(why)));
    if (!why[0] && ranks != size)
      PetscCall(PetscSNPrintf(why, sizeof(why), "it was run on %" PetscInt_FMT " ranks, this run has %d", ranks, size));
    if (!why[0] && n != nc)
      PetscCall(PetscSNPrintf(why, sizeof(why),
                              "it records %" PetscInt_FMT " cells, the mesh of this run has %" PetscInt_FMT
                              " (not the same mesh or refinement)",
                              n, nc));
    if (!why[0]) { /* every cell once, on a rank of the run: sizes and the cells grouped by rank */
      PetscInt *seen, *next;
      PetscCall(PetscCalloc2(nc + 1, &seen, size + 1, &next));
      PetscCall(PetscMalloc1(nc + 1, &points));
      for (PetscInt i = 0; i < n && !why[0]; i++) {
        if (rk[i] < 0 || rk[i] >= size || origin[i] < 0 || origin[i] >= nc || seen[origin[i]]++)
          PetscCall(PetscSNPrintf(why, sizeof(why),
                                  "its entry %" PetscInt_FMT " (rank %" PetscInt_FMT ", cell %" PetscInt_FMT
                                  ") is out of range or repeats a cell",
                                  i, rk[i], origin[i]));
        else
          sizes[rk[i]]++;
      }
      for (PetscMPIInt r = 1; r <= size; r++) next[r] = next[r - 1] + sizes[r - 1];
      for (PetscInt c = 0; c < nc && !why[0]; c++) seen[c] = -1;
      for (PetscInt i = 0; i < n && !why[0]; i++) seen[origin[i]] = rk[i];
      for (PetscInt c = 0; c < nc && !why[0]; c++) points[next[seen[c]]++] = c; /* increasing within a rank */
      PetscCall(PetscFree2(seen, next));
    }
    PetscCall(PetscFree2(rk, origin));
  }
  PetscCallMPI(MPI_Bcast(why, sizeof(why), MPI_CHAR, 0, comm));
  PetscCheck(!why[0], comm, PETSC_ERR_USER_INPUT,
             "Body '%s': cannot replay the partition of '%s' (-%spartition_file): %s", bodyname, file, prefix, why);
  {
    char what[256];
    PetscCall(PetscSNPrintf(what, sizeof(what), "partition of body '%s' (-%spartition_file)", bodyname, prefix));
    PetscCall(FCInputsAdd(file, what));
  }
  if (rank) PetscCall(PetscArrayzero(sizes, size));
  PetscCall(PetscPartitionerSetType(part, PETSCPARTITIONERSHELL));
  PetscCall(PetscPartitionerShellSetPartition(part, size, sizes, points));
  PetscCall(PetscFree(sizes));
  PetscCall(PetscFree(points));
  PetscFunctionReturn(0);
}
