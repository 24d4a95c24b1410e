/* FE body, the nonlinear correction (-<body>_correction nonlinear, for a body whose free motion is
   Newton's, fem_newton.c; the default is linear). The contact schemes correct a body linearly,
   dv = dv_free + h A^-1 J^T lambda (eq. 20), with A linearized where the free motion ended; for a
   nonlinear body in contact that state can be far from the corrected one (the free motion releases
   the contact), and the corrected state is then no equilibrium: its force balance does not close.

     predictor:   the free motion carries the last step's contact forces f_c = J^T lambda_prev
                  (world forces at the contacts' material points) as a load, so that it ends near
                  the contact state; the contact schemes see the linear free motion about it,
                      dv_free = dv_load - h A^-1 f_c,
                  with A the free motion's last Jacobian, the one their W_b (eq. 17) is built from;
     settling:    after the scheme, the body's equilibrium (eq. 5 solved by the same SNES) is solved
                  again with this step's contact forces as a load, f = J^T lambda, from the linearly
                  corrected dv (from dv_load where that start turns a cell inside out);
     re-solving:  where the settling moved the contacts' points, the free motion is linearized at the
                  settled state (dv_free = dv_settled - h A^-1 f, A at the settling's last Jacobian)
                  and the scheme solves again (src/scene/settle.c).

   The step then ends in an equilibrium with its contact forces to the SNES tolerance
   (-<body>_snes_*), the contact conditions holding to -contact_settle_tol. The contact forces act on
   the body as dead loads between solves: where the body held by them alone is unstable (a block
   compressed past its sway load with a frictionless floor, a slab crushed by an impact), A is
   indefinite there, W is no compliance or the settling does not converge, and the step fails
   (docs/method.md, 2.6). f_c is part of the body's state (restart and step control: three more
   columns). */
#include "femimpl.h"

struct _FCFEMNonlinear {
  Vec       fc;                /* the last accepted step's contact forces on the DOFs (N) */
  Vec       f;                 /* this step's */
  Vec       dvload;            /* the free motion with f_c */
  Vec       w;                 /* work */
  Vec       dvlin;             /* the linearly corrected dv, where the settling starts */
  Vec       dvset;             /* the settled dv */
  PetscBool settled, refactor; /* settled in this solve; A formed at a settling iterate */
  PetscBool loaded;            /* f_c was non-zero in this step's free motion */
};

/* -correction linear|nonlinear (read with the body's options) */
PetscErrorCode FCFEMNonlinearSetFromOptions(PetscOptionItems *PetscOptionsObject, FCBody body)
{
  FEM        *fem    = (FEM *)body->data;
  const char *kind[] = {"linear", "nonlinear"};
  PetscInt    k      = fem->correction > 0 ? 1 : 0;
  PetscBool   set;

  PetscFunctionBegin;
  PetscCall(
      PetscOptionsEList("-correction",
                        "The contact correction of a body with a Newton free motion: linear (eq. 20 from the free "
                        "motion) or nonlinear (the last step's contact forces a load of the free motion, the "
                        "equilibrium solved again with this step's, and the contact problem re-solved there)",
                        NULL, kind, 2, kind[k], &k, &set));
  if (set) fem->correction = (PetscInt)k;
  PetscFunctionReturn(0);
}

/* After FCFEMNewtonSetUp: the vectors of a nonlinear correction */
PetscErrorCode FCFEMNonlinearSetUp(FCBody body)
{
  FEM           *fem = (FEM *)body->data;
  FCFEMNonlinear nl;

  PetscFunctionBegin;
  PetscCheck(!fem->correction || fem->free_motion == FC_FREE_MOTION_NEWTON, body->comm, PETSC_ERR_USER_INPUT,
             "Body '%s': -%scorrection nonlinear solves the body's equilibrium by its Newton free motion; give "
             "-%sfree_motion newton too, or -%scorrection linear",
             body->name, body->prefix, body->prefix, body->prefix);
  if (!fem->correction) PetscFunctionReturn(0);
  PetscCall(PetscNew(&nl));
  PetscCall(VecDuplicate(fem->u, &nl->fc));
  PetscCall(VecDuplicate(fem->u, &nl->f));
  PetscCall(VecDuplicate(fem->u, &nl->dvload));
  PetscCall(VecDuplicate(fem->u, &nl->w));
  PetscCall(VecDuplicate(fem->u, &nl->dvlin));
  PetscCall(VecDuplicate(fem->u, &nl->dvset));
  fem->nl          = nl;
  body->state_cols = 9; /* u, v, f_c */
  PetscFunctionReturn(0);
}

