/* Compliance builders "inverse" and "redundant" (selected inverse): W_b = J_S C J_S^T with
   C = (A^-1)_{SS} the block of the inverse on the DOFs S that the body's contacts touch, from MUMPS
   (ICNTL(30), MatMumpsGetInverse). MUMPS prunes its elimination tree to the paths of S, so the cost
   follows |S| and the tree, not |S| full solves.
     inverse    with the factor A already has (distributed): the entries come back on rank 0,
                which forms W_b;
     redundant  every rank keeps its own sequential factor of the whole A (PCREDUNDANT's idea:
                memory for parallelism) and computes the columns of C for its 1/p share of S;
                the partial W_b are summed. A linear A is factored once; a co-rotational one
                again whenever the body refactors A.
   The correction does one solve with the distributed factor (compliance.c).
   Options: -compliance_inverse_block, -compliance_redundant_groups, -compliance_redundant_memory_limit
   (help strings below; docs/options.md). */
#include "complianceimpl.h"
#include <unistd.h>

typedef struct {
  PetscBool redundant;
  PetscInt  block;         /* MUMPS ICNTL(27) for the entries of A^-1 */
  PetscInt  groups, group; /* redundant: copies, and the one this rank belongs to */
  PetscReal memory;        /* redundant: bytes per rank a copy's factorization may take */
  MPI_Comm  rcomm;         /* redundant: the ranks of this rank's copy */
  Mat       Ar, Fr;        /* redundant: the copy of A and its factor */
} Inverse;

static PetscErrorCode SetFromOptions_Inverse(FCCompliance comp, PetscOptionItems *PetscOptionsObject)
{
  Inverse    *inv = (Inverse *)comp->data;
  PetscMPIInt size;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_size(comp->ctx.comm, &size));
  PetscCall(FCOptionsInt(PetscOptionsObject, "-compliance_inverse_block",
                         "MUMPS ICNTL(27) while it computes entries of A^-1", &inv->block, NULL));
  PetscCheck(inv->block != 0, comp->ctx.comm, PETSC_ERR_USER_INPUT,
             "Option -compliance_inverse_block must be non-zero (> 0: columns per block, < 0: MUMPS' automatic "
             "choice with that bound), got 0");
  if (!inv->redundant) PetscFunctionReturn(0);
  inv->groups = size;
  PetscCall(FCOptionsInt(PetscOptionsObject, "-compliance_redundant_groups", "Copies of A (redundant builder)",
                         &inv->groups, NULL));
  PetscCheck(inv->groups >= 1 && inv->groups <= size, comp->ctx.comm, PETSC_ERR_USER_INPUT,
             "Option -compliance_redundant_groups must be in [1, %d] (the number of ranks), got %" PetscInt_FMT, size,
             inv->groups);
  { /* default: the memory available now, shared by the ranks of this node */
    MPI_Comm    node;
    PetscMPIInt nnode;
    PetscCallMPI(MPI_Comm_split_type(comp->ctx.comm, MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &node));
    PetscCallMPI(MPI_Comm_size(node, &nnode));
    PetscCallMPI(MPI_Comm_free(&node));
    inv->memory = (PetscReal)sysconf(_SC_AVPHYS_PAGES) * (PetscReal)sysconf(_SC_PAGESIZE) / nnode;
  }
  PetscCall(FCOptionsReal(PetscOptionsObject, "-compliance_redundant_memory_limit",
                          "Bytes per rank a copy of A's factorization may take (redundant builder)", &inv->memory,
                          NULL));
  PetscCheck(inv->memory > 0, comp->ctx.comm, PETSC_ERR_USER_INPUT,
             "Option -compliance_redundant_memory_limit must be > 0, got %g", (double)inv->memory);
  PetscFunctionReturn(0);
}

/* Adds to Wb the part of J_S C J_S^T from the columns j0 <= j < j1 of C = (A^-1)_{SS}, computed
   with the factor F; a rank with j1 > j0 must hold every row of F (rank 0 of a distributed
   factor, or a sequential factor) */
