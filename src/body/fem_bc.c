/* FE body, constrained regions (docs/scenes.md):
     -fixed <region>[,<region>...]                 zero displacement
     -displacement <region>=<table t,ux,uy,uz>,...  prescribed displacement of the region's vertices
     -attach <region>:<body>,...                    the region follows a kinematic body rigidly
   A region is a gmsh physical group (name or number) or box:x0,y0,z0,x1,y1,z1 (src/mesh/region.c);
   a table is a CSV file or t0:v;t1:v (src/util/table.c). Constrained vertices leave the unknowns
   (fem.c, SetUpSection), so neither the free motion nor the contact correction moves them. The
   loads (-force, -traction, -pressure) are in fem_load.c, the reactions in fem_reaction.c.

   A prescribed motion enters the linearized step (eq. 5) through the coupling of the free DOFs f
   with the prescribed ones p: with q* the state with p at its end-of-step displacement,
   f_int(q_{t+h}) = f_int(q*) + K_ff h v_f, so the free rows get
       b_f -= K_fp (h (u_p(t+h) - u_p(t)) + h beta v_p) + M_fp (dv_p + h alpha v_p)
   (plus h K_fp u_p(t) for a linear body, whose f_int = K u sees the free DOFs only), v_p the
   vertex's prescribed velocity over the step, dv_p its change from the step before. */
#include "femimpl.h"

/* Splits "region=table,region=table": a region is a name, a number or box: and 6 numbers, and a
   table's text has no '='; each pair's region is copied into reg[] (at most 255 characters) and its
   table, of any length, into tab[] (allocated: the caller frees each) */
PetscErrorCode FCFEMSplitPairs(FCBody body, const char option[], const char spec[], PetscInt *n, char reg[][256],
                               char *tab[])
{
  const char *eq[FC_MAX_REGIONS + 1], *start[FC_MAX_REGIONS + 1], *p;
  PetscInt    k = 0;

  PetscFunctionBegin;
  for (p = strchr(spec, '='); p; p = strchr(p + 1, '=')) {
    PetscCheck(k < FC_MAX_REGIONS, body->comm, PETSC_ERR_USER_INPUT, "Option -%s%s: more than %d regions", body->prefix,
               option, FC_MAX_REGIONS);
    eq[k++] = p;
  }
  PetscCheck(k > 0, body->comm, PETSC_ERR_USER_INPUT, "Option -%s%s needs region=table pairs, got '%s'", body->prefix,
             option, spec);
  for (PetscInt i = 0; i < k; i++) { /* where each region begins */
    const char *lo = i ? eq[i - 1] + 1 : spec, *c = eq[i], *box = NULL;
    while (c > lo && c[-1] != ',') c--;
    for (const char *q = lo; q + 4 <= eq[i]; q++)
      if (!strncmp(q, "box:", 4)) box = q;
    if (box) {
      PetscInt commas = 0;
      for (const char *q = box; q < eq[i]; q++) commas += *q == ',';
      if (commas == 5) c = box;
    }
    PetscCheck(i == 0 || c > lo, body->comm, PETSC_ERR_USER_INPUT,
               "Option -%s%s: no table before the region that ends at '%s'", body->prefix, option, eq[i]);
    start[i] = c;
  }
  PetscCheck(start[0] == spec, body->comm, PETSC_ERR_USER_INPUT, "Option -%s%s: '%s' is not region=table,...",
             body->prefix, option, spec);
  start[k] = spec + strlen(spec) + 1;
  for (PetscInt i = 0; i < k; i++) {
    size_t lr = (size_t)(eq[i] - start[i]), lt = (size_t)(start[i + 1] - 1 - (eq[i] + 1));
    PetscCheck(lr > 0 && lt > 0, body->comm, PETSC_ERR_USER_INPUT,
               "Option -%s%s: pair %" PetscInt_FMT " has an empty region or table", body->prefix, option, i + 1);
    PetscCheck(lr < 256, body->comm, PETSC_ERR_USER_INPUT,
               "Option -%s%s: the region of pair %" PetscInt_FMT " is longer than 255 characters", body->prefix, option,
               i + 1);
    memcpy(reg[i], start[i], lr);
    reg[i][lr] = 0;
    PetscCall(PetscMalloc1(lt + 1, &tab[i]));
    memcpy(tab[i], eq[i] + 1, lt);
    tab[i][lt] = 0;
  }
  *n = k;
  PetscFunctionReturn(0);
}

