/* FCSurfaceTopology: the topology of a body's gathered surface triangles in the reference
   configuration (its vertices by reference position, each triangle's corners, each vertex's
   triangles, each interior edge's two half-edges). A body's mesh and partition, hence its gathered
   triangles and their order, do not change in a run: the topology is built at the first step that
   needs it and kept per body in the pairs' cache (pairs->topo), checked at each use against the
   triangles' reference positions and rebuilt if they differ. Without a cache (pairs->topo NULL) it
   is built for the one use.
   Corners and half-edges are sorted by reference position, ties in the order of the triangles, so
   that vertex normals, sharp edges and surface vertices come out in one order, summed in one order,
   whatever the sort. */
#include "collisionimpl.h"

typedef struct {
  PetscReal key[6]; /* the reference ends, smaller first */
  PetscInt  h;      /* 3 t + a: triangle t's edge a -> a + 1 */
} HalfEdge;

static int CompareHalf(const void *x, const void *y)
{
  const HalfEdge *a = (const HalfEdge *)x, *b = (const HalfEdge *)y;
  for (int i = 0; i < 6; i++)
    if (a->key[i] != b->key[i]) return a->key[i] < b->key[i] ? -1 : 1;
  return 0;
}

/* The sort's order: by the reference ends, then by half-edge (a tie in the order of the triangles) */
static int CompareHalfOrder(const void *x, const void *y)
{
  const HalfEdge *a = (const HalfEdge *)x, *b = (const HalfEdge *)y;
  int             c = CompareHalf(x, y);
  return c ? c : (a->h < b->h ? -1 : (a->h > b->h ? 1 : 0));
}

typedef struct {
  PetscReal X[3];
  PetscInt  corner; /* 3 t + a */
} Corner;

/* By reference position, then by corner (a vertex's corners in the order of the triangles) */
static int CompareCorner(const void *x, const void *y)
{
  const Corner *a = (const Corner *)x, *b = (const Corner *)y;
  int           c = FCComparePoint(a->X, b->X);
  return c ? c : (a->corner < b->corner ? -1 : (a->corner > b->corner ? 1 : 0));
}

/* The vertices (sorted, each with its first corner), each corner's vertex and each vertex's triangles */
static PetscErrorCode Vertices(FCSurfaceTopology *T, const FCSurfaceTriangle *tri)
{
  Corner  *c;
  PetscInt n = T->ntri, m = 0;

  PetscFunctionBegin;
  PetscCall(PetscMalloc1(3 * n + 1, &c));
  for (PetscInt t = 0; t < n; t++)
    for (int a = 0; a < 3; a++) {
      for (int d = 0; d < 3; d++) c[3 * t + a].X[d] = tri[t].X[a][d];
      c[3 * t + a].corner = 3 * t + a;
    }
  if (n) qsort(c, 3 * n, sizeof(Corner), CompareCorner);
  PetscCall(PetscMalloc4(9 * n + 3, &T->V, 3 * n + 1, &T->first, 3 * n + 1, &T->tv, 3 * n + 2, &T->off));
  PetscCall(PetscMalloc1(3 * n + 1, &T->vt));
  for (PetscInt k = 0; k < 3 * n; k++) {
    if (!m || FCComparePoint(&T->V[3 * (m - 1)], c[k].X)) {
      for (int d = 0; d < 3; d++) T->V[3 * m + d] = c[k].X[d];
      T->first[m++] = c[k].corner;
    }
    T->tv[c[k].corner] = m - 1;
  }
  T->nv = m;
  for (PetscInt v = 0; v <= m; v++) T->off[v] = 0;
  for (PetscInt k = 0; k < 3 * n; k++) T->off[T->tv[k] + 1]++;
  for (PetscInt v = 0; v < m; v++) T->off[v + 1] += T->off[v];
  { /* each vertex's triangles, in triangle order */
    PetscInt *fill;
    PetscCall(PetscMalloc1(m + 1, &fill));
    for (PetscInt v = 0; v < m; v++) fill[v] = T->off[v];
    for (PetscInt k = 0; k < 3 * n; k++) T->vt[fill[T->tv[k]]++] = k / 3;
    PetscCall(PetscFree(fill));
  }
  PetscCall(PetscFree(c));
  PetscFunctionReturn(0);
}

/* The interior edges: the half-edges sorted by their reference ends, two equal in a row an edge
   (a boundary edge, seen once, is skipped; the first of the two is the edge's triangle) */
static PetscErrorCode Edges(FCSurfaceTopology *T, const FCSurfaceTriangle *tri)
{
  HalfEdge *h;
  PetscInt  n = T->ntri, ne = 0;

  PetscFunctionBegin;
  PetscCall(PetscMalloc1(3 * n + 1, &h));
  for (PetscInt t = 0; t < n; t++)
    for (int a = 0; a < 3; a++) {
      const PetscReal *p = tri[t].X[a], *q = tri[t].X[(a + 1) % 3];
      if (FCComparePoint(p, q) > 0) {
        const PetscReal *s = p;
        p                  = q;
        q                  = s;
      }
      for (int i = 0; i < 3; i++) {
        h[3 * t + a].key[i]     = p[i];
        h[3 * t + a].key[3 + i] = q[i];
      }
      h[3 * t + a].h = 3 * t + a;
    }
  if (n) qsort(h, 3 * n, sizeof(HalfEdge), CompareHalfOrder);
  PetscCall(PetscMalloc1(3 * n / 2 + 1, &T->edge));
  for (PetscInt k = 0; k + 1 < 3 * n; k++) {
    if (CompareHalf(&h[k], &h[k + 1])) continue;
    T->edge[ne][0] = h[k].h;
    T->edge[ne][1] = h[k + 1].h;
    ne++;
    k++;
  }
  T->ne = ne;
  PetscCall(PetscFree(h));
  PetscFunctionReturn(0);
}

