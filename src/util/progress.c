/* One progress line on rank 0, at most once per second and at the last step; a step whose end
   the scene found wrong (points inside another body, contacts beyond the end-of-step check) gets
   its line at once, with the scene's warning (the first 10 such steps, then a line per second as
   usual, each with its warning). */
#include "../fcimpl.h"

PetscErrorCode FCProgressStart(FCProgress *p, PetscBool quiet)
{
  PetscFunctionBegin;
  PetscCall(PetscTime(&p->start));
  p->last  = p->start;
  p->quiet = quiet;
  PetscFunctionReturn(0);
}

PetscErrorCode FCProgressUpdate(FCProgress *p, MPI_Comm comm, PetscInt step, PetscInt nsteps, PetscReal t,
                                const char warning[])
{
  PetscLogDouble now;
  PetscBool      urgent = PETSC_FALSE;

  PetscFunctionBegin;
  if (p->quiet) PetscFunctionReturn(0);
  if (warning[0]) urgent = ++p->warned <= 10 ? PETSC_TRUE : PETSC_FALSE;
  PetscCall(PetscTime(&now));
  if (now - p->last < 1.0 && step < nsteps && !urgent) PetscFunctionReturn(0);
  p->last = now;
  {
    double wall = now - p->start, eta = step > 0 ? wall * (nsteps - step) / step : 0.0;
    PetscCall(PetscPrintf(comm, "step %" PetscInt_FMT "/%" PetscInt_FMT "  t = %.4e s  wall %.1f s  ETA %.1f s", step,
                          nsteps, (double)t, wall, eta));
    PetscCall(PetscPrintf(comm, "%s\n", warning));
  }
  PetscFunctionReturn(0);
}
