/* The contacts' gaps at the end of the step, on the real geometry (docs/output.md: gap_end, n_end, d_end,
   p_end): a point against a shape by the shape's signed distance now; against an FE triangle or edge along
   the triangle's (or the edges') end-of-step normal, with the vertices summed over the ranks that own them, or,
   face to face with a rigid shape's face (c->face1), along that face's turned normal; against a rigid mesh's
   triangle along its rotated normal. */
#include "collisionimpl.h"

PetscErrorCode FCCollisionBodyDirection(FCBody B, PetscInt when, const PetscReal nb[3], PetscReal n[3])
{
  FCProximity o = {0}, e = {0};
  PetscReal   p0[3], pe[3];

  PetscFunctionBegin;
  for (int d = 0; d < 3; d++) e.r[d] = nb[d];
  PetscCall(FCBodyProximityPosition(B, &o, when, p0));
  PetscCall(FCBodyProximityPosition(B, &e, when, pe));
  for (int d = 0; d < 3; d++) n[d] = pe[d] - p0[d];
  PetscFunctionReturn(0);
}

/* The end gaps of the contacts against FE triangles and edges (g: per contact gap, normal, d, p1): the
   point and the triangle's vertices now, summed over the ranks that own them; the gap is measured along
   the triangle's end-of-step normal */
static PetscErrorCode EndGapsOnSurfaces(MPI_Comm comm, FCBody bodies[], const FCContactSet *set, PetscReal g[])
{
  PetscInt   nfe = 0, *idx;
  PetscReal *xs;

  PetscFunctionBegin;
  for (PetscInt k = 0; k < set->n; k++) nfe += set->c[k].side2 != FC_SIDE_SHAPE;
  PetscCall(PetscMalloc2(nfe + 1, &idx, 12 * nfe + 1, &xs));
  PetscCall(PetscArrayzero(xs, 12 * nfe + 1));
  nfe = 0;
  for (PetscInt k = 0; k < set->n; k++) {
    FCContact *c = &set->c[k];
    if (c->side2 == FC_SIDE_SHAPE) continue;
    idx[nfe] = k;
    if (c->side2 == FC_SIDE_FE_EDGE) { /* the two ends of each edge */
      for (int s = 0; s < 2; s++)
        for (int a = 0; a < 2; a++) {
          FCProximity v = {0};
          v.nv          = 1;
          v.gdof[0]     = c->prox[s].gdof[a];
          v.w[0]        = 1.0;
          for (int d = 0; d < 3; d++) v.X[0][d] = c->prox[s].X[a][d];
          PetscCall(FCBodyAddPartialPosition(bodies[c->body[s]], &v, &xs[12 * nfe + 6 * s + 3 * a]));
        }
      nfe++;
      continue;
    }
    PetscCall(FCBodyAddPartialPosition(bodies[c->body[0]], &c->prox[0], &xs[12 * nfe]));
    for (int a = 0; a < 3 && c->side2 == FC_SIDE_FE_TRIANGLE; a++) {
      FCProximity v = {0};
      v.nv          = 1;
      v.gdof[0]     = c->prox[1].gdof[a];
      v.w[0]        = 1.0;
      for (int d = 0; d < 3; d++) v.X[0][d] = c->prox[1].X[a][d];
      PetscCall(FCBodyAddPartialPosition(bodies[c->body[1]], &v, &xs[12 * nfe + 3 + 3 * a]));
    }
    nfe++;
  }
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, xs, 12 * nfe, MPIU_REAL, MPIU_SUM, comm));
  for (PetscInt j = 0; j < nfe; j++) {
    FCContact *c = &set->c[idx[j]];
    PetscReal  tri[3][3], p2[3] = {0, 0, 0}, nrm[3], *x1 = &xs[12 * j], *gk = &g[10 * idx[j]];
    if (c->side2 == FC_SIDE_FE_EDGE) { /* the edges' cross product, on the start normal's side */
      PetscReal ea[3], eb[3], l;
      for (int d = 0; d < 3; d++) {
        ea[d] = xs[12 * j + 3 + d] - xs[12 * j + d];
        eb[d] = xs[12 * j + 9 + d] - xs[12 * j + 6 + d];
      }
      FCCross(ea, eb, nrm);
      l = PetscSqrtReal(FCDot(nrm, nrm));
      if (FCDot(nrm, c->n) < 0) l = -l;
      for (int d = 0; d < 3; d++) {
        nrm[d] = l != 0 ? nrm[d] / l : c->n[d];
        x1[d]  = c->prox[0].w[0] * xs[12 * j + d] + c->prox[0].w[1] * xs[12 * j + 3 + d];
        p2[d]  = c->prox[1].w[0] * xs[12 * j + 6 + d] + c->prox[1].w[1] * xs[12 * j + 9 + d];
      }
    } else if (c->side2 == FC_SIDE_RIGID_TRIANGLE) { /* the triangle moved rigidly: rotate its normal */
      PetscCall(FCBodyProximityPosition(bodies[c->body[1]], &c->prox[1], FC_AT_NOW, p2));
      PetscCall(FCCollisionBodyDirection(bodies[c->body[1]], FC_AT_NOW, c->nb, nrm));
    } else {
      for (int a = 0; a < 3; a++)
        for (int d = 0; d < 3; d++) tri[a][d] = xs[12 * j + 3 + 3 * a + d];
      for (int a = 0; a < 3; a++)
        for (int d = 0; d < 3; d++) p2[d] += c->prox[1].w[a] * tri[a][d];
      if (c->face1) /* face to face with a rigid shape's face (shapepoints.c): that face's normal, turned with it */
        PetscCall(FCCollisionBodyDirection(bodies[c->body[0]], FC_AT_NOW, c->nb, nrm));
      else
        FCTriangleNormal(tri, nrm);
    }
    for (int d = 0; d < 3; d++) {
      gk[1 + d] = nrm[d];
      gk[4 + d] = x1[d] - p2[d];
      gk[7 + d] = x1[d];
    }
    gk[0] = FCDot(nrm, &gk[4]);
  }
  PetscCall(PetscFree2(idx, xs));
  PetscFunctionReturn(0);
}