PetscErrorCode FCFEMNonlinearDestroy(FCBody body)
{
  FEM           *fem = (FEM *)body->data;
  FCFEMNonlinear nl  = fem->nl;

  PetscFunctionBegin;
  if (!nl) PetscFunctionReturn(0);
  PetscCall(VecDestroy(&nl->fc));
  PetscCall(VecDestroy(&nl->f));
  PetscCall(VecDestroy(&nl->dvload));
  PetscCall(VecDestroy(&nl->w));
  PetscCall(VecDestroy(&nl->dvlin));
  PetscCall(VecDestroy(&nl->dvset));
  PetscCall(PetscFree(fem->nl));
  PetscFunctionReturn(0);
}

/* The predictor's load: b_c += h f_c (before the free motion's SNES) */
PetscErrorCode FCFEMNonlinearAddLoad(FCBody body, Vec bc)
{
  FEM           *fem = (FEM *)body->data;
  FCFEMNonlinear nl  = fem->nl;
  PetscReal      norm;

  PetscFunctionBegin;
  if (!nl) PetscFunctionReturn(0);
  PetscCall(VecNorm(nl->fc, NORM_INFINITY, &norm));
  nl->loaded = norm > 0.0 ? PETSC_TRUE : PETSC_FALSE;
  if (nl->loaded) PetscCall(VecAXPY(bc, body->h, nl->fc));
  PetscFunctionReturn(0);
}

/* After the free motion with f_c, its A factored by the KSP: dv_free = dv_load - h A^-1 f_c, the
   free motion that the contact schemes linearize about (dv_load kept for the settling) */
PetscErrorCode FCFEMNonlinearUnload(FCBody body)
{
  FEM           *fem = (FEM *)body->data;
  FCFEMNonlinear nl  = fem->nl;

  PetscFunctionBegin;
  if (!nl) PetscFunctionReturn(0);
  PetscCall(VecCopy(fem->dv, nl->dvload));
  nl->settled = PETSC_FALSE;
  if (!nl->loaded) PetscFunctionReturn(0);
  PetscCall(VecAXPBY(nl->f, body->h, 0.0, nl->fc));
  PetscCall(FCFEMSolveA(body, nl->f, nl->w, "The nonlinear correction's", 0.0));
  PetscCall(VecAXPY(fem->dv, -1.0, nl->w));
  PetscFunctionReturn(0);
}

/* f = J^T lambda: each contact's world force on this body's side, shared among its proximity
   vertices by their weights (the set is the same on every rank: each adds its own rows) */
static PetscErrorCode ContactForces(FCBody body, const FCContactSet *set, Vec f)
{
  PetscScalar *a;
  PetscInt     lo, hi;

  PetscFunctionBegin;
  PetscCall(VecZeroEntries(f));
  PetscCall(VecGetOwnershipRange(f, &lo, &hi));
  PetscCall(VecGetArray(f, &a));
  for (PetscInt i = 0; set && i < set->n; i++) {
    const FCContact *c = &set->c[i];
    PetscReal        F[3];
    FCContactForceWorld(c, F); /* on side 1; side 2 takes -F */
    for (int s = 0; s < 2; s++) {
      if (c->body[s] != body->self) continue;
      for (PetscInt k = 0; k < c->prox[s].nv; k++) {
        PetscInt g = c->prox[s].gdof[k];
        if (g < lo || g >= hi) continue; /* another rank's, or a constrained vertex (g < 0) */
        for (int d = 0; d < 3; d++) a[g - lo + d] += (s == 0 ? 1.0 : -1.0) * c->prox[s].w[k] * F[d];
      }
    }
  }
  PetscCall(VecRestoreArray(f, &a));
  PetscFunctionReturn(0);
}

