/* Collision detection of a step (docs/method.md, section 2.2), run once the free motion is known.
   For each contact pair, the candidate points of one side (owned boundary vertices of an FE
   body, or the points of a rigid shape) are tested against the signed distance of the other
   side's analytic shape, or against its surface triangles; a point closer than -contact_distance
   at the start of the step makes a contact whose normal is the shape's outward normal at the
   closest point. The proximity point on the shape side is that closest point, fixed in the
   shape's body frame (so it moves rigidly with it within the step).
   With -contact_detection continuous (the default) a point farther than that whose motion over
   the step (start to free-motion end, against the other side's motion) reaches the other side
   also becomes a contact, a speculative one, with the same start-of-step normal and gap: the
   conservative tests are in ccd.c. A contact that stays open costs an inactive constraint; a
   point that would have crossed a thin body within one step is stopped at its surface. */
#include "collisionimpl.h"

/* Which side gives points (side 1) and which gives the shape (side 2): an FE body gives points;
   between two shape bodies, a rigid one with a bounded shape does */
static PetscErrorCode Sides(FCBody a, FCBody b, PetscInt ia, PetscInt ib, PetscInt *ipts, PetscInt *ishp)
{
  PetscBool afem = FCBodyIsDeformable(a), bfem = FCBodyIsDeformable(b);
  PetscBool arigid = !afem && !FCBodyIsPrescribed(a), brigid = !bfem && !FCBodyIsPrescribed(b);

  PetscFunctionBegin;
  PetscCheck(!(afem && bfem), PETSC_COMM_SELF, PETSC_ERR_SUP,
             "Contact between two FE bodies ('%s', '%s') is not implemented yet", FCBodyName(a), FCBodyName(b));
  *ipts = ia;
  *ishp = ib;
  if (bfem || (!afem && !(arigid && FCBodyHasBoundedShape(a)) && brigid && FCBodyHasBoundedShape(b))) {
    *ipts = ib;
    *ishp = ia;
  }
  PetscFunctionReturn(0);
}

/* ---- FE against FE: each owned boundary vertex of one body against the boundary triangles of
   the other (both ways). Triangles are gathered on every rank (a surface, not the volume) and
   bucketed in a sort-based spatial hash, so detection costs O(n log n) in the surface size. ---- */

/* The surface of a body, gathered on every rank; hashed by the triangles' boxes over the step
   with continuous detection (widened by the arc margin of a turning mesh, FCCCDArcMargin) */
PetscErrorCode FCCollisionSurfaceBuild(MPI_Comm comm, FCBody b, const FCContactPairs *pairs, Surface **S)
{
  PetscInt           n;
  FCSurfaceTriangle *all;
  PetscReal          arc;

  PetscFunctionBegin;
  PetscCall(FCSurfaceGather(comm, b, &n, &all));
  PetscCall(FCCCDArcMargin(b, n, all, &arc));
  if (pairs->continuous)
    PetscCall(FCSurfaceCreateSwept(n, all, pairs->distance + 2.0 * arc, S));
  else
    PetscCall(FCSurfaceCreate(n, all, pairs->distance, S));
  (*S)->arc = arc;
  PetscFunctionReturn(0);
}

/* Continuous: the triangle of S that vertex x0 -> xf comes closest to first (within tau) over the
   step, among those whose swept boxes its swept box overlaps and, with nv (the normal of the
   vertex's own surface), that face it at the start (FCSurfaceClosestFacing); -1 if none */
