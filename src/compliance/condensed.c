/* Compliance builder "condensed": W_b from the factorization of A that the step needs anyway.
   The builder owns the body's factor of A (FCComplianceFactorsA): it factors A with the body's
   contact DOFs S ordered last (schurfactor.c), which yields C = (A^-1)_SS = Sigma^-1 besides the
   factor that solves the free motion and the correction. Then

       W_b = J_S C J_S^T     (eq. 17, J_b restricted to its columns S)

   costs a few dense products on the host, and the factorization costs what a plain one costs
   (docs/benchmarks.md, "Compliance builders"). S is chosen before the contacts of the step are
   known:
     - at the first factorization of a run, S = the DOFs of the contacts a discrete proximity
       query at the start positions finds (the scene runs it at set-up, before the first free
       motion, and hands it over, Expect_Condensed), with the ring of margin of a miss if A is
       linear: a body that starts in contact is factored once in its first step;
     - at a factorization, S = the DOFs of the last step's contacts (and -compliance_condensed_ring
       rings of surface neighbours around them; one ring at least after a step that missed): an
       unchanged contact set reuses the analysis (ordering and symbolic factorization). S costs
       flops: the Schur factorization takes more than a plain one (docs/benchmarks.md), each ring
       of neighbours more;
     - a contact on a DOF outside S (the first contact of a body, a contact set that moved) is a
       miss: S grows by the new DOFs and a ring around them and A, unchanged, is factored again in
       the same step (counted; -info prints it);
     - after 3 factorizations without contacts, S is dropped.
   A linear body keeps its factor as long as its contacts stay inside S: W_b then costs the dense
   products only, and not even those while J_T (the contact DOFs, rows and weights) is the last
   build's: a body resting on a kinematic shape reuses its W_b (the "CondensedWb" event counts the
   builds that compute). Each rank keeps the rows of W_b that fall in its rows of W (all of them
   unless the scheme distributes W by block rows). Where C is on the host, the host forms W_b and
   sends each rank its rows; where C is distributed by columns (schurfactor.c), each rank forms the
   terms of its columns of C for every rank's rows, summed on that rank (one reduction per rank):
   no rank ever holds more than its rows.
   Options: -compliance_condensed_ring, -compliance_condensed_inverse and
   -compliance_condensed_distributed_size (where C = Sigma^-1 is formed and kept: spdinverse.c,
   schurfactor.c), -compliance_condensed_balance (the top levels of the ordering: schurorder.c) (help
   strings below; docs/options.md). */
#include "complianceimpl.h"

typedef struct {
  FCSchurFactor sf;
  PetscInt      ring;
  PetscInt      inverse; /* FCSPDInverseType */
  PetscInt      balance; /* -compliance_condensed_balance */
  PetscInt      distmin; /* -compliance_condensed_distributed_size */
  PetscBool    *surf;    /* host: per vertex block, a non-fixed boundary vertex */
  PetscInt      nT, *T;  /* host: the DOFs of the last build's contacts */
  PetscBool     built;   /* a build since the last factorization */
  PetscInt      idle;    /* factorizations in a row without a build */
  PetscInt      nmiss;
  PetscBool     missed; /* the last build missed: keep a ring of margin at the next factorization */
  /* what the last W_b (comp->Wb, every rank) was built from, reused while neither changed: the
     factor's count and J_T by columns (host) */
  PetscInt   wb_nfactor, *wb_cptr, *wb_crow;
  PetscReal *wb_cval;
  PetscInt   nreuse;
} Condensed;

static PetscLogEvent EV_PRODUCTS; /* "CondensedWb": W_b = J_T C J_T^T computed (not reused) */

static const char *const InverseTypes[] = {"host", "scalapack", "columns", "distributed",
                                           "auto"}; /* FCSPDInverseType's order */

