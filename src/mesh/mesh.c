/* The tetrahedral mesh of a body: read through the body's DMPlex options
   (-<body>_dm_plex_filename and every other -<body>_dm_* option: refinement, distribution with
   -<body>_petscpartitioner_type ...), validated (3D, tetrahedra only, positive volumes), with
   per-cell vertex lists in a positively oriented order and placed reference coordinates. */
#include "../fcimpl.h"
#include <petscsf.h>
#include <sys/stat.h>
#include <signal.h>
#include <unistd.h>

/* PETSc 3.18's gmsh reader trusts a file's counts and indices and can crash on a malformed one
   (tools/fuzz/petsc-gmsh-crashes, docs/reliability.md). While it reads, a memory fault ends the
   run with a line naming the file instead of a crash report: the message is prepared before, and
   the handler only writes it and exits (async-signal-safe). */
static char             reader_message[2 * PETSC_MAX_PATH_LEN];
static size_t           reader_message_len;
static struct sigaction reader_saved[3];
static const int        reader_signals[3] = {SIGSEGV, SIGBUS, SIGFPE};

static void ReaderFault(int sig)
{
  (void)sig;
  if (write(STDERR_FILENO, reader_message, reader_message_len) < 0) _exit(1);
  _exit(1);
}

static void ReaderGuard(PetscBool on, const char fname[], const char prefix[], const char bodyname[])
{
  if (getenv("FECONTACT_NO_READER_GUARD")) return; /* the fuzzers watch the reader's crashes themselves */
  if (on) {
    struct sigaction sa;
    snprintf(reader_message, sizeof(reader_message),
             "fecontact: error: cannot read mesh file '%s' (-%sdm_plex_filename) of body '%s': PETSc's gmsh reader "
             "hit a memory fault on it, the file is malformed (open it in gmsh to see where)\n",
             fname, prefix, bodyname);
    reader_message_len = strlen(reader_message);
    memset(&sa, 0, sizeof(sa));
    sa.sa_handler = ReaderFault;
    sigemptyset(&sa.sa_mask);
    for (int i = 0; i < 3; i++) sigaction(reader_signals[i], &sa, &reader_saved[i]);
  } else
    for (int i = 0; i < 3; i++) sigaction(reader_signals[i], &reader_saved[i], NULL);
}

/* PETSc 3.18's gmsh reader loops forever, at the end of the file, on a $Comments section that
   has no $EndComments (its GmshReadSection; tools/fuzz/petsc-gmsh-crashes/v22_comments_unterminated.msh):
   1 when the file has a "$Comments" with no "$EndComments" after it. One pass over the bytes; '$'
   starts both words and occurs nowhere else in them, so a mismatch restarts at '$' or at 0. */
static int UnterminatedComments(FILE *fp)
{
  static const char open[] = "$Comments", close[] = "$EndComments";
  char              buf[1 << 16];
  size_t            n, io = 0, ic = 0;
  int               inside = 0;

  while ((n = fread(buf, 1, sizeof(buf), fp)) > 0) {
    for (size_t k = 0; k < n; k++) {
      const char c = buf[k];
      io           = c == open[io] ? io + 1 : (c == '$');
      ic           = c == close[ic] ? ic + 1 : (c == '$');
      if (io == sizeof(open) - 1) inside = 1, io = 0;
      if (ic == sizeof(close) - 1) inside = 0, ic = 0;
    }
  }
  return inside;
}