static void SweptVertexHit(Surface *S, const PetscReal x0[3], const PetscReal xf[3], const PetscReal nv[3],
                           PetscReal tau, PetscInt cand[], PetscInt *best)
{
  PetscReal lo[3], hi[3], tbest = PETSC_MAX_REAL;
  PetscInt  nc;

  *best = -1;
  for (int d = 0; d < 3; d++) {
    lo[d] = PetscMin(x0[d], xf[d]) - tau;
    hi[d] = PetscMax(x0[d], xf[d]) + tau;
  }
  FCSurfaceQueryBox(S, lo, hi, cand, &nc);
  for (PetscInt k = 0; k < nc; k++) {
    const FCSurfaceTriangle *T = &S->tri[cand[k]];
    PetscReal                t;
    if (nv && FCDot(&S->nrm[3 * cand[k]], nv) > -FC_FACING_COS) continue;
    if (S->self && FCCollisionSelfExcludes(S, cand[k], x0)) continue; /* after the cheaper test */
    if (FCCCDPointTriangle(x0, xf, T->x0, T->xf, tau, &t) && (t < tbest || (t == tbest && cand[k] < *best))) {
      tbest = t;
      *best = cand[k];
    }
  }
}

/* The nearest triangle of S to x, over all of them (a self pair: but those of the body's own shape,
   FCCollisionSelfExcludes): for the rare vertex that starts inside */
static void NearestTriangle(const Surface *S, const PetscReal x[3], PetscInt *best)
{
  PetscReal bestd = PETSC_MAX_REAL;
  *best           = -1;
  for (PetscInt t = 0; t < S->n; t++) {
    PetscReal cp[3], w[3], d2 = 0.0;
    if (S->self && FCCollisionSelfExcludes(S, t, x)) continue;
    FCClosestPointTriangle(x, S->tri[t].x0[0], S->tri[t].x0[1], S->tri[t].x0[2], cp, w);
    for (int d = 0; d < 3; d++) d2 += PetscSqr(x[d] - cp[d]);
    if (d2 < bestd) {
      bestd = d2;
      *best = t;
    }
  }
}

/* The triangle of S that a point moving x0 -> xf over the step lands on: the nearest at the start
   within the alarm distance (with nv, the normal of the point's own surface, the nearest among the
   triangles that face it: -contact_facing); else, with continuous detection, the first its motion reaches; else,
   for a point that starts inside the body deeper than the alarm distance, its nearest (the ray
   grid is built at the first such test); a self pair's vertex (on S itself), when it starts inside
   another part of its body (the winding number just outside it, along its normal nv: none without
   one), its nearest triangle but those of the body's own shape; -1 if none. w, cp: the barycentric
   weights and the point of that triangle closest to x0 at the start. */
PetscErrorCode FCCollisionLandingTriangle(Surface *S, const PetscReal x0[3], const PetscReal xf[3],
                                          const PetscReal nv[3], PetscReal distance, PetscBool continuous,
                                          PetscReal tau, PetscInt cand[], FCRayGrid *grid, PetscInt *best,
                                          PetscReal w[3], PetscReal cp[3])
{
  PetscReal d2;

  PetscFunctionBegin;
  FCSurfaceClosestFacing(S, x0, nv, best, w, cp, &d2);
  if (*best >= 0 && d2 <= distance * distance) PetscFunctionReturn(0);
  *best = -1; /* (the nearest farther than the alarm distance is no contact) */
  if (continuous) SweptVertexHit(S, x0, xf, nv, tau, cand, best);
  if (*best < 0) {
    if (S->self && (!nv || !S->selfstart)) PetscFunctionReturn(0);
    if (!grid->cells) PetscCall(FCRayGridCreate(S, grid));
    if (S->self ? !FCRayGridSelfInside(S, grid, x0, nv) : !FCRayGridInside(S, grid, x0)) PetscFunctionReturn(0);
    NearestTriangle(S, x0, best);
    if (*best < 0) PetscFunctionReturn(0);
  }
  FCClosestPointTriangle(x0, S->tri[*best].x0[0], S->tri[*best].x0[1], S->tri[*best].x0[2], cp, w);
  PetscFunctionReturn(0);
}

/* The FE material point at barycentric weights w of triangle T: its proximity map (eq. 6) and its
   free-motion position */
void FCCollisionTrianglePoint(const FCSurfaceTriangle *T, const PetscReal w[3], FCProximity *p, PetscReal xf[3])
{
  p->nv = 3;
  for (int a = 0; a < 3; a++) {
    p->gdof[a] = T->gdof[a];
    p->w[a]    = w[a];
    for (int d = 0; d < 3; d++) p->X[a][d] = T->X[a][d];
  }
  for (int d = 0; d < 3; d++) xf[d] = w[0] * T->xf[0][d] + w[1] * T->xf[1][d] + w[2] * T->xf[2][d];
}