static PetscErrorCode SetFromOptions_Condensed(FCCompliance comp, PetscOptionItems *PetscOptionsObject)
{
  Condensed *cd = (Condensed *)comp->data;

  PetscFunctionBegin;
  PetscCall(FCOptionsEList(PetscOptionsObject, "-compliance_condensed_inverse",
                           "Where Sigma^-1 is formed: rank 0 (LAPACK), every rank (ScaLAPACK) and gathered on "
                           "rank 0, the host's Cholesky factor and the ranks' blocks of columns of its inverse, "
                           "Sigma and its inverse distributed (MUMPS and ScaLAPACK, never gathered), or auto: "
                           "distributed from -compliance_condensed_distributed_size on several ranks, else rank 0",
                           InverseTypes, 5, &cd->inverse, NULL));
  PetscCall(
      FCOptionsIntRange(PetscOptionsObject, "-compliance_condensed_distributed_size",
                        "Schur block size (DOFs) from which -compliance_condensed_inverse auto keeps Sigma and its "
                        "inverse distributed",
                        0, PETSC_MAX_INT, &cd->distmin, NULL));
  PetscCall(FCOptionsInt(PetscOptionsObject, "-compliance_condensed_ring",
                         "Rings of surface neighbours around contact DOFs in the Schur block", &cd->ring, NULL));
  PetscCheck(cd->ring >= 0, comp->ctx.comm, PETSC_ERR_USER_INPUT,
             "Option -compliance_condensed_ring must be >= 0, got %" PetscInt_FMT, cd->ring);
  PetscCall(FCOptionsIntRange(PetscOptionsObject, "-compliance_condensed_balance",
                              "Top levels of the nested dissection balanced in the vertices next to the Schur block", 0,
                              8, &cd->balance, NULL));
  PetscFunctionReturn(0);
}

/* Host: the surface flags of the vertex blocks, from every rank's owned boundary DOFs */
static PetscErrorCode SetUp_Condensed(FCCompliance comp)
{
  Condensed      *cd = (Condensed *)comp->data;
  PetscMPIInt     size, rank, n = (PetscMPIInt)comp->ctx.nsurface, *counts = NULL, *displs = NULL;
  PetscInt       *all = NULL, nb;
  const PetscInt *xadj, *adj;

  PetscBool mumps;

  PetscFunctionBegin;
  PetscCall(FCComplianceBodySolverIsMumps(comp, &mumps));
  PetscCheck(mumps, comp->ctx.comm, PETSC_ERR_USER_INPUT,
             "-compliance_type condensed factors A of body '%s' itself (MUMPS Cholesky), but the options of its solver "
             "(-%sksp_type, -%spc_type, -%spc_factor_mat_solver_type) ask for another one: drop them, or use "
             "-compliance_type dense",
             comp->ctx.name, comp->ctx.prefix, comp->ctx.prefix, comp->ctx.prefix);
  PetscCallMPI(MPI_Comm_size(comp->ctx.comm, &size));
  PetscCallMPI(MPI_Comm_rank(comp->ctx.comm, &rank));
  if (!EV_PRODUCTS) PetscCall(PetscLogEventRegister("CondensedWb", FC_CLASSID, &EV_PRODUCTS));
  PetscCall(FCSchurFactorCreate(comp->ctx.A, comp->ctx.name, (FCSPDInverseType)cd->inverse, cd->balance, cd->distmin,
                                &cd->sf));
  if (!rank) PetscCall(PetscMalloc2(size, &counts, size + 1, &displs));
  PetscCallMPI(MPI_Gather(&n, 1, MPI_INT, counts, 1, MPI_INT, 0, comp->ctx.comm));
  if (!rank) {
    displs[0] = 0;
    for (PetscMPIInt r = 0; r < size; r++) displs[r + 1] = displs[r] + counts[r];
    PetscCall(PetscMalloc1(displs[size] + 1, &all));
  }
  PetscCallMPI(MPI_Gatherv(comp->ctx.surface, n, MPIU_INT, all, counts, displs, MPIU_INT, 0, comp->ctx.comm));
  if (!rank) {
    PetscCall(FCSchurFactorGetGraph(cd->sf, &nb, &xadj, &adj));
    PetscCall(PetscCalloc1(nb + 1, &cd->surf));
    for (PetscMPIInt i = 0; i < displs[size]; i++) cd->surf[all[i] / 3] = PETSC_TRUE;
    PetscCall(PetscFree(all));
    PetscCall(PetscFree2(counts, displs));
  }
  PetscFunctionReturn(0);
}

