/* The intersection check at the end of every step (docs/output.md, /steps/intersections): how
   many points of the contact pairs are inside the other body of their pair, deeper than
   -contact_intersection_depth, on the real end-of-step geometry. It sees what the contact
   constraints of the step did not hold, whatever the reason (a crossing the detection missed, a
   constraint left open, bodies that started inside each other).
   The points are those the detection constrains: the vertices of a body's surface (an FE body or a
   mesh shape) or the points of a bounded rigid shape, against the analytic shape of the other body
   (its signed distance), and, between two bodies with
   surface triangles (FE-FE, FE-mesh), the vertices of each against the other's closed surface,
   both ways whatever -contact_fe_passes; and between those, the sharp edges of each (edges.c)
   through the other with both ends outside it: an edge whose point at 1/4, 1/2 or 3/4 of its
   length is inside deeper than the depth (crossed bars sunk into each other edge on edge, where
   no vertex is inside). A bounded analytic shape against a meshed body: the points of its
   picture (its tessellation's vertices, on its surface: what the detection constrains) against
   the meshed body's closed surface, besides the meshed body's vertices against the shape: a ball
   smaller than the elements, sunk into an FE slab between its vertices, has no slab vertex inside
   it. A shape that enters less deep than the gap between its surface and its picture's vertices
   is not seen (a sphere's picture has a vertex every 15 degrees of longitude and 11.25 of
   latitude, so a point of the sphere is up to about 9.4 degrees from a vertex: a gap of
   1 - cos 9.4 deg, 1.3 % of its radius).
   Inside a closed surface: an odd number of crossings of a ray from the point (in a fixed,
   generic direction, so that it does not run along the edges of structured meshes), the
   triangles bucketed in a 2D grid across the ray; deeper than d: no triangle within d (the
   spatial hash of collision.c, inflated by d).
   The vertices of a surface are taken from its gathered triangles, not from the detection's list of
   candidate points (the owned boundary vertices, src/mesh/mesh.c), so that a vertex the detection
   misses, whatever the reason (a partition on which no rank took it), is still counted when it
   goes through the other body. */
#include "collisionimpl.h"

/* A generic direction: no mesh of the repository has an edge or a face along it */
static const PetscReal RayDir[3] = {0.2672612419124244, 0.5345224838248488, 0.8017837257372732};

typedef FCRayGrid RayGrid;

static int64_t Key2(int64_t i, int64_t j)
{
  return ((i + ((int64_t)1 << 30)) << 32) | ((j + ((int64_t)1 << 30)) & 0xffffffff);
}

PetscErrorCode FCRayGridCreate(const FCSurface *S, FCRayGrid *G)
{
  PetscFunctionBegin;
  G->u[0] = RayDir[1];
  G->u[1] = -RayDir[0];
  G->u[2] = 0.0;
  {
    PetscReal l = PetscSqrtReal(FCDot(G->u, G->u));
    for (int d = 0; d < 3; d++) G->u[d] /= l;
  }
  FCCross(RayDir, G->u, G->v);
  G->h = S->h;
  for (int d = 0; d < 3; d++) {
    G->lo[d] = PETSC_MAX_REAL;
    G->hi[d] = -PETSC_MAX_REAL;
  }
  G->n     = 0;
  G->cells = NULL;
  PetscCall(PetscMalloc1(2 * S->n + 1, &G->along));
  for (PetscInt t = 0; t < S->n; t++) {
    G->along[2 * t]     = PETSC_MAX_REAL;
    G->along[2 * t + 1] = -PETSC_MAX_REAL;
    for (int a = 0; a < 3; a++) {
      PetscReal s         = FCDot(S->tri[t].x0[a], RayDir);
      G->along[2 * t]     = PetscMin(G->along[2 * t], s);
      G->along[2 * t + 1] = PetscMax(G->along[2 * t + 1], s);
    }
  }
  for (int pass = 0; pass < 2; pass++) {
    PetscInt e = 0;
    for (PetscInt t = 0; t < S->n; t++) {
      PetscReal mn[2] = {PETSC_MAX_REAL, PETSC_MAX_REAL}, mx[2] = {-PETSC_MAX_REAL, -PETSC_MAX_REAL};
      for (int a = 0; a < 3; a++) {
        PetscReal pu = FCDot(S->tri[t].x0[a], G->u), pv = FCDot(S->tri[t].x0[a], G->v);
        mn[0] = PetscMin(mn[0], pu);
        mx[0] = PetscMax(mx[0], pu);
        mn[1] = PetscMin(mn[1], pv);
        mx[1] = PetscMax(mx[1], pv);
        if (!pass)
          for (int d = 0; d < 3; d++) {
            G->lo[d] = PetscMin(G->lo[d], S->tri[t].x0[a][d]);
            G->hi[d] = PetscMax(G->hi[d], S->tri[t].x0[a][d]);
          }
      }
      for (int64_t i = (int64_t)PetscFloorReal(mn[0] / G->h); i <= (int64_t)PetscFloorReal(mx[0] / G->h); i++)
        for (int64_t j = (int64_t)PetscFloorReal(mn[1] / G->h); j <= (int64_t)PetscFloorReal(mx[1] / G->h); j++) {
          if (pass) {
            G->cells[e].key = Key2(i, j);
            G->cells[e].tri = t;
          }
          e++;
        }
    }
    if (!pass) {
      G->n = e;
      PetscCall(PetscMalloc1(e + 1, &G->cells));
    }
  }
  PetscCall(FCCellEntrySort(G->n, G->cells));
  PetscFunctionReturn(0);
}

