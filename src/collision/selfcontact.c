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
   A vertex of the surface lies on it, where a ray's parity says nothing: the start-inside rule of the
   two-body pairs takes a vertex with no landing triangle that is inside another part of its body
   (FCRayGridSelfInside: the winding number just outside it) to its nearest triangle but those of the
   body's own shape, and only where the last intersection count found the body inside itself
   (pairs->self_inside).
   The sharp edges of the body meet its own in edges.c, with the same two rules for edges
   (FCSelfRingEdgeIn here). The ring walks the surface's topology (topology.c), built once per run. */
#include "collisionimpl.h"

struct _FCSelfRing {
  const FCSurfaceTopology *T; /* the surface's (borrowed) */
  PetscInt                 k;
  PetscReal                X[3];         /* the current vertex */
  PetscInt                *mark, *queue; /* nv: the BFS's marks and queue */
  PetscInt                *skip, nskip;  /* the current vertex's ring triangles, each once */
  PetscInt                *in, walk;     /* ntri: the last walk that put the triangle on skip */
  PetscBool                pending;      /* the current vertex's ring is still to be found */
};

static PetscInt VertexOf(const FCSurfaceTopology *T, const PetscReal X[3])
{
  const PetscReal *f = (const PetscReal *)bsearch(X, T->V, T->nv, 3 * sizeof(PetscReal), FCComparePoint);
  return f ? (PetscInt)((f - T->V) / 3) : -1;
}

PetscErrorCode FCSelfRingCreate(const FCSurfaceTopology *T, PetscInt k, FCSelfRing **ring)
{
  FCSelfRing *r;

  PetscFunctionBegin;
  PetscCall(PetscNew(&r));
  r->T = T;
  r->k = k;
  PetscCall(PetscMalloc4(T->nv + 1, &r->mark, T->nv + 1, &r->queue, T->ntri + 1, &r->skip, T->ntri + 1, &r->in));
  for (PetscInt v = 0; v < T->nv; v++) r->mark[v] = -1;
  for (PetscInt t = 0; t < T->ntri; t++) r->in[t] = -1;
  *ring = r;
  PetscFunctionReturn(0);
}

PetscErrorCode FCSelfRingDestroy(FCSelfRing **ring)
{
  PetscFunctionBegin;
  if (!*ring) PetscFunctionReturn(0);
  PetscCall(PetscFree4((*ring)->mark, (*ring)->queue, (*ring)->skip, (*ring)->in));
  PetscCall(PetscFree(*ring));
  PetscFunctionReturn(0);
}

/* X is the current vertex: its ring is found when a triangle is first tested against it (most
   vertices of a body that does not fold have no candidate triangle that faces them) */
void FCSelfRingVertex(FCSelfRing *r, const PetscReal X[3])
{
  for (int d = 0; d < 3; d++) r->X[d] = X[d];
  r->pending = PETSC_TRUE;
}

/* The triangles around the vertices within k - 1 edges of the vertex X (a breadth-first walk over
   the surface's triangles), as r->skip, each marked by the walk's number in r->in */
static void RingFind(FCSelfRing *r, const PetscReal X[3])
{
  const FCSurfaceTopology *T = r->T;
  PetscInt                 v0, head = 0, tail = 0, n = 0;

  v0         = VertexOf(T, X);
  r->nskip   = 0;
  r->pending = PETSC_FALSE;
  r->walk++;
  if (v0 < 0) return;
  r->mark[v0]      = 0;
  r->queue[tail++] = v0;
  while (head < tail) {
    PetscInt v = r->queue[head++];
    for (PetscInt j = T->off[v]; j < T->off[v + 1]; j++) {
      PetscInt t = T->vt[j];
      if (r->in[t] != r->walk) {
        r->in[t]     = r->walk;
        r->skip[n++] = t;
      }
      if (r->mark[v] + 1 <= r->k - 1)
        for (int a = 0; a < 3; a++) {
          PetscInt w = T->tv[3 * t + a];
          if (r->mark[w] < 0) {
            r->mark[w]       = r->mark[v] + 1;
            r->queue[tail++] = w;
          }
        }
    }
  }
  for (PetscInt i = 0; i < tail; i++) r->mark[r->queue[i]] = -1;
  r->nskip = n;
}

