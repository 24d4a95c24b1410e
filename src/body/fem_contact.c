/* FE body, contact geometry and response: its candidate contact points (owned boundary vertices)
   and surface triangles, the positions of proximity points, and the compliance builder
   (src/compliance/) that gives its part of W (eq. 17) and its correction (eq. 20). */
#include "femimpl.h"

/* Owned boundary vertices: positions at the start of the step and after the free motion
   x_free = X + u + h (v + dv_free) (+ delta, fem_rotation.c) */
PetscErrorCode ContactPoints_FEM(FCBody body, PetscInt *n, FCProximity **prox, PetscReal **x0, PetscReal **xf,
                                 PetscReal **key)
{
  FEM               *fem = (FEM *)body->data;
  FCMesh            *m   = &fem->mesh;
  const PetscScalar *u, *v, *dv, *sh = NULL;
  PetscInt           lo;

  PetscFunctionBegin;
  PetscCall(VecGetOwnershipRange(fem->u, &lo, NULL));
  PetscCall(VecGetArrayRead(fem->u, &u));
  PetscCall(VecGetArrayRead(fem->v, &v));
  PetscCall(VecGetArrayRead(fem->dv, &dv));
  if (fem->shifted) PetscCall(VecGetArrayRead(fem->shift, &sh));
  for (PetscInt i = 0; i < fem->nbv; i++) {
    PetscInt     vtx = fem->bv[i], g = fem->gdof[vtx];
    FCProximity *p = &fem->bprox[i];
    PetscCall(PetscMemzero(p, sizeof(*p)));
    p->nv      = 1;
    p->gdof[0] = g;
    p->w[0]    = 1.0;
    for (int d = 0; d < 3; d++) {
      PetscReal X          = m->X[3 * vtx + d];
      p->r[d]              = X;
      p->X[0][d]           = X;
      fem->bkey[3 * i + d] = X;
      fem->bx0[3 * i + d]  = X + FCFEMOwnedU(fem, vtx, u, lo, d);
      fem->bxf[3 * i + d]  = g < 0 ? X + FCFEMConstrainedU(fem, fem->creg[vtx], &m->X[3 * vtx], FC_BC_END, d)
                                   : fem->bx0[3 * i + d] + body->h * PetscRealPart(v[g - lo + d] + dv[g - lo + d]);
      if (sh && g >= 0) fem->bxf[3 * i + d] += PetscRealPart(sh[g - lo + d]);
    }
  }
  PetscCall(VecRestoreArrayRead(fem->u, &u));
  PetscCall(VecRestoreArrayRead(fem->v, &v));
  PetscCall(VecRestoreArrayRead(fem->dv, &dv));
  if (sh) PetscCall(VecRestoreArrayRead(fem->shift, &sh));
  *n    = fem->nbv;
  *prox = fem->bprox;
  *x0   = fem->bx0;
  *xf   = fem->bxf;
  *key  = fem->bkey;
  PetscFunctionReturn(0);
}

/* Boundary triangles held by this rank with their positions at the start of the step and
   after the free motion (ghost vertices included, through the local vectors; a shifted step's
   delta goes in as delta / h in the local dv) */