static PetscErrorCode AddInverseColumns(Mat F, PetscInt N, PetscInt ns, const PetscInt S[], const PetscInt cptr[],
                                        const PetscInt crow[], const PetscReal cval[], PetscInt j0, PetscInt j1,
                                        PetscInt block, PetscInt ncols, PetscReal *Wb)
{
  MPI_Comm    comm = PetscObjectComm((PetscObject)F);
  PetscMPIInt size;
  PetscInt    nloc = j1 > j0 ? N : 0, *nnz, icntl21, icntl27, icntl30;
  PetscReal  *T;
  Mat         Bt, Btseq, spRHS;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_size(comm, &size));
  /* row S_j of Bt lists the entries wanted in column S_j of A^-1 */
  PetscCall(MatCreateAIJ(comm, nloc, nloc, N, N, 0, NULL, 0, NULL, &Bt));
  PetscCall(PetscCalloc1(nloc + 1, &nnz));
  for (PetscInt j = j0; j < j1; j++) nnz[S[j]] = ns;
  PetscCall(MatSeqAIJSetPreallocation(Bt, 0, nnz));
  PetscCall(MatMPIAIJSetPreallocation(Bt, 0, nnz, 0, NULL));
  PetscCall(PetscFree(nnz));
  {
    PetscScalar *zero;
    PetscCall(PetscCalloc1(ns + 1, &zero));
    for (PetscInt j = j0; j < j1; j++) PetscCall(MatSetValues(Bt, 1, &S[j], ns, S, zero, INSERT_VALUES));
    PetscCall(PetscFree(zero));
  }
  PetscCall(MatAssemblyBegin(Bt, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(Bt, MAT_FINAL_ASSEMBLY));
  PetscCall(MatCreateTranspose(Bt, &spRHS));
  /* PETSc 3.18 leaves ICNTL(30) = 1 and ICNTL(21) = 0 (centralized solution) set after the call,
     which breaks the later solves with a distributed factor: restore both */
  PetscCall(MatMumpsGetIcntl(F, 21, &icntl21));
  PetscCall(MatMumpsGetIcntl(F, 27, &icntl27));
  PetscCall(MatMumpsGetIcntl(F, 30, &icntl30));
  PetscCall(MatMumpsSetIcntl(F, 27, block)); /* columns of A^-1 per block: -compliance_inverse_block */
  PetscCall(MatMumpsGetInverse(F, spRHS));
  PetscCall(MatMumpsSetIcntl(F, 21, icntl21));
  PetscCall(MatMumpsSetIcntl(F, 27, icntl27));
  PetscCall(MatMumpsSetIcntl(F, 30, icntl30));
  if (size > 1)
    PetscCall(MatMPIAIJGetSeqAIJ(Bt, &Btseq, NULL, NULL));
  else
    Btseq = Bt;
  /* per own column j: T = (J_S C)(:, j), then Wb(a, b) += T(a) J_S(b, j) */
  PetscCall(PetscMalloc1(ncols + 1, &T));
  for (PetscInt j = j0; j < j1; j++) {
    PetscInt           nc;
    const PetscInt    *cols;
    const PetscScalar *vals;
    PetscCall(MatGetRow(Btseq, S[j], &nc, &cols, &vals)); /* C(:, j), in the order of S */
    PetscCheck(nc == ns, PETSC_COMM_SELF, PETSC_ERR_LIB,
               "MUMPS returned %" PetscInt_FMT " of %" PetscInt_FMT " entries", nc, ns);
    FCComplianceAddColumn(ncols, ns, cptr, crow, cval, j, vals, T, Wb);
    PetscCall(MatRestoreRow(Btseq, S[j], &nc, &cols, &vals));
  }
  PetscCall(PetscFree(T));
  PetscCall(MatDestroy(&spRHS));
  PetscCall(MatDestroy(&Bt));
  PetscFunctionReturn(0);
}

/* Before the copies are factored: MUMPS' estimate of the memory of this rank's share of its copy
   (INFO(15), MB, in-core) against -compliance_redundant_memory_limit, so that a copy that would not
   fit stops with a clear error instead of an allocation failure or the kernel's OOM killer */
