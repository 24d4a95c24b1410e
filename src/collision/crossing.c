/* The crossing audit (docs/method.md, 2.7; /steps/crossings): after a step's solve and integration,
   what went through the surface of another body over the step's actual motion without a contact
   holding it. Every point moves linearly from its start-of-step position to its end-of-step one;
   the features are those of the detection and of the intersection count (intersection.c):
   - a vertex of a surface (an FE body's, a rigid mesh's) or a point of a bounded shape's picture,
     against the triangles of another body's surface (both ways between two meshed bodies), and in a
     self pair (a:a) a vertex against its own body's triangles outside its ring (-contact_self_ring);
   - a sharp edge of a surface (-contact_edge_angle) against the edges of another body's surface (two meshed
     bodies).
   A vertex crosses a triangle when, at some time of the step, it passes through the triangle's
   interior from its outer side (the outward normal's) to its inner side: the triple product
   f(t) = n(t) . (p(t) - a(t)), n = (b - a) x (c - a), a cubic in t, goes from + to - at a time
   where the point is inside the triangle, the triangle facing the same way as at the step's start and end (one that
   turns over, an element inside out, moves its plane across the point instead). It counts when at the end of the step
   the point is still behind that triangle's plane by more than -contact_intersection_depth and farther than that from
   the other body's surface: deep inside it, or through it and out on its other side (a ball that
   went wholly through a membrane). A vertex that a contact holds on the surface is within that depth
   of it; one that started behind the triangle (an intersection already counted) does not cross it
   again. An edge crosses another when the four ends become coplanar at a time where the segments
   meet, and counts when at the end a point of it (1/4, 1/2, 3/4) is inside the other body deeper
   than the depth with neither of its ends (a vertex inside is that vertex's crossing).
   The start positions are taken at the sub-step's start (FCCrossingAuditStart), the end positions
   after the integration; the surfaces are gathered on every rank, and each rank checks every
   size-th vertex, edge and point; the count and the deepest are the same on every rank. */
#include "collisionimpl.h"
#include <string.h>

/* x = x0 + t (x1 - x0) */
static inline void Lerp(const PetscReal x0[3], const PetscReal x1[3], PetscReal t, PetscReal x[3])
{
  for (int d = 0; d < 3; d++) x[d] = x0[d] + t * (x1[d] - x0[d]);
}

struct _FCCrossingAudit {
  PetscInt            nbodies;
  PetscInt           *ntri; /* per scene body: its gathered triangles at the start (0: not taken) */
  FCSurfaceTriangle **tri;
  PetscInt           *npts; /* per scene body: a bounded shape's picture points at the start */
  PetscReal         **pts;
};

/* A body's surface over the step: its triangles with x0 the end positions and xf the start ones, hashed by their boxes
   over the step (inflated by the depth), bucketed across the ray at the end; its topology */
typedef struct {
  FCSurface         *S;
  FCRayGrid          G;
  FCSurfaceTopology *T;
  FCSelfRing        *ring; /* a self pair's */
} Swept;

static PetscErrorCode SweptCreate(MPI_Comm comm, FCBody body, PetscInt ib, const FCContactPairs *pairs,
                                  FCCrossingAudit A, Swept *w)
{
  PetscInt           n;
  FCSurfaceTriangle *tri;

  PetscFunctionBegin;
  PetscCall(FCSurfaceGather(comm, body, &n, &tri));
  PetscCheck(n == A->ntri[ib], comm, PETSC_ERR_PLIB, "The surface of body %" PetscInt_FMT " changed over the step", ib);
  for (PetscInt t = 0; t < n; t++) {
    PetscCheck(!memcmp(tri[t].X, A->tri[ib][t].X, sizeof(tri[t].X)), comm, PETSC_ERR_PLIB,
               "The surface of body %" PetscInt_FMT " changed order over the step", ib);
    PetscCall(PetscArraycpy(&tri[t].xf[0][0], &A->tri[ib][t].x0[0][0], 9));
  }
  PetscCall(FCSurfaceCreateSwept(n, tri, pairs->intersection_depth, &w->S));
  PetscCall(FCRayGridCreate(w->S, &w->G));
  PetscCall(FCSurfaceTopologyGet(pairs, ib, n, w->S->tri, &w->T));
  w->ring = NULL;
  PetscFunctionReturn(0);
}

static PetscErrorCode SweptDestroy(const FCContactPairs *pairs, Swept *w)
{
  PetscFunctionBegin;
  PetscCall(FCSelfRingDestroy(&w->ring));
  PetscCall(FCSurfaceTopologyRestore(pairs, &w->T));
  PetscCall(FCRayGridDestroy(&w->G));
  PetscCall(FCSurfaceDestroy(&w->S));
  PetscFunctionReturn(0);
}

