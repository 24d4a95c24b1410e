/* FCScheme: a constraint scheme, -constraint_scheme <type> (default fast), one file per type:
     explicit  Algorithm 1: linearize once, W = sum J A^-1 J^T, PGS, correction   (explicit.c)
     standard  Algorithm 2: Newton iterations, W_k rebuilt by solves and the proximity measured
               on the corrected state                                             (standard.c)
     fast      Algorithm 3: W_H = H A^-1 H^T once per step, then Newton iterations with
               W_k = C_k W_H C_k^T and p = p_free + h^2 W_H C_k^T lambda         (fast.c)
   recursive.c holds what the two recursive schemes share (their options, the re-linearization,
   the convergence test). This file holds what all three share: the options below, the contact
   solver (-pgs_*, -contact_solver: src/contact/solver.c), the memory check, the assembly of W and its check, the
   correction of every body, and the check of the solver's residual. The warm start is one rule
   for all three (FCContactSetWarmStart): the previous step's world force of the same contact,
   projected on this step's frame.
   Options: -constraint_scheme, -contact_memory_limit, -pgs_fail_residual (help strings below;
   docs/options.md). */
#include "schemeimpl.h"
#include <unistd.h>

PetscFunctionList FCSchemeList = NULL;

PetscErrorCode FCSchemeRegister(const char name[], PetscErrorCode (*create)(FCScheme))
{
  PetscFunctionBegin;
  FCValidPointer(name, 1);
  FCValidPointer(create, 2);
  PetscCall(PetscFunctionListAdd(&FCSchemeList, name, create));
  PetscFunctionReturn(0);
}

/* The built-in types: a new type is one file with its create function, declared and registered here */
PETSC_INTERN PetscErrorCode FCSchemeCreate_Explicit(FCScheme);
PETSC_INTERN PetscErrorCode FCSchemeCreate_Standard(FCScheme);
PETSC_INTERN PetscErrorCode FCSchemeCreate_Fast(FCScheme);

PetscErrorCode FCSchemeRegisterAll(void)
{
  PetscFunctionBegin;
  PetscCall(FCSchemeRegister(FCSCHEMEEXPLICIT, FCSchemeCreate_Explicit));
  PetscCall(FCSchemeRegister(FCSCHEMESTANDARD, FCSchemeCreate_Standard));
  PetscCall(FCSchemeRegister(FCSCHEMEFAST, FCSchemeCreate_Fast));
  PetscFunctionReturn(0);
}

PetscErrorCode FCSchemeCreate(MPI_Comm comm, PetscInt nbodies, FCBody bodies[], FCScheme *scheme)
{
  FCScheme s;

  PetscFunctionBegin;
  PetscCall(FCInitializePackage());
  PetscCall(PetscNew(&s));
  s->comm          = comm;
  s->nbodies       = nbodies;
  s->bodies        = bodies;
  s->memory_limit  = 0.5 * (PetscReal)sysconf(_SC_PHYS_PAGES) * (PetscReal)sysconf(_SC_PAGESIZE);
  s->fail_residual = 1e-2;
  *scheme          = s;
  PetscFunctionReturn(0);
}

PetscErrorCode FCSchemeSetType(FCScheme scheme, FCSchemeType type)
{
  PetscErrorCode (*create)(FCScheme) = NULL;

  PetscFunctionBegin;
  PetscCheck(!scheme->type[0], scheme->comm, PETSC_ERR_ORDER, "The constraint scheme already has a type");
  PetscCall(FCRegistryFind(scheme->comm, FCSchemeList, "constraint scheme", "-constraint_scheme", type,
                           (void (**)(void)) & create));
  PetscCall(PetscStrncpy(scheme->type, type, sizeof(scheme->type)));
  PetscCall((*create)(scheme));
  PetscFunctionReturn(0);
}

/* The shared options, -constraint_scheme, then the type's own: another type's options stay
   unread and FCOptionsCheckUnused reports them */
PetscErrorCode FCSchemeSetFromOptions(FCScheme scheme)
{
  char type[FC_MAX_NAME] = FCSCHEMEFAST;

  PetscFunctionBegin;
  PetscOptionsBegin(scheme->comm, NULL, "Constraint scheme", "FCScheme");
  PetscCall(PetscOptionsFList("-constraint_scheme", "Constraint scheme", "FCSchemeSetType", FCSchemeList, type, type,
                              sizeof(type), NULL));
  PetscCall(FCOptionsReal(PetscOptionsObject, "-pgs_fail_residual",
                          "Stop the run when the contact solver ends a step above this residual",
                          &scheme->fail_residual, NULL));
  PetscCall(FCOptionsReal(PetscOptionsObject, "-contact_memory_limit",
                          "Bytes the dense contact matrices of a step may take per rank", &scheme->memory_limit, NULL));
  PetscCheck(scheme->memory_limit > 0, scheme->comm, PETSC_ERR_USER_INPUT,
             "Option -contact_memory_limit must be > 0, got %g", (double)scheme->memory_limit);
  PetscCheck(scheme->fail_residual > 0, scheme->comm, PETSC_ERR_USER_INPUT,
             "Option -pgs_fail_residual must be > 0, got %g", (double)scheme->fail_residual);
  if (!scheme->type[0]) PetscCall(FCSchemeSetType(scheme, type));
  if (scheme->ops.setfromoptions) PetscCall((*scheme->ops.setfromoptions)(scheme, PetscOptionsObject));
  PetscOptionsEnd();
  PetscCall(FCContactSolverCreate(scheme->comm, &scheme->solver));
  PetscCall(FCContactSolverSetFromOptions(scheme->solver));
  PetscFunctionReturn(0);
}

