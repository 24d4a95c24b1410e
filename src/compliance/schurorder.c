/* The fill-reducing ordering of the condensed builder's factorization (schurfactor.c): the interior
   DOFs (A's vertex blocks outside S) by nested dissection of their graph (METIS_NodeND, or with
   -compliance_condensed_balance the top levels balanced bisections of ours), then S last, so that
   MUMPS keeps S as the Schur block. */
#include "complianceimpl.h"
#include <metis.h>

/* The subgraph of (xadj, adj) induced by the n vertices vtx[] (loc: scratch of the graph's size,
   all -1 on entry and on return) */
static PetscErrorCode Induced(const idx_t xadj[], const idx_t adj[], idx_t n, const idx_t vtx[], idx_t loc[],
                              idx_t **sxadj, idx_t **sadj)
{
  idx_t m = 0;

  PetscFunctionBegin;
  for (idx_t i = 0; i < n; i++) {
    loc[vtx[i]] = i;
    m += xadj[vtx[i] + 1] - xadj[vtx[i]];
  }
  PetscCall(PetscMalloc2(n + 1, sxadj, m + 1, sadj));
  m           = 0;
  (*sxadj)[0] = 0;
  for (idx_t i = 0; i < n; i++) {
    for (idx_t k = xadj[vtx[i]]; k < xadj[vtx[i] + 1]; k++)
      if (loc[adj[k]] >= 0) (*sadj)[m++] = loc[adj[k]];
    (*sxadj)[i + 1] = m;
  }
  for (idx_t i = 0; i < n; i++) loc[vtx[i]] = -1;
  PetscFunctionReturn(0);
}

/* Appends to order[*no] the n vertices vtx[] (NULL: all) of the interior graph in a fill-reducing order:
   METIS_NodeND, or with levels > 0 (-compliance_condensed_balance) the top levels of the
   dissection are ours, each a bisection balanced in two constraints at once, the vertex count and
   the count of vertices next to S (touch), with the boundary of the larger side as separator,
   ordered after both halves. Why: METIS_NodeND cuts a cube resting on a face as readily parallel
   to that face as across it; cut parallel, one half holds every front that S's variables widen,
   and MUMPS, which maps the two halves to different ranks, gives one rank most of the flops
   (-info prints the split). Balanced, the split is closer to even, but the step is not faster
   (docs/scaling.md), so it is not the default. */
#define V(i) (vtx ? vtx[i] : (i))
static PetscErrorCode Dissect(const char name[], const idx_t xadj[], const idx_t adj[], const idx_t touch[], idx_t n,
                              const idx_t vtx[], PetscInt levels, idx_t loc[], idx_t order[], idx_t *no)
{
  idx_t *sx = (idx_t *)xadj, *sa = (idx_t *)adj, ntouch = 0; /* vtx NULL: the whole graph, not copied */

  PetscFunctionBegin;
  if (!n) PetscFunctionReturn(0);
  for (idx_t i = 0; i < n; i++) ntouch += touch[V(i)];
  if (vtx) PetscCall(Induced(xadj, adj, n, vtx, loc, &sx, &sa));
  if (levels > 0 && n > 64 && ntouch > 8) { /* METIS needs weight in both constraints */
    idx_t ncon = 2, nparts = 2, cut, *w, *part, *sub, nsub[3] = {0, 0, 0}, big, n1 = 0;
    idx_t opts[METIS_NOPTIONS];
    int   err;
    PetscCall(PetscMalloc3(2 * n, &w, n, &part, n, &sub));
    for (idx_t i = 0; i < n; i++) {
      w[2 * i]     = 1;
      w[2 * i + 1] = touch[V(i)];
    }
    METIS_SetDefaultOptions(opts);
    opts[METIS_OPTION_NUMBERING] = 0;
    err = METIS_PartGraphRecursive(&n, &ncon, sx, sa, w, NULL, NULL, &nparts, NULL, NULL, opts, &cut, part);
    PetscCheck(err == METIS_OK, PETSC_COMM_SELF, PETSC_ERR_LIB,
               "METIS_PartGraphRecursive on A of body '%s' failed (%d)", name, err);
    for (idx_t i = 0; i < n; i++) n1 += part[i];
    big = 2 * n1 > n ? 1 : 0;
    for (idx_t i = 0; i < n; i++) /* the separator: the larger part's vertices with a neighbour in the other */
      if (part[i] == big)
        for (idx_t k = sx[i]; k < sx[i + 1]; k++)
          if (part[sa[k]] == 1 - big) {
            part[i] = 2;
            break;
          }
    for (int p = 0; p < 3; p++) {
      idx_t m = 0;
      for (idx_t i = 0; i < n; i++)
        if (part[i] == p) sub[m++] = V(i);
      nsub[p] = m;
      if (p < 2)
        PetscCall(Dissect(name, xadj, adj, touch, m, sub, levels - 1, loc, order, no));
      else
        for (idx_t i = 0; i < m; i++) order[(*no)++] = sub[i];
    }
    PetscCall(PetscInfo(NULL, "body %s: balanced bisection of %d vertices (%d next to S): %d | %d, separator %d\n",
                        name, (int)n, (int)ntouch, (int)nsub[0], (int)nsub[1], (int)nsub[2]));
    PetscCall(PetscFree3(w, part, sub));
  } else if (n > 2) {
    idx_t *perm, *iperm, opts[METIS_NOPTIONS];
    int    err;
    PetscCall(PetscMalloc2(n, &perm, n, &iperm));
    METIS_SetDefaultOptions(opts);
    opts[METIS_OPTION_NUMBERING] = 0;
    err                          = METIS_NodeND(&n, sx, sa, NULL, opts, perm, iperm);
    PetscCheck(err == METIS_OK, PETSC_COMM_SELF, PETSC_ERR_LIB, "METIS_NodeND on A of body '%s' failed (%d)", name,
               err);
    for (idx_t i = 0; i < n; i++) order[(*no)++] = V(perm[i]);
    PetscCall(PetscFree2(perm, iperm));
  } else
    for (idx_t i = 0; i < n; i++) order[(*no)++] = V(i);
  if (vtx) PetscCall(PetscFree2(sx, sa));
  PetscFunctionReturn(0);
}

