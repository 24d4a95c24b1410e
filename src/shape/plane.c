/* Infinite plane through the body origin with outward normal -<body>_normal (body frame,
   default +z). It has no mass: only kinematic bodies may be planes. -<body>_length sets the
   side of the square drawn in pictures (default 4). */
#include "../fcimpl.h"

static PetscErrorCode SetFromOptions_Plane(PetscOptionItems *PetscOptionsObject, FCShape s, const char bodyname[])
{
  PetscReal n;

  PetscFunctionBegin;
  s->normal[0] = s->normal[1] = 0.0;
  s->normal[2]                = 1.0;
  s->length                   = 4.0;
  PetscCall(FCOptionsRealArray(PetscOptionsObject, "-normal", "Plane normal in the body frame", 3, s->normal, NULL));
  PetscCall(FCOptionsReal(PetscOptionsObject, "-length", "Side of the square drawn for the plane", &s->length, NULL));
  PetscCall(FCCheckPositive(PetscOptionsObject->comm, PetscOptionsObject->prefix, "-length", s->length));
  n = PetscSqrtReal(FCDot(s->normal, s->normal));
  PetscCheck(n > 0.0, PetscOptionsObject->comm, PETSC_ERR_USER_INPUT,
             "Plane body '%s': -%snormal must be a non-zero vector", bodyname, PetscOptionsObject->prefix);
  for (int i = 0; i < 3; i++) s->normal[i] /= n;
  PetscFunctionReturn(0);
}

static PetscErrorCode Tessellate_Plane(FCShape s, PetscInt *nv, PetscReal **xyz, PetscInt *nt, PetscInt **tri)
{
  PetscReal e[3] = {1, 0, 0}, t1[3], t2[3], n, *x, hl = 0.5 * s->length;
  PetscInt *T;

  PetscFunctionBegin;
  if (PetscAbsReal(s->normal[0]) > 0.9) {
    e[0] = 0;
    e[1] = 1;
  }
  FCCross(s->normal, e, t1);
  n = PetscSqrtReal(FCDot(t1, t1));
  for (int i = 0; i < 3; i++) t1[i] /= n;
  FCCross(s->normal, t1, t2);
  *nv = 4;
  *nt = 2;
  PetscCall(PetscMalloc1(12, &x));
  PetscCall(PetscMalloc1(6, &T));
  for (int v = 0; v < 4; v++) {
    PetscReal a = (v == 1 || v == 2) ? hl : -hl, b = (v >= 2) ? hl : -hl;
    for (int i = 0; i < 3; i++) x[3 * v + i] = a * t1[i] + b * t2[i];
  }
  T[0] = 0;
  T[1] = 1;
  T[2] = 2;
  T[3] = 0;
  T[4] = 2;
  T[5] = 3;
  *xyz = x;
  *tri = T;
  PetscFunctionReturn(0);
}

/* d = n . x: the plane passes through the body origin */
static PetscErrorCode Distance_Plane(FCShape s, const PetscReal x[3], PetscReal *d, PetscReal n[3], PetscReal cp[3])
{
  PetscFunctionBegin;
  *d = FCDot(s->normal, x);
  for (int i = 0; i < 3; i++) {
    n[i]  = s->normal[i];
    cp[i] = x[i] - (*d) * n[i];
  }
  PetscFunctionReturn(0);
}

PetscErrorCode FCShapeCreate_Plane(FCShape s)
{
  PetscFunctionBegin;
  s->bounded        = PETSC_FALSE;
  s->setfromoptions = SetFromOptions_Plane;
  s->tessellate     = Tessellate_Plane;
  s->distance       = Distance_Plane;
  PetscFunctionReturn(0);
}
