/* Hyperelastic materials (neohookean, stvk) at the element level, on a distributed mesh (any number
   of ranks):
   - patch test: a homogeneous deformation u = (F - I) X + c gives no force at the interior vertices
     (to 1e-10 of the largest force), and the forces on the boundary vertices sum to zero;
   - objectivity: a rigid rotation of a deformed body leaves its elastic energy unchanged and turns
     its forces with it (to 1e-12 relative);
   - small-strain limit: at a displacement gradient of 1e-7 the force is linear elasticity's with the
     same Lame parameters, to 1e-6 relative (norms and work, the bodies' layouts being their own). */
#include <fecontact.h>
#include "util/util.h"

/* u = R (F X) - X + shift (1, 2, 3), R the rotation by th about axis (no shift at small strain: its
   work on the round-off of the forces would hide the comparison) */
static PetscErrorCode Deform(FCBody body, const PetscReal F[9], const PetscReal axis[3], PetscReal th, PetscReal shift,
                             Vec u)
{
  Vec                X;
  const PetscScalar *x;
  PetscScalar       *ua;
  PetscInt           n;
  PetscReal          q4[4], R[9];

  PetscFunctionBegin;
  FCQuatFromAxisAngle(axis, th, q4); /* the project's rotation (src/util) */
  FCQuatToMat3(q4, R);
  PetscCall(FCBodyFEMGetReferenceCoordinates(body, &X));
  PetscCall(VecGetLocalSize(X, &n));
  PetscCall(VecGetArrayRead(X, &x));
  PetscCall(VecGetArray(u, &ua));
  for (PetscInt k = 0; k < n; k += 3) {
    PetscReal p[3] = {PetscRealPart(x[k]), PetscRealPart(x[k + 1]), PetscRealPart(x[k + 2])}, q[3];
    for (int i = 0; i < 3; i++) q[i] = F[3 * i] * p[0] + F[3 * i + 1] * p[1] + F[3 * i + 2] * p[2];
    for (int i = 0; i < 3; i++)
      ua[k + i] = R[3 * i] * q[0] + R[3 * i + 1] * q[1] + R[3 * i + 2] * q[2] - p[i] + shift * (i + 1);
  }
  PetscCall(VecRestoreArray(u, &ua));
  PetscCall(VecRestoreArrayRead(X, &x));
  PetscCall(VecDestroy(&X));
  PetscFunctionReturn(0);
}

static int passed = 0, failed = 0;

static PetscErrorCode Check(PetscBool ok, const char what[], PetscReal value, PetscReal bound)
{
  PetscFunctionBegin;
  if (ok)
    passed++;
  else
    failed++;
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "%s: %s %.3e (<= %.0e)\n", ok ? "PASS" : "FAIL", what, (double)value,
                        (double)bound));
  PetscFunctionReturn(0);
}

static PetscErrorCode CreateBody(const char name[], const char material[], FCBody *b)
{
  char o[64];

  PetscFunctionBegin;
  PetscCall(PetscSNPrintf(o, sizeof(o), "-%s_dm_plex_filename", name));
  PetscCall(PetscOptionsSetValue(NULL, o, "meshes/cube_coarse.msh"));
  PetscCall(PetscSNPrintf(o, sizeof(o), "-%s_type", name));
  PetscCall(PetscOptionsSetValue(NULL, o, "fem"));
  PetscCall(PetscSNPrintf(o, sizeof(o), "-%s_material", name));
  PetscCall(PetscOptionsSetValue(NULL, o, material));
  PetscCall(PetscSNPrintf(o, sizeof(o), "-%s_young", name));
  PetscCall(PetscOptionsSetValue(NULL, o, "1e6"));
  PetscCall(PetscSNPrintf(o, sizeof(o), "-%s_poisson", name));
  PetscCall(PetscOptionsSetValue(NULL, o, "0.35"));
  PetscCall(PetscSNPrintf(o, sizeof(o), "-%s_density", name));
  PetscCall(PetscOptionsSetValue(NULL, o, "1000"));
  PetscCall(FCBodyCreate(PETSC_COMM_WORLD, name, b));
  PetscCall(FCBodySetFromOptions(*b));
  PetscCall(FCBodySetUp(*b));
  PetscFunctionReturn(0);
}

