/* Continuous narrow phase (docs/method.md, section 2.2): does a feature pair come into contact
   during the step? Every point moves linearly from its start to its free-motion position (the
   only motion of the step the detection knows), and the test is conservative advancement
   (Mirtich): with d(t) the distance of the pair at time t and V a bound on how fast it can
   shrink (|d'(t)| <= V), no time in [t, t + (d(t) - tau/2) / V] can bring the pair closer than
   tau/2, so the root finder steps over it. It never misses a crossing (the distance of a
   crossing pair goes to 0); a pair that only passes within tau is a hit too, and costs an
   inactive (speculative) constraint. A pair that needs more than FC_CCD_MAX_IT steps (a long
   graze at about tau) is reported as a hit, for the same reason. */
#include "collisionimpl.h"

#define FC_CCD_MAX_IT 64

PetscReal FCCCDThreshold(PetscReal distance)
{
  /* -contact_distance 0 still needs a positive threshold to stop on: 1 nm (scenes are in metres) */
  return distance > 0 ? 0.1 * distance : 1e-9;
}

PetscErrorCode FCCCDArcMargin(FCBody b, PetscInt ntri, const FCSurfaceTriangle *tri, PetscReal *margin)
{
  PetscReal theta, c[3], rho2 = 0.0;

  PetscFunctionBegin;
  *margin = 0.0;
  if (FCBodyIsDeformable(b)) PetscFunctionReturn(0);
  PetscCall(FCBodyStepRotation(b, &theta, c));
  if (theta <= 0.0) PetscFunctionReturn(0);
  for (PetscInt t = 0; t < ntri; t++)
    for (int a = 0; a < 3; a++) {
      PetscReal d2 = 0.0;
      for (int i = 0; i < 3; i++) d2 += PetscSqr(tri[t].X[a][i] - c[i]);
      rho2 = PetscMax(rho2, d2);
    }
  *margin = PetscSqrtReal(rho2) * theta * theta / 8.0;
  PetscFunctionReturn(0);
}

/* A point against an analytic shape. In the shape's frame the point moves from its start-of-step
   body-frame position r0 to its free-motion one rf; the test follows the chord r0 -> rf, whose
   distance to the shape is 1-Lipschitz with speed V = |rf - r0|. The true path is the chord only
   for a translating shape: when the shape turns by theta over the step about the body-frame
   point c (its centre, or a kinematic body's -pivot), the point, moving linearly in the world,
   follows r(t) = Q(t) (y0 + t dy) - c with y0 = r0 - c, |dy| <= |rf - r0| + theta |rf - c|, and
   Q(t) the rotation by t theta; it leaves the chord by at most
       e = |y0| theta^2 / 8 + theta |dy| / 4
   (the sagitta of the arc of radius |y0|, plus t (1 - t) theta |dy|). So a chord that comes within
   tau + 2 e is a hit: the true path may come within tau (a point on the orbit of a fast kinematic
   body that the chord cuts inside, input/hard/orbit.opts). d0 is the signed distance at the start
   (already computed by the discrete test). */
PetscErrorCode FCCCDPointShape(FCBody S, const PetscReal x0[3], const PetscReal xf[3], PetscReal d0, PetscReal tau,
                               PetscBool *hit)
{
  PetscReal r0[3], rf[3], dr[3], c[3], y0[3], yf[3], theta, L, t = 0.0, d = d0;

  PetscFunctionBegin;
  *hit = d0 <= tau ? PETSC_TRUE : PETSC_FALSE;
  if (*hit) PetscFunctionReturn(0);
  PetscCall(FCBodyToBodyFrame(S, FC_AT_NOW, x0, PETSC_FALSE, r0));
  PetscCall(FCBodyToBodyFrame(S, FC_AT_FREE, xf, PETSC_FALSE, rf));
  PetscCall(FCBodyStepRotation(S, &theta, c));
  for (int i = 0; i < 3; i++) {
    dr[i] = rf[i] - r0[i];
    y0[i] = r0[i] - c[i];
    yf[i] = rf[i] - c[i];
  }
  L = PetscSqrtReal(FCDot(dr, dr));
  if (theta > 0.0) { /* the arc's departure from the chord widens the threshold */
    PetscReal dy = L + theta * PetscSqrtReal(FCDot(yf, yf));
    tau += 2.0 * (PetscSqrtReal(FCDot(y0, y0)) * theta * theta / 8.0 + theta * dy / 4.0);
    if (d0 <= tau) {
      *hit = PETSC_TRUE;
      PetscFunctionReturn(0);
    }
  }
  /* a non-finite free motion is no motion to follow: the end-of-step state check reports it */
  if (!PetscIsNormalReal(L) || d0 - 0.5 * tau >= L) PetscFunctionReturn(0); /* out of reach in this step */
  for (int it = 0; it < FC_CCD_MAX_IT; it++) {
    PetscReal r[3], n[3], cp[3];
    t += (d - 0.5 * tau) / L;
    if (t > 1.0) PetscFunctionReturn(0);
    for (int i = 0; i < 3; i++) r[i] = r0[i] + t * dr[i];
    PetscCall(FCBodyShapeDistanceLocal(S, r, &d, n, cp));
    if (d <= tau) break;
  }
  *hit = PETSC_TRUE; /* a hit, or the iterations ran out (conservative) */
  PetscFunctionReturn(0);
}

