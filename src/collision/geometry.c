/* Closest-point, triangle and ray kernels of the collision detection (src/collision/collisionimpl.h). */
#include "collisionimpl.h"

void FCClosestPointTriangle(const PetscReal p[3], const PetscReal a[3], const PetscReal b[3], const PetscReal c[3],
                            PetscReal cp[3], PetscReal w[3])
{
  PetscReal ab[3], ac[3], ap[3], bp[3], cpv[3], d1, d2, d3, d4, d5, d6, va, vb, vc, v, t, den;
  for (int i = 0; i < 3; i++) {
    ab[i]  = b[i] - a[i];
    ac[i]  = c[i] - a[i];
    ap[i]  = p[i] - a[i];
    bp[i]  = p[i] - b[i];
    cpv[i] = p[i] - c[i];
  }
  d1 = FCDot(ab, ap);
  d2 = FCDot(ac, ap);
  d3 = FCDot(ab, bp);
  d4 = FCDot(ac, bp);
  d5 = FCDot(ab, cpv);
  d6 = FCDot(ac, cpv);
  vc = d1 * d4 - d3 * d2;
  vb = d5 * d2 - d1 * d6;
  va = d3 * d6 - d5 * d4;
  if (d1 <= 0 && d2 <= 0) {
    w[0] = 1;
    w[1] = 0;
    w[2] = 0;
  } else if (d3 >= 0 && d4 <= d3) {
    w[0] = 0;
    w[1] = 1;
    w[2] = 0;
  } else if (d6 >= 0 && d5 <= d6) {
    w[0] = 0;
    w[1] = 0;
    w[2] = 1;
  } else if (vc <= 0 && d1 >= 0 && d3 <= 0) {
    v    = d1 / (d1 - d3);
    w[0] = 1 - v;
    w[1] = v;
    w[2] = 0;
  } else if (vb <= 0 && d2 >= 0 && d6 <= 0) {
    t    = d2 / (d2 - d6);
    w[0] = 1 - t;
    w[1] = 0;
    w[2] = t;
  } else if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    t    = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    w[0] = 0;
    w[1] = 1 - t;
    w[2] = t;
  } else {
    den  = 1.0 / (va + vb + vc);
    w[1] = vb * den;
    w[2] = vc * den;
    w[0] = 1 - w[1] - w[2];
  }
  for (int i = 0; i < 3; i++) cp[i] = w[0] * a[i] + w[1] * b[i] + w[2] * c[i];
}

void FCTriangleNormal(const PetscReal x[3][3], PetscReal n[3])
{
  PetscReal e1[3], e2[3], l;
  for (int i = 0; i < 3; i++) {
    e1[i] = x[1][i] - x[0][i];
    e2[i] = x[2][i] - x[0][i];
  }
  FCCross(e1, e2, n);
  l = PetscSqrtReal(FCDot(n, n));
  for (int i = 0; i < 3; i++) n[i] /= l > 0 ? l : 1.0;
}

static PetscReal Clamp01(PetscReal x)
{
  return x < 0 ? 0 : (x > 1 ? 1 : x);
}

PetscReal FCClosestSegmentSegment(const PetscReal p0[3], const PetscReal p1[3], const PetscReal q0[3],
                                  const PetscReal q1[3], PetscReal *s, PetscReal *t)
{
  PetscReal d1[3], d2[3], r[3], a, e, f, c, b, den, dist2 = 0.0;
  for (int i = 0; i < 3; i++) {
    d1[i] = p1[i] - p0[i];
    d2[i] = q1[i] - q0[i];
    r[i]  = p0[i] - q0[i];
  }
  a = FCDot(d1, d1);
  e = FCDot(d2, d2);
  f = FCDot(d2, r);
  if (a <= PETSC_SMALL * PETSC_SMALL && e <= PETSC_SMALL * PETSC_SMALL) {
    *s = *t = 0.0;
  } else if (a <= PETSC_SMALL * PETSC_SMALL) {
    *s = 0.0;
    *t = Clamp01(f / e);
  } else {
    c = FCDot(d1, r);
    if (e <= PETSC_SMALL * PETSC_SMALL) {
      *t = 0.0;
      *s = Clamp01(-c / a);
    } else {
      b   = FCDot(d1, d2);
      den = a * e - b * b;
      *s  = den > 0 ? Clamp01((b * f - c * e) / den) : 0.0; /* parallel: any s, take 0 */
      *t  = (b * (*s) + f) / e;
      if (*t < 0) {
        *t = 0.0;
        *s = Clamp01(-c / a);
      } else if (*t > 1) {
        *t = 1.0;
        *s = Clamp01((b - c) / a);
      }
    }
  }
  for (int i = 0; i < 3; i++) {
    PetscReal x = p0[i] + (*s) * d1[i] - q0[i] - (*t) * d2[i];
    dist2 += x * x;
  }
  return dist2;
}