/* Interior vertices' largest force over the largest force; the sum of all forces over it */
static PetscErrorCode PatchResidual(FCBody body, Vec f, PetscReal *interior, PetscReal *sum)
{
  Vec                X;
  const PetscScalar *x, *fa;
  PetscInt           n;
  PetscReal lo[3] = {PETSC_MAX_REAL, PETSC_MAX_REAL, PETSC_MAX_REAL}, hi[3], fin = 0.0, fmax = 0.0, s[3] = {0, 0, 0};

  PetscFunctionBegin;
  for (int d = 0; d < 3; d++) hi[d] = -PETSC_MAX_REAL;
  PetscCall(FCBodyFEMGetReferenceCoordinates(body, &X));
  PetscCall(VecGetLocalSize(X, &n));
  PetscCall(VecGetArrayRead(X, &x));
  for (PetscInt k = 0; k < n; k++) {
    lo[k % 3] = PetscMin(lo[k % 3], PetscRealPart(x[k]));
    hi[k % 3] = PetscMax(hi[k % 3], PetscRealPart(x[k]));
  }
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, lo, 3, MPIU_REAL, MPIU_MIN, PETSC_COMM_WORLD));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, hi, 3, MPIU_REAL, MPIU_MAX, PETSC_COMM_WORLD));
  PetscCall(VecGetArrayRead(f, &fa));
  for (PetscInt k = 0; k < n; k += 3) {
    PetscBool inside = PETSC_TRUE;
    for (int d = 0; d < 3; d++) {
      PetscReal tol = 1e-9 * (hi[d] - lo[d]), p = PetscRealPart(x[k + d]);
      if (p < lo[d] + tol || p > hi[d] - tol) inside = PETSC_FALSE;
    }
    for (int d = 0; d < 3; d++) {
      PetscReal v = PetscAbsReal(PetscRealPart(fa[k + d]));
      fmax        = PetscMax(fmax, v);
      if (inside) fin = PetscMax(fin, v);
      s[d] += PetscRealPart(fa[k + d]);
    }
  }
  PetscCall(VecRestoreArrayRead(f, &fa));
  PetscCall(VecRestoreArrayRead(X, &x));
  PetscCall(VecDestroy(&X));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &fin, 1, MPIU_REAL, MPIU_MAX, PETSC_COMM_WORLD));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &fmax, 1, MPIU_REAL, MPIU_MAX, PETSC_COMM_WORLD));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, s, 3, MPIU_REAL, MPIU_SUM, PETSC_COMM_WORLD));
  *interior = fin / fmax;
  *sum      = PetscMax(PetscMax(PetscAbsReal(s[0]), PetscAbsReal(s[1])), PetscAbsReal(s[2])) / fmax;
  PetscFunctionReturn(0);
}

