/* The tetrahedral mesh of a body: read through the body's DMPlex options
   (-<body>_dm_plex_filename and every other -<body>_dm_* option: refinement, distribution with
   -<body>_petscpartitioner_type ...), validated (3D, tetrahedra only, positive volumes), with
   per-cell vertex lists in a positively oriented order and placed reference coordinates. */
#include "../fcimpl.h"
#include <petscsf.h>

/* -<body>_petscpartitioner_type (default ptscotch; metis: src/mesh/partmetis.c), or the partition of
   an earlier run (-<body>_partition_file: src/mesh/partreplay.c). Each cell keeps its index in the
   mesh as read (cellOrigin: the root of the migration SF), which the output records with the rank
   that holds it, so that a run can be replayed on the same partition */
static PetscErrorCode Distribute(MPI_Comm comm, const char prefix[], const char bodyname[], PetscBool distribute,
                                 FCMesh *mesh)
{
  PetscPartitioner part;
  DM               pdm       = NULL;
  PetscSF          migration = NULL;
  PetscMPIInt      size;
  PetscInt         sStart, sEnd;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_size(comm, &size));
  PetscCall(DMPlexGetHeightStratum(mesh->dm, 0, &sStart, &sEnd));
  if (distribute) {
    PetscCall(DMPlexGetPartitioner(mesh->dm, &part));
    PetscCall(PetscObjectSetOptionsPrefix((PetscObject)part, prefix));
    PetscCall(PetscPartitionerSetType(part, PETSCPARTITIONERPTSCOTCH));
    PetscCall(PetscPartitionerSetFromOptions(part));
    PetscCall(FCMeshPartitionReplay(mesh->dm, part, prefix, bodyname));
    if (size > 1) PetscCall(DMPlexDistribute(mesh->dm, 0, &migration, &pdm));
  }
  if (pdm) {
    PetscCall(DMDestroy(&mesh->dm));
    mesh->dm = pdm;
    PetscCall(PetscObjectSetName((PetscObject)mesh->dm, bodyname));
    PetscCall(DMSetOptionsPrefix(mesh->dm, prefix));
  }
  PetscCall(DMPlexGetHeightStratum(mesh->dm, 0, &mesh->cStart, &mesh->cEnd));
  PetscCall(PetscMalloc1(mesh->cEnd - mesh->cStart + 1, &mesh->cellOrigin));
  for (PetscInt c = mesh->cStart; c < mesh->cEnd; c++) mesh->cellOrigin[c - mesh->cStart] = c - sStart;
  if (migration) {
    PetscInt           nleaves;
    const PetscInt    *ilocal;
    const PetscSFNode *iremote;
    PetscCall(PetscSFGetGraph(migration, NULL, &nleaves, &ilocal, &iremote));
    for (PetscInt i = 0; i < nleaves; i++) {
      PetscInt p = ilocal ? ilocal[i] : i;
      if (p >= mesh->cStart && p < mesh->cEnd) mesh->cellOrigin[p - mesh->cStart] = iremote[i].index - sStart;
    }
    PetscCall(PetscSFDestroy(&migration));
  }
  PetscFunctionReturn(0);
}

/* A 3D mesh of tetrahedra only, with at least one cell */
static PetscErrorCode CheckTetrahedra(MPI_Comm comm, const char fname[], const char bodyname[], FCMesh *mesh)
{
  PetscInt dim, bad = 0, nc;

  PetscFunctionBegin;
  PetscCall(DMViewFromOptions(mesh->dm, NULL, "-dm_view"));
  PetscCall(DMGetDimension(mesh->dm, &dim));
  PetscCheck(dim == 3, comm, PETSC_ERR_USER_INPUT,
             "Mesh '%s' of body '%s' is %" PetscInt_FMT "-dimensional; fecontact needs a 3D tetrahedral mesh", fname,
             bodyname, dim);
  PetscCall(DMPlexGetHeightStratum(mesh->dm, 0, &mesh->cStart, &mesh->cEnd));
  PetscCall(DMPlexGetDepthStratum(mesh->dm, 0, &mesh->vStart, &mesh->vEnd));
  for (PetscInt cell = mesh->cStart; cell < mesh->cEnd; cell++) {
    DMPolytopeType ct;
    PetscCall(DMPlexGetCellType(mesh->dm, cell, &ct));
    if (ct != DM_POLYTOPE_TETRAHEDRON) bad = 1;
  }
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &bad, 1, MPIU_INT, MPI_MAX, comm));
  PetscCheck(!bad, comm, PETSC_ERR_USER_INPUT,
             "Mesh '%s' of body '%s' has cells that are not tetrahedra (P1 tetrahedra only)", fname, bodyname);
  nc = mesh->cEnd - mesh->cStart;
  {
    PetscInt ncg;
    PetscCall(MPIU_Allreduce(&nc, &ncg, 1, MPIU_INT, MPI_SUM, comm));
    PetscCheck(ncg > 0, comm, PETSC_ERR_USER_INPUT, "Mesh '%s' of body '%s' has no cells", fname, bodyname);
  }

  PetscFunctionReturn(0);
}

