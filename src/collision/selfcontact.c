/* Self-contact of an FE body (a pair a:a, docs/method.md section 2.2): the body's owned boundary
   vertices against its own surface, in one pass (each vertex against every triangle covers both
   directions of a fold), by the machinery of the two-body pairs (the nearest facing triangle
   within the alarm distance, else the first one the vertex's motion reaches). A vertex is on its
   own surface, so two rules keep a body's own shape from being taken for a contact (FCCollisionSelfExcludes):
     - the ring: a vertex leaves out the triangles that touch a surface vertex within
       -contact_self_ring - 1 edges of it in the reference configuration (ring 1: the triangles
       around it, which it lies on; ring 2, the default, also those around its neighbours, which a
       concave corner of the surface brings within the alarm distance at rest);
     - the body's own thickness: a triangle the vertex is behind (on the side its outward normal
       points away from) in the reference configuration and at the start of the step, there deeper
       than -contact_intersection_depth, is the other face of a wall or slab, never a landing place
       (a fold that has crossed was in front of it in the reference configuration, and stays one;
       a vertex held a little behind a fold's other side stays in contact with it).
   With -contact_facing (on by default for self-contact too) a vertex lands only on triangles whose
   normal opposes its own, so the flat and convex parts of the surface around it are never landing
   places either, and a fold is (its two sides face each other).
   A vertex of the surface lies on it, so the start-inside fallback of the two-body pairs (a point
   inside the other body) does not apply; continuous detection keeps a fold from crossing.
   The sharp edges of the body meet its own in edges.c, with the same two rules for edges
   (FCCollisionSelfEdgeInRing here). */
#include "collisionimpl.h"

struct _FCSelfRing {
  const Surface *S;     /* whose triangles */
  PetscBool      built; /* the topology below is built (at the first ring a vertex needs) */
  PetscInt       nv, ntri, k;
  PetscReal     *X;             /* 3 nv: the surface's vertices by reference position, sorted */
  PetscInt      *tv;            /* 3 ntri: each triangle's vertices */
  PetscInt      *off, *vt;      /* vertex -> its triangles */
  PetscInt      *mark, *queue;  /* nv: the BFS's marks and queue */
  PetscInt      *skip, nskipmx; /* the current vertex's ring triangles (3 ntri + 1), sorted */
  PetscInt       nskip;
  PetscBool      pending; /* the current vertex's ring is still to be found */
};

static PetscInt VertexOf(const struct _FCSelfRing *r, const PetscReal X[3])
{
  const PetscReal *f = (const PetscReal *)bsearch(X, r->X, r->nv, 3 * sizeof(PetscReal), FCComparePoint);
  return f ? (PetscInt)((f - r->X) / 3) : -1;
}

static int CompareInt(const void *a, const void *b)
{
  PetscInt x = *(const PetscInt *)a, y = *(const PetscInt *)b;
  return x < y ? -1 : (x > y ? 1 : 0);
}

/* The surface's topology in the reference configuration: its vertices by reference position
   (sorted), each triangle's vertices and each vertex's triangles */
static void RingBuild(struct _FCSelfRing *r)
{
  const Surface *S = r->S;
  PetscInt       m = 0;

  r->built = PETSC_TRUE;
  for (PetscInt t = 0; t < S->n; t++)
    for (int a = 0; a < 3; a++)
      for (int d = 0; d < 3; d++) r->X[9 * t + 3 * a + d] = S->tri[t].X[a][d];
  if (S->n) qsort(r->X, 3 * S->n, 3 * sizeof(PetscReal), FCComparePoint);
  for (PetscInt i = 0; i < 3 * S->n; i++)
    if (!m || FCComparePoint(&r->X[3 * (m - 1)], &r->X[3 * i])) {
      for (int d = 0; d < 3; d++) r->X[3 * m + d] = r->X[3 * i + d];
      m++;
    }
  r->nv = m;
  for (PetscInt v = 0; v <= m; v++) r->off[v] = 0;
  for (PetscInt t = 0; t < S->n; t++)
    for (int a = 0; a < 3; a++) {
      r->tv[3 * t + a] = VertexOf(r, S->tri[t].X[a]);
      r->off[r->tv[3 * t + a] + 1]++;
    }
  for (PetscInt v = 0; v < m; v++) r->off[v + 1] += r->off[v];
  for (PetscInt v = 0; v < m; v++) r->mark[v] = r->off[v]; /* as fill pointers */
  for (PetscInt t = 0; t < S->n; t++)
    for (int a = 0; a < 3; a++) r->vt[r->mark[r->tv[3 * t + a]]++] = t;
  for (PetscInt v = 0; v < m; v++) r->mark[v] = -1;
}

/* The ring's storage for S (3 ntri vertices at most); its topology is built at the first ring a
   vertex needs: a body that does not fold needs none in most steps */
