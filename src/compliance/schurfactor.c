/* FCSchurFactor: one sparse Cholesky factorization of A (MUMPS, called directly) with a set S of
   DOFs ordered last and kept as the Schur block, so that the factor that solves A x = b also gives

       Sigma = A_SS - A_SI A_II^-1 A_IS   and   (A^-1)_SS = Sigma^-1

   (block elimination; docs/method.md, "W_b from the factorization"). The condensed compliance
   builder (condensed.c) uses it as the body's only factor of A.

   Why MUMPS directly and not through PETSc: PETSc 3.18 ignores the ordering argument of a MUMPS
   Cholesky factorization, and MUMPS asked for a Schur complement without a given ordering falls
   back to AMD (INFOG(7) = 0 whatever ICNTL(7) says), whose fill is far larger. Here the
   ordering is METIS nested dissection of the vertex graph of the interior (V \ S), S appended
   last (ICNTL(7) = 1): on a cube resting on a whole face the Schur factorization then takes 1.8x
   the flops of a plain one (docs/method.md has the command that prints both).

   Layout: A is handed to MUMPS as the upper triangles of each rank's rows (distributed input,
   ICNTL(18) = 3 on several ranks); the ordering, the Schur complement and the right-hand sides are
   centralized on rank 0 (the host); Sigma^-1 is formed there with LAPACK, or over all the ranks
   with ScaLAPACK and gathered back (spdinverse.c). A solve is condensation
   (ICNTL(26) = 1), x_S = Sigma^-1 r_S on the host, then expansion (ICNTL(26) = 2).
   Distributed (-compliance_condensed_inverse distributed, or auto from a Schur block of
   -compliance_condensed_distributed_size DOFs on several ranks): MUMPS returns Sigma by
   block-cyclic columns over a 1 x p grid (ICNTL(19) = 3), ScaLAPACK inverts it there, every rank
   keeps its columns of C (ns^2 / p values) and S; x_S = C r_S is the sum of the ranks' columns
   times r_S, reduced on the host. Nothing of size ns^2 is ever on one rank.
   The DOFs come in vertex blocks of 3 (A's block size), and S is a union of blocks. */
#include "schurfactorimpl.h"
#include <petscblaslapack.h>

/* -log_view: where a factorization's time goes */
static PetscLogEvent EV_ANALYSIS, EV_NUMERIC, EV_INVERSE, EV_SOLVE;

/* struct _FCSchurFactor: schurfactorimpl.h */

/* S holds every DOF (a thin body all in contact): MUMPS takes only a Schur block smaller than A
   (SIZE_SCHUR < N, else INFOG(1) = -49), and Sigma = A: gathered dense and inverted, no MUMPS.
   ns is known on every rank once analysed. */
static inline PetscBool Full(FCSchurFactor f)
{
  return f->ns >= f->N ? PETSC_TRUE : PETSC_FALSE;
}

/* Whether this analysis (ns known on the host) will have Sigma distributed */
static inline PetscBool DistAsked(FCSchurFactor f)
{
  return (
      PetscBool)(f->size > 1 && f->ns &&
                 (f->type == FC_SPD_INVERSE_DISTRIBUTED || (f->type == FC_SPD_INVERSE_AUTO && f->ns >= f->distmin)));
}

/* MUMPS call with its error (INFOG(1) < 0) turned into a PETSc error naming the body and the phase */
/* MUMPS' pointers to the triples (distributed on several ranks, centralized on one) */
static void Entries(FCSchurFactor f)
{
  if (f->size > 1) {
    f->id.nnz_loc = f->nnz;
    f->id.irn_loc = f->irn;
    f->id.jcn_loc = f->jcn;
    f->id.a_loc   = f->val;
  } else {
    f->id.nnz = f->nnz;
    f->id.irn = f->irn;
    f->id.jcn = f->jcn;
    f->id.a   = f->val;
  }
}