PetscErrorCode FCSchemeSolve(FCScheme scheme, FCContactSet *set, const FCContactSet *previous, FCSchemeStats *st)
{
  PetscFunctionBegin;
  st->contacts = set->n;
  st->rows     = set->nrows;
  st->sweeps   = 0;
  st->residual = 0.0;
  st->newton   = 0;
  if (!set->n) PetscFunctionReturn(0);
  { /* the dense contact matrices, replicated on every rank, against -contact_memory_limit */
    PetscReal   bytes;
    const char *what;
    PetscCall((*scheme->ops.memory)(scheme, set, &bytes, &what));
    PetscCheck(bytes <= scheme->memory_limit, scheme->comm, PETSC_ERR_MEM,
               "%" PetscInt_FMT " contacts (%" PetscInt_FMT " rows): the %s scheme's %s need %.3g GB per rank, above "
               "-contact_memory_limit %.3g GB; use fewer contacts (-contact_distance, coarser surfaces), another "
               "-constraint_scheme (explicit needs W only, %" PetscInt_FMT "^2), or raise the limit",
               set->n, set->nrows, scheme->type, what, (double)(bytes / 1e9), (double)(scheme->memory_limit / 1e9),
               set->nrows);
  }
  PetscCall((*scheme->ops.solve)(scheme, set, previous, st));
  PetscFunctionReturn(0);
}

/* The solve's verdict, apart from it (nothing of the solve is left to free here: step control redoes
   a step that fails it) */
PetscErrorCode FCSchemeCheck(FCScheme scheme, PetscInt step, const FCSchemeStats *st)
{
  PetscFunctionBegin;
  PetscCheck(!(st->residual > scheme->fail_residual), scheme->comm, PETSC_ERR_CONV_FAILED,
             "Step %" PetscInt_FMT ": the contact solver could not reduce its residual: %g after %" PetscInt_FMT
             " sweeps, above -pgs_fail_residual %g (raise -pgs_max_it, lower -time_step, or see docs/hard-cases.md)",
             step, (double)st->residual, st->sweeps, (double)scheme->fail_residual);
  PetscFunctionReturn(0);
}

