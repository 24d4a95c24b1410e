/* What the recursive schemes (standard.c, fast.c) share: their Newton options, the linearization
   of the contacts at the start of the step and its re-linearization at the proximity positions of
   a Newton iteration, and the convergence test. d = p1 - p2 per contact (world), d_free and d0 its
   values after the free motion and at the start of the step.
   Options: -newton_max_it, -newton_tol (help strings below; docs/options.md). */
#include "schemeimpl.h"

PetscErrorCode FCSchemeRecursiveSetFromOptions(FCScheme scheme, PetscOptionItems *PetscOptionsObject)
{
  PetscFunctionBegin;
  scheme->newton_max_it = 5;
  scheme->newton_tol    = 1e-10;
  PetscCall(FCOptionsInt(PetscOptionsObject, "-newton_max_it", "Newton iterations of a recursive scheme",
                         &scheme->newton_max_it, NULL));
  PetscCall(FCOptionsReal(PetscOptionsObject, "-newton_tol",
                          "Stop the Newton iterations when frames and right-hand sides change less",
                          &scheme->newton_tol, NULL));
  PetscCheck(scheme->newton_max_it >= 1, scheme->comm, PETSC_ERR_USER_INPUT,
             "Option -newton_max_it must be >= 1, got %" PetscInt_FMT, scheme->newton_max_it);
  PetscCheck(scheme->newton_tol >= 0, scheme->comm, PETSC_ERR_USER_INPUT, "Option -newton_tol must be >= 0, got %g",
             (double)scheme->newton_tol);
  PetscFunctionReturn(0);
}

/* Frames of every contact at the current F (d = d_free + W_H F already computed) and the
   right-hand side q of the contact problem in those frames */
PetscErrorCode FCSchemeLinearize(FCScheme scheme, FCContactSet *set, const PetscReal dfree[], const PetscReal d0[],
                                 const PetscReal d[], PetscReal q[], PetscReal *frame_change)
{
  PetscFunctionBegin;
  *frame_change = 0.0;
  for (PetscInt k = 0; k < set->n; k++) {
    FCContact *c   = &set->c[k];
    FCBody     B   = scheme->bodies[c->body[1]];
    PetscReal  gap = 0.0, dd[3];
    for (int i = 0; i < 3; i++) dd[i] = d[3 * k + i] - dfree[3 * k + i];
    PetscBool reeval = (PetscBool)(c->side2 == FC_SIDE_SHAPE && FCBodyIsPrescribed(B));
    PetscReal p1[3], n[3], cpb[3];
    if (reeval) { /* its pose at the end of the step is known */
      for (int i = 0; i < 3; i++) p1[i] = c->pfree[0][i] + dd[i];
      PetscCall(FCBodyShapeDistance(B, FC_AT_FREE, p1, &gap, n, cpb));
      /* a contact the continuous detection made where the shape can pass the point within the step (c->swept:
         a sphere orbiting over a ball) keeps its linearization: the shape's end pose may be beyond the point */
      if (c->swept) reeval = PETSC_FALSE;
      { /* on an edge of the shape: the normal it has (the probe's scale: the iteration's motion) */
        PetscBool keep;
        PetscCall(FCBodyShapeKeepsNormal(B, FC_AT_FREE, p1, gap, n, c->n, PetscSqrtReal(FCDot(dd, dd)), &keep));
        if (keep) reeval = PETSC_FALSE; /* its gap linearized along it */
      }
    }
    if (reeval) {
      for (int i = 0; i < 3; i++) *frame_change = PetscMax(*frame_change, PetscAbsReal(n[i] - c->n[i]));
      for (int i = 0; i < 3; i++) c->n[i] = n[i];
      FCContactFrame(c->n, c->t1, c->t2);
      q[c->row] = gap - FCDot(c->n, dd) + c->slack;
    } else
      q[c->row] = FCDot(c->n, &dfree[3 * k]) + c->qcurv + c->slack;
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
PetscBool FCSchemeConverged(FCScheme scheme, PetscInt M, const PetscReal q[], const PetscReal qold[],
                            PetscReal frame_change)
{
  PetscReal dq = 0.0, qs = 0.0;
  for (PetscInt r = 0; r < M; r++) {
    dq = PetscMax(dq, PetscAbsReal(q[r] - qold[r]));
    qs = PetscMax(qs, PetscAbsReal(q[r]));
  }
  return scheme->newton_tol > 0 && frame_change <= scheme->newton_tol &&
                 dq <= scheme->newton_tol * PetscMax(qs, PETSC_SMALL)
             ? PETSC_TRUE
             : PETSC_FALSE;
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
    /* slack: the penetration the step may leave (collision.c); qcurv: a rounded shape's turn (shapepoints.c) */
    q[c->row] = FCDot(c->n, &dfree[3 * k]) + c->qcurv + c->slack;
    if (c->dim == 3) {
      q[c->row + 1] = FCDot(c->t1, rel);
      q[c->row + 2] = FCDot(c->t2, rel);
    }
    mu[k]   = c->mu;
    dims[k] = c->dim;
  }
}
