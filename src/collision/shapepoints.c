/* -contact_shape_points (default on, called by FCCollisionDetect): the FE vertices see a bounded shape only at the
   vertices, so a shape smaller than the elements, a box's corner or a sphere's cap sinks into an FE face between them
   (the end-of-step check counts its points inside, intersection.c). The points of the shape's picture (rank 0) are then
   contacts too, in one of two forms:
   - a smooth shape (sphere, capsule; SmoothShapeOnSurface): each picture point finds its triangle
     of the FE surface as a vertex does (FCCollisionLandingTriangle), and the contact is the FE material point
     there (barycentric weights, side 1) against the shape's signed distance (side 2): the kind of
     contact an FE vertex has, so the schemes re-linearize it with the shape's closest point, which
     follows a turning or rolling shape (the fingers of the grasp slide 5 cm a step over the cube:
     a point fixed in the shape's frame would leave its triangle);
   - a shape with corners and edges (box, cylinder; ShapePointsOnSurface): the picture point,
     fixed in the shape's frame, against its landing triangle, as a rigid mesh's vertex. (The
     shape's distance at the FE point is degenerate at a corner: the FE point above a box corner
     sunk into the face is on the box's edge, at distance 0.)
   The first kind is made only where the shape dips between the triangle's vertices: where its gap
   at the point is smaller than the gaps of the vertices interpolated there by more than
   -contact_intersection_depth (at the start of the step, for a point within the alarm
   distance); elsewhere the vertices' own contacts hold the point to within that depth. A point
   whose triangle point is an FE vertex is that vertex's own contact, and two picture points
   landing on one triangle point make one contact. Near the vertices' own contacts these rows are
   nearly redundant (W nearly singular, the forces not unique): results stay reproducible because
   the contacts are sorted by keys that do not depend on round-off (FCReferencePoint). */
#include "collisionimpl.h"

