/* The candidate points of one body against the signed distance of another body's analytic shape (called by
   FCCollisionDetect, collision.c) */
#include "collisionimpl.h"

/* The contact of FE vertex x0 -> xf (prox: its proximity) against the rounded shape S (-contact_rounded_surface exact,
   the shape's surface points taken after the free motion: FCCollisionRoundedFollows), taken as the surface points of
   roundedsurface.c are: the normal the shape's at the vertex after the free motion, the shape's point the one along
   it from the core's nearest point at the start (no moment about the core), the gap the solver starts from the
   shape's exact distance after the free motion (qcurv). Linearized at the start instead, the contact of a vertex
   just ahead of a rolling ball or cylinder is the plane tangent to the shape there, which the shape's forward motion
   runs into: a vertical kick and a brake at each vertex it rolls over. */
static PetscErrorCode VertexAtFree(FCBody S, const PetscReal x0[3], const PetscReal xf[3], const PetscReal nv[3],
                                   FCContact *c)
{
  PetscInt    ncore;
  PetscReal   core[2][3], r, df, cpf[3], cw[3], cb[3], p2[3], dfree[3];
  PetscBool   flat;
  FCProximity q = {0};

  PetscFunctionBegin;
  FCBodyGetShapeCore(S, &ncore, core, &r, &flat);
  PetscCall(FCBodyShapeDistance(S, FC_AT_FREE, xf, &df, c->n, cpf));
  { /* the core's point nearest the vertex after the free motion (body frame) */
    PetscReal fr[2][3], t = 0.0;
    for (PetscInt k = 0; k < ncore; k++) {
      for (int i = 0; i < 3; i++) q.r[i] = core[k][i];
      PetscCall(FCBodyProximityPosition(S, &q, FC_AT_FREE, fr[k]));
    }
    if (ncore == 2) {
      PetscReal ab[3], ay[3];
      for (int i = 0; i < 3; i++) {
        ab[i] = fr[1][i] - fr[0][i];
        ay[i] = xf[i] - fr[0][i];
      }
      t = FCDot(ay, ab) / FCDot(ab, ab);
      if (flat) { /* a cylinder: where its side is nearest, the side's own distance (its normal radial at the rims,
                     where the end faces are as near and sideways) */
        PetscReal L = PetscSqrtReal(FCDot(ab, ab)), u[3], ds, ns[3];
        PetscBool side;
        for (int i = 0; i < 3; i++) u[i] = ab[i] / L;
        FCCylinderSideDistance(fr[0], u, L, r, xf, nv, &ds, ns, &side);
        if (side) {
          df = ds;
          for (int i = 0; i < 3; i++) c->n[i] = ns[i];
        }
      }
      t = PetscMin(1.0, PetscMax(0.0, t));
    }
    for (int i = 0; i < 3; i++) cw[i] = ncore == 2 ? fr[0][i] + t * (fr[1][i] - fr[0][i]) : fr[0][i];
    PetscCall(FCBodyToBodyFrame(S, FC_AT_FREE, cw, PETSC_FALSE, cb));
  }
  for (int i = 0; i < 3; i++) q.r[i] = cb[i];
  PetscCall(FCBodyProximityPosition(S, &q, FC_AT_NOW, p2));
  for (int i = 0; i < 3; i++) p2[i] += r * c->n[i];
  PetscCall(FCBodyToBodyFrame(S, FC_AT_NOW, p2, PETSC_FALSE, c->prox[1].r));
  for (int i = 0; i < 3; i++) {
    c->p0[0][i]    = x0[i];
    c->pfree[0][i] = xf[i];
  }
  PetscCall(FCBodyProximityPosition(S, &c->prox[1], FC_AT_START, c->p0[1]));
  PetscCall(FCBodyProximityPosition(S, &c->prox[1], FC_AT_FREE, c->pfree[1]));
  for (int i = 0; i < 3; i++) dfree[i] = c->pfree[0][i] - c->pfree[1][i];
  c->qcurv = df - FCDot(c->n, dfree);
  PetscFunctionReturn(0);
}