PetscErrorCode FCFEMBCSetFromOptions(PetscOptionItems *PetscOptionsObject, FCBody body)
{
  FEM *fem = (FEM *)body->data;

  PetscFunctionBegin;
  /* values of any length (a table written inline may have thousands of rows) */
  PetscCall(FCOptionsStringAlloc(
      PetscOptionsObject, "-fixed",
      "Regions with zero displacement: gmsh groups (name or number) or box:x0,y0,z0,x1,y1,z1", &fem->bcspec[0], NULL));
  PetscCall(FCOptionsStringAlloc(PetscOptionsObject, "-displacement",
                                 "Prescribed displacement: region=table of t,ux,uy,uz[,region=table...]",
                                 &fem->bcspec[1], NULL));
  PetscCall(FCOptionsStringAlloc(PetscOptionsObject, "-force",
                                 "Total force on a region: region=table of t,fx,fy,fz[,...]", &fem->bcspec[2], NULL));
  PetscCall(FCOptionsStringAlloc(PetscOptionsObject, "-traction",
                                 "Force per area on a surface region: region=table of t,tx,ty,tz[,...]",
                                 &fem->bcspec[3], NULL));
  PetscCall(FCOptionsStringAlloc(PetscOptionsObject, "-attach",
                                 "Regions that follow a kinematic body: region:body[,region:body...]", &fem->bcspec[5],
                                 NULL));
  PetscCall(FCOptionsStringAlloc(PetscOptionsObject, "-pressure",
                                 "Pressure on a surface region (positive into the body): region=table of t,p[,...]",
                                 &fem->bcspec[4], NULL));
  PetscFunctionReturn(0);
}

/* Marks the vertices of constraint k; a vertex in two constraints is an error naming both */
static PetscErrorCode MarkConstraint(FCBody body, PetscInt k, const char option[], PetscBool *mark)
{
  FEM     *fem   = (FEM *)body->data;
  FCMesh  *m     = &fem->mesh;
  PetscInt clash = -1;
  char     opt[FC_MAX_NAME + 32];

  PetscFunctionBegin;
  PetscCall(PetscSNPrintf(opt, sizeof(opt), "-%s%s", body->prefix, option));
  PetscCall(
      FCMeshRegion(m, fem->cons[k].region, opt, body->name, mark, &fem->cons[k].nface, &fem->cons[k].facev, NULL));
  for (PetscInt v = 0; v < m->vEnd - m->vStart; v++) {
    if (!mark[v]) continue;
    if (fem->creg[v] >= 0 && fem->creg[v] != k && (fem->cons[k].moves || fem->cons[fem->creg[v]].moves))
      clash = PetscMax(clash, fem->creg[v]);
    if (fem->creg[v] < 0 || fem->cons[k].moves) fem->creg[v] = k;
  }
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &clash, 1, MPIU_INT, MPI_MAX, body->comm));
  PetscCheck(clash < 0, body->comm, PETSC_ERR_USER_INPUT,
             "Body '%s': regions '%s' and '%s' share vertices, and one of them is prescribed (-%sdisplacement or "
             "-%sattach): a vertex has one constraint",
             body->name, fem->cons[clash].region, fem->cons[k].region, body->prefix, body->prefix);
  { /* an empty region constrains nothing; one whose vertices all belong to a region before it (the
       same region given twice, or under its name and its number) would report a reaction of 0 */
    PetscInt cnt[2] = {0, 0}, first = PETSC_MAX_INT;
    for (PetscInt v = 0; v < m->vEnd - m->vStart; v++) {
      if (!mark[v]) continue;
      cnt[0]++;
      if (fem->creg[v] == k)
        cnt[1]++;
      else
        first = PetscMin(first, fem->creg[v]);
    }
    PetscCall(MPIU_Allreduce(MPI_IN_PLACE, cnt, 2, MPIU_INT, MPI_SUM, body->comm));
    PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &first, 1, MPIU_INT, MPI_MIN, body->comm));
    PetscCheck(cnt[0] > 0, body->comm, PETSC_ERR_USER_INPUT, "Option %s: region '%s' of body '%s' is empty", opt,
               fem->cons[k].region, body->name);
    PetscCheck(cnt[1] > 0, body->comm, PETSC_ERR_USER_INPUT,
               "Option %s: every vertex of region '%s' of body '%s' is in region '%s' given before it (a region given "
               "twice?): its reaction would be 0",
               opt, fem->cons[k].region, body->name, fem->cons[first].region);
  }
  PetscFunctionReturn(0);
}