/* The largest relative displacement over the step between a point of one feature and a point of
   the other: both are convex combinations of their vertices, so the largest over vertex pairs
   bounds it, and with it |d'(t)|. Features are flat arrays of n vertices (3 n values). */
static PetscReal RelativeSpeed(PetscInt na, const PetscReal *a0, const PetscReal *af, PetscInt nb, const PetscReal *b0,
                               const PetscReal *bf)
{
  PetscReal v = 0.0;
  for (PetscInt i = 0; i < na; i++)
    for (PetscInt j = 0; j < nb; j++) {
      PetscReal w2 = 0.0;
      for (int d = 0; d < 3; d++) w2 += PetscSqr((af[3 * i + d] - a0[3 * i + d]) - (bf[3 * j + d] - b0[3 * j + d]));
      v = PetscMax(v, w2);
    }
  return PetscSqrtReal(v);
}

static void Lerp(PetscInt n, const PetscReal *x0, const PetscReal *xf, PetscReal t, PetscReal *x)
{
  for (PetscInt i = 0; i < 3 * n; i++) x[i] = x0[i] + t * (xf[i] - x0[i]);
}

/* The advancement loop shared by the two feature tests: dist(t) is evaluated by `kind` (0: point
   p against triangle a, 1: edge p against edge a) */
static PetscBool Advance(int kind, const PetscReal *p0, const PetscReal *pf, const PetscReal *a0, const PetscReal *af,
                         PetscReal tau, PetscReal *thit)
{
  PetscInt  np = kind == 0 ? 1 : 2, na = kind == 0 ? 3 : 2;
  PetscReal V = RelativeSpeed(np, p0, pf, na, a0, af), t = 0.0;

  if (V != 0.0 && !PetscIsNormalReal(V)) return PETSC_FALSE; /* non-finite free motion: see FCCCDPointShape */
  for (int it = 0; it < FC_CCD_MAX_IT; it++) {
    PetscReal p[6], a[9], d;
    Lerp(np, p0, pf, t, p);
    Lerp(na, a0, af, t, a);
    if (kind == 0) {
      PetscReal cp[3], w[3], d2 = 0.0;
      FCClosestPointTriangle(p, &a[0], &a[3], &a[6], cp, w);
      for (int i = 0; i < 3; i++) d2 += PetscSqr(p[i] - cp[i]);
      d = PetscSqrtReal(d2);
    } else {
      PetscReal s, u;
      d = PetscSqrtReal(FCClosestSegmentSegment(&p[0], &p[3], &a[0], &a[3], &s, &u));
    }
    if (d <= tau) {
      *thit = t;
      return PETSC_TRUE;
    }
    if (V <= 0.0) return PETSC_FALSE; /* no relative motion: the start decides */
    t += (d - 0.5 * tau) / V;
    if (t > 1.0) return PETSC_FALSE;
  }
  *thit = t; /* out of iterations: conservative */
  return PETSC_TRUE;
}

PetscBool FCCCDPointTriangle(const PetscReal p0[3], const PetscReal pf[3], const PetscReal a0[3][3],
                             const PetscReal af[3][3], PetscReal tau, PetscReal *thit)
{
  return Advance(0, p0, pf, &a0[0][0], &af[0][0], tau, thit);
}

PetscBool FCCCDEdgeEdge(const PetscReal *a0, const PetscReal *af, const PetscReal *b0, const PetscReal *bf,
                        PetscReal tau, PetscReal *thit)
{
  return Advance(1, a0, af, b0, bf, tau, thit);
}

