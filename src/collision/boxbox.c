/* Two boxes (rigid or kinematic) face to face. The corners of one against the other's signed
   distance (collision.c) take the normal of the face nearest each corner alone; a corner that lies
   on an edge of the other box (two equal boxes stacked: the upper one's corners sit on the lower
   one's top edges) is as near the side face as the top one, and the side face wins as soon as the
   corner is a round-off inside: a sideways normal, no support, and the upper box sinks through. A
   wide box on a narrow one has no corner over the narrow one's face at all, and falls through.
   So, where the two boxes have a face each parallel to the other's (within FC_BOX_PARALLEL_COS),
   the pair decides: the axis of least overlap among the six face normals (separating axes, at the
   start of the step) names the face F that the other box C meets, and
     - every corner of C over F (its projection within F, widened by the alarm distance) is a
       contact along F's normal, at its projection on F;
     - every corner of F's box over C's opposite face likewise, along that face's normal, unless
       a corner of C lies within the alarm distance of it (equal faces: one contact per corner).
   Other configurations (edge on edge, a tilted box on its edge) keep the corners against the
   signed distance. */
#include "collisionimpl.h"

#define FC_BOX_PARALLEL_COS 0.9998476951563913 /* cos 1 degree */

typedef struct {
  FCBody       b;
  PetscInt     index; /* the body's index in the scene */
  PetscReal    h[3];  /* half extents */
  PetscReal    R[9];  /* body axes as columns (world = R body), now */
  PetscInt     n;     /* corners */
  FCProximity *prox;
  PetscReal   *x0, *xf, *key;
} Box;

static PetscErrorCode BoxGet(FCBody b, PetscInt index, Box *B)
{
  PetscFunctionBegin;
  B->b     = b;
  B->index = index;
  FCBodyGetBoxHalfExtents(b, B->h);
  for (int j = 0; j < 3; j++) { /* R^T e_j is row j of R */
    PetscReal e[3] = {0, 0, 0}, r[3];
    e[j] = 1.0;
    PetscCall(FCBodyToBodyFrame(b, FC_AT_NOW, e, PETSC_TRUE, r));
    for (int k = 0; k < 3; k++) B->R[3 * j + k] = r[k];
  }
  PetscCall(FCBodyGetContactPoints(b, &B->n, &B->prox, &B->x0, &B->xf, &B->key));
  PetscFunctionReturn(0);
}

/* The overlap of C's corners with F along each of F's axes (negative: a gap), and on which side of F they lie */
static PetscErrorCode Overlaps(const Box *F, const Box *C, PetscReal ov[3], PetscReal side[3])
{
  PetscReal lo[3] = {PETSC_MAX_REAL, PETSC_MAX_REAL, PETSC_MAX_REAL}, hi[3] = {PETSC_MIN_REAL, PETSC_MIN_REAL, PETSC_MIN_REAL};

  PetscFunctionBegin;
  for (int k = 0; k < 3; k++) side[k] = 0.0;
  for (PetscInt i = 0; i < C->n; i++) {
    PetscReal y[3];
    PetscCall(FCBodyToBodyFrame(F->b, FC_AT_NOW, &C->x0[3 * i], PETSC_FALSE, y));
    for (int k = 0; k < 3; k++) {
      lo[k] = PetscMin(lo[k], y[k]);
      hi[k] = PetscMax(hi[k], y[k]);
      side[k] += y[k];
    }
  }
  for (int k = 0; k < 3; k++) ov[k] = PetscMin(F->h[k], hi[k]) - PetscMax(-F->h[k], lo[k]);
  PetscFunctionReturn(0);
}