static PetscErrorCode CallMumps(FCSchurFactor f, int job, const char phase[])
{
  PetscFunctionBegin;
  f->id.job = job;
  dmumps_c(&f->id);
  PetscCheck(f->id.INFOG(1) >= 0, f->comm, PETSC_ERR_LIB,
             "MUMPS %s of A of body '%s' failed: INFOG(1) = %d, INFOG(2) = %d (MUMPS users' guide, section "
             "'Error diagnostics')",
             phase, f->name, (int)f->id.INFOG(1), (int)f->id.INFOG(2));
  PetscFunctionReturn(0);
}

PetscErrorCode FCSchurFactorCreate(Mat A, const char name[], FCSPDInverseType inverse, PetscInt balance,
                                   PetscInt distmin, FCSchurFactor *sf)
{
  FCSchurFactor f;
  PetscBool     sbaij;
  Vec           b;

  PetscFunctionBegin;
  if (!EV_ANALYSIS) {
    PetscCall(PetscLogEventRegister("SchurAnalysis", FC_CLASSID, &EV_ANALYSIS));
    PetscCall(PetscLogEventRegister("SchurNumeric", FC_CLASSID, &EV_NUMERIC));
    PetscCall(PetscLogEventRegister("SchurInverse", FC_CLASSID, &EV_INVERSE));
    PetscCall(PetscLogEventRegister("SchurSolve", FC_CLASSID, &EV_SOLVE));
  }
  PetscCall(PetscNew(&f));
  PetscCallMPI(MPI_Comm_dup(PetscObjectComm((PetscObject)A), &f->comm));
  PetscCallMPI(MPI_Comm_rank(f->comm, &f->rank));
  PetscCallMPI(MPI_Comm_size(f->comm, &f->size));
  PetscCall(PetscStrncpy(f->name, name, sizeof(f->name)));
  f->balance = balance;
  f->type    = inverse;
  f->distmin = distmin;
  PetscCall(MatGetSize(A, &f->N, NULL));
  PetscCall(MatGetOwnershipRange(A, &f->lo, &f->hi));
  PetscCall(PetscObjectTypeCompareAny((PetscObject)A, &sbaij, MATSBAIJ, MATSEQSBAIJ, MATMPISBAIJ, ""));
  /* the FE body numbers the DOFs of a vertex consecutively, from a multiple of 3 */
  PetscCheck(f->N % 3 == 0 && f->lo % 3 == 0 && f->hi % 3 == 0 && !sbaij, f->comm, PETSC_ERR_SUP,
             "-compliance_type condensed needs A of body '%s' by rows of vertex blocks of 3 DOFs (AIJ or BAIJ, "
             "not SBAIJ)",
             name);
  PetscCall(FCSchurFactorTriples(f, A, PETSC_FALSE));
  PetscCall(FCSchurFactorGatherGraph(f, A));
  PetscCall(MatCreateVecs(A, &b, NULL));
  PetscCall(VecScatterCreateToZero(b, &f->tohost, &f->bseq));
  PetscCall(VecDestroy(&b));
  PetscCall(FCSPDInverseCreate(f->comm, name, inverse, &f->inv));

  f->id.job          = -1;
  f->id.par          = 1;
  f->id.sym          = 1; /* A is SPD (M + h^2 K, the body sets MAT_SPD): no pivoting */
  f->id.comm_fortran = (MUMPS_INT)MPI_Comm_c2f(f->comm);
  dmumps_c(&f->id);
  PetscCheck(f->id.INFOG(1) >= 0, f->comm, PETSC_ERR_LIB, "MUMPS initialization for body '%s' failed: INFOG(1) = %d",
             name, (int)f->id.INFOG(1));
  f->id.ICNTL(1)  = -1; /* errors come back through INFOG(1) (CallMumps) */
  f->id.ICNTL(2)  = -1;
  f->id.ICNTL(3)  = -1;
  f->id.ICNTL(4)  = 0;
  f->id.ICNTL(7)  = 1; /* the ordering is ours (perm_in) */
  f->id.ICNTL(18) = f->size > 1 ? 3 : 0;
  f->id.ICNTL(20) = 0; /* right-hand side and solution centralized on the host */
  f->id.ICNTL(21) = 0;
  f->id.ICNTL(28) = 1; /* sequential analysis: perm_in is used as given */
  f->id.n         = (MUMPS_INT)f->N;
  Entries(f);
  *sf = f;
  PetscFunctionReturn(0);
}

