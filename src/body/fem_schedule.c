/* FE body, the factorization schedule of a co-rotational body (-<body>_factorization).

   every_step: A = M + h B + h^2 K(R) is assembled and factored at every step (fem_step.c): the free
   motion (eq. 5), W_b (eq. 17) and the correction (eq. 20) are exact for the step's linearization.

   reuse: A is factored now and then, and the steps between keep that factor F of A_0 (the A of
   the last factorization, at per-vertex rotations R_0):
     - the free motion is exact to -<body>_ksp_rtol: conjugate gradients on today's A, applied
       without assembling it (per cell, R K_e R^T x with R the cell's rotation now,
       FCMaterialRotatedApply; M by its matrix), preconditioned by the warped factor
           P^-1 = Q A_0^-1 Q^T,  Q = blockdiag(R_v R_0,v^T),
       R_v the rotation of vertex v now (the polar factor of the volume-weighted sum of its cells'
       rotations). Q A_0 Q^T is A_0 turned with the body, so a body that rotates keeps a good
       preconditioner (compliance warping, Mueller & Gross 2004; Courtecuisse et al. 2010);
     - the compliance and the correction take the same warped operator in place of A^-1:
           W_b = J Q A_0^-1 Q^T J^T,  dv += h Q A_0^-1 Q^T J^T lambda
       (the builder gets Q, FCComplianceSetWarp), so the contact forces solve the problem of that
       operator and the positions they give agree with W. This is the approximation: the
       compliance of the deformation since the last factorization is that of A_0 turned;
     - A is factored again at the step's state, before its solves, when the last step's contact
       correction, turned with the vertices since, leaves a relative residual above
       -<body>_refactor_residual in today's A (Predict: the warped compliance's error along the
       contacts' forces), when the largest vertex rotation since the last factorization,
       measured against the body's mean rotation since then (a rigid rotation is exact under the
       warp), passes -<body>_refactor_rotation, after a step whose CG took more than
       -<body>_refactor_iterations iterations, every -<body>_refactor_every steps (0: never for
       age), or at once when CG does not converge in -<body>_ksp_max_it iterations (the step then
       solves with the new factor). A contact outside the condensed builder's Schur block
       refactors A_0 (the builder's miss), which keeps Q.
   reuse needs the body's default solver (MUMPS Cholesky) and, in a contact pair, the condensed
   builder. every_step is the default: reuse's correction does not conserve momentum where Q
   varies, and its restarts are not exact (docs/accuracy.md, "Factorization schedule").
   The counts go to /steps/factorizations and /steps/krylov_iterations. */
#include "femimpl.h"
#include "../compliance/compliance.h"

/* A body held by nothing keeps the momentum of its free motion: A 1_d = M 1_d for a translation
   1_d (K annihilates it), so the exact x = A^-1 b has sum(M x)_d = sum(b)_d. CG stopped at its
   tolerance does not; x gets the translation velocity that restores it (no elastic force, and the
   positions move by what the tolerance left) */
static PetscErrorCode KeepMomentum(FCBody body, Vec b, Vec x)
{
  FEM               *fem = (FEM *)body->data;
  const PetscScalar *ba, *ma;
  PetscScalar       *xa;
  PetscReal          s[6] = {0};
  PetscInt           n;

  PetscFunctionBegin;
  if (fem->nfixed > 0) PetscFunctionReturn(0);
  PetscCall(MatMult(fem->M, x, fem->xres));
  PetscCall(VecGetLocalSize(x, &n));
  PetscCall(VecGetArrayRead(b, &ba));
  PetscCall(VecGetArrayRead(fem->xres, &ma));
  for (PetscInt i = 0; i < n; i++) {
    s[i % 3] += PetscRealPart(ba[i]);
    s[3 + i % 3] += PetscRealPart(ma[i]);
  }
  PetscCall(VecRestoreArrayRead(b, &ba));
  PetscCall(VecRestoreArrayRead(fem->xres, &ma));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, s, 6, MPIU_REAL, MPIU_SUM, body->comm));
  PetscCall(VecGetArray(x, &xa));
  for (PetscInt i = 0; i < n; i++) xa[i] += (s[i % 3] - s[3 + i % 3]) / fem->mass;
  PetscCall(VecRestoreArray(x, &xa));
  PetscFunctionReturn(0);
}

