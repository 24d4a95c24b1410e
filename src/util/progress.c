/* One progress line on rank 0, at most once per second and at the last step; a step that ends
   with points inside another body gets its line at once, with a warning (the first 10 such
   steps, then a line per second as usual, each with the warning and the count of such steps). */
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
                                PetscInt intersections)
{
  PetscLogDouble now;
  PetscBool      urgent = PETSC_FALSE;

  PetscFunctionBegin;
  if (p->quiet) PetscFunctionReturn(0);
  if (intersections) urgent = ++p->warned <= 10 ? PETSC_TRUE : PETSC_FALSE;
  PetscCall(PetscTime(&now));
  if (now - p->last < 1.0 && step < nsteps && !urgent) PetscFunctionReturn(0);
  p->last = now;
  {
    double wall = now - p->start, eta = step > 0 ? wall * (nsteps - step) / step : 0.0;
    PetscCall(PetscPrintf(comm, "step %" PetscInt_FMT "/%" PetscInt_FMT "  t = %.4e s  wall %.1f s  ETA %.1f s", step,
                          nsteps, (double)t, wall, eta));
    if (intersections)
      PetscCall(PetscPrintf(comm,
                            "  WARNING: %" PetscInt_FMT " point(s) inside another body (%" PetscInt_FMT
                            " step(s) so far; /steps/intersections)",
                            intersections, p->warned));
    PetscCall(PetscPrintf(comm, "\n"));
  }
  PetscFunctionReturn(0);
}
