/* FE body, what it reports of its state: centroid, energies, the positions of its visual mesh and
   its fields (displacement, velocity, von Mises stress, energy density), the restart state (get
   and set) and the NaN check. */
#include "femimpl.h"
#include <petsc/private/petscimpl.h> /* PetscObjectStateGet: public from PETSc 3.19 on */

/* Mass-weighted centroid: for P1, int x dV over a tet is V times the mean of its vertices */
PetscErrorCode GetCentroid_FEM(FCBody body, PetscReal c[3])
{
  FEM               *fem = (FEM *)body->data;
  FCMesh            *m   = &fem->mesh;
  const PetscScalar *ul;
  PetscReal          acc[4] = {0, 0, 0, 0};

  PetscFunctionBegin;
  PetscCall(DMGlobalToLocal(m->dm, fem->u, INSERT_VALUES, fem->uloc));
  PetscCall(VecGetArrayRead(fem->uloc, &ul));
  for (PetscInt e = 0; e < m->cEnd - m->cStart; e++) {
    PetscReal X[12], x[12];
    FCFEMGatherElement(fem, e, ul, X, x);
    acc[3] += fem->vol[e];
    for (int d = 0; d < 3; d++) acc[d] += fem->vol[e] * 0.25 * (x[d] + x[3 + d] + x[6 + d] + x[9 + d]);
  }
  PetscCall(VecRestoreArrayRead(fem->uloc, &ul));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, acc, 4, MPIU_REAL, MPIU_SUM, body->comm));
  for (int d = 0; d < 3; d++) c[d] = acc[d] / acc[3];
  PetscFunctionReturn(0);
}

/* Kinetic 1/2 v^T M v, elastic (sum of element energies), gravity -m g . x_centroid */
PetscErrorCode GetEnergy_FEM(FCBody body, FCEnergy *E)
{
  FEM               *fem = (FEM *)body->data;
  FCMesh            *m   = &fem->mesh;
  const PetscScalar *ul;
  PetscReal          c[3];
  PetscScalar        vMv;

  PetscFunctionBegin;
  { /* asked for twice a step (the energy guard, the step's row): the element loop of a co-rotational
       body costs about a third of an assembly, so it runs once per state of u and v */
    PetscObjectState su, sv;
    PetscCall(PetscObjectStateGet((PetscObject)fem->u, &su));
    PetscCall(PetscObjectStateGet((PetscObject)fem->v, &sv));
    if (fem->energy_u && su == fem->energy_u && sv == fem->energy_v) {
      *E = fem->energy;
      PetscFunctionReturn(0);
    }
  }
  PetscCall(MatMult(fem->M, fem->v, fem->work));
  PetscCall(VecDot(fem->v, fem->work, &vMv));
  E->kinetic = body->quasistatic ? 0.0 : 0.5 * PetscRealPart(vMv); /* static: v is a displacement rate */
  E->elastic = 0.0;
  PetscCall(DMGlobalToLocal(m->dm, fem->u, INSERT_VALUES, fem->uloc));
  PetscCall(VecGetArrayRead(fem->uloc, &ul));
  for (PetscInt e = 0; e < m->cEnd - m->cStart; e++) {
    PetscReal X[12], x[12], Ee;
    FCFEMGatherElement(fem, e, ul, X, x);
    PetscCall((*fem->mat->energy)(fem->mat, x, X, &fem->Dminv[9 * e], fem->vol[e], &Ee));
    E->elastic += Ee;
  }
  PetscCall(VecRestoreArrayRead(fem->uloc, &ul));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &E->elastic, 1, MPIU_REAL, MPIU_SUM, body->comm));
  PetscCall(GetCentroid_FEM(body, c));
  E->gravity  = -fem->mass * FCDot(body->gravity, c);
  fem->energy = *E;
  PetscCall(PetscObjectStateGet((PetscObject)fem->u, &fem->energy_u));
  PetscCall(PetscObjectStateGet((PetscObject)fem->v, &fem->energy_v));
  PetscFunctionReturn(0);
}

