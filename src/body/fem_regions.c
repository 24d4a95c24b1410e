/* FE body, what identifies its regions from one run to the next (a restart's check,
   src/io/restartcheck.c): per constraint and per load its kind and its region as given, and per
   constraint the number of its vertices and their centroid in the reference configuration. The
   tables of time may change at a restart, their regions may not: a load or a prescribed motion moved
   to another region, or a region that now names other vertices, is another scene. The figures do not
   depend on the partition, so a restart on another number of ranks compares equal. */
#include "femimpl.h"

/* names: "kind:region" per entry, separated by '\n' (PetscFree it); values: per entry its vertex
   count and their centroid (4 numbers; a load's are 0) (PetscFree it) */
PetscErrorCode GetRegions_FEM(FCBody body, PetscInt *n, char **names, PetscReal **values)
{
  FEM        *fem    = (FEM *)body->data;
  FCMesh     *m      = &fem->mesh;
  const char *kind[] = {"force", "traction", "pressure"};
  PetscInt    ne     = fem->ncons + fem->nload;
  size_t      len    = 1;
  PetscReal  *val;
  char       *s;

  PetscFunctionBegin;
  for (PetscInt k = 0; k < fem->ncons; k++) len += strlen(fem->cons[k].region) + FC_MAX_NAME + 16;
  for (PetscInt l = 0; l < fem->nload; l++) len += strlen(fem->load[l].region) + 16;
  PetscCall(PetscCalloc1(len, &s));
  PetscCall(PetscCalloc1(4 * ne + 1, &val));
  for (PetscInt k = 0; k < fem->ncons; k++) {
    const FCFEMConstraint *c = &fem->cons[k];
    const char            *other;
    if (c->body) PetscCall(FCBodyGetName(c->body, &other));
    PetscCall(PetscStrlcat(s, c->body ? "attach:" : c->moves ? "displacement:" : "fixed:", len));
    if (c->body) {
      PetscCall(PetscStrlcat(s, other, len));
      PetscCall(PetscStrlcat(s, ":", len));
    }
    PetscCall(PetscStrlcat(s, c->region, len));
    PetscCall(PetscStrlcat(s, "\n", len));
    for (PetscInt v = 0; v < m->vEnd - m->vStart; v++) {
      if (fem->creg[v] != k || !m->owned[v]) continue;
      val[4 * k] += 1.0;
      for (int d = 0; d < 3; d++) val[4 * k + 1 + d] += m->X[3 * v + d];
    }
  }
  for (PetscInt l = 0; l < fem->nload; l++) {
    PetscCall(PetscStrlcat(s, kind[fem->load[l].kind], len));
    PetscCall(PetscStrlcat(s, ":", len));
    PetscCall(PetscStrlcat(s, fem->load[l].region, len));
    PetscCall(PetscStrlcat(s, "\n", len));
  }
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, val, 4 * ne, MPIU_REAL, MPIU_SUM, body->comm));
  for (PetscInt k = 0; k < fem->ncons; k++)
    for (int d = 1; d < 4; d++) val[4 * k + d] /= val[4 * k] > 0.0 ? val[4 * k] : 1.0;
  *n      = ne;
  *names  = s;
  *values = val;
  PetscFunctionReturn(0);
}
