/* Co-rotational elasticity: a body rigidly rotated by 90 degrees (about z and about a generic
   axis, plus a translation) has zero elastic force, to 1e-10 relative to the force the linear
   model gives for the same displacement; a small pure stretch gives the linear model's force.
   Runs on any number of ranks (the mesh is distributed).
   One element turned inside out (a vertex pushed through the opposite face, the element turned
   and moved as well): its internal force undoes the inversion (a small step along the force -f
   raises the signed smallest stretch of F, and where the vertex is a little through, J = det F
   too, at first order and over the step), and is continuous through J = 0 (J = -1e-9, 0, 1e-9
   give the same force to 1e-6 of its size): the invertible-FEM rotation of FCMat3Polar. */
#include <fecontact.h>
#include "material/material.h"

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

/* J = det F of one element of reference Dm^-1 at positions x */
static PetscReal VolumeRatio(const PetscReal x[12], const PetscReal Dminv[9])
{
  PetscReal F[9];
  FCMaterialDeformationGradient(x, Dminv, F);
  return FCMat3Det(F);
}

/* The unit tetrahedron with vertex 3 at (0.2, 0.1, z) (J = z), turned by R and moved by (0.7, 1.4,
   2.1): its positions x and internal force f (the energy's gradient: the force on the vertices is -f) */
static PetscErrorCode InvertedElement(FCMaterial m, const PetscReal R[9], PetscReal z, PetscReal x[12], PetscReal f[12])
{
  const PetscReal X[12] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1}, Dminv[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  PetscReal       y[12];

  PetscFunctionBegin;
  for (int k = 0; k < 12; k++) y[k] = X[k];
  y[9]  = 0.2;
  y[10] = 0.1;
  y[11] = z;
  for (int a = 0; a < 4; a++) {
    FCMat3Vec(R, &y[3 * a], &x[3 * a]);
    for (int i = 0; i < 3; i++) x[3 * a + i] += 0.7 * (i + 1);
  }
  PetscCall((*m->element)(m, x, X, Dminv, 1.0 / 6.0, f, NULL));
  PetscFunctionReturn(0);
}

/* The signed smallest singular value of F (negative when J < 0): the element's extent, over its
   reference one, along the direction it is flattened or turned through; from the smallest
   eigenvalue of F^T F in closed form (Smith 1961), independent of FCMat3Polar's */
static PetscReal SignedSmallestStretch(const PetscReal x[12], const PetscReal Dminv[9])
{
  PetscReal F[9], C[9], q, p1, p2, p, B[9], r, phi, e;
  FCMaterialDeformationGradient(x, Dminv, F);
  FCMat3MultTranspose(F, F, C);
  q  = (C[0] + C[4] + C[8]) / 3.0;
  p1 = C[1] * C[1] + C[2] * C[2] + C[5] * C[5];
  p2 = (C[0] - q) * (C[0] - q) + (C[4] - q) * (C[4] - q) + (C[8] - q) * (C[8] - q) + 2.0 * p1;
  p  = PetscSqrtReal(p2 / 6.0);
  for (int i = 0; i < 9; i++) B[i] = (C[i] - (i % 4 == 0 ? q : 0.0)) / p;
  r   = PetscMax(-1.0, PetscMin(1.0, FCMat3Det(B) / 2.0));
  phi = PetscAcosReal(r) / 3.0;
  e   = q + 2.0 * p * PetscCosReal(phi + 2.0 * PETSC_PI / 3.0);
  return (FCMat3Det(F) < 0 ? -1.0 : 1.0) * PetscSqrtReal(PetscMax(e, 0.0));
}

/* The element checks of the header. A step along -f raises the signed smallest stretch at every
   inversion (J = -1e-9 to -3), and J itself where a vertex is pushed a little through (J = -1e-9 to
   -0.3); deeper, with the three stretches near 1 in size, the volume term first widens the element
   in its other directions, which lowers J while the flattened direction comes back. f is finite and
   continuous at J = -1e-9, 0, 1e-9 */