PetscErrorCode FCRayGridDestroy(FCRayGrid *G)
{
  PetscFunctionBegin;
  PetscCall(PetscFree(G->cells));
  PetscCall(PetscFree(G->along));
  PetscFunctionReturn(0);
}

/* Whether triangle t lies wholly behind the start of a ray along s RayDir (s = +-1) from x (xs:
   x . RayDir), by more than a thousandth of its extent along the ray (a margin far above the
   round-off of the crossing test): the ray cannot cross it */
static inline PetscBool Behind(const FCRayGrid *G, PetscInt t, PetscReal xs, PetscReal s)
{
  PetscReal lo = G->along[2 * t], hi = G->along[2 * t + 1], m = 1e-3 * (hi - lo);
  return s > 0 ? hi < xs - m : lo > xs + m;
}

/* Odd number of crossings of the ray from x: inside the closed surface */
/* The grid cell of the ray from x: its key, and the index of its first entry in G->cells */
static PetscInt RayCell(const FCRayGrid *G, const PetscReal x[3], int64_t *key)
{
  PetscInt lo = 0, hi = G->n;

  *key = Key2((int64_t)PetscFloorReal(FCDot(x, G->u) / G->h), (int64_t)PetscFloorReal(FCDot(x, G->v) / G->h));
  while (lo < hi) {
    PetscInt mid = (lo + hi) / 2;
    if (G->cells[mid].key < *key)
      lo = mid + 1;
    else
      hi = mid;
  }
  return lo;
}

PetscBool FCRayGridInside(const FCSurface *S, const FCRayGrid *G, const PetscReal x[3])
{
  int64_t   key;
  PetscInt  lo, crossings = 0;
  PetscReal xs = FCDot(x, RayDir);

  for (int d = 0; d < 3; d++)
    if (x[d] < G->lo[d] || x[d] > G->hi[d]) return PETSC_FALSE;
  for (lo = RayCell(G, x, &key); lo < G->n && G->cells[lo].key == key; lo++) {
    const FCSurfaceTriangle *T = &S->tri[G->cells[lo].tri];
    if (Behind(G, G->cells[lo].tri, xs, 1.0)) continue;
    if (FCRayHitsTriangle(x, RayDir, T->x0[0], T->x0[1], T->x0[2])) crossings++;
  }
  return crossings % 2 ? PETSC_TRUE : PETSC_FALSE;
}

/* A body's closed surface, gathered, hashed and bucketed across the ray once per check: its points
   are tested against the other body's, and its sharp edges come from its triangles (S->tri) */
typedef struct {
  FCSurface         *S;
  RayGrid            G;
  FCSurfaceTopology *T; /* its topology (topology.c) */
} Closed;

/* the closed surface of body ib of the scene */
static PetscErrorCode ClosedCreate(MPI_Comm comm, FCBody bodies[], PetscInt ib, const FCContactPairs *pairs, Closed *c)
{
  PetscInt           n;
  FCSurfaceTriangle *tri;

  PetscFunctionBegin;
  PetscCall(FCSurfaceGather(comm, bodies[ib], &n, &tri));
  PetscCall(FCSurfaceCreate(n, tri, pairs->intersection_depth, &c->S));
  PetscCall(FCRayGridCreate(c->S, &c->G));
  PetscCall(FCSurfaceTopologyGet(pairs, ib, c->S->n, c->S->tri, &c->T));
  PetscFunctionReturn(0);
}

