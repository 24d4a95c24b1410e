/* Contact candidates on every partition (issue 31). An FE body's candidate contact points are
   its owned boundary vertices (src/mesh/boundary.c, FCMeshGetBoundary); over the ranks they must be
   every vertex of the body's surface, each taken by exactly one rank, whatever the partition.
   Checked on the meshes that lost vertices before the boundary marks were summed to the owners
   (a coarse gmsh sphere, the 6-tet cube, the cube at lc 0.15 and 0.2) with the partitioners
   simple, metis and ptscotch, on the ranks this runs on: the candidates' reference positions,
   gathered, against the distinct vertices of the gathered surface triangles (which every rank
   sees whole). Then the end-of-step intersection count (src/collision/intersection.c) does not
   depend on that list: a cube sunk into a plane, and two overlapping cubes, count the same
   intersections with every rank's candidate list emptied, and as many as there are surface
   vertices below the plane.
   Runs on any number of ranks (ctest: 1, 2, 3, 4 and 8, oversubscribed). */
/* a unit test of the candidate points on the partition: it reads an FE body's mesh and surface, inside src/body/ and
 * src/collision/ */
#include "fcimpl.h"
#include "body/femimpl.h"
#include "collision/collisionimpl.h"

static int CompareX(const void *a, const void *b)
{
  const PetscReal *x = (const PetscReal *)a, *y = (const PetscReal *)b;
  for (int i = 0; i < 3; i++)
    if (x[i] != y[i]) return x[i] < y[i] ? -1 : 1;
  return 0;
}

/* Sorts n points (3 reals each) and drops repeats: returns the number left */
static PetscInt Distinct(PetscInt n, PetscReal x[])
{
  PetscInt m = 0;
  if (n) qsort(x, n, 3 * sizeof(PetscReal), CompareX);
  for (PetscInt k = 0; k < n; k++)
    if (!m || CompareX(&x[3 * (m - 1)], &x[3 * k])) {
      for (int d = 0; d < 3; d++) x[3 * m + d] = x[3 * k + d];
      m++;
    }
  return m;
}

static PetscErrorCode CreateBody(const char name[], const char type[], const char extra[], FCBody *body)
{
  char opts[1024];

  PetscFunctionBegin;
  PetscCall(PetscSNPrintf(opts, sizeof(opts), "-%s_type %s %s", name, type, extra));
  PetscCall(PetscOptionsInsertString(NULL, opts));
  PetscCall(FCBodyCreate(PETSC_COMM_WORLD, name, body));
  PetscCall(FCBodySetFromOptions(*body));
  PetscCall(FCBodySetTimeStep(*body, 0.01));
  PetscCall(FCBodySetUp(*body));
  PetscFunctionReturn(0);
}

static PetscErrorCode FEBody(const char name[], const char mesh[], const char extra[], FCBody *body)
{
  char opts[1024];

  PetscFunctionBegin;
  PetscCall(PetscSNPrintf(opts, sizeof(opts), "-%s_dm_plex_filename %s -%s_young 1e5 -%s_density 1000 %s", name, mesh,
                          name, name, extra));
  PetscCall(CreateBody(name, "fem", opts, body));
  PetscFunctionReturn(0);
}

/* Candidates of body b against the vertices of its surface: *ncand summed over the ranks, *nsurf
   distinct surface vertices, *same whether the gathered candidates are exactly those vertices */
static PetscErrorCode CompareCandidates(FCBody b, PetscInt *ncand, PetscInt *nsurf, PetscBool *same)
{
  PetscInt           n, ntri, ntot;
  FCProximity       *prox;
  PetscReal         *x0, *xf, *key, *all, *sv;
  FCSurfaceTriangle *tri;

  PetscFunctionBegin;
  PetscCall(FCBodyGetContactPoints(b, &n, &prox, &x0, &xf, &key));
  PetscCall(FCAllgatherRecords(PETSC_COMM_WORLD, n, 3 * sizeof(PetscReal), key, &ntot, (void **)&all));
  PetscCall(FCSurfaceGather(PETSC_COMM_WORLD, b, &ntri, &tri));
  PetscCall(PetscMalloc1(9 * ntri + 1, &sv));
  for (PetscInt t = 0; t < ntri; t++)
    for (int a = 0; a < 3; a++)
      for (int d = 0; d < 3; d++) sv[9 * t + 3 * a + d] = tri[t].X[a][d];
  *nsurf = Distinct(3 * ntri, sv);
  *ncand = ntot;
  if (ntot) qsort(all, ntot, 3 * sizeof(PetscReal), CompareX);
  *same = ntot == *nsurf ? PETSC_TRUE : PETSC_FALSE;
  for (PetscInt k = 0; k < ntot && *same; k++)
    if (CompareX(&all[3 * k], &sv[3 * k])) *same = PETSC_FALSE;
  PetscCall(PetscFree(all));
  PetscCall(PetscFree(sv));
  PetscCall(PetscFree(tri));
  PetscFunctionReturn(0);
}

/* The intersections of the pair (a, b) as counted at the end of a step, with the FE bodies'
   candidate lists as they are (*full) and emptied on every rank (*hidden) */