/* Host: *S = sorted union of S0 and T, T grown by `rings` rings of surface neighbours */
static PetscErrorCode Grow(Condensed *cd, PetscInt nS0, const PetscInt S0[], PetscInt nT, const PetscInt T[],
                           PetscInt rings, PetscInt *nS, PetscInt **S)
{
  PetscInt        nb, *front, nfront = 0, n = 0;
  PetscBool      *mark;
  const PetscInt *xadj, *adj;

  PetscFunctionBegin;
  PetscCall(FCSchurFactorGetGraph(cd->sf, &nb, &xadj, &adj));
  PetscCall(PetscCalloc1(nb + 1, &mark));
  PetscCall(PetscMalloc1(nb + 1, &front));
  for (PetscInt i = 0; i < nS0; i++) mark[S0[i] / 3] = PETSC_TRUE;
  for (PetscInt i = 0; i < nT; i++)
    if (i == 0 || T[i] / 3 != T[i - 1] / 3) front[nfront++] = T[i] / 3; /* T sorted */
  for (PetscInt i = 0; i < nfront; i++) mark[front[i]] = PETSC_TRUE;
  for (PetscInt r = 0; r < rings; r++) { /* breadth-first, over surface blocks only */
    PetscInt nnext = 0, *next;
    PetscCall(PetscMalloc1(nb + 1, &next));
    for (PetscInt i = 0; i < nfront; i++)
      for (PetscInt k = xadj[front[i]]; k < xadj[front[i] + 1]; k++)
        if (!mark[adj[k]] && cd->surf[adj[k]]) {
          mark[adj[k]]  = PETSC_TRUE;
          next[nnext++] = adj[k];
        }
    PetscCall(PetscFree(front));
    front  = next;
    nfront = nnext;
  }
  for (PetscInt b = 0; b < nb; b++) n += mark[b] ? 3 : 0;
  PetscCall(PetscMalloc1(n + 1, S));
  n = 0;
  for (PetscInt b = 0; b < nb; b++)
    if (mark[b])
      for (int d = 0; d < 3; d++) (*S)[n++] = 3 * b + d;
  *nS = n;
  PetscCall(PetscFree(front));
  PetscCall(PetscFree(mark));
  PetscFunctionReturn(0);
}

/* A changed (the body refactors): choose S from the last step's contacts, then factor */
static PetscErrorCode Factor_Condensed(FCCompliance comp)
{
  Condensed  *cd = (Condensed *)comp->data;
  PetscMPIInt rank;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_rank(comp->ctx.comm, &rank));
  if (!rank) {
    PetscInt        ns, nw, *want = NULL;
    const PetscInt *S;
    PetscCall(FCSchurFactorGetInverse(cd->sf, &ns, &S, NULL));
    if (cd->built) {
      cd->idle = 0;
      PetscCall(Grow(cd, 0, NULL, cd->nT, cd->T, cd->missed ? PetscMax(cd->ring, 1) : cd->ring, &nw, &want));
      PetscCall(FCSchurFactorSetSchur(cd->sf, nw, want)); /* the same set keeps the analysis */
    } else if (++cd->idle >= 3)
      PetscCall(FCSchurFactorSetSchur(cd->sf, 0, NULL));
    else
      PetscCall(FCSchurFactorSetSchur(cd->sf, ns, S));
    PetscCall(PetscFree(want));
  } else
    PetscCall(FCSchurFactorSetSchur(cd->sf, 0, NULL)); /* collective; the host's set counts */
  cd->built  = PETSC_FALSE;
  cd->missed = PETSC_FALSE;
  PetscCall(FCSchurFactorFactor(cd->sf, comp->ctx.A));
  PetscFunctionReturn(0);
}

/* Keeps, on the host, what W_b was built from: J_T by columns (taken) and the factor's count (T is
   cd->T); elsewhere cptr, crow, cval are NULL */
static PetscErrorCode KeepWb(Condensed *cd, PetscInt *cptr, PetscInt *crow, PetscReal *cval)
{
  PetscFunctionBegin;
  PetscCall(PetscFree(cd->wb_cptr));
  PetscCall(PetscFree(cd->wb_crow));
  PetscCall(PetscFree(cd->wb_cval));
  cd->wb_cptr = cptr;
  cd->wb_crow = crow;
  cd->wb_cval = cval;
  if (cptr) PetscCall(FCSchurFactorGetCounts(cd->sf, NULL, &cd->wb_nfactor)); /* the host */
  PetscFunctionReturn(0);
}

