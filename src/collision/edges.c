/* Edge-edge contacts between two bodies with surface triangles (FE-FE, FE-mesh): two edges that
   cross each other where neither body has a vertex (crossed bars) are invisible to the
   vertex-triangle detection. The candidates are the sharp edges of each surface (adjacent
   triangles' normals more than -contact_edge_angle apart, 30 degrees by default: the edges of a flat
   face triangulation mostly repeat what its vertices and triangles already constrain; 0: every edge, where two
   flat faces of non-matching meshes pressed together cross each other between their vertices); a pair is a contact when
   its closest points are inside both edges, the edges are not (nearly) parallel, and they come within the alarm
   distance at the start of the step, or, with continuous detection, over the step (ccd.c). Each edge of the first body
   keeps its nearest (or first reached) edge of the other. The contact has two barycentric weights per side (prox nv =
   2, eq. 6), so every compliance builder and the fast scheme's H take it as they take a vertex-triangle contact; its
   normal is the cross product of the two edges at the start, pointing out of the second body. Against a rigid mesh the
   second side is a point and a normal fixed in the mesh's frame (FC_SIDE_RIGID_TRIANGLE). */
#include "collisionimpl.h"

#define FC_PARALLEL_DEG 10.0  /* edges closer than this to parallel: left to the vertex contacts */
#define FC_EDGE_INTERIOR 0.02 /* closest points within this fraction of an end: a vertex contact's */

typedef struct {
  PetscInt  gdof[2];
  PetscReal X[2][3], x0[2][3], xf[2][3], nout[3]; /* nout: sum of the two adjacent outward normals */
  PetscReal nref[3];                              /* the same in the reference configuration */
} Edge;

/* The sharp edges of a closed surface: its interior edges (topology.c, in their order) whose two
   triangles' normals at the start of the step turn more than angle (degrees; 0: all of them) */
static PetscErrorCode SharpEdges(const FCSurfaceTopology *T, const FCSurfaceTriangle *tri, PetscReal angle,
                                 PetscInt *ne, Edge **edges)
{
  PetscReal cmax = PetscCosReal(angle * PETSC_PI / 180.0), *nrm;
  PetscInt  n    = 0;

  PetscFunctionBegin;
  PetscCall(PetscMalloc1(T->ne + 1, edges));
  PetscCall(PetscMalloc1(3 * T->ntri + 1, &nrm));
  for (PetscInt t = 0; t < T->ntri; t++) FCTriangleNormal(tri[t].x0, &nrm[3 * t]);
  for (PetscInt k = 0; k < T->ne; k++) {
    PetscInt                 t1 = T->edge[k][0] / 3, a1 = T->edge[k][0] % 3, t2 = T->edge[k][1] / 3;
    PetscReal               *n1 = &nrm[3 * t1], *n2 = &nrm[3 * t2], r1[3], r2[3];
    const FCSurfaceTriangle *Tr = &tri[t1];
    Edge                    *E  = &(*edges)[n];
    if (angle > 0.0 && FCDot(n1, n2) > cmax) continue;
    for (int j = 0; j < 2; j++) {
      int v      = (a1 + j) % 3;
      E->gdof[j] = Tr->gdof[v];
      for (int i = 0; i < 3; i++) {
        E->X[j][i]  = Tr->X[v][i];
        E->x0[j][i] = Tr->x0[v][i];
        E->xf[j][i] = Tr->xf[v][i];
      }
    }
    FCTriangleNormal(tri[t1].X, r1);
    FCTriangleNormal(tri[t2].X, r2);
    for (int i = 0; i < 3; i++) {
      E->nout[i] = n1[i] + n2[i];
      E->nref[i] = r1[i] + r2[i];
    }
    n++;
  }
  PetscCall(PetscFree(nrm));
  *ne = n;
  PetscFunctionReturn(0);
}

