/* Discrete collision detection at the start of the step (DESIGN.md section 2, step 2).
   For each contact pair, the candidate points of one side (owned boundary vertices of an FE
   body, or the points of a rigid shape) are tested against the signed distance of the other
   side's analytic shape; a point closer than -contact_distance makes a contact whose normal is
   the shape's outward normal at the closest point. The proximity point on the shape side is that
   closest point, fixed in the shape's body frame (so it moves rigidly with it within the step). */
#include "../fcimpl.h"

static PetscBool HasShape(FCBody b)
{
  return b->ops.shapedistance ? PETSC_TRUE : PETSC_FALSE;
}

/* Which side gives points (side 1) and which gives the shape (side 2): an FE body gives points;
   between two shape bodies, a rigid one with a bounded shape does */
static PetscErrorCode Sides(FCBody a, FCBody b, PetscInt ia, PetscInt ib, PetscInt *ipts, PetscInt *ishp)
{
  PetscBool afem, bfem, arigid, brigid;

  PetscFunctionBegin;
  PetscCall(PetscStrcmp(a->type, FCBODYFEM, &afem));
  PetscCall(PetscStrcmp(b->type, FCBODYFEM, &bfem));
  PetscCall(PetscStrcmp(a->type, FCBODYRIGID, &arigid));
  PetscCall(PetscStrcmp(b->type, FCBODYRIGID, &brigid));
  PetscCheck(!(afem && bfem), a->comm, PETSC_ERR_SUP,
             "Contact between two FE bodies ('%s', '%s') is not implemented yet", a->name, b->name);
  *ipts = ia;
  *ishp = ib;
  if (bfem || (!afem && !(arigid && a->shape->bounded) && brigid && b->shape->bounded)) {
    *ipts = ib;
    *ishp = ia;
  }
  PetscFunctionReturn(0);
}

PetscErrorCode FCCollisionDetect(MPI_Comm comm, PetscInt nbodies, FCBody bodies[], const FCContactPairs *pairs,
                                 FCContactSet *set)
{
  PetscMPIInt rank;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCall(FCContactSetReset(set));
  for (PetscInt p = 0; p < pairs->n; p++) {
    PetscInt     ipts = 0, ishp = 0, n;
    FCBody       P, S;
    FCProximity *prox;
    PetscReal   *x0, *xf, *key;

    PetscCall(Sides(bodies[pairs->body[p][0]], bodies[pairs->body[p][1]], pairs->body[p][0], pairs->body[p][1], &ipts,
                    &ishp));
    P = bodies[ipts];
    S = bodies[ishp];
    PetscCheck(P->ops.contactpoints && HasShape(S), comm, PETSC_ERR_SUP,
               "Contact between '%s' (%s) and '%s' (%s) is not implemented yet", P->name, P->type, S->name, S->type);
    PetscCall((*P->ops.contactpoints)(P, &n, &prox, &x0, &xf, &key));
    for (PetscInt i = 0; i < n; i++) {
      PetscReal d, nrm[3], cpb[3];
      FCContact c;
      PetscCall((*S->ops.shapedistance)(S, &x0[3 * i], &d, nrm, cpb));
      if (d >= pairs->distance) continue;
      PetscCall(PetscMemzero(&c, sizeof(c)));
      c.pair    = p;
      c.body[0] = ipts;
      c.body[1] = ishp;
      c.prox[0] = prox[i];
      for (int k = 0; k < 3; k++) {
        c.prox[1].r[k] = cpb[k];
        c.key[k]       = key[3 * i + k];
        c.n[k]         = nrm[k];
        c.p0[0][k]     = x0[3 * i + k];
        c.pfree[0][k]  = xf[3 * i + k];
      }
      PetscCall((*S->ops.proximityposition)(S, &c.prox[1], FC_AT_START, c.p0[1]));
      PetscCall((*S->ops.proximityposition)(S, &c.prox[1], FC_AT_FREE, c.pfree[1]));
      c.gap0  = d;
      c.mu    = pairs->mu[p];
      c.owner = rank;
      PetscCall(FCContactSetAdd(set, &c));
    }
  }
  PetscCall(FCContactSetGather(set, comm));
  PetscCall(FCContactSetFinalize(set));
  PetscFunctionReturn(0);
}

PetscErrorCode FCCollisionEndGaps(MPI_Comm comm, PetscInt nbodies, FCBody bodies[], FCContactSet *set,
                                  PetscReal *maxpen)
{
  PetscMPIInt rank;
  PetscReal  *g, minimum = PETSC_MAX_REAL;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCall(PetscCalloc1(set->n + 1, &g));
  for (PetscInt k = 0; k < set->n; k++) {
    FCContact *c = &set->c[k];
    PetscReal  x[3], n[3], cpb[3];
    if (c->owner != rank) continue;
    PetscCall((*bodies[c->body[0]]->ops.proximityposition)(bodies[c->body[0]], &c->prox[0], FC_AT_NOW, x));
    PetscCall((*bodies[c->body[1]]->ops.shapedistance)(bodies[c->body[1]], x, &g[k], n, cpb));
  }
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, g, set->n, MPIU_REAL, MPIU_SUM, comm));
  for (PetscInt k = 0; k < set->n; k++) {
    set->c[k].gap_end = g[k];
    minimum           = PetscMin(minimum, g[k]);
  }
  *maxpen = set->n ? PetscMax(0.0, -minimum) : 0.0;
  PetscCall(PetscFree(g));
  PetscFunctionReturn(0);
}
