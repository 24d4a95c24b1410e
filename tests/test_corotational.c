/* Co-rotational elasticity: a body rigidly rotated by 90 degrees (about z and about a generic
   axis, plus a translation) has zero elastic force, to 1e-10 relative to the force the linear
   model gives for the same displacement; a small pure stretch gives the linear model's force.
   Runs on any number of ranks (the mesh is distributed). */
#include <fecontact.h>

static PetscErrorCode RotatedDisplacement(FCBody body, const PetscReal axis[3], PetscReal deg, Vec u)
{
  Vec                X;
  const PetscScalar *x;
  PetscScalar       *ua;
  PetscInt           n;
  PetscReal          n2 = PetscSqrtReal(axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]), a[3],
            th = deg * PETSC_PI / 180, c = PetscCosReal(th), s = PetscSinReal(th), R[9];

  PetscFunctionBegin;
  for (int i = 0; i < 3; i++) a[i] = axis[i] / n2;
  /* Rodrigues: R = c I + s [a]x + (1 - c) a a^T */
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) R[3 * i + j] = (i == j ? c : 0.0) + (1 - c) * a[i] * a[j];
  R[1] -= s * a[2];
  R[2] += s * a[1];
  R[3] += s * a[2];
  R[5] -= s * a[0];
  R[6] -= s * a[1];
  R[7] += s * a[0];
  PetscCall(FCBodyFEMGetReferenceCoordinates(body, &X));
  PetscCall(VecGetLocalSize(X, &n));
  PetscCall(VecGetArrayRead(X, &x));
  PetscCall(VecGetArray(u, &ua));
  for (PetscInt k = 0; k < n; k += 3) {
    PetscReal p[3] = {PetscRealPart(x[k]), PetscRealPart(x[k + 1]), PetscRealPart(x[k + 2])};
    for (int i = 0; i < 3; i++)
      ua[k + i] = R[3 * i] * p[0] + R[3 * i + 1] * p[1] + R[3 * i + 2] * p[2] - p[i] + 0.7 * (i + 1);
  }
  PetscCall(VecRestoreArray(u, &ua));
  PetscCall(VecRestoreArrayRead(X, &x));
  PetscCall(VecDestroy(&X));
  PetscFunctionReturn(0);
}

int main(int argc, char **argv)
{
  FCBody          cor, lin;
  Vec             u, ul, fc, fl;
  PetscReal       ncor, nlin, nd;
  const PetscReal axes[2][3] = {{0, 0, 1}, {1, 2, -0.5}};
  int             failed = 0, passed = 0;

  PetscCall(PetscInitialize(&argc, &argv, NULL, NULL));
  PetscCall(PetscOptionsSetValue(NULL, "-cor_dm_plex_filename", "meshes/cube_coarse.msh"));
  PetscCall(PetscOptionsSetValue(NULL, "-lin_dm_plex_filename", "meshes/cube_coarse.msh"));
  PetscCall(FCBodyCreate(PETSC_COMM_WORLD, "cor", &cor));
  PetscCall(FCBodyCreate(PETSC_COMM_WORLD, "lin", &lin));
  PetscCall(PetscOptionsSetValue(NULL, "-cor_material", "corotational"));
  for (int b = 0; b < 2; b++) {
    const char *p = b ? "-lin_" : "-cor_";
    char        o[64];
    PetscCall(PetscSNPrintf(o, sizeof(o), "%stype", p));
    PetscCall(PetscOptionsSetValue(NULL, o, "fem"));
    PetscCall(PetscSNPrintf(o, sizeof(o), "%syoung", p));
    PetscCall(PetscOptionsSetValue(NULL, o, "1e6"));
    PetscCall(PetscSNPrintf(o, sizeof(o), "%sdensity", p));
    PetscCall(PetscOptionsSetValue(NULL, o, "1000"));
  }
  PetscCall(FCBodySetFromOptions(cor));
  PetscCall(FCBodySetFromOptions(lin));
  PetscCall(FCBodySetUp(cor));
  PetscCall(FCBodySetUp(lin));
  PetscCall(FCBodyFEMGetState(cor, &u, NULL));
  PetscCall(VecDuplicate(u, &u));
  PetscCall(VecDuplicate(u, &fc));
  PetscCall(FCBodyFEMGetState(lin, &ul, NULL)); /* each body has its own partition and layout */
  PetscCall(VecDuplicate(ul, &ul));
  PetscCall(VecDuplicate(ul, &fl));
  for (int k = 0; k < 2; k++) {
    PetscCall(RotatedDisplacement(cor, axes[k], 90.0, u));
    PetscCall(RotatedDisplacement(lin, axes[k], 90.0, ul));
    PetscCall(FCBodyFEMComputeElasticForce(cor, u, fc));
    PetscCall(FCBodyFEMComputeElasticForce(lin, ul, fl));
    PetscCall(VecNorm(fc, NORM_2, &ncor));
    PetscCall(VecNorm(fl, NORM_2, &nlin));
    if (ncor <= 1e-10 * nlin)
      passed++;
    else
      failed++;
    PetscCall(
        PetscPrintf(PETSC_COMM_WORLD,
                    "%s: rotation by 90 deg about (%g,%g,%g) + translation: |f_corot| / |f_linear| = %.3e (< 1e-10)\n",
                    ncor <= 1e-10 * nlin ? "PASS" : "FAIL", (double)axes[k][0], (double)axes[k][1], (double)axes[k][2],
                    (double)(ncor / nlin)));
  }
  { /* small stretch u = 1e-4 X: no rotation, so both models give the same force; the bodies'
       layouts differ, so compare the norms of the forces and the work u . f */
    Vec         X;
    PetscScalar wc, wl;
    PetscReal   nc;
    for (int b = 0; b < 2; b++) {
      PetscCall(FCBodyFEMGetReferenceCoordinates(b ? lin : cor, &X));
      PetscCall(VecCopy(X, b ? ul : u));
      PetscCall(VecScale(b ? ul : u, 1e-4));
      PetscCall(VecDestroy(&X));
    }
    PetscCall(FCBodyFEMComputeElasticForce(cor, u, fc));
    PetscCall(FCBodyFEMComputeElasticForce(lin, ul, fl));
    PetscCall(VecNorm(fl, NORM_2, &nlin));
    PetscCall(VecNorm(fc, NORM_2, &nc));
    PetscCall(VecDot(u, fc, &wc));
    PetscCall(VecDot(ul, fl, &wl));
    nd = PetscMax(PetscAbsReal(nc - nlin) / nlin, PetscAbsScalar(wc - wl) / PetscAbsScalar(wl));
    if (nd <= 1e-10)
      passed++;
    else
      failed++;
    PetscCall(PetscPrintf(PETSC_COMM_WORLD,
                          "%s: small stretch: corotational vs linear force norm and work differ by %.3e (< 1e-10)\n",
                          nd <= 1e-10 ? "PASS" : "FAIL", (double)nd));
  }
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "%d passed, %d failed\n", passed, failed));
  PetscCall(VecDestroy(&u));
  PetscCall(VecDestroy(&fc));
  PetscCall(VecDestroy(&fl));
  PetscCall(VecDestroy(&ul));
  PetscCall(FCBodyDestroy(&cor));
  PetscCall(FCBodyDestroy(&lin));
  PetscCall(PetscFinalize());
  return failed ? 1 : 0;
}