/* The edges of B as degenerate triangles (a, b, b) for the spatial hash: their boxes over the step
   (continuous) or at the start (discrete: xf taken as x0) */
static PetscErrorCode EdgeHash(PetscInt ne, const Edge *E, PetscBool continuous, PetscReal inflate, FCSurface **S)
{
  FCSurfaceTriangle *t;

  PetscFunctionBegin;
  PetscCall(PetscCalloc1(ne + 1, &t));
  for (PetscInt k = 0; k < ne; k++)
    for (int a = 0; a < 3; a++)
      for (int i = 0; i < 3; i++) {
        t[k].x0[a][i] = E[k].x0[PetscMin(a, 1)][i];
        t[k].xf[a][i] = continuous ? E[k].xf[PetscMin(a, 1)][i] : t[k].x0[a][i];
      }
  PetscCall(FCSurfaceCreateSwept(ne, t, inflate, S));
  PetscFunctionReturn(0);
}

/* The contact of edge a (body ia, FE) with edge b (body ib) at parameters s, t, normal n */
static PetscErrorCode AddEdgeContact(FCBody Bb, PetscInt ia, PetscInt ib, const Edge *a, const Edge *b, PetscReal s,
                                     PetscReal t, const PetscReal n[3], PetscInt pair, PetscReal mu, PetscMPIInt rank,
                                     FCContactSet *set)
{
  FCContact c;
  PetscReal ws[2] = {1 - s, s}, wt[2] = {1 - t, t}, d[3];

  PetscFunctionBegin;
  PetscCall(PetscMemzero(&c, sizeof(c)));
  c.pair       = pair;
  c.body[0]    = ia;
  c.body[1]    = ib;
  c.prox[0].nv = 2;
  c.prox[1].nv = 2;
  for (int j = 0; j < 2; j++) {
    c.prox[0].gdof[j] = a->gdof[j];
    c.prox[1].gdof[j] = b->gdof[j];
    c.prox[0].w[j]    = ws[j];
    c.prox[1].w[j]    = wt[j];
    for (int i = 0; i < 3; i++) {
      c.prox[0].X[j][i] = a->X[j][i];
      c.prox[1].X[j][i] = b->X[j][i];
    }
  }
  FCReferencePoint(2, a->X, ws, c.key); /* the key: free of the weights' round-off */
  for (int i = 0; i < 3; i++) {
    c.n[i]        = n[i];
    c.p0[0][i]    = ws[0] * a->x0[0][i] + ws[1] * a->x0[1][i];
    c.pfree[0][i] = ws[0] * a->xf[0][i] + ws[1] * a->xf[1][i];
    c.p0[1][i]    = wt[0] * b->x0[0][i] + wt[1] * b->x0[1][i];
    c.pfree[1][i] = wt[0] * b->xf[0][i] + wt[1] * b->xf[1][i];
    d[i]          = c.p0[0][i] - c.p0[1][i];
  }
  c.side2 = FC_SIDE_FE_EDGE;
  if (!FCBodyIsDeformable(Bb)) { /* a rigid or kinematic mesh: point and normal fixed in its frame */
    c.side2      = FC_SIDE_RIGID_TRIANGLE;
    c.prox[1].nv = 0;
    PetscCall(FCBodyToBodyFrame(Bb, FC_AT_NOW, c.p0[1], PETSC_FALSE, c.prox[1].r));
    PetscCall(FCBodyToBodyFrame(Bb, FC_AT_NOW, n, PETSC_TRUE, c.nb));
    PetscCall(FCBodyProximityPosition(Bb, &c.prox[1], FC_AT_FREE, c.pfree[1]));
  }
  c.gap0  = FCDot(n, d);
  c.mu    = mu;
  c.owner = rank;
  PetscCall(FCContactSetAdd(set, &c));
  PetscFunctionReturn(0);
}

/* The unit normal of a pair of crossing edges, out of b (side 2) and into a; PETSC_FALSE when the
   edges are nearly parallel or do not face each other (a's outward side away from b's) */
