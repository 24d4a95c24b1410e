/* Re-linearization of the contacts at the proximity positions of a Newton iteration, shared by the
   recursive schemes (fast.c, standard.c). d = p1 - p2 per contact (world), d_free and d0 its
   values after the free motion and at the start of the step. */
#include "../fcimpl.h"

/* Frames of every contact at the current F (d = d_free + W_H F already computed) and the
   right-hand side q of the contact problem in those frames */
PetscErrorCode FCSchemeLinearize(FCSchemeContext *ctx, const PetscReal dfree[], const PetscReal d0[],
                                 const PetscReal d[], PetscReal q[], PetscReal *frame_change)
{
  FCContactSet *set = ctx->set;

  PetscFunctionBegin;
  *frame_change = 0.0;
  for (PetscInt k = 0; k < set->n; k++) {
    FCContact *c   = &set->c[k];
    FCBody     B   = ctx->bodies[c->body[1]];
    PetscReal  gap = 0.0, dd[3];
    PetscBool  kin;
    PetscCall(PetscStrcmp(B->type, FCBODYKINEMATIC, &kin));
    for (int i = 0; i < 3; i++) dd[i] = d[3 * k + i] - dfree[3 * k + i];
    if (c->side2 == FC_SIDE_SHAPE && kin && B->ops.shapedistancefree && B->shape->distance) {
      PetscReal p1[3], n[3], cpb[3];
      for (int i = 0; i < 3; i++) p1[i] = c->pfree[0][i] + dd[i];
      PetscCall((*B->ops.shapedistancefree)(B, p1, &gap, n, cpb));
      for (int i = 0; i < 3; i++) *frame_change = PetscMax(*frame_change, PetscAbsReal(n[i] - c->n[i]));
      for (int i = 0; i < 3; i++) c->n[i] = n[i];
      FCContactFrame(c->n, c->t1, c->t2);
      q[c->row] = gap - FCDot(c->n, dd);
    } else
      q[c->row] = FCDot(c->n, &dfree[3 * k]);
    if (c->dim == 3) {
      PetscReal rel[3];
      for (int i = 0; i < 3; i++) rel[i] = dfree[3 * k + i] - d0[3 * k + i];
      q[c->row + 1] = FCDot(c->t1, rel);
      q[c->row + 2] = FCDot(c->t2, rel);
    }
  }
  PetscFunctionReturn(0);
}

/* The Newton loop stops when the frames moved by at most newton_tol and the right-hand side
   changed by at most newton_tol relative to its size (never when newton_tol = 0) */
PetscBool FCSchemeConverged(const FCSchemeContext *ctx, PetscInt M, const PetscReal q[], const PetscReal qold[],
                            PetscReal frame_change)
{
  PetscReal dq = 0.0, qs = 0.0;
  for (PetscInt r = 0; r < M; r++) {
    dq = PetscMax(dq, PetscAbsReal(q[r] - qold[r]));
    qs = PetscMax(qs, PetscAbsReal(q[r]));
  }
  return ctx->newton_tol > 0 && frame_change <= ctx->newton_tol && dq <= ctx->newton_tol * PetscMax(qs, PETSC_SMALL)
             ? PETSC_TRUE
             : PETSC_FALSE;
}

/* Contact states from the forces: 0 open, 1 stick, 2 slip (on the cone up to 1e-6) */
void FCContactSetUpdateStates(FCContactSet *set)
{
  for (PetscInt k = 0; k < set->n; k++) {
    FCContact *c  = &set->c[k];
    PetscReal  ft = PetscSqrtReal(c->force[1] * c->force[1] + c->force[2] * c->force[2]);
    c->state      = c->force[0] <= 0.0 ? 0 : (c->dim == 3 && ft >= c->mu * c->force[0] * (1.0 - 1e-6) ? 2 : 1);
  }
}