PetscBool FCSelfRingHas(FCSelfRing *r, PetscInt t)
{
  if (r->pending) RingFind(r, r->X);
  return r->in[t] == r->walk ? PETSC_TRUE : PETSC_FALSE;
}

PetscBool FCSelfRingEdgeIn(FCSelfRing *r, const PetscReal Xa[2][3], const PetscReal Xb[2][3])
{
  const FCSurfaceTopology *T = r->T;
  PetscInt                 vb[2];
  PetscBool                in = PETSC_FALSE;

  vb[0] = VertexOf(T, Xb[0]);
  vb[1] = VertexOf(T, Xb[1]);
  for (int e = 0; e < 2 && !in; e++) {
    RingFind(r, Xa[e]);
    for (PetscInt i = 0; i < r->nskip && !in; i++)
      for (int a = 0; a < 3; a++)
        if (T->tv[3 * r->skip[i] + a] == vb[0] || T->tv[3 * r->skip[i] + a] == vb[1]) in = PETSC_TRUE;
  }
  r->pending = PETSC_TRUE; /* r->skip no longer holds the current vertex's ring */
  return in;
}

/* Before vertex X's landing: X is the current vertex of S's ring */
void FCCollisionSelfVertex(Surface *S, const PetscReal X[3])
{
  for (int d = 0; d < 3; d++) S->selfX[d] = X[d];
  FCSelfRingVertex(S->ring, X);
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

PetscBool FCCollisionSelfExcludes(const Surface *S, PetscInt t, const PetscReal x[3])
{
  if (FCSelfRingHas(S->ring, t)) return PETSC_TRUE;
  /* across the body's own thickness: behind the triangle now and in the reference configuration
     (a fold that has crossed was in front of it there, and stays a landing place). Now: deeper
     than -contact_intersection_depth, so that a vertex of a fold that a contact holds a little
     behind its other side (within the solver's tolerance) stays in contact with it */
  return Behind(x, S->tri[t].x0, S->selfdepth) && Behind(S->selfX, S->tri[t].X, 0.0) ? PETSC_TRUE : PETSC_FALSE;
}

PetscErrorCode FCCollisionSelfPair(MPI_Comm comm, FCBody b, PetscInt ib, PetscInt pair, const FCContactPairs *pairs,
                                   PetscMPIInt rank, FCContactSet *set)
{
  Surface           *S   = NULL;
  FCVertexNormal    *vn  = NULL;
  FCSurfaceTopology *T   = NULL;
  PetscInt           nvn = 0;

  PetscFunctionBegin;
  PetscCall(FCCollisionSurfaceBuild(comm, b, pairs, &S));
  PetscCall(FCSurfaceTopologyGet(pairs, ib, S->n, S->tri, &T));
  if (pairs->facing) PetscCall(FCCollisionVertexNormals(T, S->tri, &nvn, &vn));
  PetscCall(FCSelfRingCreate(T, pairs->self_ring, &S->ring));
  S->self      = PETSC_TRUE;
  S->selfdepth = pairs->intersection_depth;
  S->selfstart = !pairs->self_inside || pairs->self_inside[pair] ? PETSC_TRUE : PETSC_FALSE;
  PetscCall(FCCollisionVerticesAgainstSurface(b, b, ib, ib, S, nvn, vn, pair, pairs, rank, set));
  if (pairs->edges) PetscCall(FCCollisionEdgeEdge(comm, b, b, ib, ib, S->n, S->tri, S->n, S->tri, pair, pairs, set));
  PetscCall(FCSelfRingDestroy(&S->ring));
  PetscCall(FCSurfaceTopologyRestore(pairs, &T));
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