/* The Schur DOFs of the next factorization (host; sorted global DOFs, whole vertex blocks). A
   set equal to the current one keeps the analysis. */
PetscErrorCode FCSchurFactorSetSchur(FCSchurFactor f, PetscInt ns, const PetscInt S[])
{
  PetscBool same = PETSC_FALSE;

  PetscFunctionBegin;
  if (!f->rank) {
    same = (PetscBool)(f->analysed && ns == f->ns);
    for (PetscInt i = 0; same && i < ns; i++) same = (PetscBool)(S[i] == f->S[i]);
    if (!same) {
      PetscCall(PetscFree(f->Snext));
      PetscCall(PetscMalloc1(ns + 1, &f->Snext));
      PetscCall(PetscArraycpy(f->Snext, S, ns));
      f->nsnext = ns;
    }
  }
  PetscCallMPI(MPI_Bcast(&same, 1, MPIU_BOOL, 0, f->comm));
  if (!same) f->analysed = PETSC_FALSE;
  PetscFunctionReturn(0);
}

/* Host: perm_in = nested dissection of the vertex graph without S, then S in its order (schurorder.c) */
static PetscErrorCode Ordering(FCSchurFactor f)
{
  PetscInt *perm;

  PetscFunctionBegin;
  PetscCall(PetscMalloc1(f->N + 1, &perm));
  PetscCall(FCSchurOrdering(f->name, f->nb, f->xadj, f->adj, f->ns, f->S, f->N, f->balance, perm));
  PetscCall(PetscFree(f->perm));
  PetscCall(PetscMalloc1(f->N + 1, &f->perm));
  for (PetscInt i = 0; i < f->N; i++) f->perm[i] = (MUMPS_INT)perm[i];
  PetscCall(PetscFree(perm));
  PetscFunctionReturn(0);
}

