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
     settling:    after the scheme, the body's equilibrium (eq. 5, the same SNES) is solved again
                  with this step's contact forces f = J^T lambda as a load, from the linearly
                  corrected dv (from dv_load where that start turns a cell inside out);
     re-solving:  while the settling's springs (below) carry more than -contact_settle_rtol of the
                  contact forces, the free motion is linearized at the settled state
                  (dv_free = dv_settled - h A^-1 f, A at the settling's last Jacobian) and the scheme
                  solves again (src/scene/settle.c).

   Springs. The contact forces are dead loads in these solves, and a body held by dead loads alone can
   be unstable where the body held by its contacts is not (a block pressed on a floor past its shear
   load, a crushed block whose top sticks to a plate): its A is indefinite, W = J A^-1 J^T then has as
   many negative eigenvalues (the inertia of [A J^T; J 0]) and is no compliance, and the Newton
   solves diverge. Each vertex that carries a contact force therefore gets a spring of stiffness rho
   (-correction_penalty times the largest diagonal of K): along the force where its contacts slide or
   have no friction, in every direction where one sticks; anchored where its velocity at the step's
   start takes it in the free motion, and where the linear correction put the vertex in the settling.
   They stand for the contacts' constraint in A (an augmented Lagrangian: A + rho n n^T on the contact
   vertices), so that A and W stay definite; each solve ends only when what they carry is below -contact_settle_rtol of
   the contact forces, so that the step's state is the equilibrium with its contact forces alone.
   f_c and the sticking vertices are part of the body's state (restart and step control). */
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
  /* the stabilizing springs (header) */
  Vec       sn, sx;        /* per vertex the springs' direction (0: none) and anchor */
  Vec       stick, stickc; /* this step's and the last accepted step's sticking vertices (1 per DOF) */
  Vec       ss;            /* the springs' sticking vertices (a spring in every direction there): one of them */
  PetscBool springs;
  PetscReal rho; /* their stiffness (N/m) */
};

/* -correction linear|nonlinear (read with the body's options) */
PetscErrorCode FCFEMNonlinearSetFromOptions(PetscOptionItems *PetscOptionsObject, FCBody body)
{
  FEM        *fem    = (FEM *)body->data;
  const char *kind[] = {"linear", "nonlinear"};
  PetscInt    k      = fem->correction != 0 ? 1 : 0;
  PetscBool   set;

  PetscFunctionBegin;
  PetscCall(FCOptionsEList(PetscOptionsObject, "-correction",
                           "The contact correction of a body with a Newton free motion: linear (eq. 20 from the free "
                           "motion) or nonlinear (the last step's contact forces a load of the free motion, the "
                           "equilibrium solved again with this step's, and the contact problem re-solved there)",
                           kind, 2, &k, &set));
  if (set) fem->correction = (PetscInt)k;
  PetscCall(FCOptionsReal(PetscOptionsObject, "-correction_penalty",
                          "The nonlinear correction's springs along the contact forces: their stiffness over the "
                          "largest diagonal of K (0: none)",
                          &fem->penalty, NULL));
  PetscCheck(fem->penalty >= 0.0, body->comm, PETSC_ERR_USER_INPUT, "Option -%scorrection_penalty must be >= 0, got %g",
             body->prefix, (double)fem->penalty);
  PetscFunctionReturn(0);
}

