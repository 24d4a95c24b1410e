/* bench_pgs: the cost of one contact-solver sweep against its floor, one dense product W r of the
   same size (BLAS dgemv), measured in the same run on the same W.
     bench_pgs -problem file.hdf5 [-sweeps 30] [-repeat 5] [-dense 1] [-pgs_* options]
   The problem is an FCLIB file (e.g. written by fecontact -pgs_dump_problem); -dense 1 (default)
   keeps W dense, as the schemes do, -dense 0 solves it in block-sparse form. The solver runs
   exactly -sweeps sweeps (-pgs_tol 1e-300, warm start 0), -repeat times; the best time is kept,
   and so for the products. Prints rows, contacts, time per sweep, time per dgemv, their ratio. */
#include <fecontact.h>
#include <petscblaslapack.h>

int main(int argc, char **argv)
{
  char             path[PETSC_MAX_PATH_LEN] = "";
  PetscBool        set, dense = PETSC_TRUE;
  FCContactProblem p, pd      = NULL;
  FCContactSolver  s;
  PetscInt         nc, n, sweeps = 30, repeat = 5, done;
  PetscReal       *r, *u, *W = NULL, res, best_sweep = PETSC_MAX_REAL, best_gemv = PETSC_MAX_REAL;

  PetscCall(PetscInitialize(&argc, &argv, NULL, "bench_pgs -problem file.hdf5 [-sweeps 30] [-repeat 5] [-dense 1]\n"));
  PetscCall(FCInitializePackage());
  PetscCall(PetscOptionsGetString(NULL, NULL, "-problem", path, sizeof(path), &set));
  PetscCheck(set, PETSC_COMM_WORLD, PETSC_ERR_USER_INPUT, "Give -problem <file.hdf5> (FCLIB local problem)");
  PetscCall(PetscOptionsGetInt(NULL, NULL, "-sweeps", &sweeps, NULL));
  PetscCall(PetscOptionsGetInt(NULL, NULL, "-repeat", &repeat, NULL));
  PetscCall(PetscOptionsGetBool(NULL, NULL, "-dense", &dense, NULL));
  PetscCheck(sweeps >= 1 && repeat >= 1, PETSC_COMM_WORLD, PETSC_ERR_USER_INPUT, "-sweeps and -repeat must be >= 1");
  PetscCall(FCContactProblemLoadFCLIB(path, &p));
  PetscCall(FCContactProblemGetSizes(p, &nc, &n));
  PetscCall(PetscCalloc2(n, &r, n, &u));
  PetscCall(PetscMalloc1(n * n, &W));
  { /* dense W, row by row: W e_k = (W e_k + q) - q (W symmetric: row k) */
    PetscReal *e, *q;
    PetscCall(PetscCalloc2(n, &e, n, &q));
    PetscCall(FCContactProblemVelocity(p, e, q));
    for (PetscInt k = 0; k < n; k++) {
      e[k] = 1.0;
      PetscCall(FCContactProblemVelocity(p, e, &W[k * n]));
      for (PetscInt j = 0; j < n; j++) W[k * n + j] -= q[j];
      e[k] = 0.0;
    }
    PetscCall(PetscFree2(e, q));
  }
  if (dense) { /* the problem again, dense, with the same q and mu */
    PetscInt  *dim;
    PetscReal *mu, *q, *z;
    PetscCall(PetscMalloc4(nc, &dim, nc, &mu, n, &q, n, &z));
    PetscCall(PetscArrayzero(z, n));
    PetscCall(FCContactProblemVelocity(p, z, q));
    for (PetscInt i = 0; i < nc; i++) dim[i] = n / nc;
    PetscCall(FCContactProblemGetFriction(p, mu));
    PetscCall(FCContactProblemCreateDense(nc, dim, mu, W, q, &pd));
    PetscCall(PetscFree4(dim, mu, q, z));
  }
  PetscCall(FCContactSolverCreate(PETSC_COMM_SELF, &s));
  PetscCall(FCContactSolverSetFromOptions(s));
  PetscCall(FCContactSolverSetTolerances(s, 1e-300, sweeps));
  for (PetscInt k = 0; k < repeat; k++) {
    PetscLogDouble t0, t1;
    PetscCall(PetscArrayzero(r, n));
    PetscCall(PetscTime(&t0));
    PetscCall(FCContactSolverSolve(s, dense ? pd : p, r));
    PetscCall(PetscTime(&t1));
    PetscCall(FCContactSolverGetConvergence(s, &done, &res, NULL));
    best_sweep = PetscMin(best_sweep, (t1 - t0) / done);
  }
  for (PetscInt k = 0; k < repeat; k++) { /* the floor: u = W r + u, sweeps times */
    PetscLogDouble t0, t1;
    PetscBLASInt   bn, one = 1;
    PetscScalar    a = 1.0, b = 1.0;
    PetscCall(PetscBLASIntCast(n, &bn));
    PetscCall(PetscTime(&t0));
    for (PetscInt it = 0; it < sweeps; it++)
      PetscCallBLAS("BLASgemv", BLASgemv_("T", &bn, &bn, &a, W, &bn, r, &one, &b, u, &one));
    PetscCall(PetscTime(&t1));
    best_gemv = PetscMin(best_gemv, (t1 - t0) / sweeps);
  }
  PetscCall(PetscPrintf(PETSC_COMM_WORLD,
                        "rows %" PetscInt_FMT " contacts %" PetscInt_FMT " %s sweep %.4f ms dgemv %.4f ms ratio %.2f "
                        "(residual after %" PetscInt_FMT " sweeps %.2e)\n",
                        n, nc, dense ? "dense" : "sparse", 1e3 * best_sweep, 1e3 * best_gemv, best_sweep / best_gemv,
                        done, (double)res));
  PetscCall(FCContactSolverDestroy(&s));
  PetscCall(FCContactProblemDestroy(&pd));
  PetscCall(FCContactProblemDestroy(&p));
  PetscCall(PetscFree(W));
  PetscCall(PetscFree2(r, u));
  PetscCall(PetscFinalize());
  return 0;
}