PetscErrorCode GetVisualPositions_FEM(FCBody body, PetscReal x[])
{
  FEM               *fem = (FEM *)body->data;
  FCMesh            *m   = &fem->mesh;
  const PetscScalar *ul;

  PetscFunctionBegin;
  PetscCall(DMGlobalToLocal(m->dm, fem->u, INSERT_VALUES, fem->uloc));
  PetscCall(VecGetArrayRead(fem->uloc, &ul));
  for (PetscInt i = 0; i < body->visual.nv; i++) {
    PetscInt v = m->visVert[i];
    for (int d = 0; d < 3; d++) x[3 * i + d] = m->X[3 * v + d] + FCFEMLocalU(fem, v, ul, d);
  }
  PetscCall(VecRestoreArrayRead(fem->uloc, &ul));
  PetscFunctionReturn(0);
}

/* A vector (u or v) at the owned visual vertices; on constrained vertices their displacement or
   velocity over the last step */
static PetscErrorCode VisualVertexValues(FCBody body, Vec g, PetscReal out[])
{
  FEM               *fem = (FEM *)body->data;
  FCMesh            *m   = &fem->mesh;
  Vec                loc;
  const PetscScalar *a;

  PetscFunctionBegin;
  PetscCall(DMGetLocalVector(m->dm, &loc));
  PetscCall(DMGlobalToLocal(m->dm, g, INSERT_VALUES, loc));
  PetscCall(VecGetArrayRead(loc, &a));
  for (PetscInt i = 0; i < body->visual.nv; i++) {
    PetscInt v = m->visVert[i];
    for (int d = 0; d < 3; d++) {
      PetscInt k     = fem->creg[v];
      out[3 * i + d] = !fem->fixed[v] ? PetscRealPart(a[fem->ldof[v] + d])
                       : g == fem->u  ? FCFEMConstrainedU(fem, k, &m->X[3 * v], FC_BC_NOW, d)
                                      : FCFEMConstrainedV(fem, k, &m->X[3 * v], PETSC_TRUE, body->h, d);
    }
  }
  PetscCall(VecRestoreArrayRead(loc, &a));
  PetscCall(DMRestoreLocalVector(m->dm, &loc));
  PetscFunctionReturn(0);
}

/* A value per owned cell (the visual cells, in their order): the von Mises stress of the
   material's stress, or the element's elastic energy over its reference volume */
static PetscErrorCode VisualCellValues(FCBody body, FCVisualField field, PetscReal out[])
{
  FEM               *fem = (FEM *)body->data;
  FCMesh            *m   = &fem->mesh;
  const PetscScalar *ul;
  const PetscInt    *gc;
  PetscInt           k = 0;

  PetscFunctionBegin;
  PetscCall(DMGlobalToLocal(m->dm, fem->u, INSERT_VALUES, fem->uloc));
  PetscCall(VecGetArrayRead(fem->uloc, &ul));
  PetscCall(ISGetIndices(m->cellNumbering, &gc));
  for (PetscInt e = 0; e < m->cEnd - m->cStart; e++) {
    PetscReal X[12], x[12];
    if (gc[e] < 0) continue; /* a ghost cell: its owner writes it */
    FCFEMGatherElement(fem, e, ul, X, x);
    if (field == FC_FIELD_VON_MISES) {
      PetscReal S[9], p, s2 = 0.0;
      PetscCall((*fem->mat->stress)(fem->mat, x, X, &fem->Dminv[9 * e], S));
      p = (S[0] + S[4] + S[8]) / 3.0;
      for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
          PetscReal sij = S[3 * i + j] - (i == j ? p : 0.0);
          s2 += sij * sij;
        }
      out[k++] = PetscSqrtReal(1.5 * s2);
    } else {
      PetscReal E;
      PetscCall((*fem->mat->energy)(fem->mat, x, X, &fem->Dminv[9 * e], fem->vol[e], &E));
      out[k++] = E / fem->vol[e];
    }
  }
  PetscCall(ISRestoreIndices(m->cellNumbering, &gc));
  PetscCall(VecRestoreArrayRead(fem->uloc, &ul));
  PetscCheck(k == body->visual.nc, PETSC_COMM_SELF, PETSC_ERR_PLIB,
             "Body '%s': %" PetscInt_FMT " owned cells, %" PetscInt_FMT " visual cells", body->name, k,
             body->visual.nc);
  PetscFunctionReturn(0);
}

