/* -contact_shape_points (default on, called by FCCollisionDetect): the FE vertices see a bounded shape only at the
   vertices, so a shape smaller than the elements, a box's corner or a sphere's cap sinks into an FE face between them
   (the end-of-step check counts its points inside, intersection.c). Contacts of the shape with the FE surface
   between the vertices are then made too (rank 0), in one of two forms:
   - a rounded shape (sphere, capsule, and a cylinder's side; roundedsurface.c): the points of the FE surface
     nearest the shape's core (a point or a segment; a cylinder lying on the surface: the points under its lowest
     line), the FE material point there (barycentric weights, side 1) against the shape's signed distance (side 2):
     the kind of contact an FE vertex has, exact for the shape, so a ball, a capsule or a cylinder rolls over the
     surface as it rolls on a plane and not as the polyhedron of its picture (each facet an impact); taken after the
     free motion (-contact_rounded_surface exact), as are the FE vertices' own contacts with the shape then
     (collision.c). A shape that moves more than half its radius in a step, or a dynamic one whose free motion takes
     it deeper into the surface than the alarm distance (an impact) or that lies on a surface whose own free motion
     turns the shape's normal at its points (a soft membrane springing back from under a ball;
     FCCollisionRoundedSurfaceTurns), has a sphere's or capsule's picture points instead, each against the triangle
     it lands on (PicturePointOnSurface);
   - a shape with corners and edges (box, cylinder; ShapePointsOnSurface): the points
     of the shape's picture, fixed in the shape's frame, against their landing triangles, as a rigid mesh's
     vertices, dormant; a cylinder's rims not while its side lies on the surface (the ends of its lowest line hold
     the rims' lowest points: FCCollisionCylinderLies). (The shape's distance at the FE point is degenerate at a
     corner: the FE point above a box corner sunk into the face is on the box's edge, at distance 0.)
   The first kind is made only where the shape dips between the triangle's vertices: where its gap at the point is
   smaller than the gaps of the vertices interpolated there by more than -contact_intersection_depth (at the start
   of the step, for a point within the alarm distance); elsewhere the vertices' own contacts hold the point to
   within that depth. A point at an FE vertex is that vertex's own contact. Near the vertices' own contacts these
   rows are nearly redundant (W nearly singular, the forces not unique): results stay reproducible because the
   contacts are sorted by keys that do not depend on round-off (FCReferencePoint, edge points from the edge alone). */
#include "collisionimpl.h"

PetscErrorCode FCCollisionPictureLandings(FCBody Sh, Surface *S, const FCContactPairs *pairs, FCLandingFn fn, void *ctx)
{
  PetscInt     n, *cand = NULL, nmade = 0;
  FCRayGrid    grid = {{0}};
  FCProximity *prox;
  PetscReal   *x0, *xf, *key, *made = NULL, tau = FCCCDThreshold(pairs->distance);

  PetscFunctionBegin;
  PetscCall(FCBodyGetContactPoints(Sh, &n, &prox, &x0, &xf, &key));
  if (!n) PetscFunctionReturn(0);
  PetscCall(PetscMalloc2(S->n + 1, &cand, 3 * n, &made));
  for (PetscInt i = 0; i < n; i++) {
    PetscInt  best;
    PetscReal bw[3] = {0, 0, 0}, bcp[3] = {0, 0, 0}, X[3];
    PetscBool dup = PETSC_FALSE, mk = PETSC_FALSE;
    PetscCall(FCCollisionLandingTriangle(S, &x0[3 * i], &xf[3 * i], NULL, pairs->distance, pairs->continuous, tau, cand,
                                         &grid, &best, bw, bcp));
    if (best < 0 || bw[0] == 1.0 || bw[1] == 1.0 || bw[2] == 1.0) continue; /* none, or an FE vertex */
    FCReferencePoint(3, S->tri[best].X, bw, X); /* the key: free of the weights' round-off */
    for (PetscInt m = 0; m < nmade && !dup; m++)
      dup = made[3 * m] == X[0] && made[3 * m + 1] == X[1] && made[3 * m + 2] == X[2] ? PETSC_TRUE : PETSC_FALSE;
    if (dup) continue;
    PetscCall(fn(&S->tri[best], bw, bcp, X, ctx, &mk));
    if (!mk) continue;
    for (int k = 0; k < 3; k++) made[3 * nmade + k] = X[k];
    nmade++;
  }
  PetscCall(PetscFree2(cand, made));
  PetscCall(FCRayGridDestroy(&grid));
  PetscFunctionReturn(0);
}