/* Vertex lists; PETSc's closure order of a tet has a negative triple product, swapping the
   second and third vertices makes valid cells positive for the kernels in tet.c */
static PetscErrorCode CellVertices(MPI_Comm comm, const char fname[], const char bodyname[], FCMesh *mesh)
{
  PetscInt bad = 0, nc = mesh->cEnd - mesh->cStart;

  PetscFunctionBegin;
  PetscCall(PetscMalloc1(4 * nc, &mesh->cellVerts));
  for (PetscInt cell = mesh->cStart; cell < mesh->cEnd; cell++) {
    PetscInt *closure = NULL, n, k = 0, *cv = &mesh->cellVerts[4 * (cell - mesh->cStart)];
    PetscCall(DMPlexGetTransitiveClosure(mesh->dm, cell, PETSC_TRUE, &n, &closure));
    for (PetscInt i = 0; i < n; i++) {
      PetscInt p = closure[2 * i];
      if (p >= mesh->vStart && p < mesh->vEnd) {
        PetscCheck(k < 4, PETSC_COMM_SELF, PETSC_ERR_PLIB, "Tetrahedron with more than 4 vertices");
        cv[k++] = p;
      }
    }
    PetscCall(DMPlexRestoreTransitiveClosure(mesh->dm, cell, PETSC_TRUE, &n, &closure));
    if (k < 4) bad = 1; /* an element naming a missing or repeated node: cv[k..3] unset */
    {
      PetscInt t = cv[1];
      cv[1]      = cv[2];
      cv[2]      = t;
    }
  }

  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &bad, 1, MPIU_INT, MPI_MAX, comm));
  PetscCheck(!bad, comm, PETSC_ERR_USER_INPUT,
             "Mesh '%s' of body '%s' has a tetrahedron without 4 distinct vertices (missing or repeated node)", fname,
             bodyname);
  PetscFunctionReturn(0);
}

/* Reference coordinates per local vertex: 3 per vertex, and none elsewhere (a second-order mesh's
   coordinates live on edges and cells too, and its vertices have none of their own), finite */
