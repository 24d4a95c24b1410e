/* Solid cylinder of radius -<body>_radius and length -<body>_length along the body z axis,
   centred on the body origin. */
#include "../fcimpl.h"

static PetscErrorCode SetFromOptions_Cylinder(PetscOptionItems *PetscOptionsObject, FCShape s, const char bodyname[])
{
  PetscBool setr, setl;

  PetscFunctionBegin;
  PetscCall(FCOptionsReal(PetscOptionsObject, "-radius", "Cylinder radius", &s->radius, &setr));
  PetscCall(FCOptionsReal(PetscOptionsObject, "-length", "Cylinder length", &s->length, &setl));
  PetscCheck(setr && setl, PetscOptionsObject->comm, PETSC_ERR_USER_INPUT,
             "Cylinder body '%s' needs -%sradius and -%slength", bodyname, PetscOptionsObject->prefix,
             PetscOptionsObject->prefix);
  PetscCall(FCCheckPositive(PetscOptionsObject->comm, PetscOptionsObject->prefix, "-radius", s->radius));
  PetscCall(FCCheckPositive(PetscOptionsObject->comm, PetscOptionsObject->prefix, "-length", s->length));
  s->ncore = 2; /* the axis segment between the end faces' centres */
  s->flat  = PETSC_TRUE;
  for (int k = 0; k < 2; k++) s->core[k][2] = (k ? 0.5 : -0.5) * s->length;
  PetscFunctionReturn(0);
}

static PetscErrorCode MassProperties_Cylinder(FCShape s, PetscReal *V, PetscReal J[9])
{
  PetscReal r = s->radius, L = s->length;

  PetscFunctionBegin;
  *V = PETSC_PI * r * r * L;
  for (int i = 0; i < 9; i++) J[i] = 0.0;
  J[0] = J[4] = (*V) * (3.0 * r * r + L * L) / 12.0;
  J[8]        = 0.5 * (*V) * r * r;
  PetscFunctionReturn(0);
}

static PetscErrorCode Tessellate_Cylinder(FCShape s, PetscInt *nv, PetscReal **xyz, PetscInt *nt, PetscInt **tri)
{
  const PetscInt n = 32;
  PetscReal     *x;
  PetscInt      *T, t = 0;

  PetscFunctionBegin;
  *nv = 2 * n + 2;
  *nt = 4 * n;
  PetscCall(PetscMalloc1(3 * (*nv), &x));
  PetscCall(PetscMalloc1(3 * (*nt), &T));
  for (PetscInt k = 0; k < 2; k++)
    for (PetscInt j = 0; j < n; j++) {
      PetscReal phi          = 2.0 * PETSC_PI * j / n;
      x[3 * (k * n + j) + 0] = s->radius * PetscCosReal(phi);
      x[3 * (k * n + j) + 1] = s->radius * PetscSinReal(phi);
      x[3 * (k * n + j) + 2] = (k ? -0.5 : 0.5) * s->length;
    }
  x[6 * n + 0] = x[6 * n + 1] = 0.0;
  x[6 * n + 2]                = 0.5 * s->length;
  x[6 * n + 3] = x[6 * n + 4] = 0.0;
  x[6 * n + 5]                = -0.5 * s->length;
  for (PetscInt j = 0; j < n; j++) {
    PetscInt j1  = (j + 1) % n;
    T[3 * t]     = j;
    T[3 * t + 1] = n + j;
    T[3 * t + 2] = n + j1;
    t++;
    T[3 * t]     = j;
    T[3 * t + 1] = n + j1;
    T[3 * t + 2] = j1;
    t++;
    T[3 * t]     = 2 * n;
    T[3 * t + 1] = j;
    T[3 * t + 2] = j1;
    t++;
    T[3 * t]     = 2 * n + 1;
    T[3 * t + 1] = n + j1;
    T[3 * t + 2] = n + j;
    t++;
  }
  *xyz = x;
  *tri = T;
  PetscFunctionReturn(0);
}

/* Solid cylinder (axis z): the 2D distance in (radial, axial) coordinates */
static PetscErrorCode Distance_Cylinder(FCShape s, const PetscReal x[3], PetscReal *d, PetscReal n[3], PetscReal cp[3])
{
  PetscReal rho = PetscSqrtReal(x[0] * x[0] + x[1] * x[1]), e[2], dr = rho - s->radius,
            dz = PetscAbsReal(x[2]) - 0.5 * s->length, sz = x[2] >= 0 ? 1.0 : -1.0;

  PetscFunctionBegin;
  e[0] = rho > 0 ? x[0] / rho : 1.0;
  e[1] = rho > 0 ? x[1] / rho : 0.0;
  if (dr > 0 && dz > 0) { /* beyond the rim */
    PetscReal r = PetscSqrtReal(dr * dr + dz * dz);
    *d          = r;
    n[0]        = e[0] * dr / r;
    n[1]        = e[1] * dr / r;
    n[2]        = sz * dz / r;
  } else if (dr > dz) { /* side */
    *d   = dr;
    n[0] = e[0];
    n[1] = e[1];
    n[2] = 0.0;
  } else { /* cap */
    *d   = dz;
    n[0] = n[1] = 0.0;
    n[2]        = sz;
  }
  cp[0] = e[0] * PetscMin(rho, s->radius);
  cp[1] = e[1] * PetscMin(rho, s->radius);
  cp[2] = sz * PetscMin(PetscAbsReal(x[2]), 0.5 * s->length);
  if (!(dr > 0 && dz > 0)) {
    if (dr > dz) {
      cp[0] = e[0] * s->radius;
      cp[1] = e[1] * s->radius;
      cp[2] = x[2];
    } else {
      cp[0] = x[0];
      cp[1] = x[1];
      cp[2] = sz * 0.5 * s->length;
    }
  }
  PetscFunctionReturn(0);
}

PetscErrorCode FCShapeCreate_Cylinder(FCShape s)
{
  PetscFunctionBegin;
  s->setfromoptions = SetFromOptions_Cylinder;
  s->massproperties = MassProperties_Cylinder;
  s->tessellate     = Tessellate_Cylinder;
  s->distance       = Distance_Cylinder;
  PetscFunctionReturn(0);
}