PetscErrorCode FCCollisionSurfaceShapeContact(FCBody Sh, PetscInt ish, PetscInt ife, PetscInt pair,
                                              const FCContactPairs *pairs, PetscMPIInt rank, const FCProximity *tp,
                                              const PetscReal X[3], const PetscReal bcp[3], const PetscReal yf[3],
                                              const PetscReal n[3], const PetscReal r1[3], PetscReal gap0, FCContact *c)
{
  PetscFunctionBegin;
  PetscCall(PetscMemzero(c, sizeof(*c)));
  c->pair    = pair;
  c->body[0] = ife;
  c->body[1] = ish;
  c->prox[0] = *tp;
  for (int k = 0; k < 3; k++) {
    c->prox[0].r[k] = X[k];
    c->prox[1].r[k] = r1[k];
    c->key[k]       = X[k];
    c->n[k]         = n[k];
    c->p0[0][k]     = bcp[k];
    c->pfree[0][k]  = yf[k];
  }
  PetscCall(FCBodyProximityPosition(Sh, &c->prox[1], FC_AT_START, c->p0[1]));
  PetscCall(FCBodyProximityPosition(Sh, &c->prox[1], FC_AT_FREE, c->pfree[1]));
  c->side2 = FC_SIDE_SHAPE;
  c->gap0  = gap0;
  c->mu    = pairs->mu[pair];
  c->owner = rank;
  PetscFunctionReturn(0);
}

typedef struct {
  FCBody                Sh;
  PetscInt              ish, ife, pair;
  const FCContactPairs *pairs;
  PetscMPIInt           rank;
  FCContactSet         *set;
} PictureCtx;

/* A sphere or a capsule (-contact_rounded_surface picture; with exact, the default, one that moves more than half its
   radius in the step, an impact): the points of its picture, each against the FE triangle it lands on
   (FCCollisionLandingTriangle: continuous, so a fast shape's points find the surface they will reach), as the FE
   material point there against the shape's signed distance, where the shape dips between the triangle's vertices */
static PetscErrorCode PicturePointOnSurface(const FCSurfaceTriangle *T, const PetscReal bw[3], const PetscReal bcp[3],
                                            const PetscReal X[3], void *ctx, PetscBool *made)
{
  PictureCtx           *P     = (PictureCtx *)ctx;
  const FCContactPairs *pairs = P->pairs;
  PetscReal             yf[3], d, nrm[3], cpb[3], distance = pairs->distance;
  FCProximity           tp = {0};
  FCContact             c;

  PetscFunctionBegin;
  *made = PETSC_FALSE;
  FCCollisionTrianglePoint(T, bw, &tp, yf);
  PetscCall(FCBodyShapeDistance(P->Sh, FC_AT_NOW, bcp, &d, nrm, cpb));
  { /* needed only where the shape dips between the vertices: deeper than the gap the vertices'
       own constraints hold (interpolated) by more than the intersection depth */
    PetscReal interp = 0.0;
    for (int a = 0; a < 3; a++) {
      PetscReal da, na[3], ca[3];
      PetscCall(FCBodyShapeDistance(P->Sh, FC_AT_NOW, T->x0[a], &da, na, ca));
      interp += bw[a] * da;
    }
    /* (a point only the motion brings to the surface keeps its contact: its dip is not
       known at the start of the step) */
    if (d < distance && d >= interp - PetscMax(pairs->intersection_depth, PETSC_SMALL)) PetscFunctionReturn(0);
  }
  if (d >= distance) { /* the triangle point's own motion against the shape decides */
    PetscBool hit = PETSC_FALSE;
    if (pairs->continuous) PetscCall(FCCCDPointShape(P->Sh, bcp, yf, d, FCCCDThreshold(distance), &hit));
    if (!hit) PetscFunctionReturn(0);
  }
  *made = PETSC_TRUE;
  PetscCall(
      FCCollisionSurfaceShapeContact(P->Sh, P->ish, P->ife, P->pair, pairs, P->rank, &tp, X, bcp, yf, nrm, cpb, d, &c));
  PetscCall(FCContactSetAdd(P->set, &c));
  PetscFunctionReturn(0);
}

/* A box's point face to face with the FE surface it lands on: the box's face at the point (body frame r) whose inward
   normal is within FACE_ANGLE of the landing triangle's normal nb (body frame, pointing to the box), where that face
   touches the FE surface near the point (FaceTouches). The box's face is then the contact's surface, as it is for the
   FE vertices' own contacts against it: the triangle, bent a few degrees where the box's edge presses into it, would
   tilt the force of a sliding box off its face and Coulomb's sum over the face with it. A box on its edge or corner
   (the face off the surface: a box landing tilted) and a point pressed into a steeper slope keep the triangle's normal.
 */