PetscErrorCode GetVisualField_FEM(FCBody body, FCVisualField field, PetscReal out[], PetscBool *has)
{
  FEM *fem = (FEM *)body->data;

  PetscFunctionBegin;
  *has = PETSC_TRUE;
  switch (field) {
  case FC_FIELD_DISPLACEMENT:
    PetscCall(VisualVertexValues(body, fem->u, out));
    break;
  case FC_FIELD_VELOCITY:
    PetscCall(VisualVertexValues(body, fem->v, out));
    break;
  case FC_FIELD_VON_MISES:
  case FC_FIELD_ENERGY_DENSITY:
    PetscCall(VisualCellValues(body, field, out));
    break;
  case FC_FIELD_CONTACT_PRESSURE:
    PetscCall(FCFEMContactPressure(body, out));
    break;
  default:
    *has = PETSC_FALSE;
  }
  PetscFunctionReturn(0);
}

/* Restart state: per owned vertex in the visual (global) order, u and v (0 on fixed vertices), and a
   nonlinear correction's f_c (fem_nonlinear.c) */
PetscErrorCode GetState_FEM(FCBody body, PetscReal s[])
{
  FEM               *fem = (FEM *)body->data;
  FCMesh            *m   = &fem->mesh;
  const PetscScalar *u, *v;
  PetscInt           lo, cols = body->state_cols;

  PetscFunctionBegin;
  PetscCall(VecGetOwnershipRange(fem->u, &lo, NULL));
  PetscCall(VecGetArrayRead(fem->u, &u));
  PetscCall(VecGetArrayRead(fem->v, &v));
  for (PetscInt i = 0; i < body->visual.nv; i++) {
    PetscInt vx = m->visVert[i];
    for (int d = 0; d < 3; d++) {
      s[cols * i + d]     = FCFEMOwnedU(fem, vx, u, lo, d);
      s[cols * i + 3 + d] = fem->fixed[vx]
                                ? FCFEMConstrainedV(fem, fem->creg[vx], &m->X[3 * vx], PETSC_TRUE, body->h, d)
                                : PetscRealPart(v[fem->gdof[vx] - lo + d]);
    }
  }
  PetscCall(VecRestoreArrayRead(fem->u, &u));
  PetscCall(VecRestoreArrayRead(fem->v, &v));
  PetscCall(FCFEMNonlinearGetState(body, cols, s));
  PetscFunctionReturn(0);
}

/* The state of a restart: A of a co-rotational body is reassembled and factored at the next step,
   as it would have been with -factorization every_step (reuse starts from a new factor) */
PetscErrorCode SetState_FEM(FCBody body, const PetscReal s[])
{
  FEM         *fem = (FEM *)body->data;
  FCMesh      *m   = &fem->mesh;
  PetscScalar *u, *v;
  PetscInt     lo, cols = body->state_cols;

  PetscFunctionBegin;
  PetscCall(VecGetOwnershipRange(fem->u, &lo, NULL));
  PetscCall(VecGetArray(fem->u, &u));
  PetscCall(VecGetArray(fem->v, &v));
  for (PetscInt i = 0; i < body->visual.nv; i++) {
    PetscInt vx = m->visVert[i];
    if (fem->fixed[vx]) continue;
    for (int d = 0; d < 3; d++) {
      u[fem->gdof[vx] - lo + d] = s[cols * i + d];
      v[fem->gdof[vx] - lo + d] = s[cols * i + 3 + d];
    }
  }
  PetscCall(VecRestoreArray(fem->u, &u));
  PetscCall(VecRestoreArray(fem->v, &v));
  PetscCall(FCFEMNonlinearSetState(body, cols, s));
  fem->Rcurrent = PETSC_FALSE;
  if (!fem->mat->linear) {
    fem->Acurrent      = PETSC_FALSE;
    fem->refactor_next = PETSC_TRUE;
  }
  PetscFunctionReturn(0);
}

