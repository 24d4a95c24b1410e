/* FCCompliance: how an FE body computes its part of the contact compliance (eq. 17)
       W_b = J_b A_b^-1 J_b^T
   and applies the contact forces to its motion (eq. 20)
       dv_b = dv_free,b + h A_b^-1 J_b^T lambda.
   One file per builder type, registered here (-compliance_type, default condensed):
     dense, sparse      dense.c        MUMPS solves with dense or sparse right-hand sides J_b^T
     schur              schur.c        Schur complement of the augmented matrix [[0, J], [J^T, A]]
     inverse, redundant inverse.c      the block of A^-1 on the contact DOFs (selected inverse)
     precomputed        precomputed.c  cached surface columns of A_0^-1, warped by the best-fit rotation
     condensed          condensed.c    (A^-1)_SS from the body's own factorization of A with the contact
                                       DOFs S last (schurfactor.c): the factor the step needs anyway
   This file holds what every builder shares: J_b^T of the step by entries, the scatter of the
   builder's W_b into W, and the correction by one solve with the body's factor; congruence.c the
   dense products J_S C J_S^T of the selected-inverse builders. The body hands
   a builder an FCComplianceContext (A, its factorization, layout, surface) and the builder never
   calls the body back. docs/architecture.md says how to add a builder. */
#include "complianceimpl.h"

PetscFunctionList FCComplianceList = NULL;

PetscErrorCode FCComplianceRegister(const char name[], PetscErrorCode (*create)(FCCompliance))
{
  PetscFunctionBegin;
  FCValidPointer(name, 1);
  FCValidPointer(create, 2);
  PetscCall(PetscFunctionListAdd(&FCComplianceList, name, create));
  PetscFunctionReturn(0);
}

/* The built-in types: a new type is one file with its create function, declared and registered here */
PETSC_INTERN PetscErrorCode FCComplianceCreate_Dense(FCCompliance);
PETSC_INTERN PetscErrorCode FCComplianceCreate_Sparse(FCCompliance);
PETSC_INTERN PetscErrorCode FCComplianceCreate_Schur(FCCompliance);
PETSC_INTERN PetscErrorCode FCComplianceCreate_Inverse(FCCompliance);
PETSC_INTERN PetscErrorCode FCComplianceCreate_Redundant(FCCompliance);
PETSC_INTERN PetscErrorCode FCComplianceCreate_Precomputed(FCCompliance);
PETSC_INTERN PetscErrorCode FCComplianceCreate_Condensed(FCCompliance);

PetscErrorCode FCComplianceRegisterAll(void)
{
  PetscFunctionBegin;
  PetscCall(FCComplianceRegister(FCCOMPLIANCEDENSE, FCComplianceCreate_Dense));
  PetscCall(FCComplianceRegister(FCCOMPLIANCESPARSE, FCComplianceCreate_Sparse));
  PetscCall(FCComplianceRegister(FCCOMPLIANCESCHUR, FCComplianceCreate_Schur));
  PetscCall(FCComplianceRegister(FCCOMPLIANCEINVERSE, FCComplianceCreate_Inverse));
  PetscCall(FCComplianceRegister(FCCOMPLIANCEREDUNDANT, FCComplianceCreate_Redundant));
  PetscCall(FCComplianceRegister(FCCOMPLIANCEPRECOMPUTED, FCComplianceCreate_Precomputed));
  PetscCall(FCComplianceRegister(FCCOMPLIANCECONDENSED, FCComplianceCreate_Condensed));
  PetscFunctionReturn(0);
}

PetscErrorCode FCComplianceCreate(const FCComplianceContext *ctx, FCCompliance *comp)
{
  FCCompliance c;

  PetscFunctionBegin;
  PetscCall(FCInitializePackage());
  PetscCall(PetscNew(&c));
  c->ctx = *ctx;
  FCMat3Identity(c->R);
  *comp = c;
  PetscFunctionReturn(0);
}

PetscErrorCode FCComplianceSetType(FCCompliance comp, FCComplianceType type)
{
  PetscErrorCode (*create)(FCCompliance) = NULL;

  PetscFunctionBegin;
  PetscCheck(!comp->type[0], comp->ctx.comm, PETSC_ERR_ORDER, "The compliance builder of body '%s' already has a type",
             comp->ctx.name);
  PetscCall(FCRegistryFind(comp->ctx.comm, FCComplianceList, "compliance type", "-compliance_type", type,
                           (void (**)(void)) & create));
  PetscCall(PetscStrncpy(comp->type, type, sizeof(comp->type)));
  PetscCall((*create)(comp));
  PetscFunctionReturn(0);
}