/* The preconditioner: z = Q A_0^-1 Q^T r with the last factor */
static PetscErrorCode WarpedSolve(PC pc, Vec r, Vec z)
{
  FCBody body;
  FEM   *fem;

  PetscFunctionBegin;
  PetscCall(PCShellGetContext(pc, &body));
  fem = (FEM *)body->data;
  PetscCall(VecCopy(r, fem->rw2));
  PetscCall(FCFEMWarpTurn(fem->dR, fem->rw2, PETSC_TRUE));
  PetscCall(FCFEMSolveA(body, fem->rw2, z, "Preconditioner", fem->tnow));
  PetscCall(FCFEMWarpTurn(fem->dR, z, PETSC_FALSE));
  PetscFunctionReturn(0);
}

/* -factorization and, with reuse, its tolerance and triggers (read with the body's options; a
   linear body refuses the option) */
PetscErrorCode FCFEMScheduleSetFromOptions(PetscOptionItems *PetscOptionsObject, FCBody body)
{
  FEM *fem = (FEM *)body->data;

  PetscFunctionBegin;
  if (!strcmp(fem->material, "linear")) { /* A never changes: factored once */
    PetscBool given;
    PetscCall(PetscOptionsHasName(NULL, body->prefix, "-factorization", &given));
    PetscCheck(!given, body->comm, PETSC_ERR_USER_INPUT,
               "Body '%s': -%sfactorization is for a body whose A changes (co-rotational, hyperelastic); the linear "
               "material's A is factored once",
               body->name, body->prefix);
    PetscFunctionReturn(0);
  }
  {
    char fmode[FC_MAX_NAME] = "every_step";
    if (fem->factorization == FC_FACTORIZATION_REUSE) PetscCall(PetscStrncpy(fmode, "reuse", sizeof(fmode)));
    PetscCall(PetscOptionsString(
        "-factorization", "When A is factored: every_step, or reuse (CG with the last factor, warped compliance)", NULL,
        fmode, fmode, sizeof(fmode), NULL));
    PetscCheck(strcmp(fmode, "async"), body->comm, PETSC_ERR_USER_INPUT,
               "-%sfactorization async (the factorization in the background) is not available: a second MUMPS "
               "factorization beside the step needs MPI_THREAD_MULTIPLE or a spare rank, and on 2 cores it would "
               "share them with the step (docs/method.md, \"When A is factored\"); use reuse",
               body->prefix);
    PetscCheck(!strcmp(fmode, "every_step") || !strcmp(fmode, "reuse"), body->comm, PETSC_ERR_USER_INPUT,
               "Unknown value '%s' of -%sfactorization (known: every_step, reuse)", fmode, body->prefix);
    fem->factorization = !strcmp(fmode, "reuse") ? FC_FACTORIZATION_REUSE : FC_FACTORIZATION_EVERY_STEP;
    if (fem->factorization == FC_FACTORIZATION_REUSE) {
      PetscCall(FCOptionsReal(PetscOptionsObject, "-ksp_rtol", "reuse: relative residual of the free motion's CG",
                              &fem->ksp_rtol, NULL));
      PetscCall(FCOptionsInt(PetscOptionsObject, "-ksp_max_it",
                             "reuse: CG iterations after which A is factored at once", &fem->ksp_max_it, NULL));
      PetscCall(FCOptionsReal(PetscOptionsObject, "-refactor_rotation",
                              "reuse: factor A when a vertex turned more (rad) since the last factorization",
                              &fem->refactor_rotation, NULL));
      PetscCall(FCOptionsInt(PetscOptionsObject, "-refactor_iterations",
                             "reuse: factor A after a step whose CG took more iterations", &fem->refactor_iterations,
                             NULL));
      PetscCall(FCOptionsReal(PetscOptionsObject, "-refactor_residual",
                              "reuse: factor A when the last contact correction, by the warped factor, leaves a larger "
                              "relative residual in today's A",
                              &fem->refactor_residual, NULL));
      PetscCall(FCOptionsInt(PetscOptionsObject, "-refactor_every",
                             "reuse: factor A at least every k steps (0: no limit by age)", &fem->refactor_every,
                             NULL));
    }
  }
  if (fem->factorization == FC_FACTORIZATION_REUSE) {
    PetscCheck(fem->refactor_every >= 0, body->comm, PETSC_ERR_USER_INPUT,
               "Option -%srefactor_every must be >= 0, got %" PetscInt_FMT, body->prefix, fem->refactor_every);
    PetscCheck(fem->ksp_rtol > 0.0 && fem->ksp_rtol < 1.0, body->comm, PETSC_ERR_USER_INPUT,
               "Option -%sksp_rtol must lie in (0, 1), got %g", body->prefix, (double)fem->ksp_rtol);
    PetscCheck(fem->ksp_max_it >= 1, body->comm, PETSC_ERR_USER_INPUT,
               "Option -%sksp_max_it must be >= 1, got %" PetscInt_FMT, body->prefix, fem->ksp_max_it);
    PetscCheck(fem->refactor_iterations >= 1, body->comm, PETSC_ERR_USER_INPUT,
               "Option -%srefactor_iterations must be >= 1, got %" PetscInt_FMT, body->prefix,
               fem->refactor_iterations);
    PetscCheck(fem->refactor_residual > 0.0, body->comm, PETSC_ERR_USER_INPUT,
               "Option -%srefactor_residual must be > 0, got %g", body->prefix, (double)fem->refactor_residual);
    PetscCheck(fem->refactor_rotation > 0.0, body->comm, PETSC_ERR_USER_INPUT,
               "Option -%srefactor_rotation must be > 0 (radians), got %g", body->prefix,
               (double)fem->refactor_rotation);
  }
  PetscFunctionReturn(0);
}