static PetscErrorCode CheckRedundantMemory(FCCompliance comp)
{
  Inverse  *inv = (Inverse *)comp->data;
  PetscInt  mb;
  PetscReal need, worst;

  PetscFunctionBegin;
  PetscCall(MatMumpsGetInfo(inv->Fr, 15, &mb));
  need = 1e6 * (PetscReal)mb;
  PetscCall(MPIU_Allreduce(&need, &worst, 1, MPIU_REAL, MPIU_MAX, comp->ctx.comm));
  PetscCheck(worst <= inv->memory, comp->ctx.comm, PETSC_ERR_MEM,
             "-compliance_type redundant: the copy of A of body '%s' needs about %.3g GB per rank to factor (MUMPS "
             "estimate), above -compliance_redundant_memory_limit %.3g GB; use fewer copies "
             "(-compliance_redundant_groups k), -compliance_type inverse, or raise the limit",
             comp->ctx.name, (double)(worst / 1e9), (double)(inv->memory / 1e9));
  PetscFunctionReturn(0);
}

/* redundant: this rank's copy of A (on the rcomm of its group), refreshed, and at the first call
   its analysis and the memory check; groups = size (the default): a sequential copy per rank. On
   one rank A's own factor is already sequential and serves. */
static PetscErrorCode RedundantCopy(FCCompliance comp)
{
  Inverse      *inv = (Inverse *)comp->data;
  PetscMPIInt   size, rank;
  MatFactorInfo info;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_size(comp->ctx.comm, &size));
  PetscCallMPI(MPI_Comm_rank(comp->ctx.comm, &rank));
  if (size == 1) PetscFunctionReturn(0);
  if (inv->rcomm == MPI_COMM_NULL) { /* contiguous groups of ranks */
    inv->group = (PetscInt)(((PetscInt64)rank * inv->groups) / size);
    PetscCallMPI(MPI_Comm_split(comp->ctx.comm, (PetscMPIInt)inv->group, rank, &inv->rcomm));
  }
  PetscCall(MatCreateRedundantMatrix(comp->ctx.A, inv->groups, inv->rcomm,
                                     inv->Ar ? MAT_REUSE_MATRIX : MAT_INITIAL_MATRIX, &inv->Ar));
  PetscCall(MatSetOption(inv->Ar, MAT_SYMMETRIC, PETSC_TRUE));
  PetscCall(MatFactorInfoInitialize(&info));
  if (!inv->Fr) { /* the pattern of A never changes: one analysis */
    PetscCall(MatGetFactor(inv->Ar, MATSOLVERMUMPS, MAT_FACTOR_CHOLESKY, &inv->Fr));
    PetscCall(MatCholeskyFactorSymbolic(inv->Fr, inv->Ar, NULL, &info));
    PetscCall(CheckRedundantMemory(comp));
  }
  PetscFunctionReturn(0);
}

/* redundant: the copy factored with A, each time the body factors A */
static PetscErrorCode RedundantFactor(FCCompliance comp)
{
  Inverse *inv = (Inverse *)comp->data;

  PetscFunctionBegin;
  PetscCall(RedundantCopy(comp));
  if (inv->Fr) PetscCall(FCMumpsCholeskyChecked(&inv->Fr, inv->Ar, NULL, "the redundant copy of A", comp->ctx.name));
  PetscFunctionReturn(0);
}

/* The selected-inverse builders need MUMPS as the factorization of A */
static PetscErrorCode SetUp_Inverse(FCCompliance comp)
{
  Inverse      *inv = (Inverse *)comp->data;
  PC            pc;
  MatSolverType stype;
  PetscBool     mumps;

  PetscFunctionBegin;
  PetscCall(KSPGetPC(comp->ctx.ksp, &pc));
  PetscCall(PCFactorGetMatSolverType(pc, &stype)); /* A is not factored yet */
  PetscCall(PetscStrcmp(stype, MATSOLVERMUMPS, &mumps));
  PetscCheck(mumps, comp->ctx.comm, PETSC_ERR_USER_INPUT,
             "-compliance_type %s needs MUMPS as the factorization of body '%s' (it has '%s' from "
             "-%spc_factor_mat_solver_type): use MUMPS or -compliance_type dense",
             comp->type, comp->ctx.name, stype, comp->ctx.prefix);
  if (inv->redundant) PetscCall(RedundantCopy(comp)); /* the copies' analysis and memory check, at set-up */
  PetscFunctionReturn(0);
}

