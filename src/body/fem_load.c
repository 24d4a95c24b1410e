/* FE body, loads on regions (docs/scenes.md): -<name>_force (a total force spread by area, volume or
   count), -<name>_traction (force per area, fixed direction) and -<name>_pressure (along each face's
   outward normal at the start of the step), each a table of time per region (src/util/table.c),
   evaluated at the end of the step (backward Euler) into the global vector fload. */
#include "femimpl.h"

/* The loads of one option (kind), their faces and per-vertex weights */
static PetscErrorCode SetUpLoads(FCBody body, FCLoadKind kind, const char option[], const char spec[])
{
  FEM     *fem = (FEM *)body->data;
  FCMesh  *m   = &fem->mesh;
  PetscInt nv = m->vEnd - m->vStart, nc = m->cEnd - m->cStart, n;
  char     reg[FC_MAX_REGIONS][256], *tab[FC_MAX_REGIONS], what[FC_MAX_NAME + 300], opt[FC_MAX_NAME + 32];

  PetscFunctionBegin;
  if (!spec || !spec[0]) PetscFunctionReturn(0);
  PetscCall(FCFEMSplitPairs(body, option, spec, &n, reg, tab));
  PetscCall(PetscSNPrintf(opt, sizeof(opt), "-%s%s", body->prefix, option));
  for (PetscInt i = 0; i < n; i++) {
    FCFEMLoad *L = &fem->load[fem->nload];
    PetscBool *vmark, *cmark;
    PetscReal  area = 0.0, tot[3] = {0, 0, 0}; /* faces' area, cells' volume, vertex count */
    PetscCheck(fem->nload < FC_MAX_REGIONS, body->comm, PETSC_ERR_USER_INPUT, "Body '%s': more than %d loads",
               body->name, FC_MAX_REGIONS);
    PetscCall(PetscStrncpy(L->region, reg[i], sizeof(L->region)));
    L->kind = kind;
    PetscCall(PetscSNPrintf(what, sizeof(what), "option %s, region %s", opt, reg[i]));
    PetscCall(FCTableCreate(body->comm, tab[i], kind == FC_LOAD_PRESSURE ? 1 : 3, kind == FC_LOAD_PRESSURE ? 1 : 3,
                            what, &L->table));
    PetscCall(PetscCalloc2(nv + 1, &vmark, nc + 1, &cmark));
    PetscCall(PetscCalloc1(nv + 1, &L->weight));
    PetscCall(FCMeshRegion(m, reg[i], opt, body->name, vmark, &L->nface, &L->facev, cmark));
    for (PetscInt f = 0; f < L->nface; f++) {
      PetscReal e1[3], e2[3], nn[3];
      PetscInt *t = &L->facev[3 * f];
      for (int d = 0; d < 3; d++) {
        e1[d] = m->X[3 * t[1] + d] - m->X[3 * t[0] + d];
        e2[d] = m->X[3 * t[2] + d] - m->X[3 * t[0] + d];
      }
      FCCross(e1, e2, nn);
      area += 0.5 * PetscSqrtReal(FCDot(nn, nn));
      for (int a = 0; a < 3; a++) L->weight[t[a]] += PetscSqrtReal(FCDot(nn, nn)) / 6.0;
    }
    tot[0] = area;
    PetscCall(MPIU_Allreduce(MPI_IN_PLACE, tot, 1, MPIU_REAL, MPIU_SUM, body->comm));
    PetscCheck(kind == FC_LOAD_FORCE || tot[0] > 0.0, body->comm, PETSC_ERR_USER_INPUT,
               "Option %s: region '%s' of body '%s' has no boundary face (a surface region is needed)", opt, reg[i],
               body->name);
    if (kind == FC_LOAD_FORCE) { /* by area on a surface, else by mass on cells, else by count */
      if (tot[0] <= 0.0) {
        for (PetscInt c = 0; c < nc; c++)
          if (cmark[c])
            for (int a = 0; a < 4; a++) L->weight[m->cellVerts[4 * c + a] - m->vStart] += fem->vol[c] / 4.0;
        for (PetscInt v = 0; v < nv; v++) tot[1] += L->weight[v];
        PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &tot[1], 1, MPIU_REAL, MPIU_SUM, body->comm));
        if (tot[1] <= 0.0) {
          for (PetscInt v = 0; v < nv; v++) L->weight[v] = (vmark[v] && m->owned[v]) ? 1.0 : 0.0;
          for (PetscInt v = 0; v < nv; v++) tot[2] += L->weight[v];
          PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &tot[2], 1, MPIU_REAL, MPIU_SUM, body->comm));
          PetscCheck(tot[2] > 0.0, body->comm, PETSC_ERR_USER_INPUT, "Option %s: region '%s' of body '%s' is empty",
                     opt, reg[i], body->name);
        }
      }
      for (PetscInt v = 0; v < nv; v++) L->weight[v] /= tot[0] > 0.0 ? tot[0] : tot[1] > 0.0 ? tot[1] : tot[2];
    }
    PetscCall(PetscFree2(vmark, cmark));
    fem->nload++;
  }
  for (PetscInt i = 0; i < n; i++) PetscCall(PetscFree(tab[i]));
  PetscFunctionReturn(0);
}

