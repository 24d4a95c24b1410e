/* Accuracy measures of a step's contacts at the end of the step, on the real geometry
   (FCCollisionEndGaps gives each contact's end gap, end normal and d = p1 - p2). They judge what
   a scheme delivered, independently of the linearization it solved (eq. 18 in its frames):
     penetration      max and RMS over contacts of max(0, -gap_end)                          (m)
     violation        max over contacts of |gap_end| if the contact pushes (F_n above 1e-12 of the
                      largest F_n: a force of round-off pushes nothing), else max(0, -gap_end)
     complementarity  RMS over contacts of the natural-map error ||r - P_K(r - (u + mu |u_T| e_n))||
                      with u = (gap_end, t1e.(d_end - d0), t2e.(d_end - d0)) in the end frame
                      [n_end t1e t2e] and r = W_nn F (the force as the displacement it causes
                      alone, so that r and u are both lengths)                                (m)
     cone violation   max over contacts of (||F_T|| - mu F_n)^+ + (-F_n)^+ in the end frame,
                      relative to the largest contact force (frictionless: any tangential part
                      of F in the end frame is outside the cone)                              (-)
   and the end-of-step check (-contact_check_cone, -contact_check_complementarity: src/collision/pairs.c):
   the contacts beyond either tolerance, and the largest contact's natural-map error. */
#include "contactimpl.h"

void FCContactSetMeasure(const FCContactSet *set, PetscReal cone_tol, PetscReal complementarity_tol,
                         FCContactMeasures *m)
{
  PetscReal pen2 = 0.0, e2 = 0.0, fmax = 0.0, fnmax = 0.0;

  PetscMemzero(m, sizeof(*m));
  for (PetscInt k = 0; k < set->n; k++) {
    PetscReal F[3];
    FCContactForceWorld(&set->c[k], F);
    fnmax = PetscMax(fnmax, set->c[k].force[0]);
    fmax  = PetscMax(fmax, PetscSqrtReal(FCDot(F, F)));
  }
  for (PetscInt k = 0; k < set->n; k++) {
    const FCContact *c = &set->c[k];
    PetscReal        t1[3], t2[3], F[3], Fe[3], r[3], u[3], rel[3], pen = PetscMax(0.0, -c->gap_end), ft, e, cone;
    m->max_penetration = PetscMax(m->max_penetration, pen);
    pen2 += pen * pen;
    m->violation = PetscMax(m->violation, c->force[0] > 1e-12 * fnmax ? PetscAbsReal(c->gap_end) : pen);
    FCContactFrame(c->n_end, t1, t2);
    FCContactForceWorld(c, F);
    for (int i = 0; i < 3; i++) rel[i] = c->d_end[i] - (c->p0[0][i] - c->p0[1][i]);
    Fe[0] = FCDot(F, c->n_end);
    Fe[1] = FCDot(F, t1);
    Fe[2] = FCDot(F, t2);
    u[0]  = c->gap_end;
    u[1]  = FCDot(rel, t1);
    u[2]  = FCDot(rel, t2);
    for (int i = 0; i < 3; i++) r[i] = c->wnn * Fe[i];
    e = FCContactNaturalMapError2(c->dim, c->mu, r, u);
    e2 += e;
    e                      = PetscSqrtReal(e);
    m->max_complementarity = PetscMax(m->max_complementarity, e);
    ft                     = PetscSqrtReal(Fe[1] * Fe[1] + Fe[2] * Fe[2]);
    cone              = PetscMax(0.0, ft - (c->dim == 3 ? c->mu : 0.0) * PetscMax(Fe[0], 0.0)) + PetscMax(0.0, -Fe[0]);
    cone              = fmax > 0.0 ? cone / fmax : 0.0;
    m->cone_violation = PetscMax(m->cone_violation, cone);
    if (cone > cone_tol || e > complementarity_tol) m->beyond++;
  }
  if (set->n) {
    m->rms_penetration = PetscSqrtReal(pen2 / set->n);
    m->complementarity = PetscSqrtReal(e2 / set->n);
  }
}
