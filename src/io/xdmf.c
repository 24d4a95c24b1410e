/* XDMF index of the HDF5 output, so that ParaView opens the run (File > Open out.xmf): one temporal
   collection per body (the frame's mesh with its fields) and, with contact pairs, one of the contacts
   of each frame's step (a point set, grid "contact-points"). Layout in docs/output.md.

   The readers of ParaView 5.11 accept neither an XDMF HyperSlab of a frame's row as geometry (the
   XDMF reader: "Cannot find DataItem element in geometry xml", the Xdmf3 readers: empty meshes,
   "Skipping unrecognized array type") nor an empty DataItem (a step without contacts). So each
   frame's data is referred to through HDF5 virtual datasets /xdmf/frame<k>/...: views of a row of
   /bodies/<name>/{positions,<field>} and of the frame's rows of /contacts, with no copy of the
   data; a frame without contacts is an empty spatial collection. */
#include "ioimpl.h"
#include <errno.h>

/* A virtual dataset `name` in `loc`: rows [row, row + n) of the source dataset `src` (of row shape
   rowdims[0..rank-2]), or, with col >= 0, column col of those rows as a (n,) dataset */
static PetscErrorCode CreateView(hid_t loc, const char name[], hid_t type, const char src[], int rank,
                                 const hsize_t rowdims[], hsize_t row, hsize_t n, int col, PetscBool dropfirst)
{
  hsize_t sdims[3] = {row + n, 0, 0}, smax[3] = {H5S_UNLIMITED, 0, 0}, start[3] = {row, 0, 0}, count[3] = {n, 0, 0};
  hsize_t vdims[3];
  int     vrank = 0;
  hid_t   dcpl, sspace, vspace, dset;

  PetscFunctionBegin;
  for (int i = 1; i < rank; i++) sdims[i] = smax[i] = count[i] = rowdims[i - 1];
  if (!dropfirst) vdims[vrank++] = n;
  if (col >= 0) {
    start[1] = (hsize_t)col;
    count[1] = 1;
  } else
    for (int i = 1; i < rank; i++) vdims[vrank++] = rowdims[i - 1];
  sspace = H5Screate_simple(rank, sdims, smax);
  H5Sselect_hyperslab(sspace, H5S_SELECT_SET, start, NULL, count, NULL);
  vspace = H5Screate_simple(vrank, vdims, NULL);
  dcpl   = H5Pcreate(H5P_DATASET_CREATE);
  FCH5Check(H5Pset_virtual(dcpl, vspace, ".", src, sspace), name);
  dset = H5Dcreate2(loc, name, type, vspace, H5P_DEFAULT, dcpl, H5P_DEFAULT);
  FCH5Check(dset, name);
  H5Dclose(dset);
  H5Pclose(dcpl);
  H5Sclose(vspace);
  H5Sclose(sspace);
  PetscFunctionReturn(0);
}