/* An MPI count of n values (W_b's rows can pass 2^31 entries before memory does on a large machine) */
static PetscErrorCode Count(MPI_Comm comm, PetscInt64 n, PetscMPIInt *c)
{
  PetscFunctionBegin;
  PetscCheck(n <= PETSC_MPI_INT_MAX, comm, PETSC_ERR_SUP,
             "The condensed builder's W_b has %" PetscInt64_FMT " entries to move in one message, more than MPI counts",
             n);
  *c = (PetscMPIInt)n;
  PetscFunctionReturn(0);
}

/* This rank's rows [wa0, wa1) of W_b = J_T C_TT J_T^T, C_TT the block of C on the contact DOFs T
   within S, from J_T by columns (the host's cptr, crow, cval): formed on the host and sent by rows
   (C on the host), or by every rank from its columns of C and summed on each rank for its rows
   (C distributed) */
static PetscErrorCode Products(FCCompliance comp, const PetscInt hcptr[], const PetscInt hcrow[],
                               const PetscReal hcval[], PetscReal Wb[])
{
  Condensed       *cd    = (Condensed *)comp->data;
  PetscInt         ncols = comp->ncols, ns, nb, nloc, nT = cd->nT, *pos = NULL, *win, *lcol, maxrows = 0;
  PetscInt        *cptr = (PetscInt *)hcptr, *crow = (PetscInt *)hcrow;
  PetscReal       *cval = (PetscReal *)hcval, *buf = NULL;
  const PetscInt  *S;
  const PetscReal *C;
  PetscBool        dist, whole = PETSC_TRUE;
  PetscMPIInt      rank, size;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_rank(comp->ctx.comm, &rank));
  PetscCallMPI(MPI_Comm_size(comp->ctx.comm, &size));
  PetscCall(PetscMalloc1(2 * size, &win)); /* every rank's rows of W_b */
  {
    PetscInt mine[2] = {comp->wa0, comp->wa1};
    PetscCallMPI(MPI_Allgather(mine, 2, MPIU_INT, win, 2, MPIU_INT, comp->ctx.comm));
  }
  for (PetscMPIInt r = 0; r < size; r++) {
    whole   = (PetscBool)(whole && win[2 * r] == 0 && win[2 * r + 1] == ncols);
    maxrows = PetscMax(maxrows, win[2 * r + 1] - win[2 * r]);
  }
  PetscCall(FCSchurFactorGetLocalInverse(cd->sf, &dist, &ns, &S, &nb, &nloc, &C));
  if (!rank) { /* T within S */
    const PetscInt *Sh;
    PetscCall(FCSchurFactorGetInverse(cd->sf, &ns, &Sh, dist ? NULL : &C));
    PetscCall(PetscMalloc1(nT + 1, &pos));
    for (PetscInt i = 0; i < nT; i++) PetscCall(PetscFindInt(cd->T[i], ns, Sh, &pos[i]));
  }
  if (!dist) {
    PetscReal   *full = Wb;
    PetscMPIInt *cnt = NULL, *dsp = NULL;
    if (!rank) {
      if (!whole) PetscCall(PetscMalloc1(ncols * ncols, &full));
      PetscCall(PetscArrayzero(full, ncols * ncols)); /* it may hold the last W_b */
      PetscCall(FCComplianceAddCongruence(ncols, 0, ncols, nT, cptr, crow, cval, pos, NULL, ns, C, full));
    }
    if (whole) {
      PetscMPIInt n = 0;
      PetscCall(Count(comp->ctx.comm, (PetscInt64)ncols * ncols, &n));
      PetscCallMPI(MPI_Bcast(Wb, n, MPIU_REAL, 0, comp->ctx.comm));
    } else {
      PetscCall(PetscMalloc2(size, &cnt, size, &dsp));
      for (PetscMPIInt r = 0; r < size; r++) {
        PetscCall(Count(comp->ctx.comm, (PetscInt64)(win[2 * r + 1] - win[2 * r]) * ncols, &cnt[r]));
        PetscCall(Count(comp->ctx.comm, (PetscInt64)win[2 * r] * ncols, &dsp[r]));
      }
      PetscCallMPI(MPI_Scatterv(full, cnt, dsp, MPIU_REAL, Wb, cnt[rank], MPIU_REAL, 0, comp->ctx.comm));
      PetscCall(PetscFree2(cnt, dsp));
      if (!rank) PetscCall(PetscFree(full));
    }
    PetscCall(PetscFree(pos));
    PetscCall(PetscFree(win));
    PetscFunctionReturn(0);
  }
  /* C by columns: J_T and T within S to every rank */
  PetscCallMPI(MPI_Bcast(&nT, 1, MPIU_INT, 0, comp->ctx.comm));
  if (rank) PetscCall(PetscMalloc1(nT + 1, &cptr));
  PetscCallMPI(MPI_Bcast(cptr, (PetscMPIInt)(nT + 1), MPIU_INT, 0, comp->ctx.comm));
  if (rank) PetscCall(PetscMalloc3(cptr[nT] + 1, &crow, cptr[nT] + 1, &cval, nT + 1, &pos));
  PetscCallMPI(MPI_Bcast(crow, (PetscMPIInt)cptr[nT], MPIU_INT, 0, comp->ctx.comm));
  PetscCallMPI(MPI_Bcast(cval, (PetscMPIInt)cptr[nT], MPIU_REAL, 0, comp->ctx.comm));
  PetscCallMPI(MPI_Bcast(pos, (PetscMPIInt)nT, MPIU_INT, 0, comp->ctx.comm));
  PetscCall(PetscMalloc1(ns + 1, &lcol)); /* the local column of each column of C, or -1 */
  for (PetscInt j = 0; j < ns; j++) lcol[j] = -1;
  for (PetscInt jl = 0; jl < nloc; jl++) lcol[FCSPDGlobalColumn(jl, nb, rank, size)] = jl;
  if (whole) {
    PetscCall(PetscArrayzero(Wb, ncols * ncols));
    PetscCall(FCComplianceAddCongruence(ncols, 0, ncols, nT, cptr, crow, cval, pos, lcol, ns, C, Wb));
    PetscMPIInt n = 0;
    PetscCall(Count(comp->ctx.comm, (PetscInt64)ncols * ncols, &n));
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, Wb, n, MPIU_REAL, MPIU_SUM, comp->ctx.comm));
  } else { /* rank q's rows: every rank's terms, summed on q, a panel of rows at a time (a scratch of
              1/16 of the largest rank's rows, and the reduction's own buffer as small) */
    PetscInt panel = PetscMax(1, (maxrows + 15) / 16);
    PetscCall(PetscMalloc1(panel * ncols + 1, &buf));
    for (PetscMPIInt q = 0; q < size; q++)
      for (PetscInt p0 = win[2 * q]; p0 < win[2 * q + 1]; p0 += panel) {
        PetscInt    p1  = PetscMin(win[2 * q + 1], p0 + panel);
        PetscReal  *out = q == rank ? Wb + (p0 - win[2 * q]) * ncols : buf;
        PetscMPIInt n   = 0;
        PetscCall(Count(comp->ctx.comm, (PetscInt64)(p1 - p0) * ncols, &n));
        PetscCall(PetscArrayzero(out, (p1 - p0) * ncols));
        PetscCall(FCComplianceAddCongruence(ncols, p0, p1, nT, cptr, crow, cval, pos, lcol, ns, C, out));
        PetscCallMPI(MPI_Reduce(q == rank ? MPI_IN_PLACE : buf, out, n, MPIU_REAL, MPIU_SUM, q, comp->ctx.comm));
      }
    PetscCall(PetscFree(buf));
  }
  if (rank) PetscCall(PetscFree3(crow, cval, pos));
  if (rank)
    PetscCall(PetscFree(cptr));
  else
    PetscCall(PetscFree(pos));
  PetscCall(PetscFree(lcol));
  PetscCall(PetscFree(win));
  PetscFunctionReturn(0);
}