/* The next constraint of the body, its region named (at most FC_MAX_REGIONS) */
static PetscErrorCode NewConstraint(FCBody body, const char region[], FCFEMConstraint **c)
{
  FEM *fem = (FEM *)body->data;

  PetscFunctionBegin;
  PetscCheck(fem->ncons < FC_MAX_REGIONS, body->comm, PETSC_ERR_USER_INPUT, "Body '%s': more than %d constraints",
             body->name, FC_MAX_REGIONS);
  PetscCheck(strlen(region) < sizeof((*c)->region), body->comm, PETSC_ERR_USER_INPUT,
             "Body '%s': a region is longer than %d characters", body->name, (int)sizeof((*c)->region) - 1);
  PetscCheck(!strchr(region, '/'), body->comm, PETSC_ERR_USER_INPUT,
             "Body '%s': region '%s' has a '/', which cannot name its reaction in the output", body->name, region);
  *c = &fem->cons[fem->ncons];
  PetscCall(PetscStrncpy((*c)->region, region, sizeof((*c)->region)));
  PetscFunctionReturn(0);
}

/* The next item of a comma-separated list of regions (a box takes its six numbers, and what follows
   the sixth up to the next comma, as -attach's ":body"); *s moves past it */
static PetscErrorCode NextItem(FCBody body, const char option[], char **s, char item[], size_t len)
{
  char    *tok    = *s;
  PetscInt commas = !strncmp(tok, "box:", 4) ? 6 : 1;

  PetscFunctionBegin;
  while (**s && commas) {
    if (**s == ',') commas--;
    if (commas) (*s)++;
  }
  PetscCheck((size_t)(*s - tok) < len, body->comm, PETSC_ERR_USER_INPUT,
             "Option -%s%s: an item is longer than %d characters", body->prefix, option, (int)len - 1);
  PetscCall(PetscStrncpy(item, tok, (size_t)(*s - tok) + 1));
  if (**s == ',') (*s)++;
  PetscFunctionReturn(0);
}