static PetscErrorCode CountBothWays(FCBody a, FCBody b, PetscInt *full, PetscInt *hidden)
{
  FCBody         bodies[2]  = {a, b};
  PetscInt       pair[1][2] = {{0, 1}}, saved[2] = {0, 0};
  PetscReal      mu[1] = {0.0};
  FCContactPairs pairs;

  PetscFunctionBegin;
  PetscCall(PetscMemzero(&pairs, sizeof(pairs)));
  pairs.n                  = 1;
  pairs.body               = pair;
  pairs.mu                 = mu;
  pairs.distance           = 0.01;
  pairs.passes             = 2;
  pairs.intersection_depth = 1e-4;
  PetscCall(FCCollisionCountPairIntersections(PETSC_COMM_WORLD, 2, bodies, &pairs, full));
  for (int s = 0; s < 2; s++)
    if (FCBodyIsDeformable(bodies[s])) {
      FEM *fem;
      PetscCall(FCFEMGet(bodies[s], &fem));
      saved[s] = fem->nbv;
      fem->nbv = 0;
    }
  PetscCall(FCCollisionCountPairIntersections(PETSC_COMM_WORLD, 2, bodies, &pairs, hidden));
  for (int s = 0; s < 2; s++)
    if (FCBodyIsDeformable(bodies[s])) {
      FEM *fem;
      PetscCall(FCFEMGet(bodies[s], &fem));
      fem->nbv = saved[s];
    }
  PetscFunctionReturn(0);
}

int main(int argc, char **argv)
{
  const char *meshes[] = {"meshes/sphere_coarse.msh", "meshes/six_tets.msh", "meshes/cube_015.msh",
                          "meshes/cube_coarse.msh"};
  const char *parts[]  = {"simple", "metis", "ptscotch"};
  PetscMPIInt size;
  int         fails = 0;

  PetscCall(PetscInitialize(&argc, &argv, NULL, NULL));
  PetscCall(FCInitializePackage());
  PetscCallMPI(MPI_Comm_size(PETSC_COMM_WORLD, &size));
  for (size_t m = 0; m < sizeof(meshes) / sizeof(meshes[0]); m++)
    for (size_t p = 0; p < sizeof(parts) / sizeof(parts[0]); p++) {
      char      name[32], extra[128];
      FCBody    b;
      PetscInt  ncand, nsurf;
      PetscBool same;
      PetscCall(PetscSNPrintf(name, sizeof(name), "m%dp%d", (int)m, (int)p));
      PetscCall(PetscSNPrintf(extra, sizeof(extra), "-%s_petscpartitioner_type %s", name, parts[p]));
      PetscCall(FEBody(name, meshes[m], extra, &b));
      PetscCall(CompareCandidates(b, &ncand, &nsurf, &same));
      fails += !same;
      PetscCall(PetscPrintf(PETSC_COMM_WORLD,
                            "%s: %-26s %-8s on %d ranks: %4" PetscInt_FMT " candidates, %4" PetscInt_FMT
                            " surface vertices, the same points: %s\n",
                            same ? "PASS" : "FAIL", meshes[m], parts[p], size, ncand, nsurf, same ? "yes" : "no"));
      PetscCall(FCBodyDestroy(&b));
    }
  { /* a cube sunk 5 cm into a plane; two cubes overlapping by 10 cm */
    FCBody             cube, ground, left, right;
    PetscInt           full, hidden, below = 0, ntri;
    PetscReal         *v;
    FCSurfaceTriangle *tri;
    PetscCall(
        FEBody("cube", "meshes/cube_coarse.msh", "-cube_translate 0,0,0.45 -cube_petscpartitioner_type simple", &cube));
    PetscCall(CreateBody("ground", "kinematic", "-ground_shape plane -ground_length 3", &ground));
    PetscCall(CountBothWays(cube, ground, &full, &hidden));
    PetscCall(FCSurfaceGather(PETSC_COMM_WORLD, cube, &ntri, &tri));
    PetscCall(PetscMalloc1(9 * ntri + 1, &v));
    for (PetscInt t = 0; t < ntri; t++)
      for (int a = 0; a < 3; a++)
        for (int d = 0; d < 3; d++) v[9 * t + 3 * a + d] = tri[t].x0[a][d];
    ntri = Distinct(3 * ntri, v);
    for (PetscInt k = 0; k < ntri; k++) below += v[3 * k + 2] < -1e-4;
    PetscCall(PetscFree(v));
    PetscCall(PetscFree(tri));
    fails += !(full == below && hidden == below && below > 0);
    PetscCall(PetscPrintf(PETSC_COMM_WORLD,
                          "%s: cube 5 cm into a plane: %" PetscInt_FMT " intersections, %" PetscInt_FMT
                          " with no candidates, %" PetscInt_FMT " surface vertices below it\n",
                          full == below && hidden == below && below > 0 ? "PASS" : "FAIL", full, hidden, below));
    PetscCall(FEBody("left", "meshes/cube_coarse.msh", "-left_petscpartitioner_type simple", &left));
    PetscCall(FEBody("right", "meshes/cube_coarse.msh", "-right_translate 0.9,0.05,0.05", &right));
    PetscCall(CountBothWays(left, right, &full, &hidden));
    fails += !(full == hidden && full > 0);
    PetscCall(PetscPrintf(PETSC_COMM_WORLD,
                          "%s: two cubes 10 cm into each other: %" PetscInt_FMT " intersections, %" PetscInt_FMT
                          " with no candidates\n",
                          full == hidden && full > 0 ? "PASS" : "FAIL", full, hidden));
    PetscCall(FCBodyDestroy(&cube));
    PetscCall(FCBodyDestroy(&ground));
    PetscCall(FCBodyDestroy(&left));
    PetscCall(FCBodyDestroy(&right));
  }
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "%d failed\n", fails));
  PetscCall(PetscFinalize());
  return fails ? 1 : 0;
}
