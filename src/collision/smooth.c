/* A smooth shape (sphere, capsule) against an analytic shape (plane, sphere, box, capsule, cylinder),
   from their exact closest points, not from the smooth shape's drawn surface: a sphere that touches
   through the vertices of its picture rolls as a polyhedron (each facet an impact: a ball rolling on
   a plane loses speed, and bumps, at every step). A smooth shape is the set of points within its
   radius r of its core, a point or a segment (FCShape). For a core point c, the other shape's
   signed distance d(c), outward normal n and closest point give the contact: the smooth shape's
   point c - r n (fixed in its body frame for the step, as every rigid proximity point), the normal
   n, the gap d(c) - r. The candidates are the core's point (sphere), or the segment's two ends and,
   where the distance to the other shape is smallest inside the segment, that point (capsule: the
   distance to a convex shape is convex along a segment; a golden-section search finds it). A core
   point farther than the alarm distance is a speculative contact where its support point's motion
   over the step reaches the other shape (continuous detection, ccd.c). The key of a contact is its
   core point in the body frame, which does not move as the shape rolls: the warm start follows it.
   The smooth shape's bodies are on rank 0 (rigid and kinematic bodies are), so rank 0 makes these
   contacts. */
#include "collisionimpl.h"

#define FC_GOLDEN_IT 60 /* golden-section steps: the segment shrinks by 0.618^60, below round-off */

/* d of the other shape S at the core point t of the segment a + t (b - a) (world, now) */
static PetscErrorCode SegmentDistance(FCBody S, const PetscReal a[3], const PetscReal b[3], PetscReal t, PetscReal *d)
{
  PetscReal x[3], n[3], cp[3];

  PetscFunctionBegin;
  for (int i = 0; i < 3; i++) x[i] = a[i] + t * (b[i] - a[i]);
  PetscCall(FCBodyShapeDistance(S, FC_AT_NOW, x, d, n, cp));
  PetscFunctionReturn(0);
}

/* The contact of core point cb (body frame of P, the smooth shape of radius r) with shape S */
static PetscErrorCode CoreContact(FCBody P, FCBody S, PetscInt ip, PetscInt is, const PetscReal cb[3], PetscReal r,
                                  PetscInt pair, const FCContactPairs *pairs, PetscMPIInt rank, FCContactSet *set)
{
  FCProximity core = {0};
  FCContact   c;
  PetscReal   c0[3], cf[3], d, n[3], cpb[3], x0[3], xf[3], gap;

  PetscFunctionBegin;
  for (int i = 0; i < 3; i++) core.r[i] = cb[i];
  PetscCall(FCBodyProximityPosition(P, &core, FC_AT_NOW, c0));
  PetscCall(FCBodyProximityPosition(P, &core, FC_AT_FREE, cf));
  PetscCall(FCBodyShapeDistance(S, FC_AT_NOW, c0, &d, n, cpb));
  gap = d - r;
  for (int i = 0; i < 3; i++) { /* the support point: the smooth shape's point nearest S */
    x0[i] = c0[i] - r * n[i];
    xf[i] = cf[i] - r * n[i];
  }
  if (gap >= pairs->distance) { /* continuous: a speculative contact if the support point's motion reaches S */
    PetscBool hit = PETSC_FALSE;
    if (pairs->continuous) PetscCall(FCCCDPointShape(S, x0, xf, gap, FCCCDThreshold(pairs->distance), &hit));
    if (!hit) PetscFunctionReturn(0);
  }
  PetscCall(PetscMemzero(&c, sizeof(c)));
  c.pair    = pair;
  c.body[0] = ip;
  c.body[1] = is;
  PetscCall(FCBodyToBodyFrame(P, FC_AT_NOW, x0, PETSC_FALSE, c.prox[0].r));
  for (int i = 0; i < 3; i++) {
    c.prox[1].r[i] = cpb[i];
    c.key[i]       = cb[i];
    c.n[i]         = n[i];
    c.p0[0][i]     = x0[i];
  }
  PetscCall(FCBodyProximityPosition(P, &c.prox[0], FC_AT_FREE, c.pfree[0]));
  PetscCall(FCBodyProximityPosition(S, &c.prox[1], FC_AT_START, c.p0[1]));
  PetscCall(FCBodyProximityPosition(S, &c.prox[1], FC_AT_FREE, c.pfree[1]));
  c.gap0  = gap;
  c.mu    = pairs->mu[pair];
  c.owner = rank;
  c.side2 = FC_SIDE_SHAPE;
  PetscCall(FCContactSetAdd(set, &c));
  PetscFunctionReturn(0);
}

PetscErrorCode FCCollisionSmoothShape(FCBody P, FCBody S, PetscInt ip, PetscInt is, PetscInt pair,
                                      const FCContactPairs *pairs, PetscMPIInt rank, FCContactSet *set)
{
  PetscInt  ncore;
  PetscReal core[2][3], r;

  PetscFunctionBegin;
  if (rank) PetscFunctionReturn(0);
  FCBodyGetShapeCore(P, &ncore, core, &r);
  PetscCheck(ncore > 0, P->comm, PETSC_ERR_PLIB, "Body '%s' has no smooth shape", P->name);
  for (PetscInt k = 0; k < ncore; k++) PetscCall(CoreContact(P, S, ip, is, core[k], r, pair, pairs, rank, set));
  if (ncore == 2) { /* the segment's interior: where the distance to S is smallest, if not at an end */
    FCProximity e[2] = {{0}, {0}};
    PetscReal   a[3], b[3], lo = 0.0, hi = 1.0, g = 0.5 * (PetscSqrtReal(5.0) - 1.0), t1, t2, d1, d2, da, db;
    for (int i = 0; i < 3; i++) {
      e[0].r[i] = core[0][i];
      e[1].r[i] = core[1][i];
    }
    PetscCall(FCBodyProximityPosition(P, &e[0], FC_AT_NOW, a));
    PetscCall(FCBodyProximityPosition(P, &e[1], FC_AT_NOW, b));
    t1 = hi - g * (hi - lo);
    t2 = lo + g * (hi - lo);
    PetscCall(SegmentDistance(S, a, b, t1, &d1));
    PetscCall(SegmentDistance(S, a, b, t2, &d2));
    for (int it = 0; it < FC_GOLDEN_IT; it++) {
      if (d1 <= d2) {
        hi = t2;
        t2 = t1;
        d2 = d1;
        t1 = hi - g * (hi - lo);
        PetscCall(SegmentDistance(S, a, b, t1, &d1));
      } else {
        lo = t1;
        t1 = t2;
        d1 = d2;
        t2 = lo + g * (hi - lo);
        PetscCall(SegmentDistance(S, a, b, t2, &d2));
      }
    }
    t1 = 0.5 * (lo + hi);
    PetscCall(SegmentDistance(S, a, b, t1, &d1));
    PetscCall(SegmentDistance(S, a, b, 0.0, &da));
    PetscCall(SegmentDistance(S, a, b, 1.0, &db));
    /* inside the segment, and nearer than both ends by more than round-off (a capsule lying flat
       on a plane has its two ends: a third contact between them would only repeat them) */
    if (t1 > 0.01 && t1 < 0.99 && d1 < PetscMin(da, db) - 1e-9 * r) {
      PetscReal cb[3];
      for (int i = 0; i < 3; i++) cb[i] = core[0][i] + t1 * (core[1][i] - core[0][i]);
      PetscCall(CoreContact(P, S, ip, is, cb, r, pair, pairs, rank, set));
    }
  }
  PetscFunctionReturn(0);
}