/* Owned boundary vertices of body P (index ipts) against the surface S of body ishp: the nearest
   triangle within the alarm distance at the start of the step gives the contact; with continuous
   detection, a vertex that has none gets the first triangle its motion over the step reaches, as
   a speculative contact; a vertex that starts inside the other body, deeper than the alarm
   distance, gets its nearest triangle (the start-inside rule of FCCollisionDetect then bounds how
   fast it is pushed out). Either way the contact carries the triangle's outward normal at the
   start, the start-of-step gap along it and the barycentric weights of the closest point at the
   start as the proximity map (eq. 6). With vn (-contact_facing), a vertex lands only on triangles
   that face its own surface's normal there. */
PetscErrorCode FCCollisionVerticesAgainstSurface(FCBody P, FCBody Sb, PetscInt ipts, PetscInt ishp, Surface *S,
                                                 PetscInt nvn, const FCVertexNormal *vn, PetscInt pair,
                                                 const FCContactPairs *pairs, PetscMPIInt rank, FCContactSet *set)
{
  PetscInt     n, *cand = NULL;
  FCRayGrid    grid = {{0}};
  FCProximity *prox;
  PetscReal   *x0, *xf, *key, distance = pairs->distance, tau = FCCCDThreshold(distance), mu = pairs->mu[pair];

  PetscFunctionBegin;
  PetscCall(FCBodyGetContactPoints(P, &n, &prox, &x0, &xf, &key));
  if (pairs->continuous) PetscCall(PetscMalloc1(S->n + 1, &cand));
  tau += 2.0 * S->arc; /* the vertices of a turning mesh leave their chords: a wider threshold covers their arcs */
  for (PetscInt i = 0; i < n; i++) {
    PetscInt              best;
    PetscReal             bw[3] = {0, 0, 0}, bcp[3] = {0, 0, 0};
    const FCVertexNormal *own = NULL;
    if (vn && prox[i].nv == 1) {
      FCVertexNormal key1;
      for (int d = 0; d < 3; d++) key1.X[d] = prox[i].X[0][d];
      own = (const FCVertexNormal *)bsearch(&key1, vn, nvn, sizeof(FCVertexNormal), FCComparePoint);
    }
    if (S->self) FCCollisionSelfVertex(S, prox[i].X[0]);
    PetscCall(FCCollisionLandingTriangle(S, &x0[3 * i], &xf[3 * i], own ? own->n : NULL, distance, pairs->continuous,
                                         tau, cand, &grid, &best, bw, bcp));
    if (best < 0) continue;
    {
      const FCSurfaceTriangle *T = &S->tri[best];
      FCContact                c;
      PetscReal                nrm[3], diff[3];
      FCTriangleNormal(T->x0, nrm);
      for (int d = 0; d < 3; d++) diff[d] = x0[3 * i + d] - bcp[d];
      PetscCall(PetscMemzero(&c, sizeof(c)));
      c.pair    = pair;
      c.body[0] = ipts;
      c.body[1] = ishp;
      c.prox[0] = prox[i];
      FCCollisionTrianglePoint(T, bw, &c.prox[1], c.pfree[1]);
      for (int d = 0; d < 3; d++) {
        c.key[d]      = key[3 * i + d];
        c.n[d]        = nrm[d];
        c.p0[0][d]    = x0[3 * i + d];
        c.pfree[0][d] = xf[3 * i + d];
        c.p0[1][d]    = bcp[d];
      }
      if (!FCBodyIsDeformable(Sb)) { /* a rigid or kinematic mesh: the point is fixed in its body frame */
        c.side2      = FC_SIDE_RIGID_TRIANGLE;
        c.prox[1].nv = 0;
        PetscCall(FCBodyToBodyFrame(Sb, FC_AT_NOW, bcp, PETSC_FALSE, c.prox[1].r));
        PetscCall(FCBodyToBodyFrame(Sb, FC_AT_NOW, nrm, PETSC_TRUE, c.nb));
        PetscCall(FCBodyProximityPosition(Sb, &c.prox[1], FC_AT_FREE, c.pfree[1]));
      } else
        c.side2 = FC_SIDE_FE_TRIANGLE;
      c.gap0  = FCDot(nrm, diff);
      c.mu    = mu;
      c.owner = rank;
      PetscCall(FCContactSetAdd(set, &c));
    }
  }
  PetscCall(PetscFree(cand));
  PetscCall(FCRayGridDestroy(&grid));
  PetscFunctionReturn(0);
}