/* After FCFEMNewtonSetUp: the vectors of a nonlinear correction */
PetscErrorCode FCFEMNonlinearSetUp(FCBody body)
{
  FEM           *fem = (FEM *)body->data;
  FCFEMNonlinear nl;

  PetscFunctionBegin;
  if (fem->correction < 0) fem->correction = fem->free_motion == FC_FREE_MOTION_NEWTON ? 1 : 0;
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
  PetscCall(VecDuplicate(fem->u, &nl->sn));
  PetscCall(VecDuplicate(fem->u, &nl->sx));
  PetscCall(VecDuplicate(fem->u, &nl->stick));
  PetscCall(VecDuplicate(fem->u, &nl->stickc));
  { /* rho: -correction_penalty times the largest diagonal of K at the reference state */
    Vec d;
    PetscCall(VecDuplicate(fem->u, &d));
    PetscCall(MatGetDiagonal(fem->K, d));
    PetscCall(VecMax(d, NULL, &nl->rho));
    PetscCall(VecDestroy(&d));
    nl->rho *= fem->penalty;
  }
  fem->nl          = nl;
  body->state_cols = 10; /* u, v, f_c, sticking */
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
  PetscCall(VecDestroy(&nl->sn));
  PetscCall(VecDestroy(&nl->sx));
  PetscCall(VecDestroy(&nl->stick));
  PetscCall(VecDestroy(&nl->stickc));
  PetscCall(PetscFree(fem->nl));
  PetscFunctionReturn(0);
}

/* Springs on the vertices that carry contact forces f, anchored at the end-of-step positions
   x* = u + h (v + dv_anchor) (dv_anchor NULL: 0, where the velocity at t takes them): along f_v / |f_v|
   where the contacts slide or have no friction, in every direction where one sticks (stick, kept as is
   while the springs are set) */
static PetscErrorCode SetSprings(FCBody body, Vec f, Vec stick, Vec dv_anchor)
{
  FEM           *fem = (FEM *)body->data;
  FCFEMNonlinear nl  = fem->nl;
  PetscScalar   *n;
  PetscInt       m;

  PetscFunctionBegin;
  nl->springs = nl->rho > 0.0 ? PETSC_TRUE : PETSC_FALSE;
  if (!nl->springs) PetscFunctionReturn(0);
  PetscCall(VecCopy(f, nl->sn));
  PetscCall(VecGetLocalSize(nl->sn, &m));
  PetscCall(VecGetArray(nl->sn, &n));
  for (PetscInt i = 0; i < m; i += 3) {
    PetscReal a = PetscSqrtReal(PetscSqr(PetscRealPart(n[i])) + PetscSqr(PetscRealPart(n[i + 1])) +
                                PetscSqr(PetscRealPart(n[i + 2])));
    for (int d = 0; d < 3; d++) n[i + d] = a > 0.0 ? n[i + d] / a : 0.0;
  }
  PetscCall(VecRestoreArray(nl->sn, &n));
  nl->ss = stick;
  if (dv_anchor) {
    PetscCall(VecWAXPY(nl->sx, 1.0, fem->v, dv_anchor));
    PetscCall(VecAYPX(nl->sx, body->h, fem->u));
  } else
    PetscCall(VecWAXPY(nl->sx, body->h, fem->v, fem->u));
  PetscFunctionReturn(0);
}

/* F += h rho (n . (w - x*)) n at every spring, w the iterate's state at t + h (the Newton residual's) */
PetscErrorCode FCFEMNonlinearAddSpringForce(FCBody body, Vec w, Vec F)
{
  FEM               *fem = (FEM *)body->data;
  FCFEMNonlinear     nl  = fem->nl;
  const PetscScalar *n, *x, *a, *st;
  PetscScalar       *r;
  PetscInt           m;

  PetscFunctionBegin;
  if (!nl || !nl->springs) PetscFunctionReturn(0);
  PetscCall(VecGetLocalSize(F, &m));
  PetscCall(VecGetArrayRead(nl->ss, &st));
  PetscCall(VecGetArrayRead(nl->sn, &n));
  PetscCall(VecGetArrayRead(nl->sx, &a));
  PetscCall(VecGetArrayRead(w, &x));
  PetscCall(VecGetArray(F, &r));
  for (PetscInt i = 0; i < m; i += 3) {
    PetscScalar g = 0.0;
    if (n[i] == 0.0 && n[i + 1] == 0.0 && n[i + 2] == 0.0) continue;
    if (PetscRealPart(st[i]) > 0.0) {
      for (int d = 0; d < 3; d++) r[i + d] += body->h * nl->rho * (x[i + d] - a[i + d]);
      continue;
    }
    for (int d = 0; d < 3; d++) g += n[i + d] * (x[i + d] - a[i + d]);
    for (int d = 0; d < 3; d++) r[i + d] += body->h * nl->rho * g * n[i + d];
  }
  PetscCall(VecRestoreArrayRead(nl->ss, &st));
  PetscCall(VecRestoreArray(F, &r));
  PetscCall(VecRestoreArrayRead(w, &x));
  PetscCall(VecRestoreArrayRead(nl->sx, &a));
  PetscCall(VecRestoreArrayRead(nl->sn, &n));
  PetscFunctionReturn(0);
}

