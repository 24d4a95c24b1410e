/* FE body, the free motion by Newton's method (-<body>_free_motion newton; the default of the
   hyperelastic materials). The implicit Euler step of eq. 5 without its linearization: find dv
   with
       F(dv) = (1 + h alpha) M dv + h alpha M v + h f_int(u + h (v + dv)) - b_c = 0,
       b_c   = h (f_grav + f_load) - M_fc ((v_c' - v_c) + h alpha v_c'),
   the constrained vertices at their prescribed positions at t + h (M_fc their coupling with the
   free rows, v_c' and v_c their velocities over this step and the last, fem_bc.c). Quasi-static:
   F(dv) = h f_int(u + h dv) - h (f + f_load), h dv the step's displacement. The Jacobian is
       A = (1 + h alpha) M + h^2 K_t(u + h (v + dv)),
   the A of eq. 5 at the iterate, factored by the body's KSP (MUMPS). PETSc's SNES drives the
   iterations (-<body>_snes_*: line search, tolerances, monitors); an iterate that turns a cell
   inside out is a domain error, which the line search cuts back. The contact schemes then take
   the A of Newton's last Jacobian (at the iterate before the converged one, within the last
   Newton step of it): W_b = J A^-1 J^T (eq. 17) and the correction (eq. 20) are those of the step
   linearized there (docs/method.md, "Nonlinear bodies"). A condensed builder, which owns the
   body's factor, factors that A once more with its Schur complement; the KSP keeps its own factor
   beside it. */
#include "femimpl.h"
#include "../compliance/compliance.h"

/* w = u + h (v + dv): the state at t + h of the iterate */
static PetscErrorCode EndState(FCBody body, Vec dv)
{
  FEM *fem = (FEM *)body->data;

  PetscFunctionBegin;
  PetscCall(VecWAXPY(fem->nw, 1.0, fem->v, dv));
  PetscCall(VecAYPX(fem->nw, body->h, fem->u));
  PetscFunctionReturn(0);
}

static PetscErrorCode Residual(SNES snes, Vec dv, Vec F, void *ctx)
{
  FCBody    body = (FCBody)ctx;
  FEM      *fem  = (FEM *)body->data;
  PetscReal h    = body->h;
  PetscInt  bad;

  PetscFunctionBegin;
  PetscCall(EndState(body, dv));
  fem->mat->ninverted = 0;
  PetscCall(FCFEMAssembleElasticAt(body, fem->nw, FC_BC_END, fem->nf, NULL));
  PetscCall(MPIU_Allreduce(&fem->mat->ninverted, &bad, 1, MPIU_INT, MPI_SUM, body->comm));
  if (bad) { /* a cell turned inside out: no energy there, the line search steps back */
    PetscCall(SNESSetFunctionDomainError(snes));
    PetscFunctionReturn(0);
  }
  PetscCall(VecAXPBYPCZ(F, h, -1.0, 0.0, fem->nf, fem->nbc));
  if (!body->quasistatic) {
    PetscCall(MatMult(fem->M, dv, fem->nf));
    PetscCall(VecAXPY(F, 1.0 + h * fem->alpha, fem->nf));
    if (fem->alpha != 0.0) {
      PetscCall(MatMult(fem->M, fem->v, fem->nf));
      PetscCall(VecAXPY(F, h * fem->alpha, fem->nf));
    }
  }
  PetscCall(FCFEMNonlinearAddSpringForce(body, fem->nw, F)); /* a nonlinear correction's (fem_nonlinear.c) */
  PetscFunctionReturn(0);
}

/* A at the iterate, and its factorization by the body's KSP (SNES then solves with it: the same
   operator, so no second factorization) */
static PetscErrorCode Jacobian(SNES snes, Vec dv, Mat J, Mat P, void *ctx)
{
  FCBody body = (FCBody)ctx;
  FEM   *fem  = (FEM *)body->data;

  PetscFunctionBegin;
  (void)snes;
  (void)J;
  (void)P;
  PetscCall(EndState(body, dv));
  PetscCall(FCFEMAssembleElasticAt(body, fem->nw, FC_BC_END, NULL, fem->K));
  PetscCall(FCFEMFormA(body));
  PetscCall(FCFEMNonlinearAddSpringStiffness(body, fem->A));
  /* the tangent of a hyperelastic body need not be definite: MUMPS' symmetric LDL^T, not Cholesky */
  PetscCall(MatSetOption(fem->A, MAT_SPD, PETSC_FALSE));
  PetscCall(MatSetOption(fem->A, MAT_SYMMETRIC, PETSC_TRUE));
  PetscCall(FCPhaseBegin(FC_PHASE_FACTORIZATION));
  PetscCall(KSPSetOperators(fem->ksp, fem->A, fem->A));
  PetscCall(KSPSetUp(fem->ksp));
  PetscCall(FCMumpsKSPChecked(fem->ksp, fem->A, "A", body->name));
  PetscCall(FCPhaseEnd(FC_PHASE_FACTORIZATION));
  fem->nfactor++;
  fem->jacobian = PETSC_TRUE;
  PetscFunctionReturn(0);
}

