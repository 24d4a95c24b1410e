/* Disk space for the output, reserved before HDF5 is asked to write (src/io/ioimpl.h). Parallel
   HDF5 1.10 does not survive a write that fails on one rank inside its own collective operations
   (chunk allocation, metadata flush): that rank leaves the operation, the others wait in it for
   ever, and a file whose metadata cannot be written cannot be closed. So a full disk is met here,
   outside HDF5: before the header and before every output step, rank 0 allocates the space the
   writes will need beyond HDF5's end of allocation (EOA) and its failure is agreed by all ranks
   (FCH5Agree) while HDF5 holds nothing unwritten, so that the file closes cleanly.

   The space is allocated as part of the file (fallocate mode 0: the file's size grows), not kept
   beyond its end: HDF5 1.10 writes the superblock's EOA at a flush before the file has grown to
   it (a chunk allocated but not yet written, fill values off), and a process killed then leaves a
   file shorter than its superblock says, which HDF5 refuses to open at all ("truncated file").
   With the file always at least EOA + the reservation long, that cannot happen; the zeros beyond
   the EOA are cut off when the file is closed (FCH5Release). Where fallocate is not supported
   (some network file systems) the file is only extended (ftruncate, sparse: nothing reserved) and
   the file system's free space (statvfs) must hold what the writes will need beyond the blocks the
   file has: a full disk is then still met here, unless another process fills it in between (a
   failure inside HDF5 is collective per call, FCH5Check, but HDF5 1.10 may not survive it: a
   hang on several ranks, a file it cannot close). A file that is not a regular file (a device) is
   probed by writing a byte. */
#define _GNU_SOURCE
#include "ioimpl.h"
#include <fcntl.h>
#include <sys/stat.h>
#include <sys/statvfs.h>
#include <unistd.h>

PetscErrorCode FCH5Reserve(MPI_Comm comm, const char file[], hid_t h5, size_t bytes, const char what[])
{
  PetscMPIInt rank;
  int         ok = 1, err = 0;
  char        msg[256];

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  /* FECONTACT_NO_RESERVE=1: as where fallocate is not supported (the tests use it) */
  if (rank == 0) {
    int         fd = open(file, O_WRONLY);
    struct stat st;
    if (fd < 0 && errno == ENOENT) {
      /* not created yet: nothing to reserve */
    } else if (fd < 0 || fstat(fd, &st)) {
      ok  = 0;
      err = errno;
    } else if (S_ISREG(st.st_mode)) {
      haddr_t eoa = 0;
      off_t   end;
      if (h5 < 0 || H5Fget_eoa(h5, &eoa) < 0) eoa = (haddr_t)st.st_size;
      end = (off_t)(eoa + bytes);
      if (end > st.st_size && (getenv("FECONTACT_NO_RESERVE") ? (errno = EOPNOTSUPP, -1)
                                                              : fallocate(fd, 0, st.st_size, end - st.st_size))) {
        if (errno == EOPNOTSUPP || errno == ENOSYS) { /* sparse, and the free space checked */
          struct statvfs fs;
          off_t          have = (off_t)st.st_blocks * 512;
          if (!fstatvfs(fd, &fs) && end > have && (off_t)fs.f_bavail * (off_t)fs.f_frsize < end - have) {
            ok  = 0;
            err = ENOSPC;
          } else if (ftruncate(fd, end)) {
            ok  = 0;
            err = errno;
          }
        } else {
          ok  = 0;
          err = errno;
        }
      }
    } else if (S_ISCHR(st.st_mode) || S_ISBLK(st.st_mode)) {
      const char zero = 0;
      if (write(fd, &zero, 1) != 1) {
        ok  = 0;
        err = errno;
      }
    }
    if (fd >= 0) close(fd);
  }
  PetscCall(PetscSNPrintf(msg, sizeof(msg), "reserving %zu bytes for %s", bytes, what));
  PetscCall(FCH5AgreeClean(ok, err, msg));
  PetscFunctionReturn(0);
}

/* Cuts what was reserved beyond HDF5's end of allocation (after the file is closed by every rank:
   rank 0 reads the EOA the closed file records and truncates the file to it) */
PetscErrorCode FCH5Release(MPI_Comm comm, const char file[])
{
  PetscMPIInt rank;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  if (rank == 0) {
    struct stat st;
    haddr_t     eoa = 0;
    hid_t       f   = stat(file, &st) || !S_ISREG(st.st_mode) ? -1 : H5Fopen(file, H5F_ACC_RDONLY, H5P_DEFAULT);
    if (f >= 0) {
      if (H5Fget_eoa(f, &eoa) < 0) eoa = 0;
      H5Fclose(f);
    }
    if (eoa > 0 && (off_t)eoa < st.st_size) (void)!truncate(file, (off_t)eoa);
  }
  PetscFunctionReturn(0);
}