/* FCFEMBCSetUpConstraints with the scratch marks of a region's vertices (mark, nv long) */
static PetscErrorCode SetUpConstraints(FCBody body, PetscBool mark[])
{
  FEM             *fem = (FEM *)body->data;
  FCMesh          *m   = &fem->mesh;
  PetscInt         nv  = m->vEnd - m->vStart;
  FCFEMConstraint *c;
  char             item[512];

  PetscFunctionBegin;
  PetscCall(PetscMalloc1(nv + 1, &fem->creg));
  for (PetscInt v = 0; v < nv; v++) fem->creg[v] = -1;
  fem->ncons = 0;
  for (PetscInt b = 0; b < fem->nfixed_box; b++) { /* -fixed_box: constraints named box:... */
    const PetscReal *x = &fem->fixed_box[6 * b];
    PetscCall(PetscSNPrintf(item, sizeof(item), "box:%.17g,%.17g,%.17g,%.17g,%.17g,%.17g", x[0], x[1], x[2], x[3], x[4],
                            x[5]));
    PetscCall(NewConstraint(body, item, &c));
    PetscCall(MarkConstraint(body, fem->ncons++, "fixed_box", mark));
  }
  for (char *s = fem->bcspec[0]; s && *s;) { /* -fixed: names and boxes */
    char *end;
    if (s != fem->bcspec[0] && !strncmp(fem->cons[fem->ncons - 1].region, "box:", 4)) { /* a box's seventh number? */
      (void)strtod(s, &end);
      PetscCheck(end == s || (*end && *end != ','), body->comm, PETSC_ERR_USER_INPUT,
                 "Option -%sfixed: '%s' has a seventh number after it (a box has six: x0,y0,z0,x1,y1,z1; a group "
                 "given by number goes before the box)",
                 body->prefix, fem->cons[fem->ncons - 1].region);
    }
    PetscCall(NextItem(body, "fixed", &s, item, sizeof(item)));
    PetscCall(NewConstraint(body, item, &c));
    PetscCall(MarkConstraint(body, fem->ncons++, "fixed", mark));
  }
  if (fem->bcspec[1] && fem->bcspec[1][0]) { /* -displacement */
    char     reg[FC_MAX_REGIONS][256], *tab[FC_MAX_REGIONS], what[FC_MAX_NAME + 300];
    PetscInt n;
    PetscCall(FCFEMSplitPairs(body, "displacement", fem->bcspec[1], &n, reg, tab));
    for (PetscInt i = 0; i < n; i++) {
      PetscCall(NewConstraint(body, reg[i], &c));
      c->moves = PETSC_TRUE;
      PetscCall(PetscSNPrintf(what, sizeof(what), "option -%sdisplacement, region %s", body->prefix, reg[i]));
      PetscCall(FCTableCreate(body->comm, tab[i], 3, 3, what, &c->table));
      PetscCall(MarkConstraint(body, fem->ncons++, "displacement", mark));
    }
    for (PetscInt i = 0; i < n; i++) PetscCall(PetscFree(tab[i]));
  }
  for (char *s = fem->bcspec[5]; s && *s;) { /* -attach region:body */
    char  *colon;
    FCBody b = NULL;
    PetscCall(NextItem(body, "attach", &s, item, sizeof(item)));
    colon = strrchr(item, ':');
    PetscCheck(colon && colon != item + 3 && colon[1], body->comm, PETSC_ERR_USER_INPUT,
               "Option -%sattach: '%s' is not region:body", body->prefix, item);
    *colon = 0;
    for (PetscInt i = 0; i < body->nscene; i++)
      if (!strcmp(FCBodyName(body->scene[i]), colon + 1)) b = body->scene[i];
    PetscCheck(b && b != body, body->comm, PETSC_ERR_USER_INPUT,
               "Option -%sattach: '%s' is no other body of -scene_bodies", body->prefix, colon + 1);
    PetscCheck(b->ops.poseat, body->comm, PETSC_ERR_USER_INPUT,
               "Option -%sattach: body '%s' is %s; a region can follow a kinematic body only (its motion is given)",
               body->prefix, colon + 1, b->type);
    PetscCall(NewConstraint(body, item, &c));
    c->body    = b;
    c->moves   = PETSC_TRUE;
    c->rotates = PETSC_TRUE;
    for (int w = 0; w < 3; w++) FCMat3Identity(c->RR[w]); /* at rest until the first pose (FCFEMBCPoses) */
    FCMat3Identity(c->R0T);
    PetscCall(MarkConstraint(body, fem->ncons++, "attach", mark));
  }
  fem->moving = PETSC_FALSE;
  for (PetscInt k = 0; k < fem->ncons; k++) fem->moving = (PetscBool)(fem->moving || fem->cons[k].moves);
  for (PetscInt v = 0; v < nv; v++) fem->fixed[v] = (PetscBool)(fem->creg[v] >= 0);
  PetscFunctionReturn(0);
}