/* W_b = J_S C J_S^T (this rank's rows: Products); a contact DOF outside S first grows S and refactors.
   A build with the factor and J_T of the last one (a linear body whose contacts keep their DOFs
   and weights, as on a kinematic plane) reuses the last W_b: no products, no broadcast. */
static PetscErrorCode Build_Condensed(FCCompliance comp, PetscInt self, const FCContactSet *set, PetscReal Wb[])
{
  Condensed  *cd   = (Condensed *)comp->data;
  PetscInt   *cptr = NULL, *crow = NULL;
  PetscReal  *cval = NULL;
  PetscMPIInt rank;
  PetscBool   flag[2] = {PETSC_FALSE, PETSC_FALSE}; /* a contact DOF outside S; the last W_b still holds */
  PetscBool   valid   = comp->wb_valid;             /* on every rank: its rows may have moved */

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_rank(comp->ctx.comm, &rank));
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &valid, 1, MPIU_BOOL, MPI_LAND, comp->ctx.comm));
  if (!rank) { /* T: the DOFs the contacts touch, and J_T by columns (every rank holds every entry of J_b) */
    PetscInt        ns, nT, *T, nf;
    const PetscInt *S;
    PetscCall(FCComplianceContactDofs(comp, &nT, &T, &cptr, &crow, &cval));
    PetscCall(FCSchurFactorGetInverse(cd->sf, &ns, &S, NULL));
    for (PetscInt i = 0, at; i < nT && !flag[0]; i++) {
      PetscCall(PetscFindInt(T[i], ns, S, &at));
      flag[0] = (PetscBool)(at < 0);
    }
    /* the same factor and the same J_T as the last build (whose T is still cd->T): the same W_b */
    PetscCall(FCSchurFactorGetCounts(cd->sf, NULL, &nf));
    flag[1] = (PetscBool)(!flag[0] && valid && cd->wb_cptr && nf == cd->wb_nfactor && nT == cd->nT);
    if (flag[1]) PetscCall(PetscArraycmp(T, cd->T, nT, &flag[1]));
    if (flag[1]) PetscCall(PetscArraycmp(cptr, cd->wb_cptr, nT + 1, &flag[1]));
    if (flag[1]) PetscCall(PetscArraycmp(crow, cd->wb_crow, cptr[nT], &flag[1]));
    if (flag[1]) PetscCall(PetscArraycmp(cval, cd->wb_cval, cptr[nT], &flag[1]));
    PetscCall(PetscFree(cd->T));
    cd->nT = nT;
    cd->T  = T;
  }
  PetscCallMPI(MPI_Bcast(flag, 2, MPIU_BOOL, 0, comp->ctx.comm));
  if (flag[1]) { /* Wb holds it (comp->keepswb) */
    comp->kept = PETSC_TRUE;
    PetscCall(PetscFree(cptr));
    PetscCall(PetscFree(crow));
    PetscCall(PetscFree(cval));
    cd->built = PETSC_TRUE;
    cd->nreuse++;
    PetscFunctionReturn(0);
  }
  if (flag[0]) { /* A is the matrix of the current factor: factor it again with the larger S */
    if (!rank) { /* S, the new DOFs and a ring around them */
      PetscInt        ns, nw, *want, nnew = 0, *fresh;
      const PetscInt *S;
      PetscCall(FCSchurFactorGetInverse(cd->sf, &ns, &S, NULL));
      PetscCall(PetscMalloc1(cd->nT + 1, &fresh));
      for (PetscInt i = 0, at; i < cd->nT; i++) {
        PetscCall(PetscFindInt(cd->T[i], ns, S, &at));
        if (at < 0) fresh[nnew++] = cd->T[i];
      }
      PetscCall(Grow(cd, ns, S, nnew, fresh, PetscMax(cd->ring, 1), &nw, &want));
      PetscCall(PetscFree(fresh));
      PetscCall(FCSchurFactorSetSchur(cd->sf, nw, want));
      PetscCall(PetscFree(want));
    } else
      PetscCall(FCSchurFactorSetSchur(cd->sf, 0, NULL));
    PetscCall(PetscInfo(NULL, "condensed builder of body %s: contact DOFs outside the Schur block, refactoring\n",
                        comp->ctx.name));
    PetscCall(FCSchurFactorFactor(cd->sf, comp->ctx.A));
    cd->nmiss++;
    comp->nownfactor++;
    cd->missed = PETSC_TRUE;
  }
  cd->built = PETSC_TRUE;
  PetscCall(PetscLogEventBegin(EV_PRODUCTS, 0, 0, 0, 0));
  PetscCall(Products(comp, cptr, crow, cval, Wb));
  PetscCall(PetscLogEventEnd(EV_PRODUCTS, 0, 0, 0, 0));
  PetscCall(KeepWb(cd, cptr, crow, cval)); /* takes cptr, crow, cval (the host's) */
  PetscFunctionReturn(0);
}

