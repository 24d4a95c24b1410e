/* Regions of a body's mesh (docs/scenes.md, "Regions"): the vertices, boundary faces and cells of
   a gmsh physical group, by name or number (the reader makes one DMPlex label per group, named
   after it, its value the group's number: -dm_plex_gmsh_use_regions, set in read.c; labels follow
   the cells through distribution), or of a box of placed coordinates, "box:x0,y0,z0,x1,y1,z1". */
#include "../fcimpl.h"
#include <petscsf.h>

/* Labels that are not physical groups */
static PetscBool Internal(const char name[])
{
  return (PetscBool)(!strcmp(name, "depth") || !strcmp(name, "celltype") || !strncmp(name, "fc_", 3));
}

/* The mesh's physical groups, "name (number)", for an error message */
static PetscErrorCode GroupList(DM dm, char list[], size_t len)
{
  PetscInt n;

  PetscFunctionBegin;
  list[0] = 0;
  PetscCall(DMGetNumLabels(dm, &n));
  for (PetscInt i = 0; i < n; i++) {
    const char *name;
    DMLabel     l;
    IS          vals;
    PetscInt    nv = 0;
    PetscCall(DMGetLabelName(dm, i, &name));
    if (Internal(name)) continue;
    PetscCall(DMGetLabel(dm, name, &l));
    PetscCall(DMLabelGetValueIS(l, &vals));
    PetscCall(ISGetLocalSize(vals, &nv));
    {
      const PetscInt *v;
      char            item[FC_MAX_NAME + 32];
      PetscCall(ISGetIndices(vals, &v));
      PetscCall(PetscSNPrintf(item, sizeof(item), "%s%s", list[0] ? ", " : "", name));
      if (nv) PetscCall(PetscSNPrintf(item + strlen(item), sizeof(item) - strlen(item), " (%" PetscInt_FMT ")", v[0]));
      PetscCall(ISRestoreIndices(vals, &v));
      if (strlen(list) + strlen(item) + 1 < len) strcat(list, item);
    }
    PetscCall(ISDestroy(&vals));
  }
  if (!list[0]) PetscCall(PetscStrncpy(list, "none (the file has no physical groups)", len));
  PetscFunctionReturn(0);
}

/* The label and value of a group given by name (value -1: every value) or number; NULL when none */
static PetscErrorCode FindGroup(FCMesh *m, const char region[], const char option[], const char bodyname[],
                                DMLabel *label, PetscInt *value)
{
  MPI_Comm  comm = PetscObjectComm((PetscObject)m->dm);
  char     *end;
  long      num = strtol(region, &end, 10);
  PetscInt  n, found = 0;
  PetscBool has;

  PetscFunctionBegin;
  *label = NULL;
  *value = -1;
  PetscCall(DMGetNumLabels(m->dm, &n));
  if (end == region || *end) { /* a name */
    PetscCall(DMHasLabel(m->dm, region, &has));
    if (has && !Internal(region)) PetscCall(DMGetLabel(m->dm, region, label));
    found = *label ? 1 : 0;
  } else
    for (PetscInt i = 0; i < n; i++) { /* a number: the groups of every dimension that have it */
      const char *name;
      DMLabel     l;
      IS          is;
      PetscInt    size = 0;
      PetscCall(DMGetLabelName(m->dm, i, &name));
      if (Internal(name)) continue;
      PetscCall(DMGetLabel(m->dm, name, &l));
      PetscCall(DMLabelGetStratumIS(l, (PetscInt)num, &is));
      if (is) PetscCall(ISGetLocalSize(is, &size));
      PetscCall(ISDestroy(&is));
      PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &size, 1, MPIU_INT, MPI_SUM, comm));
      if (size) {
        PetscCheck(!found, comm, PETSC_ERR_USER_INPUT,
                   "Region %s of option %s (body '%s'): groups of several dimensions have the number %ld; name the "
                   "group instead",
                   region, option, bodyname, num);
        *label = l;
        *value = (PetscInt)num;
        found  = 1;
      }
    }
  if (!(end == region || *end)) { /* a number that is also a group's name ("7"): the name when no number matches */
    PetscCall(DMHasLabel(m->dm, region, &has));
    if (has && !Internal(region)) {
      DMLabel named;
      PetscCall(DMGetLabel(m->dm, region, &named));
      PetscCheck(!found || named == *label, comm, PETSC_ERR_USER_INPUT,
                 "Region %s of option %s (body '%s'): a group is named '%s' and another has the number %ld; the "
                 "region is ambiguous",
                 region, option, bodyname, region, num);
      if (!found) {
        *label = named;
        *value = -1;
        found  = 1;
      }
    }
  }
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &found, 1, MPIU_INT, MPI_MAX, comm));
  if (!found) {
    char list[1024];
    PetscCall(GroupList(m->dm, list, sizeof(list)));
    SETERRQ(comm, PETSC_ERR_USER_INPUT,
            "Option %s: body '%s' has no region '%s' (its mesh's physical groups: %s; or a box: "
            "box:x0,y0,z0,x1,y1,z1)",
            option, bodyname, region, list);
  }
  PetscFunctionReturn(0);
}