PetscErrorCode FCSchemeCompliance(FCScheme scheme, const FCContactSet *set, const FCRows *rows, PetscReal W[],
                                  PetscBool *kept)
{
  FCBody   *bodies = scheme->bodies;
  PetscReal h      = scheme->nbodies ? FCBodyTimeStep(bodies[0]) : 0.0;
  PetscBool same   = (PetscBool)(kept && *kept);
  PetscInt  n = set->nrows, r0 = rows ? rows->r0 : 0, r1 = rows ? rows->r1 : n, nw = (r1 - r0) * n;

  PetscFunctionBegin;
  for (PetscInt b = 0; b < scheme->nbodies; b++) { /* every body builds, even once one has changed */
    PetscBool s;
    PetscCall(FCBodyBuildCompliance(bodies[b], b, set, rows, &s));
    same = (PetscBool)(same && s);
  }
  if (rows) PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &same, 1, MPIU_BOOL, MPI_LAND, scheme->comm));
  if (kept) *kept = same;
  if (same) PetscFunctionReturn(0); /* W, summed and checked from these same parts, holds */
  PetscCall(PetscLogEventBegin(FC_EVENT_COMPLIANCE_SUM, 0, 0, 0, 0));
  PetscCall(PetscArrayzero(W, nw));
  for (PetscInt b = 0; b < scheme->nbodies; b++) PetscCall(FCBodyAddCompliance(bodies[b], b, set, rows, W));
  for (PetscInt k = 0; k < nw; k++) W[k] *= h * h;
  { /* a compliance is symmetric with a non-negative diagonal: anything else is a failed factorization
       or builder, which the contact solver would turn into wrong forces without noticing (by rows:
       this rank's diagonal and diagonal block; one verdict) */
    const PetscInt tile = 64; /* the symmetry by tiles: W's columns stay in the cache */
    PetscInt       bad = -1, badrow = -1;
    PetscReal      wmax = 0.0, asym = 0.0, wbad = 0.0;
    for (PetscInt i = r0; i < r1; i++) wmax = PetscMax(wmax, PetscAbsReal(W[(i - r0) * n + i]));
    for (PetscInt k = 0; k < set->n && bad < 0; k++) {
      const FCContact *c     = &set->c[k];
      PetscBool        moves = PETSC_FALSE; /* W_kk > 0 unless neither side can move at the contact */
      for (PetscInt s = 0; s < 2; s++) {
        if (!FCBodyIsPrescribed(bodies[c->body[s]]) && !c->prox[s].nv) moves = PETSC_TRUE; /* rigid */
        for (PetscInt v = 0; v < c->prox[s].nv; v++) /* FE: a free vertex with a weight */
          moves = moves || (c->prox[s].gdof[v] >= 0 && c->prox[s].w[v] != 0.0);
      }
      if (c->row < r0 || c->row >= r1) continue; /* another rank's rows */
      for (PetscInt i = c->row; i < c->row + c->dim && bad < 0; i++) {
        PetscReal d = W[(i - r0) * n + i];
        if (PetscIsInfOrNanReal(d) || d < 0.0 || (moves && d <= 0.0)) {
          bad    = k;
          badrow = i;
          wbad   = d;
        }
      }
    }
    for (PetscInt i0 = r0; i0 < r1; i0 += tile)
      for (PetscInt j0 = i0; j0 < r1; j0 += tile)
        for (PetscInt i = i0; i < PetscMin(i0 + tile, r1); i++)
          for (PetscInt j = PetscMax(j0, i + 1); j < PetscMin(j0 + tile, r1); j++)
            asym = PetscMax(asym, PetscAbsReal(W[(i - r0) * n + j] - W[(j - r0) * n + i]));
    if (rows) { /* one verdict: the first bad contact, the largest asymmetry and diagonal */
      PetscReal v[3] = {bad >= 0 ? (PetscReal)bad : (PetscReal)set->n, -asym, -wmax};
      PetscCallMPI(MPIU_Allreduce(MPI_IN_PLACE, v, 3, MPIU_REAL, MPIU_MIN, scheme->comm));
      if ((PetscInt)v[0] != bad) bad = -1; /* reported by its rank */
      asym = -v[1];
      wmax = -v[2];
      PetscCheck((PetscInt)v[0] >= set->n || bad >= 0, scheme->comm, PETSC_ERR_CONV_FAILED,
                 "The contact compliance W is not a compliance at contact %" PetscInt_FMT
                 " (on another rank's rows); the factorization or the -compliance_type builder failed",
                 (PetscInt)v[0]);
    }
    if (bad >= 0)
      SETERRQ(PETSC_COMM_SELF, PETSC_ERR_CONV_FAILED,
              "The contact compliance W is not a compliance: W(%" PetscInt_FMT ",%" PetscInt_FMT
              ") = %g (contact %" PetscInt_FMT ", bodies '%s' and '%s'); the factorization or the -compliance_type "
              "builder failed",
              badrow, badrow, (double)wbad, bad, FCBodyName(bodies[set->c[bad].body[0]]),
              FCBodyName(bodies[set->c[bad].body[1]]));
    PetscCheck(asym <= 1e-8 * wmax, scheme->comm, PETSC_ERR_CONV_FAILED,
               "The contact compliance W is not symmetric (max |W_ij - W_ji| = %g, max W_ii = %g); the factorization "
               "or the -compliance_type builder failed",
               (double)asym, (double)wmax);
  }
  PetscCall(PetscLogEventEnd(FC_EVENT_COMPLIANCE_SUM, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

PetscErrorCode FCSchemeContactSolve(FCScheme scheme, FCContactSet *set, FCContactProblem prob, PetscReal lambda[])
{
  PetscBool *dormant;
  PetscReal  depth;

  PetscFunctionBegin;
  PetscCall(FCContactSetDormantMask(set, &dormant, &depth));
  if (dormant) PetscCall(FCContactProblemSetDormant(prob, dormant, depth));
  PetscCall(FCContactSolverSolve(scheme->solver, prob, lambda));
  PetscCall(FCContactSetDormantRestore(set, &dormant));
  PetscFunctionReturn(0);
}

PetscErrorCode FCSchemeCorrect(FCScheme scheme, const FCContactSet *set, const PetscReal lambda[])
{
  PetscFunctionBegin;
  for (PetscInt b = 0; b < scheme->nbodies; b++) PetscCall(FCBodyApplyCorrection(scheme->bodies[b], b, set, lambda));
  PetscFunctionReturn(0);
}

PetscErrorCode FCSchemeGetHeldMemory(FCScheme scheme, PetscReal *wh, PetscReal *wk)
{
  PetscFunctionBegin;
  *wh = *wk = 0.0;
  if (scheme->ops.held) PetscCall((*scheme->ops.held)(scheme, wh, wk));
  PetscFunctionReturn(0);
}

PetscErrorCode FCSchemeDestroy(FCScheme *scheme)
{
  PetscFunctionBegin;
  if (!*scheme) PetscFunctionReturn(0);
  if ((*scheme)->ops.destroy) PetscCall((*(*scheme)->ops.destroy)(*scheme));
  PetscCall(FCContactSolverDestroy(&(*scheme)->solver));
  PetscCall(PetscFree(*scheme));
  PetscFunctionReturn(0);
}