/* The corners of C over face (k, s) of F: contacts along that face's normal. skip (or NULL): C's corners to leave out */
static PetscErrorCode CornersOnFace(const Box *F, const Box *C, int k, PetscReal s, const PetscBool skip[],
                                    PetscInt pair, const FCContactPairs *pairs, PetscMPIInt rank, FCContactSet *set,
                                    PetscBool used[])
{
  PetscReal n[3];

  PetscFunctionBegin;
  for (int j = 0; j < 3; j++) n[j] = s * F->R[3 * j + k];
  for (PetscInt i = 0; i < C->n; i++) {
    PetscReal y[3], d, cp[3];
    PetscBool over = PETSC_TRUE;
    FCContact c;
    if (skip && skip[i]) continue;
    PetscCall(FCBodyToBodyFrame(F->b, FC_AT_NOW, &C->x0[3 * i], PETSC_FALSE, y));
    for (int j = 0; j < 3; j++) {
      cp[j] = PetscMax(-F->h[j], PetscMin(F->h[j], y[j]));
      if (j != k && PetscAbsReal(y[j]) > F->h[j] + pairs->distance) over = PETSC_FALSE;
    }
    d = s * y[k] - F->h[k];
    if (!over || d < -F->h[k]) continue; /* beyond the face, or past F's middle: a corner of the far side */
    cp[k] = s * F->h[k];
    if (d >= pairs->distance) { /* continuous: a speculative contact if the corner's motion reaches F */
      PetscBool hit = PETSC_FALSE;
      if (pairs->continuous)
        PetscCall(FCCCDPointShape(F->b, &C->x0[3 * i], &C->xf[3 * i], d, FCCCDThreshold(pairs->distance), &hit));
      if (!hit) continue;
    }
    PetscCall(PetscMemzero(&c, sizeof(c)));
    c.pair    = pair;
    c.body[0] = C->index;
    c.body[1] = F->index;
    c.prox[0] = C->prox[i];
    for (int j = 0; j < 3; j++) {
      c.prox[1].r[j] = cp[j];
      c.key[j]       = C->key[3 * i + j];
      c.n[j]         = n[j];
      c.p0[0][j]     = C->x0[3 * i + j];
      c.pfree[0][j]  = C->xf[3 * i + j];
    }
    PetscCall(FCBodyProximityPosition(F->b, &c.prox[1], FC_AT_START, c.p0[1]));
    PetscCall(FCBodyProximityPosition(F->b, &c.prox[1], FC_AT_FREE, c.pfree[1]));
    c.gap0  = d;
    c.mu    = pairs->mu[pair];
    c.owner = rank;
    c.side2 = FC_SIDE_SHAPE;
    PetscCall(FCContactSetAdd(set, &c));
    if (used) used[i] = PETSC_TRUE;
  }
  PetscFunctionReturn(0);
}

PetscErrorCode FCCollisionBoxBox(FCBody P, FCBody S, PetscInt ip, PetscInt is, PetscInt pair,
                                 const FCContactPairs *pairs, PetscMPIInt rank, FCContactSet *set, PetscBool *done)
{
  Box       B[2];
  PetscReal ov[2][3], side[2][3], best = PETSC_MAX_REAL, dot = 0.0, s;
  int       f = 0, k = 0, m = 0;
  PetscBool used[8] = {0}, skip[8] = {0};

  PetscFunctionBegin;
  *done = PETSC_FALSE;
  PetscCall(BoxGet(S, is, &B[0]));
  PetscCall(BoxGet(P, ip, &B[1]));
  if (B[0].n != 8 || B[1].n != 8) PetscFunctionReturn(0);
  PetscCall(Overlaps(&B[0], &B[1], ov[0], side[0]));
  PetscCall(Overlaps(&B[1], &B[0], ov[1], side[1]));
  for (int a = 0; a < 2; a++) /* the separating axis of least overlap among the face normals (S first on ties) */
    for (int j = 0; j < 3; j++)
      if (ov[a][j] < best) {
        best = ov[a][j];
        f    = a;
        k    = j;
      }
  if (best < -pairs->distance) PetscFunctionReturn(0); /* apart: the corners' own test (with the continuous one) */
  for (int j = 0; j < 3; j++) { /* the axis of the other box most aligned with F's axis k */
    PetscReal dj = 0.0;
    for (int i = 0; i < 3; i++) dj += B[f].R[3 * i + k] * B[1 - f].R[3 * i + j];
    if (PetscAbsReal(dj) > PetscAbsReal(dot)) {
      dot = dj;
      m   = j;
    }
  }
  if (PetscAbsReal(dot) < FC_BOX_PARALLEL_COS) PetscFunctionReturn(0);
  *done = PETSC_TRUE;
  s     = side[f][k] >= 0.0 ? 1.0 : -1.0; /* the face of F toward C */
  PetscCall(CornersOnFace(&B[f], &B[1 - f], k, s, NULL, pair, pairs, rank, set, used));
  for (PetscInt i = 0; i < 8; i++) /* F's corners that a corner of C already holds */
    for (PetscInt j = 0; j < 8 && !skip[i]; j++) {
      PetscReal dx[3];
      if (!used[j]) continue;
      for (int a = 0; a < 3; a++) dx[a] = B[f].x0[3 * i + a] - B[1 - f].x0[3 * j + a];
      skip[i] = (PetscBool)(FCDot(dx, dx) <= PetscSqr(pairs->distance));
    }
  /* C's face opposite: its outward normal along -s (F's axis k) */
  PetscCall(CornersOnFace(&B[1 - f], &B[f], m, dot * s > 0.0 ? -1.0 : 1.0, skip, pair, pairs, rank, set, NULL));
  PetscFunctionReturn(0);
}