PetscErrorCode FCCollisionSelfRingSetUp(Surface *S, PetscInt k)
{
  struct _FCSelfRing *r;
  PetscInt            n = S->n;

  PetscFunctionBegin;
  PetscCall(PetscNew(&r));
  r->S    = S;
  r->ntri = n;
  r->k    = k;
  PetscCall(PetscMalloc1(9 * n + 3, &r->X));
  PetscCall(PetscMalloc5(3 * n + 1, &r->tv, 3 * n + 2, &r->off, 3 * n + 1, &r->vt, 3 * n + 1, &r->mark, 3 * n + 1,
                         &r->queue));
  r->nskipmx = 3 * n + 1; /* every triangle three times at most */
  PetscCall(PetscMalloc1(r->nskipmx, &r->skip));
  S->ring = r;
  PetscFunctionReturn(0);
}

PetscErrorCode FCCollisionSelfRingReset(Surface *S)
{
  struct _FCSelfRing *r = S->ring;

  PetscFunctionBegin;
  if (!r) PetscFunctionReturn(0);
  PetscCall(PetscFree(r->X));
  PetscCall(PetscFree5(r->tv, r->off, r->vt, r->mark, r->queue));
  PetscCall(PetscFree(r->skip));
  PetscCall(PetscFree(S->ring));
  PetscFunctionReturn(0);
}

/* X is the current vertex: its ring is found when a triangle is first tested against it (most
   vertices of a body that does not fold have no candidate triangle that faces them) */
void FCCollisionSelfVertex(Surface *S, const PetscReal X[3])
{
  for (int d = 0; d < 3; d++) S->selfX[d] = X[d];
  S->ring->pending = PETSC_TRUE;
}

/* The triangles around the vertices within k - 1 edges of the current vertex X (a breadth-first
   walk over the surface's triangles), sorted, as r->skip */
static void RingFind(struct _FCSelfRing *r, const PetscReal X[3])
{
  PetscInt v0, head = 0, tail = 0, n = 0;

  if (!r->built) RingBuild(r);
  v0         = VertexOf(r, X);
  r->nskip   = 0;
  r->pending = PETSC_FALSE;
  if (v0 < 0) return;
  r->mark[v0]      = 0;
  r->queue[tail++] = v0;
  while (head < tail) {
    PetscInt v = r->queue[head++];
    for (PetscInt j = r->off[v]; j < r->off[v + 1]; j++) {
      PetscInt t = r->vt[j];
      if (n < r->nskipmx) r->skip[n++] = t; /* (a triangle repeats once per ring vertex it touches) */
      if (r->mark[v] + 1 <= r->k - 1)
        for (int a = 0; a < 3; a++) {
          PetscInt w = r->tv[3 * t + a];
          if (r->mark[w] < 0) {
            r->mark[w]       = r->mark[v] + 1;
            r->queue[tail++] = w;
          }
        }
    }
  }
  for (PetscInt i = 0; i < tail; i++) r->mark[r->queue[i]] = -1;
  qsort(r->skip, n, sizeof(PetscInt), CompareInt);
  {
    PetscInt u = 0;
    for (PetscInt i = 0; i < n; i++)
      if (!u || r->skip[u - 1] != r->skip[i]) r->skip[u++] = r->skip[i];
    n = u;
  }
  r->nskip = n;
}

/* Behind triangle T (on the side its outward normal points away from) at p, T's corners c: the
   signed distance from T's closest point along T's normal is below -tol */
static PetscBool Behind(const PetscReal p[3], const PetscReal c[3][3], PetscReal tol)
{
  PetscReal cp[3], w[3], n[3], s = 0.0;
  FCClosestPointTriangle(p, c[0], c[1], c[2], cp, w);
  FCTriangleNormal(c, n);
  for (int d = 0; d < 3; d++) s += (p[d] - cp[d]) * n[d];
  return s < -tol ? PETSC_TRUE : PETSC_FALSE;
}

PetscBool FCCollisionSelfExcludesRing(const Surface *S, PetscInt t)
{
  struct _FCSelfRing *r  = S->ring;
  PetscInt            lo = 0, hi;
  if (r->pending) RingFind(r, S->selfX);
  hi = r->nskip;
  while (lo < hi) { /* the ring (sorted) */
    PetscInt m = (lo + hi) / 2;
    if (r->skip[m] == t) return PETSC_TRUE;
    if (r->skip[m] < t)
      lo = m + 1;
    else
      hi = m;
  }
  return PETSC_FALSE;
}