int main(int argc, char **argv)
{
  const char *models[] = {"neohookean", "stvk"};
  /* a large general deformation (stretch 1.3, compression 0.8, shears), det F > 0 */
  const PetscReal F[9] = {1.3, 0.2, -0.1, 0.05, 0.8, 0.15, -0.12, 0.1, 1.1}, axis[3] = {1, -2, 0.7};
  FCBody          lin;

  PetscCall(PetscInitialize(&argc, &argv, NULL, NULL));
  PetscCall(CreateBody("lin", "linear", &lin));
  for (int k = 0; k < 2; k++) {
    FCBody      body;
    Vec         u, f, f2, ul, fl;
    FCEnergy    E1, E2;
    PetscReal   in, sum, n1, n2, d;
    PetscScalar w1, w2;
    char        what[160];

    PetscCall(CreateBody(models[k], models[k], &body));
    PetscCall(FCBodyFEMGetState(body, &u, NULL));
    PetscCall(VecDuplicate(u, &f));
    PetscCall(VecDuplicate(u, &f2));
    /* patch test */
    PetscCall(Deform(body, F, axis, 0.0, 0.3, u));
    PetscCall(FCBodyFEMComputeElasticForce(body, u, f));
    PetscCall(PatchResidual(body, f, &in, &sum));
    PetscCall(
        PetscSNPrintf(what, sizeof(what), "%s, homogeneous deformation: interior force / largest force", models[k]));
    PetscCall(Check((PetscBool)(in <= 1e-10), what, in, 1e-10));
    PetscCall(
        PetscSNPrintf(what, sizeof(what), "%s, homogeneous deformation: sum of the forces / largest force", models[k]));
    PetscCall(Check((PetscBool)(sum <= 1e-10), what, sum, 1e-10));
    /* objectivity: the same deformation turned by 1.1 rad */
    PetscCall(FCBodyGetEnergy(body, &E1));
    PetscCall(VecNorm(f, NORM_2, &n1));
    PetscCall(Deform(body, F, axis, 1.1, 0.3, u));
    PetscCall(FCBodyGetEnergy(body, &E2));
    PetscCall(FCBodyFEMComputeElasticForce(body, u, f2));
    PetscCall(VecNorm(f2, NORM_2, &n2));
    d = PetscAbsReal(E2.elastic - E1.elastic) / E1.elastic;
    PetscCall(PetscSNPrintf(what, sizeof(what), "%s, rigid rotation of the deformed body: energy change (relative)",
                            models[k]));
    PetscCall(Check((PetscBool)(d <= 1e-12), what, d, 1e-12));
    d = PetscAbsReal(n2 - n1) / n1;
    PetscCall(
        PetscSNPrintf(what, sizeof(what), "%s, rigid rotation of the deformed body: |f| change (relative)", models[k]));
    PetscCall(Check((PetscBool)(d <= 1e-12), what, d, 1e-12));
    /* small-strain limit */
    {
      const PetscReal H[9] = {1 + 1e-7, 3e-8, -2e-8, 5e-8, 1 - 6e-8, 4e-8, -1e-8, 2e-8, 1 + 8e-8}, none[3] = {0, 0, 1};
      PetscCall(FCBodyFEMGetState(lin, &ul, NULL));
      PetscCall(VecDuplicate(ul, &fl));
      PetscCall(Deform(body, H, none, 0.0, 0.0, u));
      PetscCall(Deform(lin, H, none, 0.0, 0.0, ul));
      PetscCall(FCBodyFEMComputeElasticForce(body, u, f));
      PetscCall(FCBodyFEMComputeElasticForce(lin, ul, fl));
      PetscCall(VecNorm(f, NORM_2, &n1));
      PetscCall(VecNorm(fl, NORM_2, &n2));
      PetscCall(VecDot(u, f, &w1));
      PetscCall(VecDot(ul, fl, &w2));
      d = PetscMax(PetscAbsReal(n1 - n2) / n2, PetscAbsScalar(w1 - w2) / PetscAbsScalar(w2));
      PetscCall(PetscSNPrintf(what, sizeof(what),
                              "%s, displacement gradient 1e-7: force norm and work against linear elasticity",
                              models[k]));
      PetscCall(Check((PetscBool)(d <= 1e-6), what, d, 1e-6));
      PetscCall(VecDestroy(&fl));
    }
    PetscCall(VecDestroy(&f));
    PetscCall(VecDestroy(&f2));
    PetscCall(FCBodyDestroy(&body));
  }
  PetscCall(FCBodyDestroy(&lin));
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "%d passed, %d failed\n", passed, failed));
  PetscCall(PetscFinalize());
  return failed ? 1 : 0;
}