/* What reuse needs: per-cell rotations, the vertex rotations and their reference, the surface
   table of the compliance builder, the matrix-free A and its CG. With every_step: nothing */
PetscErrorCode FCFEMScheduleSetUp(FCBody body)
{
  FEM     *fem = (FEM *)body->data;
  FCMesh  *m   = &fem->mesh;
  PetscInt n, N, nc = m->cEnd - m->cStart;
  PC       pc;

  PetscFunctionBegin;
  if (fem->factorization != FC_FACTORIZATION_REUSE) PetscFunctionReturn(0);
  { /* the preconditioner is the body's factor: its solver must be one (preonly + Cholesky + MUMPS) */
    PetscBool mumps;
    PetscCall(FCComplianceKSPIsMumps(fem->ksp, &mumps));
    PetscCheck(mumps, body->comm, PETSC_ERR_USER_INPUT,
               "-%sfactorization reuse preconditions with the body's factorization of A, but the options of its solver "
               "(-%sksp_type, -%spc_type, -%spc_factor_mat_solver_type) ask for another solver than MUMPS Cholesky: "
               "drop them, or use -%sfactorization every_step",
               body->prefix, body->prefix, body->prefix, body->prefix, body->prefix);
  }
  fem->Acurrent = PETSC_FALSE; /* the first step takes its operator (and first factor) at its state */
  fem->factored = PETSC_FALSE;
  PetscCall(VecGetLocalSize(fem->u, &n));
  PetscCall(VecGetSize(fem->u, &N));
  PetscCall(PetscMalloc5(9 * nc + 1, &fem->Rcell, 3 * n + 1, &fem->Rv0, 3 * n + 1, &fem->dR, 3 * n + 1, &fem->Rvnow,
                         3 * n + 1, &fem->Rvprev));
  for (PetscInt b = 0; b < n / 3; b++) {
    FCMat3Identity(&fem->Rv0[9 * b]);
    FCMat3Identity(&fem->dR[9 * b]);
  }
  for (int j = 0; j < 3; j++) {
    PetscCall(VecDuplicate(fem->u, &fem->rcol[j]));
    PetscCall(DMCreateLocalVector(m->dm, &fem->rcolloc[j]));
  }
  PetscCall(VecDuplicate(fem->u, &fem->rw2));
  PetscCall(VecDuplicate(fem->u, &fem->xlast));
  PetscCall(VecDuplicate(fem->u, &fem->xres));
  PetscCall(VecDuplicate(fem->u, &fem->xcorr));
  PetscCall(VecDuplicate(fem->u, &fem->xprev));
  PetscCall(VecDuplicate(fem->u, &fem->rprev));
  PetscCall(MatCreateShell(body->comm, n, n, N, N, body, &fem->Aop));
  PetscCall(MatShellSetOperation(fem->Aop, MATOP_MULT, (void (*)(void))FCFEMWarpAMult));
  PetscCall(KSPCreate(body->comm, &fem->kspk));
  PetscCall(KSPSetType(fem->kspk, KSPCG));
  PetscCall(KSPSetOperators(fem->kspk, fem->Aop, fem->Aop));
  PetscCall(KSPSetNormType(fem->kspk, KSP_NORM_UNPRECONDITIONED));
  PetscCall(KSPSetInitialGuessNonzero(fem->kspk, PETSC_TRUE));
  PetscCall(KSPSetTolerances(fem->kspk, fem->ksp_rtol, PETSC_DEFAULT, PETSC_DEFAULT, fem->ksp_max_it));
  PetscCall(KSPGetPC(fem->kspk, &pc));
  PetscCall(PCSetType(pc, PCSHELL));
  PetscCall(PCShellSetContext(pc, body));
  PetscCall(PCShellSetApply(pc, WarpedSolve));
  PetscCall(PCShellSetName(pc, "warped factor of the last A"));
  PetscFunctionReturn(0);
}