PetscErrorCode FCFEMBCSetUpConstraints(FCBody body)
{
  FEM           *fem = (FEM *)body->data;
  PetscBool     *mark;
  PetscErrorCode ierr;

  PetscFunctionBegin;
  PetscCall(PetscMalloc1(fem->mesh.vEnd - fem->mesh.vStart + 1, &mark));
  ierr = SetUpConstraints(body, mark); /* a wrong region fails here: the marks are freed all the same */
  PetscCall(PetscFree(mark));
  PetscCall(ierr);
  PetscFunctionReturn(0);
}

PetscErrorCode FCFEMBCSetUp(FCBody body)
{
  FEM     *fem = (FEM *)body->data;
  FCMesh  *m   = &fem->mesh;
  PetscInt nc  = m->cEnd - m->cStart;

  PetscFunctionBegin;
  PetscCall(FCFEMLoadsSetUp(body));
  PetscCall(PetscMalloc1(nc + 1, &fem->ccell));
  fem->nccell = 0;
  for (PetscInt c = 0; c < nc; c++) {
    PetscBool any = PETSC_FALSE;
    for (int a = 0; a < 4; a++) any = (PetscBool)(any || fem->fixed[m->cellVerts[4 * c + a] - m->vStart]);
    if (any) fem->ccell[fem->nccell++] = c;
  }
  PetscFunctionReturn(0);
}

/* The prescribed constraints' poses at t - h, t and t + h (a table is held before its first row;
   an attachment's pose at t = 0 is its reference) */
PetscErrorCode FCFEMBCPoses(FCBody body, PetscReal t)
{
  FEM      *fem = (FEM *)body->data;
  PetscReal h   = body->h;

  PetscFunctionBegin;
  for (PetscInt k = 0; k < fem->ncons; k++) {
    FCFEMConstraint *c = &fem->cons[k];
    if (!c->moves) continue;
    if (c->body && !c->referenced) { /* the reference pose, at t = 0, once (the body is set up by now) */
      PetscReal q[4], R[9];
      PetscCall(FCBodyGetPoseAt(c->body, 0.0, c->x0, q));
      FCQuatToMat3(q, R);
      FCMat3Transpose(R, c->R0T);
      c->referenced = PETSC_TRUE;
    }
    for (int w = 0; w < 3; w++) {
      PetscReal tw = t + (w - 1) * h;
      if (c->table)
        FCTableEval(c->table, tw, c->x[w]);
      else {
        PetscReal q[4], R[9];
        PetscCall(FCBodyGetPoseAt(c->body, tw, c->x[w], q));
        FCQuatToMat3(q, R);
        FCMat3Mult(R, c->R0T, c->RR[w]);
      }
    }
  }
  PetscFunctionReturn(0);
}

/* The constraints' poses of the step, and the loads at t + h */
PetscErrorCode FCFEMBCBeginStep(FCBody body, PetscReal t)
{
  PetscFunctionBegin;
  PetscCall(FCFEMBCPoses(body, t));
  PetscCall(FCFEMLoadsAt(body, t + body->h));
  PetscFunctionReturn(0);
}