static PetscErrorCode InvertedChecks(int *passed, int *failed)
{
  const PetscReal Dminv[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1}, axis[3] = {1, 2, -0.5};
  const PetscReal zs[6] = {-1e-9, -0.1, -0.3, -0.9, -1.2, -3.0};
  PetscReal       q[4], R[9], x[12], f[12], fp[12], fz[12], J, dJ[12], work, jump = 0.0, nf = 0.0, step;
  FCMaterial      m;
  PetscBool       ok;

  PetscFunctionBegin;
  PetscCall(FCMaterialCreate("corotational", 1e6, 0.3, &m));
  FCQuatFromAxisAngle(axis, 0.8, q);
  FCQuatToMat3(q, R);
  for (int k = 0; k < 6; k++) {
    PetscReal xs[12], fmax = 0.0, s0, s1, J1;
    PetscCall(InvertedElement(m, R, zs[k], x, f));
    J    = VolumeRatio(x, Dminv);
    work = 0.0;
    for (int i = 0; i < 12; i++) { /* J is linear in each coordinate: the difference is its derivative */
      for (int j = 0; j < 12; j++) xs[j] = x[j];
      xs[i] += 1e-3;
      dJ[i] = (VolumeRatio(xs, Dminv) - J) / 1e-3;
      work -= f[i] * dJ[i];
      fmax = PetscMax(fmax, PetscAbsReal(f[i]));
    }
    step = 1e-3 / fmax; /* the vertex that moves most moves by 1e-3 of an edge */
    for (int i = 0; i < 12; i++) xs[i] = x[i] - step * f[i];
    s0 = SignedSmallestStretch(x, Dminv);
    s1 = SignedSmallestStretch(xs, Dminv);
    J1 = VolumeRatio(xs, Dminv);
    if (zs[k] >= -0.3) {
      ok = (PetscBool)(J < 0 && s1 > s0 && work > 0 && J1 > J);
      PetscCall(
          PetscPrintf(PETSC_COMM_WORLD,
                      "%s: inverted element, J = %.1e: -f . dJ/dx = %.3e (> 0); a step along -f: J %+.3e, smallest "
                      "stretch %.4f %+.3e (> 0)\n",
                      ok ? "PASS" : "FAIL", (double)J, (double)work, (double)(J1 - J), (double)s0, (double)(s1 - s0)));
    } else {
      ok = (PetscBool)(J < 0 && s1 > s0);
      PetscCall(PetscPrintf(PETSC_COMM_WORLD,
                            "%s: inverted element, J = %.1e: a step along -f: smallest stretch %.4f %+.3e (> 0) (J "
                            "%+.3e)\n",
                            ok ? "PASS" : "FAIL", (double)J, (double)s0, (double)(s1 - s0), (double)(J1 - J)));
    }
    if (ok)
      (*passed)++;
    else
      (*failed)++;
  }
  PetscCall(InvertedElement(m, R, 1e-9, x, fp));
  PetscCall(InvertedElement(m, R, 0.0, x, fz));
  PetscCall(InvertedElement(m, R, -1e-9, x, f));
  for (int i = 0; i < 12; i++) {
    nf   = PetscMax(nf, PetscAbsReal(f[i]));
    jump = PetscMax(jump, PetscMax(PetscAbsReal(fp[i] - f[i]), PetscAbsReal(fz[i] - f[i])));
  }
  ok = (PetscBool)(!PetscIsInfOrNanReal(nf) && !PetscIsInfOrNanReal(jump) && nf > 0 && jump <= 1e-6 * nf);
  if (ok)
    (*passed)++;
  else
    (*failed)++;
  PetscCall(PetscPrintf(PETSC_COMM_WORLD,
                        "%s: through J = 0 (J = 1e-9, 0, -1e-9): largest force %.3e, largest change %.3e (<= 1e-6 of "
                        "it)\n",
                        ok ? "PASS" : "FAIL", (double)nf, (double)jump));
  PetscCall(FCMaterialDestroy(&m));
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
  PetscCall(InvertedChecks(&passed, &failed));
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
