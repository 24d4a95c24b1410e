/* Two boxes (rigid or kinematic) face to face. The corners of one against the other's signed
   distance (collision.c) take the normal of the face nearest each corner alone; a corner that lies
   on an edge of the other box (two equal boxes stacked: the upper one's corners sit on the lower
   one's top edges) is as near the side face as the top one, and the side face wins as soon as the
   corner is a round-off inside: a sideways normal, no support, and the upper box sinks through. A
   wide box on a narrow one has no corner over the narrow one's face at all, and falls through; a
   box set across another, or half over it, is held by corners of both and by points where their
   edges cross.
   So, where the two boxes have a face each parallel to the other's (within FC_BOX_PARALLEL_COS),
   the pair decides, as rigid-body codes do (the face-face case of box-box collision, e.g. ODE's
   dBoxBox): the axis of least overlap among the six face normals (separating axes, at the start of
   the step) names the reference face F of one box; the other box's face most opposed to it is the
   incident face. The contacts are the corners of the polygon where the two faces overlap, seen
   along F's normal, each along that normal:
     - the incident face's corners over F (widened by the alarm distance);
     - F's corners under the incident face, unless an incident corner is within the alarm distance
       (equal faces: one contact per corner);
     - the points where an edge of one face crosses an edge of the other.
   Each is a point of the incident box's face against F; its key is the corner's body-frame
   position, or the two crossing edges' numbers (stable from step to step for the warm start).
   Other configurations (edge on edge, a tilted box on its edge) keep the corners against the
   signed distance. */
#include "collisionimpl.h"

#define FC_BOX_PARALLEL_COS 0.9998476951563913 /* cos 1 degree */
#define FC_BOX_EDGE_KEY (-1e9)                 /* the key of an edge crossing: edge numbers below this */

typedef struct {
  FCBody       b;
  PetscInt     index; /* the body's index in the scene */
  PetscReal    h[3];  /* half extents */
  PetscReal    R[9];  /* body axes as columns (world = R body), now */
  PetscInt     n;     /* contact points: the corners */
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
    e[j]           = 1.0;
    PetscCall(FCBodyToBodyFrame(b, FC_AT_NOW, e, PETSC_TRUE, r));
    for (int k = 0; k < 3; k++) B->R[3 * j + k] = r[k];
  }
  PetscCall(FCBodyGetContactPoints(b, &B->n, &B->prox, &B->x0, &B->xf, &B->key));
  PetscFunctionReturn(0);
}

/* The world position now of body-frame point r of box B */
static PetscErrorCode World(const Box *B, const PetscReal r[3], PetscReal x[3])
{
  FCProximity q;

  PetscFunctionBegin;
  PetscCall(PetscMemzero(&q, sizeof(q)));
  for (int i = 0; i < 3; i++) q.r[i] = r[i];
  PetscCall(FCBodyProximityPosition(B->b, &q, FC_AT_NOW, x));
  PetscFunctionReturn(0);
}

