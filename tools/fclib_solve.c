/* fclib_solve: solve a local frictional contact problem stored in the FCLIB HDF5 layout with
   fecontact's contact solver; prints contacts, sweeps, residual and time, and writes r and u.
     fclib_solve -problem file.hdf5 [-pgs_tol 1e-8] [-pgs_max_it N] [-solution out.h5] [-dense] [-repeat k]
   -repeat k: solve k times, each from r = 0 (default 1); the time printed is the fastest (caches
   warm, the machine's noise out), the sweeps and forces are the last solve's (the same each time).
   -dense: W expanded to a dense array (what the schemes hand the solver), which -pgs_ranks split
   needs; the solver then runs on PETSC_COMM_WORLD, so that `mpirun -n p fclib_solve -dense
   -pgs_ranks split` times the split sweeps on p ranks (every rank reads the problem). */
#include <fecontact.h>
#include <hdf5.h>

static PetscErrorCode WriteVector(hid_t f, const char name[], PetscInt n, const PetscReal v[])
{
  hsize_t dims = (hsize_t)n;
  hid_t   s    = H5Screate_simple(1, &dims, NULL),
        d      = H5Dcreate2(f, name, H5T_NATIVE_DOUBLE, s, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);

  PetscFunctionBegin;
  PetscCheck(d >= 0 && H5Dwrite(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v) >= 0, PETSC_COMM_SELF,
             PETSC_ERR_FILE_WRITE, "Cannot write %s", name);
  H5Dclose(d);
  H5Sclose(s);
  PetscFunctionReturn(0);
}

int main(int argc, char **argv)
{
  char             path[PETSC_MAX_PATH_LEN] = "", sol[PETSC_MAX_PATH_LEN] = "";
  PetscBool        set, conv, dense = PETSC_FALSE;
  PetscInt         repeat = 1;
  PetscLogDouble   best   = PETSC_MAX_REAL;
  PetscReal       *Wd     = NULL;
  FCContactProblem p;
  FCContactSolver  s;
  PetscInt         nc, n, sweeps;
  PetscReal       *r, *u, res, abs;
  PetscLogDouble   t0, t1;
  PetscMPIInt      rank;

  PetscCall(PetscInitialize(&argc, &argv, NULL, "fclib_solve -problem file.hdf5 [-solution out.h5]\n"));
  PetscCall(FCInitializePackage());
  PetscCall(PetscOptionsGetString(NULL, NULL, "-problem", path, sizeof(path), &set));
  PetscCheck(set, PETSC_COMM_WORLD, PETSC_ERR_USER_INPUT, "Give -problem <file.hdf5> (FCLIB local problem)");
  PetscCall(PetscOptionsGetString(NULL, NULL, "-solution", sol, sizeof(sol), NULL));
  PetscCall(FCContactProblemLoadFCLIB(path, &p));
  PetscCall(FCContactProblemGetSizes(p, &nc, &n));
  PetscCall(PetscOptionsGetBool(NULL, NULL, "-dense", &dense, NULL));
  PetscCall(PetscOptionsGetInt(NULL, NULL, "-repeat", &repeat, NULL));
  PetscCheck(repeat >= 1, PETSC_COMM_WORLD, PETSC_ERR_USER_INPUT, "Option -repeat must be >= 1, got %" PetscInt_FMT,
             repeat);
  if (dense) { /* the same problem with W dense */
    FCContactProblem pd;
    PetscInt        *dim;
    PetscReal       *mu, *q, *zero;
    PetscCall(PetscMalloc4(nc, &dim, nc, &mu, n, &q, n, &zero));
    PetscCall(FCContactProblemGetDenseW(p, &Wd));
    PetscCall(FCContactProblemGetFriction(p, mu));
    for (PetscInt i = 0; i < n; i++) zero[i] = 0.0;
    PetscCall(FCContactProblemVelocity(p, zero, q)); /* q = W 0 + q */
    for (PetscInt i = 0; i < nc; i++) dim[i] = n / nc;
    PetscCall(FCContactProblemCreateDense(nc, dim, mu, Wd, q, &pd));
    PetscCall(PetscFree4(dim, mu, q, zero));
    PetscCall(FCContactProblemDestroy(&p));
    p = pd;
  }
  PetscCall(FCContactSolverCreate(dense ? PETSC_COMM_WORLD : PETSC_COMM_SELF, &s));
  PetscCall(FCContactSolverSetFromOptions(s));
  PetscCall(PetscCalloc2(n, &r, n, &u));
  for (PetscInt k = 0; k < repeat; k++) {
    PetscCall(PetscArrayzero(r, n));
    PetscCallMPI(MPI_Barrier(PETSC_COMM_WORLD));
    PetscCall(PetscTime(&t0));
    PetscCall(FCContactSolverSolve(s, p, r));
    PetscCall(PetscTime(&t1));
    best = PetscMin(best, t1 - t0);
  }
  PetscCall(FCContactSolverGetConvergence(s, &sweeps, &res, &conv));
  PetscCall(FCContactProblemResidual(p, r, &abs, NULL));
  PetscCall(PetscPrintf(PETSC_COMM_WORLD,
                        "problem %s contacts %" PetscInt_FMT " rows %" PetscInt_FMT " sweeps %" PetscInt_FMT
                        " residual %.12e absolute %.12e converged %d time %.6f\n",
                        path, nc, n, sweeps, (double)res, (double)abs, (int)conv, best));
  PetscCallMPI(MPI_Comm_rank(PETSC_COMM_WORLD, &rank));
  if (sol[0] && !rank) { /* every rank has the forces: rank 0 writes them */
    hid_t f = H5Fcreate(sol, H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
    PetscCheck(f >= 0, PETSC_COMM_SELF, PETSC_ERR_USER_INPUT, "Cannot create %s", sol);
    PetscCall(FCContactProblemVelocity(p, r, u));
    PetscCall(WriteVector(f, "r", n, r));
    PetscCall(WriteVector(f, "u", n, u));
    H5Fclose(f);
  }
  PetscCall(PetscFree2(r, u));
  PetscCall(FCContactSolverDestroy(&s));
  PetscCall(FCContactProblemDestroy(&p));
  PetscCall(PetscFree(Wd));
  PetscCall(PetscFinalize());
  return 0;
}