static PetscErrorCode Analyse(FCSchurFactor f)
{
  PetscFunctionBegin;
  PetscCall(PetscLogEventBegin(EV_ANALYSIS, 0, 0, 0, 0));
  if (!f->rank) {
    PetscCall(PetscFree(f->S));
    f->S      = f->Snext;
    f->ns     = f->nsnext;
    f->Snext  = NULL;
    f->nsnext = 0;
    PetscCall(Ordering(f));
    PetscCall(PetscFree(f->list));
    PetscCall(PetscFree3(f->sigma, f->red, f->work));
    PetscCall(PetscMalloc1(f->ns + 1, &f->list));
    PetscCall(PetscMalloc3(Full(f) || !DistAsked(f) ? f->ns * f->ns + 1 : 1, &f->sigma, f->ns + 1, &f->red, f->ns + 1,
                           &f->work));
    for (PetscInt i = 0; i < f->ns; i++) f->list[i] = (MUMPS_INT)(f->S[i] + 1);
    f->id.perm_in       = f->perm;
    f->id.size_schur    = (MUMPS_INT)f->ns;
    f->id.listvar_schur = f->list;
    f->id.schur         = f->sigma;
    f->id.schur_lld     = (MUMPS_INT)f->ns;
  }
  PetscCallMPI(MPI_Bcast(&f->ns, 1, MPIU_INT, 0, f->comm));
  f->dist = (PetscBool)(DistAsked(f) && !Full(f));
  PetscCall(PetscFree3(f->loc, f->rl, f->yl));
  PetscCall(PetscFree(f->Sall));
  f->nloc = 0;
  if (f->dist) { /* Sigma by block-cyclic columns over the 1 x p grid of spdinverse.c, whole columns */
    PetscCall(PetscMalloc1(f->ns + 1, &f->Sall));
    if (!f->rank) PetscCall(PetscArraycpy(f->Sall, f->S, f->ns));
    PetscCallMPI(MPI_Bcast(f->Sall, (PetscMPIInt)f->ns, MPIU_INT, 0, f->comm));
    f->cnb  = FCSPDBlock(f->ns, f->size);
    f->nloc = FCSPDLocalColumns(f->ns, f->cnb, f->rank, f->size);
    PetscCall(PetscMalloc3((size_t)f->ns * f->nloc + 1, &f->loc, f->nloc + 1, &f->rl, f->ns + 1, &f->yl));
    f->id.nprow     = 1;
    f->id.npcol     = (MUMPS_INT)f->size;
    f->id.mblock    = (MUMPS_INT)f->cnb;
    f->id.nblock    = (MUMPS_INT)f->cnb;
    f->id.ICNTL(19) = 3;    /* distributed on the grid, both triangles */
    f->id.schur     = NULL; /* given after the analysis, at its size */
  } else
    f->id.ICNTL(19) = f->ns ? 1 : 0; /* Schur complement centralized on the host (lower triangle by rows) */
  f->id.ICNTL(23) = 0;               /* MUMPS' own workspace estimate (FCSchurFactorFactor raises it on a -9) */
  if (!Full(f)) PetscCall(CallMumps(f, 1, "analysis"));
  if (f->dist) { /* MUMPS' layout is the grid's (one verdict: a rank alone leaving would hang the others) */
    PetscBool ok = (PetscBool)(f->id.schur_mloc == (MUMPS_INT)f->ns && f->id.schur_nloc == (MUMPS_INT)f->nloc &&
                               f->id.nprow == 1 && f->id.npcol == (MUMPS_INT)f->size &&
                               f->id.mblock == (MUMPS_INT)f->cnb && f->id.nblock == (MUMPS_INT)f->cnb);
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &ok, 1, MPIU_BOOL, MPI_LAND, f->comm));
    PetscCheck(ok, f->comm, PETSC_ERR_LIB,
               "MUMPS' distributed Schur block of body '%s' is not on the expected 1 x %d grid of %" PetscInt_FMT
               " x %" PetscInt_FMT "-column blocks (rank %d: %d x %d local, grid %d x %d)",
               f->name, (int)f->size, f->ns, f->cnb, (int)f->rank, (int)f->id.schur_mloc, (int)f->id.schur_nloc,
               (int)f->id.nprow, (int)f->id.npcol);
    f->id.schur     = f->loc;
    f->id.schur_lld = (MUMPS_INT)f->ns;
  }
  PetscCall(PetscLogEventEnd(EV_ANALYSIS, 0, 0, 0, 0));
  f->analysed = PETSC_TRUE;
  f->nanalysis++;
  PetscFunctionReturn(0);
}

/* S = every DOF: Sigma = A, its upper triangle (the owned rows' triples) gathered into the
   host's column-major array, as MUMPS would return it */
typedef struct {
  PetscInt  i, j;
  PetscReal v;
} Entry;

static PetscErrorCode GatherDense(FCSchurFactor f)
{
  Entry   *loc, *all;
  PetscInt ntot;

  PetscFunctionBegin;
  PetscCall(PetscMalloc1(f->nnz + 1, &loc));
  for (PetscInt k = 0; k < f->nnz; k++) {
    loc[k].i = (PetscInt)f->irn[k] - 1;
    loc[k].j = (PetscInt)f->jcn[k] - 1;
    loc[k].v = f->val[k];
  }
  PetscCall(FCAllgatherRecords(f->comm, f->nnz, sizeof(Entry), loc, &ntot, (void **)&all));
  if (!f->rank) {
    PetscCall(PetscArrayzero(f->sigma, f->N * f->N));
    for (PetscInt k = 0; k < ntot; k++) f->sigma[all[k].i + all[k].j * f->N] += all[k].v; /* i <= j */
  }
  PetscCall(PetscFree(all));
  PetscCall(PetscFree(loc));
  PetscFunctionReturn(0);
}

