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

/* What the first form's contacts share: the shape, the FE surface and the triangle points made */
typedef struct {
  FCBody     Sh;
  PetscInt   ish, ife, pair, nmade, *made_tri;
  Surface   *S;
  PetscReal *made; /* reference positions of the triangle points made */
} Smooth;

/* The contact of the FE material point at weights bw of triangle best (bcp: its start position)
   against the smooth shape, unless it is an FE vertex, made already, or not needed (no dip) */
static PetscErrorCode TrianglePoint(Smooth *M, PetscInt best, const PetscReal bw[3], const PetscReal bcp[3],
                                    const FCContactPairs *pairs, PetscMPIInt rank, FCContactSet *set)
{
  const FCSurfaceTriangle *T = &M->S->tri[best];
  PetscReal                yf[3], X[3] = {0, 0, 0}, d, nrm[3], cpb[3], distance = pairs->distance;
  FCProximity              tp = {0};
  FCContact                c;

  PetscFunctionBegin;
  if (bw[0] == 1.0 || bw[1] == 1.0 || bw[2] == 1.0) PetscFunctionReturn(0); /* an FE vertex: its own contact */
  FCCollisionTrianglePoint(T, bw, &tp, yf);                                 /* bcp: its start position */
  FCReferencePoint(3, T->X, bw, X); /* the key: free of the weights' round-off */
  for (PetscInt m = 0; m < M->nmade; m++)
    if (M->made[3 * m] == X[0] && M->made[3 * m + 1] == X[1] && M->made[3 * m + 2] == X[2]) PetscFunctionReturn(0);
  PetscCall(FCBodyShapeDistance(M->Sh, FC_AT_NOW, bcp, &d, nrm, cpb));
  { /* needed only where the shape dips between the vertices: deeper than the gap the vertices'
       own constraints hold (interpolated) by more than the intersection depth */
    PetscReal interp = 0.0;
    for (int a = 0; a < 3; a++) {
      PetscReal da, na[3], ca[3];
      PetscCall(FCBodyShapeDistance(M->Sh, FC_AT_NOW, T->x0[a], &da, na, ca));
      interp += bw[a] * da;
    }
    /* (a point only the motion brings to the surface keeps its contact: its dip is not
       known at the start of the step) */
    if (d < distance && d >= interp - PetscMax(pairs->intersection_depth, PETSC_SMALL)) PetscFunctionReturn(0);
  }
  if (d >= distance) { /* the triangle point's own motion against the shape decides */
    PetscBool hit = PETSC_FALSE;
    if (pairs->continuous) PetscCall(FCCCDPointShape(M->Sh, bcp, yf, d, FCCCDThreshold(distance), &hit));
    if (!hit) PetscFunctionReturn(0);
  }
  for (int k = 0; k < 3; k++) M->made[3 * M->nmade + k] = X[k];
  M->made_tri[M->nmade++] = best;
  PetscCall(PetscMemzero(&c, sizeof(c)));
  c.pair    = M->pair;
  c.body[0] = M->ife;
  c.body[1] = M->ish;
  c.prox[0] = tp;
  for (int k = 0; k < 3; k++) {
    c.prox[0].r[k] = X[k];
    c.prox[1].r[k] = cpb[k];
    c.key[k]       = X[k];
    c.n[k]         = nrm[k];
    c.p0[0][k]     = bcp[k];
    c.pfree[0][k]  = yf[k];
  }
  PetscCall(FCBodyProximityPosition(M->Sh, &c.prox[1], FC_AT_START, c.p0[1]));
  PetscCall(FCBodyProximityPosition(M->Sh, &c.prox[1], FC_AT_FREE, c.pfree[1]));
  c.side2 = FC_SIDE_SHAPE;
  c.gap0  = d;
  c.mu    = pairs->mu[M->pair];
  c.owner = rank;
  PetscCall(FCContactSetAdd(set, &c));
  PetscFunctionReturn(0);
}

