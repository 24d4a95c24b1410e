/* A sphere, a capsule or a cylinder's side against an FE surface, from their exact closest points
   (-contact_shape_points, called by FCCollisionShapePoints, shapepoints.c): besides the FE vertices against the
   shape's signed distance, the points of the FE surface nearest the shape's core, each the FE material point there
   (barycentric weights, side 1) against the shape's distance (side 2), taken where the point and the shape will be
   after the free motion. A ball, a capsule or a cylinder then rolls over an FE surface as it rolls on a plane, not as
   the polyhedron of its picture (each facet an impact) nor over the surface's vertices (a bump at each). */
#include "collisionimpl.h"

typedef struct {
  const PetscReal (*core)[3], (*T)[3];
} CoreCtx;

/* The distance from the core segment's point t to the triangle, for FCGoldenMinimum */
static PetscErrorCode CoreAt(PetscReal t, void *ctx, PetscReal *d)
{
  CoreCtx  *cc = (CoreCtx *)ctx;
  PetscReal x[3];

  for (int i = 0; i < 3; i++) x[i] = cc->core[0][i] + t * (cc->core[1][i] - cc->core[0][i]);
  *d = FCTriangleDistance(cc->T, x);
  return 0;
}

/* The core points (world) that may be nearest the triangle with vertices at T: a sphere's centre; a
   capsule's two ends and the point of its segment nearest T where that is inside (the distance to a
   triangle is convex along a segment) */
static PetscErrorCode CorePoints(PetscInt ncore, const PetscReal core[2][3], const PetscReal T[3][3], PetscReal c[3][3],
                                 PetscInt *n)
{
  CoreCtx   cc = {core, T};
  PetscReal t, dt, d0, d1;

  PetscFunctionBegin;
  *n = ncore;
  for (PetscInt k = 0; k < ncore; k++)
    for (int i = 0; i < 3; i++) c[k][i] = core[k][i];
  if (ncore == 1) PetscFunctionReturn(0);
  PetscCall(FCGoldenMinimum(CoreAt, &cc, &t));
  PetscCall(CoreAt(t, &cc, &dt));
  PetscCall(CoreAt(0.0, &cc, &d0));
  PetscCall(CoreAt(1.0, &cc, &d1));
  if (dt < PetscMin(d0, d1) - PETSC_SMALL) {
    for (int i = 0; i < 3; i++) c[*n][i] = core[0][i] + t * (core[1][i] - core[0][i]);
    (*n)++;
  }
  PetscFunctionReturn(0);
}

/* A cylinder's side over the triangle with vertices at T (reference positions Xr, outward normal nt): the axis points
   (world) whose feet on the triangle's plane are the ends of the part of the axis' foot that lies on the triangle, so
   that their nearest points on the triangle are the points under the side's lowest line where it crosses the
   triangle's edges, and its ends over the triangle: the FE points a cylinder lying on the surface presses. A crossing
   is recomputed from its edge alone (the axis' point nearest the edge, its ends in reference order), so that the two
   triangles of the edge find the same point to the bit. The line's ends are kept where their feet on the plane stay
   within the end faces (a tilted axis: a foot beyond the lower rim is not under the side). None where the triangle
   has no area or the axis is steeper than 30 degrees to its plane (the cylinder stands on a rim or an end: its
   picture's points). */