static PetscErrorCode ParseBox(const char region[], const char option[], const char bodyname[], MPI_Comm comm,
                               PetscReal box[6])
{
  const char *p = region + 4;
  PetscInt    n = 0;

  PetscFunctionBegin;
  while (n < 6) {
    char *end;
    box[n] = strtod(p, &end);
    if (end == p) break;
    n++;
    p = end;
    if (*p == ',')
      p++;
    else
      break;
  }
  PetscCheck(n == 6 && !*p, comm, PETSC_ERR_USER_INPUT,
             "Option %s (body '%s'): region '%s' is not a box x0,y0,z0,x1,y1,z1 (6 numbers after 'box:')", option,
             bodyname, region);
  for (int d = 0; d < 6; d++)
    PetscCheck(PetscIsNormalReal(box[d]) || box[d] == 0.0, comm, PETSC_ERR_USER_INPUT,
               "Option %s (body '%s'): box '%s' has a bound that is not a finite number", option, bodyname, region);
  for (int d = 0; d < 3; d++)
    PetscCheck(box[d] <= box[3 + d], comm, PETSC_ERR_USER_INPUT, "Option %s (body '%s'): box '%s' has min > max in %c",
               option, bodyname, region, "xyz"[d]);
  PetscFunctionReturn(0);
}

