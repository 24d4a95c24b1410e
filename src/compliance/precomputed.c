/* Compliance builder "precomputed": columns of C_0 = A_0^-1 restricted to the body's surface,
   computed once per surface vertex (the first time it is in contact) and reused; A_0 is A at the
   reference state. A co-rotational body warps them with its best-fit rotation R, which it hands
   over before each build (FCComplianceSetRotation):
       W_b = J R C_0 R^T J^T,   and the correction dv += h R A_0^-1 R^T J^T lambda,
   the same operator, so that W and the correction agree. */
#include "complianceimpl.h"

typedef struct {
  KSP        ksp0; /* co-rotational: factor of A_0 (reference state); linear: NULL (the body's) */
  Mat        A0;
  PetscInt   nsurf; /* non-fixed boundary vertices of the whole body */
  PetscInt  *surf;  /* their first global DOF, sorted (replicated)    */
  PetscInt  *slot;  /* per surface vertex: its cached columns, or -1   */
  PetscReal *cache; /* slot j: 3 nsurf x 3, column-major              */
  PetscInt   ncached, maxcached;
} Precomputed;

/* Factor of A_0: ksp0 (co-rotational) or the body's own (linear: A never changes) */
static KSP ReferenceSolver(FCCompliance comp)
{
  Precomputed *pc = (Precomputed *)comp->data;
  return pc->ksp0 ? pc->ksp0 : comp->ctx.ksp;
}

/* The surface (sorted first global DOFs of the non-fixed boundary vertices, on every rank) and,
   for a co-rotational body, a factor of A_0: at set-up, while A is still A at q = 0 */
static PetscErrorCode SetUp_Precomputed(FCCompliance comp)
{
  Precomputed *pre = (Precomputed *)comp->data;
  PetscMPIInt  size, n = (PetscMPIInt)comp->ctx.nsurface, *counts, *displs;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_size(comp->ctx.comm, &size));
  PetscCall(PetscMalloc2(size, &counts, size + 1, &displs));
  PetscCallMPI(MPI_Allgather(&n, 1, MPI_INT, counts, 1, MPI_INT, comp->ctx.comm));
  displs[0] = 0;
  for (PetscMPIInt r = 0; r < size; r++) displs[r + 1] = displs[r] + counts[r];
  pre->nsurf = displs[size];
  PetscCall(PetscMalloc2(pre->nsurf + 1, &pre->surf, pre->nsurf + 1, &pre->slot));
  PetscCallMPI(MPI_Allgatherv(comp->ctx.surface, n, MPIU_INT, pre->surf, counts, displs, MPIU_INT, comp->ctx.comm));
  PetscCall(PetscSortInt(pre->nsurf, pre->surf));
  for (PetscInt i = 0; i < pre->nsurf; i++) pre->slot[i] = -1;
  PetscCall(PetscFree2(counts, displs));
  comp->rotation = comp->ctx.linear ? PETSC_FALSE : PETSC_TRUE;
  if (!comp->ctx.linear) {
    PC pc;
    PetscCall(MatDuplicate(comp->ctx.A, MAT_COPY_VALUES, &pre->A0));
    PetscCall(KSPCreate(comp->ctx.comm, &pre->ksp0));
    PetscCall(KSPSetOptionsPrefix(pre->ksp0, comp->ctx.prefix));
    PetscCall(KSPSetType(pre->ksp0, KSPPREONLY));
    PetscCall(KSPGetPC(pre->ksp0, &pc));
    PetscCall(PCSetType(pc, PCCHOLESKY));
    PetscCall(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS));
    PetscCall(KSPSetFromOptions(pre->ksp0));
    PetscCall(KSPSetOperators(pre->ksp0, pre->A0, pre->A0));
    PetscCall(KSPSetUp(pre->ksp0));
  }
  PetscFunctionReturn(0);
}

/* The columns of C_0 = A_0^-1 of the nnew surface vertices newv (A_0^-1 [e_g e_g+1 e_g+2], by the reference
   factor), kept on the surface rows in the cache, the same on every rank */