/* Whether the world point x is over the face of S (at `when`) whose plane is (point cb, outward normal nb, body frame):
   its projection on the plane, moved out by eps, is nearest that plane (not an edge or another face) */
static PetscErrorCode OverFace(FCBody S, PetscInt when, const PetscReal x[3], const PetscReal cb[3],
                               const PetscReal nb[3], PetscReal eps, PetscBool *over)
{
  PetscReal xb[3], rel[3], h, nw[3], q[3], dq, nq[3], cq[3];

  PetscFunctionBegin;
  PetscCall(FCBodyToBodyFrame(S, when, x, PETSC_FALSE, xb));
  for (int k = 0; k < 3; k++) rel[k] = xb[k] - cb[k];
  h = FCDot(rel, nb);
  PetscCall(FCCollisionBodyDirection(S, when, nb, nw));
  for (int k = 0; k < 3; k++) q[k] = x[k] - (h - eps) * nw[k];
  PetscCall(FCBodyShapeDistance(S, when, q, &dq, nq, cq));
  *over = PetscAbsReal(dq - eps) < 0.5 * eps && FCDot(nq, nw) > 0.999 ? PETSC_TRUE : PETSC_FALSE;
  PetscFunctionReturn(0);
}

/* the cosine of 1 degree: a vertex's contact whose normal is further than this from opposed to the vertex's own is at
   an edge or a side of the shape (FacingFace) */
#define FC_FACE_COS 0.9998476951563913
/* the cosine of 10 degrees: the face of a shape that a vertex takes instead lies within this of parallel to the
   vertex's own surface (a box flat on a slab, not a box's face pushing a curved body at an angle) */
#define FC_PARALLEL_FACE_COS 0.984807753012208

/* A vertex x0 -> xf (own outward normal nv) near an edge or a side of the shape S, its nearest feature's normal n more
   than a degree from facing it (a slab vertex at the front edge of a box sliding over it), takes instead the face of
   S that faces it, where it is over that face at the start or after the free motion: the face nearest the point
   c - R nv (c the shape's centre, R beyond its reach), whose outward normal is opposed to nv within 10 degrees; the
   contact is against that face's plane, at the point of the plane under x0, with the depth of x0 below it as its gap.
   Otherwise d, n and cpb stay. Along the edge's or the front face's normal the contact would be a wall across the
   sliding motion: the box snags on the vertex and hops. */
static PetscErrorCode FacingFace(FCBody S, const PetscReal x0[3], const PetscReal xf[3], const PetscReal nv[3],
                                 PetscReal eps, PetscReal *d, PetscReal n[3], PetscReal cpb[3])
{
  FCProximity o = {0};
  PetscReal   c[3], R, y[3], dy, ny[3], cb[3], nb[3], xb[3], h, rel[3];
  PetscBool   over0, overf;

  PetscFunctionBegin;
  if (!(eps > 0.0)) PetscFunctionReturn(0);
  PetscCall(FCBodyProximityPosition(S, &o, FC_AT_NOW, c));
  for (int k = 0; k < 3; k++) rel[k] = x0[k] - c[k];
  R = 2.0 * PetscSqrtReal(FCDot(rel, rel)) + eps;
  for (int k = 0; k < 3; k++) y[k] = c[k] - R * nv[k];
  PetscCall(FCBodyShapeDistance(S, FC_AT_NOW, y, &dy, ny, cb));
  if (!(dy > 0.0) || FCDot(ny, nv) > -FC_PARALLEL_FACE_COS) PetscFunctionReturn(0);
  PetscCall(FCBodyToBodyFrame(S, FC_AT_NOW, ny, PETSC_TRUE, nb));
  PetscCall(OverFace(S, FC_AT_NOW, x0, cb, nb, eps, &over0));
  PetscCall(OverFace(S, FC_AT_FREE, xf, cb, nb, eps, &overf));
  if (!over0 && !overf) PetscFunctionReturn(0);
  PetscCall(FCBodyToBodyFrame(S, FC_AT_NOW, x0, PETSC_FALSE, xb));
  for (int k = 0; k < 3; k++) rel[k] = xb[k] - cb[k];
  h  = FCDot(rel, nb);
  *d = h;
  for (int k = 0; k < 3; k++) {
    n[k]   = ny[k];
    cpb[k] = xb[k] - h * nb[k];
  }
  PetscFunctionReturn(0);
}