static PetscErrorCode TopologyCreate(PetscInt ntri, const FCSurfaceTriangle *tri, FCSurfaceTopology **topo)
{
  FCSurfaceTopology *T;

  PetscFunctionBegin;
  PetscCall(PetscNew(&T));
  T->ntri = ntri;
  PetscCall(PetscMalloc1(9 * ntri + 1, &T->X));
  for (PetscInt t = 0; t < ntri; t++) PetscCall(PetscArraycpy(&T->X[9 * t], &tri[t].X[0][0], 9));
  PetscCall(Vertices(T, tri));
  PetscCall(Edges(T, tri));
  *topo = T;
  PetscFunctionReturn(0);
}

PetscErrorCode FCSurfaceTopologyDestroy(FCSurfaceTopology **topo)
{
  FCSurfaceTopology *T = *topo;

  PetscFunctionBegin;
  if (!T) PetscFunctionReturn(0);
  PetscCall(PetscFree(T->X));
  PetscCall(PetscFree4(T->V, T->first, T->tv, T->off));
  PetscCall(PetscFree(T->vt));
  PetscCall(PetscFree(T->edge));
  PetscCall(PetscFree(*topo));
  PetscFunctionReturn(0);
}

/* Whether T was built from these triangles (the same reference corners in the same order) */
static PetscBool Matches(const FCSurfaceTopology *T, PetscInt ntri, const FCSurfaceTriangle *tri)
{
  if (T->ntri != ntri) return PETSC_FALSE;
  for (PetscInt t = 0; t < ntri; t++)
    for (int a = 0; a < 3; a++)
      for (int d = 0; d < 3; d++)
        if (T->X[9 * t + 3 * a + d] != tri[t].X[a][d]) return PETSC_FALSE;
  return PETSC_TRUE;
}

PetscErrorCode FCSurfaceTopologyGet(const FCContactPairs *pairs, PetscInt ib, PetscInt ntri,
                                    const FCSurfaceTriangle *tri, FCSurfaceTopology **topo)
{
  PetscFunctionBegin;
  if (!pairs->topo) {
    PetscCall(TopologyCreate(ntri, tri, topo));
    PetscFunctionReturn(0);
  }
  if (pairs->topo[ib] && !Matches(pairs->topo[ib], ntri, tri)) PetscCall(FCSurfaceTopologyDestroy(&pairs->topo[ib]));
  if (!pairs->topo[ib]) PetscCall(TopologyCreate(ntri, tri, &pairs->topo[ib]));
  *topo = pairs->topo[ib];
  PetscFunctionReturn(0);
}

PetscErrorCode FCSurfaceTopologyRestore(const FCContactPairs *pairs, FCSurfaceTopology **topo)
{
  PetscFunctionBegin;
  if (!pairs->topo) PetscCall(FCSurfaceTopologyDestroy(topo));
  *topo = NULL;
  PetscFunctionReturn(0);
}

/* The outward normals of the vertices at the start of the step, in the topology's vertex order:
   the sums of their triangles' normals weighted by area (in triangle order), normalized */
PetscErrorCode FCCollisionVertexNormals(const FCSurfaceTopology *T, const FCSurfaceTriangle tri[], PetscInt *nvn,
                                        FCVertexNormal **vn)
{
  FCVertexNormal *all;
  PetscReal      *c;

  PetscFunctionBegin;
  PetscCall(PetscMalloc1(T->nv + 1, &all));
  PetscCall(PetscMalloc1(3 * T->ntri + 1, &c));
  for (PetscInt t = 0; t < T->ntri; t++) {
    PetscReal e1[3], e2[3];
    for (int d = 0; d < 3; d++) {
      e1[d] = tri[t].x0[1][d] - tri[t].x0[0][d];
      e2[d] = tri[t].x0[2][d] - tri[t].x0[0][d];
    }
    FCCross(e1, e2, &c[3 * t]); /* twice the area times the unit normal */
  }
  for (PetscInt v = 0; v < T->nv; v++) {
    PetscReal l;
    for (int d = 0; d < 3; d++) {
      all[v].X[d] = T->V[3 * v + d];
      all[v].n[d] = c[3 * T->vt[T->off[v]] + d];
    }
    for (PetscInt j = T->off[v] + 1; j < T->off[v + 1]; j++)
      for (int d = 0; d < 3; d++) all[v].n[d] += c[3 * T->vt[j] + d];
    l = PetscSqrtReal(FCDot(all[v].n, all[v].n));
    for (int d = 0; d < 3; d++) all[v].n[d] = l > 0.0 ? all[v].n[d] / l : 0.0;
  }
  PetscCall(PetscFree(c));
  *nvn = T->nv;
  *vn  = all;
  PetscFunctionReturn(0);
}
