/* One progress line on rank 0, at most once per second and at the last step. */
#include "../fcimpl.h"

PetscErrorCode FCProgressStart(FCProgress *p, PetscBool quiet)
{
  PetscFunctionBegin;
  PetscCall(PetscTime(&p->start));
  p->last  = p->start;
  p->quiet = quiet;
  PetscFunctionReturn(0);
}

PetscErrorCode FCProgressUpdate(FCProgress *p, MPI_Comm comm, PetscInt step, PetscInt nsteps, PetscReal t)
{
  PetscLogDouble now;

  PetscFunctionBegin;
  if (p->quiet) PetscFunctionReturn(0);
  PetscCall(PetscTime(&now));
  if (now - p->last < 1.0 && step < nsteps) PetscFunctionReturn(0);
  p->last = now;
  {
    double wall = now - p->start, eta = step > 0 ? wall * (nsteps - step) / step : 0.0;
    PetscCall(PetscPrintf(comm, "step %" PetscInt_FMT "/%" PetscInt_FMT "  t = %.4e s  wall %.1f s  ETA %.1f s\n", step,
                          nsteps, (double)t, wall, eta));
  }
  PetscFunctionReturn(0);
}