/* Whether a KSP is the default solver of an FE body, preonly + Cholesky by MUMPS (a factorization) */
PetscErrorCode FCComplianceKSPIsMumps(KSP ksp, PetscBool *mumps)
{
  PC            pc;
  KSPType       ktype;
  MatSolverType stype;
  PetscBool     preonly, cholesky;

  PetscFunctionBegin;
  PetscCall(KSPGetType(ksp, &ktype));
  PetscCall(KSPGetPC(ksp, &pc));
  PetscCall(PetscStrcmp(ktype, KSPPREONLY, &preonly));
  PetscCall(PetscObjectTypeCompare((PetscObject)pc, PCCHOLESKY, &cholesky));
  *mumps = PETSC_FALSE;
  if (preonly && cholesky) {
    PetscCall(PCFactorGetMatSolverType(pc, &stype));
    PetscCall(PetscStrcmp(stype, MATSOLVERMUMPS, mumps));
  }
  PetscFunctionReturn(0);
}

/* Whether the body's solver is the default one */
PetscErrorCode FCComplianceBodySolverIsMumps(FCCompliance comp, PetscBool *mumps)
{
  PetscFunctionBegin;
  PetscCall(FCComplianceKSPIsMumps(comp->ctx.ksp, mumps));
  PetscFunctionReturn(0);
}

/* -compliance_type, then the options of that type only: another type's options stay unread and
   FCOptionsCheckUnused reports them. The default, from docs/benchmarks.md ("Compliance builders":
   the fastest step in contact for linear and co-rotational bodies, on 1 and 2 ranks): condensed,
   which factors A with MUMPS itself; a body whose solver options ask for another solver gets dense,
   which works with any. */
PetscErrorCode FCComplianceSetFromOptions(FCCompliance comp)
{
  char      type[FC_MAX_NAME] = FCCOMPLIANCECONDENSED;
  PetscBool set, mumps;

  PetscFunctionBegin;
  PetscCall(FCComplianceBodySolverIsMumps(comp, &mumps));
  if (!mumps) PetscCall(PetscStrncpy(type, FCCOMPLIANCEDENSE, sizeof(type)));
  PetscOptionsBegin(comp->ctx.comm, NULL, "Compliance builder of FE bodies", "FCCompliance");
  PetscCall(PetscOptionsFList("-compliance_type", "How FE bodies compute J A^-1 J^T", "FCComplianceSetType",
                              FCComplianceList, type, type, sizeof(type), &set));
  if (!comp->type[0]) PetscCall(FCComplianceSetType(comp, type));
  if (comp->ops.setfromoptions) PetscCall((*comp->ops.setfromoptions)(comp, PetscOptionsObject));
  PetscOptionsEnd();
  PetscFunctionReturn(0);
}

PetscErrorCode FCComplianceSetUp(FCCompliance comp)
{
  PetscFunctionBegin;
  if (comp->setupcalled) PetscFunctionReturn(0);
  if (!comp->type[0]) PetscCall(FCComplianceSetFromOptions(comp));
  /* a builder that keeps its W_b forms it by rows (FCComplianceBuild hands the others a zeroed whole
     W_b, where a kept one would be lost) */
  PetscCheck(!comp->keepswb || comp->windows, comp->ctx.comm, PETSC_ERR_PLIB,
             "Compliance builder '%s' keeps its W_b (keepswb) but does not form it by rows (windows)", comp->type);
  if (comp->ops.setup) PetscCall((*comp->ops.setup)(comp));
  comp->setupcalled = PETSC_TRUE;
  PetscFunctionReturn(0);
}

PetscErrorCode FCComplianceFactor(FCCompliance comp)
{
  PetscFunctionBegin;
  if (comp->setupcalled && comp->ops.factor) PetscCall((*comp->ops.factor)(comp));
  PetscFunctionReturn(0);
}

PetscBool FCComplianceFactorsA(FCCompliance comp)
{
  return comp->factors;
}

PetscErrorCode FCComplianceSolve(FCCompliance comp, Vec b, Vec x)
{
  PetscFunctionBegin;
  PetscCheck(comp->factors && comp->setupcalled, comp->ctx.comm, PETSC_ERR_PLIB,
             "FCComplianceSolve on body '%s': builder '%s' holds no factor of A", comp->ctx.name, comp->type);
  PetscCall((*comp->ops.solve)(comp, b, x));
  PetscFunctionReturn(0);
}

