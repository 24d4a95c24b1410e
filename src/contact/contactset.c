/* FCContactSet: the contacts of one step. Each rank detects the contacts of the surface it
   owns; the set is then gathered on every rank and sorted by (pair, reference position), so the
   contact solver sees the same problem in the same order whatever the partition. */
#include "contactimpl.h"

PetscErrorCode FCContactSetAdd(FCContactSet *set, const FCContact *c)
{
  PetscFunctionBegin;
  if (set->n == set->max) {
    FCContact *tmp;
    set->max = PetscMax(64, 2 * set->max);
    PetscCall(PetscMalloc1(set->max, &tmp));
    if (set->n) PetscCall(PetscArraycpy(tmp, set->c, set->n));
    PetscCall(PetscFree(set->c));
    set->c = tmp;
  }
  set->c[set->n++] = *c;
  PetscFunctionReturn(0);
}

static int CompareContacts(const void *a, const void *b)
{
  const FCContact *x = (const FCContact *)a, *y = (const FCContact *)b;
  if (x->pair != y->pair) return x->pair < y->pair ? -1 : 1;
  for (int i = 0; i < 3; i++)
    if (x->key[i] != y->key[i]) return x->key[i] < y->key[i] ? -1 : 1;
  for (int i = 0; i < 3; i++)
    if (x->prox[1].r[i] != y->prox[1].r[i]) return x->prox[1].r[i] < y->prox[1].r[i] ? -1 : 1;
  return 0;
}

static int CompareKey(const void *a, const void *b)
{
  const FCContact *x = (const FCContact *)a, *y = (const FCContact *)b;
  if (x->pair != y->pair) return x->pair < y->pair ? -1 : 1;
  for (int i = 0; i < 3; i++)
    if (x->key[i] != y->key[i]) return x->key[i] < y->key[i] ? -1 : 1;
  return 0;
}

const FCContact *FCContactSetFind(const FCContactSet *set, const FCContact *c)
{
  PetscInt lo = 0, hi = set->n;
  while (lo < hi) { /* the set is sorted by (pair, key, ...): lower bound on (pair, key) */
    PetscInt mid = (lo + hi) / 2;
    if (CompareKey(&set->c[mid], c) < 0)
      lo = mid + 1;
    else
      hi = mid;
  }
  return lo < set->n && !CompareKey(&set->c[lo], c) ? &set->c[lo] : NULL;
}

PetscErrorCode FCContactSetCopy(const FCContactSet *from, FCContactSet *to)
{
  PetscFunctionBegin;
  if (to->max < from->n) {
    PetscCall(PetscFree(to->c));
    to->max = from->n;
    PetscCall(PetscMalloc1(to->max, &to->c));
  }
  if (from->n) PetscCall(PetscArraycpy(to->c, from->c, from->n));
  to->n             = from->n;
  to->nrows         = from->nrows;
  to->dormant_depth = from->dormant_depth;
  PetscFunctionReturn(0);
}

PetscErrorCode FCContactSetGather(FCContactSet *set, MPI_Comm comm)
{
  PetscMPIInt size;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_size(comm, &size));
  if (size > 1) {
    PetscInt   total;
    FCContact *all;
    PetscCall(FCAllgatherRecords(comm, set->n, sizeof(FCContact), set->c, &total, (void **)&all));
    PetscCall(PetscFree(set->c));
    set->c   = all;
    set->n   = total;
    set->max = total + 1;
  }
  if (set->n > 1) qsort(set->c, set->n, sizeof(FCContact), CompareContacts);
  PetscFunctionReturn(0);
}

void FCContactForceWorld(const FCContact *c, PetscReal F[3])
{
  for (int i = 0; i < 3; i++) F[i] = c->force[0] * c->n[i] + c->force[1] * c->t1[i] + c->force[2] * c->t2[i];
}

void FCContactFrame(const PetscReal n[3], PetscReal t1[3], PetscReal t2[3])
{
  PetscReal e[3] = {1, 0, 0}, nn;
  if (PetscAbsReal(n[0]) > 0.6) {
    e[0] = 0;
    e[1] = 1;
  }
  FCCross(n, e, t1);
  nn = PetscSqrtReal(FCDot(t1, t1));
  for (int i = 0; i < 3; i++) t1[i] /= nn;
  FCCross(n, t1, t2);
}

/* Tangents t1, t2 completing n (frame C_i = [n t1 t2], only n when mu = 0) and row offsets */
PetscErrorCode FCContactSetFinalize(FCContactSet *set)
{
  PetscFunctionBegin;
  set->nrows = 0;
  for (PetscInt k = 0; k < set->n; k++) {
    FCContact *c = &set->c[k];
    FCContactFrame(c->n, c->t1, c->t2);
    c->dim = c->mu > 0.0 ? 3 : 1;
    c->row = set->nrows;
    set->nrows += c->dim;
  }
  PetscFunctionReturn(0);
}

PetscErrorCode FCContactSetReset(FCContactSet *set)
{
  PetscFunctionBegin;
  set->n     = 0;
  set->nrows = 0;
  PetscFunctionReturn(0);
}

PetscErrorCode FCContactSetDestroy(FCContactSet *set)
{
  PetscFunctionBegin;
  PetscCall(PetscFree(set->c));
  set->n = set->max = set->nrows = 0;
  PetscFunctionReturn(0);
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

void FCContactSetWarmStart(const FCContactSet *set, const FCContactSet *previous, PetscReal lambda[])
{
  for (PetscInt k = 0; k < set->n; k++) {
    const FCContact *c = &set->c[k];
    PetscReal        F[3];
    FCContactPreviousForce(previous, c, F);
    for (PetscInt a = 0; a < c->dim; a++) lambda[c->row + a] = FCDot(a == 0 ? c->n : (a == 1 ? c->t1 : c->t2), F);
  }
}

void FCContactSetStoreForces(FCContactSet *set, const PetscReal lambda[])
{
  for (PetscInt k = 0; k < set->n; k++) {
    FCContact *c = &set->c[k];
    for (PetscInt a = 0; a < 3; a++) c->force[a] = a < c->dim ? lambda[c->row + a] : 0.0;
  }
}

PetscErrorCode FCContactSetDormantMask(const FCContactSet *set, PetscBool **mask, PetscReal *depth)
{
  PetscBool any = PETSC_FALSE;

  PetscFunctionBegin;
  *mask  = NULL;
  *depth = set->dormant_depth;
  for (PetscInt k = 0; k < set->n; k++) any = any || set->c[k].dormant;
  if (!any) PetscFunctionReturn(0);
  PetscCall(PetscMalloc1(set->n, mask));
  for (PetscInt k = 0; k < set->n; k++) (*mask)[k] = set->c[k].dormant;
  PetscFunctionReturn(0);
}

PetscErrorCode FCContactSetDormantRestore(FCContactSet *set, PetscBool **mask)
{
  PetscFunctionBegin;
  if (!*mask) PetscFunctionReturn(0);
  for (PetscInt k = 0; k < set->n; k++) set->c[k].dormant = (*mask)[k];
  PetscCall(PetscFree(*mask));
  PetscFunctionReturn(0);
}
