/* Sphere of radius -<body>_radius centred on the body origin. */
#include "tessellate.h"

static PetscErrorCode SetFromOptions_Sphere(PetscOptionItems *PetscOptionsObject, FCShape s, const char bodyname[])
{
  PetscBool set;

  PetscFunctionBegin;
  PetscCall(FCOptionsReal(PetscOptionsObject, "-radius", "Sphere radius", &s->radius, &set));
  PetscCheck(set, PetscOptionsObject->comm, PETSC_ERR_USER_INPUT, "Sphere body '%s' needs -%sradius", bodyname,
             PetscOptionsObject->prefix);
  PetscCall(FCCheckPositive(PetscOptionsObject->comm, PetscOptionsObject->prefix, "-radius", s->radius));
  PetscFunctionReturn(0);
}

static PetscErrorCode MassProperties_Sphere(FCShape s, PetscReal *V, PetscReal J[9])
{
  PetscReal r = s->radius;

  PetscFunctionBegin;
  *V = 4.0 / 3.0 * PETSC_PI * r * r * r;
  for (int i = 0; i < 9; i++) J[i] = (i % 4 == 0) ? 0.4 * (*V) * r * r : 0.0;
  PetscFunctionReturn(0);
}

static PetscErrorCode Tessellate_Sphere(FCShape s, PetscInt *nv, PetscReal **xyz, PetscInt *nt, PetscInt **tri)
{
  PetscFunctionBegin;
  PetscCall(FCTessellateCapsule(s->radius, 0.0, 8, 24, nv, xyz, nt, tri));
  PetscFunctionReturn(0);
}

static PetscErrorCode Distance_Sphere(FCShape s, const PetscReal x[3], PetscReal *d, PetscReal n[3], PetscReal cp[3])
{
  PetscReal r = PetscSqrtReal(FCDot(x, x));

  PetscFunctionBegin;
  *d = r - s->radius;
  for (int i = 0; i < 3; i++) n[i] = r > 0 ? x[i] / r : (i == 2 ? 1.0 : 0.0);
  for (int i = 0; i < 3; i++) cp[i] = s->radius * n[i];
  PetscFunctionReturn(0);
}

PetscErrorCode FCShapeCreate_Sphere(FCShape s)
{
  PetscFunctionBegin;
  s->setfromoptions = SetFromOptions_Sphere;
  s->massproperties = MassProperties_Sphere;
  s->tessellate     = Tessellate_Sphere;
  s->distance       = Distance_Sphere;
  s->smooth         = PETSC_TRUE;
  s->ncore          = 1; /* the centre */
  PetscFunctionReturn(0);
}
