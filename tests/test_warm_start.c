/* The warm start of every constraint scheme (src/contact/contactset.c, FCContactSetWarmStart):
   the previous step's world force of the same contact (same pair and side-1 point), projected on
   this step's frame; a new contact starts from zero. Checked against the projection computed here
   on three contacts: one whose normal turned (the force keeps its world direction and magnitude,
   not its frame components), one whose frame did not move (the components carry over to
   round-off), one that is new; and a frictionless contact, which keeps only the normal part. */
/* a unit test of the contact package: its header, not the public API, declares the contact set */
#include "contact/contact.h"

static FCContact Contact(PetscInt pair, PetscReal key, PetscReal nx, PetscReal mu)
{
  FCContact c;
  PetscReal n = PetscSqrtReal(nx * nx + 1.0);
  PetscMemzero(&c, sizeof(c));
  c.pair   = pair;
  c.key[0] = key;
  c.n[0]   = nx / n;
  c.n[2]   = 1.0 / n;
  c.mu     = mu;
  return c;
}

int main(int argc, char **argv)
{
  FCContactSet prev = {0}, set = {0};
  PetscReal    lambda[8], F0[3], err = 0.0;
  FCContact    c;
  int          fails = 0;

  PetscCall(PetscInitialize(&argc, &argv, NULL, NULL));
  /* previous step: two contacts of pair 0 (sorted by key), normals +z, forces in their frames */
  c          = Contact(0, 0.0, 0.0, 0.5);
  c.force[0] = 2.0;
  c.force[1] = 0.5;
  c.force[2] = -0.3;
  PetscCall(FCContactSetAdd(&prev, &c));
  c          = Contact(0, 1.0, 0.0, 0.5);
  c.force[0] = 1.0;
  c.force[1] = 0.25;
  PetscCall(FCContactSetAdd(&prev, &c));
  PetscCall(FCContactSetFinalize(&prev));
  for (int i = 0; i < 3; i++) F0[i] = 2.0 * prev.c[0].n[i] + 0.5 * prev.c[0].t1[i] - 0.3 * prev.c[0].t2[i];
  /* this step: the first contact's normal turned, the second unchanged but frictionless, a new one */
  c = Contact(0, 0.0, 0.3, 0.5);
  PetscCall(FCContactSetAdd(&set, &c));
  c = Contact(0, 1.0, 0.0, 0.0);
  PetscCall(FCContactSetAdd(&set, &c));
  c = Contact(0, 2.0, 0.0, 0.5);
  PetscCall(FCContactSetAdd(&set, &c));
  PetscCall(FCContactSetFinalize(&set));
  for (int i = 0; i < 8; i++) lambda[i] = -99.0;
  FCContactSetWarmStart(&set, &prev, lambda);
  { /* turned: projection of the world force; its magnitude is kept */
    const FCContact *t       = &set.c[0];
    PetscReal        want[3] = {FCDot(t->n, F0), FCDot(t->t1, F0), FCDot(t->t2, F0)}, m2 = 0.0;
    for (int a = 0; a < 3; a++) {
      err = PetscMax(err, PetscAbsReal(lambda[t->row + a] - want[a]));
      m2 += lambda[t->row + a] * lambda[t->row + a];
    }
    fails += err > 1e-14 || PetscAbsReal(m2 - FCDot(F0, F0)) > 1e-13;
    { /* and not the old frame's components (2, 0.5, -0.3), which the projection must not keep */
      PetscReal dold = PetscAbsReal(lambda[t->row] - 2.0) + PetscAbsReal(lambda[t->row + 1] - 0.5) +
                       PetscAbsReal(lambda[t->row + 2] + 0.3);
      fails += dold < 0.1;
    }
    PetscCall(PetscPrintf(PETSC_COMM_WORLD,
                          "turned normal: lambda = (%g, %g, %g), projection error %.1e, |lambda|^2 %.15g vs %.15g\n",
                          (double)lambda[t->row], (double)lambda[t->row + 1], (double)lambda[t->row + 2], (double)err,
                          (double)m2, (double)FCDot(F0, F0)));
  }
  { /* unchanged frame, now frictionless: the normal component only, to round-off */
    const FCContact *u = &set.c[1];
    fails += u->dim != 1 || PetscAbsReal(lambda[u->row] - 1.0) > 1e-15;
    PetscCall(PetscPrintf(PETSC_COMM_WORLD, "unchanged frame, frictionless: lambda = %.17g (want 1)\n",
                          (double)lambda[u->row]));
  }
  { /* new contact: zero */
    const FCContact *w = &set.c[2];
    fails += lambda[w->row] != 0.0 || lambda[w->row + 1] != 0.0 || lambda[w->row + 2] != 0.0;
  }
  /* no previous step: zero everywhere */
  FCContactSetWarmStart(&set, NULL, lambda);
  for (PetscInt r = 0; r < set.nrows; r++) fails += lambda[r] != 0.0;
  PetscCall(FCContactSetDestroy(&prev));
  PetscCall(FCContactSetDestroy(&set));
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "warm start: %s\n", fails ? "FAILED" : "passed"));
  PetscCall(PetscFinalize());
  return fails ? 1 : 0;
}