/* The contacts a start-of-run proximity query expects (before the first factorization): taken as
   the last build's (with the ring of margin of a miss if A is linear), so that the first
   factorization has them in S instead of a plain factorization followed by a miss and a second */
static PetscErrorCode Expect_Condensed(FCCompliance comp)
{
  Condensed  *cd = (Condensed *)comp->data;
  PetscMPIInt rank;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_rank(comp->ctx.comm, &rank));
  if (!rank) {
    PetscInt  *cptr, *crow;
    PetscReal *cval;
    PetscCall(PetscFree(cd->T));
    PetscCall(FCComplianceContactDofs(comp, &cd->nT, &cd->T, &cptr, &crow, &cval));
    PetscCall(PetscFree(cptr));
    PetscCall(PetscFree(crow));
    PetscCall(PetscFree(cval));
    cd->built = (PetscBool)(cd->nT > 0);
    /* the ring of margin only where the factor lasts (a linear A): a body that refactors every step
       chooses S again from its first step's contacts, so a ring would only widen the first Schur
       block and cost a second analysis in step 2 */
    cd->missed = (PetscBool)(cd->built && comp->ctx.linear);
  }
  PetscFunctionReturn(0);
}

static PetscErrorCode Solve_Condensed(FCCompliance comp, Vec b, Vec x)
{
  Condensed *cd = (Condensed *)comp->data;

  PetscFunctionBegin;
  PetscCall(FCSchurFactorSolve(cd->sf, b, x));
  PetscFunctionReturn(0);
}