/* The state after a (sub-)step: finite, and the elements turned inside out (J = det F <= 0) counted,
   with the smallest J of the body (fem->inverted: the last check's, which the scene records once the
   step is accepted, in /steps and the run's summary). An element turned inside out is a body crushed
   or stretched through its own thickness, whose surface then crosses itself and whatever touches it:
   a co-rotational element gets a force that turns it back (the invertible-FE rotation of
   FCMat3Polar) and the run goes on by default; a linear element has none, and a hyperelastic energy
   no value there, so that for these the step fails by default (-inverted error) with the located
   error below: step control redoes it with a smaller time step, or the run stops. The J of every
   element is computed at every check, in this one loop */
PetscErrorCode CheckState_FEM(FCBody body, PetscInt step)
{
  FEM               *fem = (FEM *)body->data;
  FCMesh            *m   = &fem->mesh;
  FCInverted        *inv = &fem->inverted;
  PetscReal          nu, nv, count = 0.0;
  const PetscScalar *ul;
  struct {
    double J;
    int    rank;
  } worst              = {PETSC_MAX_REAL, 0}, all; /* MPI_DOUBLE_INT for MPI_MINLOC */
  PetscReal   where[3] = {0, 0, 0};                /* centroid of the worst cell */
  PetscMPIInt rank;

  PetscFunctionBegin;
  PetscCall(VecNorm(fem->u, NORM_INFINITY, &nu));
  PetscCall(VecNorm(fem->v, NORM_INFINITY, &nv));
  PetscCheck(!PetscIsInfOrNanReal(nu) && !PetscIsInfOrNanReal(nv), body->comm, PETSC_ERR_FP,
             "Body '%s' diverged at step %" PetscInt_FMT
             ": its displacement or velocity is NaN or Inf (time step too large?)",
             body->name, step);
  PetscCallMPI(MPI_Comm_rank(body->comm, &rank));
  PetscCall(DMGlobalToLocal(m->dm, fem->u, INSERT_VALUES, fem->uloc));
  PetscCall(VecGetArrayRead(fem->uloc, &ul));
  for (PetscInt c = 0; c < m->cEnd - m->cStart; c++) {
    PetscReal X[12], x[12], F[9], J;
    FCFEMGatherElement(fem, c, ul, X, x);
    FCMaterialDeformationGradient(x, &fem->Dminv[9 * c], F);
    J = FCMat3Det(F);
    if (J <= 0.0) count += 1.0;
    if (J < worst.J) {
      worst.J = (double)J;
      if (J <= 0.0)
        for (int d = 0; d < 3; d++) where[d] = 0.25 * (x[d] + x[3 + d] + x[6 + d] + x[9 + d]);
    }
  }
  PetscCall(VecRestoreArrayRead(fem->uloc, &ul));
  worst.rank = rank;
  PetscCallMPI(MPI_Allreduce(&worst, &all, 1, MPI_DOUBLE_INT, MPI_MINLOC, body->comm)); /* cells: no overlap */
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &count, 1, MPIU_REAL, MPIU_SUM, body->comm));
  inv->count = (PetscInt)count;
  inv->min_J = (PetscReal)all.J;
  if (!inv->count || fem->allow_inverted) PetscFunctionReturn(0);
  PetscCallMPI(MPI_Bcast(where, 3, MPIU_REAL, (PetscMPIInt)all.rank, body->comm));
  {
    char why[256];
    if (fem->mat->hyperelastic)
      PetscCall(PetscStrncpy(why, "The step went past what the material's energy can resist:", sizeof(why)));
    else if (fem->mat->linear)
      PetscCall(PetscStrncpy(why, "The material is a small-strain model and does not resist it:", sizeof(why)));
    else
      PetscCall(PetscSNPrintf(why, sizeof(why),
                              "-%sinverted error makes it a failed step (a co-rotational element would be turned "
                              "back):",
                              body->prefix));
    SETERRQ(body->comm, PETSC_ERR_CONV_FAILED,
            "Body '%s': %" PetscInt_FMT " element(s) turned inside out at step %" PetscInt_FMT
            " (volume ratio J = det F down to %g, at (%g, %g, %g)). %s the body is crushed or stretched through its "
            "own thickness, and its surface crosses itself and what it touches. Make the body stiffer or thicker, "
            "its mesh finer, or -time_step smaller; -%sinverted allow runs on",
            body->name, inv->count, step, (double)all.J, (double)where[0], (double)where[1], (double)where[2], why,
            body->prefix);
  }
}