static PetscErrorCode ReferenceCoordinates(MPI_Comm comm, const char prefix[], const char fname[],
                                           const char bodyname[], FCMesh *mesh)
{
  Vec                coords;
  PetscSection       csec;
  const PetscScalar *c;

  PetscFunctionBegin;
  PetscCall(PetscMalloc2(3 * (mesh->vEnd - mesh->vStart), &mesh->X, mesh->vEnd - mesh->vStart, &mesh->owned));
  PetscCall(DMGetCoordinatesLocal(mesh->dm, &coords));
  PetscCall(DMGetCoordinateSection(mesh->dm, &csec));
  {
    PetscInt pStart, pEnd, highorder = 0;
    PetscCall(PetscSectionGetChart(csec, &pStart, &pEnd));
    for (PetscInt p = pStart; p < pEnd; p++) {
      PetscInt dof;
      PetscCall(PetscSectionGetDof(csec, p, &dof));
      if (p >= mesh->vStart && p < mesh->vEnd ? dof != 3 : dof != 0) highorder = 1;
    }
    if (mesh->vEnd > mesh->vStart && (mesh->vStart < pStart || mesh->vEnd > pEnd)) highorder = 1;
    PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &highorder, 1, MPIU_INT, MPI_MAX, comm));
    PetscCheck(!highorder, comm, PETSC_ERR_USER_INPUT,
               "Mesh '%s' of body '%s' (-%sdm_plex_filename) is not a first-order mesh: its coordinates are not 3 per "
               "vertex (second-order, 10-node tetrahedra?); fecontact needs linear 4-node tetrahedra: mesh it again "
               "with gmsh -order 1 (Mesh.ElementOrder = 1)",
               fname, bodyname, prefix);
  }
  PetscCall(VecGetArrayRead(coords, &c));
  for (PetscInt v = mesh->vStart; v < mesh->vEnd; v++) {
    PetscInt off;
    PetscCall(PetscSectionGetOffset(csec, v, &off));
    for (PetscInt d = 0; d < 3; d++) mesh->X[3 * (v - mesh->vStart) + d] = PetscRealPart(c[off + d]);
  }
  PetscCall(VecRestoreArrayRead(coords, &c));
  { /* finite and below FC_MESH_MAX_COORDINATE in magnitude (metres): a cell's volume, of the
       cube of its size, stays finite; the first vertex that is not, by its global number */
    PetscInt        first  = PETSC_MAX_INT, gfirst;
    PetscReal       bad[3] = {0, 0, 0};
    const PetscInt *gv;
    PetscCall(DMPlexGetVertexNumbering(mesh->dm, &mesh->vertexNumbering));
    PetscCall(ISGetIndices(mesh->vertexNumbering, &gv));
    for (PetscInt v = 0; v < mesh->vEnd - mesh->vStart; v++) {
      PetscInt g = gv[v] < 0 ? -(gv[v] + 1) : gv[v];
      for (int d = 0; d < 3; d++) {
        PetscReal x = mesh->X[3 * v + d];
        if (!(PetscAbsReal(x) <= FC_MESH_MAX_COORDINATE) && g < first) {
          first = g;
          for (int e = 0; e < 3; e++) bad[e] = mesh->X[3 * v + e];
        }
      }
    }
    PetscCall(ISRestoreIndices(mesh->vertexNumbering, &gv));
    PetscCall(MPIU_Allreduce(&first, &gfirst, 1, MPIU_INT, MPI_MIN, comm));
    if (first != gfirst) bad[0] = bad[1] = bad[2] = 0.0;
    PetscCall(MPIU_Allreduce(MPI_IN_PLACE, bad, 3, MPIU_REAL, MPIU_SUM, comm));
    PetscCheck(gfirst == PETSC_MAX_INT, comm, PETSC_ERR_USER_INPUT,
               "Mesh '%s' of body '%s' (-%sdm_plex_filename): vertex %" PetscInt_FMT
               " (0-based, PETSc numbering) is at (%g, %g, %g); vertex coordinates must be finite numbers of magnitude "
               "at most %g (metres): check the file's coordinates and units",
               fname, bodyname, prefix, gfirst, (double)bad[0], (double)bad[1], (double)bad[2],
               (double)FC_MESH_MAX_COORDINATE);
  }
  PetscFunctionReturn(0);
}

/* Read, distribute, check: the mesh of a body, with per-cell vertex lists and reference coordinates */
PetscErrorCode FCMeshLoad(MPI_Comm comm, const char prefix[], const char bodyname[], FCMesh *mesh)
{
  char      fname[PETSC_MAX_PATH_LEN];
  PetscBool distribute;

  PetscFunctionBegin;
  PetscCall(PetscMemzero(mesh, sizeof(*mesh)));
  PetscCall(FCMeshRead(comm, prefix, bodyname, mesh, fname, &distribute));
  PetscCall(Distribute(comm, prefix, bodyname, distribute, mesh));
  PetscCall(CheckTetrahedra(comm, fname, bodyname, mesh));
  PetscCall(CellVertices(comm, fname, bodyname, mesh));
  PetscCall(ReferenceCoordinates(comm, prefix, fname, bodyname, mesh));
  PetscCall(DMPlexGetCellNumbering(mesh->dm, &mesh->cellNumbering));
  {
    const PetscInt *gv;
    PetscCall(ISGetIndices(mesh->vertexNumbering, &gv));
    for (PetscInt v = mesh->vStart; v < mesh->vEnd; v++)
      mesh->owned[v - mesh->vStart] = gv[v - mesh->vStart] >= 0 ? PETSC_TRUE : PETSC_FALSE;
    PetscCall(ISRestoreIndices(mesh->vertexNumbering, &gv));
  }
  PetscFunctionReturn(0);
}

/* X <- R (X - center) + center + t */
PetscErrorCode FCMeshTransform(FCMesh *mesh, const PetscReal center[3], const PetscReal R[9], const PetscReal t[3])
{
  PetscFunctionBegin;
  if (R[0] == 1.0 && R[4] == 1.0 && R[8] == 1.0) { /* no rotation: keep the file's coordinates exact */
    for (PetscInt v = 0; v < mesh->vEnd - mesh->vStart; v++)
      for (int i = 0; i < 3; i++) mesh->X[3 * v + i] += t[i];
    PetscFunctionReturn(0);
  }
  for (PetscInt v = 0; v < mesh->vEnd - mesh->vStart; v++) {
    PetscReal d[3], r[3];
    for (int i = 0; i < 3; i++) d[i] = mesh->X[3 * v + i] - center[i];
    FCMat3Vec(R, d, r);
    for (int i = 0; i < 3; i++) mesh->X[3 * v + i] = r[i] + center[i] + t[i];
  }
  PetscFunctionReturn(0);
}