static PetscErrorCode CacheColumns(FCCompliance comp, PetscInt nnew, const PetscInt newv[])
{
  Precomputed       *pre = (Precomputed *)comp->data;
  PetscInt           ns3 = 3 * pre->nsurf;
  KSP                ksp;
  PC                 pc;
  Mat                F, B, X;
  PetscInt           nloc, N, lo;
  PetscScalar       *b;
  const PetscScalar *x;
  PetscReal         *cols;

  PetscFunctionBegin;
  ksp = ReferenceSolver(comp);
  PetscCall(KSPGetPC(ksp, &pc));
  PetscCall(PCFactorGetMatrix(pc, &F));
  PetscCall(VecGetLocalSize(comp->ctx.u, &nloc));
  PetscCall(VecGetSize(comp->ctx.u, &N));
  PetscCall(VecGetOwnershipRange(comp->ctx.u, &lo, NULL));
  PetscCall(MatCreateDense(comp->ctx.comm, nloc, PETSC_DECIDE, N, 3 * nnew, NULL, &B));
  PetscCall(MatDenseGetArray(B, &b));
  PetscCall(PetscArrayzero(b, nloc * 3 * nnew));
  for (PetscInt j = 0; j < nnew; j++) {
    PetscInt g = pre->surf[newv[j]];
    if (g >= lo && g < lo + nloc)
      for (int d = 0; d < 3; d++) b[(g - lo + d) + nloc * (3 * j + d)] = 1.0;
  }
  PetscCall(MatDenseRestoreArray(B, &b));
  PetscCall(MatDuplicate(B, MAT_DO_NOT_COPY_VALUES, &X));
  PetscCall(MatMatSolve(F, B, X));
  if (pre->ncached + nnew > pre->maxcached) {
    PetscReal *grown;
    pre->maxcached = PetscMax(2 * pre->maxcached, pre->ncached + nnew);
    PetscCall(PetscMalloc1(9 * pre->nsurf * pre->maxcached, &grown));
    if (pre->ncached) PetscCall(PetscArraycpy(grown, pre->cache, 9 * pre->nsurf * pre->ncached));
    PetscCall(PetscFree(pre->cache));
    pre->cache = grown;
  }
  cols = &pre->cache[9 * pre->nsurf * pre->ncached];
  PetscCall(PetscArrayzero(cols, 9 * pre->nsurf * nnew));
  PetscCall(MatDenseGetArrayRead(X, &x));
  for (PetscInt sv = 0; sv < pre->nsurf; sv++) {
    PetscInt g = pre->surf[sv];
    if (g < lo || g >= lo + nloc) continue;
    for (PetscInt c = 0; c < 3 * nnew; c++)
      for (int d = 0; d < 3; d++) cols[(3 * sv + d) + ns3 * c] = PetscRealPart(x[(g - lo + d) + nloc * c]);
  }
  PetscCall(MatDenseRestoreArrayRead(X, &x));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, cols, 9 * pre->nsurf * nnew, MPIU_REAL, MPIU_SUM, comp->ctx.comm));
  for (PetscInt j = 0; j < nnew; j++) pre->slot[newv[j]] = pre->ncached + j;
  pre->ncached += nnew;
  PetscCall(MatDestroy(&B));
  PetscCall(MatDestroy(&X));
  PetscFunctionReturn(0);
}

/* W_b = Co^T G Co: G = C_0 on the surface vertices the contacts touch, gathered from the cache
   into a contiguous 3nu x 3nu block (column-major), then T = G Co and W_b = Co^T T with unit-stride
   inner loops (the cache itself is scattered over the slots) */
static PetscErrorCode Congruence(FCCompliance comp, const PetscInt si[], const PetscReal co[], PetscReal Wb[])
{
  Precomputed *pre   = (Precomputed *)comp->data;
  PetscInt     ncols = comp->ncols, ns3 = 3 * pre->nsurf;
  PetscInt    *u, *at, nu = 0, n3;
  PetscReal   *G, *T;

  PetscFunctionBegin;
  PetscCall(PetscMalloc2(3 * ncols + 1, &u, pre->nsurf + 1, &at));
  for (PetscInt k = 0; k < 3 * ncols; k++)
    if (si[k] >= 0) u[nu++] = si[k];
  PetscCall(PetscSortRemoveDupsInt(&nu, u));
  for (PetscInt a = 0; a < nu; a++) at[u[a]] = a;
  n3 = 3 * nu;
  PetscCall(PetscMalloc2(n3 * n3 + 1, &G, n3 * ncols + 1, &T));
  for (PetscInt b = 0; b < nu; b++)
    for (int e = 0; e < 3; e++) {
      const PetscReal *src = &pre->cache[9 * pre->nsurf * pre->slot[u[b]] + ns3 * e];
      PetscReal       *dst = &G[n3 * (3 * b + e)];
      for (PetscInt a = 0; a < nu; a++)
        for (int d = 0; d < 3; d++) dst[3 * a + d] = src[3 * u[a] + d];
    }
  PetscCall(PetscArrayzero(T, n3 * ncols));
  for (PetscInt j = 0; j < ncols; j++)
    for (int vb = 0; vb < 3; vb++) {
      if (si[3 * j + vb] < 0) continue;
      for (int e = 0; e < 3; e++) {
        const PetscReal c = co[9 * j + 3 * vb + e], *g = &G[n3 * (3 * at[si[3 * j + vb]] + e)];
        PetscReal      *t = &T[n3 * j];
        for (PetscInt r = 0; r < n3; r++) t[r] += c * g[r];
      }
    }
  for (PetscInt i = 0; i < ncols; i++)
    for (PetscInt j = 0; j < ncols; j++) {
      const PetscReal *t = &T[n3 * j];
      PetscReal        w = 0.0;
      for (int va = 0; va < 3; va++) {
        PetscInt a = si[3 * i + va];
        if (a < 0) continue;
        a = 3 * at[a];
        w += co[9 * i + 3 * va] * t[a] + co[9 * i + 3 * va + 1] * t[a + 1] + co[9 * i + 3 * va + 2] * t[a + 2];
      }
      Wb[i * ncols + j] = w;
    }
  PetscCall(PetscFree2(G, T));
  PetscCall(PetscFree2(u, at));
  PetscFunctionReturn(0);
}