static void SidePoints(const PetscReal core[2][3], PetscReal r, const PetscReal T[3][3], const PetscReal Xr[3][3],
                       const PetscReal nt[3], PetscReal c[3][3], PetscInt *n)
{
  PetscReal ab[3], lab, tin, tout, inset, tilt;
  int       ein = -1, eout = -1;

  *n = 0;
  for (int i = 0; i < 3; i++) ab[i] = core[1][i] - core[0][i];
  lab  = PetscSqrtReal(FCDot(ab, ab));
  tilt = PetscAbsReal(FCDot(ab, nt));
  if (lab == 0.0 || FCDot(nt, nt) == 0.0 || tilt > 0.5 * lab) return;
  /* the axis tilted by alpha to the plane: the foot of its lower end lies r tan(alpha) beyond the end face; keep the
     line's ends inside by that, and a hair more */
  inset = 1e-6 + r * tilt / (lab * PetscSqrtReal(lab * lab - tilt * tilt));
  tin   = inset;
  tout  = 1.0 - inset;
  for (int e = 0; e < 3; e++) { /* the foot a' + t ab' on the inner side of edge e: m . (a' - v_e) + t m . ab >= 0 */
    PetscReal ed[3], m[3], oc[3], a0[3], num, den;
    for (int i = 0; i < 3; i++) {
      ed[i] = T[(e + 1) % 3][i] - T[e][i];
      oc[i] = T[(e + 2) % 3][i] - T[e][i];
      a0[i] = core[0][i] - T[e][i];
    }
    FCCross(nt, ed, m);
    if (FCDot(m, oc) < 0.0)
      for (int i = 0; i < 3; i++) m[i] = -m[i];
    num = FCDot(m, a0); /* m is in the plane: the feet's offsets along nt do not count */
    den = FCDot(m, ab);
    if (den == 0.0) {
      if (num < 0.0) return;
    } else if (den > 0.0) {
      if (-num / den > tin) {
        tin = -num / den;
        ein = e;
      }
    } else if (-num / den < tout) {
      tout = -num / den;
      eout = e;
    }
  }
  if (tin > tout) return;
  for (int k = 0; k < 2; k++) { /* a crossing from its edge alone */
    int       e = k ? eout : ein, a, b;
    PetscReal sa, se, *t = k ? &tout : &tin;
    if (e < 0) continue;
    a = e;
    b = (e + 1) % 3;
    if (FCComparePoint(Xr[a], Xr[b]) > 0) {
      a = b;
      b = e;
    }
    (void)FCClosestSegmentSegment(core[0], core[1], T[a], T[b], &sa, &se);
    *t = PetscMin(1.0 - inset, PetscMax(inset, sa));
  }
  for (int i = 0; i < 3; i++) c[0][i] = core[0][i] + tin * ab[i];
  *n = 1;
  if (tout > tin) {
    for (int i = 0; i < 3; i++) c[1][i] = core[0][i] + tout * ab[i];
    *n = 2;
  }
}

typedef struct {
  PetscReal X[3];        /* reference position: the sort key */
  PetscInt  tri, front;  /* front: the core in front of triangle tri's plane */
  PetscReal w[3], cb[3]; /* weights in triangle tri; the core point nearest (body frame) */
} EdgePoint;

/* A rounded shape against an FE surface: what AddSurfacePoint needs */
typedef struct {
  FCBody                Sh;
  PetscInt              ish, ife, pair;
  PetscReal             r;        /* radius */
  PetscBool             side;     /* a cylinder: its side's own distance where the side is nearest */
  PetscReal             axis0[3]; /* the cylinder's axis after the free motion: its start (world), */
  PetscReal             axis[3];  /* direction (unit) */
  PetscReal             len;      /* and length */
  const FCContactPairs *pairs;
  PetscMPIInt           rank;
  FCContactSet         *set;
} Across;

/* The shape's distance at the world point y (on a triangle of outward normal nt) after the free motion and its
   normal there; where y is against a cylinder's side (FCCylinderSideDistance), the side's own, whose normal stays
   radial at the rims, where the end faces are as near */
static PetscErrorCode ShapeDistance(const Across *A, const PetscReal y[3], const PetscReal nt[3], PetscReal *d,
                                    PetscReal n[3])
{
  PetscBool side = PETSC_FALSE;
  PetscReal cf[3];

  PetscFunctionBegin;
  if (A->side) FCCylinderSideDistance(A->axis0, A->axis, A->len, A->r, y, nt, d, n, &side);
  if (!side) PetscCall(FCBodyShapeDistance(A->Sh, FC_AT_FREE, y, d, n, cf));
  PetscFunctionReturn(0);
}

/* The contact of the FE material point at weights bw of triangle T (key X) against the rounded shape whose core
   point cb (body frame) is nearest it after the free motion, made where the shape will dip between the triangle's
   vertices deeper than their own contacts hold it (by -contact_intersection_depth) within the alarm distance. It is
   taken where the point and the shape will be: the normal is the shape's at the point after the free motion, the
   shape's point is the one along n from cb at the start (a rolling ball's lowest point: its lever arm has no moment
   about the centre), and the gap the solver starts from is the shape's exact one after the free motion (qcurv), so a
   ball that rolls neither brakes nor sinks. */