/* Numeric factorization of A (analysis first when S changed), then on the host
   C = Sigma^-1 = (A^-1)_SS by LAPACK Cholesky */
PetscErrorCode FCSchurFactorFactor(FCSchurFactor f, Mat A)
{
  PetscFunctionBegin;
  if (!f->irn) { /* freed after the last factorization: the structure again */
    PetscCall(FCSchurFactorTriples(f, A, PETSC_FALSE));
    Entries(f);
  }
  PetscCall(FCSchurFactorTriples(f, A, PETSC_TRUE));
  if (!f->analysed) PetscCall(Analyse(f));
  PetscCall(PetscLogEventBegin(EV_NUMERIC, 0, 0, 0, 0));
  if (Full(f))
    PetscCall(GatherDense(f));
  else
    for (int attempt = 0;; attempt++) { /* MUMPS underestimating its workspace: -8, -9 (then ICNTL(14) doubled) */
      f->id.job = 2;
      dmumps_c(&f->id);
      if (f->id.INFOG(1) >= 0 || (f->id.INFOG(1) != -8 && f->id.INFOG(1) != -9) || attempt == 3) break;
      f->id.ICNTL(14) = 2 * f->id.ICNTL(14) + 20;
      /* a distributed Schur block: MUMPS 5.5 can fail with -9 on small problems whatever ICNTL(14)
         (input/hard/cube_thin_plate.opts, 2 ranks); a workspace given in MB, twice its estimate of
         the most loaded rank (INFOG(16)), is enough there. Until the next analysis. */
      if (f->dist) f->id.ICNTL(23) = PetscMax(2 * f->id.ICNTL(23), 2 * f->id.INFOG(16) + 16);
    }
  PetscCheck(Full(f) || f->id.INFOG(1) >= 0, f->comm, PETSC_ERR_LIB,
             "MUMPS factorization of A of body '%s' failed: INFOG(1) = %d, INFOG(2) = %d%s", f->name,
             (int)f->id.INFOG(1), (int)f->id.INFOG(2),
             f->id.INFOG(1) == -10 ? " (A is not positive definite: check the material values)" : "");
  PetscCall(PetscLogEventEnd(EV_NUMERIC, 0, 0, 0, 0));
  /* MUMPS holds A in its own structures from here (its solves read only the factor): the triples
     (16 bytes an entry of A's upper triangle) are made again at the next factorization */
  PetscCall(PetscFree3(f->irn, f->jcn, f->val));
  Entries(f);
  if (Full(f))
    PetscCall(PetscInfo(NULL, "body %s: every one of its %" PetscInt_FMT " DOFs in S: Sigma = A, gathered dense\n",
                        f->name, f->N));
  else
    PetscCall(PetscInfo(NULL,
                        "body %s: factorization with %" PetscInt_FMT
                        " Schur DOFs: %.3g flops (%.3g on this rank), %d entries in the factor\n",
                        f->name, f->ns, (double)f->id.rinfog[2], (double)f->id.rinfo[2], (int)f->id.INFOG(29)));
  f->nfactor++;
  /* MUMPS returns the lower triangle by rows: the upper one of the column-major array */
  PetscCall(PetscLogEventBegin(EV_INVERSE, 0, 0, 0, 0));
  if (f->dist)
    PetscCall(FCSPDInverseApplyLocal(f->inv, f->ns, f->cnb, f->loc));
  else
    PetscCall(FCSPDInverseApply(f->inv, f->ns, f->sigma));
  PetscCall(PetscLogEventEnd(EV_INVERSE, 0, 0, 0, 0));
  f->factored = PETSC_TRUE;
  PetscFunctionReturn(0);
}

