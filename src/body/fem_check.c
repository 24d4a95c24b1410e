/* FE body, the checks of its derived quantities at set-up: the mass, the energies its weight and
   motion can reach, the matrices M, K and A = M + h B + h^2 K, all finite, and M not negligible
   next to h^2 K on a body that no vertex holds (else A is singular to double precision for the
   body's free motions and its contact compliance meaningless). Each error names the body, the
   option to change and the range accepted on this mesh with this time step. */
#include "femimpl.h"
#include <float.h>

/* The largest energy (J) and matrix entry accepted: far from overflow, with room for sums */
#define FC_DERIVED_MAX 1e300
/* The smallest ||M|| / ||A|| of a body without fixed vertices: below it, A's free motions have
   fewer than 3 significant digits in double precision */
#define FC_MASS_RATIO_MIN 1e-13

/* |v| without overflow of the squares */
static PetscReal Norm3(const PetscReal v[3])
{
  PetscReal m = PetscMax(PetscAbsReal(v[0]), PetscMax(PetscAbsReal(v[1]), PetscAbsReal(v[2])));
  if (m == 0.0 || !PetscIsNormalReal(m)) return m;
  return m * PetscSqrtReal(PetscSqr(v[0] / m) + PetscSqr(v[1] / m) + PetscSqr(v[2] / m));
}

PetscErrorCode FCFEMCheckDerived(FCBody body)
{
  FEM        *fem = (FEM *)body->data;
  FCMesh     *m   = &fem->mesh;
  const char *p   = body->prefix;
  PetscReal   h = body->h, rho = body->density, E = fem->young, nu = fem->poisson, g = 0.0, s = 0.0;
  PetscReal   loc[3] = {0.0, 0.0, 0.0}; /* volume, largest |X|, largest unit-E element stiffness */
  PetscReal   nM, nK, nA, lam1 = nu / ((1.0 + nu) * (1.0 - 2.0 * nu)), mu1 = 1.0 / (2.0 * (1.0 + nu));

  PetscFunctionBegin;
  for (PetscInt c = 0; c < m->cEnd - m->cStart; c++) {
    PetscReal G[12], gg = 0.0;
    FCTetGradients(&fem->Dminv[9 * c], G);
    for (int i = 0; i < 12; i++) gg += G[i] * G[i];
    loc[0] += fem->vol[c];
    loc[2] = PetscMax(loc[2], fem->vol[c] * gg * (lam1 + 2.0 * mu1));
  }
  for (PetscInt v = 0; v < 3 * (m->vEnd - m->vStart); v++) loc[1] = PetscMax(loc[1], PetscAbsReal(m->X[v]));
  {
    PetscReal vol = loc[0];
    PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &vol, 1, MPIU_REAL, MPIU_SUM, body->comm));
    PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &loc[1], 2, MPIU_REAL, MPIU_MAX, body->comm));
    loc[0] = vol;
  }
  /* mass, weight and motion: m (|g| R + s^2) with R the largest |X| and s the largest initial speed */
  g = Norm3(body->gravity);
  s = Norm3(body->velocity) + Norm3(body->angular_velocity) * 2.0 * loc[1];
  {
    PetscReal perrho = loc[0] * (g * loc[1] + s * s + 1.0); /* energy scale per unit density, >= volume */
    PetscCheck(PetscIsNormalReal(fem->mass) && fem->mass > 0.0 && rho * perrho <= FC_DERIVED_MAX, body->comm,
               PETSC_ERR_USER_INPUT,
               "Body '%s': -%sdensity %g gives it a mass of %g kg, whose weight and motion energies, m (|g| R + v^2) "
               "with |g| = %g m/s^2 (-gravity), heights R up to %g m and speeds v up to %g m/s (-%svelocity, "
               "-%sangular_velocity), are not finite in double precision: -%sdensity must be at most %g kg/m^3 here "
               "(or -gravity or the speeds smaller)",
               body->name, p, (double)rho, (double)(rho * loc[0]), (double)g, (double)loc[1], (double)s, p, p, p,
               (double)(FC_DERIVED_MAX / perrho));
  }
  /* the matrices: K's entries grow like E times the size of an element */
  PetscCall(MatNorm(fem->M, NORM_INFINITY, &nM));
  PetscCall(MatNorm(fem->K, NORM_INFINITY, &nK));
  PetscCall(MatNorm(fem->A, NORM_INFINITY, &nA));
  {
    PetscReal scale = PetscMax(1.0, h * fem->beta + h * h), emax = FC_DERIVED_MAX / (64.0 * loc[2] * scale);
    PetscCheck(PetscIsNormalReal(nK) && nK <= FC_DERIVED_MAX && PetscIsNormalReal(nA) && nA <= FC_DERIVED_MAX,
               body->comm, PETSC_ERR_USER_INPUT,
               "Body '%s': -%syoung %g (with -%spoisson %g) overflows its stiffness matrix on this mesh (K or A has "
               "entries that are not finite): -%syoung must be at most about %g Pa here",
               body->name, p, (double)E, p, (double)nu, p, (double)emax);
    PetscCheck(PetscIsNormalReal(nM) && nM <= FC_DERIVED_MAX, body->comm, PETSC_ERR_USER_INPUT,
               "Body '%s': its mass matrix is not finite (||M|| = %g; -%sdensity %g)", body->name, (double)nM, p,
               (double)rho);
  }
  if (fem->nfixed == 0) { /* nothing holds the body: its rigid motions are carried by M alone */
    PetscReal ratio = nM / nA;
    PetscCheck(ratio >= FC_MASS_RATIO_MIN, body->comm, PETSC_ERR_USER_INPUT,
               "Body '%s': its mass matrix is negligible next to h^2 K (||M|| / ||A|| = %g < %g), so A = M + h B + h^2 "
               "K is singular to double precision for the free motions of a body no vertex holds: -%sdensity %g is too "
               "small for -%syoung %g and -time_step %g; -%sdensity must be at least %g kg/m^3 here (or make "
               "-%syoung or -time_step smaller)",
               body->name, (double)ratio, (double)FC_MASS_RATIO_MIN, p, (double)rho, p, (double)E, (double)h, p,
               (double)(rho * FC_MASS_RATIO_MIN / ratio), p);
  }
  PetscFunctionReturn(0);
}