static PetscErrorCode AddSurfacePoint(const Across *A, const FCSurfaceTriangle *T, const PetscReal bw[3],
                                      const PetscReal X[3], const PetscReal cb[3])
{
  PetscReal   bcp[3], yf[3], d0 = 0.0, df, interp = 0.0, n[3], p2[3], core[3], nt[3], r1[3];
  FCProximity tp = {0}, q = {0};
  FCContact   c;

  PetscFunctionBegin;
  FCCollisionTrianglePoint(T, bw, &tp, yf);
  for (int i = 0; i < 3; i++) bcp[i] = bw[0] * T->x0[0][i] + bw[1] * T->x0[1][i] + bw[2] * T->x0[2][i];
  FCTriangleNormal(T->xf, nt);
  PetscCall(ShapeDistance(A, yf, nt, &df, n));
  for (int a = 0; a < 3; a++) {
    PetscReal da, na[3], ca[3];
    if (bw[a] == 0.0) continue;
    PetscCall(FCBodyShapeDistance(A->Sh, FC_AT_FREE, T->xf[a], &da, na, ca));
    interp += bw[a] * da;
  }
  /* after the free motion: within the alarm distance, and dipping between the vertices */
  if (df >= A->pairs->distance || df >= interp - PetscMax(A->pairs->intersection_depth, PETSC_SMALL))
    PetscFunctionReturn(0);
  for (int a = 0; a < 3; a++) { /* the start gap: its vertices' (the start-inside rule, collision.c) */
    PetscReal da, na[3], ca[3];
    if (bw[a] == 0.0) continue;
    PetscCall(FCBodyShapeDistance(A->Sh, FC_AT_NOW, T->x0[a], &da, na, ca));
    d0 += bw[a] * da;
  }
  for (int i = 0; i < 3; i++) q.r[i] = cb[i];
  PetscCall(FCBodyProximityPosition(A->Sh, &q, FC_AT_NOW, core));
  for (int i = 0; i < 3; i++) p2[i] = core[i] + A->r * n[i];
  PetscCall(FCBodyToBodyFrame(A->Sh, FC_AT_NOW, p2, PETSC_FALSE, r1));
  PetscCall(FCCollisionSurfaceShapeContact(A->Sh, A->ish, A->ife, A->pair, A->pairs, A->rank, &tp, X, bcp, yf, n, r1,
                                           d0, &c));
  {
    PetscReal dfree[3];
    for (int k = 0; k < 3; k++) dfree[k] = c.pfree[0][k] - c.pfree[1][k];
    c.qcurv = df - FCDot(n, dfree);
  }
  PetscCall(FCContactSetAdd(A->set, &c));
  PetscFunctionReturn(0);
}

typedef struct {
  const Across *A;
  PetscReal     fr[3]; /* the sphere's centre after the free motion (world) */
} BehindCtx;

/* Beside the exact points of a sphere, the FE points its picture's points land on, as the same kind of contact
   (taken after the free motion, where the shape dips between the triangle's vertices): where the free motion is a
   poor guess of where the surface goes (a soft body dragged by a turning finger), they hold it where the exact
   points, taken there, do not. */
static PetscErrorCode PicturePointBehind(const FCSurfaceTriangle *T, const PetscReal bw[3], const PetscReal bcp[3],
                                         const PetscReal X[3], void *ctx, PetscBool *made)
{
  BehindCtx    *B = (BehindCtx *)ctx;
  const Across *A = B->A;
  PetscReal     cb[3];

  PetscFunctionBegin;
  *made = PETSC_TRUE;
  PetscCall(FCBodyToBodyFrame(A->Sh, FC_AT_FREE, B->fr, PETSC_FALSE, cb));
  PetscCall(AddSurfacePoint(A, T, bw, X, cb));
  PetscFunctionReturn(0);
}

/* The core of Sh after the free motion (fr, world) and the triangles of S near it: those of the box the core sweeps
   over the step (now and after the free motion), grown by grow; *cand (S->n + 1 entries) to be freed */