/* -free_motion linearized|newton (read with the body's options; the default, the material's, is
   resolved at set-up) */
PetscErrorCode FCFEMNewtonSetFromOptions(PetscOptionItems *PetscOptionsObject, FCBody body)
{
  FEM        *fem    = (FEM *)body->data;
  const char *kind[] = {"linearized", "newton"};
  PetscInt    k      = fem->free_motion == FC_FREE_MOTION_NEWTON ? 1 : 0;
  PetscBool   set;

  PetscFunctionBegin;
  PetscCall(FCOptionsEList(PetscOptionsObject, "-free_motion",
                           "The free motion (eq. 5): linearized (one linearization at the step's start) or newton "
                           "(the implicit Euler step solved by SNES; the default of neohookean and stvk)",
                           kind, 2, &k, &set));
  if (set) fem->free_motion = k == 1 ? FC_FREE_MOTION_NEWTON : FC_FREE_MOTION_LINEARIZED;
  PetscFunctionReturn(0);
}

/* The SNES of the body, prefix <body>_ (its KSP the body's): Newton with a backtracking line
   search, relative tolerance 1e-10 and absolute 1e-13 h E V^(2/3) unless the options say otherwise */
PetscErrorCode FCFEMNewtonSetUp(FCBody body)
{
  FEM *fem = (FEM *)body->data;

  PetscFunctionBegin;
  if (fem->free_motion < 0)
    fem->free_motion = fem->mat->hyperelastic ? FC_FREE_MOTION_NEWTON : FC_FREE_MOTION_LINEARIZED;
  PetscCheck(fem->factorization == FC_FACTORIZATION_EVERY_STEP || fem->mat->rotation, body->comm, PETSC_ERR_USER_INPUT,
             "Body '%s': -%sfactorization reuse warps the factor of a co-rotational body; the %s material has no "
             "element rotation (use every_step)",
             body->name, body->prefix, fem->material);
  if (fem->free_motion != FC_FREE_MOTION_NEWTON) PetscFunctionReturn(0);
  PetscCheck(fem->beta == 0.0, body->comm, PETSC_ERR_USER_INPUT,
             "Body '%s': -%sfree_motion newton takes no -%srayleigh_stiffness (the damping of a tangent that changes "
             "within the step); use -%srayleigh_mass",
             body->name, body->prefix, body->prefix, body->prefix);
  PetscCheck(fem->factorization == FC_FACTORIZATION_EVERY_STEP, body->comm, PETSC_ERR_USER_INPUT,
             "Body '%s': -%sfree_motion newton factors A at every Newton iteration; -%sfactorization reuse is for the "
             "one-linearization step of a co-rotational body",
             body->name, body->prefix, body->prefix);
  PetscCall(VecDuplicate(fem->u, &fem->nw));
  PetscCall(VecDuplicate(fem->u, &fem->nf));
  PetscCall(VecDuplicate(fem->u, &fem->nbc));
  PetscCall(VecDuplicate(fem->u, &fem->nr));
  PetscCall(SNESCreate(body->comm, &fem->snes));
  PetscCall(SNESSetOptionsPrefix(fem->snes, body->prefix));
  PetscCall(SNESSetType(fem->snes, SNESNEWTONLS));
  PetscCall(SNESSetKSP(fem->snes, fem->ksp));
  PetscCall(SNESSetFunction(fem->snes, fem->nr, Residual, body));
  PetscCall(SNESSetJacobian(fem->snes, fem->A, fem->A, Jacobian, body));
  { /* absolute: the round-off of h f_int at the force scale E V^(2/3) of the body (a step that
       starts at equilibrium cannot reduce its residual by 1e-10) */
    PetscReal V = fem->mass / body->density;
    PetscCall(SNESSetTolerances(fem->snes, 1e-13 * body->h * fem->young * PetscPowReal(V, 2.0 / 3.0), 1e-10,
                                PETSC_DEFAULT, 50, PETSC_DEFAULT));
  }
  PetscCall(SNESSetFromOptions(fem->snes));
  PetscFunctionReturn(0);
}