/* The squared distance from x to the nearest triangle of B at the end, outside the current ring of a self pair */
static inline PetscReal Nearest2(const Swept *B, const PetscReal x[3])
{
  return FCSurfaceNearestOutsideRing(B->S, B->ring, x);
}

/* Whether the point x0 -> x1 (reference position X in a self pair) crosses a triangle of B (see the top); *deepest
   grows to how far it ends behind it */
static PetscBool PointCrosses(Swept *B, const PetscReal x0[3], const PetscReal x1[3], const PetscReal X[3],
                              PetscReal depth, PetscInt cand[], PetscReal *deepest)
{
  PetscReal lo[3], hi[3];
  PetscInt  nc;

  for (int d = 0; d < 3; d++) {
    lo[d] = PetscMin(x0[d], x1[d]);
    hi[d] = PetscMax(x0[d], x1[d]);
  }
  FCSurfaceQueryBox(B->S, lo, hi, cand, &nc);
  if (B->ring) FCSelfRingVertex(B->ring, X);
  for (PetscInt k = 0; k < nc; k++) {
    const FCSurfaceTriangle *T = &B->S->tri[cand[k]];
    PetscReal                behind;
    if (B->ring && FCSelfRingHas(B->ring, cand[k])) continue;
    if (!FCCCDPointCrossesTriangle(x0, x1, T->xf, T->x0, &behind) || behind <= depth) continue;
    if (Nearest2(B, x1) <= depth * depth) continue; /* held on the surface */
    *deepest = PetscMax(*deepest, behind);
    return PETSC_TRUE;
  }
  return PETSC_FALSE;
}

/* The vertices of the surface P (every size-th from rank) against the surface B */
static PetscErrorCode VerticesCross(MPI_Comm comm, const Swept *P, Swept *B, PetscReal depth, PetscInt *count,
                                    PetscReal *deepest)
{
  PetscMPIInt rank, size;
  PetscInt   *cand;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCallMPI(MPI_Comm_size(comm, &size));
  PetscCall(PetscMalloc1(B->S->n + 1, &cand));
  for (PetscInt k = rank; k < P->T->nv; k += size) {
    const FCSurfaceTriangle *t = &P->S->tri[P->T->first[k] / 3];
    PetscInt                 a = P->T->first[k] % 3;
    if (PointCrosses(B, t->xf[a], t->x0[a], t->X[a], depth, cand, deepest)) (*count)++;
  }
  PetscCall(PetscFree(cand));
  PetscFunctionReturn(0);
}

/* x inside B at the end, with no triangle of B within depth */
static PetscBool DeepInside(const Swept *B, const PetscReal x[3], PetscReal depth)
{
  return FCRayGridInside(B->S, &B->G, x) && Nearest2(B, x) > depth * depth ? PETSC_TRUE : PETSC_FALSE;
}

/* The ends of half-edge h (3 t + a) of the swept surface W: at the start (e0) and the end (e1) */
static void HalfEdge(const Swept *W, PetscInt h, PetscReal e0[2][3], PetscReal e1[2][3])
{
  const FCSurfaceTriangle *T = &W->S->tri[h / 3];
  for (int k = 0; k < 2; k++)
    for (int d = 0; d < 3; d++) {
      e0[k][d] = T->xf[(h % 3 + k) % 3][d];
      e1[k][d] = T->x0[(h % 3 + k) % 3][d];
    }
}

/* Whether edge k of the surface W is one the edge-edge contacts take: its two triangles turn by more than the angle
   whose cosine is cmax at the end of the step (cmax > 1: every edge) */
static PetscBool Sharp(const Swept *W, PetscInt k, PetscReal cmax)
{
  PetscReal n1[3], n2[3];

  if (cmax > 1.0) return PETSC_TRUE;
  FCTriangleNormal(W->S->tri[W->T->edge[k][0] / 3].x0, n1);
  FCTriangleNormal(W->S->tri[W->T->edge[k][1] / 3].x0, n2);
  return FCDot(n1, n2) <= cmax ? PETSC_TRUE : PETSC_FALSE;
}

/* The edges of the surface P that the edge-edge contacts take (-contact_edge_angle; every size-th from rank) against
   the edges of the surface B (not a self pair) */
