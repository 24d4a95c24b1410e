/* The boundary of a body's mesh on this rank: its vertices and outward-oriented faces, checked to
   form closed surfaces. */
#include "../fcimpl.h"
#include <petscsf.h>

/* Boundary of the mesh on this rank: the vertices it owns that lie on a boundary face of any rank
   (over the ranks, every boundary vertex once), and the boundary faces it holds as vertex triples
   (local vertex indices) ordered so that (x1 - x0) x (x2 - x0) points out of the body (the fourth
   vertex of the face's cell is behind it). */
static int CompareEdge(const void *a, const void *b)
{
  const PetscInt *x = (const PetscInt *)a, *y = (const PetscInt *)b;
  if (x[0] != y[0]) return x[0] < y[0] ? -1 : 1;
  return x[1] < y[1] ? -1 : (x[1] > y[1] ? 1 : 0);
}

/* The vertices (local indices) of face f of one cell of this rank, ordered so that
   (x1 - x0) x (x2 - x0) points away from that cell (out of the body on a boundary face) */
PetscErrorCode FCMeshOrientedFace(FCMesh *m, PetscInt f, PetscInt tv[3])
{
  PetscInt       *closure = NULL, ncl, k = 0, cell, opp = -1;
  const PetscInt *supp;
  PetscReal       e1[3], e2[3], nn[3], d[3];

  PetscFunctionBegin;
  PetscCall(DMPlexGetTransitiveClosure(m->dm, f, PETSC_TRUE, &ncl, &closure));
  for (PetscInt i = 0; i < ncl && k < 3; i++)
    if (closure[2 * i] >= m->vStart && closure[2 * i] < m->vEnd) tv[k++] = closure[2 * i] - m->vStart;
  PetscCall(DMPlexRestoreTransitiveClosure(m->dm, f, PETSC_TRUE, &ncl, &closure));
  PetscCall(DMPlexGetSupport(m->dm, f, &supp));
  cell = supp[0] - m->cStart;
  for (int a = 0; a < 4; a++) {
    PetscInt v = m->cellVerts[4 * cell + a] - m->vStart;
    if (v != tv[0] && v != tv[1] && v != tv[2]) opp = v;
  }
  for (int i = 0; i < 3; i++) {
    e1[i] = m->X[3 * tv[1] + i] - m->X[3 * tv[0] + i];
    e2[i] = m->X[3 * tv[2] + i] - m->X[3 * tv[0] + i];
    d[i]  = m->X[3 * opp + i] - m->X[3 * tv[0] + i];
  }
  FCCross(e1, e2, nn);
  if (FCDot(nn, d) > 0) {
    PetscInt t = tv[1];
    tv[1]      = tv[2];
    tv[2]      = t;
  }
  PetscFunctionReturn(0);
}

/* The boundary must be a closed surface: every edge of a boundary triangle in exactly two of
   them (the contact detection and the outward normals rely on it). Edges in global vertex
   numbers, gathered on rank 0. */
static PetscErrorCode CheckClosedSurface(FCMesh *m, PetscInt nt, const PetscInt triv[])
{
  PetscMPIInt     rank, size, n = (PetscMPIInt)(6 * nt), *counts = NULL, *displs = NULL;
  PetscInt       *e, *all = NULL, bad[2] = {0, 0};
  const PetscInt *gv;
  const char     *name;
  MPI_Comm        comm = PetscObjectComm((PetscObject)m->dm);

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCallMPI(MPI_Comm_size(comm, &size));
  PetscCall(ISGetIndices(m->vertexNumbering, &gv));
  PetscCall(PetscMalloc1(6 * nt + 1, &e));
  for (PetscInt t = 0; t < nt; t++)
    for (int a = 0; a < 3; a++) {
      PetscInt g0 = gv[triv[3 * t + a]], g1 = gv[triv[3 * t + (a + 1) % 3]];
      g0                   = g0 < 0 ? -(g0 + 1) : g0;
      g1                   = g1 < 0 ? -(g1 + 1) : g1;
      e[6 * t + 2 * a]     = PetscMin(g0, g1);
      e[6 * t + 2 * a + 1] = PetscMax(g0, g1);
    }
  PetscCall(ISRestoreIndices(m->vertexNumbering, &gv));
  if (!rank) PetscCall(PetscMalloc2(size, &counts, size + 1, &displs));
  PetscCallMPI(MPI_Gather(&n, 1, MPI_INT, counts, 1, MPI_INT, 0, comm));
  if (!rank) {
    displs[0] = 0;
    for (PetscMPIInt r = 0; r < size; r++) displs[r + 1] = displs[r] + counts[r];
    PetscCall(PetscMalloc1(displs[size] + 1, &all));
  }
  PetscCallMPI(MPI_Gatherv(e, n, MPIU_INT, all, counts, displs, MPIU_INT, 0, comm));
  if (!rank) {
    PetscInt ne = displs[size] / 2;
    qsort(all, ne, 2 * sizeof(PetscInt), CompareEdge);
    for (PetscInt i = 0; i < ne && !bad[0];) {
      PetscInt j = i;
      while (j < ne && !CompareEdge(&all[2 * i], &all[2 * j])) j++;
      if (j - i != 2) {
        bad[0] = j - i;
        bad[1] = all[2 * i];
      }
      i = j;
    }
    PetscCall(PetscFree(all));
    PetscCall(PetscFree2(counts, displs));
  }
  PetscCall(PetscFree(e));
  PetscCallMPI(MPI_Bcast(bad, 2, MPIU_INT, 0, comm));
  PetscCall(PetscObjectGetName((PetscObject)m->dm, &name));
  PetscCheck(!bad[0], comm, PETSC_ERR_USER_INPUT,
             "The mesh of body '%s' has a boundary surface that is not closed: an edge at vertex %" PetscInt_FMT
             " belongs to %" PetscInt_FMT " boundary triangles instead of 2 (tetrahedra touching along an edge only?); "
             "contact needs a closed, manifold surface",
             name, bad[1], bad[0]);
  PetscFunctionReturn(0);
}