/* Every cell must have a positive volume: a zero or negative one (degenerate or inverted
   element in the file) is an error that names the first such cell by its global number. */
PetscErrorCode FCMeshCheckCells(FCMesh *mesh, const char bodyname[])
{
  MPI_Comm        comm;
  PetscInt        first[2] = {PETSC_MAX_INT, 0}; /* global cell, kind: 1 degenerate 2 inverted */
  const PetscInt *gc;

  PetscFunctionBegin;
  PetscCall(PetscObjectGetComm((PetscObject)mesh->dm, &comm));
  PetscCall(ISGetIndices(mesh->cellNumbering, &gc));
  for (PetscInt cell = mesh->cStart; cell < mesh->cEnd; cell++) {
    PetscReal X[12], Dminv[9], vol, h2 = 0.0;
    PetscInt  g = gc[cell - mesh->cStart];
    for (int a = 0; a < 4; a++)
      for (int d = 0; d < 3; d++)
        X[3 * a + d] = mesh->X[3 * (mesh->cellVerts[4 * (cell - mesh->cStart) + a] - mesh->vStart) + d];
    for (int a = 1; a < 4; a++)
      for (int d = 0; d < 3; d++) h2 = PetscMax(h2, PetscSqr(X[3 * a + d] - X[d]));
    PetscCall(FCTetReference(X, Dminv, &vol));
    if (g < 0) g = -(g + 1);
    if (vol <= 1e-12 * h2 * PetscSqrtReal(h2) && g < first[0]) {
      first[0] = g;
      first[1] = vol < 0 ? 2 : 1;
    }
  }
  PetscCall(ISRestoreIndices(mesh->cellNumbering, &gc));
  {
    PetscInt gmin;
    PetscCall(MPIU_Allreduce(&first[0], &gmin, 1, MPIU_INT, MPI_MIN, comm));
    if (first[0] != gmin) first[1] = 0;
    PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &first[1], 1, MPIU_INT, MPI_MAX, comm));
    PetscCheck(gmin == PETSC_MAX_INT, comm, PETSC_ERR_USER_INPUT,
               "Mesh of body '%s': cell %" PetscInt_FMT " (0-based, PETSc numbering) is %s", bodyname, gmin,
               first[1] == 2 ? "inverted (negative volume)" : "degenerate (zero volume)");
  }
  PetscFunctionReturn(0);
}

/* Volume, centroid and inertia per unit density about the centroid:
   int x x^T over a tet = V/20 (sum_a x_a x_a^T + s s^T), s = sum_a x_a. */
PetscErrorCode FCMeshComputeMassProperties(FCMesh *mesh, PetscReal *volume, PetscReal centroid[3], PetscReal J[9])
{
  MPI_Comm  comm;
  PetscReal acc[13] = {0}; /* V, int x (3), int x x^T (9) */

  PetscFunctionBegin;
  PetscCall(PetscObjectGetComm((PetscObject)mesh->dm, &comm));
  for (PetscInt cell = mesh->cStart; cell < mesh->cEnd; cell++) {
    PetscReal X[12], Dminv[9], V, s[3] = {0, 0, 0};
    for (int a = 0; a < 4; a++)
      for (int d = 0; d < 3; d++)
        X[3 * a + d] = mesh->X[3 * (mesh->cellVerts[4 * (cell - mesh->cStart) + a] - mesh->vStart) + d];
    PetscCall(FCTetReference(X, Dminv, &V));
    for (int a = 0; a < 4; a++)
      for (int d = 0; d < 3; d++) s[d] += X[3 * a + d];
    acc[0] += V;
    for (int d = 0; d < 3; d++) acc[1 + d] += V * s[d] / 4.0;
    for (int i = 0; i < 3; i++)
      for (int j = 0; j < 3; j++) {
        PetscReal sum = s[i] * s[j];
        for (int a = 0; a < 4; a++) sum += X[3 * a + i] * X[3 * a + j];
        acc[4 + 3 * i + j] += V / 20.0 * sum;
      }
  }
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, acc, 13, MPIU_REAL, MPIU_SUM, comm));
  *volume = acc[0];
  for (int d = 0; d < 3; d++) centroid[d] = acc[1 + d] / acc[0];
  {
    PetscReal S[9], tr;
    for (int i = 0; i < 3; i++)
      for (int j = 0; j < 3; j++) S[3 * i + j] = acc[4 + 3 * i + j] - acc[0] * centroid[i] * centroid[j];
    tr = S[0] + S[4] + S[8];
    for (int i = 0; i < 9; i++) J[i] = (i % 4 == 0 ? tr : 0.0) - S[i];
  }
  PetscFunctionReturn(0);
}