/* The second-pass contacts held by the first pass: in every FE-FE or FE-mesh pair detected both
   ways, a contact of the second pass (a vertex of the pair's second body against the first's
   surface) whose vertex has a barycentric weight > w in some first-pass contact (a vertex of the
   first body against a triangle of the second) is held by that first-pass contact, and the two
   constraints are nearly redundant (W ill-conditioned: PGS stalls, docs/hard-cases.md).
     -contact_fe_pass2_dormant w (the default, w = 0.01): the held contact is dormant: the contact
       solver keeps it out of its sweeps and wakes it only where the solution without it leaves
       its vertex deeper than -contact_dormant_depth inside (solver.c, SolveLazy);
     -contact_fe_pass2_drop w: the held contact is dropped (takes precedence).
   Vertices are matched by their reference position. Runs on the gathered set, the same on every
   rank, so it keeps the order. */
/* A shape's smallest size: a rounded shape's radius, a box's smallest half extent (a plane, a mesh: none) */
static PetscReal ShapeSize(FCBody b)
{
  if (FCBodyHasShapeCore(b)) {
    PetscInt  ncore;
    PetscReal core[2][3], r;
    PetscBool flat;
    FCBodyGetShapeCore(b, &ncore, core, &r, &flat);
    return r;
  }
  if (FCBodyIsBox(b)) {
    PetscReal h[3];
    FCBodyGetBoxHalfExtents(b, h);
    return PetscMin(h[0], PetscMin(h[1], h[2]));
  }
  return PETSC_MAX_REAL;
}

static PetscErrorCode HeldSecondPass(const FCContactPairs *pairs, FCContactSet *set)
{
  PetscReal *held, w = pairs->pass2_drop >= 0.0 ? pairs->pass2_drop : pairs->pass2_dormant;
  PetscBool  drop_held = pairs->pass2_drop >= 0.0 ? PETSC_TRUE : PETSC_FALSE;
  PetscInt   nheld = 0, kept = 0;

  PetscFunctionBegin;
  PetscCall(PetscMalloc1(9 * set->n + 3, &held));
  for (PetscInt k = 0; k < set->n; k++) {
    const FCContact *c = &set->c[k];
    if (c->side2 != FC_SIDE_FE_TRIANGLE || c->body[0] != pairs->body[c->pair][0] || c->body[0] == c->body[1])
      continue; /* (a self-contact pair has one pass) */
    for (int a = 0; a < 3; a++)
      if (c->prox[1].w[a] > w) {
        for (int d = 0; d < 3; d++) held[3 * nheld + d] = c->prox[1].X[a][d];
        nheld++;
      }
  }
  if (nheld > 1) qsort(held, nheld, 3 * sizeof(PetscReal), FCComparePoint);
  for (PetscInt k = 0; k < set->n; k++) {
    const FCContact *c      = &set->c[k];
    PetscBool        isheld = PETSC_FALSE;
    if (c->side2 == FC_SIDE_FE_TRIANGLE && c->body[0] == pairs->body[c->pair][1] && c->body[0] != c->body[1] &&
        c->prox[0].nv == 1 && nheld)
      isheld = bsearch(c->prox[0].X[0], held, nheld, 3 * sizeof(PetscReal), FCComparePoint) ? PETSC_TRUE : PETSC_FALSE;
    if (isheld && drop_held) continue;
    set->c[k].dormant = set->c[k].dormant || isheld; /* (a shape's points made dormant stay so) */
    set->c[kept++]    = set->c[k];
  }
  set->n = kept;
  PetscCall(PetscFree(held));
  PetscFunctionReturn(0);
}