/* Host: y = C x, C = (A^-1)_SS (ns x ns, symmetric, column-major; A^-1 when S is every DOF) */
static PetscErrorCode ApplyC(FCSchurFactor f, const PetscReal x[], PetscReal y[])
{
  PetscBLASInt n, one = 1;
  PetscReal    alpha = 1.0, beta = 0.0;

  PetscFunctionBegin;
  PetscCall(PetscBLASIntCast(f->ns, &n));
  if (n) PetscCallBLAS("BLASgemv", BLASgemv_("N", &n, &n, &alpha, f->sigma, &n, x, &one, &beta, y, &one));
  PetscFunctionReturn(0);
}

/* The host's reduced right-hand side r_S becomes C r_S, C by the ranks' block-cyclic columns:
   r_S broadcast, each rank's C(:, J) r_S(J), summed on the host */
static PetscErrorCode ApplyDistributedC(FCSchurFactor f)
{
  PetscReal   *r = f->rank ? f->yl : f->red, alpha = 1.0, beta = 0.0;
  PetscBLASInt n, m, one                                       = 1;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Bcast(r, (PetscMPIInt)f->ns, MPIU_REAL, 0, f->comm));
  for (PetscInt jl = 0; jl < f->nloc; jl++) f->rl[jl] = r[FCSPDGlobalColumn(jl, f->cnb, f->rank, f->size)];
  PetscCall(PetscBLASIntCast(f->ns, &n));
  PetscCall(PetscBLASIntCast(f->nloc, &m));
  if (m)
    PetscCallBLAS("BLASgemv", BLASgemv_("N", &n, &m, &alpha, f->loc, &n, f->rl, &one, &beta, f->yl, &one));
  else
    PetscCall(PetscArrayzero(f->yl, f->ns));
  PetscCallMPI(MPI_Reduce(f->yl, f->work, (PetscMPIInt)f->ns, MPIU_REAL, MPIU_SUM, 0, f->comm));
  if (!f->rank) PetscCall(PetscArraycpy(f->red, f->work, f->ns));
  PetscFunctionReturn(0);
}