PetscErrorCode FCCollisionEndGapsOf(MPI_Comm comm, PetscInt nbodies, FCBody bodies[], FCContactSet *set)
{
  PetscMPIInt rank;
  PetscReal  *g;  /* per contact: gap, end normal (3), d = p1 - p2 (3), p1 (3) */
  PetscReal  *xp; /* per contact: side 1's point now, where side 1 is FE and side 2 a shape */
  PetscBool   fe = PETSC_FALSE;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCall(PetscCalloc2(10 * set->n + 1, &g, 3 * set->n + 1, &xp));
  for (PetscInt k = 0; k < set->n; k++) { /* an FE point's vertices may lie on several ranks (a triangle */
    FCContact *c = &set->c[k];            /* point of -contact_shape_points): summed over the ranks */
    if (c->side2 == FC_SIDE_SHAPE && FCBodyIsDeformable(bodies[c->body[0]])) {
      PetscCall(FCBodyAddPartialPosition(bodies[c->body[0]], &c->prox[0], &xp[3 * k]));
      fe = PETSC_TRUE;
    }
  }
  if (fe) PetscCall(MPIU_Allreduce(MPI_IN_PLACE, xp, 3 * set->n, MPIU_REAL, MPIU_SUM, comm));
  for (PetscInt k = 0; k < set->n; k++) {
    FCContact *c = &set->c[k];
    PetscReal  x[3], p2[3], cpb[3];
    if (c->side2 != FC_SIDE_SHAPE || c->owner != rank) continue; /* triangles below */
    if (FCBodyIsDeformable(bodies[c->body[0]]))
      for (int d = 0; d < 3; d++) x[d] = xp[3 * k + d];
    else
      PetscCall(FCBodyProximityPosition(bodies[c->body[0]], &c->prox[0], FC_AT_NOW, x));
    PetscCall(FCBodyShapeDistance(bodies[c->body[1]], FC_AT_NOW, x, &g[10 * k], &g[10 * k + 1], cpb));
    { /* on an edge of the shape: the normal the contact was solved with, where it is still one of the edge's */
      PetscReal move = 0.0;
      PetscBool keep;
      for (int d = 0; d < 3; d++) move += PetscSqr(x[d] - c->p0[0][d]);
      PetscCall(FCBodyShapeKeepsNormal(bodies[c->body[1]], FC_AT_NOW, x, g[10 * k], &g[10 * k + 1], c->n,
                                       PetscSqrtReal(move), &keep));
      if (keep)
        for (int d = 0; d < 3; d++) g[10 * k + 1 + d] = c->n[d];
    }
    PetscCall(FCBodyProximityPosition(bodies[c->body[1]], &c->prox[1], FC_AT_NOW, p2));
    for (int d = 0; d < 3; d++) {
      g[10 * k + 4 + d] = x[d] - p2[d];
      g[10 * k + 7 + d] = x[d];
    }
  }
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, g, 10 * set->n, MPIU_REAL, MPIU_SUM, comm));
  PetscCall(EndGapsOnSurfaces(comm, bodies, set, g));
  for (PetscInt k = 0; k < set->n; k++) {
    FCContact *c = &set->c[k];
    c->gap_end   = g[10 * k];
    for (int d = 0; d < 3; d++) {
      c->n_end[d] = g[10 * k + 1 + d];
      c->d_end[d] = g[10 * k + 4 + d];
      c->p_end[d] = g[10 * k + 7 + d];
    }
  }
  PetscCall(PetscFree2(g, xp));
  PetscFunctionReturn(0);
}