/* The overlap of C's corners with F along each of F's axes (negative: a gap), and on which side of F they lie */
static PetscErrorCode Overlaps(const Box *F, const Box *C, PetscReal ov[3], PetscReal side[3])
{
  PetscReal lo[3] = {PETSC_MAX_REAL, PETSC_MAX_REAL, PETSC_MAX_REAL},
            hi[3] = {PETSC_MIN_REAL, PETSC_MIN_REAL, PETSC_MIN_REAL};

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

/* The contact of point x (world, now) of C's incident face against face (k, s) of F, keyed by key */
static PetscErrorCode AddPoint(const Box *F, const Box *C, int k, PetscReal s, const PetscReal x[3],
                               const PetscReal key[3], PetscInt pair, const FCContactPairs *pairs, PetscMPIInt rank,
                               FCContactSet *set)
{
  PetscReal y[3], n[3], cp[3];

  PetscFunctionBegin;
  PetscCall(FCBodyToBodyFrame(F->b, FC_AT_NOW, x, PETSC_FALSE, y));
  for (int j = 0; j < 3; j++) {
    cp[j] = j == k ? s * F->h[k] : PetscMax(-F->h[j], PetscMin(F->h[j], y[j]));
    n[j]  = s * F->R[3 * j + k];
  }
  PetscCall(FCCollisionAddShapeContact(C->b, F->b, C->index, F->index, pair, x, s * y[k] - F->h[k], n, cp, key, pairs,
                                       rank, set));
  PetscFunctionReturn(0);
}

/* The body-frame corners of face (k, s) of a box of half extents h, in order around it */
static void FaceCorners(const PetscReal h[3], int k, PetscReal s, PetscReal r[4][3])
{
  static const PetscReal sign[4][2] = {{1, 1}, {-1, 1}, {-1, -1}, {1, -1}};
  int                    a = (k + 1) % 3, b = (k + 2) % 3;
  for (int i = 0; i < 4; i++) {
    r[i][k] = s * h[k];
    r[i][a] = sign[i][0] * h[a];
    r[i][b] = sign[i][1] * h[b];
  }
}

/* Whether 2D point p is within tol of one of the n points seen */
static PetscBool Seen(PetscInt n, const PetscReal seen[][2], const PetscReal p[2], PetscReal tol)
{
  for (PetscInt i = 0; i < n; i++)
    if (PetscSqr(seen[i][0] - p[0]) + PetscSqr(seen[i][1] - p[1]) <= tol * tol) return PETSC_TRUE;
  return PETSC_FALSE;
}

PetscErrorCode FCCollisionBoxBox(FCBody P, FCBody S, PetscInt ip, PetscInt is, PetscInt pair,
                                 const FCContactPairs *pairs, PetscMPIInt rank, FCContactSet *set, PetscBool *done)
{
  Box       B[2], *F, *C;
  PetscReal ov[2][3], side[2][3], best = PETSC_MAX_REAL, dot = 0.0, s, sc, tol = pairs->distance;
  PetscReal cr[4][3], cx[4][3], cy[4][3], fr[4][3], fx[4][3], seen[16][2];
  PetscInt  nseen = 0;
  int       f = 0, k = 0, m = 0, j1, j2;

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
  if (best < -tol) PetscFunctionReturn(0); /* apart: the corners' own test (with the continuous one) */
  F = &B[f];
  C = &B[1 - f];
  for (int j = 0; j < 3; j++) { /* the axis of C most aligned with F's axis k */
    PetscReal dj = 0.0;
    for (int i = 0; i < 3; i++) dj += F->R[3 * i + k] * C->R[3 * i + j];
    if (PetscAbsReal(dj) > PetscAbsReal(dot)) {
      dot = dj;
      m   = j;
    }
  }
  if (PetscAbsReal(dot) < FC_BOX_PARALLEL_COS) PetscFunctionReturn(0);
  *done = PETSC_TRUE;
  s     = side[f][k] >= 0.0 ? 1.0 : -1.0; /* F's face toward C, outward normal s F_k */
  sc    = dot * s > 0.0 ? -1.0 : 1.0;     /* C's incident face, outward normal sc C_m (about -s F_k) */
  j1    = (k + 1) % 3;
  j2    = (k + 2) % 3;
  FaceCorners(C->h, m, sc, cr);
  FaceCorners(F->h, k, s, fr);
  for (int i = 0; i < 4; i++) {
    PetscCall(World(C, cr[i], cx[i]));
    PetscCall(FCBodyToBodyFrame(F->b, FC_AT_NOW, cx[i], PETSC_FALSE, cy[i]));
    PetscCall(World(F, fr[i], fx[i]));
  }
  for (int i = 0; i < 4; i++) /* the incident corners over F */
    if (PetscAbsReal(cy[i][j1]) <= F->h[j1] + tol && PetscAbsReal(cy[i][j2]) <= F->h[j2] + tol) {
      PetscCall(AddPoint(F, C, k, s, cx[i], cr[i], pair, pairs, rank, set));
      seen[nseen][0]   = cy[i][j1];
      seen[nseen++][1] = cy[i][j2];
    }
  for (int i = 0; i < 4; i++) { /* F's corners under the incident face: the point of that face over each */
    PetscReal z[3], x[3], p[2] = {fr[i][j1], fr[i][j2]};
    PetscCall(FCBodyToBodyFrame(C->b, FC_AT_NOW, fx[i], PETSC_FALSE, z));
    if (PetscAbsReal(z[(m + 1) % 3]) > C->h[(m + 1) % 3] + tol ||
        PetscAbsReal(z[(m + 2) % 3]) > C->h[(m + 2) % 3] + tol || Seen(nseen, seen, p, tol))
      continue;
    z[m] = sc * C->h[m];
    PetscCall(World(C, z, x));
    PetscCall(AddPoint(F, C, k, s, x, fr[i], pair, pairs, rank, set));
    seen[nseen][0]   = p[0];
    seen[nseen++][1] = p[1];
  }
  for (int i = 0; i < 4; i++) /* edge crossings, seen along F's normal */
    for (int e = 0; e < 4; e++) {
      const PetscReal *p0 = cy[i], *p1 = cy[(i + 1) % 4], *q0 = fr[e], *q1 = fr[(e + 1) % 4];
      PetscReal        a[2] = {p1[j1] - p0[j1], p1[j2] - p0[j2]}, b[2] = {q1[j1] - q0[j1], q1[j2] - q0[j2]};
      PetscReal        w[2] = {q0[j1] - p0[j1], q0[j2] - p0[j2]}, den = a[0] * b[1] - a[1] * b[0], t, u, p[2], x[3];
      if (PetscAbsReal(den) <= PETSC_SMALL * PetscSqrtReal((a[0] * a[0] + a[1] * a[1]) * (b[0] * b[0] + b[1] * b[1])))
        continue; /* parallel edges: their overlap's ends are corners */
      t = (w[0] * b[1] - w[1] * b[0]) / den;
      u = (w[0] * a[1] - w[1] * a[0]) / den;
      if (t <= 0.0 || t >= 1.0 || u <= 0.0 || u >= 1.0) continue;
      p[0] = p0[j1] + t * a[0];
      p[1] = p0[j2] + t * a[1];
      if (Seen(nseen, seen, p, tol) || nseen == 16) continue;
      for (int d = 0; d < 3; d++) x[d] = cx[i][d] + t * (cx[(i + 1) % 4][d] - cx[i][d]);
      {
        PetscReal key[3] = {FC_BOX_EDGE_KEY - i, FC_BOX_EDGE_KEY - e, FC_BOX_EDGE_KEY};
        PetscCall(AddPoint(F, C, k, s, x, key, pair, pairs, rank, set));
      }
      seen[nseen][0]   = p[0];
      seen[nseen++][1] = p[1];
    }
  PetscFunctionReturn(0);
}