PetscBool FCRayHitsTriangle(const PetscReal x[3], const PetscReal dir[3], const PetscReal a[3], const PetscReal b[3],
                            const PetscReal c[3])
{
  PetscReal e1[3], e2[3], pv[3], tv[3], qv[3], det, u, v, s;
  for (int i = 0; i < 3; i++) {
    e1[i] = b[i] - a[i];
    e2[i] = c[i] - a[i];
    tv[i] = x[i] - a[i];
  }
  FCCross(dir, e2, pv);
  det = FCDot(e1, pv);
  if (det == 0.0) return PETSC_FALSE; /* the ray is parallel to the triangle's plane */
  u = FCDot(tv, pv) / det;
  if (u < 0.0 || u > 1.0) return PETSC_FALSE;
  FCCross(tv, e1, qv);
  v = FCDot(dir, qv) / det;
  if (v < 0.0 || u + v > 1.0) return PETSC_FALSE;
  s = FCDot(e2, qv) / det;
  return s > 0.0 ? PETSC_TRUE : PETSC_FALSE;
}

/* X = X_0 + sum_{a >= 1} w_a (X_a - X_0): the point at weights w of nv reference positions, the
   key that sorts a contact on a triangle or an edge (FCContactSetGather). From the first vertex,
   a coordinate the vertices share (x = 0.5 on a cube's face) is exact, not 0.5 give or take an ulp
   that would reorder the contacts with the round-off of the weights, and with them the sweeps: a
   restarted run then left the uninterrupted one at the solver's tolerance */
void FCReferencePoint(PetscInt nv, const PetscReal Xv[][3], const PetscReal w[], PetscReal X[3])
{
  for (int k = 0; k < 3; k++) {
    X[k] = Xv[0][k];
    for (PetscInt a = 1; a < nv; a++) X[k] += w[a] * (Xv[a][k] - Xv[0][k]);
  }
}

int FCComparePoint(const void *a, const void *b)
{
  const PetscReal *x = (const PetscReal *)a, *y = (const PetscReal *)b;
  for (int i = 0; i < 3; i++)
    if (x[i] != y[i]) return x[i] < y[i] ? -1 : 1;
  return 0;
}

PetscErrorCode FCGoldenMinimum(PetscErrorCode (*f)(PetscReal, void *, PetscReal *), void *ctx, PetscReal *t)
{
  PetscReal lo = 0.0, hi = 1.0, g = 0.5 * (PetscSqrtReal(5.0) - 1.0), t1, t2, d1, d2;

  PetscFunctionBegin;
  t1 = hi - g * (hi - lo);
  t2 = lo + g * (hi - lo);
  PetscCall((*f)(t1, ctx, &d1));
  PetscCall((*f)(t2, ctx, &d2));
  for (int it = 0; it < FC_GOLDEN_IT; it++) {
    if (d1 <= d2) {
      hi = t2;
      t2 = t1;
      d2 = d1;
      t1 = hi - g * (hi - lo);
      PetscCall((*f)(t1, ctx, &d1));
    } else {
      lo = t1;
      t1 = t2;
      d1 = d2;
      t2 = lo + g * (hi - lo);
      PetscCall((*f)(t2, ctx, &d2));
    }
  }
  *t = 0.5 * (lo + hi);
  PetscFunctionReturn(0);
}

