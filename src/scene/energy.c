/* The guard on the energy of a scene. Nothing in fecontact adds energy: backward Euler and
   friction dissipate it, gravity is counted in it. It can grow only by the work of kinematic
   bodies (prescribed motions push the others) and by the separation of bodies that start inside
   each other (-contact_separation_speed). A total energy that grows far beyond all of that is a
   numerical blow-up (a time step too large for the contacts or the stiffness), not physics: the
   run stops there, naming the likely cause, rather than run on to an absurd end with exit status
   0. Option -energy_growth_limit g (help string below; docs/options.md): the run stops when the total
   energy (kinetic + elastic + gravity of every body) exceeds its value at set-up by more than g times
   the scene's energy scale, the energy the scene could receive: the initial kinetic energy, the weight
   of every body over the scene's height (the bounding box of every body, widened by the distance
   kinematic bodies travel over the run), 1/2 m V^2 with V the fastest kinematic point plus the
   separation speed, the initial elastic energy, and the work that FE bodies' prescribed displacements and
   loads have done so far (in magnitude).
   At set-up every body's energies must also be finite (a message names the body). */
#include "../fcimpl.h"

PetscErrorCode FCEnergyGuardSetFromOptions(FCEnergyGuard *g, MPI_Comm comm)
{
  PetscFunctionBegin;
  g->limit = 10.0;
  PetscOptionsBegin(comm, NULL, "Energy guard", "FCScene");
  PetscCall(FCOptionsReal(PetscOptionsObject, "-energy_growth_limit",
                          "Stop when the total energy grows by more than this many times the scene's energy scale (0: "
                          "never)",
                          &g->limit, NULL));
  PetscOptionsEnd();
  PetscCall(FCCheckNonNegative(comm, NULL, "-energy_growth_limit", g->limit));
  PetscFunctionReturn(0);
}

static PetscReal Total(const FCEnergy *E)
{
  return E->kinetic + E->elastic + E->gravity;
}

PetscErrorCode FCEnergyGuardSetUp(FCEnergyGuard *g, MPI_Comm comm, PetscInt nbodies, FCBody bodies[], PetscReal h,
                                  PetscInt nsteps, PetscReal speed)
{
  PetscReal lo[3] = {PETSC_MAX_REAL, PETSC_MAX_REAL, PETSC_MAX_REAL}, hi[3], H = 0.0, vkin = 0.0, grav = 0.0, gv[3];

  PetscFunctionBegin;
  g->E0 = g->scale = 0.0;
  g->reported      = PETSC_FALSE;
  for (int d = 0; d < 3; d++) hi[d] = -PETSC_MAX_REAL;
  for (PetscInt i = 0; i < nbodies; i++) { /* the scene's bounding box */
    const FCBodyVisual *vis;
    PetscReal          *x;
    PetscCall(FCBodyGetVisual(bodies[i], &vis));
    PetscCall(PetscMalloc1(3 * vis->nv + 1, &x));
    PetscCall(FCBodyGetVisualPositions(bodies[i], x));
    for (PetscInt k = 0; k < vis->nv; k++)
      for (int d = 0; d < 3; d++) {
        lo[d] = PetscMin(lo[d], x[3 * k + d]);
        hi[d] = PetscMax(hi[d], x[3 * k + d]);
      }
    PetscCall(PetscFree(x));
  }
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, lo, 3, MPIU_REAL, MPIU_MIN, comm));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, hi, 3, MPIU_REAL, MPIU_MAX, comm));
  for (int d = 0; d < 3; d++) H += PetscSqr(hi[d] - lo[d]);
  H = PetscSqrtReal(H); /* the diagonal: any height the scene spans, in any direction of gravity */
  for (PetscInt i = 0; i < nbodies; i++) {
    PetscReal v[3], w[3];
    if (!FCBodyIsPrescribed(bodies[i])) continue; /* the fastest point of a kinematic body */
    FCBodyGetPrescribedMotion(bodies[i], v, w);
    vkin = PetscMax(vkin, PetscSqrtReal(FCDot(v, v)) + PetscSqrtReal(FCDot(w, w)) * H);
  }
  H += vkin * h * nsteps;
  speed += vkin;
  for (PetscInt i = 0; i < nbodies; i++) {
    FCEnergy    E;
    const char *name;
    PetscReal   m = FCBodyGetMass(bodies[i]);
    PetscCall(FCBodyGetEnergy(bodies[i], &E));
    PetscCall(FCBodyGetName(bodies[i], &name));
    PetscCheck(PetscIsNormalReal(Total(&E)) || Total(&E) == 0.0, comm, PETSC_ERR_USER_INPUT,
               "Body '%s': its initial energy is not finite (kinetic %g, elastic %g, gravity %g J): its mass %g kg "
               "(-%s_density), speed (-%s_velocity, -%s_angular_velocity) or placement (-%s_translate) is too large",
               name, (double)E.kinetic, (double)E.elastic, (double)E.gravity, (double)m, name, name, name, name);
    g->Eb0[i] = Total(&E);
    g->E0 += g->Eb0[i];
    FCBodyGetGravity(bodies[i], gv);
    grav = PetscSqrtReal(FCDot(gv, gv));
    g->scale += PetscAbsReal(E.kinetic) + PetscAbsReal(E.elastic) + m * grav * H + 0.5 * m * speed * speed;
  }
  PetscFunctionReturn(0);
}