/* The candidate points of P (an FE body's owned boundary vertices, a shape's picture points)
   against the signed distance of the shape of S. With vn (-contact_facing; the vertex normals of
   an FE P's surface), a vertex outside the shape whose closest point's normal is within 75 degrees
   of square to its own (|n . n_v| < FC_FACING_COS: a box's side face or rim seen by a slab vertex
   just ahead of the box as it slides) is not a contact: a constraint along that normal would be a
   wall across the sliding motion; a vertex that then moves inside is taken by the face it entered
   under. (A vertex whose surface faces away from the shape, n . n_v > 0 beyond that band, belongs to
   a body the shape has crossed, a discrete step into a thin plate: it keeps its contact, which holds
   it on the side it is on.) */
PetscErrorCode FCCollisionPointsAgainstShape(FCBody P, FCBody S, PetscInt ipts, PetscInt ishp, PetscInt p, PetscInt nvn,
                                             const FCVertexNormal *vn, PetscBool atfree, const FCContactPairs *pairs,
                                             PetscMPIInt rank, FCContactSet *set)
{
  PetscInt     n;
  FCProximity *prox;
  PetscReal   *x0, *xf, *key, tau = FCCCDThreshold(pairs->distance);

  PetscFunctionBegin;
  PetscCall(FCBodyGetContactPoints(P, &n, &prox, &x0, &xf, &key));
  for (PetscInt i = 0; i < n; i++) {
    PetscReal             d, nrm[3], cpb[3];
    FCContact             c;
    const FCVertexNormal *own;
    PetscCall(FCBodyShapeDistance(S, FC_AT_NOW, &x0[3 * i], &d, nrm, cpb));
    own = NULL; /* the vertex's own outward normal (with -contact_facing) */
    if (vn && prox[i].nv == 1) {
      FCVertexNormal key1;
      for (int k = 0; k < 3; k++) key1.X[k] = prox[i].X[0][k];
      own = (const FCVertexNormal *)bsearch(&key1, vn, nvn, sizeof(FCVertexNormal), FCComparePoint);
    }
    if (d >= pairs->distance) { /* continuous: a speculative contact if the motion reaches the shape */
      PetscBool hit = PETSC_FALSE;
      if (pairs->continuous) PetscCall(FCCCDPointShape(S, &x0[3 * i], &xf[3 * i], d, tau, &hit));
      if (!hit) continue;
    }
    if (own && pairs->facing_face && FCBodyHasBoundedShape(S) && FCDot(nrm, own->n) > -FC_FACE_COS)
      PetscCall(FacingFace(S, &x0[3 * i], &xf[3 * i], own->n, 1e-3 * pairs->distance, &d, nrm, cpb));
    if (own && d > 0.0 && PetscAbsReal(FCDot(nrm, own->n)) < FC_FACING_COS) continue;
    PetscCall(PetscMemzero(&c, sizeof(c)));
    c.pair    = p;
    c.body[0] = ipts;
    c.body[1] = ishp;
    c.prox[0] = prox[i];
    for (int k = 0; k < 3; k++) {
      c.prox[1].r[k] = cpb[k];
      c.key[k]       = key[3 * i + k];
      c.n[k]         = nrm[k];
      c.p0[0][k]     = x0[3 * i + k];
      c.pfree[0][k]  = xf[3 * i + k];
    }
    PetscCall(FCBodyProximityPosition(S, &c.prox[1], FC_AT_START, c.p0[1]));
    PetscCall(FCBodyProximityPosition(S, &c.prox[1], FC_AT_FREE, c.pfree[1]));
    if (atfree) PetscCall(VertexAtFree(S, &x0[3 * i], &xf[3 * i], own ? own->n : NULL, &c));
    c.gap0  = d;
    c.mu    = pairs->mu[p];
    c.owner = rank;
    PetscCall(FCContactSetAdd(set, &c));
  }
  PetscFunctionReturn(0);
}