PetscErrorCode SurfaceTriangles_FEM(FCBody body, PetscInt *n, FCSurfaceTriangle **tri)
{
  FEM               *fem = (FEM *)body->data;
  FCMesh            *m   = &fem->mesh;
  const PetscScalar *u, *v, *dv;

  PetscFunctionBegin;
  PetscCall(DMGlobalToLocal(m->dm, fem->u, INSERT_VALUES, fem->uloc));
  PetscCall(DMGlobalToLocal(m->dm, fem->v, INSERT_VALUES, fem->vloc));
  if (fem->shifted) {
    PetscCall(VecWAXPY(fem->work, 1.0 / body->h, fem->shift, fem->dv));
    PetscCall(DMGlobalToLocal(m->dm, fem->work, INSERT_VALUES, fem->dvloc));
  } else
    PetscCall(DMGlobalToLocal(m->dm, fem->dv, INSERT_VALUES, fem->dvloc));
  PetscCall(VecGetArrayRead(fem->uloc, &u));
  PetscCall(VecGetArrayRead(fem->vloc, &v));
  PetscCall(VecGetArrayRead(fem->dvloc, &dv));
  for (PetscInt t = 0; t < fem->ntri; t++) {
    FCSurfaceTriangle *T = &fem->tri[t];
    for (int a = 0; a < 3; a++) {
      PetscInt vtx = fem->triv[3 * t + a], o = fem->ldof[vtx];
      T->gdof[a] = fem->gdof[vtx];
      for (int d = 0; d < 3; d++) {
        PetscReal X = m->X[3 * vtx + d], uu = FCFEMLocalU(fem, vtx, u, d);
        T->X[a][d]  = X;
        T->x0[a][d] = X + uu;
        T->xf[a][d] = fem->fixed[vtx] ? X + FCFEMConstrainedU(fem, fem->creg[vtx], &m->X[3 * vtx], FC_BC_END, d)
                                      : T->x0[a][d] + body->h * PetscRealPart(v[o + d] + dv[o + d]);
      }
    }
  }
  PetscCall(VecRestoreArrayRead(fem->uloc, &u));
  PetscCall(VecRestoreArrayRead(fem->vloc, &v));
  PetscCall(VecRestoreArrayRead(fem->dvloc, &dv));
  *n   = fem->ntri;
  *tri = fem->tri;
  PetscFunctionReturn(0);
}

/* x += sum of w_k x_k over the vertices of p: owned vertices at the current state X + u, or at
   the trial state X + u + h (v + dv) (+ delta, fem_rotation.c); fixed vertices (never moving, X kept in the proximity)
   are added by rank 0 only, so that a sum over the ranks counts every vertex once */