/* A += h^2 rho n n^T at every spring (the residual's derivative; assembled) */
PetscErrorCode FCFEMNonlinearAddSpringStiffness(FCBody body, Mat A)
{
  FEM               *fem = (FEM *)body->data;
  FCFEMNonlinear     nl  = fem->nl;
  const PetscScalar *n, *st;
  PetscInt           m, lo;

  PetscFunctionBegin;
  if (!nl || !nl->springs) PetscFunctionReturn(0);
  PetscCall(VecGetArrayRead(nl->ss, &st));
  PetscCall(VecGetLocalSize(nl->sn, &m));
  PetscCall(VecGetOwnershipRange(nl->sn, &lo, NULL));
  PetscCall(VecGetArrayRead(nl->sn, &n));
  for (PetscInt i = 0; i < m; i += 3) {
    PetscInt    idx[3] = {lo + i, lo + i + 1, lo + i + 2};
    PetscScalar k[9];
    if (n[i] == 0.0 && n[i + 1] == 0.0 && n[i + 2] == 0.0) continue;
    for (int a = 0; a < 3; a++)
      for (int b = 0; b < 3; b++)
        k[3 * a + b] = body->h * body->h * nl->rho *
                       (PetscRealPart(st[i]) > 0.0 ? (a == b ? 1.0 : 0.0) : PetscRealPart(n[i + a] * n[i + b]));
    PetscCall(MatSetValues(A, 3, idx, 3, idx, k, ADD_VALUES));
  }
  PetscCall(VecRestoreArrayRead(nl->sn, &n));
  PetscCall(VecRestoreArrayRead(nl->ss, &st));
  PetscCall(MatAssemblyBegin(A, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(A, MAT_FINAL_ASSEMBLY));
  PetscFunctionReturn(0);
}

/* Whether this step's free motion carries contact forces (after FCFEMNonlinearAddLoad) */
PetscBool FCFEMNonlinearLoaded(FCBody body)
{
  FEM *fem = (FEM *)body->data;
  return fem->nl && fem->nl->loaded ? PETSC_TRUE : PETSC_FALSE;
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
  nl->loaded  = norm > 0.0 ? PETSC_TRUE : PETSC_FALSE;
  nl->springs = PETSC_FALSE;
  if (nl->loaded) {
    PetscCall(VecAXPY(bc, body->h, nl->fc));
    PetscCall(SetSprings(body, nl->fc, nl->stickc, NULL)); /* the contact vertices held where the last step left them */
  }
  PetscFunctionReturn(0);
}

/* dv = base - h A^-1 f_c: the motion from base without the contact forces f_c, linearized by the A
   that W_b is built from (f serves as work) */
static PetscErrorCode Unloaded(FCBody body, Vec base)
{
  FEM           *fem = (FEM *)body->data;
  FCFEMNonlinear nl  = fem->nl;

  PetscFunctionBegin;
  PetscCall(VecAXPBY(nl->f, body->h, 0.0, nl->fc));
  PetscCall(FCFEMSolveA(body, nl->f, nl->w, "The nonlinear correction's", 0.0));
  if (base == fem->dv)
    PetscCall(VecAXPY(fem->dv, -1.0, nl->w));
  else
    PetscCall(VecWAXPY(fem->dv, -1.0, nl->w, base));
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
  PetscCall(Unloaded(body, fem->dv));
  PetscFunctionReturn(0);
}

/* f = J^T lambda: each contact's world force on this body's side, shared among its proximity
   vertices by their weights (the set is the same on every rank: each adds its own rows) */
static PetscErrorCode ContactForces(FCBody body, const FCContactSet *set, Vec f, Vec stick)
{
  PetscScalar *a, *sk;
  PetscInt     lo, hi;

  PetscFunctionBegin;
  PetscCall(VecZeroEntries(f));
  PetscCall(VecZeroEntries(stick));
  PetscCall(VecGetOwnershipRange(f, &lo, &hi));
  PetscCall(VecGetArray(f, &a));
  PetscCall(VecGetArray(stick, &sk));
  for (PetscInt i = 0; set && i < set->n; i++) {
    const FCContact *c = &set->c[i];
    PetscReal        F[3], ft = PetscSqrtReal(PetscSqr(c->force[1]) + PetscSqr(c->force[2]));
    PetscBool        sticks = (PetscBool)(c->dim == 3 && c->force[0] > 0.0 && ft < c->mu * c->force[0] * (1.0 - 1e-6));
    FCContactForceWorld(c, F); /* on side 1; side 2 takes -F */
    for (int s = 0; s < 2; s++) {
      if (c->body[s] != body->self) continue;
      for (PetscInt k = 0; k < c->prox[s].nv; k++) {
        PetscInt g = c->prox[s].gdof[k];
        if (g < lo || g >= hi) continue; /* another rank's, or a constrained vertex (g < 0) */
        for (int d = 0; d < 3; d++) a[g - lo + d] += (s == 0 ? 1.0 : -1.0) * c->prox[s].w[k] * F[d];
        if (sticks && c->prox[s].w[k] > 0.0)
          for (int d = 0; d < 3; d++) sk[g - lo + d] = 1.0;
      }
    }
  }
  PetscCall(VecRestoreArray(f, &a));
  PetscCall(VecRestoreArray(stick, &sk));
  PetscFunctionReturn(0);
}

/* What the springs hold after a settling, relative: rho times the largest displacement h |dv - dv_lin|
   of a contact vertex from where the correction put it, over the largest contact force on a vertex */
static PetscErrorCode SpringsHold(FCBody body, PetscReal *held)
{
  FEM               *fem = (FEM *)body->data;
  FCFEMNonlinear     nl  = fem->nl;
  const PetscScalar *a, *b, *f;
  PetscInt           m;
  PetscReal          mx[2] = {0.0, 0.0}, all[2]; /* largest displacement, largest force */

  PetscFunctionBegin;
  PetscCall(VecGetLocalSize(fem->dv, &m));
  PetscCall(VecGetArrayRead(fem->dv, &a));
  PetscCall(VecGetArrayRead(nl->dvlin, &b));
  PetscCall(VecGetArrayRead(nl->f, &f));
  for (PetscInt i = 0; i < m; i += 3) {
    PetscReal d2 = 0.0, f2 = 0.0;
    for (int d = 0; d < 3; d++) {
      d2 += PetscSqr(PetscRealPart(a[i + d] - b[i + d]));
      f2 += PetscSqr(PetscRealPart(f[i + d]));
    }
    if (f2 == 0.0) continue; /* no contact force on this vertex */
    mx[0] = PetscMax(mx[0], body->h * PetscSqrtReal(d2));
    mx[1] = PetscMax(mx[1], PetscSqrtReal(f2));
  }
  PetscCall(VecRestoreArrayRead(fem->dv, &a));
  PetscCall(VecRestoreArrayRead(nl->dvlin, &b));
  PetscCall(VecRestoreArrayRead(nl->f, &f));
  PetscCall(MPIU_Allreduce(mx, all, 2, MPIU_REAL, MPIU_MAX, body->comm));
  *held = all[1] > 0.0 ? nl->rho * all[0] / all[1] : 0.0;
  PetscFunctionReturn(0);
}

/* After the scheme: the equilibrium with this step's contact forces f = J^T lambda (b_c += h (f - f_c)),
   solved from the corrected dv (from dv_load where that start turns a cell inside out); f becomes f_c.
   *held: what the springs hold there (SpringsHold). A Newton that fails is a failed step (step control) */
PetscErrorCode FCFEMNonlinearSettle(FCBody body, const FCContactSet *set, PetscReal t, PetscReal *held)
{
  FEM                *fem = (FEM *)body->data;
  FCFEMNonlinear      nl  = fem->nl;
  PetscReal           norm;
  SNESConvergedReason reason;
  PetscInt            its;

  PetscFunctionBegin;
  *held = 0.0;
  if (!nl) PetscFunctionReturn(0);
  PetscCall(ContactForces(body, set, nl->f, nl->stick));
  PetscCall(VecNorm(nl->f, NORM_INFINITY, &norm));
  if (norm == 0.0 && !nl->loaded) PetscFunctionReturn(0); /* no contact force before or now: dv is the free motion */
  PetscCall(FCPhaseBegin(FC_PHASE_CORRECTION));
  PetscCall(VecCopy(fem->dv, nl->dvlin));
  PetscCall(
      SetSprings(body, nl->f, nl->stick, nl->dvlin)); /* the contact vertices held where the correction put them */
  PetscCall(VecAXPY(fem->nbc, body->h, nl->f));
  PetscCall(VecAXPY(fem->nbc, -body->h, nl->fc));
  PetscCall(FCFEMNewtonSolve(body, nl->dvload, &reason, &its)); /* dv_load where the correction inverts a cell */
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
  PetscCall(VecCopy(nl->stick, nl->stickc));
  PetscCall(SpringsHold(body, held));
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
  PetscCall(Unloaded(body, nl->dvset));
  PetscFunctionReturn(0);
}

/* Restart and step control: f_c and the sticking flag of the vertices in visual order (4 values after u and v) */
PetscErrorCode FCFEMNonlinearGetState(FCBody body, PetscInt cols, PetscReal s[])
{
  FEM               *fem = (FEM *)body->data;
  FCMesh            *m   = &fem->mesh;
  const PetscScalar *f, *k;
  PetscInt           lo;

  PetscFunctionBegin;
  if (!fem->nl) PetscFunctionReturn(0);
  PetscCall(VecGetOwnershipRange(fem->nl->fc, &lo, NULL));
  PetscCall(VecGetArrayRead(fem->nl->fc, &f));
  PetscCall(VecGetArrayRead(fem->nl->stickc, &k));
  for (PetscInt i = 0; i < body->visual.nv; i++) {
    PetscInt vx = m->visVert[i];
    for (int d = 0; d < 3; d++) s[cols * i + 6 + d] = fem->fixed[vx] ? 0.0 : PetscRealPart(f[fem->gdof[vx] - lo + d]);
    s[cols * i + 9] = fem->fixed[vx] ? 0.0 : PetscRealPart(k[fem->gdof[vx] - lo]);
  }
  PetscCall(VecRestoreArrayRead(fem->nl->fc, &f));
  PetscCall(VecRestoreArrayRead(fem->nl->stickc, &k));
  PetscFunctionReturn(0);
}

PetscErrorCode FCFEMNonlinearSetState(FCBody body, PetscInt cols, const PetscReal s[])
{
  FEM         *fem = (FEM *)body->data;
  FCMesh      *m   = &fem->mesh;
  PetscScalar *f, *k;
  PetscInt     lo;

  PetscFunctionBegin;
  if (!fem->nl) PetscFunctionReturn(0);
  PetscCall(VecGetOwnershipRange(fem->nl->fc, &lo, NULL));
  PetscCall(VecGetArray(fem->nl->fc, &f));
  PetscCall(VecGetArray(fem->nl->stickc, &k));
  for (PetscInt i = 0; i < body->visual.nv; i++) {
    PetscInt vx = m->visVert[i];
    if (fem->fixed[vx]) continue;
    for (int d = 0; d < 3; d++) {
      f[fem->gdof[vx] - lo + d] = s[cols * i + 6 + d];
      k[fem->gdof[vx] - lo + d] = s[cols * i + 9];
    }
  }
  PetscCall(VecRestoreArray(fem->nl->fc, &f));
  PetscCall(VecRestoreArray(fem->nl->stickc, &k));
  PetscFunctionReturn(0);
}