/* Two meshed bodies (FE, mesh shapes): the vertices of each against the other's surface, or with
   -contact_fe_passes 1 only the first body's vertices against the second's surface; then the sharp edges
   of the FE body against the other's (the first body's if both are FE) */
static PetscErrorCode MeshedPair(MPI_Comm comm, FCBody bodies[], PetscInt p, const FCContactPairs *pairs,
                                 PetscMPIInt rank, FCContactSet *set)
{
  Surface           *Sf[2]  = {NULL, NULL};
  FCVertexNormal    *vn[2]  = {NULL, NULL};
  PetscInt           nvn[2] = {0, 0}, ntri0 = 0;
  FCSurfaceTriangle *tri0 = NULL; /* one pass: the first body's triangles, gathered for its normals or edges */
  FCSurfaceTopology *T;
  PetscInt           ea = 0; /* the sharp edges: the FE body's against the other's (the first body's if both are FE) */

  PetscFunctionBegin;
  if (pairs->body[p][0] == pairs->body[p][1]) { /* self-contact: vertices, then sharp edges */
    PetscCall(FCCollisionSelfPair(comm, bodies[pairs->body[p][0]], pairs->body[p][0], p, pairs, rank, set));
    PetscFunctionReturn(0);
  }
  if (!FCBodyIsDeformable(bodies[pairs->body[p][0]])) ea = 1;
  for (int side = 0; side < 2; side++) {
    FCBody b = bodies[pairs->body[p][side]];
    if (side == 1 || pairs->passes == 2) { /* a surface some vertex lands on */
      PetscCall(FCCollisionSurfaceBuild(comm, b, pairs, &Sf[side]));
      if (pairs->facing && FCBodyIsDeformable(b)) {
        PetscCall(FCSurfaceTopologyGet(pairs, pairs->body[p][side], Sf[side]->n, Sf[side]->tri, &T));
        PetscCall(FCCollisionVertexNormals(T, Sf[side]->tri, &nvn[side], &vn[side]));
        PetscCall(FCSurfaceTopologyRestore(pairs, &T));
      }
    } else if ((pairs->facing && FCBodyIsDeformable(b)) || pairs->edges) { /* one pass: its normals, its edges */
      PetscCall(FCSurfaceGather(comm, b, &ntri0, &tri0));
      if (pairs->facing && FCBodyIsDeformable(b)) {
        PetscCall(FCSurfaceTopologyGet(pairs, pairs->body[p][side], ntri0, tri0, &T));
        PetscCall(FCCollisionVertexNormals(T, tri0, &nvn[side], &vn[side]));
        PetscCall(FCSurfaceTopologyRestore(pairs, &T));
      }
    }
  }
  for (int side = 0; side < pairs->passes; side++) {
    PetscInt a = pairs->body[p][side], b2 = pairs->body[p][1 - side];
    PetscCall(FCCollisionVerticesAgainstSurface(bodies[a], bodies[b2], a, b2, Sf[1 - side], nvn[side], vn[side], p,
                                                pairs, rank, set));
  }
  if (pairs->edges && FCBodyIsDeformable(bodies[pairs->body[p][ea]])) {
    PetscInt                 n[2];
    const FCSurfaceTriangle *t[2];
    for (int side = 0; side < 2; side++) {
      n[side] = Sf[side] ? Sf[side]->n : ntri0;
      t[side] = Sf[side] ? Sf[side]->tri : tri0;
    }
    PetscCall(FCCollisionEdgeEdge(comm, bodies[pairs->body[p][ea]], bodies[pairs->body[p][1 - ea]], pairs->body[p][ea],
                                  pairs->body[p][1 - ea], n[ea], t[ea], n[1 - ea], t[1 - ea], p, pairs, set));
  }
  for (int side = 0; side < 2; side++) {
    if (Sf[side]) PetscCall(FCSurfaceDestroy(&Sf[side]));
    PetscCall(PetscFree(vn[side]));
  }
  PetscCall(PetscFree(tri0));
  PetscFunctionReturn(0);
}