/* The exact crossing tests of the crossing audit (crossing.c): every point moving linearly over the step, the times
   where four points become coplanar are the roots of a cubic in t */
/* the value of the cubic c at t */
static inline PetscReal Cubic(const PetscReal c[4], PetscReal t)
{
  return ((c[3] * t + c[2]) * t + c[1]) * t + c[0];
}

/* The cubic f(t) = n(t) . q(t) with n(t) = u(t) x v(t): u, v, q linear in t (u0 + t du, ...) */
static void TripleCubic(const PetscReal u0[3], const PetscReal du[3], const PetscReal v0[3], const PetscReal dv[3],
                        const PetscReal q0[3], const PetscReal dq[3], PetscReal c[4])
{
  PetscReal n0[3], n1[3], n2[3], a[3], b[3];

  FCCross(u0, v0, n0);
  FCCross(u0, dv, a);
  FCCross(du, v0, b);
  for (int d = 0; d < 3; d++) n1[d] = a[d] + b[d];
  FCCross(du, dv, n2);
  c[0] = FCDot(n0, q0);
  c[1] = FCDot(n1, q0) + FCDot(n0, dq);
  c[2] = FCDot(n2, q0) + FCDot(n1, dq);
  c[3] = FCDot(n2, dq);
}

/* The times in [0, 1] where the cubic c changes sign (down: only from + to -), earliest first, each
   to round-off: [0, 1] is split where c' = 0 into pieces on which c is monotone, and a piece whose
   ends have opposite signs is bisected. At most 3. */
static PetscInt SignChanges(const PetscReal c[4], PetscBool down, PetscReal roots[3])
{
  PetscReal br[4] = {0.0, 1.0, 1.0, 1.0}, A = 3.0 * c[3], B = 2.0 * c[2], C = c[1];
  PetscInt  nb = 1, nr = 0;

  if (A != 0.0) {
    PetscReal disc = B * B - 4.0 * A * C;
    if (disc > 0.0) {
      PetscReal s = PetscSqrtReal(disc), q = -0.5 * (B + (B >= 0 ? s : -s)), t1 = q / A, t2 = q != 0.0 ? C / q : t1;
      if (t1 > t2) {
        PetscReal w = t1;
        t1          = t2;
        t2          = w;
      }
      if (t1 > 0.0 && t1 < 1.0) br[nb++] = t1;
      if (t2 > 0.0 && t2 < 1.0 && t2 != t1) br[nb++] = t2;
    }
  } else if (B != 0.0) {
    PetscReal t1 = -C / B;
    if (t1 > 0.0 && t1 < 1.0) br[nb++] = t1;
  }
  br[nb++] = 1.0;
  for (PetscInt i = 0; i + 1 < nb; i++) {
    PetscReal lo = br[i], hi = br[i + 1], flo = Cubic(c, lo), fhi = Cubic(c, hi);
    if (!(flo > 0.0 && fhi <= 0.0) && (down || !(flo < 0.0 && fhi >= 0.0))) continue;
    for (int it = 0; it < 60; it++) {
      PetscReal mid = 0.5 * (lo + hi), fm = Cubic(c, mid);
      if ((fm > 0.0) == (flo > 0.0)) {
        lo  = mid;
        flo = fm;
      } else
        hi = mid;
    }
    roots[nr++] = hi;
  }
  return nr;
}

/* Whether the triangle a (at some time of the step; a0 at its start, a1 at its end) faces the way it did at both ends,
   with at least a tenth of the smaller of their areas: one that turns over (an element inside out) changes the side a
   point is on without the point going through it */
static void AreaVector(const PetscReal a[3][3], PetscReal n[3])
{
  PetscReal u[3], v[3];
  for (int d = 0; d < 3; d++) {
    u[d] = a[1][d] - a[0][d];
    v[d] = a[2][d] - a[0][d];
  }
  FCCross(u, v, n);
}

static PetscBool Keeps(const PetscReal a0[3][3], const PetscReal a1[3][3], const PetscReal a[3][3])
{
  PetscReal n0[3], n1[3], n[3], m0, m1, m;

  AreaVector(a0, n0);
  AreaVector(a1, n1);
  AreaVector(a, n);
  m0 = PetscSqrtReal(FCDot(n0, n0));
  m1 = PetscSqrtReal(FCDot(n1, n1));
  m  = PetscSqrtReal(FCDot(n, n));
  return FCDot(n, n0) > 0.0 && FCDot(n, n1) > 0.0 && m >= 0.1 * PetscMin(m0, m1) ? PETSC_TRUE : PETSC_FALSE;
}