PetscErrorCode FCMeshLoad(MPI_Comm comm, const char prefix[], const char bodyname[], FCMesh *mesh)
{
  char               fname[PETSC_MAX_PATH_LEN];
  PetscBool          set;
  PetscMPIInt        rank;
  PetscInt           dim, readable = 1, comments = 0, bad = 0, nc;
  PetscBool          distribute = PETSC_TRUE;
  Vec                coords;
  PetscSection       csec;
  const PetscScalar *c;

  PetscFunctionBegin;
  PetscCall(PetscMemzero(mesh, sizeof(*mesh)));
  PetscCall(PetscOptionsGetString(NULL, prefix, "-dm_plex_filename", fname, sizeof(fname), &set));
  PetscCheck(set, comm, PETSC_ERR_USER_INPUT, "Body '%s' needs a mesh: -%sdm_plex_filename <file.msh>", bodyname,
             prefix);
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  if (rank == 0) {
    struct stat st;
    FILE       *fp = NULL;
    if (stat(fname, &st) || !S_ISREG(st.st_mode) || !(fp = fopen(fname, "rb"))) readable = 0;
    if (fp) {
      comments = UnterminatedComments(fp);
      fclose(fp);
    }
  }
  {
    PetscInt flags[2] = {readable, comments};
    PetscCallMPI(MPI_Bcast(flags, 2, MPIU_INT, 0, comm));
    readable = flags[0];
    comments = flags[1];
  }
  PetscCheck(readable, comm, PETSC_ERR_USER_INPUT,
             "Cannot open mesh file '%s' given by -%sdm_plex_filename for body '%s'", fname, prefix, bodyname);
  PetscCheck(!comments, comm, PETSC_ERR_USER_INPUT,
             "Cannot read mesh file '%s' (-%sdm_plex_filename) of body '%s': a $Comments section has no $EndComments "
             "(the file is truncated or malformed; PETSc's gmsh reader would not return on it)",
             fname, prefix, bodyname);
  { /* an input: no output may overwrite it (src/util/inputs.c) */
    char what[256];
    PetscCall(PetscSNPrintf(what, sizeof(what), "mesh of body '%s' (-%sdm_plex_filename)", bodyname, prefix));
    PetscCall(FCInputsAdd(fname, what));
  }

  PetscCall(DMCreate(comm, &mesh->dm));
  PetscCall(DMSetType(mesh->dm, DMPLEX));
  PetscCall(PetscObjectSetName((PetscObject)mesh->dm, bodyname));
  PetscCall(DMSetOptionsPrefix(mesh->dm, prefix));
  {
    /* reads (on rank 0), interpolates, refines; a malformed file fails on rank 0 only, so this
       stays an abort-class error. Not distributed here: the reader replaces the DM's data, and
       with it the partitioner, by a default one that never sees the body's options; the mesh is
       distributed below, by a partitioner that does (-<body>_dm_distribute, read here, is
       restored after the read) */
    PetscErrorCode ierr;
    char           opt[FC_MAX_NAME + 32];
    PetscCall(PetscOptionsGetBool(NULL, prefix, "-dm_distribute", &distribute, NULL));
    PetscCall(PetscSNPrintf(opt, sizeof(opt), "-%sdm_distribute", prefix));
    PetscCall(PetscOptionsSetValue(NULL, opt, "0"));
    ReaderGuard(PETSC_TRUE, fname, prefix, bodyname);
    ierr = DMSetFromOptions(mesh->dm);
    ReaderGuard(PETSC_FALSE, fname, prefix, bodyname);
    PetscCall(PetscOptionsSetValue(NULL, opt, distribute ? "1" : "0"));
    if (ierr) { /* PETSc has printed the reader's message; name the file and the option */
      fprintf(stderr,
              "fecontact: error: cannot read mesh file '%s' (-%sdm_plex_filename) of body '%s': not a valid or "
              "complete gmsh file\n",
              fname, prefix, bodyname);
      return ierr;
    }
  }
  { /* -<body>_petscpartitioner_type (default ptscotch; metis: src/mesh/partmetis.c), or the partition
       of an earlier run (-<body>_partition_file: src/mesh/partreplay.c). Each cell keeps its index in
       the mesh as read (cellOrigin: the root of the migration SF), which the output records with the
       rank that holds it, so that a run can be replayed on the same partition */
    PetscPartitioner part;
    DM               pdm       = NULL;
    PetscSF          migration = NULL;
    PetscMPIInt      size;
    PetscInt         sStart, sEnd;
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
  }
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

  /* Vertex lists; PETSc's closure order of a tet has a negative triple product, swapping the
     second and third vertices makes valid cells positive for the kernels in tet.c */
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

  /* Reference coordinates per local vertex: 3 per vertex, and none elsewhere (a second-order
     mesh's coordinates live on edges and cells too, and its vertices have none of their own) */
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

PetscErrorCode FCMeshGetBoundary(FCMesh *m, PetscInt *nbv, PetscInt **bv, PetscInt *ntri, PetscInt **triv)
{
  DMLabel    label;
  PetscInt   fStart, fEnd, nv = m->vEnd - m->vStart, nt = 0, nb = 0;
  PetscBool *isb, has;

  PetscFunctionBegin;
  PetscCall(DMPlexGetHeightStratum(m->dm, 1, &fStart, &fEnd));
  PetscCall(DMHasLabel(m->dm, "fc_boundary", &has));
  if (!has) {
    /* boundary faces: one cell in the whole mesh. A face on the interface between two ranks has
       one cell on each; PETSc 3.18's DMPlexMarkBoundaryFaces marks it on its owner (the cube's
       396 boundary triangles became 476 on 2 ranks), so the support sizes are summed over the
       point SF here */
    PetscSF  sf;
    PetscInt pStart, pEnd, *supp;
    PetscCall(DMPlexGetChart(m->dm, &pStart, &pEnd));
    PetscCall(PetscCalloc1(pEnd - pStart, &supp));
    for (PetscInt f = fStart; f < fEnd; f++) PetscCall(DMPlexGetSupportSize(m->dm, f, &supp[f - pStart]));
    PetscCall(DMGetPointSF(m->dm, &sf));
    PetscCall(PetscSFReduceBegin(sf, MPIU_INT, supp, supp, MPI_SUM));
    PetscCall(PetscSFReduceEnd(sf, MPIU_INT, supp, supp, MPI_SUM));
    PetscCall(PetscSFBcastBegin(sf, MPIU_INT, supp, supp, MPI_REPLACE));
    PetscCall(PetscSFBcastEnd(sf, MPIU_INT, supp, supp, MPI_REPLACE));
    PetscCall(DMCreateLabel(m->dm, "fc_boundary"));
    PetscCall(DMGetLabel(m->dm, "fc_boundary", &label));
    for (PetscInt f = fStart; f < fEnd; f++) {
      PetscInt ls;
      PetscCall(DMPlexGetSupportSize(m->dm, f, &ls));
      if (supp[f - pStart] == 1 && ls == 1) PetscCall(DMLabelSetValue(label, f, 1));
    }
    PetscCall(PetscFree(supp));
  } else
    PetscCall(DMGetLabel(m->dm, "fc_boundary", &label));
  PetscCall(PetscCalloc1(nv, &isb));
  for (PetscInt f = fStart; f < fEnd; f++) {
    PetscInt val;
    PetscCall(DMLabelGetValue(label, f, &val));
    if (val == 1) nt++;
  }
  PetscCall(PetscMalloc1(3 * nt + 1, triv));
  nt = 0;
  for (PetscInt f = fStart; f < fEnd; f++) {
    PetscInt        val, *closure = NULL, ncl, k = 0, *tv = &(*triv)[3 * nt], cell, opp = -1;
    const PetscInt *supp;
    PetscReal       e1[3], e2[3], nn[3], d[3];
    PetscCall(DMLabelGetValue(label, f, &val));
    if (val != 1) continue;
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