static PetscErrorCode ClosedDestroy(const FCContactPairs *pairs, Closed *c)
{
  PetscFunctionBegin;
  PetscCall(FCSurfaceTopologyRestore(pairs, &c->T));
  PetscCall(FCRayGridDestroy(&c->G));
  PetscCall(FCSurfaceDestroy(&c->S));
  PetscFunctionReturn(0);
}

/* x inside the closed surface, and no triangle of it within depth */
static PetscBool DeepInside(const Closed *c, const PetscReal x[3], PetscReal depth)
{
  PetscInt  best;
  PetscReal w[3], cp[3], d2;
  if (!FCRayGridInside(c->S, &c->G, x)) return PETSC_FALSE;
  FCSurfaceClosest(c->S, x, &best, w, cp, &d2);
  return best < 0 || d2 > depth * depth ? PETSC_TRUE : PETSC_FALSE;
}

/* The vertices of the gathered triangles tri of topology T, in its order (by reference position),
   as [X (3), x now (3)] each: T->nv of them in *vx (to be freed) */
static PetscErrorCode SurfaceVertices(const FCSurfaceTopology *T, const FCSurfaceTriangle *tri, PetscReal **vx)
{
  PetscReal *v;

  PetscFunctionBegin;
  PetscCall(PetscMalloc1(6 * T->nv + 1, &v));
  for (PetscInt k = 0; k < T->nv; k++)
    for (int d = 0; d < 3; d++) {
      v[6 * k + d]     = T->V[3 * k + d];
      v[6 * k + 3 + d] = tri[T->first[k] / 3].x0[T->first[k] % 3][d];
    }
  *vx = v;
  PetscFunctionReturn(0);
}

/* The points of a body that this rank checks: the vertices of its closed surface c (body ib,
   gathered here when c is NULL), each checked by one rank (k % size); or, for a body without
   surface triangles (a bounded analytic shape), the points of its picture (FCBodyGetContactPoints).
   x: 3 per point (to be freed) */
static PetscErrorCode CheckedPoints(MPI_Comm comm, FCBody bodies[], PetscInt ib, const FCContactPairs *pairs,
                                    const Closed *c, PetscInt *n, PetscReal **x)
{
  FCBody body = bodies[ib];

  PetscFunctionBegin;
  if (FCBodyHasSurfaceTriangles(body)) {
    PetscInt           m = 0, nv;
    PetscReal         *vx;
    PetscMPIInt        rank, size;
    FCSurfaceTriangle *tri = NULL;
    FCSurfaceTopology *T   = NULL;
    PetscCallMPI(MPI_Comm_rank(comm, &rank));
    PetscCallMPI(MPI_Comm_size(comm, &size));
    if (c)
      PetscCall(SurfaceVertices(c->T, c->S->tri, &vx));
    else {
      PetscInt ntri;
      PetscCall(FCSurfaceGather(comm, body, &ntri, &tri));
      PetscCall(FCSurfaceTopologyGet(pairs, ib, ntri, tri, &T));
      PetscCall(SurfaceVertices(T, tri, &vx));
    }
    nv = c ? c->T->nv : T->nv;
    PetscCall(FCSurfaceTopologyRestore(pairs, &T));
    PetscCall(PetscFree(tri));
    for (PetscInt k = rank; k < nv; k += size, m++)
      for (int d = 0; d < 3; d++) vx[3 * m + d] = vx[6 * k + 3 + d];
    *n = m;
    *x = vx;
  } else {
    FCProximity *prox;
    PetscReal   *x0, *xf, *key;
    PetscCall(FCBodyGetContactPoints(body, n, &prox, &x0, &xf, &key));
    PetscCall(PetscMalloc1(3 * (*n) + 1, x));
    PetscCall(PetscArraycpy(*x, x0, 3 * (*n)));
  }
  PetscFunctionReturn(0);
}

/* Points x of a body inside the closed surface B, deeper than depth */
static PetscErrorCode PointsInSurface(PetscInt n, const PetscReal x[], const Closed *B, PetscReal depth,
                                      PetscInt *count)
{
  PetscFunctionBegin;
  for (PetscInt i = 0; i < n; i++)
    if (DeepInside(B, &x[3 * i], depth)) (*count)++;
  PetscFunctionReturn(0);
}