PetscErrorCode FCFEMLoadsSetUp(FCBody body)
{
  FEM *fem = (FEM *)body->data;

  PetscFunctionBegin;
  PetscCall(SetUpLoads(body, FC_LOAD_FORCE, "force", fem->bcspec[2]));
  PetscCall(SetUpLoads(body, FC_LOAD_TRACTION, "traction", fem->bcspec[3]));
  PetscCall(SetUpLoads(body, FC_LOAD_PRESSURE, "pressure", fem->bcspec[4]));
  /* a load on a constrained vertex is taken by its support: it goes into fcons, for the reaction */
  if (fem->nload) {
    PetscCall(VecDuplicate(fem->u, &fem->fload));
    PetscCall(PetscCalloc1(3 * (fem->mesh.vEnd - fem->mesh.vStart) + 1, &fem->fcons));
  }
  PetscFunctionReturn(0);
}

/* fload = the loads at time t */
PetscErrorCode FCFEMLoadsAt(FCBody body, PetscReal t)
{
  FEM    *fem = (FEM *)body->data;
  FCMesh *m   = &fem->mesh;

  PetscFunctionBegin;
  if (fem->nload) {
    Vec                fl;
    PetscScalar       *f;
    const PetscScalar *ul;
    PetscCall(DMGetLocalVector(m->dm, &fl));
    PetscCall(VecZeroEntries(fl));
    PetscCall(VecGetArray(fl, &f));
    PetscCall(DMGlobalToLocal(m->dm, fem->u, INSERT_VALUES, fem->uloc));
    PetscCall(VecGetArrayRead(fem->uloc, &ul));
    PetscCall(PetscArrayzero(fem->fcons, 3 * (m->vEnd - m->vStart)));
    for (PetscInt l = 0; l < fem->nload; l++) {
      FCFEMLoad *L = &fem->load[l];
      PetscReal  val[3];
      FCTableEval(L->table, t, val);
      if (L->kind == FC_LOAD_FORCE) {
        for (PetscInt v = 0; v < m->vEnd - m->vStart; v++)
          if (L->weight[v] != 0.0) {
            if (fem->fixed[v])
              for (int d = 0; d < 3; d++) fem->fcons[3 * v + d] += L->weight[v] * val[d];
            else
              for (int d = 0; d < 3; d++) f[fem->ldof[v] + d] += L->weight[v] * val[d];
          }
        continue;
      }
      for (PetscInt k = 0; k < L->nface; k++) { /* area / 3 to each vertex; pressure along the current normal */
        PetscInt *tv = &L->facev[3 * k];
        PetscReal x[9], e1[3], e2[3], an[3], load[3];
        for (int a = 0; a < 3; a++)
          for (int d = 0; d < 3; d++) x[3 * a + d] = m->X[3 * tv[a] + d] + FCFEMLocalU(fem, tv[a], ul, d);
        for (int d = 0; d < 3; d++) {
          e1[d] = x[3 + d] - x[d];
          e2[d] = x[6 + d] - x[d];
        }
        FCCross(e1, e2, an); /* twice the area times the outward normal */
        for (int d = 0; d < 3; d++)
          load[d] = L->kind == FC_LOAD_PRESSURE ? -val[0] * an[d] / 6.0 : val[d] * PetscSqrtReal(FCDot(an, an)) / 6.0;
        for (int a = 0; a < 3; a++)
          if (!fem->fixed[tv[a]])
            for (int d = 0; d < 3; d++) f[fem->ldof[tv[a]] + d] += load[d];
          else
            for (int d = 0; d < 3; d++) fem->fcons[3 * tv[a] + d] += load[d];
      }
    }
    PetscCall(VecRestoreArrayRead(fem->uloc, &ul));
    PetscCall(VecRestoreArray(fl, &f));
    PetscCall(VecZeroEntries(fem->fload));
    PetscCall(DMLocalToGlobal(m->dm, fl, ADD_VALUES, fem->fload));
    PetscCall(DMRestoreLocalVector(m->dm, &fl));
  }
  PetscFunctionReturn(0);
}