/* FCMeshRegion with the scratch marks of the region's points (fmark, zeroed, one per point of the chart) */
static PetscErrorCode Region(FCMesh *m, const char region[], const char option[], const char bodyname[],
                             PetscBool vmark[], PetscInt *nface, PetscInt **facev, PetscBool cmark[], PetscBool fmark[])
{
  MPI_Comm  comm = PetscObjectComm((PetscObject)m->dm);
  PetscInt  nv = m->vEnd - m->vStart, nc = m->cEnd - m->cStart, fStart, fEnd, nf = 0;
  PetscBool isbox = (PetscBool)!strncmp(region, "box:", 4);
  DMLabel   label = NULL, bnd;
  PetscInt  value = -1, pStart, pEnd;

  PetscFunctionBegin;
  PetscCall(DMPlexGetChart(m->dm, &pStart, &pEnd));
  PetscCall(DMPlexGetHeightStratum(m->dm, 1, &fStart, &fEnd));
  if (isbox) {
    PetscReal box[6];
    PetscCall(ParseBox(region, option, bodyname, comm, box));
    for (PetscInt v = 0; v < nv; v++) {
      PetscBool in = PETSC_TRUE;
      for (int d = 0; d < 3; d++) in = (PetscBool)(in && m->X[3 * v + d] >= box[d] && m->X[3 * v + d] <= box[3 + d]);
      fmark[m->vStart + v - pStart] = in;
    }
    for (PetscInt p = pStart; p < pEnd; p++) { /* a face or cell whose vertices are all inside */
      PetscInt *cl = NULL, ncl, all = 1, any = 0;
      if (p >= m->vStart && p < m->vEnd) continue;
      PetscCall(DMPlexGetTransitiveClosure(m->dm, p, PETSC_TRUE, &ncl, &cl));
      for (PetscInt i = 0; i < ncl; i++)
        if (cl[2 * i] >= m->vStart && cl[2 * i] < m->vEnd) {
          any = 1;
          if (!fmark[cl[2 * i] - pStart]) all = 0;
        }
      PetscCall(DMPlexRestoreTransitiveClosure(m->dm, p, PETSC_TRUE, &ncl, &cl));
      fmark[p - pStart] = (PetscBool)(all && any);
    }
  } else {
    /* PETSc 3.18's reader, with -dm_plex_gmsh_mark_vertices, puts a node in the label of every group
       whose number is the node's tag, whatever the dimensions (a volume and a surface group both
       numbered 1 share their vertices): a group with faces or cells takes its vertices from their
       closures only, a Physical Point group (vertices alone) its vertices */
    PetscInt higher = 0;
    PetscCall(FindGroup(m, region, option, bodyname, &label, &value));
    for (PetscInt p = pStart; p < pEnd && label; p++) {
      PetscInt val;
      if (p >= m->vStart && p < m->vEnd) continue;
      PetscCall(DMLabelGetValue(label, p, &val));
      if (val != -1 && (value < 0 || val == value)) higher = 1;
    }
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &higher, 1, MPIU_INT, MPI_MAX, comm));
    for (PetscInt p = pStart; p < pEnd; p++) {
      PetscInt val;
      if (!label) break;
      if (higher && p >= m->vStart && p < m->vEnd) continue;
      PetscCall(DMLabelGetValue(label, p, &val));
      if (val == -1 || (value >= 0 && val != value)) continue;
      { /* the point and its closure's vertices */
        PetscInt *cl      = NULL, ncl;
        fmark[p - pStart] = PETSC_TRUE;
        PetscCall(DMPlexGetTransitiveClosure(m->dm, p, PETSC_TRUE, &ncl, &cl));
        for (PetscInt i = 0; i < ncl; i++)
          if (cl[2 * i] >= m->vStart && cl[2 * i] < m->vEnd) fmark[cl[2 * i] - pStart] = PETSC_TRUE;
        PetscCall(DMPlexRestoreTransitiveClosure(m->dm, p, PETSC_TRUE, &ncl, &cl));
      }
    }
  }
  { /* a vertex of the region on one rank is in it on every rank that holds a copy */
    PetscSF   sf;
    PetscInt *mk;
    PetscCall(PetscCalloc1(pEnd - pStart, &mk));
    for (PetscInt v = m->vStart; v < m->vEnd; v++) mk[v - pStart] = fmark[v - pStart];
    PetscCall(DMGetPointSF(m->dm, &sf));
    PetscCall(PetscSFReduceBegin(sf, MPIU_INT, mk, mk, MPI_MAX));
    PetscCall(PetscSFReduceEnd(sf, MPIU_INT, mk, mk, MPI_MAX));
    PetscCall(PetscSFBcastBegin(sf, MPIU_INT, mk, mk, MPI_REPLACE));
    PetscCall(PetscSFBcastEnd(sf, MPIU_INT, mk, mk, MPI_REPLACE));
    for (PetscInt v = 0; v < nv; v++) vmark[v] = mk[m->vStart + v - pStart] ? PETSC_TRUE : PETSC_FALSE;
    PetscCall(PetscFree(mk));
  }
  if (cmark)
    for (PetscInt c = 0; c < nc; c++) cmark[c] = fmark[m->cStart + c - pStart];
  if (nface) {
    PetscCall(FCMeshBoundaryLabel(m, &bnd));
    for (PetscInt pass = 0; pass < 2; pass++) {
      nf = 0;
      for (PetscInt f = fStart; f < fEnd; f++) {
        PetscInt val;
        if (!fmark[f - pStart]) continue;
        PetscCall(DMLabelGetValue(bnd, f, &val));
        if (val != 1) continue;
        if (pass) PetscCall(FCMeshOrientedFace(m, f, &(*facev)[3 * nf]));
        nf++;
      }
      if (!pass) PetscCall(PetscMalloc1(3 * nf + 1, facev));
    }
    *nface = nf;
  }
  PetscFunctionReturn(0);
}

PetscErrorCode FCMeshRegion(FCMesh *m, const char region[], const char option[], const char bodyname[],
                            PetscBool vmark[], PetscInt *nface, PetscInt **facev, PetscBool cmark[])
{
  PetscBool     *fmark;
  PetscInt       pStart, pEnd;
  PetscErrorCode ierr;

  PetscFunctionBegin;
  PetscCall(DMPlexGetChart(m->dm, &pStart, &pEnd));
  PetscCall(PetscCalloc1(pEnd - pStart + 1, &fmark)); /* every point of the region on this rank */
  ierr = Region(m, region, option, bodyname, vmark, nface, facev, cmark, fmark); /* freed on an error too */
  PetscCall(PetscFree(fmark));
  PetscCall(ierr);
  PetscFunctionReturn(0);
}
