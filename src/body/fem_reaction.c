/* FE body, the reactions of its constrained regions (docs/scenes.md): after the integration, the
   residual of the constrained rows at the end of the step, R_p = M_p a + B_p v + f_int,p - f_g,p
   (quasi-static: f_int,p - f_g,p), less the loads on its vertices (which their supports take),
   summed over each region, with its moment about the region's centroid; and the work that the
   prescribed motions and loads have done (the energy guard's). */
#include "femimpl.h"

/* The centroid of each constrained region now (cen: 4 per region, the last the weight): of its
   boundary faces' area, else of its vertices */
static PetscErrorCode RegionCentroids(FCBody body, PetscReal cen[])
{
  FEM    *fem = (FEM *)body->data;
  FCMesh *m   = &fem->mesh;

  PetscFunctionBegin;
  for (PetscInt k = 0; k < fem->ncons; k++) /* the regions' centroids: of their faces' area */
    for (PetscInt f = 0; f < fem->cons[k].nface; f++) {
      PetscInt *tv = &fem->cons[k].facev[3 * f];
      PetscReal e1[3], e2[3], an[3], A;
      for (int d = 0; d < 3; d++) {
        e1[d] = m->X[3 * tv[1] + d] - m->X[3 * tv[0] + d];
        e2[d] = m->X[3 * tv[2] + d] - m->X[3 * tv[0] + d];
      }
      FCCross(e1, e2, an);
      A = 0.5 * PetscSqrtReal(FCDot(an, an));
      for (int d = 0; d < 3; d++)
        for (int a = 0; a < 3; a++)
          cen[4 * k + d] += A / 3.0 * (m->X[3 * tv[a] + d] + FCFEMConstrainedU(fem, k, &m->X[3 * tv[a]], FC_BC_NOW, d));
      cen[4 * k + 3] += A;
    }
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, cen, 4 * fem->ncons, MPIU_REAL, MPIU_SUM, body->comm));
  for (PetscInt k = 0; k < fem->ncons; k++) { /* no faces: of the vertices */
    PetscReal c[4] = {0, 0, 0, 0};
    if (cen[4 * k + 3] > 0.0) continue;
    for (PetscInt v = 0; v < m->vEnd - m->vStart; v++) {
      if (fem->creg[v] != k || !m->owned[v]) continue;
      for (int d = 0; d < 3; d++) c[d] += m->X[3 * v + d] + FCFEMConstrainedU(fem, k, &m->X[3 * v], FC_BC_NOW, d);
      c[3] += 1.0;
    }
    PetscCall(MPIU_Allreduce(MPI_IN_PLACE, c, 4, MPIU_REAL, MPIU_SUM, body->comm));
    for (int d = 0; d < 4; d++) cen[4 * k + d] = c[d];
  }
  for (PetscInt k = 0; k < fem->ncons; k++)
    for (int d = 0; d < 3; d++) cen[4 * k + d] /= cen[4 * k + 3] > 0.0 ? cen[4 * k + 3] : 1.0;
  PetscFunctionReturn(0);
}

/* The loads on the constrained vertices, which their supports take (fcons: each rank its share),
   subtracted from the reactions R and their moments about the regions' centroids cen */
static void LoadsOnSupports(const FEM *fem, const PetscScalar *ul, const PetscReal cen[], PetscReal R[])
{
  const FCMesh *m = &fem->mesh;

  for (PetscInt v = 0; v < m->vEnd - m->vStart; v++) {
    PetscInt  k = fem->creg[v];
    PetscReal arm[3], r[3], mo[3];
    if (k < 0) continue;
    for (int d = 0; d < 3; d++) {
      r[d]   = -fem->fcons[3 * v + d];
      arm[d] = m->X[3 * v + d] + FCFEMLocalU(fem, v, ul, d) - cen[4 * k + d];
    }
    FCCross(arm, r, mo);
    for (int d = 0; d < 3; d++) {
      R[6 * k + d] += r[d];
      R[6 * k + 3 + d] += mo[d];
    }
  }
}

/* After the integration: the constraints move to their end-of-step displacement, and each one's
   reaction R_p = M_p a + B_p v + f_int,p - f_g,p (header) and its moment about the region's centroid */
