/* Capsule: a cylinder of radius -<body>_radius and length -<body>_length along the body z
   axis, closed by two hemispheres; centred on the body origin. */
#include "tessellate.h"

static PetscErrorCode SetFromOptions_Capsule(PetscOptionItems *PetscOptionsObject, FCShape s, const char bodyname[])
{
  PetscBool setr, setl;

  PetscFunctionBegin;
  PetscCall(FCOptionsReal(PetscOptionsObject, "-radius", "Capsule radius", &s->radius, &setr));
  PetscCall(FCOptionsReal(PetscOptionsObject, "-length", "Capsule length between cap centres", &s->length, &setl));
  PetscCheck(setr && setl, PetscOptionsObject->comm, PETSC_ERR_USER_INPUT,
             "Capsule body '%s' needs -%sradius and -%slength", bodyname, PetscOptionsObject->prefix,
             PetscOptionsObject->prefix);
  PetscCall(FCCheckPositive(PetscOptionsObject->comm, PetscOptionsObject->prefix, "-radius", s->radius));
  PetscCall(FCCheckNonNegative(PetscOptionsObject->comm, PetscOptionsObject->prefix, "-length", s->length));
  s->ncore = s->length > 0 ? 2 : 1; /* the axis segment between the cap centres */
  for (int k = 0; k < 2; k++) s->core[k][2] = (k ? 0.5 : -0.5) * s->length;
  PetscFunctionReturn(0);
}

/* Cylinder part plus two hemispheres whose centroids sit 3r/8 beyond the cylinder ends */
static PetscErrorCode MassProperties_Capsule(FCShape s, PetscReal *V, PetscReal J[9])
{
  PetscReal r = s->radius, L = s->length, Vc = PETSC_PI * r * r * L, Vs = 4.0 / 3.0 * PETSC_PI * r * r * r;

  PetscFunctionBegin;
  *V = Vc + Vs;
  for (int i = 0; i < 9; i++) J[i] = 0.0;
  J[0] = J[4] = Vc * (3.0 * r * r + L * L) / 12.0 + Vs * (0.4 * r * r + 0.25 * L * L + 0.375 * L * r);
  J[8]        = 0.5 * Vc * r * r + 0.4 * Vs * r * r;
  PetscFunctionReturn(0);
}

static PetscErrorCode Tessellate_Capsule(FCShape s, PetscInt *nv, PetscReal **xyz, PetscInt *nt, PetscInt **tri)
{
  PetscFunctionBegin;
  PetscCall(FCTessellateCapsule(s->radius, s->length, 8, 24, nv, xyz, nt, tri));
  PetscFunctionReturn(0);
}

/* distance to the axis segment [-L/2, L/2] on z, minus the radius */
static PetscErrorCode Distance_Capsule(FCShape s, const PetscReal x[3], PetscReal *d, PetscReal n[3], PetscReal cp[3])
{
  PetscReal z = PetscMax(-0.5 * s->length, PetscMin(0.5 * s->length, x[2])), a[3] = {0, 0, z}, v[3], r;

  PetscFunctionBegin;
  for (int i = 0; i < 3; i++) v[i] = x[i] - a[i];
  r  = PetscSqrtReal(FCDot(v, v));
  *d = r - s->radius;
  for (int i = 0; i < 3; i++) n[i] = r > 0 ? v[i] / r : (i == 0 ? 1.0 : 0.0);
  for (int i = 0; i < 3; i++) cp[i] = a[i] + s->radius * n[i];
  PetscFunctionReturn(0);
}

PetscErrorCode FCShapeCreate_Capsule(FCShape s)
{
  PetscFunctionBegin;
  s->setfromoptions = SetFromOptions_Capsule;
  s->massproperties = MassProperties_Capsule;
  s->tessellate     = Tessellate_Capsule;
  s->distance       = Distance_Capsule;
  s->smooth         = PETSC_TRUE;
  PetscFunctionReturn(0);
}
