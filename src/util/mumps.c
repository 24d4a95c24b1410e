/* A MUMPS factorization through PETSc, checked by MUMPS' own status and retried when MUMPS runs out
   of workspace (used by the FE body's factor of A, src/body/fem_step.c, and by the compliance
   builders' factors, src/compliance/compliance.c).

   PETSc 3.18 records a MUMPS failure in the factor (MatFactorGetError) instead of raising it. After
   a failure its numeric phase returns at once, with no error and nothing factored, for as long as
   MUMPS' INFOG(1) holds that failure, and its symbolic phase does nothing on a factor analysed
   before: a failed factor cannot be factored again, only replaced. Parallel MUMPS intermittently
   underestimates its workspace (INFOG(1) = -8 or -9: seen on 2 and 4 ranks). So success is read
   from MUMPS (INFOG(1) >= 0), and out of workspace is retried up to 3 times on a new factor with
   ICNTL(14), the workspace margin in percent, doubled (max(2 m + 20, 20)). */
#include "../fcimpl.h"

/* The status of a factor: 0 done, 1 out of workspace (retry), or an error naming the failure and
   the option that sets the margin (under the factor's options prefix: the body's for its factor of
   A, none for a builder's own factors) */
static PetscErrorCode Status(Mat F, Mat A, PetscBool last, const char what[], const char body[], PetscInt *icntl14,
                             int *retry)
{
  PetscInt    infog1, infog2;
  const char *prefix;
  char        hint[256] = "";

  PetscFunctionBegin;
  PetscCall(MatMumpsGetInfog(F, 1, &infog1));
  PetscCall(MatMumpsGetIcntl(F, 14, icntl14));
  *retry = infog1 >= 0 ? 0 : 1;
  if (infog1 >= 0 || ((infog1 == -8 || infog1 == -9) && !last)) PetscFunctionReturn(0);
  PetscCall(MatMumpsGetInfog(F, 2, &infog2));
  PetscCall(PetscObjectGetOptionsPrefix((PetscObject)F, &prefix));
  if (infog1 == -8 || infog1 == -9)
    PetscCall(PetscSNPrintf(hint, sizeof(hint),
                            ": out of workspace, even with its margin doubled 3 times: raise it, -%smat_mumps_icntl_14",
                            prefix ? prefix : ""));
  else if (infog1 == -10)
    PetscCall(PetscStrncpy(hint, ": A is not positive definite: check the material values", sizeof(hint)));
  SETERRQ(PetscObjectComm((PetscObject)A), PETSC_ERR_CONV_FAILED,
          "MUMPS factorization of %s of body '%s' failed: INFOG(1) = %" PetscInt_FMT ", INFOG(2) = %" PetscInt_FMT
          "%s (ICNTL(14) = %" PetscInt_FMT "; MUMPS users' guide, 'Error diagnostics')",
          what, body, infog1, infog2, hint, *icntl14);
}

/* The next margin, max(2 m + 20, 20), set where a factor's set-up reads it, whatever set the
   last one: the options database under the factor's prefix (PETSc's symbolic phase reads
   -<prefix>mat_mumps_icntl_14 there, over a value set on the factor) */
static PetscErrorCode SetMargin(Mat F, Mat A, PetscInt icntl14, const char what[], const char body[])
{
  const char *prefix;
  char        name[256], value[32];

  PetscFunctionBegin;
  PetscCall(PetscObjectGetOptionsPrefix((PetscObject)F, &prefix));
  PetscCall(PetscSNPrintf(name, sizeof(name), "-%smat_mumps_icntl_14", prefix ? prefix : ""));
  PetscCall(PetscSNPrintf(value, sizeof(value), "%" PetscInt_FMT, PetscMax(2 * icntl14 + 20, 20)));
  PetscCall(
      PetscInfo(A, "MUMPS out of workspace factoring %s of body %s: %s %s, a new factor\n", what, body, name, value));
  PetscCall(PetscOptionsSetValue(NULL, name, value));
  PetscFunctionReturn(0);
}

/* A builder's factor *F of A (analysed, numeric phase not yet called), factored and checked; a
   retry replaces *F by a new factor (MUMPS Cholesky, with schur as its Schur indices if not NULL) */
PetscErrorCode FCMumpsCholeskyChecked(Mat *F, Mat A, IS schur, const char what[], const char body[])
{
  MatFactorInfo info;
  PetscInt      icntl14;
  int           retry;

  PetscFunctionBegin;
  PetscCall(MatFactorInfoInitialize(&info));
  PetscCall(MatCholeskyFactorNumeric(*F, A, &info));
  for (int attempt = 0;; attempt++) {
    PetscCall(Status(*F, A, attempt == 3, what, body, &icntl14, &retry));
    if (!retry) break;
    PetscCall(SetMargin(*F, A, icntl14, what, body));
    PetscCall(MatDestroy(F));
    PetscCall(MatGetFactor(A, MATSOLVERMUMPS, MAT_FACTOR_CHOLESKY, F));
    if (schur) PetscCall(MatFactorSetSchurIS(*F, schur));
    PetscCall(MatCholeskyFactorSymbolic(*F, A, NULL, &info));
    PetscCall(MatCholeskyFactorNumeric(*F, A, &info));
  }
  PetscFunctionReturn(0);
}

/* The factorization of A by a KSP (set up already), checked: a MUMPS factor (Cholesky or LU) by
   MUMPS' status, out of workspace retried with the PC set up again on a new margin; any other by
   its PC's failure reason */
PetscErrorCode FCMumpsKSPChecked(KSP ksp, Mat A, const char what[], const char body[])
{
  PC             pc;
  PCFailedReason reason;
  MatSolverType  stype = NULL;
  PetscBool      mumps = PETSC_FALSE, chol, lu;

  PetscFunctionBegin;
  PetscCall(KSPGetPC(ksp, &pc));
  PetscCall(PetscObjectTypeCompare((PetscObject)pc, PCCHOLESKY, &chol));
  PetscCall(PetscObjectTypeCompare((PetscObject)pc, PCLU, &lu));
  if (chol || lu) PetscCall(PCFactorGetMatSolverType(pc, &stype));
  if (stype) PetscCall(PetscStrcmp(stype, MATSOLVERMUMPS, &mumps));
  for (int attempt = 0; mumps; attempt++) {
    Mat      F;
    PetscInt icntl14;
    int      retry;
    PetscCall(PCFactorGetMatrix(pc, &F));
    PetscCall(Status(F, A, attempt == 3, what, body, &icntl14, &retry));
    if (!retry) {
      PetscCall(PCSetFailedReason(pc, PC_NOERROR));
      break;
    }
    PetscCall(SetMargin(F, A, icntl14, what, body));
    PetscCall(PCReset(pc));
    PetscCall(KSPSetOperators(ksp, A, A));
    PetscCall(KSPSetUp(ksp));
  }
  PetscCall(PCGetFailedReason(pc, &reason));
  PetscCheck(reason == PC_NOERROR, PetscObjectComm((PetscObject)A), PETSC_ERR_CONV_FAILED,
             "Factorization of %s for body '%s' failed: %s", what, body, PCFailedReasons[reason]);
  PetscFunctionReturn(0);
}