static PetscErrorCode EdgesCross(MPI_Comm comm, const Swept *P, Swept *B, PetscReal angle, PetscReal depth,
                                 PetscInt *count, PetscReal *deepest)
{
  PetscMPIInt rank, size;
  PetscInt   *cand;
  PetscReal   cmax = angle > 0.0 ? PetscCosReal(angle * PETSC_PI / 180.0) : 2.0;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCallMPI(MPI_Comm_size(comm, &size));
  PetscCall(PetscMalloc1(B->S->n + 1, &cand));
  for (PetscInt k = rank; k < P->T->ne; k += size) {
    PetscReal a0[2][3], a1[2][3], lo[3], hi[3];
    PetscInt  nc;
    PetscBool met  = PETSC_FALSE;
    PetscReal deep = 0.0;
    if (!Sharp(P, k, cmax)) continue;
    HalfEdge(P, P->T->edge[k][0], a0, a1);
    if (DeepInside(B, a1[0], depth) || DeepInside(B, a1[1], depth)) continue; /* a vertex's own */
    for (int q = 1; q <= 3; q++) { /* how deep its deepest point is inside B, if deeper than the depth */
      PetscReal x[3];
      Lerp(a1[0], a1[1], 0.25 * q, x);
      if (DeepInside(B, x, depth)) deep = PetscMax(deep, PetscSqrtReal(PetscMin(Nearest2(B, x), PETSC_MAX_REAL / 2)));
    }
    if (deep == 0.0) continue;
    for (int d = 0; d < 3; d++) {
      lo[d] = PetscMin(PetscMin(a0[0][d], a0[1][d]), PetscMin(a1[0][d], a1[1][d]));
      hi[d] = PetscMax(PetscMax(a0[0][d], a0[1][d]), PetscMax(a1[0][d], a1[1][d]));
    }
    FCSurfaceQueryBox(B->S, lo, hi, cand, &nc);
    for (PetscInt c = 0; c < nc && !met; c++)
      for (int e = 0; e < 3 && !met; e++) {
        PetscReal b0[2][3], b1[2][3];
        HalfEdge(B, 3 * cand[c] + e, b0, b1);
        met = FCCCDEdgesMeet(a0, a1, b0, b1);
      }
    if (!met) continue;
    (*count)++;
    *deepest = PetscMax(*deepest, deep);
  }
  PetscCall(PetscFree(cand));
  PetscFunctionReturn(0);
}

/* The picture points of a bounded shape (body ib) against the surface B */
static PetscErrorCode ShapePointsCross(FCBody body, PetscInt ib, FCCrossingAudit A, Swept *B, PetscReal depth,
                                       PetscInt *count, PetscReal *deepest)
{
  FCProximity *prox;
  PetscReal   *x1, *xf, *key;
  PetscInt     n, *cand;

  PetscFunctionBegin;
  PetscCall(FCBodyGetContactPoints(body, &n, &prox, &x1, &xf, &key));
  PetscCheck(n == A->npts[ib], PETSC_COMM_SELF, PETSC_ERR_PLIB, "The points of body %" PetscInt_FMT " changed", ib);
  PetscCall(PetscMalloc1(B->S->n + 1, &cand));
  for (PetscInt i = 0; i < n; i++)
    if (PointCrosses(B, &A->pts[ib][3 * i], &x1[3 * i], &key[3 * i], depth, cand, deepest)) (*count)++;
  PetscCall(PetscFree(cand));
  PetscFunctionReturn(0);
}

PetscErrorCode FCCrossingAuditCreate(PetscInt nbodies, FCCrossingAudit *audit)
{
  FCCrossingAudit A;

  PetscFunctionBegin;
  PetscCall(PetscNew(&A));
  A->nbodies = nbodies;
  PetscCall(PetscCalloc4(nbodies, &A->ntri, nbodies, &A->tri, nbodies, &A->npts, nbodies, &A->pts));
  *audit = A;
  PetscFunctionReturn(0);
}

static PetscErrorCode AuditClear(FCCrossingAudit A)
{
  PetscFunctionBegin;
  for (PetscInt b = 0; b < A->nbodies; b++) {
    PetscCall(PetscFree(A->tri[b]));
    PetscCall(PetscFree(A->pts[b]));
    A->ntri[b] = A->npts[b] = 0;
  }
  PetscFunctionReturn(0);
}

PetscErrorCode FCCrossingAuditDestroy(FCCrossingAudit *audit)
{
  PetscFunctionBegin;
  if (!*audit) PetscFunctionReturn(0);
  PetscCall(AuditClear(*audit));
  PetscCall(PetscFree4((*audit)->ntri, (*audit)->tri, (*audit)->npts, (*audit)->pts));
  PetscCall(PetscFree(*audit));
  PetscFunctionReturn(0);
}

/* whether the features of body b (a surface's vertices and edges, a bounded shape's points) are audited against the
   surface of body o */
static PetscBool Audited(FCBody b, FCBody o)
{
  return FCBodyHasSurfaceTriangles(o) && (FCBodyHasSurfaceTriangles(b) || FCBodyHasBoundedShape(b)) ? PETSC_TRUE
                                                                                                    : PETSC_FALSE;
}

