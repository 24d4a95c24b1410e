/* Box of half extents -<body>_half_extents a,b,c along the body axes, centred on the origin. */
#include "../fcimpl.h"

static PetscErrorCode SetFromOptions_Box(PetscOptionItems *PetscOptionsObject, FCShape s, const char bodyname[])
{
  PetscBool set;

  PetscFunctionBegin;
  PetscCall(
      FCOptionsRealArray(PetscOptionsObject, "-half_extents", "Box half extents a,b,c", 3, s->half_extents, &set));
  PetscCheck(set, PetscOptionsObject->comm, PETSC_ERR_USER_INPUT, "Box body '%s' needs -%shalf_extents a,b,c", bodyname,
             PetscOptionsObject->prefix);
  for (int i = 0; i < 3; i++)
    PetscCall(
        FCCheckPositive(PetscOptionsObject->comm, PetscOptionsObject->prefix, "-half_extents", s->half_extents[i]));
  PetscFunctionReturn(0);
}

static PetscErrorCode MassProperties_Box(FCShape s, PetscReal *V, PetscReal J[9])
{
  PetscReal a = s->half_extents[0], b = s->half_extents[1], c = s->half_extents[2];

  PetscFunctionBegin;
  *V = 8.0 * a * b * c;
  for (int i = 0; i < 9; i++) J[i] = 0.0;
  J[0] = (*V) * (b * b + c * c) / 3.0;
  J[4] = (*V) * (a * a + c * c) / 3.0;
  J[8] = (*V) * (a * a + b * b) / 3.0;
  PetscFunctionReturn(0);
}

static PetscErrorCode Tessellate_Box(FCShape s, PetscInt *nv, PetscReal **xyz, PetscInt *nt, PetscInt **tri)
{
  /* vertex v has coordinates (+-a, +-b, +-c) with bit 0 -> x, bit 1 -> y, bit 2 -> z */
  static const PetscInt faces[12][3] = {{0, 2, 3}, {0, 3, 1}, {4, 5, 7}, {4, 7, 6}, {0, 1, 5}, {0, 5, 4},
                                        {2, 6, 7}, {2, 7, 3}, {0, 4, 6}, {0, 6, 2}, {1, 3, 7}, {1, 7, 5}};
  PetscReal            *x;
  PetscInt             *T;

  PetscFunctionBegin;
  *nv = 8;
  *nt = 12;
  PetscCall(PetscMalloc1(24, &x));
  PetscCall(PetscMalloc1(36, &T));
  for (PetscInt v = 0; v < 8; v++)
    for (PetscInt d = 0; d < 3; d++) x[3 * v + d] = ((v >> d) & 1 ? 1.0 : -1.0) * s->half_extents[d];
  for (PetscInt t = 0; t < 12; t++)
    for (PetscInt k = 0; k < 3; k++) T[3 * t + k] = faces[t][k];
  *xyz = x;
  *tri = T;
  PetscFunctionReturn(0);
}

/* Box signed distance: outside, distance to the clamped point; inside, the nearest face */
static PetscErrorCode Distance_Box(FCShape s, const PetscReal x[3], PetscReal *d, PetscReal n[3], PetscReal cp[3])
{
  const PetscReal *h      = s->half_extents;
  PetscBool        inside = PETSC_TRUE;

  PetscFunctionBegin;
  for (int i = 0; i < 3; i++) {
    cp[i] = PetscMax(-h[i], PetscMin(h[i], x[i]));
    if (cp[i] != x[i]) inside = PETSC_FALSE;
  }
  if (!inside) {
    PetscReal v[3], r;
    for (int i = 0; i < 3; i++) v[i] = x[i] - cp[i];
    r  = PetscSqrtReal(FCDot(v, v));
    *d = r;
    for (int i = 0; i < 3; i++) n[i] = v[i] / r;
  } else {
    int       k    = 0;
    PetscReal best = PETSC_MAX_REAL;
    for (int i = 0; i < 3; i++)
      if (h[i] - PetscAbsReal(x[i]) < best) {
        best = h[i] - PetscAbsReal(x[i]);
        k    = i;
      }
    *d = -best;
    for (int i = 0; i < 3; i++) n[i] = (i == k) ? (x[k] >= 0 ? 1.0 : -1.0) : 0.0;
    for (int i = 0; i < 3; i++) cp[i] = x[i];
    cp[k] = n[k] * h[k];
  }
  PetscFunctionReturn(0);
}

PetscErrorCode FCShapeCreate_Box(FCShape s)
{
  PetscFunctionBegin;
  s->setfromoptions = SetFromOptions_Box;
  s->massproperties = MassProperties_Box;
  s->tessellate     = Tessellate_Box;
  s->distance       = Distance_Box;
  PetscFunctionReturn(0);
}