static PetscBool EdgeNormal(const Edge *a, const Edge *b, PetscReal n[3])
{
  PetscReal ea[3], eb[3], la, lb, ln, smin = PetscSinReal(FC_PARALLEL_DEG * PETSC_PI / 180.0);
  for (int i = 0; i < 3; i++) {
    ea[i] = a->x0[1][i] - a->x0[0][i];
    eb[i] = b->x0[1][i] - b->x0[0][i];
  }
  FCCross(ea, eb, n);
  la = PetscSqrtReal(FCDot(ea, ea));
  lb = PetscSqrtReal(FCDot(eb, eb));
  ln = PetscSqrtReal(FCDot(n, n));
  if (!(ln > smin * la * lb)) return PETSC_FALSE;
  for (int i = 0; i < 3; i++) n[i] /= ln;
  if (FCDot(n, b->nout) < 0)
    for (int i = 0; i < 3; i++) n[i] = -n[i];
  return FCDot(n, b->nout) > 0 && FCDot(n, a->nout) < 0 ? PETSC_TRUE : PETSC_FALSE;
}

/* A self pair's edge b at t is edge a's own shape at s: a vertex of b on a triangle of the ring of
   either end of a (selfcontact.c), or a behind b in the reference configuration (the other side of
   the body's own thickness; a fold that has crossed was in front there) */
static PetscBool SelfExcluded(FCSelfRing *R, const Edge *a, const Edge *b, PetscReal s, PetscReal t)
{
  PetscReal d = 0.0;
  if (FCSelfRingEdgeIn(R, a->X, b->X)) return PETSC_TRUE;
  for (int i = 0; i < 3; i++)
    d += ((1 - s) * a->X[0][i] + s * a->X[1][i] - (1 - t) * b->X[0][i] - t * b->X[1][i]) * b->nref[i];
  return d < 0.0 ? PETSC_TRUE : PETSC_FALSE;
}

/* A against B; A == B (a self pair): each crossing once, found from its edge of lower index, the
   edges of the body's own shape left out (SelfExcluded) */
