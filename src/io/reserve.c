/* Disk space for the output, reserved before HDF5 is asked to write (src/io/ioimpl.h). Parallel
   HDF5 1.10 does not survive a write that fails on one rank inside its own collective operations
   (chunk allocation, metadata flush): that rank leaves the operation, the others wait in it for
   ever, and a file whose metadata cannot be written cannot be closed. So a full disk is met here,
   outside HDF5: before the header and before every output step, rank 0 allocates the space the
   writes will need beyond the end of the file (fallocate, FALLOC_FL_KEEP_SIZE: the file's size is
   unchanged, HDF5 sees nothing), and its failure is agreed by all ranks (FCH5Agree) while HDF5
   holds nothing unwritten, so that the file closes cleanly. Where fallocate is not supported
   (some network file systems) nothing is reserved and a failure inside HDF5 is still collective
   per call (FCH5Check), but may hang or leave the file unclosable; a file that is not a regular
   file (a device) is probed by writing a byte. */
#define _GNU_SOURCE
#include "ioimpl.h"
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

PetscErrorCode FCH5Reserve(MPI_Comm comm, const char file[], size_t bytes, const char what[])
{
  PetscMPIInt rank;
  int         ok = 1, err = 0;
  char        msg[256];

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  /* FECONTACT_NO_RESERVE=1: no reservation, as where fallocate is not supported (the tests use it
     to reach the failure of a write inside HDF5) */
  if (rank == 0 && !getenv("FECONTACT_NO_RESERVE")) {
    int         fd = open(file, O_WRONLY);
    struct stat st;
    if (fd < 0 && errno == ENOENT) {
      /* not created yet: nothing to reserve */
    } else if (fd < 0 || fstat(fd, &st)) {
      ok  = 0;
      err = errno;
    } else if (S_ISREG(st.st_mode)) {
      if (fallocate(fd, FALLOC_FL_KEEP_SIZE, st.st_size, (off_t)bytes) && errno != EOPNOTSUPP && errno != ENOSYS) {
        ok  = 0;
        err = errno;
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

/* Gives back what was reserved beyond the end of the file (after the file is closed) */
PetscErrorCode FCH5Release(MPI_Comm comm, const char file[])
{
  PetscMPIInt rank;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  if (rank == 0) {
    int         fd = open(file, O_WRONLY);
    struct stat st;
    if (fd >= 0 && !fstat(fd, &st) && S_ISREG(st.st_mode)) (void)!ftruncate(fd, st.st_size);
    if (fd >= 0) close(fd);
  }
  PetscFunctionReturn(0);
}

/* The size of the file (rank 0's view, 0 on the others and where unknown) */
size_t FCH5FileSize(const char file[])
{
  struct stat st;
  return stat(file, &st) || !S_ISREG(st.st_mode) ? 0 : (size_t)st.st_size;
}
