#include "tessellate.h"

PetscErrorCode FCTessellateCapsule(PetscReal r, PetscReal L, PetscInt nlat, PetscInt nlon, PetscInt *nv,
                                   PetscReal **xyz, PetscInt *nt, PetscInt **tri)
{
  /* rings: north pole, nlat-1 rings in the north, equator (twice if L > 0), south mirrored */
  PetscInt   nring = 2 * nlat + 1 + (L > 0 ? 1 : 0), v = 0, t = 0, *ringStart, *ringSize;
  PetscReal *x;
  PetscInt  *T;

  PetscFunctionBegin;
  PetscCall(PetscMalloc2(nring, &ringStart, nring, &ringSize));
  *nv = 0;
  for (PetscInt i = 0; i < nring; i++) {
    ringSize[i]  = (i == 0 || i == nring - 1) ? 1 : nlon;
    ringStart[i] = *nv;
    *nv += ringSize[i];
  }
  *nt = 0;
  for (PetscInt i = 0; i + 1 < nring; i++) *nt += (ringSize[i] == 1 || ringSize[i + 1] == 1) ? nlon : 2 * nlon;
  PetscCall(PetscMalloc1(3 * (*nv), &x));
  PetscCall(PetscMalloc1(3 * (*nt), &T));
  for (PetscInt i = 0; i < nring; i++) {
    /* polar angle of the ring and which hemisphere it belongs to */
    PetscInt  k     = (L > 0 && i > nlat) ? i - 1 : i; /* latitude index 0..2 nlat */
    PetscReal theta = PETSC_PI * k / (2.0 * nlat), zoff = (i <= nlat) ? 0.5 * L : -0.5 * L;
    for (PetscInt j = 0; j < ringSize[i]; j++, v++) {
      PetscReal phi = 2.0 * PETSC_PI * j / nlon;
      x[3 * v + 0]  = r * PetscSinReal(theta) * PetscCosReal(phi);
      x[3 * v + 1]  = r * PetscSinReal(theta) * PetscSinReal(phi);
      x[3 * v + 2]  = r * PetscCosReal(theta) + zoff;
    }
  }
  for (PetscInt i = 0; i + 1 < nring; i++) {
    PetscInt a = ringStart[i], b = ringStart[i + 1];
    for (PetscInt j = 0; j < nlon; j++) {
      PetscInt j1 = (j + 1) % nlon;
      if (ringSize[i] == 1) {
        T[3 * t]     = a;
        T[3 * t + 1] = b + j;
        T[3 * t + 2] = b + j1;
        t++;
      } else if (ringSize[i + 1] == 1) {
        T[3 * t]     = a + j;
        T[3 * t + 1] = b;
        T[3 * t + 2] = a + j1;
        t++;
      } else {
        T[3 * t]     = a + j;
        T[3 * t + 1] = b + j;
        T[3 * t + 2] = b + j1;
        t++;
        T[3 * t]     = a + j;
        T[3 * t + 1] = b + j1;
        T[3 * t + 2] = a + j1;
        t++;
      }
    }
  }
  PetscCall(PetscFree2(ringStart, ringSize));
  *xyz = x;
  *tri = T;
  PetscFunctionReturn(0);
}