static PetscErrorCode Build_Inverse(FCCompliance comp, PetscInt self, const FCContactSet *set, PetscReal Wb[])
{
  Inverse    *inv = (Inverse *)comp->data;
  PetscMPIInt rank, size;
  PetscInt    N, ns = 0, *S = NULL, *cptr = NULL, *crow = NULL, j0, j1;
  PetscReal  *cval = NULL;
  Mat         F;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_rank(comp->ctx.comm, &rank));
  PetscCallMPI(MPI_Comm_size(comp->ctx.comm, &size));
  PetscCall(VecGetSize(comp->ctx.u, &N));
  PetscCall(FCComplianceGetFactor(comp, &F)); /* MUMPS: checked at set-up */
  PetscCall(FCComplianceContactDofs(comp, &ns, &S, &cptr, &crow, &cval));
  if (!ns) { /* every contact DOF is fixed: W_b = 0 (MUMPS refuses an empty selection, INFOG(1) = -45) */
    PetscCall(PetscFree(S));
    PetscCall(PetscFree(cptr));
    PetscCall(PetscFree(crow));
    PetscCall(PetscFree(cval));
    PetscFunctionReturn(0);
  }
  if (inv->redundant && size > 1) { /* the group's share of S, on rank 0 of its copy */
    PetscMPIInt grank = 0;
    F                 = inv->Fr;
    PetscCallMPI(MPI_Comm_rank(inv->rcomm, &grank));
    j0 = (ns * inv->group) / inv->groups;
    j1 = grank ? j0 : (ns * (inv->group + 1)) / inv->groups;
  } else { /* all of S on rank 0 of the distributed factor */
    j0 = 0;
    j1 = rank ? 0 : ns;
  }
  PetscCall(AddInverseColumns(F, N, ns, S, cptr, crow, cval, j0, j1, inv->block, comp->ncols, Wb));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, Wb, comp->ncols * comp->ncols, MPIU_REAL, MPIU_SUM, comp->ctx.comm));
  PetscCall(PetscFree(S));
  PetscCall(PetscFree(cptr));
  PetscCall(PetscFree(crow));
  PetscCall(PetscFree(cval));
  PetscFunctionReturn(0);
}

static PetscErrorCode Destroy_Inverse(FCCompliance comp)
{
  Inverse *inv = (Inverse *)comp->data;

  PetscFunctionBegin;
  PetscCall(MatDestroy(&inv->Fr));
  PetscCall(MatDestroy(&inv->Ar));
  if (inv->rcomm != MPI_COMM_NULL) PetscCallMPI(MPI_Comm_free(&inv->rcomm));
  PetscCall(PetscFree(comp->data));
  PetscFunctionReturn(0);
}

static PetscErrorCode Create(FCCompliance comp, PetscBool redundant)
{
  Inverse *inv;

  PetscFunctionBegin;
  PetscCall(PetscNew(&inv));
  inv->redundant           = redundant;
  inv->block               = 256;
  inv->memory              = PETSC_MAX_REAL;
  inv->rcomm               = MPI_COMM_NULL;
  comp->data               = inv;
  comp->ops.setfromoptions = SetFromOptions_Inverse;
  comp->ops.setup          = SetUp_Inverse;
  comp->ops.factor         = redundant ? RedundantFactor : NULL;
  comp->ops.build          = Build_Inverse;
  comp->ops.destroy        = Destroy_Inverse;
  PetscFunctionReturn(0);
}

PetscErrorCode FCComplianceCreate_Inverse(FCCompliance comp)
{
  PetscFunctionBegin;
  PetscCall(Create(comp, PETSC_FALSE));
  PetscFunctionReturn(0);
}

PetscErrorCode FCComplianceCreate_Redundant(FCCompliance comp)
{
  PetscFunctionBegin;
  PetscCall(Create(comp, PETSC_TRUE));
  PetscFunctionReturn(0);
}