/* Whether the point p0 -> p1 passes through the triangle a0 -> a1 (corners, start and end) from its outer side to its
   inner side during the step; *behind: how far the point ends behind the triangle's plane */
PetscBool FCCCDPointCrossesTriangle(const PetscReal p0[3], const PetscReal p1[3], const PetscReal a0[3][3],
                                    const PetscReal a1[3][3], PetscReal *behind)
{
  PetscReal u0[3], du[3], v0[3], dv[3], q0[3], dq[3], c[4], roots[3], n1[3];
  PetscInt  nr;

  for (int d = 0; d < 3; d++) {
    u0[d] = a0[1][d] - a0[0][d];
    du[d] = a1[1][d] - a1[0][d] - u0[d];
    v0[d] = a0[2][d] - a0[0][d];
    dv[d] = a1[2][d] - a1[0][d] - v0[d];
    q0[d] = p0[d] - a0[0][d];
    dq[d] = p1[d] - a1[0][d] - q0[d];
  }
  TripleCubic(u0, du, v0, dv, q0, dq, c);
  {
    PetscReal u1[3], v1[3];
    for (int d = 0; d < 3; d++) {
      u1[d] = u0[d] + du[d];
      v1[d] = v0[d] + dv[d];
    }
    FCCross(u1, v1, n1);
  }
  *behind = -Cubic(c, 1.0) / PetscMax(PetscSqrtReal(FCDot(n1, n1)), PETSC_SMALL * PETSC_SMALL);
  if (!(c[0] > 0.0)) return PETSC_FALSE; /* starts in the plane or behind it */
  nr = SignChanges(c, PETSC_TRUE, roots);
  for (PetscInt r = 0; r < nr; r++) {
    PetscReal p[3], a[3][3], cp[3], w[3], d2 = 0.0, L2 = 0.0;
    Lerp(1, p0, p1, roots[r], p);
    for (int k = 0; k < 3; k++) Lerp(1, a0[k], a1[k], roots[r], a[k]);
    if (!Keeps(a0, a1, a)) continue; /* a triangle turning over, not a point going through it */
    FCClosestPointTriangle(p, a[0], a[1], a[2], cp, w);
    for (int d = 0; d < 3; d++) {
      d2 += PetscSqr(p[d] - cp[d]);
      for (int k = 0; k < 3; k++) L2 = PetscMax(L2, PetscSqr(a[(k + 1) % 3][d] - a[k][d]));
    }
    if (d2 <= 1e-12 * 3.0 * L2) return PETSC_TRUE;
  }
  return PETSC_FALSE;
}

/* Whether the segments a (ends a0[0], a0[1] at the start, a1[] at the end) and b meet during the step */
PetscBool FCCCDEdgesMeet(const PetscReal a0[2][3], const PetscReal a1[2][3], const PetscReal b0[2][3],
                         const PetscReal b1[2][3])
{
  PetscReal u0[3], du[3], v0[3], dv[3], q0[3], dq[3], c[4], roots[3];
  PetscInt  nr;

  for (int d = 0; d < 3; d++) {
    u0[d] = a0[1][d] - a0[0][d];
    du[d] = a1[1][d] - a1[0][d] - u0[d];
    v0[d] = b0[1][d] - b0[0][d];
    dv[d] = b1[1][d] - b1[0][d] - v0[d];
    q0[d] = b0[0][d] - a0[0][d];
    dq[d] = b1[0][d] - a1[0][d] - q0[d];
  }
  TripleCubic(u0, du, v0, dv, q0, dq, c);
  nr = SignChanges(c, PETSC_FALSE, roots);
  for (PetscInt r = 0; r < nr; r++) {
    PetscReal pa[2][3], pb[2][3], s, t, L2 = 0.0;
    for (int k = 0; k < 2; k++) {
      Lerp(1, a0[k], a1[k], roots[r], pa[k]);
      Lerp(1, b0[k], b1[k], roots[r], pb[k]);
    }
    for (int d = 0; d < 3; d++)
      L2 = PetscMax(L2, PetscMax(PetscSqr(pa[1][d] - pa[0][d]), PetscSqr(pb[1][d] - pb[0][d])));
    if (FCClosestSegmentSegment(pa[0], pa[1], pb[0], pb[1], &s, &t) <= 1e-12 * 3.0 * L2) return PETSC_TRUE;
  }
  return PETSC_FALSE;
}