static PetscErrorCode AddVertexPositions(FCBody body, const FCProximity *p, PetscBool trial, PetscReal x[3])
{
  FEM               *fem = (FEM *)body->data;
  const PetscScalar *u, *X, *v = NULL, *dv = NULL, *sh = NULL;
  PetscInt           lo, hi;
  PetscMPIInt        rank;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_rank(body->comm, &rank));
  PetscCall(VecGetOwnershipRange(fem->u, &lo, &hi));
  PetscCall(VecGetArrayRead(fem->u, &u));
  PetscCall(VecGetArrayRead(fem->Xg, &X));
  if (trial) {
    PetscCall(VecGetArrayRead(fem->v, &v));
    PetscCall(VecGetArrayRead(fem->dv, &dv));
    if (fem->shifted) PetscCall(VecGetArrayRead(fem->shift, &sh));
  }
  for (PetscInt k = 0; k < p->nv; k++) {
    PetscInt g = p->gdof[k];
    if (g < 0) {
      if (!rank) /* a constrained vertex: at its displacement now, or at the end of the step */
        for (int d = 0; d < 3; d++)
          x[d] += p->w[k] * (p->X[k][d] + FCFEMConstrainedU(fem, FCFEMConstrainedOfDof(g), p->X[k],
                                                            trial ? FC_BC_END : FC_BC_NOW, d));
      continue;
    }
    if (g < lo || g >= hi) continue;
    for (int d = 0; d < 3; d++)
      x[d] += p->w[k] *
              PetscRealPart(X[g - lo + d] + u[g - lo + d] + (trial ? body->h * (v[g - lo + d] + dv[g - lo + d]) : 0.0) +
                            (sh ? sh[g - lo + d] : 0.0));
  }
  PetscCall(VecRestoreArrayRead(fem->u, &u));
  PetscCall(VecRestoreArrayRead(fem->Xg, &X));
  if (trial) {
    PetscCall(VecRestoreArrayRead(fem->v, &v));
    PetscCall(VecRestoreArrayRead(fem->dv, &dv));
    if (sh) PetscCall(VecRestoreArrayRead(fem->shift, &sh));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode PartialPosition_FEM(FCBody body, const FCProximity *p, PetscReal x[3])
{
  PetscFunctionBegin;
  PetscCall(AddVertexPositions(body, p, PETSC_FALSE, x));
  PetscFunctionReturn(0);
}

/* G(q) at the trial state of a recursive scheme */
PetscErrorCode TrialPosition_FEM(FCBody body, const FCProximity *p, PetscReal x[3])
{
  PetscFunctionBegin;
  PetscCall(AddVertexPositions(body, p, PETSC_TRUE, x));
  PetscFunctionReturn(0);
}

PetscErrorCode SaveFree_FEM(FCBody body)
{
  FEM *fem = (FEM *)body->data;
  PetscFunctionBegin;
  if (!fem->dvfree) PetscCall(VecDuplicate(fem->dv, &fem->dvfree));
  PetscCall(VecCopy(fem->dv, fem->dvfree));
  PetscFunctionReturn(0);
}

PetscErrorCode RestoreFree_FEM(FCBody body)
{
  FEM *fem = (FEM *)body->data;
  PetscFunctionBegin;
  PetscCall(VecCopy(fem->dvfree, fem->dv));
  PetscFunctionReturn(0);
}

/* Current position of a proximity point whose vertices this rank owns */
PetscErrorCode ProximityPosition_FEM(FCBody body, const FCProximity *p, PetscInt when, PetscReal x[3])
{
  FEM               *fem = (FEM *)body->data;
  const PetscScalar *u, *X;
  PetscInt           lo, hi;

  PetscFunctionBegin;
  PetscCheck(when == FC_AT_NOW, body->comm, PETSC_ERR_SUP,
             "FE proximity positions are evaluated at the current state only");
  PetscCall(VecGetOwnershipRange(fem->u, &lo, &hi));
  PetscCall(VecGetArrayRead(fem->u, &u));
  PetscCall(VecGetArrayRead(fem->Xg, &X));
  for (int d = 0; d < 3; d++) x[d] = 0.0;
  for (PetscInt k = 0; k < p->nv; k++) {
    PetscInt g = p->gdof[k];
    if (g < 0) { /* constrained vertex: at its prescribed displacement */
      for (int d = 0; d < 3; d++)
        x[d] += p->w[k] * (p->X[k][d] + FCFEMConstrainedU(fem, FCFEMConstrainedOfDof(g), p->X[k], FC_BC_NOW, d));
      continue;
    }
    PetscCheck(g >= lo && g < hi, PETSC_COMM_SELF, PETSC_ERR_PLIB, "Proximity vertex not owned by this rank");
    for (int d = 0; d < 3; d++) x[d] += p->w[k] * PetscRealPart(X[g - lo + d] + u[g - lo + d]);
  }
  PetscCall(VecRestoreArrayRead(fem->u, &u));
  PetscCall(VecRestoreArrayRead(fem->Xg, &X));
  PetscFunctionReturn(0);
}

/* A body named in a contact pair gets its compliance builder, set up while A is still A at the
   reference state (the precomputed builder keeps it) */
PetscErrorCode SetUpContact_FEM(FCBody body)
{
  FEM                *fem = (FEM *)body->data;
  FCComplianceContext ctx;

  PetscFunctionBegin;
  if (fem->comp) PetscFunctionReturn(0);
  ctx.comm     = body->comm;
  ctx.name     = body->name;
  ctx.prefix   = body->prefix;
  ctx.u        = fem->u;
  ctx.A        = fem->A;
  ctx.ksp      = fem->ksp;
  ctx.linear   = fem->mat->linear;
  ctx.nsurface = fem->nsurface;
  ctx.surface  = fem->surface;
  PetscCall(FCComplianceCreate(&ctx, &fem->comp));
  PetscCall(FCComplianceSetFromOptions(fem->comp));
  /* A is factored at its first use (the free motion of the first step), by the KSP or, for a
     builder that owns the factor (condensed), by the builder: the KSP then never factors */
  PetscCall(FCComplianceSetUp(fem->comp));
  PetscCall(FCFEMWarpSetUpContact(body)); /* reuse: the builder warps W_b and the correction */
  body->expects = FCComplianceUsesExpectedContacts(fem->comp);
  PetscFunctionReturn(0);
}

PetscErrorCode ExpectContacts_FEM(FCBody body, PetscInt self, const FCContactSet *set)
{
  FEM *fem = (FEM *)body->data;

  PetscFunctionBegin;
  PetscCall(FCComplianceExpectContacts(fem->comp, self, set));
  PetscFunctionReturn(0);
}

/* Best-fit rotation of the body now (shape matching: the polar factor of
   sum (x - c)(X - C)^T over the vertices) */
static PetscErrorCode BestFitRotation(FCBody body, PetscReal R[9])
{
  FEM               *fem   = (FEM *)body->data;
  FCMesh            *m     = &fem->mesh;
  PetscReal          s[16] = {0}, A[9]; /* sum X, sum x, count, sum x X^T */
  const PetscScalar *u;
  PetscInt           lo;

  PetscFunctionBegin;
  PetscCall(VecGetOwnershipRange(fem->u, &lo, NULL));
  PetscCall(VecGetArrayRead(fem->u, &u));
  for (PetscInt v = 0; v < m->vEnd - m->vStart; v++) {
    PetscReal X[3], x[3];
    if (!m->owned[v]) continue;
    for (int d = 0; d < 3; d++) {
      X[d] = m->X[3 * v + d];
      x[d] = X[d] + FCFEMOwnedU(fem, v, u, lo, d);
      s[d] += X[d];
      s[3 + d] += x[d];
    }
    s[6] += 1.0;
    for (int i = 0; i < 3; i++)
      for (int j = 0; j < 3; j++) s[7 + 3 * i + j] += x[i] * X[j];
  }
  PetscCall(VecRestoreArrayRead(fem->u, &u));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, s, 16, MPIU_REAL, MPIU_SUM, body->comm));
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) A[3 * i + j] = s[7 + 3 * i + j] - s[3 + i] * s[j] / s[6];
  FCMat3Polar(A, R);
  PetscFunctionReturn(0);
}

