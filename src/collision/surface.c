/* The surface of a body for the narrow phase: its triangles gathered on every rank (a surface,
   not the volume) and bucketed in a sort-based spatial hash (cells of the mean edge length), so
   that a query costs O(log n) and the detection O(n log n) in the surface size
   (docs/benchmarks.md, "Collision detection"). A surface is hashed by its triangles' boxes at
   the start of the step, or over the whole step for continuous detection (swept). */
#include "collisionimpl.h"

/* digit k (11 bits from shift) of a key, its sign bit flipped so that unsigned order is signed order */
static inline PetscInt Digit(int64_t key, int shift)
{
  return (PetscInt)((((uint64_t)key ^ ((uint64_t)1 << 63)) >> shift) & 2047);
}

/* Sorts n cell entries by key, stably, by least-significant-digit radix sort (O(n): a comparison
   sort was the hash's largest cost). Filled by ascending triangle, the entries of a cell keep that
   order: the order of (key, triangle). */
PetscErrorCode FCCellEntrySort(PetscInt n, FCCellEntry e[])
{
  FCCellEntry *tmp, *src = e, *dst;
  PetscInt     count[2048];

  PetscFunctionBegin;
  if (n < 2) PetscFunctionReturn(0);
  PetscCall(PetscMalloc1(n, &tmp));
  dst = tmp;
  for (int shift = 0; shift < 64; shift += 11) {
    PetscInt sum = 0;
    PetscCall(PetscArrayzero(count, 2048));
    for (PetscInt i = 0; i < n; i++) count[Digit(src[i].key, shift)]++;
    if (count[Digit(src[0].key, shift)] == n) continue; /* one digit for all: nothing to move */
    for (PetscInt d = 0; d < 2048; d++) {
      PetscInt c = count[d];
      count[d]   = sum;
      sum += c;
    }
    for (PetscInt i = 0; i < n; i++) dst[count[Digit(src[i].key, shift)]++] = src[i];
    {
      FCCellEntry *s = src;
      src            = dst;
      dst            = s;
    }
  }
  if (src != e) PetscCall(PetscArraycpy(e, src, n));
  PetscCall(PetscFree(tmp));
  PetscFunctionReturn(0);
}

static int64_t CellKey(int64_t i, int64_t j, int64_t k)
{
  const int64_t off = (int64_t)1 << 20, mask = ((int64_t)1 << 21) - 1;
  return (((i + off) & mask) << 42) | (((j + off) & mask) << 21) | ((k + off) & mask);
}

/* The surface triangles of a body (FE or mesh shape), gathered on every rank (*tri: to free) */
PetscErrorCode FCSurfaceGather(MPI_Comm comm, FCBody b, PetscInt *ntri, FCSurfaceTriangle **tri)
{
  PetscInt           n;
  FCSurfaceTriangle *loc;

  PetscFunctionBegin;
  PetscCall(FCBodyGetSurfaceTriangles(b, &n, &loc));
  PetscCall(FCAllgatherRecords(comm, n, sizeof(FCSurfaceTriangle), loc, ntri, (void **)tri));
  PetscFunctionReturn(0);
}

/* The spatial hash of n triangles (taken over): cells of the mean edge length, at least twice
   the alarm distance; each triangle is listed in every cell its inflated box overlaps (its box
   at the start of the step, or over the whole step when swept) */