/* The distance from world point y to the side of a cylinder of radius r whose axis runs from a along the unit vector
   u for a length L, where y is against the side: its foot on the axis within the segment, and, given the outward
   normal nv of the surface y lies on, that surface facing the side more than an end face (|nv . radial| >= |nv . u|:
   a surface under a cylinder lying on it, where a point just inside a rim is as near the end face); without nv, y
   outside the radius or nearer the side than either end face. *side false otherwise (the shape's own distance decides:
   an end face, a rim, the axis) */
void FCCylinderSideDistance(const PetscReal a[3], const PetscReal u[3], PetscReal L, PetscReal r, const PetscReal y[3],
                            const PetscReal nv[3], PetscReal *d, PetscReal n[3], PetscBool *side)
{
  PetscReal v[3], s, l;

  for (int i = 0; i < 3; i++) v[i] = y[i] - a[i];
  s = FCDot(v, u);
  for (int i = 0; i < 3; i++) v[i] -= s * u[i];
  l     = PetscSqrtReal(FCDot(v, v));
  *side = (PetscBool)(s >= 0.0 && s <= L && l > 0.0);
  if (*side && nv)
    *side = (PetscBool)(PetscAbsReal(FCDot(nv, v)) >= l * PetscAbsReal(FCDot(nv, u)));
  else if (*side)
    *side = (PetscBool)(l >= r || r - l <= PetscMin(s, L - s));
  if (!*side) return;
  *d = l - r;
  for (int i = 0; i < 3; i++) n[i] = v[i] / l;
}

/* The point of the triangle with vertices at x (reference positions Xr) nearest the world point c: its weights w
   and the number of them above 0 (1 a vertex, 2 an edge, 3 the face). An edge point is recomputed from the
   edge alone, its ends in reference order, so that the two triangles of the edge give the same
   point to the bit, and X its reference position (the key) from the edge alone too. */
#define FC_FEATURE_EPS 1e-9
PetscInt FCTriangleNearestFeature(const PetscReal x[3][3], const PetscReal Xr[3][3], const PetscReal c[3],
                                  PetscReal w[3], PetscReal X[3])
{
  PetscReal cp[3];
  PetscInt  nz = 0, e[3] = {0, 0, 0};

  FCClosestPointTriangle(c, x[0], x[1], x[2], cp, w);
  { /* a weight within round-off of 0 is 0: the point is on the edge or at the vertex */
    PetscReal sum = 0.0;
    for (int a = 0; a < 3; a++) {
      if (w[a] < FC_FEATURE_EPS) w[a] = 0.0;
      sum += w[a];
    }
    for (int a = 0; a < 3; a++) w[a] /= sum;
  }
  for (int a = 0; a < 3; a++)
    if (w[a] > 0.0) e[nz++] = a;
  if (nz == 2) {
    PetscInt  a = e[0], b = e[1], o = 3 - a - b;
    PetscReal ab[3], ac[3], t;
    if (FCComparePoint(Xr[a], Xr[b]) > 0) {
      a = e[1];
      b = e[0];
    }
    for (int i = 0; i < 3; i++) {
      ab[i] = x[b][i] - x[a][i];
      ac[i] = c[i] - x[a][i];
    }
    t    = PetscMin(1.0, PetscMax(0.0, FCDot(ac, ab) / FCDot(ab, ab)));
    w[a] = 1.0 - t;
    w[b] = t;
    w[o] = 0.0;
    {
      const PetscReal Xe[2][3] = {{Xr[a][0], Xr[a][1], Xr[a][2]}, {Xr[b][0], Xr[b][1], Xr[b][2]}}, we[2] = {1.0 - t, t};
      FCReferencePoint(2, Xe, we, X);
    }
    if (t == 0.0 || t == 1.0) return 1; /* an end of the edge */
  } else
    FCReferencePoint(3, Xr, w, X);
  return nz;
}

/* The distance from the world point x to the triangle with vertices at t */
PetscReal FCTriangleDistance(const PetscReal t[3][3], const PetscReal x[3])
{
  PetscReal cp[3], w[3], d2 = 0.0;
  FCClosestPointTriangle(x, t[0], t[1], t[2], cp, w);
  for (int i = 0; i < 3; i++) d2 += PetscSqr(x[i] - cp[i]);
  return PetscSqrtReal(d2);
}
