/* bench_collision: time of the FE-FE broad + narrow phase (spatial hash of triangles, nearest
   triangle per point) for surfaces of N triangles: a wavy triangulated square of N triangles and
   one query point above each of its vertices (within the alarm distance).
     bench_collision [-sizes 10000,100000,1000000] [-repeat 3]
   Prints, per N: build time, query time, their sum per triangle and the ratio
   t / (N log2 N) normalized by the smallest size (flat: n log n growth, falling: better). */
/* times the spatial hash of triangles, which the contact package declares (src/contact/contact.h) */
#include "../src/contact/contact.h"

int main(int argc, char **argv)
{
  PetscInt  sizes[8] = {10000, 100000, 1000000}, ns = 8, repeat = 3;
  PetscReal ref = 0.0;
  PetscBool set;

  PetscCall(PetscInitialize(&argc, &argv, NULL, NULL));
  PetscCall(PetscOptionsGetIntArray(NULL, NULL, "-sizes", sizes, &ns, &set));
  if (!set) ns = 3;
  PetscCall(PetscOptionsGetInt(NULL, NULL, "-repeat", &repeat, NULL));
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "| triangles | points | hash build (s) | queries (s) | total per triangle "
                                          "(us) | t / (N log2 N), normalized |\n|---:|---:|---:|---:|---:|---:|\n"));
  for (PetscInt s = 0; s < ns; s++) {
    PetscInt  m = (PetscInt)PetscSqrtReal(sizes[s] / 2.0), N = 2 * m * m, np = (m + 1) * (m + 1);
    PetscReal hgrid = 1.0 / m, best[2] = {PETSC_MAX_REAL, PETSC_MAX_REAL}, *pts, found = 0;
    PetscCall(PetscMalloc1(3 * np, &pts));
    for (PetscInt i = 0; i <= m; i++)
      for (PetscInt j = 0; j <= m; j++) {
        PetscReal x = i * hgrid, y = j * hgrid;
        pts[3 * (i * (m + 1) + j) + 0] = x + 0.3 * hgrid;
        pts[3 * (i * (m + 1) + j) + 1] = y + 0.2 * hgrid;
        pts[3 * (i * (m + 1) + j) + 2] = 0.02 * PetscSinReal(6.0 * x) * PetscCosReal(5.0 * y) + 0.25 * hgrid;
      }
    for (PetscInt r = 0; r < repeat; r++) {
      FCSurfaceTriangle *tri;
      FCSurface         *S;
      PetscLogDouble     t0, t1, t2;
      PetscCall(PetscCalloc1(N, &tri));
      for (PetscInt i = 0; i < m; i++)
        for (PetscInt j = 0; j < m; j++)
          for (PetscInt k = 0; k < 2; k++) {
            FCSurfaceTriangle *T          = &tri[2 * (i * m + j) + k];
            const PetscInt     c[2][3][2] = {{{0, 0}, {1, 0}, {1, 1}}, {{0, 0}, {1, 1}, {0, 1}}};
            for (int a = 0; a < 3; a++) {
              PetscReal x = (i + c[k][a][0]) * hgrid, y = (j + c[k][a][1]) * hgrid;
              T->gdof[a]  = -1;
              T->x0[a][0] = T->xf[a][0] = T->X[a][0] = x;
              T->x0[a][1] = T->xf[a][1] = T->X[a][1] = y;
              T->x0[a][2] = T->xf[a][2] = T->X[a][2] = 0.02 * PetscSinReal(6.0 * x) * PetscCosReal(5.0 * y);
            }
          }
      PetscCall(PetscTime(&t0));
      PetscCall(FCSurfaceCreate(N, tri, 0.5 * hgrid, &S));
      PetscCall(PetscTime(&t1));
      found = 0;
      for (PetscInt p = 0; p < np; p++) {
        PetscInt  t;
        PetscReal w[3], cp[3], d2;
        FCSurfaceClosest(S, &pts[3 * p], &t, w, cp, &d2);
        found += (t >= 0 && d2 <= PetscSqr(0.5 * hgrid));
      }
      PetscCall(PetscTime(&t2));
      best[0] = PetscMin(best[0], t1 - t0);
      best[1] = PetscMin(best[1], t2 - t1);
      PetscCall(FCSurfaceDestroy(&S));
    }
    {
      PetscReal tot = best[0] + best[1], r = tot / (N * PetscLog2Real((PetscReal)N));
      if (s == 0) ref = r;
      PetscCall(PetscPrintf(PETSC_COMM_WORLD, "| %" PetscInt_FMT " | %" PetscInt_FMT " | %.4f | %.4f | %.3f | %.2f |\n",
                            N, np, (double)best[0], (double)best[1], (double)(1e6 * tot / N), (double)(r / ref)));
      PetscCheck(found >= 0.95 * np, PETSC_COMM_SELF, PETSC_ERR_PLIB,
                 "Only %g of %" PetscInt_FMT " points found their triangle", (double)found, np);
    }
    PetscCall(PetscFree(pts));
  }
  PetscCall(PetscFinalize());
  return 0;
}