/* Sharp edges of the closed surface P through the closed surface B: both ends outside B, a point
   of the edge inside deeper than depth. The edges are on every rank: rank r counts those with
   k % size == r */
static PetscErrorCode EdgesThroughSurface(MPI_Comm comm, const Closed *P, const Closed *B, PetscReal angle,
                                          PetscReal depth, PetscInt *count)
{
  PetscInt    ne;
  PetscReal  *ends;
  PetscMPIInt rank, size;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCallMPI(MPI_Comm_size(comm, &size));
  PetscCall(FCSurfaceSharpEdgeEnds(P->T, P->S->tri, angle, PETSC_FALSE, &ne, &ends));
  for (PetscInt k = rank; k < ne; k += size) {
    const PetscReal *a = &ends[6 * k], *b = &ends[6 * k + 3];
    if (FCRayGridInside(B->S, &B->G, a) || FCRayGridInside(B->S, &B->G, b))
      continue; /* a vertex inside: counted as one */
    for (int q = 1; q <= 3; q++) {
      PetscReal x[3];
      for (int i = 0; i < 3; i++) x[i] = a[i] + 0.25 * q * (b[i] - a[i]);
      if (DeepInside(B, x, depth)) {
        (*count)++;
        break;
      }
    }
  }
  PetscCall(PetscFree(ends));
  PetscFunctionReturn(0);
}

/* Points x of a body inside the analytic shape of B, deeper than depth */
static PetscErrorCode PointsInShape(PetscInt n, const PetscReal x[], FCBody B, PetscReal depth, PetscInt *count)
{
  PetscFunctionBegin;
  for (PetscInt i = 0; i < n; i++) {
    PetscReal d, nrm[3], cpb[3];
    PetscCall(FCBodyShapeDistance(B, FC_AT_NOW, &x[3 * i], &d, nrm, cpb));
    if (d < -depth) (*count)++;
  }
  PetscFunctionReturn(0);
}

/* Self-intersection of a body's closed surface (a self-contact pair): a vertex inside another
   part of its own body, deeper than depth. A vertex is on its own surface, where a ray's parity
   says nothing; the point just outside it, x + eps n (n its outward normal, eps 1e-7 of the
   surface's size), is outside its own part, winding number 0, and 1 inside another part. The
   winding number is the ray's signed crossings (+1 leaving through a triangle, -1 entering), the
   ray along RayDir or its opposite, whichever leaves the vertex's own surface (a ray that starts
   into it would cross it within eps of the vertex, where its triangles meet: a crossing counted
   twice or not at all). Deeper than depth: no triangle outside the vertex's ring within depth. */
static PetscInt SelfWinding(const FCSurface *S, const FCRayGrid *G, const PetscReal x[3], const PetscReal n[3])
{
  int64_t   cell;
  PetscInt  lo, wind  = 0;
  PetscReal dir[3], s = FCDot(RayDir, n) >= 0.0 ? 1.0 : -1.0, xs = FCDot(x, RayDir);

  for (int d = 0; d < 3; d++) dir[d] = s * RayDir[d];
  for (lo = RayCell(G, x, &cell); lo < G->n && G->cells[lo].key == cell; lo++) {
    const FCSurfaceTriangle *T = &S->tri[G->cells[lo].tri];
    PetscReal                e1[3], e2[3], nt[3]; /* the outward normal, unnormalized: its side of the ray */
    if (Behind(G, G->cells[lo].tri, xs, s)) continue;
    if (!FCRayHitsTriangle(x, dir, T->x0[0], T->x0[1], T->x0[2])) continue;
    for (int d = 0; d < 3; d++) {
      e1[d] = T->x0[1][d] - T->x0[0][d];
      e2[d] = T->x0[2][d] - T->x0[0][d];
    }
    FCCross(e1, e2, nt);
    wind += FCDot(nt, dir) > 0.0 ? 1 : -1;
  }
  return wind;
}

PetscBool FCRayGridSelfInside(const FCSurface *S, const FCRayGrid *G, const PetscReal x[3], const PetscReal n[3])
{
  PetscReal xout[3], ln = PetscSqrtReal(FCDot(n, n)), eps = 0.0;

  for (int d = 0; d < 3; d++) eps = PetscMax(eps, 1e-7 * (G->hi[d] - G->lo[d]));
  for (int d = 0; d < 3; d++) xout[d] = x[d] + eps * n[d] / (ln > 0 ? ln : 1.0);
  return SelfWinding(S, G, xout, n) >= 1 ? PETSC_TRUE : PETSC_FALSE;
}