#undef V

PetscErrorCode FCSchurOrdering(const char name[], PetscInt nb, const PetscInt gxadj[], const PetscInt gadj[],
                               PetscInt ns, const PetscInt S[], PetscInt N, PetscInt balance, PetscInt perm[])
{
  PetscInt *inS, ni = 0, m = 0;
  idx_t    *xadj, *adj, *touch, *loc, *order, no = 0;

  PetscFunctionBegin;
  PetscCall(PetscCalloc1(nb + 1, &inS));
  for (PetscInt i = 0; i < ns; i += 3) inS[S[i] / 3] = 1;
  for (PetscInt b = 0; b < nb; b++) inS[b] = inS[b] ? -1 : ni++; /* interior index, or -1 */
  PetscCall(PetscMalloc3(ni + 1, &xadj, gxadj[nb] + 1, &adj, ni + 1, &touch));
  PetscCall(PetscMalloc2(ni + 1, &loc, ni + 1, &order));
  xadj[0] = 0;
  for (PetscInt b = 0; b < nb; b++) {
    if (inS[b] < 0) continue;
    touch[inS[b]] = 0;
    for (PetscInt k = gxadj[b]; k < gxadj[b + 1]; k++)
      if (inS[gadj[k]] >= 0)
        adj[m++] = (idx_t)inS[gadj[k]];
      else
        touch[inS[b]] = 1;
    xadj[inS[b] + 1] = (idx_t)m;
  }
  for (PetscInt i = 0; i < ni; i++) loc[i] = -1;
  PetscCall(Dissect(name, xadj, adj, touch, (idx_t)ni, NULL, balance, loc, order, &no));
  PetscCheck(no == (idx_t)ni, PETSC_COMM_SELF, PETSC_ERR_PLIB, "the ordering of body '%s' lost vertices", name);
  for (PetscInt i = 0; i < ni; i++) loc[order[i]] = (idx_t)i; /* loc: the position of each interior vertex */
  for (PetscInt b = 0; b < nb; b++)
    if (inS[b] >= 0)
      for (int d = 0; d < 3; d++) perm[3 * b + d] = (PetscInt)(3 * loc[inS[b]] + d + 1);
  for (PetscInt i = 0; i < ns; i++) perm[S[i]] = 3 * ni + i + 1;
  PetscCall(PetscFree3(xadj, adj, touch));
  PetscCall(PetscFree2(loc, order));
  PetscCall(PetscFree(inS));
  PetscFunctionReturn(0);
}