PetscErrorCode FCEnergyGuardCheck(FCEnergyGuard *g, MPI_Comm comm, PetscInt nbodies, FCBody bodies[], PetscInt step,
                                  PetscReal t, PetscReal h)
{
  PetscReal   Etot = 0.0, grow = -PETSC_MAX_REAL, work = 0.0;
  PetscInt    worst = 0;
  FCEnergy    E;
  const char *name;
  char        cause[512] = "";

  PetscFunctionBegin;
  if (g->limit == 0.0 || g->reported) PetscFunctionReturn(0);
  for (PetscInt i = 0; i < nbodies; i++) {
    PetscReal w;
    PetscCall(FCBodyGetEnergy(bodies[i], &E));
    PetscCall(FCBodyGetExternalWork(bodies[i], &w));
    Etot += Total(&E);
    work += w;
    if (!(Total(&E) - g->Eb0[i] <= grow)) { /* NaN counts as the largest growth */
      grow  = Total(&E) - g->Eb0[i];
      worst = i;
    }
  }
  if (PetscIsNormalReal(Etot - g->E0) || Etot == g->E0) {
    if (Etot - g->E0 <= g->limit * (g->scale + work)) PetscFunctionReturn(0);
  }
  g->reported = PETSC_TRUE;
  PetscCall(FCBodyGetName(bodies[worst], &name));
  if (PetscIsInfOrNanReal(Etot) || PetscIsInfOrNanReal(work)) { /* not a growth: no figure to compare */
    PetscCall(FCBodyGetEnergy(bodies[worst], &E));
    SETERRQ(comm, PETSC_ERR_FP,
            "step %" PetscInt_FMT " (t = %g s): the energy of body '%s' is not finite (kinetic %g, elastic %g, gravity "
            "%g J; work of its loads and prescribed motion %g J): its state holds a NaN or an infinity. A numerical "
            "blow-up grows finite first, and this guard stops it there (-energy_growth_limit); a state that is not "
            "finite at once comes from an input that is not: a load, a table of time or a trajectory, a kinematic "
            "body's pose",
            step, (double)t, name, (double)E.kinetic, (double)E.elastic, (double)E.gravity, (double)work);
  }
  if (FCBodyIsDeformable(bodies[worst]))
    PetscCall(PetscSNPrintf(cause, sizeof(cause), " or body '%s' too stiff for it (-%s_young)", name, name));
  SETERRQ(comm, PETSC_ERR_CONV_FAILED,
          "step %" PetscInt_FMT " (t = %g s): the total energy grew from %g J to %g J, more than -energy_growth_limit "
          "%g times the %g J the scene can receive (initial kinetic energy, weight over the scene's height, work of "
          "kinematic bodies, prescribed displacements and loads, separation of overlapping bodies); the energy of body "
          "'%s' grew most. Nothing does such "
          "work: the run is blowing up numerically. Likely cause: -time_step %g too large for the contacts%s; make "
          "-time_step smaller, or raise -energy_growth_limit (0: off) if the growth is real",
          step, (double)t, (double)g->E0, (double)Etot, (double)g->limit, (double)(g->scale + work), name, (double)h,
          cause);
}