PetscReal FCSurfaceNearestOutsideRing(const FCSurface *S, FCSelfRing *ring, const PetscReal x[3])
{
  PetscInt  cb, ce;
  PetscReal bestd = PETSC_MAX_REAL;
  FCSurfaceQueryPoint(S, x, &cb, &ce);
  for (PetscInt e = cb; e < ce; e++) {
    const FCSurfaceTriangle *T = &S->tri[S->cells[e].tri];
    PetscReal                cp[3], w[3], d2 = 0.0;
    if (ring && FCSelfRingHas(ring, S->cells[e].tri)) continue;
    FCClosestPointTriangle(x, T->x0[0], T->x0[1], T->x0[2], cp, w);
    for (int d = 0; d < 3; d++) d2 += PetscSqr(x[d] - cp[d]);
    bestd = PetscMin(bestd, d2);
  }
  return bestd;
}

/* Whether x on the surface (outward normal n, not unit) is inside another part of the body deeper
   than depth: the winding number just outside x is 1, and no triangle outside the ring of the
   surface vertex X is within depth */
static PetscErrorCode SelfDeep(Closed *c, const FCContactPairs *pairs, const PetscReal x[3], const PetscReal n[3],
                               const PetscReal X[3], PetscBool *deep)
{
  PetscFunctionBegin;
  *deep = PETSC_FALSE;
  if (!FCRayGridSelfInside(c->S, &c->G, x, n)) PetscFunctionReturn(0);
  if (!c->S->ring) PetscCall(FCSelfRingCreate(c->T, pairs->self_ring, &c->S->ring)); /* at the first such point */
  FCSelfRingVertex(c->S->ring, X);
  *deep = FCSurfaceNearestOutsideRing(c->S, c->S->ring, x) > pairs->intersection_depth * pairs->intersection_depth
              ? PETSC_TRUE
              : PETSC_FALSE;
  PetscFunctionReturn(0);
}

/* The sharp edges of a self pair's body through another part of it: both ends not counted as
   vertices inside, a point of the edge inside deeper than depth (as EdgesThroughSurface) */
static PetscErrorCode SelfEdgesThrough(MPI_Comm comm, Closed *c, const FCContactPairs *pairs, PetscInt *count)
{
  PetscInt    ne;
  PetscReal  *ed;
  PetscMPIInt rank, size;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCallMPI(MPI_Comm_size(comm, &size));
  PetscCall(FCSurfaceSharpEdgeEnds(c->T, c->S->tri, pairs->edge_angle, PETSC_TRUE, &ne, &ed));
  for (PetscInt k = rank; k < ne; k += size) {
    const PetscReal *a = &ed[15 * k], *b = a + 3, *Xa = a + 6, *Xb = a + 9, *n = a + 12;
    PetscBool        deep = PETSC_FALSE, end = PETSC_FALSE;
    for (int q = 1; q <= 3 && !deep; q++) {
      PetscReal x[3];
      for (int i = 0; i < 3; i++) x[i] = a[i] + 0.25 * q * (b[i] - a[i]);
      PetscCall(SelfDeep(c, pairs, x, n, q < 2 ? Xa : Xb, &deep));
    }
    if (!deep) continue;
    PetscCall(SelfDeep(c, pairs, a, n, Xa, &end)); /* a vertex inside: counted as one */
    if (!end) PetscCall(SelfDeep(c, pairs, b, n, Xb, &end));
    if (!end) (*count)++;
  }
  PetscCall(PetscFree(ed));
  PetscFunctionReturn(0);
}

static PetscErrorCode SelfIntersections(MPI_Comm comm, FCBody bodies[], PetscInt ib, const FCContactPairs *pairs,
                                        PetscInt *count)
{
  Closed          c;
  PetscInt        nvn;
  PetscReal      *vx;
  FCVertexNormal *vn;
  PetscMPIInt     rank, size;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCallMPI(MPI_Comm_size(comm, &size));
  PetscCall(ClosedCreate(comm, bodies, ib, pairs, &c));
  PetscCall(FCCollisionVertexNormals(c.T, c.S->tri, &nvn, &vn));
  PetscCall(SurfaceVertices(c.T, c.S->tri, &vx));
  for (PetscInt k = rank; k < nvn; k += size) { /* vn: the same vertices in the same order */
    PetscBool deep;
    PetscCall(SelfDeep(&c, pairs, &vx[6 * k + 3], vn[k].n, vn[k].X, &deep));
    if (deep) (*count)++;
  }
  PetscCall(SelfEdgesThrough(comm, &c, pairs, count));
  PetscCall(PetscFree(vx));
  PetscCall(PetscFree(vn));
  PetscCall(FCSelfRingDestroy(&c.S->ring));
  PetscCall(ClosedDestroy(pairs, &c));
  PetscFunctionReturn(0);
}