static PetscErrorCode NearTriangles(FCBody Sh, Surface *S, PetscInt ncore, const PetscReal core[2][3], PetscReal grow,
                                    PetscReal fr[2][3], PetscInt **cand, PetscInt *nc)
{
  FCProximity q = {0};
  PetscReal   now[2][3], lo[3], hi[3];

  PetscFunctionBegin;
  for (PetscInt k = 0; k < ncore; k++) {
    for (int i = 0; i < 3; i++) q.r[i] = core[k][i];
    PetscCall(FCBodyProximityPosition(Sh, &q, FC_AT_NOW, now[k]));
    PetscCall(FCBodyProximityPosition(Sh, &q, FC_AT_FREE, fr[k]));
  }
  for (int i = 0; i < 3; i++) {
    lo[i] = PETSC_MAX_REAL;
    hi[i] = -PETSC_MAX_REAL;
    for (PetscInt k = 0; k < ncore; k++) {
      lo[i] = PetscMin(lo[i], PetscMin(now[k][i], fr[k][i]) - grow);
      hi[i] = PetscMax(hi[i], PetscMax(now[k][i], fr[k][i]) + grow);
    }
  }
  PetscCall(PetscMalloc1(S->n + 1, cand));
  *nc = 0;
  if (S->swept) /* boxes over the step: they hold the triangles' free positions too */
    FCSurfaceQueryBox(S, lo, hi, *cand, nc);
  else
    for (PetscInt t = 0; t < S->n; t++) (*cand)[(*nc)++] = t;
  PetscFunctionReturn(0);
}

/* Whether the side of cylinder Sh lies over a triangle of S near it after the free motion (SidePoints has points
   there within reach): the side's points then hold the rims' lowest points too (the ends of the side's lowest line),
   and its picture's points on the rims would be rows redundant with them, fixed in the shape's frame */
PetscErrorCode FCCollisionCylinderLies(FCBody Sh, Surface *S, const FCContactPairs *pairs, PetscBool *lies)
{
  PetscInt  ncore, nc = 0, *cand;
  PetscReal core[2][3], fr[2][3], grow, r;
  PetscBool flat = PETSC_FALSE;

  PetscFunctionBegin;
  *lies = PETSC_FALSE;
  FCBodyGetShapeCore(Sh, &ncore, core, &r, &flat);
  if (ncore != 2 || !flat) PetscFunctionReturn(0);
  grow = r + pairs->distance;
  PetscCall(NearTriangles(Sh, S, ncore, core, grow, fr, &cand, &nc));
  for (PetscInt k = 0; k < nc && !*lies; k++) {
    const FCSurfaceTriangle *T = &S->tri[cand[k]];
    PetscReal                c[3][3], nt[3];
    PetscInt                 np;
    FCTriangleNormal(T->xf, nt);
    SidePoints(fr, r, T->xf, T->X, nt, c, &np);
    for (PetscInt j = 0; j < np; j++)
      if (FCTriangleDistance(T->xf, c[j]) <= grow) *lies = PETSC_TRUE;
  }
  PetscCall(PetscFree(cand));
  PetscFunctionReturn(0);
}

/* The exact points are linearized after the free motion: their normal is the shape's at the FE point's free position.
   That is where the surface ends only if the step's contact forces move it little from there, as under a ball that
   rolls. A soft surface that holds the shape up (a membrane under a falling ball) springs back without the forces in
   the free motion, deep inside the shape, and the forces put it back: the normal at its free position is then turned
   from the one where it ends by an angle theta, and the plane of the linearized contact, tangent to the shape along
   that normal, holds the point r (1 - cos theta) off the shape with a force far from the shape's normal, which pushes
   the membrane sideways (input/membrane.opts: an element of it turned inside out).
   Here: whether, at any point of the surface nearest the core after the free motion and within the alarm distance,
   the free motion of the FE point alone (the core after the free motion) turns the shape's normal by theta with
   r (1 - cos theta) above -contact_intersection_depth; or whether the shape's own free motion takes it deeper into
   the surface than the alarm distance: an impact, after which the shape does not end near its free pose either, and
   the contacts taken there, deep inside, make a nearly singular problem (a cylinder whose end face touches the
   surface counts so too: its end's centre is on the surface). The caller (shapepoints.c) then takes the shape's
   picture points, linearized at the start of the step. From the gathered surface and the shape's pose: the same on
   every rank. */
