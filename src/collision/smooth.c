/* A rounded shape (sphere, capsule, cylinder) against an analytic shape (plane, sphere, box,
   capsule, cylinder), from their exact closest points, not from the rounded shape's drawn surface:
   a ball or a cylinder that touches through the vertices of its picture rolls as a polyhedron (each
   facet an impact: it loses speed, and bumps, at every step).
   A rounded shape is the set of points within its radius r of its core, a point or a segment
   (FCShape), cut by flat ends for a cylinder. For a point c of the core, the other shape's signed
   distance d(c) and outward normal n there give the rounded shape's point nearest the other shape,
   its support point: c - r n for a sphere or a capsule; for a cylinder's end the point of its rim
   c - r u / |u|, u = n - (n.a) a the part of n across the axis a, or, where the end face lies flat
   against the other shape (|u| < sin FC_FLAT_DEG), FC_FACE_POINTS points of its rim. The candidates
   are the core's point (sphere), the segment's two ends and, where the distance to the other shape
   is smallest inside the segment, that point (a capsule or a cylinder on a sphere or a box edge: the
   distance to a convex shape is convex along a segment, a golden-section search finds it). Each
   support point is a contact as a rigid point is: fixed in its body frame for the step, with the
   other shape's distance, normal and closest point there; farther than the alarm distance, it is a
   speculative contact where its motion over the step reaches the other shape (continuous
   detection, ccd.c). The key of a contact is its core point in the body frame (a rim point of a flat
   face: itself), which does not move as the shape rolls, so the warm start follows it. The rounded
   shape's body is rigid or kinematic, on rank 0, which makes these contacts. */
#include "collisionimpl.h"

#define FC_FLAT_DEG 5.0  /* a cylinder's end within this of parallel to the other surface lies flat on it */
#define FC_FACE_POINTS 8 /* rim points of an end face that lies flat */
#define FC_INTERIOR 0.01 /* a segment's interior point within this fraction of an end is that end's */

typedef struct {
  FCBody    P, S;
  PetscInt  ip, is, ncore;
  PetscReal core[2][3], r, a[3]; /* core (body frame), radius, axis (world, core 0 -> core 1; 0 for a point) */
  PetscBool flat;
} Rounded;

/* S's signed distance at the world point x */
static PetscErrorCode Distance(const Rounded *R, const PetscReal x[3], PetscReal *d, PetscReal n[3], PetscReal cpb[3])
{
  PetscFunctionBegin;
  PetscCall(FCBodyShapeDistance(R->S, FC_AT_NOW, x, d, n, cpb));
  PetscFunctionReturn(0);
}

/* World position now of the body-frame point xb of P */
static PetscErrorCode World(const Rounded *R, const PetscReal xb[3], PetscInt when, PetscReal x[3])
{
  FCProximity q = {0};

  PetscFunctionBegin;
  for (int i = 0; i < 3; i++) q.r[i] = xb[i];
  PetscCall(FCBodyProximityPosition(R->P, &q, when, x));
  PetscFunctionReturn(0);
}

PetscErrorCode FCCollisionAddShapeContact(FCBody P, FCBody S, PetscInt ip, PetscInt is, PetscInt pair,
                                          const PetscReal x[3], PetscReal d, const PetscReal n[3],
                                          const PetscReal cpb[3], const PetscReal key[3], const FCContactPairs *pairs,
                                          PetscMPIInt rank, FCContactSet *set)
{
  FCContact c;

  PetscFunctionBegin;
  PetscCall(PetscMemzero(&c, sizeof(c)));
  PetscCall(FCBodyToBodyFrame(P, FC_AT_NOW, x, PETSC_FALSE, c.prox[0].r));
  PetscCall(FCBodyProximityPosition(P, &c.prox[0], FC_AT_FREE, c.pfree[0]));
  if (d >= pairs->distance) { /* continuous: a speculative contact if the point's motion reaches S */
    PetscBool hit = PETSC_FALSE;
    if (pairs->continuous) PetscCall(FCCCDPointShape(S, x, c.pfree[0], d, FCCCDThreshold(pairs->distance), &hit));
    if (!hit) PetscFunctionReturn(0);
  }
  c.pair    = pair;
  c.body[0] = ip;
  c.body[1] = is;
  for (int i = 0; i < 3; i++) {
    c.prox[1].r[i] = cpb[i];
    c.key[i]       = key[i];
    c.n[i]         = n[i];
    c.p0[0][i]     = x[i];
  }
  PetscCall(FCBodyProximityPosition(S, &c.prox[1], FC_AT_START, c.p0[1]));
  PetscCall(FCBodyProximityPosition(S, &c.prox[1], FC_AT_FREE, c.pfree[1]));
  c.gap0  = d;
  c.mu    = pairs->mu[pair];
  c.owner = rank;
  c.side2 = FC_SIDE_SHAPE;
  PetscCall(FCContactSetAdd(set, &c));
  PetscFunctionReturn(0);
}

/* The contact of P's point x (world, now) with S, keyed by key (body frame of P) */
static PetscErrorCode AddContact(const Rounded *R, const PetscReal x[3], const PetscReal key[3], PetscInt pair,
                                 const FCContactPairs *pairs, PetscMPIInt rank, FCContactSet *set)
{
  PetscReal d, n[3], cpb[3];

  PetscFunctionBegin;
  PetscCall(Distance(R, x, &d, n, cpb));
  PetscCall(FCCollisionAddShapeContact(R->P, R->S, R->ip, R->is, pair, x, d, n, cpb, key, pairs, rank, set));
  PetscFunctionReturn(0);
}

/* The support point(s) of the core point cb (body frame; `end` 0 or 1 for a segment's ends, -1
   inside it): contacts keyed by cb, or by each rim point of an end face that lies flat */