#define FACE_ANGLE 10.0 /* degrees */
static PetscBool BoxFaceOf(FCBody Sh, const PetscReal r[3], const PetscReal nb[3], PetscReal m[3])
{
  PetscReal h[3], best = PetscCosReal(FACE_ANGLE * PETSC_PI / 180.0);
  PetscBool found = PETSC_FALSE;

  FCBodyGetBoxHalfExtents(Sh, h);
  for (int i = 0; i < 3; i++) {
    PetscReal s = r[i] > 0 ? -1.0 : 1.0; /* the face's inward normal, along which the FE surface lies beyond it */
    if (PetscAbsReal(r[i]) < h[i] * (1 - 1e-6) || s * nb[i] < best) continue;
    best  = s * nb[i];
    found = PETSC_TRUE;
    for (int d = 0; d < 3; d++) m[d] = d == i ? s : 0.0;
  }
  return found;
}

/* Whether the box's face with inward normal n (world) touches the FE surface S near contact c's point at the start of
   the step: an FE vertex within twice the landing triangle's longest edge of the point lies on the face, inside it
   (its nearest feature the face itself, not an edge) within the intersection depth. A box resting on its edge, tilted
   from the surface, has no such vertex unless the tilt is small enough that its face is within that depth of them.
   The triangles from S's hash (cand: work, S->n entries): the landing one is among those at its point p0[1] */
static PetscErrorCode FaceTouches(FCBody Sh, Surface *S, const FCContact *c, const PetscReal n[3],
                                  const FCContactPairs *pairs, PetscInt cand[], PetscBool *touches)
{
  PetscReal tol = PetscMax(pairs->intersection_depth, PETSC_SMALL), R2 = 0.0, lo[3], hi[3];
  PetscInt  nc;

  PetscFunctionBegin;
  *touches = PETSC_FALSE;
  FCSurfaceQueryBox(S, c->p0[1], c->p0[1], cand, &nc);
  for (PetscInt i = 0; i < nc && R2 == 0.0; i++) { /* the landing triangle: its size */
    const FCSurfaceTriangle *T = &S->tri[cand[i]];
    PetscBool                same;
    PetscCall(PetscArraycmp(&T->X[0][0], &c->prox[1].X[0][0], 9, &same));
    for (int a = 0; a < 3 && same; a++) {
      PetscReal l2 = 0.0;
      for (int d = 0; d < 3; d++) l2 += PetscSqr(T->x0[a][d] - T->x0[(a + 1) % 3][d]);
      R2 = PetscMax(R2, 4.0 * l2);
    }
  }
  for (int d = 0; d < 3; d++) {
    lo[d] = c->p0[0][d] - PetscSqrtReal(R2);
    hi[d] = c->p0[0][d] + PetscSqrtReal(R2);
  }
  FCSurfaceQueryBox(S, lo, hi, cand, &nc);
  for (PetscInt i = 0; i < nc && !*touches; i++)
    for (int a = 0; a < 3 && !*touches; a++) {
      const PetscReal *x = S->tri[cand[i]].x0[a];
      PetscReal        d, nrm[3], cp[3];
      if (PetscSqr(x[0] - c->p0[0][0]) + PetscSqr(x[1] - c->p0[0][1]) + PetscSqr(x[2] - c->p0[0][2]) > R2) continue;
      PetscCall(FCBodyShapeDistance(Sh, FC_AT_NOW, x, &d, nrm, cp));
      *touches = (PetscBool)(PetscAbsReal(d) <= tol && -FCDot(nrm, n) >= 1.0 - 1e-9);
    }
  PetscFunctionReturn(0);
}

/* The second form (a box, a cylinder): the picture points against the FE triangles as a rigid
   mesh's vertices (FCCollisionVerticesAgainstSurface), dormant (solver.c, SolveLazy): where the
   vertices' own contacts already hold the shape, a point's row is nearly a combination of theirs
   (W nearly singular, the forces not unique); the solver takes it up only where the solution
   leaves the point deeper inside than -contact_dormant_depth. A box's point face to face with the surface has the
   box's face's normal (BoxFaceOf, FaceTouches; c->face1, fixed in the box's frame: endgaps.c turns it with the box). */