static PetscErrorCode Predict(FCBody, PetscReal *);

/* Factor A at the state (K assembled there), which becomes A_0: Q = I */
static PetscErrorCode Refactor(FCBody body, const PetscReal Rv[])
{
  FEM     *fem = (FEM *)body->data;
  PetscInt n;

  PetscFunctionBegin;
  PetscCall(FCFEMAssembleElastic(body, fem->state, NULL, fem->K));
  PetscCall(FCFEMFormA(body));
  PetscCall(FCFEMFactorA(body));
  PetscCall(VecGetLocalSize(fem->u, &n));
  PetscCall(PetscArraycpy(fem->Rv0, Rv, 3 * n));
  PetscCall(FCFEMWarpUpdate(body, Rv));
  fem->refactor_next = PETSC_FALSE;
  fem->fresh         = PETSC_TRUE;
  fem->hasprev       = PETSC_FALSE;
  PetscFunctionReturn(0);
}

/* The operator of the step at `state` (u, or the turned state): every_step assembles K and f_int
   and factors A; reuse computes the cells' rotations and f_int, the vertex rotations since the last
   factorization, and factors A when one of the triggers says so */
PetscErrorCode FCFEMScheduleOperator(FCBody body, Vec state)
{
  FEM       *fem = (FEM *)body->data;
  PetscReal *Rv, res = 0.0;
  PetscBool  due;

  PetscFunctionBegin;
  fem->state = state;
  fem->fresh = PETSC_FALSE;
  if (fem->factorization != FC_FACTORIZATION_REUSE) {
    PetscCall(FCFEMAssembleElastic(body, state, fem->fint, fem->K));
    PetscCall(FCFEMFormA(body));
    PetscCall(FCFEMFactorA(body));
    fem->fresh = PETSC_TRUE;
    PetscFunctionReturn(0);
  }
  PetscCall(FCPhaseBegin(FC_PHASE_ASSEMBLY));
  PetscCall(FCFEMWarpAtState(body, state));
  Rv = fem->Rvnow;
  PetscCall(Predict(body, &res));
  PetscCall(FCPhaseEnd(FC_PHASE_ASSEMBLY));
  due =
      (PetscBool)(!fem->factored || fem->refactor_next || fem->angle > fem->refactor_rotation ||
                  res > fem->refactor_residual || (fem->refactor_every > 0 && fem->factor_age >= fem->refactor_every));
  if (due) {
    PetscCall(PetscInfo(NULL,
                        "body %s: factoring A (rotation since the last factorization %g rad, residual of the last "
                        "correction %g, age %" PetscInt_FMT ", CG iterations above the limit: %s)\n",
                        body->name, (double)fem->angle, (double)res, fem->factor_age, PetscBools[fem->refactor_next]));
    PetscCall(Refactor(body, Rv));
  }
  PetscFunctionReturn(0);
}

/* x = A^-1 b for the free motion: with the factor of this step's A, one solve; else CG to
   ksp_rtol, and a factorization now if it does not converge */
PetscErrorCode FCFEMScheduleSolve(FCBody body, Vec b, Vec x, PetscReal t)
{
  FEM               *fem = (FEM *)body->data;
  KSPConvergedReason reason;
  PetscInt           its;

  PetscFunctionBegin;
  fem->tnow = t;
  if (fem->fresh || fem->factorization != FC_FACTORIZATION_REUSE) {
    PetscCall(FCFEMSolveA(body, b, x, "Free-motion", t));
    if (fem->xlast) PetscCall(VecCopy(x, fem->xlast));
    PetscFunctionReturn(0);
  }
  PetscCall(VecCopy(fem->xlast, x)); /* the last step's solution: the free motion changes little from step to step */
  PetscCall(KSPSolve(fem->kspk, b, x));
  PetscCall(KeepMomentum(body, b, x));
  PetscCall(VecCopy(x, fem->xlast));
  PetscCall(KSPGetConvergedReason(fem->kspk, &reason));
  PetscCall(KSPGetIterationNumber(fem->kspk, &its));
  fem->nkrylov += its;
  if (its > fem->refactor_iterations) fem->refactor_next = PETSC_TRUE;
  if (reason < 0) { /* the old factor is too far from A: a new one, and a direct solve */
    PetscCall(PetscInfo(
        NULL, "body %s: CG with the old factor did not converge (%s, %" PetscInt_FMT " iterations): refactoring\n",
        body->name, KSPConvergedReasons[reason], its));
    PetscCall(Refactor(body, fem->Rvnow));
    PetscCall(FCFEMSolveA(body, b, x, "Free-motion", t));
  }
  PetscFunctionReturn(0);
}

