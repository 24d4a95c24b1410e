/* Fields of the output frames (docs/output.md): -output_fields names them, and only those are
   computed, once per frame (every -output_every steps), never between frames. Each body that has a
   requested field gets an extendible dataset /bodies/<name>/<field>, one row per frame:
     displacement, velocity   (F, V, 3) point data, every body (rigid, kinematic: of its picture)
     von_mises, energy_density (F, C)   cell data, FE bodies only
   in the order of /bodies/<name>/mesh (each rank writes its owned vertices or cells). The values
   come from the bodies (FCBodyGetVisualField: src/body/fem_state.c, pose.c). */
#include "ioimpl.h"

const char *const FCVisualFieldNames[FC_FIELD_NUM] = {"displacement", "velocity", "von_mises", "energy_density",
                                                      "contact_pressure"};

PetscBool FCVisualFieldIsCell(FCVisualField f)
{
  return f == FC_FIELD_VON_MISES || f == FC_FIELD_ENERGY_DENSITY ? PETSC_TRUE : PETSC_FALSE;
}

PetscBool FCVisualFieldIsScalar(FCVisualField f)
{
  return FCVisualFieldIsCell(f) || f == FC_FIELD_CONTACT_PRESSURE ? PETSC_TRUE : PETSC_FALSE;
}

/* "displacement,velocity" -> mask; "none" (alone) -> 0 */
PetscErrorCode FCOutputFieldsParse(MPI_Comm comm, const char list[], PetscInt *mask)
{
  char      buf[256], *tok, *save = NULL;
  char      known[256] = "";
  PetscBool none       = PETSC_FALSE;

  PetscFunctionBegin;
  *mask = 0;
  PetscCall(PetscStrncpy(buf, list, sizeof(buf)));
  for (int f = 0; f < FC_FIELD_NUM; f++) {
    PetscCall(PetscStrlcat(known, FCVisualFieldNames[f], sizeof(known)));
    PetscCall(PetscStrlcat(known, ", ", sizeof(known)));
  }
  PetscCall(PetscStrlcat(known, "none", sizeof(known)));
  for (tok = strtok_r(buf, ",", &save); tok; tok = strtok_r(NULL, ",", &save)) {
    int f;
    if (!strcmp(tok, "none")) {
      none = PETSC_TRUE;
      continue;
    }
    for (f = 0; f < FC_FIELD_NUM; f++)
      if (!strcmp(tok, FCVisualFieldNames[f])) break;
    PetscCheck(f < FC_FIELD_NUM, comm, PETSC_ERR_USER_INPUT, "Unknown field '%s' in -output_fields (known: %s)", tok,
               known);
    *mask |= (PetscInt)1 << f;
  }
  PetscCheck(!none || !*mask, comm, PETSC_ERR_USER_INPUT,
             "-output_fields: 'none' cannot be combined with fields (got '%s')", list);
  PetscFunctionReturn(0);
}

PetscErrorCode FCOutputSetFields(FCOutput out, PetscInt mask)
{
  PetscFunctionBegin;
  out->fieldmask = mask;
  PetscFunctionReturn(0);
}

static PetscErrorCode FieldSize(FCBody b, FCVisualField f, PetscInt *n, PetscInt *nglobal, PetscInt *start)
{
  const FCBodyVisual *vis;

  PetscFunctionBegin;
  PetscCall(FCBodyGetVisual(b, &vis));
  *n       = FCVisualFieldIsCell(f) ? vis->nc : vis->nv;
  *nglobal = FCVisualFieldIsCell(f) ? vis->nc_global : vis->nv_global;
  *start   = FCVisualFieldIsCell(f) ? vis->cstart : vis->vstart;
  PetscFunctionReturn(0);
}

/* A dataset per body and requested field the body has (asked once, at set-up: the answer depends on
   the body's type only, the same on every rank) */
PetscErrorCode FCOutputFieldsCreate(FCOutput out)
{
  PetscFunctionBegin;
  PetscCall(PetscMalloc1(out->nbodies, &out->fields));
  for (PetscInt i = 0; i < out->nbodies; i++)
    for (int f = 0; f < FC_FIELD_NUM; f++) {
      PetscInt   n, ng, start;
      PetscReal *v;
      PetscBool  has    = PETSC_FALSE;
      out->fields[i][f] = -1;
      if (!(out->fieldmask & ((PetscInt)1 << f))) continue;
      PetscCall(FieldSize(out->bodies[i], (FCVisualField)f, &n, &ng, &start));
      PetscCall(PetscMalloc1(3 * n + 1, &v));
      PetscCall(FCBodyGetVisualField(out->bodies[i], (FCVisualField)f, v, &has));
      PetscCall(PetscFree(v));
      if (!has) continue;
      {
        hsize_t rows[2] = {(hsize_t)ng, 3};
        PetscCall(FCH5CreateRows(out->bo[i].group, FCVisualFieldNames[f], H5T_NATIVE_DOUBLE,
                                 FCVisualFieldIsScalar((FCVisualField)f) ? 2 : 3, rows, 1, &out->fields[i][f]));
      }
    }
  PetscFunctionReturn(0);
}

/* The frame's row of every field dataset: each rank its owned vertices or cells */
PetscErrorCode FCOutputFieldsWrite(FCOutput out)
{
  PetscFunctionBegin;
  for (PetscInt i = 0; i < out->nbodies; i++)
    for (int f = 0; f < FC_FIELD_NUM; f++) {
      hid_t      dset = out->fields[i][f], fspace, mspace;
      int        rank = FCVisualFieldIsScalar((FCVisualField)f) ? 2 : 3;
      hsize_t    dims[3], start[3] = {0, 0, 0}, count[3] = {1, 0, 3};
      PetscInt   n, ng, first;
      PetscReal *v;
      PetscBool  has;
      if (dset < 0) continue;
      PetscCall(FieldSize(out->bodies[i], (FCVisualField)f, &n, &ng, &first));
      PetscCall(PetscMalloc1(3 * n + 1, &v));
      PetscCall(FCBodyGetVisualField(out->bodies[i], (FCVisualField)f, v, &has));
      fspace = H5Dget_space(dset);
      H5Sget_simple_extent_dims(fspace, dims, NULL);
      H5Sclose(fspace);
      start[0] = dims[0];
      start[1] = (hsize_t)first;
      dims[0] += 1;
      FCH5Check(H5Dset_extent(dset, dims), FCVisualFieldNames[f]);
      fspace   = H5Dget_space(dset);
      count[1] = (hsize_t)n;
      if (n) {
        H5Sselect_hyperslab(fspace, H5S_SELECT_SET, start, NULL, count, NULL);
        mspace = H5Screate_simple(rank, count, NULL);
      } else {
        H5Sselect_none(fspace);
        mspace = H5Screate(H5S_NULL);
      }
      FCH5Check(H5Dwrite(dset, H5T_NATIVE_DOUBLE, mspace, fspace, H5P_DEFAULT, v), FCVisualFieldNames[f]);
      H5Sclose(mspace);
      H5Sclose(fspace);
      PetscCall(PetscFree(v));
    }
  PetscFunctionReturn(0);
}

PetscErrorCode FCOutputFieldsDestroy(FCOutput out)
{
  PetscFunctionBegin;
  if (out->fields && !FCH5FailedInside())
    for (PetscInt i = 0; i < out->nbodies; i++)
      for (int f = 0; f < FC_FIELD_NUM; f++)
        if (out->fields[i][f] >= 0) H5Dclose(out->fields[i][f]);
  PetscCall(PetscFree(out->fields));
  PetscFunctionReturn(0);
}