/* The largest displacement h |dv - dv_lin| of a vertex of this body's contacts: how far the settling
   moved them from where the scheme's linear correction put them */
static PetscErrorCode ContactVerticesMoved(FCBody body, const FCContactSet *set, PetscReal *moved)
{
  FEM               *fem = (FEM *)body->data;
  FCFEMNonlinear     nl  = fem->nl;
  const PetscScalar *a, *b;
  PetscInt           lo, hi;
  PetscReal          m = 0.0;

  PetscFunctionBegin;
  PetscCall(VecGetOwnershipRange(fem->dv, &lo, &hi));
  PetscCall(VecGetArrayRead(fem->dv, &a));
  PetscCall(VecGetArrayRead(nl->dvlin, &b));
  for (PetscInt i = 0; set && i < set->n; i++)
    for (int s = 0; s < 2; s++) {
      if (set->c[i].body[s] != body->self) continue;
      for (PetscInt k = 0; k < set->c[i].prox[s].nv; k++) {
        PetscInt  g  = set->c[i].prox[s].gdof[k];
        PetscReal d2 = 0.0;
        if (g < lo || g >= hi) continue;
        for (int d = 0; d < 3; d++) d2 += PetscSqr(PetscRealPart(a[g - lo + d] - b[g - lo + d]));
        m = PetscMax(m, body->h * PetscSqrtReal(d2));
      }
    }
  PetscCall(VecRestoreArrayRead(fem->dv, &a));
  PetscCall(VecRestoreArrayRead(nl->dvlin, &b));
  PetscCall(MPIU_Allreduce(&m, moved, 1, MPIU_REAL, MPIU_MAX, body->comm));
  PetscFunctionReturn(0);
}

/* After the scheme: the equilibrium with this step's contact forces f = J^T lambda (b_c += h (f - f_c)),
   solved from the corrected dv (from dv_load where that start turns a cell inside out); f becomes f_c.
   *moved: how far that took the contacts' vertices from the linear correction. A Newton that fails
   is a failed step (step control) */
PetscErrorCode FCFEMNonlinearSettle(FCBody body, const FCContactSet *set, PetscReal t, PetscReal *moved)
{
  FEM                *fem = (FEM *)body->data;
  FCFEMNonlinear      nl  = fem->nl;
  PetscReal           norm;
  SNESConvergedReason reason;
  PetscInt            its;

  PetscFunctionBegin;
  *moved = 0.0;
  if (!nl) PetscFunctionReturn(0);
  PetscCall(ContactForces(body, set, nl->f));
  PetscCall(VecNorm(nl->f, NORM_INFINITY, &norm));
  if (norm == 0.0 && !nl->loaded) PetscFunctionReturn(0); /* no contact force before or now: dv is the free motion */
  PetscCall(FCPhaseBegin(FC_PHASE_CORRECTION));
  PetscCall(VecCopy(fem->dv, nl->dvlin));
  PetscCall(VecAXPY(fem->nbc, body->h, nl->f));
  PetscCall(VecAXPY(fem->nbc, -body->h, nl->fc));
  fem->jacobian = PETSC_FALSE;
  PetscCall(SNESSolve(fem->snes, NULL, fem->dv));
  PetscCall(SNESGetConvergedReason(fem->snes, &reason));
  PetscCall(SNESGetIterationNumber(fem->snes, &its));
  if (reason == SNES_DIVERGED_FUNCTION_DOMAIN && its == 0) { /* the linear correction turned a cell inside out */
    PetscCall(VecCopy(nl->dvload, fem->dv));
    PetscCall(SNESSolve(fem->snes, NULL, fem->dv));
    PetscCall(SNESGetConvergedReason(fem->snes, &reason));
    PetscCall(SNESGetIterationNumber(fem->snes, &its));
  }
  PetscCall(FCPhaseEnd(FC_PHASE_CORRECTION));
  PetscCheck(reason > 0, body->comm, PETSC_ERR_CONV_FAILED,
             "The equilibrium of body '%s' with its contact forces (-%scorrection nonlinear) did not converge at t = "
             "%g: %s after %" PetscInt_FMT " iterations (-%ssnes_monitor shows them; a smaller -time_step)",
             body->name, body->prefix, (double)t, SNESConvergedReasons[reason], its, body->prefix);
  fem->nnewton += its;
  nl->settled  = PETSC_TRUE;
  nl->refactor = fem->jacobian;
  PetscCall(VecCopy(fem->dv, nl->dvset));
  PetscCall(VecCopy(nl->f, nl->fc));
  PetscCall(ContactVerticesMoved(body, set, moved));
  PetscFunctionReturn(0);
}