static PetscErrorCode Build_Precomputed(FCCompliance comp, PetscInt self, const FCContactSet *set, PetscReal Wb[])
{
  Precomputed *pre   = (Precomputed *)comp->data;
  PetscInt     ncols = comp->ncols, *si, nnew = 0, *newv;
  PetscReal   *co, Rt[9];

  PetscFunctionBegin;
  FCMat3Transpose(comp->R, Rt);
  /* per column: up to 3 (surface vertex, coefficient 3-vector) */
  PetscCall(PetscMalloc3(3 * ncols, &si, 9 * ncols, &co, 3 * ncols, &newv));
  {
    PetscInt col = 0;
    for (PetscInt k = 0; k < set->n; k++)
      for (PetscInt s = 0; s < 2; s++) {
        const FCContact *c = &set->c[k];
        if (c->body[s] != self) continue;
        for (PetscInt a = 0; a < c->dim; a++, col++) {
          PetscReal e[3], er[3];
          FCComplianceDirection(c, s, a, e);
          FCMat3Vec(Rt, e, er);
          for (PetscInt vtx = 0; vtx < 3; vtx++) {
            PetscInt g = vtx < c->prox[s].nv ? c->prox[s].gdof[vtx] : -1, idx = -1;
            if (g >= 0) PetscCall(PetscFindInt(g, pre->nsurf, pre->surf, &idx));
            PetscCheck(g < 0 || idx >= 0, PETSC_COMM_SELF, PETSC_ERR_PLIB,
                       "Contact point of body '%s' is not on its surface", comp->ctx.name);
            si[3 * col + vtx] = idx;
            for (int d = 0; d < 3; d++) co[9 * col + 3 * vtx + d] = idx >= 0 ? c->prox[s].w[vtx] * er[d] : 0.0;
            if (idx >= 0 && pre->slot[idx] == -1) {
              pre->slot[idx] = -2; /* queued */
              newv[nnew++]   = idx;
            }
          }
        }
      }
  }
  if (nnew) PetscCall(CacheColumns(comp, nnew, newv));
  PetscCall(Congruence(comp, si, co, Wb));
  PetscCall(PetscFree3(si, co, newv));
  PetscFunctionReturn(0);
}

/* v = R v (or R^T v) on every vertex block of a global vector */
static PetscErrorCode RotateBlocks(FCCompliance comp, Vec v, PetscBool transpose)
{
  PetscScalar *a;
  PetscInt     n;

  PetscFunctionBegin;
  if (comp->ctx.linear) PetscFunctionReturn(0);
  PetscCall(VecGetLocalSize(v, &n));
  PetscCall(VecGetArray(v, &a));
  for (PetscInt i = 0; i < n; i += 3) {
    PetscReal x[3] = {PetscRealPart(a[i]), PetscRealPart(a[i + 1]), PetscRealPart(a[i + 2])}, y[3];
    if (transpose)
      FCMat3TVec(comp->R, x, y);
    else
      FCMat3Vec(comp->R, x, y);
    for (int d = 0; d < 3; d++) a[i + d] = y[d];
  }
  PetscCall(VecRestoreArray(v, &a));
  PetscFunctionReturn(0);
}

/* The correction's solve: x = R A_0^-1 R^T b */
static PetscErrorCode Solve_Precomputed(FCCompliance comp, Vec b, Vec x)
{
  PetscFunctionBegin;
  PetscCall(RotateBlocks(comp, b, PETSC_TRUE));
  PetscCall(KSPSolve(ReferenceSolver(comp), b, x));
  PetscCall(RotateBlocks(comp, x, PETSC_FALSE));
  PetscFunctionReturn(0);
}

static PetscErrorCode Destroy_Precomputed(FCCompliance comp)
{
  Precomputed *pre = (Precomputed *)comp->data;

  PetscFunctionBegin;
  PetscCall(KSPDestroy(&pre->ksp0));
  PetscCall(MatDestroy(&pre->A0));
  PetscCall(PetscFree2(pre->surf, pre->slot));
  PetscCall(PetscFree(pre->cache));
  PetscCall(PetscFree(comp->data));
  PetscFunctionReturn(0);
}

PetscErrorCode FCComplianceCreate_Precomputed(FCCompliance comp)
{
  Precomputed *pc;

  PetscFunctionBegin;
  PetscCall(PetscNew(&pc));
  comp->data        = pc;
  comp->ops.setup   = SetUp_Precomputed;
  comp->ops.build   = Build_Precomputed;
  comp->ops.solve   = Solve_Precomputed;
  comp->ops.destroy = Destroy_Precomputed;
  PetscFunctionReturn(0);
}