/* The views of frame k = xframes (collective: every rank creates the same metadata) */
PetscErrorCode FCXdmfAddFrame(FCOutput out, PetscReal t)
{
  char      path[PETSC_MAX_PATH_LEN];
  hid_t     gx, gf, gb;
  PetscInt  k = out->xframes;
  long long n = out->contacts ? out->clast : 0, first = out->ctotal - n;

  PetscFunctionBegin;
  if (k == out->xmax) {
    double    *t2;
    long long *f2, *c2;
    out->xmax = PetscMax(64, 2 * out->xmax);
    PetscCall(PetscMalloc3(out->xmax, &t2, out->xmax, &f2, out->xmax, &c2));
    PetscCall(PetscArraycpy(t2, out->xtime, k));
    PetscCall(PetscArraycpy(f2, out->xfirst, k));
    PetscCall(PetscArraycpy(c2, out->xcount, k));
    PetscCall(PetscFree3(out->xtime, out->xfirst, out->xcount));
    out->xtime  = t2;
    out->xfirst = f2;
    out->xcount = c2;
  }
  out->xtime[k]  = t;
  out->xfirst[k] = first;
  out->xcount[k] = n;
  gx             = k ? H5Gopen2(out->file, "xdmf", H5P_DEFAULT)
                     : H5Gcreate2(out->file, "xdmf", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  if (!k) PetscCall(FCH5CreateRows(gx, "vertex", H5T_NATIVE_LLONG, 1, NULL, 1024, &out->xvertex));
  if (n > out->xnvertex) { /* grow 0, 1, 2, ... to the largest contact count so far */
    long long *iota;
    PetscCall(PetscMalloc1(n - out->xnvertex, &iota));
    for (long long j = out->xnvertex; j < n; j++) iota[j - out->xnvertex] = j;
    PetscCall(FCH5AppendRows(out->rank, out->xvertex, H5T_NATIVE_LLONG, (hsize_t)(n - out->xnvertex), iota));
    PetscCall(PetscFree(iota));
    out->xnvertex = n;
  }
  PetscCall(PetscSNPrintf(path, sizeof(path), "frame%" PetscInt_FMT, k));
  gf = H5Gcreate2(gx, path, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  FCH5Check(gf, path);
  gb = H5Gcreate2(gf, "bodies", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  for (PetscInt i = 0; i < out->nbodies; i++) {
    const FCBodyVisual *vis;
    const char         *name;
    hid_t               g;
    PetscCall(FCBodyGetVisual(out->bodies[i], &vis));
    PetscCall(FCBodyGetName(out->bodies[i], &name));
    g = H5Gcreate2(gb, name, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    for (int f = -1; f < FC_FIELD_NUM; f++) { /* -1: the positions */
      hsize_t     rows[2] = {(hsize_t)vis->nv_global, 3};
      const char *fname   = f < 0 ? "positions" : FCVisualFieldNames[f];
      PetscBool   cell    = f >= 0 && FCVisualFieldIsCell((FCVisualField)f);
      PetscBool   scalar  = f >= 0 && FCVisualFieldIsScalar((FCVisualField)f);
      if (f >= 0 && out->fields[i][f] < 0) continue;
      if (cell) rows[0] = (hsize_t)vis->nc_global;
      PetscCall(PetscSNPrintf(path, sizeof(path), "/bodies/%s/%s", name, fname));
      PetscCall(CreateView(g, fname, H5T_NATIVE_DOUBLE, path, scalar ? 2 : 3, rows, (hsize_t)k, 1, -1, PETSC_TRUE));
    }
    H5Gclose(g);
  }
  H5Gclose(gb);
  if (n > 0) { /* the step's contact records [first, first + n): written at this frame's flush */
    const hsize_t three[1] = {3};
    hid_t         gc       = H5Gcreate2(gf, "contacts", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    PetscCall(
        CreateView(gc, "point_end", H5T_NATIVE_DOUBLE, "/contacts/point_end", 2, three, first, n, -1, PETSC_FALSE));
    PetscCall(
        CreateView(gc, "force_world", H5T_NATIVE_DOUBLE, "/contacts/force_world", 2, three, first, n, -1, PETSC_FALSE));
    PetscCall(CreateView(gc, "force_normal", H5T_NATIVE_DOUBLE, "/contacts/force", 2, three, first, n, 0, PETSC_FALSE));
    PetscCall(CreateView(gc, "force_tangential", H5T_NATIVE_DOUBLE, "/contacts/force_tangential", 1, NULL, first, n, -1,
                         PETSC_FALSE));
    PetscCall(CreateView(gc, "normal", H5T_NATIVE_DOUBLE, "/contacts/normal", 2, three, first, n, -1, PETSC_FALSE));
    PetscCall(CreateView(gc, "gap", H5T_NATIVE_DOUBLE, "/contacts/gap", 1, NULL, first, n, -1, PETSC_FALSE));
    PetscCall(CreateView(gc, "state", H5T_NATIVE_LLONG, "/contacts/state", 1, NULL, first, n, -1, PETSC_FALSE));
    PetscCall(CreateView(gc, "vertex", H5T_NATIVE_LLONG, "/xdmf/vertex", 1, NULL, 0, n, -1, PETSC_FALSE));
    H5Gclose(gc);
  }
  H5Gclose(gf);
  H5Gclose(gx);
  out->xframes++;
  PetscFunctionReturn(0);
}

PetscErrorCode FCXdmfDestroy(FCOutput out)
{
  PetscFunctionBegin;
  PetscCall(PetscFree3(out->xtime, out->xfirst, out->xcount));
  if (out->xframes && !FCH5FailedInside()) H5Dclose(out->xvertex); /* nothing closes after a failure inside HDF5 */
  PetscFunctionReturn(0);
}

static void Item(FILE *fp, const char *indent, const char dims[], const char type[], const char base[],
                 const char path[])
{
  fprintf(fp, "%s<DataItem Dimensions=\"%s\" NumberType=\"%s\" Precision=\"8\" Format=\"HDF\">%s:%s</DataItem>\n",
          indent, dims, type, base, path);
}

/* Rank 0 rewrites the index from what FCXdmfAddFrame remembered */
/* Body i's temporal collection: per frame its mesh, positions, partition and fields */
static PetscErrorCode BodyGrid(FCOutput out, FILE *fp, const char base[], PetscInt i)
{
  char                dims[64], path[PETSC_MAX_PATH_LEN];
  const FCBodyVisual *vis;
  const char         *topo, *name;

  PetscFunctionBegin;
  PetscCall(FCBodyGetVisual(out->bodies[i], &vis));
  PetscCall(FCBodyGetName(out->bodies[i], &name));
  topo = vis->nvpc == 4 ? "Tetrahedron" : "Triangle";
  fprintf(fp, "  <Grid Name=\"%s\" GridType=\"Collection\" CollectionType=\"Temporal\">\n", name);
  for (PetscInt k = 0; k < out->xframes; k++) {
    fprintf(fp, "   <Grid Name=\"%s\" GridType=\"Uniform\">\n    <Time Value=\"%.17g\"/>\n", name, out->xtime[k]);
    fprintf(fp, "    <Topology TopologyType=\"%s\" NumberOfElements=\"%" PetscInt_FMT "\">\n", topo, vis->nc_global);
    PetscCall(PetscSNPrintf(dims, sizeof(dims), "%" PetscInt_FMT " %" PetscInt_FMT, vis->nc_global, vis->nvpc));
    PetscCall(PetscSNPrintf(path, sizeof(path), "/bodies/%s/mesh/cells", name));
    Item(fp, "     ", dims, "Int", base, path);
    fprintf(fp, "    </Topology>\n    <Geometry GeometryType=\"XYZ\">\n");
    PetscCall(PetscSNPrintf(dims, sizeof(dims), "%" PetscInt_FMT " 3", vis->nv_global));
    PetscCall(PetscSNPrintf(path, sizeof(path), "/xdmf/frame%" PetscInt_FMT "/bodies/%s/positions", k, name));
    Item(fp, "     ", dims, "Float", base, path);
    fprintf(fp, "    </Geometry>\n");
    if (vis->origin) { /* the partition: which rank held each cell */
      fprintf(fp, "    <Attribute Name=\"rank\" AttributeType=\"Scalar\" Center=\"Cell\">\n");
      PetscCall(PetscSNPrintf(dims, sizeof(dims), "%" PetscInt_FMT, vis->nc_global));
      PetscCall(PetscSNPrintf(path, sizeof(path), "/bodies/%s/mesh/rank", name));
      Item(fp, "     ", dims, "Int", base, path);
      fprintf(fp, "    </Attribute>\n");
    }
    for (int f = 0; f < FC_FIELD_NUM; f++) {
      PetscBool cell = FCVisualFieldIsCell((FCVisualField)f), scalar = FCVisualFieldIsScalar((FCVisualField)f);
      if (out->fields[i][f] < 0) continue;
      fprintf(fp, "    <Attribute Name=\"%s\" AttributeType=\"%s\" Center=\"%s\">\n", FCVisualFieldNames[f],
              scalar ? "Scalar" : "Vector", cell ? "Cell" : "Node");
      if (cell)
        PetscCall(PetscSNPrintf(dims, sizeof(dims), "%" PetscInt_FMT, vis->nc_global));
      else if (scalar)
        PetscCall(PetscSNPrintf(dims, sizeof(dims), "%" PetscInt_FMT, vis->nv_global));
      else
        PetscCall(PetscSNPrintf(dims, sizeof(dims), "%" PetscInt_FMT " 3", vis->nv_global));
      PetscCall(PetscSNPrintf(path, sizeof(path), "/xdmf/frame%" PetscInt_FMT "/bodies/%s/%s", k, name,
                              FCVisualFieldNames[f]));
      Item(fp, "     ", dims, "Float", base, path);
      fprintf(fp, "    </Attribute>\n");
    }
    fprintf(fp, "   </Grid>\n");
  }
  fprintf(fp, "  </Grid>\n");
  PetscFunctionReturn(0);
}

/* The contact points' temporal collection: per frame the points and their forces, normal, gap, state */
static PetscErrorCode ContactGrid(FCOutput out, FILE *fp, const char base[])
{
  char dims[64], path[PETSC_MAX_PATH_LEN];
  const struct {
    const char *name, *type, *kind;
    int         ncomp;
  } attr[] = {
      {"force_world", "Float", "Vector", 3},
      {"force_normal", "Float", "Scalar", 1},
      {"force_tangential", "Float", "Scalar", 1},
      {"normal", "Float", "Vector", 3},
      {"gap", "Float", "Scalar", 1},
      {"state", "Int", "Scalar", 1},
  };

  PetscFunctionBegin;
  fprintf(fp, "  <Grid Name=\"contact-points\" GridType=\"Collection\" CollectionType=\"Temporal\">\n");
  for (PetscInt k = 0; k < out->xframes; k++) {
    long long n = out->xcount[k];
    if (!n) { /* no points: an empty collection (the readers reject empty DataItems) */
      fprintf(fp,
              "   <Grid Name=\"contact-points\" GridType=\"Collection\" CollectionType=\"Spatial\">\n    <Time "
              "Value=\"%.17g\"/>\n   </Grid>\n",
              out->xtime[k]);
      continue;
    }
    fprintf(fp, "   <Grid Name=\"contact-points\" GridType=\"Uniform\">\n    <Time Value=\"%.17g\"/>\n", out->xtime[k]);
    fprintf(fp, "    <Topology TopologyType=\"Polyvertex\" NumberOfElements=\"%lld\" NodesPerElement=\"1\">\n", n);
    PetscCall(PetscSNPrintf(dims, sizeof(dims), "%lld", n));
    PetscCall(PetscSNPrintf(path, sizeof(path), "/xdmf/frame%" PetscInt_FMT "/contacts/vertex", k));
    Item(fp, "     ", dims, "Int", base, path);
    fprintf(fp, "    </Topology>\n    <Geometry GeometryType=\"XYZ\">\n");
    PetscCall(PetscSNPrintf(dims, sizeof(dims), "%lld 3", n));
    PetscCall(PetscSNPrintf(path, sizeof(path), "/xdmf/frame%" PetscInt_FMT "/contacts/point_end", k));
    Item(fp, "     ", dims, "Float", base, path);
    fprintf(fp, "    </Geometry>\n");
    for (size_t a = 0; a < sizeof(attr) / sizeof(attr[0]); a++) {
      fprintf(fp, "    <Attribute Name=\"%s\" AttributeType=\"%s\" Center=\"Node\">\n", attr[a].name, attr[a].kind);
      if (attr[a].ncomp == 3)
        PetscCall(PetscSNPrintf(dims, sizeof(dims), "%lld 3", n));
      else
        PetscCall(PetscSNPrintf(dims, sizeof(dims), "%lld", n));
      PetscCall(PetscSNPrintf(path, sizeof(path), "/xdmf/frame%" PetscInt_FMT "/contacts/%s", k, attr[a].name));
      Item(fp, "     ", dims, attr[a].type, base, path);
      fprintf(fp, "    </Attribute>\n");
    }
    fprintf(fp, "   </Grid>\n");
  }
  fprintf(fp, "  </Grid>\n");
  PetscFunctionReturn(0);
}

PetscErrorCode FCXdmfWrite(FCOutput out)
{
  FILE       *fp;
  const char *base = strrchr(out->filename, '/');
  char        tmpname[PETSC_MAX_PATH_LEN];

  PetscFunctionBegin;
  base = base ? base + 1 : out->filename;
  PetscCall(PetscSNPrintf(tmpname, sizeof(tmpname), "%s.tmp", out->xdmfname));
  fp = fopen(tmpname, "w");
  PetscCheck(fp, PETSC_COMM_SELF, PETSC_ERR_FILE_OPEN, "Cannot write XDMF file '%s'", tmpname);
  fprintf(fp, "<?xml version=\"1.0\" ?>\n<Xdmf Version=\"3.0\">\n <Domain>\n");
  for (PetscInt i = 0; i < out->nbodies; i++) PetscCall(BodyGrid(out, fp, base, i));
  if (out->contacts) PetscCall(ContactGrid(out, fp, base));
  fprintf(fp, " </Domain>\n</Xdmf>\n");
  { /* a failed write (a full disk) leaves the previous index in place */
    int bad = ferror(fp), err = errno;
    if (fclose(fp)) bad = 1, err = errno;
    if (bad) {
      (void)remove(tmpname);
      errno = err;
      SETERRQ(PETSC_COMM_SELF, PETSC_ERR_FILE_WRITE, "Cannot write XDMF file '%s'", tmpname);
    }
  }
  PetscCheck(!rename(tmpname, out->xdmfname), PETSC_COMM_SELF, PETSC_ERR_FILE_WRITE, "Cannot rename '%s' to '%s'",
             tmpname, out->xdmfname);
  PetscFunctionReturn(0);
}