/* The label "fc_boundary" (value 1 on the boundary faces this rank holds), made at its first use.
   A boundary face has one cell in the whole mesh. A face on the interface between two ranks has
   one cell on each; PETSc 3.18's DMPlexMarkBoundaryFaces marks it on its owner (the cube's 396
   boundary triangles became 476 on 2 ranks), so the support sizes are summed over the point SF */
PetscErrorCode FCMeshBoundaryLabel(FCMesh *m, DMLabel *label)
{
  PetscInt  fStart, fEnd;
  PetscBool has;

  PetscFunctionBegin;
  PetscCall(DMHasLabel(m->dm, "fc_boundary", &has));
  if (!has) {
    PetscSF  sf;
    PetscInt pStart, pEnd, *supp;
    PetscCall(DMPlexGetHeightStratum(m->dm, 1, &fStart, &fEnd));
    PetscCall(DMPlexGetChart(m->dm, &pStart, &pEnd));
    PetscCall(PetscCalloc1(pEnd - pStart, &supp));
    for (PetscInt f = fStart; f < fEnd; f++) PetscCall(DMPlexGetSupportSize(m->dm, f, &supp[f - pStart]));
    PetscCall(DMGetPointSF(m->dm, &sf));
    PetscCall(PetscSFReduceBegin(sf, MPIU_INT, supp, supp, MPI_SUM));
    PetscCall(PetscSFReduceEnd(sf, MPIU_INT, supp, supp, MPI_SUM));
    PetscCall(PetscSFBcastBegin(sf, MPIU_INT, supp, supp, MPI_REPLACE));
    PetscCall(PetscSFBcastEnd(sf, MPIU_INT, supp, supp, MPI_REPLACE));
    PetscCall(DMCreateLabel(m->dm, "fc_boundary"));
    PetscCall(DMGetLabel(m->dm, "fc_boundary", label));
    for (PetscInt f = fStart; f < fEnd; f++) {
      PetscInt ls;
      PetscCall(DMPlexGetSupportSize(m->dm, f, &ls));
      if (supp[f - pStart] == 1 && ls == 1) PetscCall(DMLabelSetValue(*label, f, 1));
    }
    PetscCall(PetscFree(supp));
  } else
    PetscCall(DMGetLabel(m->dm, "fc_boundary", label));
  PetscFunctionReturn(0);
}

PetscErrorCode FCMeshGetBoundary(FCMesh *m, PetscInt *nbv, PetscInt **bv, PetscInt *ntri, PetscInt **triv)
{
  DMLabel    label;
  PetscInt   fStart, fEnd, nv = m->vEnd - m->vStart, nt = 0, nb = 0;
  PetscBool *isb;

  PetscFunctionBegin;
  PetscCall(DMPlexGetHeightStratum(m->dm, 1, &fStart, &fEnd));
  PetscCall(FCMeshBoundaryLabel(m, &label));
  PetscCall(PetscCalloc1(nv, &isb));
  for (PetscInt f = fStart; f < fEnd; f++) {
    PetscInt val;
    PetscCall(DMLabelGetValue(label, f, &val));
    if (val == 1) nt++;
  }
  PetscCall(PetscMalloc1(3 * nt + 1, triv));
  nt = 0;
  for (PetscInt f = fStart; f < fEnd; f++) {
    PetscInt val, *tv = &(*triv)[3 * nt];
    PetscCall(DMLabelGetValue(label, f, &val));
    if (val != 1) continue;
    PetscCall(FCMeshOrientedFace(m, f, tv));
    for (int a = 0; a < 3; a++) isb[tv[a]] = PETSC_TRUE;
    nt++;
  }
  { /* a vertex is on the boundary when any rank holds a boundary face through it: with overlap 0 a
       boundary face lives only on the rank of its one cell, which need not be the vertex's owner, so
       the marks are summed to the owner over the point SF before the ownership filter below (else a
       vertex whose owner holds none of its faces would be nobody's candidate) */
    PetscSF   sf;
    PetscInt  pStart, pEnd;
    PetscInt *mark;
    PetscCall(DMPlexGetChart(m->dm, &pStart, &pEnd));
    PetscCall(PetscCalloc1(pEnd - pStart, &mark));
    for (PetscInt v = 0; v < nv; v++) mark[m->vStart + v - pStart] = isb[v];
    PetscCall(DMGetPointSF(m->dm, &sf));
    PetscCall(PetscSFReduceBegin(sf, MPIU_INT, mark, mark, MPI_MAX));
    PetscCall(PetscSFReduceEnd(sf, MPIU_INT, mark, mark, MPI_MAX));
    for (PetscInt v = 0; v < nv; v++) isb[v] = mark[m->vStart + v - pStart] ? PETSC_TRUE : PETSC_FALSE;
    PetscCall(PetscFree(mark));
  }
  for (PetscInt v = 0; v < nv; v++) nb += (isb[v] && m->owned[v]);
  PetscCall(PetscMalloc1(nb + 1, bv));
  nb = 0;
  for (PetscInt v = 0; v < nv; v++)
    if (isb[v] && m->owned[v]) (*bv)[nb++] = v;
  PetscCall(PetscFree(isb));
  *nbv  = nb;
  *ntri = nt;
  PetscCall(CheckClosedSurface(m, nt, *triv));
  PetscFunctionReturn(0);
}