static int CompareGlobal(const void *a, const void *b)
{
  const PetscInt *x = (const PetscInt *)a, *y = (const PetscInt *)b;
  return (x[0] > y[0]) - (x[0] < y[0]);
}

/* Owned vertices in increasing global number (a contiguous range per rank) and owned cells */
PetscErrorCode FCMeshCreateVisual(FCMesh *mesh, FCBodyVisual *vis)
{
  MPI_Comm        comm;
  const PetscInt *gv, *gc;
  PetscInt       *pairs, nv = 0, nc = 0, k;

  PetscFunctionBegin;
  PetscCall(PetscObjectGetComm((PetscObject)mesh->dm, &comm));
  PetscCall(ISGetIndices(mesh->vertexNumbering, &gv));
  PetscCall(ISGetIndices(mesh->cellNumbering, &gc));
  for (PetscInt v = 0; v < mesh->vEnd - mesh->vStart; v++) nv += gv[v] >= 0;
  for (PetscInt c = 0; c < mesh->cEnd - mesh->cStart; c++) nc += gc[c] >= 0;
  PetscCall(PetscMalloc1(2 * nv, &pairs));
  k = 0;
  for (PetscInt v = 0; v < mesh->vEnd - mesh->vStart; v++)
    if (gv[v] >= 0) {
      pairs[2 * k]     = gv[v];
      pairs[2 * k + 1] = v;
      k++;
    }
  if (nv) qsort(pairs, nv, 2 * sizeof(PetscInt), CompareGlobal); /* a rank may own no vertex (pairs NULL) */
  vis->nv     = nv;
  vis->vstart = nv ? pairs[0] : 0;
  vis->nvpc   = 4;
  for (PetscInt i = 0; i < nv; i++)
    PetscCheck(pairs[2 * i] == vis->vstart + i, PETSC_COMM_SELF, PETSC_ERR_PLIB,
               "Owned vertex numbers are not contiguous");
  PetscCall(PetscMalloc1(3 * nv, &vis->reference));
  PetscCall(PetscMalloc1(nv, &mesh->visVert));
  for (PetscInt i = 0; i < nv; i++) {
    mesh->visVert[i] = pairs[2 * i + 1];
    for (int d = 0; d < 3; d++) vis->reference[3 * i + d] = mesh->X[3 * pairs[2 * i + 1] + d];
  }
  PetscCall(PetscFree(pairs));
  vis->nc = nc;
  PetscCall(PetscMalloc1(4 * nc, &vis->cells));
  PetscCall(PetscMalloc1(nc + 1, &vis->origin));
  k           = 0;
  vis->cstart = PETSC_MAX_INT;
  for (PetscInt c = 0; c < mesh->cEnd - mesh->cStart; c++) {
    if (gc[c] < 0) continue;
    vis->cstart    = PetscMin(vis->cstart, gc[c]);
    vis->origin[k] = mesh->cellOrigin[c];
    for (int a = 0; a < 4; a++) {
      PetscInt g            = gv[mesh->cellVerts[4 * c + a] - mesh->vStart];
      vis->cells[4 * k + a] = g >= 0 ? g : -(g + 1);
    }
    k++;
  }
  if (!nc) vis->cstart = 0;
  PetscCall(ISRestoreIndices(mesh->vertexNumbering, &gv));
  PetscCall(ISRestoreIndices(mesh->cellNumbering, &gc));
  PetscCall(MPIU_Allreduce(&vis->nv, &vis->nv_global, 1, MPIU_INT, MPI_SUM, comm));
  PetscCall(MPIU_Allreduce(&vis->nc, &vis->nc_global, 1, MPIU_INT, MPI_SUM, comm));
  PetscFunctionReturn(0);
}

PetscErrorCode FCMeshDestroy(FCMesh *mesh)
{
  PetscFunctionBegin;
  PetscCall(PetscFree(mesh->cellVerts));
  PetscCall(PetscFree2(mesh->X, mesh->owned));
  PetscCall(PetscFree(mesh->visVert));
  PetscCall(PetscFree(mesh->cellOrigin));
  PetscCall(DMDestroy(&mesh->dm));
  PetscFunctionReturn(0);
}