PetscErrorCode FCCollisionRoundedSurfaceTurns(FCBody Sh, Surface *S, const FCContactPairs *pairs, PetscBool *turns)
{
  PetscInt  ncore, nc = 0, *cand;
  PetscReal core[2][3], fr[2][3], grow, r, tol = PetscMax(pairs->intersection_depth, PETSC_SMALL);
  PetscBool flat = PETSC_FALSE;

  PetscFunctionBegin;
  *turns = PETSC_FALSE;
  FCBodyGetShapeCore(Sh, &ncore, core, &r, &flat);
  if (ncore <= 0) PetscFunctionReturn(0);
  grow = r + pairs->distance;
  PetscCall(NearTriangles(Sh, S, ncore, core, grow, fr, &cand, &nc));
  for (PetscInt k = 0; k < nc && !*turns; k++) {
    const FCSurfaceTriangle *T = &S->tri[cand[k]];
    PetscReal                c[3][3];
    PetscInt                 np;
    PetscCall(CorePoints(ncore, fr, T->xf, c, &np));
    for (PetscInt j = 0; j < np && !*turns; j++) {
      PetscReal cp[3], w[3], nf[3], ns[3], lf, ls;
      FCClosestPointTriangle(c[j], T->xf[0], T->xf[1], T->xf[2], cp, w);
      for (int i = 0; i < 3; i++) {
        nf[i] = cp[i] - c[j][i];
        ns[i] = w[0] * T->x0[0][i] + w[1] * T->x0[1][i] + w[2] * T->x0[2][i] - c[j][i];
      }
      lf = PetscSqrtReal(FCDot(nf, nf));
      ls = PetscSqrtReal(FCDot(ns, ns));
      if (lf - r >= pairs->distance) continue; /* out of reach after the free motion */
      if (lf <= PETSC_SMALL * r || ls <= PETSC_SMALL * r || r * (1.0 - FCDot(nf, ns) / (lf * ls)) > tol ||
          r - lf > pairs->distance)
        *turns = PETSC_TRUE;
    }
  }
  PetscCall(PetscFree(cand));
  PetscFunctionReturn(0);
}

/* A rounded shape (sphere, capsule, a cylinder's side): the points of the FE surface nearest the shape's core (a
   cylinder's: those under its lowest line, SidePoints, against the side's own distance), from each triangle near the
   shape (its swept box over the step, grown by the radius and the alarm distance): a
   point inside a face whose outer side the core is on; a point on an edge where both triangles of the edge find
   it (the distance to the surface is smallest there: a ridge, or the foot of the core on the edge itself;
   elsewhere the face beside it holds a nearer point); a vertex is that vertex's own contact. These are the exact
   closest points of the shape and the surface, which move continuously as the shape rolls (its picture's points
   would make it roll as a polyhedron). They are taken after the free motion (the caller decides: shapepoints.c,
   CoreFollows). */
/* The edge points both triangles of their edge find, the core in front of one of them at least (not an edge of
   the surface's far side, seen through a thin body); the edge's lowest triangle makes it, the same on any run */
static PetscErrorCode AddEdgePoints(const Across *A, Surface *S, EdgePoint edge[], PetscInt nedge)
{
  PetscFunctionBegin;
  if (nedge > 1) qsort(edge, nedge, sizeof(EdgePoint), FCComparePoint);
  for (PetscInt e = 0; e < nedge;) {
    PetscInt f = e + 1, first = e, front = edge[e].front;
    while (f < nedge && !FCComparePoint(&edge[e], &edge[f])) {
      if (edge[f].tri < edge[first].tri) first = f;
      front = front || edge[f].front;
      f++;
    }
    if (f - e >= 2 && front)
      PetscCall(AddSurfacePoint(A, &S->tri[edge[first].tri], edge[first].w, edge[first].X, edge[first].cb));
    e = f;
  }
  PetscFunctionReturn(0);
}

/* A cylinder's line of contacts (set->c[first..]): its two extreme points along the axis awake, those between
   dormant */
static void CylinderLine(const Across *A, FCContactSet *set, PetscInt first)
{
  PetscInt  lo = first, hi = first;
  PetscReal slo = PETSC_MAX_REAL, shi = -PETSC_MAX_REAL;
  for (PetscInt k = first; k < set->n; k++) {
    PetscReal v[3], sk;
    for (int i = 0; i < 3; i++) v[i] = set->c[k].pfree[1][i] - A->axis0[i];
    sk = FCDot(v, A->axis);
    if (sk < slo) {
      slo = sk;
      lo  = k;
    }
    if (sk > shi) {
      shi = sk;
      hi  = k;
    }
  }
  for (PetscInt k = first; k < set->n; k++) set->c[k].dormant = (PetscBool)(k != lo && k != hi);
}