PetscBool FCComplianceUsesRotation(FCCompliance comp)
{
  return comp->rotation;
}

PetscBool FCComplianceKeepsInitialA(FCCompliance comp)
{
  return strcmp(comp->type, FCCOMPLIANCEPRECOMPUTED) ? PETSC_FALSE : PETSC_TRUE;
}

PetscErrorCode FCComplianceSetRotation(FCCompliance comp, const PetscReal R[9])
{
  PetscFunctionBegin;
  for (int i = 0; i < 9; i++) comp->R[i] = R[i];
  PetscFunctionReturn(0);
}

PetscErrorCode FCComplianceSetWarp(FCCompliance comp, PetscInt nsurf, const PetscInt sdof[], const PetscReal sQ[],
                                   PetscInt nowned, const PetscReal oQ[])
{
  PetscFunctionBegin;
  comp->wnsurf  = nsurf;
  comp->wsdof   = sdof;
  comp->wsQ     = sQ;
  comp->wnowned = nowned;
  comp->woQ     = oQ;
  PetscFunctionReturn(0);
}

PetscErrorCode FCComplianceGetCorrectionRHS(FCCompliance comp, Vec *rhs)
{
  PetscFunctionBegin;
  *rhs = comp->ops.correct ? NULL : comp->rhs;
  PetscFunctionReturn(0);
}

PetscInt FCComplianceOwnFactorizations(FCCompliance comp)
{
  return comp->nownfactor;
}

void FCComplianceDirection(const FCContact *c, PetscInt side, PetscInt a, PetscReal e[3])
{
  const PetscReal *f = a == 0 ? c->n : (a == 1 ? c->t1 : c->t2);
  for (int i = 0; i < 3; i++) e[i] = (side == 0 ? 1.0 : -1.0) * f[i];
}

PetscErrorCode FCComplianceGetFactor(FCCompliance comp, Mat *F)
{
  PC pc;

  PetscFunctionBegin;
  PetscCall(KSPGetPC(comp->ctx.ksp, &pc));
  PetscCall(PCFactorGetMatrix(pc, F));
  PetscFunctionReturn(0);
}

/* Forgets the step's contact columns */
static PetscErrorCode Reset(FCCompliance comp)
{
  PetscFunctionBegin;
  if (comp->ops.reset) PetscCall((*comp->ops.reset)(comp));
  PetscCall(PetscFree(comp->cols));
  PetscCall(PetscFree3(comp->jtr, comp->jtc, comp->jtv));
  comp->ncols = comp->njt = comp->nje = 0;
  comp->pending                       = PETSC_FALSE;
  PetscFunctionReturn(0);
}

/* J_b^T of the contacts touching body `self` by entries, at most 9 per column (3 vertices x 3
   components): the owned DOFs' first (pass 0, njt of them), then the others' (pass 1, nje in all;
   the selected-inverse builders need every entry, on every rank) */
static PetscErrorCode BuildJacobian(FCCompliance comp, PetscInt self, const FCContactSet *set)
{
  PetscInt nloc, lo, ncols = 0, n = 0;

  PetscFunctionBegin;
  for (PetscInt k = 0; k < set->n; k++)
    for (PetscInt s = 0; s < 2; s++)
      if (set->c[k].body[s] == self) {
        ncols += set->c[k].dim;
        n += set->c[k].dim * 3 * set->c[k].prox[s].nv;
      }
  if (!ncols) PetscFunctionReturn(0);
  PetscCall(PetscMalloc1(ncols, &comp->cols));
  PetscCall(PetscMalloc3(n, &comp->jtr, n, &comp->jtc, n, &comp->jtv));
  PetscCall(VecGetLocalSize(comp->ctx.u, &nloc));
  PetscCall(VecGetOwnershipRange(comp->ctx.u, &lo, NULL));
  for (int pass = 0; pass < 2; pass++) {
    if (pass) comp->njt = comp->nje;
    ncols = 0;
    for (PetscInt k = 0; k < set->n; k++)
      for (PetscInt s = 0; s < 2; s++) {
        const FCContact *c = &set->c[k];
        if (c->body[s] != self) continue;
        for (PetscInt a = 0; a < c->dim; a++, ncols++) {
          PetscReal e[3];
          comp->cols[ncols] = c->row + a;
          FCComplianceDirection(c, s, a, e);
          for (PetscInt vtx = 0; vtx < c->prox[s].nv; vtx++) {
            PetscInt  g = c->prox[s].gdof[vtx];
            PetscReal ew[3];
            if (g < 0 || (g >= lo && g < lo + nloc) == (pass == 1)) continue; /* fixed, or the other pass's */
            if (comp->wsdof) { /* the row of J Q at this vertex: (Q^T e)^T */
              PetscInt at;
              PetscCall(PetscFindInt(g, comp->wnsurf, comp->wsdof, &at));
              PetscCheck(at >= 0, comp->ctx.comm, PETSC_ERR_PLIB,
                         "Body '%s': contact DOF %" PetscInt_FMT " is not on the surface the warp knows",
                         comp->ctx.name, g);
              FCMat3TVec(&comp->wsQ[9 * at], e, ew);
            } else
              for (int d = 0; d < 3; d++) ew[d] = e[d];
            for (int d = 0; d < 3; d++, comp->nje++) {
              comp->jtr[comp->nje] = g - lo + d;
              comp->jtc[comp->nje] = ncols;
              comp->jtv[comp->nje] = c->prox[s].w[vtx] * ew[d];
            }
          }
        }
      }
  }
  comp->ncols = ncols;
  PetscFunctionReturn(0);
}