static PetscErrorCode Memory_Condensed(FCCompliance comp, PetscReal *sigma, PetscReal *factor, PetscReal *factormax)
{
  Condensed *cd = (Condensed *)comp->data;

  PetscFunctionBegin;
  PetscCall(FCSchurFactorGetMemory(cd->sf, sigma, factor, factormax));
  PetscFunctionReturn(0);
}

static PetscErrorCode Destroy_Condensed(FCCompliance comp)
{
  Condensed *cd = (Condensed *)comp->data;

  PetscFunctionBegin;
  if (cd->sf) {
    PetscInt na, nf;
    PetscCall(FCSchurFactorGetCounts(cd->sf, &na, &nf));
    PetscCall(PetscInfo(NULL,
                        "condensed builder of body %s: %" PetscInt_FMT " analyses, %" PetscInt_FMT
                        " factorizations, %" PetscInt_FMT " misses, %" PetscInt_FMT " W_b reused\n",
                        comp->ctx.name, na, nf, cd->nmiss, cd->nreuse));
  }
  PetscCall(FCSchurFactorDestroy(&cd->sf));
  PetscCall(PetscFree(cd->wb_cptr));
  PetscCall(PetscFree(cd->wb_crow));
  PetscCall(PetscFree(cd->wb_cval));
  PetscCall(PetscFree(cd->surf));
  PetscCall(PetscFree(cd->T));
  PetscCall(PetscFree(comp->data));
  PetscFunctionReturn(0);
}

PetscErrorCode FCComplianceCreate_Condensed(FCCompliance comp)
{
  Condensed *cd;

  PetscFunctionBegin;
  PetscCall(PetscNew(&cd));
  cd->inverse              = FC_SPD_INVERSE_AUTO; /* docs/options.md */
  cd->distmin              = 3000;
  comp->data               = cd;
  comp->factors            = PETSC_TRUE;
  comp->keepswb            = PETSC_TRUE; /* Build_Condensed keeps W_b while it holds */
  comp->windows            = PETSC_TRUE; /* and forms only this rank's rows */
  comp->ops.memory         = Memory_Condensed;
  comp->ops.setfromoptions = SetFromOptions_Condensed;
  comp->ops.setup          = SetUp_Condensed;
  comp->ops.factor         = Factor_Condensed;
  comp->ops.build          = Build_Condensed;
  comp->ops.solve          = Solve_Condensed;
  comp->ops.expect         = Expect_Condensed;
  comp->ops.destroy        = Destroy_Condensed;
  PetscFunctionReturn(0);
}