PetscErrorCode FCCollisionRoundedOnSurface(FCBody Sh, PetscInt ish, PetscInt ife, Surface *S, PetscInt pair,
                                           const FCContactPairs *pairs, PetscMPIInt rank, FCContactSet *set)
{
  PetscInt   ncore, nc = 0, nedge = 0, *cand;
  PetscReal  core[2][3], fr[2][3], grow;
  PetscInt   first;
  EdgePoint *edge;
  Across     A    = {0};
  PetscBool  flat = PETSC_FALSE;

  PetscFunctionBegin;
  if (rank) PetscFunctionReturn(0);
  first = set->n;
  FCBodyGetShapeCore(Sh, &ncore, core, &A.r, &flat);
  PetscCheck(ncore > 0, PETSC_COMM_SELF, PETSC_ERR_PLIB, "Body '%s' has no rounded shape", FCBodyName(Sh));
  A.Sh    = Sh;
  A.ish   = ish;
  A.ife   = ife;
  A.pair  = pair;
  A.pairs = pairs;
  A.rank  = rank;
  A.set   = set;
  grow    = A.r + pairs->distance;
  PetscCall(NearTriangles(Sh, S, ncore, core, grow, fr, &cand, &nc));
  if (flat) { /* a cylinder: its side */
    for (int i = 0; i < 3; i++) {
      A.axis0[i] = fr[0][i];
      A.axis[i]  = fr[1][i] - fr[0][i];
    }
    A.len = PetscSqrtReal(FCDot(A.axis, A.axis));
    for (int i = 0; i < 3; i++) A.axis[i] /= A.len;
    A.side = PETSC_TRUE;
  }
  PetscCall(PetscMalloc1(3 * S->n + 1, &edge));
  for (PetscInt k = 0; k < nc; k++) {
    const FCSurfaceTriangle *T = &S->tri[cand[k]];
    const PetscReal(*x)[3]     = T->xf;
    PetscReal c[3][3], nt[3];
    PetscInt  np;
    FCTriangleNormal(x, nt);
    if (flat)
      SidePoints(fr, A.r, x, T->X, nt, c, &np);
    else
      PetscCall(CorePoints(ncore, fr, x, c, &np));
    for (PetscInt j = 0; j < np; j++) {
      PetscReal w[3], X[3], side[3], cb[3];
      PetscInt  nz;
      if (FCTriangleDistance(x, c[j]) > grow) continue; /* too far from the shape at the end */
      nz = FCTriangleNearestFeature(x, T->X, c[j], w, X);
      if (nz < 2) continue; /* a vertex: its own contact */
      PetscCall(FCBodyToBodyFrame(Sh, FC_AT_FREE, c[j], PETSC_FALSE, cb));
      for (int i = 0; i < 3; i++) side[i] = c[j][i] - (w[0] * x[0][i] + w[1] * x[1][i] + w[2] * x[2][i]);
      if (nz == 3) {
        if (FCDot(side, nt) <= 0.0) continue; /* the core behind the face */
        PetscCall(AddSurfacePoint(&A, T, w, X, cb));
      } else {
        for (int i = 0; i < 3; i++) {
          edge[nedge].X[i]  = X[i];
          edge[nedge].w[i]  = w[i];
          edge[nedge].cb[i] = cb[i];
        }
        edge[nedge].tri   = cand[k];
        edge[nedge].front = FCDot(side, nt) > 0.0;
        nedge++;
      }
    }
  }
  PetscCall(AddEdgePoints(&A, S, edge, nedge));
  PetscCall(PetscFree(cand));
  PetscCall(PetscFree(edge));
  if (flat && set->n - first > 2) CylinderLine(&A, set, first);
  /* (a capsule lying on a face: its picture's points along the line of contact, woken by the step's
     linearization, made the problem rank-deficient: so not for a capsule) */
  if (ncore == 1) {
    BehindCtx B = {&A, {0}};
    for (int i = 0; i < 3; i++) B.fr[i] = fr[0][i];
    PetscCall(FCCollisionPictureLandings(Sh, S, pairs, PicturePointBehind, &B));
  }
  PetscFunctionReturn(0);
}