/* The elements turned inside out, as the last CheckState_FEM counted them */
PetscErrorCode GetInverted_FEM(FCBody body, FCInverted *inv, PetscBool *has)
{
  PetscFunctionBegin;
  *inv = ((FEM *)body->data)->inverted;
  *has = PETSC_TRUE;
  PetscFunctionReturn(0);
}

/* contact_pressure: per owned visual vertex, the normal force of the last step's contacts on it
   (its share w_k lambda_n of each contact it is a vertex of, dormant and open contacts carrying
   none) over its area, a third of its boundary faces' (placed reference areas); 0 on constrained
   vertices, whose contacts the supports take */
PetscErrorCode FCFEMContactPressure(FCBody body, PetscReal out[])
{
  FEM                *fem = (FEM *)body->data;
  FCMesh             *m   = &fem->mesh;
  const FCContactSet *set = body->contacts;
  PetscScalar        *f;
  const PetscScalar  *A;
  PetscInt            lo, hi;

  PetscFunctionBegin;
  if (!fem->varea) { /* the vertex areas, once */
    Vec          al;
    PetscScalar *a;
    PetscCall(VecDuplicate(fem->u, &fem->varea));
    PetscCall(DMGetLocalVector(m->dm, &al));
    PetscCall(VecZeroEntries(al));
    PetscCall(VecGetArray(al, &a));
    for (PetscInt t = 0; t < fem->ntri; t++) {
      const PetscInt *tv = &fem->triv[3 * t];
      PetscReal       e1[3], e2[3], n[3];
      for (int d = 0; d < 3; d++) {
        e1[d] = m->X[3 * tv[1] + d] - m->X[3 * tv[0] + d];
        e2[d] = m->X[3 * tv[2] + d] - m->X[3 * tv[0] + d];
      }
      FCCross(e1, e2, n);
      for (int k = 0; k < 3; k++)
        if (!fem->fixed[tv[k]]) a[fem->ldof[tv[k]]] += PetscSqrtReal(FCDot(n, n)) / 6.0;
    }
    PetscCall(VecRestoreArray(al, &a));
    PetscCall(VecZeroEntries(fem->varea));
    PetscCall(DMLocalToGlobal(m->dm, al, ADD_VALUES, fem->varea));
    PetscCall(DMRestoreLocalVector(m->dm, &al));
  }
  PetscCall(VecGetOwnershipRange(fem->work, &lo, &hi));
  PetscCall(VecZeroEntries(fem->work));
  PetscCall(VecGetArray(fem->work, &f));
  for (PetscInt i = 0; set && i < set->n; i++) { /* the set is the same on every rank: each adds its own rows */
    const FCContact *c = &set->c[i];
    for (int s = 0; s < 2; s++) {
      if (c->body[s] != body->self) continue;
      for (PetscInt k = 0; k < c->prox[s].nv; k++) {
        PetscInt g = c->prox[s].gdof[k];
        if (g >= lo && g < hi) f[g - lo] += c->prox[s].w[k] * PetscAbsReal(c->force[0]);
      }
    }
  }
  PetscCall(VecGetArrayRead(fem->varea, &A));
  for (PetscInt i = 0; i < body->visual.nv; i++) {
    PetscInt v = m->visVert[i], g = fem->gdof[v];
    out[i] = g < 0 || PetscRealPart(A[g - lo]) <= 0.0 ? 0.0 : PetscRealPart(f[g - lo] / A[g - lo]);
  }
  PetscCall(VecRestoreArrayRead(fem->varea, &A));
  PetscCall(VecRestoreArray(fem->work, &f));
  PetscFunctionReturn(0);
}