/* SNES from dv; where its first iterate turns a cell inside out (the velocity kept, in a fast impact
   on a thin body), once more from `again` (NULL: dv = -v, the positions at t, where every cell was
   upright at the end of the last step) */
PetscErrorCode FCFEMNewtonSolve(FCBody body, Vec again, SNESConvergedReason *reason, PetscInt *its)
{
  FEM *fem = (FEM *)body->data;

  PetscFunctionBegin;
  fem->jacobian = PETSC_FALSE;
  PetscCall(SNESSolve(fem->snes, NULL, fem->dv));
  PetscCall(SNESGetConvergedReason(fem->snes, reason));
  PetscCall(SNESGetIterationNumber(fem->snes, its));
  if (*reason != SNES_DIVERGED_FUNCTION_DOMAIN || *its) PetscFunctionReturn(0);
  if (again)
    PetscCall(VecCopy(again, fem->dv));
  else {
    PetscCall(VecCopy(fem->v, fem->dv));
    PetscCall(VecScale(fem->dv, -1.0));
  }
  PetscCall(SNESSolve(fem->snes, NULL, fem->dv));
  PetscCall(SNESGetConvergedReason(fem->snes, reason));
  PetscCall(SNESGetIterationNumber(fem->snes, its));
  PetscFunctionReturn(0);
}

PetscErrorCode FCFEMNewtonFreeMotion(FCBody body, PetscReal t)
{
  FEM                *fem = (FEM *)body->data;
  PetscReal           h   = body->h;
  SNESConvergedReason reason;
  PetscInt            its;

  PetscFunctionBegin;
  PetscCall(FCPhaseBegin(FC_PHASE_FREE_MOTION));
  PetscCall(VecZeroEntries(fem->nbc));
  if (body->gravity[0] != 0.0 || body->gravity[1] != 0.0 || body->gravity[2] != 0.0)
    PetscCall(VecAXPY(fem->nbc, h, fem->fgrav));
  PetscCall(FCFEMBCAddRHS(body, fem->nbc, PETSC_FALSE)); /* loads, and the inertia of the prescribed motion */
  PetscCall(FCFEMNonlinearAddLoad(body, fem->nbc));      /* the last step's contact forces (fem_nonlinear.c) */
  /* the first iterate: the velocity kept; quasi-static with contact forces carried, the last step's rate */
  if (!(body->quasistatic && FCFEMNonlinearLoaded(body))) PetscCall(VecZeroEntries(fem->dv));
  PetscCall(FCPhaseEnd(FC_PHASE_FREE_MOTION));
  PetscCall(FCFEMNewtonSolve(body, NULL, &reason, &its));
  PetscCheck(reason > 0, body->comm, PETSC_ERR_CONV_FAILED,
             "The Newton free motion of body '%s' did not converge at t = %g: %s after %" PetscInt_FMT
             " iterations (-%ssnes_monitor shows them; -%ssnes_max_it, -%ssnes_rtol, or a smaller -time_step)",
             body->name, (double)t, SNESConvergedReasons[reason], its, body->prefix, body->prefix, body->prefix);
  fem->nnewton += its;
  /* the contact schemes take A of Newton's last Jacobian, factored by the builder that owns it or
     already by the KSP (a solve that converged at once forms it here, at the converged state) */
  if (!fem->jacobian) PetscCall(Jacobian(fem->snes, fem->dv, fem->A, fem->A, body));
  if (fem->comp && FCComplianceFactorsA(fem->comp))
    PetscCall(FCFEMFactorA(body));
  else {
    if (fem->comp) PetscCall(FCComplianceFactor(fem->comp)); /* builders that keep their own copy of A */
    fem->factor_age = 0;
    fem->factored   = PETSC_TRUE;
  }
  fem->Acurrent = PETSC_TRUE;
  PetscCall(FCFEMNonlinearUnload(body)); /* the free motion without them, linearized there */
  PetscFunctionReturn(0);
}

PetscErrorCode FCFEMNewtonDestroy(FCBody body)
{
  FEM *fem = (FEM *)body->data;

  PetscFunctionBegin;
  PetscCall(SNESDestroy(&fem->snes));
  PetscCall(VecDestroy(&fem->nw));
  PetscCall(VecDestroy(&fem->nf));
  PetscCall(VecDestroy(&fem->nbc));
  PetscCall(VecDestroy(&fem->nr));
  PetscFunctionReturn(0);
}