/* b += h f_load, and the coupling of the free rows with the prescribed motion (header) */
PetscErrorCode FCFEMBCAddRHS(FCBody body, Vec b, PetscBool stiffness)
{
  FEM      *fem = (FEM *)body->data;
  FCMesh   *m   = &fem->mesh;
  PetscReal h   = body->h;

  PetscFunctionBegin;
  if (fem->nload) PetscCall(VecAXPY(b, h, fem->fload));
  if (fem->moving) {
    Vec                bl;
    PetscScalar       *f;
    const PetscScalar *ul;
    PetscCall(DMGetLocalVector(m->dm, &bl));
    PetscCall(VecZeroEntries(bl));
    PetscCall(VecGetArray(bl, &f));
    PetscCall(DMGlobalToLocal(m->dm, fem->u, INSERT_VALUES, fem->uloc));
    PetscCall(VecGetArrayRead(fem->uloc, &ul));
    for (PetscInt i = 0; i < fem->nccell; i++) {
      PetscInt  c = fem->ccell[i];
      PetscReal X[12], x[12], Ke[144], Me[144], wk[12] = {0}, wm[12] = {0};
      PetscBool any = PETSC_FALSE;
      for (int a = 0; a < 4; a++) {
        PetscInt v = m->cellVerts[4 * c + a] - m->vStart, k = fem->creg[v];
        if (k < 0 || !fem->cons[k].moves) continue;
        any = PETSC_TRUE;
        for (int d = 0; d < 3; d++) {
          const PetscReal *Xv = &m->X[3 * v], vp = FCFEMConstrainedV(fem, k, Xv, PETSC_FALSE, h, d),
                          v0 = FCFEMConstrainedV(fem, k, Xv, PETSC_TRUE, h, d);
          wk[3 * a + d]      = !stiffness ? 0.0
                                          : h * h * vp + h * fem->beta * vp +
                                           (fem->mat->linear ? h * FCFEMConstrainedU(fem, k, Xv, FC_BC_NOW, d) : 0.0);
          wm[3 * a + d]      = body->quasistatic ? 0.0 : (vp - v0) + h * fem->alpha * vp;
        }
      }
      if (!any) continue;
      FCFEMGatherElement(fem, c, ul, X, x);
      if (stiffness)
        PetscCall((*fem->mat->element)(fem->mat, x, X, &fem->Dminv[9 * c], fem->vol[c], NULL, Ke));
      else
        PetscCall(PetscArrayzero(Ke, 144));
      FCTetMass(body->density, fem->vol[c], fem->lumped, Me);
      for (int a = 0; a < 4; a++) {
        PetscInt v = m->cellVerts[4 * c + a] - m->vStart;
        if (fem->fixed[v]) continue;
        for (int r = 3 * a; r < 3 * a + 3; r++) {
          PetscReal s = 0.0;
          for (int j = 0; j < 12; j++) s += Ke[12 * r + j] * wk[j] + Me[12 * r + j] * wm[j];
          f[fem->ldof[v] + r - 3 * a] -= s;
        }
      }
    }
    PetscCall(VecRestoreArrayRead(fem->uloc, &ul));
    PetscCall(VecRestoreArray(bl, &f));
    PetscCall(DMLocalToGlobal(m->dm, bl, ADD_VALUES, b));
    PetscCall(DMRestoreLocalVector(m->dm, &bl));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode FCFEMBCDestroy(FCBody body)
{
  FEM *fem = (FEM *)body->data;

  PetscFunctionBegin;
  for (PetscInt k = 0; k < fem->ncons; k++) {
    PetscCall(FCTableDestroy(&fem->cons[k].table));
    PetscCall(PetscFree(fem->cons[k].facev));
  }
  for (PetscInt l = 0; l < fem->nload; l++) {
    PetscCall(FCTableDestroy(&fem->load[l].table));
    PetscCall(PetscFree(fem->load[l].facev));
    PetscCall(PetscFree(fem->load[l].weight));
  }
  for (int i = 0; i < 6; i++) PetscCall(PetscFree(fem->bcspec[i]));
  PetscCall(VecDestroy(&fem->fload));
  PetscCall(PetscFree(fem->fcons));
  PetscCall(VecDestroy(&fem->varea));
  PetscCall(PetscFree(fem->creg));
  PetscCall(PetscFree(fem->ccell));
  PetscFunctionReturn(0);
}