PetscBool FCComplianceUsesExpectedContacts(FCCompliance comp)
{
  return (PetscBool)(comp->ops.expect != NULL);
}

/* The contacts of a start-of-run proximity query, before the first factorization: J_b^T of
   them for the builder's expect, then forgotten (the step's Add builds its own) */
PetscErrorCode FCComplianceExpectContacts(FCCompliance comp, PetscInt self, const FCContactSet *set)
{
  PetscFunctionBegin;
  if (!comp->ops.expect) PetscFunctionReturn(0);
  PetscCall(Reset(comp));
  PetscCall(BuildJacobian(comp, self, set));
  PetscCall((*comp->ops.expect)(comp));
  PetscCall(Reset(comp));
  PetscFunctionReturn(0);
}

PetscErrorCode FCComplianceBuild(FCCompliance comp, PetscInt self, const FCContactSet *set, const FCRows *rows,
                                 PetscBool *same)
{
  PetscInt  ncols0 = comp->ncols, *cols0 = comp->cols, ncols, a0, a1;
  PetscBool eq = PETSC_TRUE;

  PetscFunctionBegin;
  PetscCheck(comp->setupcalled, comp->ctx.comm, PETSC_ERR_ORDER, "Compliance builder of body '%s' not set up",
             comp->ctx.name);
  comp->cols = NULL; /* the last build's rows of W, compared below */
  PetscCall(Reset(comp));
  PetscCall(BuildJacobian(comp, self, set));
  ncols      = comp->ncols;
  comp->kept = PETSC_FALSE;
  a0         = 0; /* the rows of W_b in this rank's rows of W: comp->cols ascends (contact order) */
  a1         = ncols;
  if (rows) {
    while (a0 < ncols && comp->cols[a0] < rows->r0) a0++;
    for (a1 = a0; a1 < ncols && comp->cols[a1] < rows->r1;) a1++;
  }
  if (ncols != comp->wb_n || a0 != comp->wa0 || a1 != comp->wa1) {
    PetscCall(PetscFree(comp->Wb));
    PetscCall(PetscMalloc1((a1 - a0) * ncols + 1, &comp->Wb));
    comp->wb_n     = ncols;
    comp->wa0      = a0;
    comp->wa1      = a1;
    comp->wb_valid = PETSC_FALSE;
  }
  if (ncols) {
    if (!comp->keepswb || !comp->wb_valid) PetscCall(PetscArrayzero(comp->Wb, (a1 - a0) * ncols));
    if (comp->windows || (a0 == 0 && a1 == ncols))
      PetscCall((*comp->ops.build)(comp, self, set, comp->Wb));
    else { /* a builder that forms W_b whole: its rows of this rank kept */
      PetscReal *full;
      PetscCall(PetscCalloc1(ncols * ncols, &full));
      PetscCall((*comp->ops.build)(comp, self, set, full));
      PetscCall(PetscArraycpy(comp->Wb, full + a0 * ncols, (a1 - a0) * ncols));
      PetscCall(PetscFree(full));
    }
    comp->wb_valid = PETSC_TRUE;
  }
  comp->pending = PETSC_TRUE;
  if (ncols == ncols0 && ncols) PetscCall(PetscArraycmp(comp->cols, cols0, ncols, &eq));
  *same = (PetscBool)(ncols == ncols0 && (!ncols || (comp->kept && eq)));
  PetscCall(PetscFree(cols0));
  PetscFunctionReturn(0);
}