PetscErrorCode FCFEMBCEndStep(FCBody body)
{
  FEM               *fem = (FEM *)body->data;
  FCMesh            *m   = &fem->mesh;
  PetscReal          h = body->h, cen[4 * FC_MAX_REGIONS] = {0}, R[6 * FC_MAX_REGIONS] = {0}, power = 0.0;
  const PetscScalar *ul, *vl, *dl;
  FCFEMConstraint    old[FC_MAX_REGIONS]; /* the poses of the step, before they move on */
  Vec                vloc, dvloc;

  PetscFunctionBegin;
  for (PetscInt k = 0; k < fem->ncons; k++) { /* the poses move on a step: now is the end of the step */
    FCFEMConstraint *c = &fem->cons[k];
    old[k]             = *c;
    for (int w = 0; w < 2; w++) {
      for (int i = 0; i < 3; i++) c->x[w][i] = c->x[w + 1][i];
      for (int i = 0; i < 9; i++) c->RR[w][i] = c->RR[w + 1][i];
    }
  }
  if (fem->nload) {
    PetscScalar w;
    PetscCall(VecDot(fem->fload, fem->v, &w));
    fem->extwork += PetscAbsReal(h * PetscRealPart(w));
  }
  if (!fem->ncons) PetscFunctionReturn(0);
  PetscCall(DMGetLocalVector(m->dm, &vloc));
  PetscCall(DMGetLocalVector(m->dm, &dvloc));
  PetscCall(DMGlobalToLocal(m->dm, fem->u, INSERT_VALUES, fem->uloc));
  PetscCall(DMGlobalToLocal(m->dm, fem->v, INSERT_VALUES, vloc));
  PetscCall(DMGlobalToLocal(m->dm, fem->dv, INSERT_VALUES, dvloc));
  PetscCall(VecGetArrayRead(fem->uloc, &ul));
  PetscCall(VecGetArrayRead(vloc, &vl));
  PetscCall(VecGetArrayRead(dvloc, &dl));
  PetscCall(RegionCentroids(body, cen));
  for (PetscInt i = 0; i < fem->nccell; i++) {
    PetscInt  c = fem->ccell[i];
    PetscReal X[12], x[12], fe[12], Ke[144], Me[144], ve[12], ae[12];
    FCFEMGatherElement(fem, c, ul, X, x);
    for (int a = 0; a < 4; a++) {
      PetscInt v = m->cellVerts[4 * c + a] - m->vStart, k = fem->creg[v];
      for (int d = 0; d < 3; d++) {
        if (k >= 0) { /* over the step, and its change from the step before */
          const PetscReal *Xv = &m->X[3 * v];
          ve[3 * a + d] =
              (FCFEMConstraintU(&old[k], Xv, FC_BC_END, d) - FCFEMConstraintU(&old[k], Xv, FC_BC_NOW, d)) / h;
          ae[3 * a + d] =
              (ve[3 * a + d] -
               (FCFEMConstraintU(&old[k], Xv, FC_BC_NOW, d) - FCFEMConstraintU(&old[k], Xv, FC_BC_BEFORE, d)) / h) /
              h;
        } else {
          ve[3 * a + d] = PetscRealPart(vl[fem->ldof[v] + d]);
          ae[3 * a + d] = PetscRealPart(dl[fem->ldof[v] + d]) / h;
        }
      }
    }
    PetscCall((*fem->mat->element)(fem->mat, x, X, &fem->Dminv[9 * c], fem->vol[c], fe, Ke));
    FCTetMass(body->density, fem->vol[c], fem->lumped, Me);
    for (int a = 0; a < 4; a++) {
      PetscInt  v = m->cellVerts[4 * c + a] - m->vStart, k = fem->creg[v];
      PetscReal r[3], arm[3], mo[3];
      if (k < 0) continue;
      for (int d = 0; d < 3; d++) {
        PetscInt row = 3 * a + d;
        r[d]         = fe[row] - body->density * fem->vol[c] / 4.0 * body->gravity[d];
        for (int j = 0; j < 12; j++)
          r[d] += body->quasistatic
                      ? 0.0
                      : Me[12 * row + j] * (ae[j] + fem->alpha * ve[j]) + fem->beta * Ke[12 * row + j] * ve[j];
        arm[d] = x[row] - cen[4 * k + d];
      }
      FCCross(arm, r, mo);
      for (int d = 0; d < 3; d++) {
        R[6 * k + d] += r[d];
        R[6 * k + 3 + d] += mo[d];
        power += r[d] * ve[3 * a + d];
      }
    }
  }
  if (fem->nload) LoadsOnSupports(fem, ul, cen, R);
  PetscCall(VecRestoreArrayRead(fem->uloc, &ul));
  PetscCall(VecRestoreArrayRead(vloc, &vl));
  PetscCall(VecRestoreArrayRead(dvloc, &dl));
  PetscCall(DMRestoreLocalVector(m->dm, &vloc));
  PetscCall(DMRestoreLocalVector(m->dm, &dvloc));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, R, 6 * fem->ncons, MPIU_REAL, MPIU_SUM, body->comm));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &power, 1, MPIU_REAL, MPIU_SUM, body->comm));
  fem->extwork += PetscAbsReal(h * power);
  for (PetscInt k = 0; k < fem->ncons; k++)
    for (int j = 0; j < 6; j++) fem->rval[6 * k + j] = R[6 * k + j];
  PetscFunctionReturn(0);
}

PetscErrorCode GetExternalWork_FEM(FCBody body, PetscReal *w)
{
  PetscFunctionBegin;
  *w = ((FEM *)body->data)->extwork;
  PetscFunctionReturn(0);
}

/* The constraints' regions and their reactions of the last step */
PetscErrorCode GetReactions_FEM(FCBody body, PetscInt *n, const char ***names, const PetscReal **values)
{
  FEM *fem = (FEM *)body->data;

  PetscFunctionBegin;
  for (PetscInt k = 0; k < fem->ncons; k++) fem->rname[k] = fem->cons[k].region;
  *n = fem->ncons;
  if (names) *names = fem->rname;
  if (values) *values = fem->rval;
  PetscFunctionReturn(0);
}
