/* Constraint schemes, -constraint_scheme <type> (read by the scene):
     explicit  Algorithm 1: linearize once, W = sum J A^-1 J^T, PGS, correction   (explicit.c)
     standard  Algorithm 2: the same Newton iterations, W_k rebuilt by solves and the proximity
               measured on the corrected state                                       (standard.c)
     fast      Algorithm 3: W_H = H A^-1 H^T once per step, then Newton iterations with
               W_k = C_k W_H C_k^T and p = p_free + h^2 W_H C_k^T lambda         (fast.c)      */
#include "../fcimpl.h"

PetscFunctionList FCSchemeList = NULL;

PetscErrorCode FCSchemeExplicitStep(FCSchemeContext *ctx, FCSchemeStats *st)
{
  PetscReal bytes = 8.0 * (PetscReal)ctx->set->nrows * ctx->set->nrows; /* W, replicated */

  PetscFunctionBegin;
  PetscCheck(bytes <= ctx->memory_limit, ctx->comm, PETSC_ERR_MEM,
             "%" PetscInt_FMT " contacts: W (%" PetscInt_FMT " rows, dense) needs %.3g GB per rank, above "
             "-contact_memory_limit %.3g GB; reduce the contacts (-contact_distance, coarser surfaces) or raise the "
             "limit",
             ctx->set->n, ctx->set->nrows, (double)(bytes / 1e9), (double)(ctx->memory_limit / 1e9));
  PetscCall(FCSchemeExplicit(ctx->comm, ctx->nbodies, ctx->bodies, ctx->set, ctx->previous, ctx->solver, st));
  st->newton = ctx->set->n ? 1 : 0;
  PetscFunctionReturn(0);
}

PetscErrorCode FCSchemeRegisterAll(void)
{
  PetscFunctionBegin;
  PetscCall(PetscFunctionListAdd(&FCSchemeList, "explicit", FCSchemeExplicitStep));
  PetscCall(PetscFunctionListAdd(&FCSchemeList, "standard", FCSchemeStandard));
  PetscCall(PetscFunctionListAdd(&FCSchemeList, "fast", FCSchemeFast));
  PetscFunctionReturn(0);
}