/* Before the scheme solves again: the free motion linearized at the settled state,
   dv_free = dv - h A^-1 f_c with A at the settling's last Jacobian (factored for the compliance
   builder too), so that the contacts' free positions and W_b are those of the settled state */
PetscErrorCode FCFEMNonlinearRelinearize(FCBody body)
{
  FEM           *fem = (FEM *)body->data;
  FCFEMNonlinear nl  = fem->nl;

  PetscFunctionBegin;
  if (!nl || !nl->settled) PetscFunctionReturn(0);
  nl->settled = PETSC_FALSE;
  if (nl->refactor) PetscCall(FCFEMFactorA(body));
  PetscCall(VecAXPBY(nl->f, body->h, 0.0, nl->fc));
  PetscCall(FCFEMSolveA(body, nl->f, nl->w, "The nonlinear correction's", 0.0));
  PetscCall(VecWAXPY(fem->dv, -1.0, nl->w, nl->dvset));
  PetscFunctionReturn(0);
}

/* Restart and step control: f_c of the vertices in visual order (3 values after u and v) */
PetscErrorCode FCFEMNonlinearGetState(FCBody body, PetscInt cols, PetscReal s[])
{
  FEM               *fem = (FEM *)body->data;
  FCMesh            *m   = &fem->mesh;
  const PetscScalar *f;
  PetscInt           lo;

  PetscFunctionBegin;
  if (!fem->nl) PetscFunctionReturn(0);
  PetscCall(VecGetOwnershipRange(fem->nl->fc, &lo, NULL));
  PetscCall(VecGetArrayRead(fem->nl->fc, &f));
  for (PetscInt i = 0; i < body->visual.nv; i++) {
    PetscInt vx = m->visVert[i];
    for (int d = 0; d < 3; d++) s[cols * i + 6 + d] = fem->fixed[vx] ? 0.0 : PetscRealPart(f[fem->gdof[vx] - lo + d]);
  }
  PetscCall(VecRestoreArrayRead(fem->nl->fc, &f));
  PetscFunctionReturn(0);
}

PetscErrorCode FCFEMNonlinearSetState(FCBody body, PetscInt cols, const PetscReal s[])
{
  FEM         *fem = (FEM *)body->data;
  FCMesh      *m   = &fem->mesh;
  PetscScalar *f;
  PetscInt     lo;

  PetscFunctionBegin;
  if (!fem->nl) PetscFunctionReturn(0);
  PetscCall(VecGetOwnershipRange(fem->nl->fc, &lo, NULL));
  PetscCall(VecGetArray(fem->nl->fc, &f));
  for (PetscInt i = 0; i < body->visual.nv; i++) {
    PetscInt vx = m->visVert[i];
    if (fem->fixed[vx]) continue;
    for (int d = 0; d < 3; d++) f[fem->gdof[vx] - lo + d] = s[cols * i + 6 + d];
  }
  PetscCall(VecRestoreArray(fem->nl->fc, &f));
  PetscFunctionReturn(0);
}