/* Two analytic shapes: a rounded one (sphere, capsule, cylinder) from the closest points of its core
   (smooth.c), exact where one is smooth; two boxes face to face by their separating axis (boxbox.c);
   otherwise the points of a box (its corners) against the other's distance; a box and a cylinder, or two
   cylinders, both ways */
static PetscErrorCode ShapePair(FCBody P, FCBody S, PetscInt ipts, PetscInt ishp, PetscInt p,
                                const FCContactPairs *pairs, PetscMPIInt rank, FCContactSet *set)
{
  PetscFunctionBegin;
  if (FCBodyHasSmoothShape(P))
    PetscCall(FCCollisionRoundedShape(P, S, ipts, ishp, p, pairs, rank, set));
  else if (FCBodyHasSmoothShape(S))
    PetscCall(FCCollisionRoundedShape(S, P, ishp, ipts, p, pairs, rank, set));
  else {
    PetscBool done = PETSC_FALSE;
    if (FCBodyIsBox(P) && FCBodyIsBox(S)) PetscCall(FCCollisionBoxBox(P, S, ipts, ishp, p, pairs, rank, set, &done));
    if (done) PetscFunctionReturn(0);
    if (FCBodyHasShapeCore(P))
      PetscCall(FCCollisionRoundedShape(P, S, ipts, ishp, p, pairs, rank, set));
    else
      PetscCall(FCCollisionPointsAgainstShape(P, S, ipts, ishp, p, 0, NULL, PETSC_FALSE, pairs, rank, set));
    if (FCBodyHasShapeCore(S)) PetscCall(FCCollisionRoundedShape(S, P, ishp, ipts, p, pairs, rank, set));
  }
  PetscFunctionReturn(0);
}

/* An FE body's vertices against a shape; against a bounded shape, with -contact_facing, only where the
   shape faces their surface, and with -contact_shape_points the shape's picture points against the FE
   surface (shapepoints.c) */
static PetscErrorCode SurfaceShapePair(MPI_Comm comm, FCBody P, FCBody S, PetscInt ipts, PetscInt ishp, PetscInt p,
                                       const FCContactPairs *pairs, PetscMPIInt rank, FCContactSet *set)
{
  Surface        *Sf     = NULL;
  FCVertexNormal *vn     = NULL;
  PetscInt        nvn    = 0;
  PetscBool       atfree = PETSC_FALSE, lies = PETSC_FALSE;

  PetscFunctionBegin;
  if (FCBodyIsDeformable(P) && FCBodyHasBoundedShape(S) && !FCBodyHasSurfaceTriangles(S) &&
      (pairs->shape_points || pairs->facing)) {
    PetscCall(FCCollisionSurfaceBuild(comm, P, pairs, &Sf));
    if (pairs->facing) {
      FCSurfaceTopology *T;
      PetscCall(FCSurfaceTopologyGet(pairs, ipts, Sf->n, Sf->tri, &T));
      PetscCall(FCCollisionVertexNormals(T, Sf->tri, &nvn, &vn));
      PetscCall(FCSurfaceTopologyRestore(pairs, &T));
    }
  }
  if (Sf && pairs->shape_points) PetscCall(FCCollisionRoundedFollows(S, Sf, pairs, &atfree));
  if (atfree && !FCBodyHasSmoothShape(S)) PetscCall(FCCollisionCylinderLies(S, Sf, pairs, &lies));
  PetscCall(FCCollisionPointsAgainstShape(P, S, ipts, ishp, p, nvn, vn, atfree, pairs, rank, set));
  if (Sf && pairs->shape_points)
    PetscCall(FCCollisionShapePoints(S, P, ishp, ipts, Sf, atfree, lies, p, pairs, rank, set));
  if (Sf) PetscCall(FCSurfaceDestroy(&Sf));
  PetscCall(PetscFree(vn));
  PetscFunctionReturn(0);
}

