/* A PetscPartitioner of type "metis": the cell graph PETSc hands the partitioner, partitioned by
   METIS_PartGraphKway (Karypis & Kumar 1998). PETSc 3.18 as Debian builds it has no ParMETIS
   (so no "parmetis" type); METIS is sequential, so the graph is gathered on rank 0, partitioned
   there and the parts scattered back (at mesh load the whole graph is on rank 0 anyway: the gmsh
   reader reads there). Registered by FCPartitionerRegisterMetis (src/fecontact.c, at start-up);
   selected per body with -<body>_petscpartitioner_type metis.
   Options (each with the body's prefix): -petscpartitioner_metis_imbalance, _objective, _seed (help
   strings below; docs/options.md).
   Vertex weights (PETSc's vertSection, e.g. -petscpartitioner_use_vertex_weights) and target part
   sizes (targetSection) are passed to METIS as they are. */
#include "../fcimpl.h"
#include <metis.h>
#include <petsc/private/partitionerimpl.h>

typedef struct {
  PetscReal imbalance;
  PetscInt  objective; /* 0 edge cut, 1 communication volume */
  PetscInt  seed;
} Partitioner_Metis;

static const char *objectives[] = {"cut", "volume"};

static PetscErrorCode Destroy_Metis(PetscPartitioner part)
{
  PetscFunctionBegin;
  PetscCall(PetscFree(part->data));
  PetscFunctionReturn(0);
}

static PetscErrorCode View_Metis(PetscPartitioner part, PetscViewer viewer)
{
  Partitioner_Metis *m = (Partitioner_Metis *)part->data;
  PetscBool          ascii;

  PetscFunctionBegin;
  PetscCall(PetscObjectTypeCompare((PetscObject)viewer, PETSCVIEWERASCII, &ascii));
  if (ascii) {
    PetscCall(PetscViewerASCIIPushTab(viewer));
    PetscCall(PetscViewerASCIIPrintf(viewer, "METIS k-way, objective %s, imbalance %g, seed %" PetscInt_FMT "\n",
                                     objectives[m->objective], (double)m->imbalance, m->seed));
    PetscCall(PetscViewerASCIIPrintf(viewer, "edge cut %" PetscInt_FMT "\n", part->edgeCut));
    PetscCall(PetscViewerASCIIPopTab(viewer));
  }
  PetscFunctionReturn(0);
}

static PetscErrorCode SetFromOptions_Metis(PetscPartitioner part, PetscOptionItems *PetscOptionsObject)
{
  Partitioner_Metis *m = (Partitioner_Metis *)part->data;
  const char        *prefix;

  PetscFunctionBegin;
  PetscOptionsHeadBegin(PetscOptionsObject, "PetscPartitioner METIS options");
  PetscCall(PetscOptionsReal("-petscpartitioner_metis_imbalance", "Allowed load imbalance (max part / mean part)", "",
                             m->imbalance, &m->imbalance, NULL));
  PetscCall(FCOptionsEList(PetscOptionsObject, "-petscpartitioner_metis_objective",
                           "Objective: edge cut or communication volume", objectives, 2, &m->objective, NULL));
  PetscCall(FCOptionsIntRange(PetscOptionsObject, "-petscpartitioner_metis_seed", "METIS random seed", 0, PETSC_MAX_INT,
                              &m->seed, NULL));
  PetscOptionsHeadEnd();
  PetscCall(PetscObjectGetOptionsPrefix((PetscObject)part, &prefix));
  PetscCheck(m->imbalance > 1.0 && m->imbalance < 100.0, PetscObjectComm((PetscObject)part), PETSC_ERR_USER_INPUT,
             "Option -%spetscpartitioner_metis_imbalance must lie in (1, 100), got %g", prefix ? prefix : "",
             (double)m->imbalance);
  PetscCheck(m->seed >= 0, PetscObjectComm((PetscObject)part), PETSC_ERR_USER_INPUT,
             "Option -%spetscpartitioner_metis_seed must be >= 0, got %" PetscInt_FMT, prefix ? prefix : "", m->seed);
  PetscFunctionReturn(0);
}