PetscErrorCode FCCrossingAuditStart(FCCrossingAudit A, MPI_Comm comm, FCBody bodies[], const FCContactPairs *pairs)
{
  PetscBool *take;

  PetscFunctionBegin;
  PetscCall(AuditClear(A));
  PetscCall(PetscCalloc1(A->nbodies, &take));
  for (PetscInt p = 0; p < pairs->n; p++)
    for (int s = 0; s < 2; s++) {
      PetscInt ib = pairs->body[p][s], io = pairs->body[p][1 - s];
      if (ib == io ? FCBodyHasSurfaceTriangles(bodies[ib])
                   : Audited(bodies[ib], bodies[io]) || Audited(bodies[io], bodies[ib]))
        take[ib] = PETSC_TRUE;
    }
  for (PetscInt b = 0; b < A->nbodies; b++) {
    if (!take[b]) continue;
    if (FCBodyHasSurfaceTriangles(bodies[b]))
      PetscCall(FCSurfaceGather(comm, bodies[b], &A->ntri[b], &A->tri[b]));
    else if (FCBodyHasBoundedShape(bodies[b])) {
      FCProximity *prox;
      PetscReal   *x0, *xf, *key;
      PetscCall(FCBodyGetContactPoints(bodies[b], &A->npts[b], &prox, &x0, &xf, &key));
      PetscCall(PetscMalloc1(3 * A->npts[b] + 1, &A->pts[b]));
      PetscCall(PetscArraycpy(A->pts[b], x0, 3 * A->npts[b]));
    }
  }
  PetscCall(PetscFree(take));
  PetscFunctionReturn(0);
}

/* One pair's crossings: a self pair's vertices against their own surface; between two bodies, each one's features
   against the other's surface */
static PetscErrorCode PairCrossings(MPI_Comm comm, FCBody bodies[], const FCContactPairs *pairs, PetscInt p,
                                    FCCrossingAudit A, PetscInt *count, PetscReal *deepest)
{
  PetscInt  ia = pairs->body[p][0], ib = pairs->body[p][1];
  FCBody    a = bodies[ia], b = bodies[ib];
  PetscReal depth = pairs->intersection_depth;
  Swept     wa, wb;

  PetscFunctionBegin;
  if (ia == ib) {
    if (!FCBodyHasSurfaceTriangles(a)) PetscFunctionReturn(0);
    PetscCall(SweptCreate(comm, a, ia, pairs, A, &wa));
    PetscCall(FCSelfRingCreate(wa.T, pairs->self_ring, &wa.ring));
    PetscCall(VerticesCross(comm, &wa, &wa, depth, count, deepest));
    PetscCall(SweptDestroy(pairs, &wa));
    PetscFunctionReturn(0);
  }
  if (!Audited(a, b) && !Audited(b, a)) PetscFunctionReturn(0);
  if (FCBodyHasSurfaceTriangles(a)) PetscCall(SweptCreate(comm, a, ia, pairs, A, &wa));
  if (FCBodyHasSurfaceTriangles(b)) PetscCall(SweptCreate(comm, b, ib, pairs, A, &wb));
  for (int s = 0; s < 2; s++) {
    FCBody   P = s ? b : a, B = s ? a : b;
    PetscInt iP = s ? ib : ia;
    Swept   *wP = s ? &wb : &wa, *wB = s ? &wa : &wb;
    if (!Audited(P, B)) continue;
    if (FCBodyHasSurfaceTriangles(P)) {
      PetscCall(VerticesCross(comm, wP, wB, depth, count, deepest));
      PetscCall(EdgesCross(comm, wP, wB, pairs->edge_angle, depth, count, deepest));
    } else {
      PetscCall(ShapePointsCross(P, iP, A, wB, depth, count, deepest));
    }
  }
  if (FCBodyHasSurfaceTriangles(a)) PetscCall(SweptDestroy(pairs, &wa));
  if (FCBodyHasSurfaceTriangles(b)) PetscCall(SweptDestroy(pairs, &wb));
  PetscFunctionReturn(0);
}

PetscErrorCode FCCrossingAuditCount(FCCrossingAudit A, MPI_Comm comm, FCBody bodies[], const FCContactPairs *pairs,
                                    PetscInt *count, PetscReal *deepest)
{
  PetscInt  local = 0;
  PetscReal deep  = 0.0;

  PetscFunctionBegin;
  for (PetscInt p = 0; p < pairs->n; p++) PetscCall(PairCrossings(comm, bodies, pairs, p, A, &local, &deep));
  PetscCall(MPIU_Allreduce(&local, count, 1, MPIU_INT, MPI_SUM, comm));
  PetscCall(MPIU_Allreduce(&deep, deepest, 1, MPIU_REAL, MPIU_MAX, comm));
  PetscFunctionReturn(0);
}