static PetscErrorCode SurfaceCreate(PetscInt n, FCSurfaceTriangle *tri, PetscReal distance, PetscBool swept,
                                    FCSurface **surface)
{
  Surface  *S;
  PetscReal len = 0.0;

  PetscFunctionBegin;
  PetscCall(PetscNew(&S));
  S->n       = n;
  S->tri     = tri;
  S->swept   = swept;
  S->inflate = distance;
  /* cell size: the mean edge length (at least twice the alarm distance) */
  for (PetscInt t = 0; t < S->n; t++)
    for (int a = 0; a < 3; a++) {
      PetscReal e = 0.0;
      for (int d = 0; d < 3; d++) e += PetscSqr(S->tri[t].x0[(a + 1) % 3][d] - S->tri[t].x0[a][d]);
      len += PetscSqrtReal(e);
    }
  S->h = PetscMax(S->n ? len / (3 * S->n) : 1.0, 2 * distance);
  if (!(S->h > 0)) S->h = 1.0;
  /* entries: every cell the inflated bounding box of a triangle overlaps (two passes: count, fill) */
  S->nentries = 0;
  S->cells    = NULL;
  for (int pass = 0; pass < 2; pass++) {
    PetscInt e = 0;
    for (PetscInt t = 0; t < S->n; t++) {
      int64_t lo[3], hi[3];
      for (int d = 0; d < 3; d++) {
        PetscReal mn = PETSC_MAX_REAL, mx = -PETSC_MAX_REAL;
        for (int a = 0; a < 3; a++) {
          mn = PetscMin(mn, S->tri[t].x0[a][d]);
          mx = PetscMax(mx, S->tri[t].x0[a][d]);
          if (swept) {
            mn = PetscMin(mn, S->tri[t].xf[a][d]);
            mx = PetscMax(mx, S->tri[t].xf[a][d]);
          }
        }
        lo[d] = (int64_t)PetscFloorReal((mn - distance) / S->h);
        hi[d] = (int64_t)PetscFloorReal((mx + distance) / S->h);
      }
      for (int64_t i = lo[0]; i <= hi[0]; i++)
        for (int64_t j = lo[1]; j <= hi[1]; j++)
          for (int64_t k = lo[2]; k <= hi[2]; k++) {
            if (pass) {
              S->cells[e].key = CellKey(i, j, k);
              S->cells[e].tri = t;
            }
            e++;
          }
    }
    if (!pass) {
      S->nentries = e;
      PetscCall(PetscMalloc1(e + 1, &S->cells));
    }
  }
  PetscCall(FCCellEntrySort(S->nentries, S->cells));
  PetscCall(PetscMalloc1(3 * S->n + 1, &S->nrm));
  for (PetscInt t = 0; t < S->n; t++) FCTriangleNormal(S->tri[t].x0, &S->nrm[3 * t]);
  PetscCall(PetscCalloc1(S->n + 1, &S->stamp)); /* FCSurfaceQueryBox's */
  *surface = S;
  PetscFunctionReturn(0);
}

PetscErrorCode FCSurfaceCreate(PetscInt n, FCSurfaceTriangle *tri, PetscReal distance, FCSurface **surface)
{
  PetscFunctionBegin;
  PetscCall(SurfaceCreate(n, tri, distance, PETSC_FALSE, surface));
  PetscFunctionReturn(0);
}

PetscErrorCode FCSurfaceCreateSwept(PetscInt n, FCSurfaceTriangle *tri, PetscReal inflate, FCSurface **surface)
{
  PetscFunctionBegin;
  PetscCall(SurfaceCreate(n, tri, inflate, PETSC_TRUE, surface));
  PetscFunctionReturn(0);
}

static void CellRange(const Surface *S, int64_t key, PetscInt *begin, PetscInt *end)
{
  PetscInt lo = 0, hi = S->nentries;
  while (lo < hi) {
    PetscInt mid = (lo + hi) / 2;
    if (S->cells[mid].key < key)
      lo = mid + 1;
    else
      hi = mid;
  }
  *begin = lo;
  while (lo < S->nentries && S->cells[lo].key == key) lo++;
  *end = lo;
}

void FCSurfaceQueryPoint(const Surface *S, const PetscReal x[3], PetscInt *begin, PetscInt *end)
{
  CellRange(S,
            CellKey((int64_t)PetscFloorReal(x[0] / S->h), (int64_t)PetscFloorReal(x[1] / S->h),
                    (int64_t)PetscFloorReal(x[2] / S->h)),
            begin, end);
}