/* PETSc's graph (CSR over this rank's vertices, adjacency in global vertex numbers) gathered on
   rank 0, METIS there, each rank's part numbers scattered back; then partSection (the number of
   this rank's vertices going to each part) and the IS of those vertices sorted by part */
static PetscErrorCode Partition_Metis(PetscPartitioner part, PetscInt nparts, PetscInt nloc, PetscInt start[],
                                      PetscInt adjacency[], PetscSection vertSection, PetscSection targetSection,
                                      PetscSection partSection, IS *partition)
{
  Partitioner_Metis *m = (Partitioner_Metis *)part->data;
  MPI_Comm           comm;
  PetscMPIInt        size, rank, nl = (PetscMPIInt)nloc, ne = (PetscMPIInt)start[nloc];
  PetscMPIInt       *vcount = NULL, *vdisp = NULL, *ecount = NULL, *edisp = NULL;
  PetscInt *assignment, *points, *lx = NULL, *lw = NULL, *gx = NULL, *gadj = NULL, *gw = NULL, *ga = NULL, nv = 0,
                                 cut = 0;
  idx_t status                       = METIS_OK;

  PetscFunctionBegin;
  PetscCall(PetscObjectGetComm((PetscObject)part, &comm));
  PetscCallMPI(MPI_Comm_size(comm, &size));
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCall(PetscMalloc3(nloc + 1, &assignment, nloc + 1, &lx, nloc + 1, &lw));
  for (PetscInt v = 0; v < nloc; v++) {
    lx[v] = start[v + 1] - start[v]; /* degrees: rank 0 rebuilds the offsets */
    lw[v] = 1;
    if (vertSection) PetscCall(PetscSectionGetDof(vertSection, v, &lw[v]));
  }
  if (!rank) PetscCall(PetscMalloc4(size, &vcount, size + 1, &vdisp, size, &ecount, size + 1, &edisp));
  PetscCallMPI(MPI_Gather(&nl, 1, MPI_INT, vcount, 1, MPI_INT, 0, comm));
  PetscCallMPI(MPI_Gather(&ne, 1, MPI_INT, ecount, 1, MPI_INT, 0, comm));
  if (!rank) {
    vdisp[0] = edisp[0] = 0;
    for (PetscMPIInt r = 0; r < size; r++) {
      vdisp[r + 1] = vdisp[r] + vcount[r];
      edisp[r + 1] = edisp[r] + ecount[r];
    }
    nv = vdisp[size];
    PetscCall(PetscMalloc4(nv + 1, &gx, edisp[size] + 1, &gadj, nv + 1, &gw, nv + 1, &ga));
  }
  PetscCallMPI(MPI_Gatherv(lx, nl, MPIU_INT, gx ? gx + 1 : NULL, vcount, vdisp, MPIU_INT, 0, comm));
  PetscCallMPI(MPI_Gatherv(lw, nl, MPIU_INT, gw, vcount, vdisp, MPIU_INT, 0, comm));
  PetscCallMPI(MPI_Gatherv(adjacency, ne, MPIU_INT, gadj, ecount, edisp, MPIU_INT, 0, comm));
  if (!rank && nv > 0) {
    idx_t  n = (idx_t)nv, ncon = 1, np = (idx_t)nparts, objval = 0, options[METIS_NOPTIONS];
    idx_t *xadj, *adj, *vwgt, *where;
    real_t ubvec = (real_t)m->imbalance, *tpwgts = NULL;
    gx[0] = 0;
    for (PetscInt v = 0; v < nv; v++) gx[v + 1] += gx[v];
    PetscCall(PetscMalloc4(nv + 1, &xadj, gx[nv] + 1, &adj, nv, &vwgt, nv, &where));
    for (PetscInt v = 0; v <= nv; v++) xadj[v] = (idx_t)gx[v];
    for (PetscInt e = 0; e < gx[nv]; e++) adj[e] = (idx_t)gadj[e];
    for (PetscInt v = 0; v < nv; v++) vwgt[v] = (idx_t)gw[v];
    if (targetSection) { /* target part sizes, as fractions (METIS rejects a zero) */
      real_t sum = 0.0;
      PetscCall(PetscMalloc1(nparts, &tpwgts));
      for (PetscInt p = 0; p < nparts; p++) {
        PetscInt t;
        PetscCall(PetscSectionGetDof(targetSection, p, &t));
        tpwgts[p] = (real_t)PetscMax((PetscReal)t, PETSC_SMALL);
        sum += tpwgts[p];
      }
      for (PetscInt p = 0; p < nparts; p++) tpwgts[p] /= sum;
    }
    METIS_SetDefaultOptions(options);
    options[METIS_OPTION_OBJTYPE] = m->objective ? METIS_OBJTYPE_VOL : METIS_OBJTYPE_CUT;
    options[METIS_OPTION_SEED]    = (idx_t)m->seed;
    if (np == 1)
      for (PetscInt v = 0; v < nv; v++) where[v] = 0;
    else
      status =
          METIS_PartGraphKway(&n, &ncon, xadj, adj, vwgt, NULL, NULL, &np, tpwgts, &ubvec, options, &objval, where);
    for (PetscInt v = 0; v < nv; v++) ga[v] = (PetscInt)where[v];
    cut = (PetscInt)objval;
    PetscCall(PetscFree4(xadj, adj, vwgt, where));
    PetscCall(PetscFree(tpwgts));
  }
  {
    PetscInt info[2] = {(PetscInt)status, cut};
    PetscCallMPI(MPI_Bcast(info, 2, MPIU_INT, 0, comm));
    PetscCheck(info[0] == METIS_OK, comm, PETSC_ERR_LIB, "METIS_PartGraphKway failed (status %" PetscInt_FMT ")",
               info[0]);
    part->edgeCut = info[1];
  }
  PetscCall(
      PetscInfo(part, "METIS k-way: %" PetscInt_FMT " parts, edge cut %" PetscInt_FMT "\n", nparts, part->edgeCut));
  PetscCallMPI(MPI_Scatterv(ga, vcount, vdisp, MPIU_INT, assignment, nl, MPIU_INT, 0, comm));
  if (!rank) {
    PetscCall(PetscFree4(vcount, vdisp, ecount, edisp));
    PetscCall(PetscFree4(gx, gadj, gw, ga));
  }
  for (PetscInt v = 0; v < nloc; v++) PetscCall(PetscSectionAddDof(partSection, assignment[v], 1));
  PetscCall(PetscMalloc1(nloc + 1, &points));
  {
    PetscInt i = 0;
    for (PetscInt p = 0; p < nparts; p++)
      for (PetscInt v = 0; v < nloc; v++)
        if (assignment[v] == p) points[i++] = v;
  }
  PetscCall(ISCreateGeneral(comm, nloc, points, PETSC_OWN_POINTER, partition));
  PetscCall(PetscFree3(assignment, lx, lw));
  PetscFunctionReturn(0);
}

static PetscErrorCode Create_Metis(PetscPartitioner part)
{
  Partitioner_Metis *m;

  PetscFunctionBegin;
  PetscCall(PetscNew(&m));
  m->imbalance              = 1.03;
  part->data                = m;
  part->noGraph             = PETSC_FALSE;
  part->ops->view           = View_Metis;
  part->ops->setfromoptions = SetFromOptions_Metis;
  part->ops->destroy        = Destroy_Metis;
  part->ops->partition      = Partition_Metis;
  PetscFunctionReturn(0);
}

PetscErrorCode FCPartitionerRegisterMetis(void)
{
  PetscFunctionBegin;
  PetscCall(PetscPartitionerRegister(FC_PARTITIONER_METIS, Create_Metis));
  PetscFunctionReturn(0);
}