/* The first form (a sphere, a capsule). First the FE surface's points nearest the shape's core
   (FCShape: the sphere's centre, the capsule's two cap centres): the deepest points of the shape
   against a surface that is flat there, exact as the shape rolls or slides over a triangle (a
   picture point lands beside them, and a rolling ball held by the picture's points rolls as a
   polyhedron); then the picture's points, each landing on a triangle none of the former took */
static PetscErrorCode SmoothShapeOnSurface(FCBody Sh, FCBody F, PetscInt ish, PetscInt ife, Surface *S, PetscInt pair,
                                           const FCContactPairs *pairs, PetscMPIInt rank, FCContactSet *set)
{
  PetscInt     n, *cand = NULL, ncore, ncoremade;
  FCRayGrid    grid = {{0}};
  FCProximity *prox;
  PetscReal   *x0, *xf, *key, distance = pairs->distance, tau = FCCCDThreshold(distance), core[2][3], r;
  PetscBool    flat;
  Smooth       M;

  PetscFunctionBegin;
  (void)F;
  PetscCall(FCBodyGetContactPoints(Sh, &n, &prox, &x0, &xf, &key));
  if (!n) PetscFunctionReturn(0); /* the shape's points and core are on rank 0 */
  FCBodyGetShapeCore(Sh, &ncore, core, &r, &flat);
  PetscCall(PetscMemzero(&M, sizeof(M)));
  M.Sh   = Sh;
  M.S    = S;
  M.ish  = ish;
  M.ife  = ife;
  M.pair = pair;
  PetscCall(PetscMalloc3(S->n + 1, &cand, 3 * (n + ncore), &M.made, n + ncore, &M.made_tri));
  for (PetscInt k = 0; k < ncore; k++) { /* the surface point nearest the core point */
    FCProximity q = {0};
    PetscReal   c0[3], lo[3], hi[3], bestd = PETSC_MAX_REAL, bw[3] = {0, 0, 0}, bcp[3] = {0, 0, 0};
    PetscInt    nc, best = -1;
    for (int i = 0; i < 3; i++) q.r[i] = core[k][i];
    PetscCall(FCBodyProximityPosition(Sh, &q, FC_AT_NOW, c0));
    for (int i = 0; i < 3; i++) {
      lo[i] = c0[i] - r - distance;
      hi[i] = c0[i] + r + distance;
    }
    FCSurfaceQueryBox(S, lo, hi, cand, &nc);
    for (PetscInt m = 0; m < nc; m++) {
      const FCSurfaceTriangle *T = &S->tri[cand[m]];
      PetscReal                cp[3], w[3], d2 = 0.0;
      FCClosestPointTriangle(c0, T->x0[0], T->x0[1], T->x0[2], cp, w);
      for (int i = 0; i < 3; i++) d2 += PetscSqr(c0[i] - cp[i]);
      if (d2 < bestd || (d2 == bestd && cand[m] < best)) {
        bestd = d2;
        best  = cand[m];
        for (int i = 0; i < 3; i++) {
          bw[i]  = w[i];
          bcp[i] = cp[i];
        }
      }
    }
    if (best >= 0) PetscCall(TrianglePoint(&M, best, bw, bcp, pairs, rank, set));
  }
  ncoremade = M.nmade;
  for (PetscInt i = 0; i < n; i++) {
    PetscInt  best;
    PetscReal bw[3] = {0, 0, 0}, bcp[3] = {0, 0, 0};
    PetscBool taken = PETSC_FALSE;
    PetscCall(FCCollisionLandingTriangle(S, &x0[3 * i], &xf[3 * i], NULL, distance, pairs->continuous, tau, cand, &grid,
                                         &best, bw, bcp));
    if (best < 0) continue;
    for (PetscInt m = 0; m < ncoremade; m++) taken = taken || M.made_tri[m] == best;
    if (!taken) PetscCall(TrianglePoint(&M, best, bw, bcp, pairs, rank, set));
  }
  PetscCall(PetscFree3(cand, M.made, M.made_tri));
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