static PetscErrorCode ShapePointsOnSurface(FCBody Sh, FCBody F, PetscInt ish, PetscInt ife, Surface *S, PetscInt pair,
                                           const FCContactPairs *pairs, PetscMPIInt rank, FCContactSet *set)
{
  PetscInt first = set->n, *cand = NULL;

  PetscFunctionBegin;
  PetscCall(FCCollisionVerticesAgainstSurface(Sh, F, ish, ife, S, 0, NULL, pair, pairs, rank, set));
  if (FCBodyIsBox(Sh) && set->n > first) PetscCall(PetscMalloc1(S->n + 1, &cand));
  for (PetscInt k = first; k < set->n; k++) {
    FCContact *c = &set->c[k];
    PetscReal  nb[3], m[3], n[3], diff[3];
    PetscBool  touches;
    c->dormant = PETSC_TRUE;
    if (!FCBodyIsBox(Sh)) continue;
    PetscCall(FCBodyToBodyFrame(Sh, FC_AT_NOW, c->n, PETSC_TRUE, nb));
    if (!BoxFaceOf(Sh, c->prox[0].r, nb, m)) continue;
    PetscCall(FCCollisionBodyDirection(Sh, FC_AT_NOW, m, n));
    PetscCall(FaceTouches(Sh, S, c, n, pairs, cand, &touches));
    if (!touches) continue;
    c->face1 = PETSC_TRUE;
    for (int d = 0; d < 3; d++) {
      c->nb[d] = m[d];
      c->n[d]  = n[d];
      diff[d]  = c->p0[0][d] - c->p0[1][d];
    }
    c->gap0 = FCDot(c->n, diff);
  }
  PetscCall(PetscFree(cand));
  PetscFunctionReturn(0);
}

/* Whether the core of rounded shape Sh moves less than half its radius over the step (rolling, sliding, resting),
   and, for a dynamic shape, the FE surface S's own free motion does not turn the shape's normal at its points
   (FCCollisionRoundedSurfaceTurns), or is kinematic (its pose at the end is given, not predicted): its surface points
   are then taken after the free motion (roundedsurface.c) */
static PetscErrorCode CoreFollows(FCBody Sh, Surface *S, const FCContactPairs *pairs, PetscBool *follows)
{
  PetscInt    ncore;
  PetscReal   core[2][3], r, move = 0.0;
  PetscBool   flat;
  FCProximity q = {0};

  PetscFunctionBegin;
  *follows = PETSC_FALSE;
  if (!pairs->rounded_exact || !FCBodyHasShapeCore(Sh)) PetscFunctionReturn(0);
  FCBodyGetShapeCore(Sh, &ncore, core, &r, &flat);
  for (PetscInt k = 0; k < ncore; k++) {
    PetscReal x0[3], xf[3];
    for (int i = 0; i < 3; i++) q.r[i] = core[k][i];
    PetscCall(FCBodyProximityPosition(Sh, &q, FC_AT_NOW, x0));
    PetscCall(FCBodyProximityPosition(Sh, &q, FC_AT_FREE, xf));
    move = PetscMax(move, PetscSqrtReal(PetscSqr(xf[0] - x0[0]) + PetscSqr(xf[1] - x0[1]) + PetscSqr(xf[2] - x0[2])));
  }
  *follows = (PetscBool)(FCBodyIsPrescribed(Sh) || move <= 0.5 * r);
  /* a dynamic shape: and the surface ends near where its free motion leaves it (roundedsurface.c; the fast scheme
     re-linearizes the normal against a kinematic shape at its given pose, not against a dynamic one) */
  if (*follows && !FCBodyIsPrescribed(Sh)) {
    PetscBool turns;
    PetscCall(FCCollisionRoundedSurfaceTurns(Sh, S, pairs, &turns));
    if (turns) *follows = PETSC_FALSE;
  }
  PetscFunctionReturn(0);
}

PetscErrorCode FCCollisionShapePoints(FCBody Sh, FCBody F, PetscInt ish, PetscInt ife, Surface *S, PetscBool follows,
                                      PetscBool lies, PetscInt pair, const FCContactPairs *pairs, PetscMPIInt rank,
                                      FCContactSet *set)
{
  PetscFunctionBegin;
  if (follows)
    PetscCall(FCCollisionRoundedOnSurface(Sh, ish, ife, S, pair, pairs, rank, set));
  else if (FCBodyHasSmoothShape(Sh)) {
    PictureCtx P = {Sh, ish, ife, pair, pairs, rank, set};
    PetscCall(FCCollisionPictureLandings(Sh, S, pairs, PicturePointOnSurface, &P));
  }
  if (!FCBodyHasSmoothShape(Sh) && !lies) PetscCall(ShapePointsOnSurface(Sh, F, ish, ife, S, pair, pairs, rank, set));
  PetscFunctionReturn(0);
}

PetscErrorCode FCCollisionRoundedFollows(FCBody Sh, Surface *S, const FCContactPairs *pairs, PetscBool *follows)
{
  PetscFunctionBegin;
  PetscCall(CoreFollows(Sh, S, pairs, follows));
  PetscFunctionReturn(0);
}