PetscBool FCCollisionSelfEdgeInRing(const Surface *S, const PetscReal Xa[2][3], const PetscReal Xb[2][3])
{
  struct _FCSelfRing *r = S->ring;
  PetscInt            vb[2];
  PetscBool           in = PETSC_FALSE;

  if (!r->built) RingBuild(r);
  vb[0] = VertexOf(r, Xb[0]);
  vb[1] = VertexOf(r, Xb[1]);
  for (int e = 0; e < 2 && !in; e++) {
    RingFind(r, Xa[e]);
    for (PetscInt i = 0; i < r->nskip && !in; i++)
      for (int a = 0; a < 3; a++)
        if (r->tv[3 * r->skip[i] + a] == vb[0] || r->tv[3 * r->skip[i] + a] == vb[1]) in = PETSC_TRUE;
  }
  r->pending = PETSC_TRUE; /* r->skip no longer holds the current vertex's ring */
  return in;
}

PetscBool FCCollisionSelfExcludes(const Surface *S, PetscInt t, const PetscReal x[3])
{
  if (FCCollisionSelfExcludesRing(S, t)) return PETSC_TRUE;
  /* across the body's own thickness: behind the triangle now and in the reference configuration
     (a fold that has crossed was in front of it there, and stays a landing place). Now: deeper
     than -contact_intersection_depth, so that a vertex of a fold that a contact holds a little
     behind its other side (within the solver's tolerance) stays in contact with it */
  return Behind(x, S->tri[t].x0, S->selfdepth) && Behind(S->selfX, S->tri[t].X, 0.0) ? PETSC_TRUE : PETSC_FALSE;
}

PetscErrorCode FCCollisionSelfPair(MPI_Comm comm, FCBody b, PetscInt ib, PetscInt pair, const FCContactPairs *pairs,
                                   PetscMPIInt rank, FCContactSet *set)
{
  Surface        *S   = NULL;
  FCVertexNormal *vn  = NULL;
  PetscInt        nvn = 0;

  PetscFunctionBegin;
  PetscCall(FCCollisionSurfaceBuild(comm, b, pairs, &S));
  if (pairs->facing) PetscCall(FCCollisionVertexNormals(S->n, S->tri, &nvn, &vn));
  PetscCall(FCCollisionSelfRingSetUp(S, pairs->self_ring));
  S->self      = PETSC_TRUE;
  S->selfdepth = pairs->intersection_depth;
  PetscCall(FCCollisionVerticesAgainstSurface(b, b, ib, ib, S, nvn, vn, pair, pairs, rank, set));
  PetscCall(FCCollisionSelfRingReset(S));
  PetscCall(FCSurfaceDestroy(&S));
  PetscCall(PetscFree(vn));
  PetscFunctionReturn(0);
}

/* A self-contact is a vertex of a fold against a triangle of its other side; the other side's
   vertices land back on the first side's triangles, and a vertex of the one is a corner of the
   other's triangle: the two constraints are nearly redundant, as those of a two-body pair's two
   passes (HeldSecondPass, collision.c). Of such a pair the contact whose vertex comes later in the
   order of reference positions is dormant: a self-contact whose vertex has a barycentric weight
   > w (-contact_fe_pass2_dormant) in another self-contact of the body whose vertex comes first.
   Runs on the gathered set, the same on every rank. */
PetscErrorCode FCCollisionSelfHeld(PetscReal w, FCContactSet *set)
{
  PetscReal *rec; /* 6 a row: a held corner's reference position, then its holder's */
  PetscInt   n = 0;

  PetscFunctionBegin;
  PetscCall(PetscMalloc1(18 * set->n + 6, &rec));
  for (PetscInt k = 0; k < set->n; k++) {
    const FCContact *c = &set->c[k];
    if (c->body[0] != c->body[1] || c->side2 != FC_SIDE_FE_TRIANGLE || c->prox[0].nv != 1) continue;
    for (int a = 0; a < 3; a++)
      if (c->prox[1].w[a] > w) {
        for (int d = 0; d < 3; d++) {
          rec[6 * n + d]     = c->prox[1].X[a][d];
          rec[6 * n + 3 + d] = c->prox[0].X[0][d];
        }
        n++;
      }
  }
  if (n > 1) qsort(rec, n, 6 * sizeof(PetscReal), FCComparePoint); /* by the held corner */
  for (PetscInt k = 0; k < set->n && n; k++) {
    FCContact       *c = &set->c[k];
    const PetscReal *f;
    if (c->body[0] != c->body[1] || c->side2 != FC_SIDE_FE_TRIANGLE || c->prox[0].nv != 1) continue;
    f = (const PetscReal *)bsearch(c->prox[0].X[0], rec, n, 6 * sizeof(PetscReal), FCComparePoint);
    if (!f) continue;
    while (f > rec && !FCComparePoint(f - 6, c->prox[0].X[0])) f -= 6; /* the first record of this corner */
    for (; f < rec + 6 * n && !FCComparePoint(f, c->prox[0].X[0]); f += 6)
      if (FCComparePoint(f + 3, c->prox[0].X[0]) < 0) c->dormant = PETSC_TRUE;
  }
  PetscCall(PetscFree(rec));
  PetscFunctionReturn(0);
}