/* The builders that warp a reference compliance get the best-fit rotation of u at the start of the step */
static PetscErrorCode SetRotation(FCBody body)
{
  FEM *fem = (FEM *)body->data;

  PetscFunctionBegin;
  PetscCheck(fem->comp, body->comm, PETSC_ERR_PLIB, "Body '%s' has contacts but is in no contact pair", body->name);
  if (FCComplianceUsesRotation(fem->comp) && !fem->Rcurrent) {
    PetscReal R[9];
    PetscCall(BestFitRotation(body, R));
    PetscCall(FCComplianceSetRotation(fem->comp, R));
    fem->Rcurrent = PETSC_TRUE;
  }
  PetscFunctionReturn(0);
}

/* W_b = J_b A_b^-1 J_b^T for the next AddCompliance, and whether it is the last one */
PetscErrorCode BuildCompliance_FEM(FCBody body, PetscInt self, const FCContactSet *set, const FCRows *rows,
                                   PetscBool *same)
{
  FEM *fem = (FEM *)body->data;

  PetscFunctionBegin;
  PetscCall(SetRotation(body));
  PetscCall(FCComplianceBuild(fem->comp, self, set, rows, same));
  PetscFunctionReturn(0);
}

/* W += J_b A_b^-1 J_b^T (eq. 17; FCSchemeCompliance scales the sum by h^2), the W_b of BuildCompliance_FEM */
PetscErrorCode AddCompliance_FEM(FCBody body, PetscInt self, const FCContactSet *set, const FCRows *rows, PetscReal W[])
{
  FEM *fem = (FEM *)body->data;

  PetscFunctionBegin;
  PetscCall(FCComplianceAdd(fem->comp, self, set, rows, W));
  PetscFunctionReturn(0);
}

/* eq. 20: dv += h A_b^-1 J_b^T lambda, for the J_b of the last AddCompliance */
PetscErrorCode ApplyCorrection_FEM(FCBody body, PetscInt self, const FCContactSet *set, const PetscReal lambda[])
{
  FEM *fem = (FEM *)body->data;

  PetscFunctionBegin;
  if (!fem->comp) PetscFunctionReturn(0);
  if (fem->xcorr) { /* reuse: the correction alone, kept to check the warped factor at the next step */
    PetscCall(VecZeroEntries(fem->xcorr));
    PetscCall(FCComplianceCorrect(fem->comp, body->h, lambda, fem->xcorr));
    PetscCall(FCFEMScheduleKeepCorrection(body, fem->xcorr));
    PetscCall(VecAXPY(fem->dv, 1.0, fem->xcorr));
  } else
    PetscCall(FCComplianceCorrect(fem->comp, body->h, lambda, fem->dv));
  PetscFunctionReturn(0);
}