/* The first form (a sphere, a capsule) */
static PetscErrorCode SmoothShapeOnSurface(FCBody Sh, FCBody F, PetscInt ish, PetscInt ife, Surface *S, PetscInt pair,
                                           const FCContactPairs *pairs, PetscMPIInt rank, FCContactSet *set)
{
  PetscInt     n, *cand = NULL, nmade = 0;
  FCRayGrid    grid = {{0}};
  FCProximity *prox;
  PetscReal   *x0, *xf, *key, *made = NULL, distance = pairs->distance, tau = FCCCDThreshold(distance);

  PetscFunctionBegin;
  PetscCall(FCBodyGetContactPoints(Sh, &n, &prox, &x0, &xf, &key));
  if (!n) PetscFunctionReturn(0);
  PetscCall(PetscMalloc2(S->n + 1, &cand, 3 * n, &made));
  for (PetscInt i = 0; i < n; i++) {
    PetscInt    best;
    PetscReal   bw[3] = {0, 0, 0}, bcp[3] = {0, 0, 0}, yf[3], X[3] = {0, 0, 0}, d, nrm[3], cpb[3];
    PetscBool   dup = PETSC_FALSE;
    FCProximity tp  = {0};
    FCContact   c;
    PetscCall(FCCollisionLandingTriangle(S, &x0[3 * i], &xf[3 * i], NULL, distance, pairs->continuous, tau, cand, &grid,
                                         &best, bw, bcp));
    if (best < 0) continue;
    if (bw[0] == 1.0 || bw[1] == 1.0 || bw[2] == 1.0) continue; /* an FE vertex: its own contact */
    {
      const FCSurfaceTriangle *T = &S->tri[best];
      FCCollisionTrianglePoint(T, bw, &tp, yf); /* bcp: its start position */
      FCReferencePoint(3, T->X, bw, X);         /* the key: free of the weights' round-off */
      for (PetscInt m = 0; m < nmade && !dup; m++)
        dup = made[3 * m] == X[0] && made[3 * m + 1] == X[1] && made[3 * m + 2] == X[2] ? PETSC_TRUE : PETSC_FALSE;
      if (dup) continue;
      PetscCall(FCBodyShapeDistance(Sh, FC_AT_NOW, bcp, &d, nrm, cpb));
      { /* needed only where the shape dips between the vertices: deeper than the gap the vertices'
           own constraints hold (interpolated) by more than the intersection depth */
        PetscReal interp = 0.0;
        for (int a = 0; a < 3; a++) {
          PetscReal da, na[3], ca[3];
          PetscCall(FCBodyShapeDistance(Sh, FC_AT_NOW, T->x0[a], &da, na, ca));
          interp += bw[a] * da;
        }
        /* (a point only the motion brings to the surface keeps its contact: its dip is not
           known at the start of the step) */
        if (d < distance && d >= interp - PetscMax(pairs->intersection_depth, PETSC_SMALL)) continue;
      }
      if (d >= distance) { /* the triangle point's own motion against the shape decides */
        PetscBool hit = PETSC_FALSE;
        if (pairs->continuous) PetscCall(FCCCDPointShape(Sh, bcp, yf, d, tau, &hit));
        if (!hit) continue;
      }
      for (int k = 0; k < 3; k++) made[3 * nmade + k] = X[k];
      nmade++;
      PetscCall(PetscMemzero(&c, sizeof(c)));
      c.pair    = pair;
      c.body[0] = ife;
      c.body[1] = ish;
      c.prox[0] = tp;
      for (int k = 0; k < 3; k++) {
        c.prox[0].r[k] = X[k];
        c.prox[1].r[k] = cpb[k];
        c.key[k]       = X[k];
        c.n[k]         = nrm[k];
        c.p0[0][k]     = bcp[k];
        c.pfree[0][k]  = yf[k];
      }
      PetscCall(FCBodyProximityPosition(Sh, &c.prox[1], FC_AT_START, c.p0[1]));
      PetscCall(FCBodyProximityPosition(Sh, &c.prox[1], FC_AT_FREE, c.pfree[1]));
      c.side2 = FC_SIDE_SHAPE;
      c.gap0  = d;
      c.mu    = pairs->mu[pair];
      c.owner = rank;
      PetscCall(FCContactSetAdd(set, &c));
    }
  }
  PetscCall(PetscFree2(cand, made));
  PetscCall(PetscFree(grid.cells));
  PetscFunctionReturn(0);
}

/* The second form (a box, a cylinder): the picture points against the FE triangles as a rigid
   mesh's vertices (FCCollisionVerticesAgainstSurface), dormant (pgs.c, SolveLazy): where the
   vertices' own contacts already hold the shape, a point's row is nearly a combination of theirs
   (W nearly singular, the forces not unique); the solver takes it up only where the solution
   leaves the point deeper inside than -contact_dormant_depth */
static PetscErrorCode ShapePointsOnSurface(FCBody Sh, FCBody F, PetscInt ish, PetscInt ife, Surface *S, PetscInt pair,
                                           const FCContactPairs *pairs, PetscMPIInt rank, FCContactSet *set)
{
  PetscInt first = set->n;

  PetscFunctionBegin;
  PetscCall(FCCollisionVerticesAgainstSurface(Sh, F, ish, ife, S, 0, NULL, pair, pairs, rank, set));
  for (PetscInt k = first; k < set->n; k++) set->c[k].dormant = PETSC_TRUE;
  PetscFunctionReturn(0);
}

PetscErrorCode FCCollisionShapePoints(FCBody Sh, FCBody F, PetscInt ish, PetscInt ife, Surface *S, PetscInt pair,
                                      const FCContactPairs *pairs, PetscMPIInt rank, FCContactSet *set)
{
  PetscFunctionBegin;
  if (FCBodyHasSmoothShape(Sh))
    PetscCall(SmoothShapeOnSurface(Sh, F, ish, ife, S, pair, pairs, rank, set));
  else
    PetscCall(ShapePointsOnSurface(Sh, F, ish, ife, S, pair, pairs, rank, set));
  PetscFunctionReturn(0);
}