/* The contact correction x = h Q A_0^-1 Q^T J^T lambda (the warped operator's), before dv += x: x
   and its right-hand side h J^T lambda kept, with the vertex rotations of the step, for the check
   of the next step (Predict). Its momentum is the warped operator's: not restored, since a
   translation added to x would move the contacts off the gaps W was solved for */
PetscErrorCode FCFEMScheduleKeepCorrection(FCBody body, Vec x)
{
  FEM     *fem = (FEM *)body->data;
  Vec      rhs;
  PetscInt n;

  PetscFunctionBegin;
  if (fem->factorization != FC_FACTORIZATION_REUSE || !fem->comp) PetscFunctionReturn(0);
  PetscCall(FCComplianceGetCorrectionRHS(fem->comp, &rhs)); /* (J Q)^T h lambda = Q^T J^T h lambda */
  if (!rhs) PetscFunctionReturn(0);
  PetscCall(VecCopy(rhs, fem->rprev));
  PetscCall(FCFEMWarpTurn(fem->dR, fem->rprev, PETSC_FALSE));
  PetscCall(VecCopy(x, fem->xprev));
  PetscCall(VecGetLocalSize(fem->u, &n));
  PetscCall(PetscArraycpy(fem->Rvprev, fem->Rvnow, 3 * n));
  fem->hasprev = PETSC_TRUE;
  PetscFunctionReturn(0);
}

/* Before the step's solves, whether the warped factor still answers the last step's contact forces:
   x and r = h J^T lambda of the last correction, turned with each vertex since (R_v R_v,last^T), and
   the relative residual ||A x - r|| / ||r|| in today's A (one matrix-free product). It measures the
   warped compliance's error along the forces of the contacts, and the change of A since they were
   computed; above -refactor_residual, A is factored now, before the contacts need it */
static PetscErrorCode Predict(FCBody body, PetscReal *res)
{
  FEM      *fem = (FEM *)body->data;
  PetscInt  n;
  PetscReal nr, nb;

  PetscFunctionBegin;
  *res = 0.0;
  if (!fem->hasprev) PetscFunctionReturn(0);
  fem->hasprev = PETSC_FALSE;
  PetscCall(VecGetLocalSize(fem->u, &n));
  for (PetscInt b = 0; b < n / 3; b++) { /* Rvprev, used up, becomes the turn since: R_v R_v,last^T */
    PetscReal PT[9];
    FCMat3Transpose(&fem->Rvprev[9 * b], PT);
    FCMat3Mult(&fem->Rvnow[9 * b], PT, &fem->Rvprev[9 * b]);
  }
  PetscCall(FCFEMWarpTurn(fem->Rvprev, fem->xprev, PETSC_FALSE));
  PetscCall(FCFEMWarpTurn(fem->Rvprev, fem->rprev, PETSC_FALSE));
  PetscCall(VecNorm(fem->rprev, NORM_2, &nb));
  if (nb == 0.0) PetscFunctionReturn(0);
  PetscCall(MatMult(fem->Aop, fem->xprev, fem->xres));
  PetscCall(VecAXPY(fem->xres, -1.0, fem->rprev));
  PetscCall(VecNorm(fem->xres, NORM_2, &nr));
  *res = nr / nb;
  PetscFunctionReturn(0);
}

PetscErrorCode FCFEMScheduleDestroy(FCBody body)
{
  FEM *fem = (FEM *)body->data;

  PetscFunctionBegin;
  PetscCall(PetscFree5(fem->Rcell, fem->Rv0, fem->dR, fem->Rvnow, fem->Rvprev));
  for (int j = 0; j < 3; j++) {
    PetscCall(VecDestroy(&fem->rcol[j]));
    PetscCall(VecDestroy(&fem->rcolloc[j]));
  }
  PetscCall(VecDestroy(&fem->rw2));
  PetscCall(VecDestroy(&fem->xlast));
  PetscCall(VecDestroy(&fem->xres));
  PetscCall(VecDestroy(&fem->xcorr));
  PetscCall(VecDestroy(&fem->xprev));
  PetscCall(VecDestroy(&fem->rprev));
  PetscCall(MatDestroy(&fem->Aop));
  PetscCall(KSPDestroy(&fem->kspk));
  PetscCall(PetscFree5(fem->swdof, fem->swperm, fem->swR, fem->swbuf, fem->swall));
  PetscCall(PetscFree2(fem->swcounts, fem->swdispls));
  PetscFunctionReturn(0);
}