/* Cells of the box, each triangle once (stamped with the query's number); a box over more than
   FC_QUERY_MAX_CELLS cells (a very fast point in small cells) takes every triangle instead */
#define FC_QUERY_MAX_CELLS 4096
void FCSurfaceQueryBox(FCSurface *S, const PetscReal lo[3], const PetscReal hi[3], PetscInt cand[], PetscInt *ncand)
{
  int64_t  l[3], h[3], ncells = 1;
  PetscInt q = ++S->nquery;

  *ncand = 0;
  for (int d = 0; d < 3; d++) {
    l[d] = (int64_t)PetscFloorReal(lo[d] / S->h);
    h[d] = (int64_t)PetscFloorReal(hi[d] / S->h);
    ncells *= h[d] - l[d] + 1;
  }
  if (ncells > FC_QUERY_MAX_CELLS) {
    for (PetscInt t = 0; t < S->n; t++) cand[(*ncand)++] = t;
    return;
  }
  for (int64_t i = l[0]; i <= h[0]; i++)
    for (int64_t j = l[1]; j <= h[1]; j++)
      for (int64_t k = l[2]; k <= h[2]; k++) {
        PetscInt b, e;
        CellRange(S, CellKey(i, j, k), &b, &e);
        for (PetscInt m = b; m < e; m++) {
          PetscInt t = S->cells[m].tri;
          if (S->stamp[t] == q) continue;
          S->stamp[t]      = q;
          cand[(*ncand)++] = t;
        }
      }
}

PetscErrorCode FCSurfaceDestroy(FCSurface **S)
{
  PetscFunctionBegin;
  if (!*S) PetscFunctionReturn(0);
  PetscCall(PetscFree((*S)->tri));
  PetscCall(PetscFree((*S)->cells));
  PetscCall(PetscFree((*S)->nrm));
  PetscCall(PetscFree((*S)->stamp));
  PetscCall(PetscFree(*S));
  PetscFunctionReturn(0);
}

/* Nearest triangle to x among those hashed in x's cell: index (-1: none), weights, closest
   point and squared distance */
void FCSurfaceClosest(const FCSurface *S, const PetscReal x[3], PetscInt *best, PetscReal bw[3], PetscReal bcp[3],
                      PetscReal *bestd)
{
  FCSurfaceClosestFacing(S, x, NULL, best, bw, bcp, bestd);
}

/* FCSurfaceClosest among the triangles that face the normal nv of the point's own surface
   (n_T . nv <= -FC_FACING_COS: a face at 90 degrees, the side face of a body sliding over a
   slab's vertex, does not); nv NULL: all */
void FCSurfaceClosestFacing(const FCSurface *S, const PetscReal x[3], const PetscReal nv[3], PetscInt *best,
                            PetscReal bw[3], PetscReal bcp[3], PetscReal *bestd)
{
  PetscInt b, e;
  *best  = -1;
  *bestd = PETSC_MAX_REAL;
  FCSurfaceQueryPoint(S, x, &b, &e);
  for (PetscInt k = b; k < e; k++) {
    const FCSurfaceTriangle *T = &S->tri[S->cells[k].tri];
    PetscReal                cp[3], w[3], d2 = 0.0;
    if (nv && FCDot(&S->nrm[3 * S->cells[k].tri], nv) > -FC_FACING_COS) continue;
    if (S->self && FCCollisionSelfExcludes(S, S->cells[k].tri, x)) continue; /* after the cheaper test */
    FCClosestPointTriangle(x, T->x0[0], T->x0[1], T->x0[2], cp, w);
    for (int d = 0; d < 3; d++) d2 += PetscSqr(x[d] - cp[d]);
    if (d2 < *bestd) {
      *bestd = d2;
      *best  = S->cells[k].tri;
      for (int d = 0; d < 3; d++) {
        bw[d]  = w[d];
        bcp[d] = cp[d];
      }
    }
  }
}