/* x = A^-1 b: condensation on S, x_S = C r_S on the host, expansion */
PetscErrorCode FCSchurFactorSolve(FCSchurFactor f, Vec b, Vec x)
{
  PetscScalar *rhs = NULL;

  PetscFunctionBegin;
  PetscCheck(f->factored, f->comm, PETSC_ERR_ORDER, "Solve with A of body '%s' before its factorization", f->name);
  PetscCall(PetscLogEventBegin(EV_SOLVE, 0, 0, 0, 0));
  PetscCall(VecScatterBegin(f->tohost, b, f->bseq, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecScatterEnd(f->tohost, b, f->bseq, INSERT_VALUES, SCATTER_FORWARD));
  if (!f->rank) {
    PetscCall(VecGetArray(f->bseq, &rhs));
    f->id.rhs     = rhs;
    f->id.nrhs    = 1;
    f->id.lrhs    = (MUMPS_INT)f->N;
    f->id.redrhs  = f->red;
    f->id.lredrhs = (MUMPS_INT)f->ns;
  }
  if (Full(f)) { /* x = C b on the host, C = A^-1 */
    if (!f->rank) {
      PetscCall(ApplyC(f, rhs, f->work));
      PetscCall(PetscArraycpy(rhs, f->work, f->N));
    }
  } else if (f->ns) {
    f->id.ICNTL(26) = 1;
    PetscCall(CallMumps(f, 3, "condensation"));
    if (f->dist)
      PetscCall(ApplyDistributedC(f));
    else if (!f->rank) {
      PetscCall(ApplyC(f, f->red, f->work));
      PetscCall(PetscArraycpy(f->red, f->work, f->ns));
    }
    f->id.ICNTL(26) = 2;
    PetscCall(CallMumps(f, 3, "expansion"));
  } else {
    f->id.ICNTL(26) = 0;
    PetscCall(CallMumps(f, 3, "solve"));
  }
  if (!f->rank) PetscCall(VecRestoreArray(f->bseq, &rhs));
  PetscCall(VecScatterBegin(f->tohost, f->bseq, x, INSERT_VALUES, SCATTER_REVERSE));
  PetscCall(VecScatterEnd(f->tohost, f->bseq, x, INSERT_VALUES, SCATTER_REVERSE));
  PetscCall(PetscLogEventEnd(EV_SOLVE, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

/* Host: S of the current factorization and C = (A^-1)_SS (ns x ns, column-major, symmetric) */
PetscErrorCode FCSchurFactorGetInverse(FCSchurFactor f, PetscInt *ns, const PetscInt **S, const PetscReal **C)
{
  PetscFunctionBegin;
  *ns = f->ns;
  if (S) *S = f->S;
  if (C) *C = f->sigma;
  PetscFunctionReturn(0);
}

/* Every rank: whether C is distributed, and then S, and this rank's block-cyclic columns of C
   (ns x nloc, lld ns, blocks of nb; global column of local jl: FCSPDGlobalColumn) */
PetscErrorCode FCSchurFactorGetLocalInverse(FCSchurFactor f, PetscBool *dist, PetscInt *ns, const PetscInt **S,
                                            PetscInt *nb, PetscInt *nloc, const PetscReal **C)
{
  PetscFunctionBegin;
  *nb   = f->cnb;
  *dist = f->dist;
  *ns   = f->ns;
  *S    = f->Sall;
  *nloc = f->nloc;
  *C    = f->loc;
  PetscFunctionReturn(0);
}

/* This rank's bytes of Sigma / C, and MUMPS' memory for the factorization on this rank and the
   largest rank (INFO(22), INFOG(21): millions of bytes) */
PetscErrorCode FCSchurFactorGetMemory(FCSchurFactor f, PetscReal *sigma, PetscReal *factor, PetscReal *factormax)
{
  PetscFunctionBegin;
  *sigma     = 8.0 * (f->dist ? (PetscReal)f->ns * f->nloc : (!f->rank ? (PetscReal)f->ns * f->ns : 0.0));
  *factor    = f->factored && !Full(f) ? 1e6 * f->id.INFO(22) : 0.0;
  *factormax = f->factored && !Full(f) ? 1e6 * f->id.INFOG(21) : 0.0;
  PetscFunctionReturn(0);
}

/* Host: the vertex-block graph of A (CSR, no self loops) */
PetscErrorCode FCSchurFactorGetGraph(FCSchurFactor f, PetscInt *nb, const PetscInt **xadj, const PetscInt **adj)
{
  PetscFunctionBegin;
  *nb   = f->nb;
  *xadj = f->xadj;
  *adj  = f->adj;
  PetscFunctionReturn(0);
}

PetscErrorCode FCSchurFactorGetCounts(FCSchurFactor f, PetscInt *nanalysis, PetscInt *nfactor)
{
  PetscFunctionBegin;
  if (nanalysis) *nanalysis = f->nanalysis;
  if (nfactor) *nfactor = f->nfactor;
  PetscFunctionReturn(0);
}

PetscErrorCode FCSchurFactorDestroy(FCSchurFactor *sf)
{
  FCSchurFactor f = *sf;

  PetscFunctionBegin;
  if (!f) PetscFunctionReturn(0);
  f->id.job = -2;
  dmumps_c(&f->id);
  PetscCall(PetscFree3(f->irn, f->jcn, f->val));
  PetscCall(PetscFree2(f->xadj, f->adj));
  PetscCall(PetscFree(f->S));
  PetscCall(PetscFree(f->Snext));
  PetscCall(PetscFree(f->perm));
  PetscCall(PetscFree(f->list));
  PetscCall(PetscFree3(f->sigma, f->red, f->work));
  PetscCall(PetscFree3(f->loc, f->rl, f->yl));
  PetscCall(PetscFree(f->Sall));
  PetscCall(VecDestroy(&f->bseq));
  PetscCall(VecScatterDestroy(&f->tohost));
  PetscCall(FCSPDInverseDestroy(&f->inv));
  PetscCallMPI(MPI_Comm_free(&f->comm));
  PetscCall(PetscFree(f));
  *sf = NULL;
  PetscFunctionReturn(0);
}