static PetscErrorCode CoreContacts(const Rounded *R, const PetscReal cb[3], PetscInt end, PetscInt pair,
                                   const FCContactPairs *pairs, PetscMPIInt rank, FCContactSet *set)
{
  PetscReal c[3], d, n[3], cpb[3], x[3], u[3], na, lu;

  PetscFunctionBegin;
  PetscCall(World(R, cb, FC_AT_NOW, c));
  PetscCall(Distance(R, c, &d, n, cpb));
  if (!R->flat) { /* sphere, capsule: the point of the surface along -n */
    for (int i = 0; i < 3; i++) x[i] = c[i] - R->r * n[i];
    PetscCall(AddContact(R, x, cb, pair, pairs, rank, set));
    PetscFunctionReturn(0);
  }
  na = FCDot(n, R->a);
  for (int i = 0; i < 3; i++) u[i] = n[i] - na * R->a[i];
  lu = PetscSqrtReal(FCDot(u, u));
  if (lu > PetscSinReal(FC_FLAT_DEG * PETSC_PI / 180.0)) { /* the rim (or the side) point nearest S */
    for (int i = 0; i < 3; i++) x[i] = c[i] - R->r * u[i] / lu;
    PetscCall(AddContact(R, x, cb, pair, pairs, rank, set));
  } else if (end >= 0 && (end ? na : -na) < 0) { /* the end face, lying flat on S: its rim points */
    for (PetscInt j = 0; j < FC_FACE_POINTS; j++) {
      PetscReal th = 2.0 * PETSC_PI * j / FC_FACE_POINTS, xb[3] = {R->r * PetscCosReal(th), R->r * PetscSinReal(th), 0};
      /* the body frame's z is the cylinder's axis (FCShape) */
      xb[2] = cb[2];
      PetscCall(World(R, xb, FC_AT_NOW, x));
      PetscCall(AddContact(R, x, xb, pair, pairs, rank, set));
    }
  }
  PetscFunctionReturn(0);
}

/* S's distance at the core point t of the segment a + t (b - a) (world) */
static PetscErrorCode SegmentDistance(const Rounded *R, const PetscReal a[3], const PetscReal b[3], PetscReal t,
                                      PetscReal *d)
{
  PetscReal x[3], n[3], cp[3];

  PetscFunctionBegin;
  for (int i = 0; i < 3; i++) x[i] = a[i] + t * (b[i] - a[i]);
  PetscCall(Distance(R, x, d, n, cp));
  PetscFunctionReturn(0);
}

typedef struct {
  const Rounded   *R;
  const PetscReal *a, *b;
} SegmentCtx;

/* SegmentDistance for FCGoldenMinimum */
static PetscErrorCode SegmentAt(PetscReal t, void *ctx, PetscReal *d)
{
  SegmentCtx *sc = (SegmentCtx *)ctx;

  PetscFunctionBegin;
  PetscCall(SegmentDistance(sc->R, sc->a, sc->b, t, d));
  PetscFunctionReturn(0);
}

PetscErrorCode FCCollisionRoundedShape(FCBody P, FCBody S, PetscInt ip, PetscInt is, PetscInt pair,
                                       const FCContactPairs *pairs, PetscMPIInt rank, FCContactSet *set)
{
  Rounded R;

  PetscFunctionBegin;
  if (rank) PetscFunctionReturn(0);
  PetscCall(PetscMemzero(&R, sizeof(R)));
  R.P  = P;
  R.S  = S;
  R.ip = ip;
  R.is = is;
  FCBodyGetShapeCore(P, &R.ncore, R.core, &R.r, &R.flat);
  PetscCheck(R.ncore > 0, PETSC_COMM_SELF, PETSC_ERR_PLIB, "Body '%s' has no rounded shape", FCBodyName(P));
  if (R.ncore == 1) {
    PetscCall(CoreContacts(&R, R.core[0], -1, pair, pairs, rank, set));
    PetscFunctionReturn(0);
  }
  {
    PetscReal a[3], b[3], l, t1, d1, da, db;
    PetscCall(World(&R, R.core[0], FC_AT_NOW, a));
    PetscCall(World(&R, R.core[1], FC_AT_NOW, b));
    for (int i = 0; i < 3; i++) R.a[i] = b[i] - a[i];
    l = PetscSqrtReal(FCDot(R.a, R.a));
    for (int i = 0; i < 3; i++) R.a[i] /= l;
    for (PetscInt k = 0; k < 2; k++) PetscCall(CoreContacts(&R, R.core[k], k, pair, pairs, rank, set));
    /* the segment's interior: where the distance to S is smallest, if not at an end */
    {
      SegmentCtx sc = {&R, a, b};
      PetscCall(FCGoldenMinimum(SegmentAt, &sc, &t1));
    }
    PetscCall(SegmentDistance(&R, a, b, t1, &d1));
    PetscCall(SegmentDistance(&R, a, b, 0.0, &da));
    PetscCall(SegmentDistance(&R, a, b, 1.0, &db));
    /* inside, and nearer than both ends by more than round-off (a capsule lying flat on a plane has
       its two ends: a contact between them would only repeat them) */
    if (t1 > FC_INTERIOR && t1 < 1.0 - FC_INTERIOR && d1 < PetscMin(da, db) - 1e-9 * R.r) {
      PetscReal cb[3];
      for (int i = 0; i < 3; i++) cb[i] = R.core[0][i] + t1 * (R.core[1][i] - R.core[0][i]);
      PetscCall(CoreContacts(&R, cb, -1, pair, pairs, rank, set));
    }
  }
  PetscFunctionReturn(0);
}