PetscErrorCode FCCollisionCountPairIntersections(MPI_Comm comm, PetscInt nbodies, FCBody bodies[],
                                                 const FCContactPairs *pairs, PetscInt *count)
{
  PetscInt local = 0, *self;

  PetscFunctionBegin;
  PetscCall(PetscCalloc1(pairs->n + 1, &self));
  for (PetscInt p = 0; p < pairs->n; p++) {
    FCBody A = bodies[pairs->body[p][0]], B = bodies[pairs->body[p][1]];
    if (A == B) { /* self-contact */
      PetscCall(SelfIntersections(comm, bodies, pairs->body[p][0], pairs, &self[p]));
      local += self[p];
      continue;
    }
    if (FCBodyHasSurfaceTriangles(A) && FCBodyHasSurfaceTriangles(B)) {
      Closed     ca, cb;
      PetscReal  depth = pairs->intersection_depth;
      PetscInt   n;
      PetscReal *x;
      PetscCall(ClosedCreate(comm, bodies, pairs->body[p][0], pairs, &ca));
      PetscCall(ClosedCreate(comm, bodies, pairs->body[p][1], pairs, &cb));
      PetscCall(CheckedPoints(comm, bodies, pairs->body[p][0], pairs, &ca, &n, &x));
      PetscCall(PointsInSurface(n, x, &cb, depth, &local));
      PetscCall(PetscFree(x));
      PetscCall(CheckedPoints(comm, bodies, pairs->body[p][1], pairs, &cb, &n, &x));
      PetscCall(PointsInSurface(n, x, &ca, depth, &local));
      PetscCall(PetscFree(x));
      PetscCall(EdgesThroughSurface(comm, &ca, &cb, pairs->edge_angle, depth, &local));
      PetscCall(EdgesThroughSurface(comm, &cb, &ca, pairs->edge_angle, depth, &local));
      PetscCall(ClosedDestroy(pairs, &ca));
      PetscCall(ClosedDestroy(pairs, &cb));
      continue;
    }
    for (int s = 0; s < 2; s++) { /* a body with points against the other's analytic shape */
      PetscInt   ix = pairs->body[p][s], iy = pairs->body[p][1 - s];
      FCBody     X = bodies[ix], Y = bodies[iy];
      PetscInt   n;
      PetscReal *x, depth = pairs->intersection_depth;
      if (!FCBodyIsDeformable(X) && !FCBodyHasBoundedShape(X)) continue; /* a plane has no points */
      if (!FCBodyHasShape(Y) && !FCBodyHasSurfaceTriangles(Y)) continue;
      PetscCall(CheckedPoints(comm, bodies, ix, pairs, NULL, &n, &x));
      if (FCBodyHasShape(Y))
        PetscCall(PointsInShape(n, x, Y, depth, &local));
      else { /* an analytic shape's points in a meshed body */
        Closed cy;
        PetscCall(ClosedCreate(comm, bodies, iy, pairs, &cy));
        PetscCall(PointsInSurface(n, x, &cy, depth, &local));
        PetscCall(ClosedDestroy(pairs, &cy));
      }
      PetscCall(PetscFree(x));
    }
  }
  PetscCall(MPIU_Allreduce(&local, count, 1, MPIU_INT, MPI_SUM, comm));
  if (pairs->self_inside) { /* where the next detection needs the self pairs' start-inside rule */
    PetscCall(MPIU_Allreduce(MPI_IN_PLACE, self, pairs->n, MPIU_INT, MPI_SUM, comm));
    for (PetscInt p = 0; p < pairs->n; p++) pairs->self_inside[p] = self[p] > 0 ? PETSC_TRUE : PETSC_FALSE;
  }
  PetscCall(PetscFree(self));
  PetscFunctionReturn(0);
}