PetscErrorCode FCCollisionEdgeEdge(MPI_Comm comm, FCBody A, FCBody B, PetscInt ia, PetscInt ib, PetscInt nta,
                                   const FCSurfaceTriangle *ta, PetscInt ntb, const FCSurfaceTriangle *tb,
                                   PetscInt pair, const FCContactPairs *pairs, FCContactSet *set)
{
  PetscInt           nea, neb, *cand;
  FCSurfaceTopology *Ta, *Tb;
  Edge              *ea, *eb;
  FCSurface         *S;
  FCSelfRing        *R = NULL; /* a self pair's ring */
  PetscMPIInt        rank, size;
  PetscBool          self = A == B ? PETSC_TRUE : PETSC_FALSE;
  PetscReal          dist = pairs->distance, tau = FCCCDThreshold(dist), lo = FC_EDGE_INTERIOR, hi = 1 - lo;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCallMPI(MPI_Comm_size(comm, &size));
  PetscCall(FCSurfaceTopologyGet(pairs, ia, nta, ta, &Ta));
  PetscCall(SharpEdges(Ta, ta, pairs->edge_angle, &nea, &ea));
  neb = nea, eb = ea, Tb = Ta;
  if (!self) {
    PetscCall(FCSurfaceTopologyGet(pairs, ib, ntb, tb, &Tb));
    PetscCall(SharpEdges(Tb, tb, pairs->edge_angle, &neb, &eb));
  }
  if (self) PetscCall(FCSelfRingCreate(Ta, pairs->self_ring, &R));
  { /* B a turning mesh: its edges' ends leave their chords (FCCCDArcMargin) */
    PetscReal arc;
    PetscCall(FCCCDArcMargin(B, ntb, tb, &arc));
    tau += 2.0 * arc;
  }
  PetscCall(EdgeHash(neb, eb, pairs->continuous, PetscMax(dist, tau), &S));
  PetscCall(PetscMalloc1(neb + 1, &cand));
  for (PetscInt k = rank; k < nea; k += size) { /* the edges are on every rank: each takes its share */
    const Edge *a = &ea[k];
    PetscReal   blo[3], bhi[3], best = PETSC_MAX_REAL, bs = 0, bt = 0, bn[3] = {0, 0, 0};
    PetscInt    nc, bj = -1;
    for (int i = 0; i < 3; i++) {
      blo[i] = PetscMin(a->x0[0][i], a->x0[1][i]);
      bhi[i] = PetscMax(a->x0[0][i], a->x0[1][i]);
      if (pairs->continuous) {
        blo[i] = PetscMin(blo[i], PetscMin(a->xf[0][i], a->xf[1][i]));
        bhi[i] = PetscMax(bhi[i], PetscMax(a->xf[0][i], a->xf[1][i]));
      }
      blo[i] -= tau;
      bhi[i] += tau;
    }
    FCSurfaceQueryBox(S, blo, bhi, cand, &nc);
    for (PetscInt m = 0; m < nc; m++) {
      const Edge *b = &eb[cand[m]];
      PetscReal   s, t, d2, n[3], th, rank_key;
      d2 = FCClosestSegmentSegment(a->x0[0], a->x0[1], b->x0[0], b->x0[1], &s, &t);
      if (d2 <= dist * dist)
        rank_key = d2; /* discrete: the nearest edge */
      else if (pairs->continuous && FCCCDEdgeEdge(&a->x0[0][0], &a->xf[0][0], &b->x0[0][0], &b->xf[0][0], tau, &th))
        rank_key = dist * dist + th;
      else
        continue; /* (continuous: the first edge reached, after every edge within the distance) */
      if (s <= lo || s >= hi || t <= lo || t >= hi || !EdgeNormal(a, b, n) || rank_key >= best) continue;
      if (self && (cand[m] <= k || SelfExcluded(R, a, b, s, t))) continue;
      best = rank_key;
      bj   = cand[m];
      bs   = s;
      bt   = t;
      for (int i = 0; i < 3; i++) bn[i] = n[i];
    }
    if (bj >= 0) PetscCall(AddEdgeContact(B, ia, ib, a, &eb[bj], bs, bt, bn, pair, pairs->mu[pair], rank, set));
  }
  PetscCall(PetscFree(cand));
  PetscCall(FCSurfaceDestroy(&S));
  PetscCall(FCSelfRingDestroy(&R));
  if (!self) {
    PetscCall(FCSurfaceTopologyRestore(pairs, &Tb));
    PetscCall(PetscFree(eb));
  }
  PetscCall(FCSurfaceTopologyRestore(pairs, &Ta));
  PetscCall(PetscFree(ea));
  PetscFunctionReturn(0);
}

PetscErrorCode FCSurfaceSharpEdgeEnds(const FCSurfaceTopology *T, const FCSurfaceTriangle *tri, PetscReal angle,
                                      PetscBool full, PetscInt *ne, PetscReal **ends)
{
  Edge    *E;
  PetscInt m = full ? 15 : 6;

  PetscFunctionBegin;
  PetscCall(SharpEdges(T, tri, angle, ne, &E));
  PetscCall(PetscMalloc1(m * (*ne) + 1, ends));
  for (PetscInt k = 0; k < *ne; k++) {
    PetscReal *e = &(*ends)[m * k];
    for (int j = 0; j < 2; j++)
      for (int i = 0; i < 3; i++) {
        e[3 * j + i] = E[k].x0[j][i];
        if (full) e[6 + 3 * j + i] = E[k].X[j][i];
      }
    if (full)
      for (int i = 0; i < 3; i++) e[12 + i] = E[k].nout[i];
  }
  PetscCall(PetscFree(E));
  PetscFunctionReturn(0);
}