/* W = h^2 sum_b J_b A_b^-1 J_b^T of the contact set in its frames (identity frames give W_H) */
PetscErrorCode FCSchemeCompliance(PetscInt nbodies, FCBody bodies[], const FCContactSet *set, PetscReal W[])
{
  PetscReal h = nbodies ? bodies[0]->h : 0.0;

  PetscFunctionBegin;
  PetscCall(PetscArrayzero(W, set->nrows * set->nrows));
  for (PetscInt b = 0; b < nbodies; b++)
    if (bodies[b]->ops.addcompliance) PetscCall((*bodies[b]->ops.addcompliance)(bodies[b], b, set, W));
  for (PetscInt k = 0; k < set->nrows * set->nrows; k++) W[k] *= h * h;
  { /* a compliance is symmetric with a non-negative diagonal: anything else is a failed factorization
       or builder, which the contact solver would turn into wrong forces without noticing */
    PetscInt  n = set->nrows, bad = -1, badrow = -1;
    PetscReal wmax = 0.0, asym = 0.0;
    for (PetscInt i = 0; i < n; i++) wmax = PetscMax(wmax, PetscAbsReal(W[i * n + i]));
    for (PetscInt k = 0; k < set->n && bad < 0; k++) {
      const FCContact *c     = &set->c[k];
      PetscBool        moves = PETSC_FALSE; /* W_kk > 0 unless neither side can move at the contact */
      for (PetscInt s = 0; s < 2; s++) {
        PetscBool kinematic;
        PetscCall(PetscStrcmp(bodies[c->body[s]]->type, FCBODYKINEMATIC, &kinematic));
        if (!kinematic && !c->prox[s].nv) moves = PETSC_TRUE; /* rigid */
        for (PetscInt v = 0; v < c->prox[s].nv; v++)          /* FE: a free vertex with a weight */
          moves = moves || (c->prox[s].gdof[v] >= 0 && c->prox[s].w[v] != 0.0);
      }
      for (PetscInt i = c->row; i < c->row + c->dim && bad < 0; i++) {
        PetscReal d = W[i * n + i];
        if (PetscIsInfOrNanReal(d) || d < 0.0 || (moves && d <= 0.0)) {
          bad    = k;
          badrow = i;
        }
        for (PetscInt j = i + 1; j < n; j++) asym = PetscMax(asym, PetscAbsReal(W[i * n + j] - W[j * n + i]));
      }
    }
    if (bad >= 0)
      SETERRQ(bodies[0]->comm, PETSC_ERR_CONV_FAILED,
              "The contact compliance W is not a compliance: W(%" PetscInt_FMT ",%" PetscInt_FMT
              ") = %g (contact %" PetscInt_FMT ", bodies '%s' and '%s'); the factorization or the -compliance_type "
              "builder failed",
              badrow, badrow, (double)W[badrow * n + badrow], bad, bodies[set->c[bad].body[0]]->name,
              bodies[set->c[bad].body[1]]->name);
    PetscCheck(asym <= 1e-8 * wmax, bodies[0]->comm, PETSC_ERR_CONV_FAILED,
               "The contact compliance W is not symmetric (max |W_ij - W_ji| = %g, max W_ii = %g); the factorization "
               "or the -compliance_type builder failed",
               (double)asym, (double)wmax);
  }
  PetscFunctionReturn(0);
}

/* The linearization of the collision detection: d_free = p1 - p2 after the free motion, d0 at
   the start of the step, q = (n . d_free, t . (d_free - d0)) in the start frames, mu and rows */
void FCSchemeStartLinearization(const FCContactSet *set, PetscReal dfree[], PetscReal d0[], PetscReal q[],
                                PetscReal mu[], PetscInt dims[])
{
  for (PetscInt k = 0; k < set->n; k++) {
    const FCContact *c = &set->c[k];
    PetscReal        rel[3];
    for (int i = 0; i < 3; i++) {
      dfree[3 * k + i] = c->pfree[0][i] - c->pfree[1][i];
      d0[3 * k + i]    = c->p0[0][i] - c->p0[1][i];
      rel[i]           = dfree[3 * k + i] - d0[3 * k + i];
    }
    q[c->row] = FCDot(c->n, &dfree[3 * k]);
    if (c->dim == 3) {
      q[c->row + 1] = FCDot(c->t1, rel);
      q[c->row + 2] = FCDot(c->t2, rel);
    }
    mu[k]   = c->mu;
    dims[k] = c->dim;
  }
}

/* World force of the same contact (pair, side-1 point) in the previous step, 0 if it is new */
void FCContactPreviousForce(const FCContactSet *previous, const FCContact *c, PetscReal F[3])
{
  const FCContact *old = previous ? FCContactSetFind(previous, c) : NULL;
  for (int i = 0; i < 3; i++)
    F[i] = old ? old->force[0] * old->n[i] + old->force[1] * old->t1[i] + old->force[2] * old->t2[i] : 0.0;
}

void FCContactSetNormalCompliance(FCContactSet *set, const PetscReal W[])
{
  for (PetscInt k = 0; k < set->n; k++) set->c[k].wnn = W[set->c[k].row * set->nrows + set->c[k].row];
}

/* The statistics of a step before any iteration: its contacts and rows, nothing solved yet */
void FCSchemeStatsReset(const FCContactSet *set, FCSchemeStats *st)
{
  st->contacts = set->n;
  st->rows     = set->nrows;
  st->sweeps   = 0;
  st->residual = 0.0;
  st->newton   = 0;
}