PetscErrorCode FCComplianceAdd(FCCompliance comp, PetscInt self, const FCContactSet *set, const FCRows *rows,
                               PetscReal W[])
{
  PetscInt         M = set->nrows, ncols, r0 = rows ? rows->r0 : 0;
  const PetscReal *Wb;

  PetscFunctionBegin;
  PetscCheck(comp->pending, comp->ctx.comm, PETSC_ERR_ORDER,
             "Compliance builder of body '%s': FCComplianceAdd without FCComplianceBuild on the same contacts",
             comp->ctx.name);
  comp->pending = PETSC_FALSE;
  ncols         = comp->ncols;
  Wb            = comp->Wb;
  for (PetscInt i = comp->wa0; i < comp->wa1; i++) {
    PetscReal       *w = W + (comp->cols[i] - r0) * M;
    const PetscReal *b = Wb + (i - comp->wa0) * ncols;
    for (PetscInt j = 0; j < ncols; j++) w[comp->cols[j]] += b[j];
  }
  PetscFunctionReturn(0);
}

/* eq. 20: dv += h A^-1 J_b^T lambda_b; by the builder's own operator, or by one solve of the
   right-hand side J_b^T (h lambda_b) assembled from the owned entries */
PetscErrorCode FCComplianceCorrect(FCCompliance comp, PetscReal h, const PetscReal lambda[], Vec dv)
{
  PetscScalar *r;

  PetscFunctionBegin;
  if (!comp->ncols) PetscFunctionReturn(0);
  if (comp->ops.correct) {
    PetscCall((*comp->ops.correct)(comp, h, lambda, dv));
    PetscFunctionReturn(0);
  }
  if (!comp->rhs) {
    PetscCall(VecDuplicate(comp->ctx.u, &comp->rhs));
    PetscCall(VecDuplicate(comp->ctx.u, &comp->work));
  }
  PetscCall(VecZeroEntries(comp->rhs));
  PetscCall(VecGetArray(comp->rhs, &r));
  for (PetscInt q = 0; q < comp->njt; q++) r[comp->jtr[q]] += comp->jtv[q] * h * lambda[comp->cols[comp->jtc[q]]];
  PetscCall(VecRestoreArray(comp->rhs, &r));
  if (comp->ops.solve)
    PetscCall((*comp->ops.solve)(comp, comp->rhs, comp->work));
  else
    PetscCall(KSPSolve(comp->ctx.ksp, comp->rhs, comp->work));
  if (comp->woQ) { /* Q A_0^-1 (J Q)^T h lambda */
    PetscCall(VecGetArray(comp->work, &r));
    for (PetscInt b = 0; b < comp->wnowned; b++) {
      PetscReal y[3], z[3] = {PetscRealPart(r[3 * b]), PetscRealPart(r[3 * b + 1]), PetscRealPart(r[3 * b + 2])};
      FCMat3Vec(&comp->woQ[9 * b], z, y);
      for (int d = 0; d < 3; d++) r[3 * b + d] = y[d];
    }
    PetscCall(VecRestoreArray(comp->work, &r));
  }
  PetscCall(VecAXPY(dv, 1.0, comp->work));
  PetscFunctionReturn(0);
}

PetscErrorCode FCComplianceGetMemory(FCCompliance comp, PetscReal *wb, PetscReal *sigma, PetscReal *factor,
                                     PetscReal *factormax)
{
  PetscFunctionBegin;
  *wb    = 8.0 * (PetscReal)(comp->wa1 - comp->wa0) * comp->wb_n;
  *sigma = *factor = *factormax = 0.0;
  if (comp->ops.memory) PetscCall((*comp->ops.memory)(comp, sigma, factor, factormax));
  PetscFunctionReturn(0);
}

PetscErrorCode FCComplianceDestroy(FCCompliance *comp)
{
  PetscFunctionBegin;
  if (!*comp) PetscFunctionReturn(0);
  PetscCall(Reset(*comp));
  PetscCall(PetscFree((*comp)->Wb));
  if ((*comp)->ops.destroy) PetscCall((*(*comp)->ops.destroy)(*comp));
  PetscCall(VecDestroy(&(*comp)->rhs));
  PetscCall(VecDestroy(&(*comp)->work));
  PetscCall(PetscFree(*comp));
  PetscFunctionReturn(0);
}