PetscErrorCode FCCollisionDetectPairs(MPI_Comm comm, PetscInt nbodies, FCBody bodies[], const FCContactPairs *pairs,
                                      FCContactSet *set)
{
  PetscMPIInt rank;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCall(FCContactSetReset(set));
  for (PetscInt p = 0; p < pairs->n; p++) {
    PetscInt ipts = 0, ishp = 0;
    FCBody   P, S;

    if (FCBodyHasSurfaceTriangles(bodies[pairs->body[p][0]]) && FCBodyHasSurfaceTriangles(bodies[pairs->body[p][1]])) {
      PetscCall(MeshedPair(comm, bodies, p, pairs, rank, set));
      continue;
    }
    PetscCall(Sides(bodies[pairs->body[p][0]], bodies[pairs->body[p][1]], pairs->body[p][0], pairs->body[p][1], &ipts,
                    &ishp));
    P = bodies[ipts];
    S = bodies[ishp];
    PetscCheck(FCBodyHasShape(S), comm, PETSC_ERR_SUP, "Contact between '%s' and '%s' is not implemented yet",
               FCBodyName(P), FCBodyName(S));
    if (!FCBodyIsDeformable(P) && !FCBodyHasSurfaceTriangles(P) && !FCBodyHasSurfaceTriangles(S))
      PetscCall(ShapePair(P, S, ipts, ishp, p, pairs, rank, set));
    else
      PetscCall(SurfaceShapePair(comm, P, S, ipts, ishp, p, pairs, rank, set));
  }
  PetscCall(FCContactSetGather(set, comm));
  { /* a contact that neither side can move (constrained FE vertices, -<body>_fixed or -displacement,
       against a kinematic body or other constrained vertices) is left out: the prescribed motions
       win, and no force could act there (docs/scenes.md) */
    PetscInt n = 0;
    for (PetscInt k = 0; k < set->n; k++) {
      PetscBool frozen = PETSC_TRUE;
      for (int s = 0; s < 2; s++) {
        const FCProximity *p = &set->c[k].prox[s];
        if (!p->nv && !FCBodyIsPrescribed(bodies[set->c[k].body[s]])) frozen = PETSC_FALSE;
        for (PetscInt v = 0; v < p->nv; v++)
          if (p->gdof[v] >= 0) frozen = PETSC_FALSE;
      }
      if (!frozen) set->c[n++] = set->c[k];
    }
    set->n = n;
  }
  set->dormant_depth = pairs->dormant_depth;
  if (pairs->passes == 2 && (pairs->pass2_drop >= 0.0 || pairs->pass2_dormant >= 0.0))
    PetscCall(HeldSecondPass(pairs, set));
  if (pairs->pass2_dormant >= 0.0) PetscCall(FCCollisionSelfHeld(pairs->pass2_dormant, set));
  /* The start-inside rule: a contact that starts d deep is not asked to close in one step (an
     impulse of d / h, the energy burst of bodies placed inside each other) but by at most
     -contact_separation_speed v per step: the step may leave max(0, d - v h) of it (q_n += slack,
     src/scheme/recursive.c). An ordinary contact (d < v h) is unchanged. */
  for (PetscInt k = 0; k < set->n; k++) {
    FCContact *c = &set->c[k];
    c->slack     = PetscMax(0.0, -c->gap0 - pairs->separation_speed * FCBodyTimeStep(bodies[c->body[0]]));
    { /* made from beyond the alarm distance against a shape that travels more than half its size over the
         step: the sides meet within the step, and the shape may pass the point (src/scheme/recursive.c) */
      PetscReal move = 0.0;
      for (int d = 0; d < 3; d++) move += PetscSqr(c->pfree[1][d] - c->p0[1][d]);
      c->swept = (PetscBool)(c->side2 == FC_SIDE_SHAPE && c->gap0 > pairs->distance &&
                             PetscSqrtReal(move) > 0.5 * ShapeSize(bodies[c->body[1]]));
    }
  }
  PetscCall(FCContactSetFinalize(set));
  PetscFunctionReturn(0);
}
