/* XDMF index of the HDF5 output, so that ParaView opens the run (File > Open out.xmf): one
   temporal collection per body, each frame a hyperslab of /bodies/<name>/positions. */
#include "../fcimpl.h"
#include <errno.h>

PetscErrorCode FCXdmfWrite(const char h5name[], const char xmfname[], PetscInt nbodies, FCBody bodies[],
                           PetscInt nframes, const PetscReal times[])
{
  FILE       *fp;
  const char *base = strrchr(h5name, '/');
  char        tmpname[PETSC_MAX_PATH_LEN];

  PetscFunctionBegin;
  base = base ? base + 1 : h5name;
  PetscCall(PetscSNPrintf(tmpname, sizeof(tmpname), "%s.tmp", xmfname));
  fp = fopen(tmpname, "w");
  PetscCheck(fp, PETSC_COMM_SELF, PETSC_ERR_FILE_OPEN, "Cannot write XDMF file '%s'", tmpname);
  fprintf(fp, "<?xml version=\"1.0\" ?>\n<Xdmf Version=\"3.0\">\n <Domain>\n");
  for (PetscInt i = 0; i < nbodies; i++) {
    const FCBodyVisual *vis;
    const char         *topo, *name;
    PetscCall(FCBodyGetVisual(bodies[i], &vis));
    PetscCall(FCBodyGetName(bodies[i], &name));
    topo = vis->nvpc == 4 ? "Tetrahedron" : "Triangle";
    fprintf(fp, "  <Grid Name=\"%s\" GridType=\"Collection\" CollectionType=\"Temporal\">\n", name);
    for (PetscInt f = 0; f < nframes; f++) {
      fprintf(fp, "   <Grid Name=\"%s\" GridType=\"Uniform\">\n    <Time Value=\"%.10g\"/>\n", name, (double)times[f]);
      fprintf(fp, "    <Topology TopologyType=\"%s\" NumberOfElements=\"%" PetscInt_FMT "\">\n", topo, vis->nc_global);
      fprintf(fp,
              "     <DataItem Dimensions=\"%" PetscInt_FMT " %" PetscInt_FMT
              "\" NumberType=\"Int\" Precision=\"8\" Format=\"HDF\">%s:/bodies/%s/mesh/cells</DataItem>\n",
              vis->nc_global, vis->nvpc, base, name);
      fprintf(fp, "    </Topology>\n    <Geometry GeometryType=\"XYZ\">\n");
      fprintf(fp, "     <DataItem ItemType=\"HyperSlab\" Dimensions=\"%" PetscInt_FMT " 3\">\n", vis->nv_global);
      fprintf(fp,
              "      <DataItem Dimensions=\"3 3\" Format=\"XML\">%" PetscInt_FMT " 0 0 1 1 1 1 %" PetscInt_FMT
              " 3</DataItem>\n",
              f, vis->nv_global);
      fprintf(fp,
              "      <DataItem Dimensions=\"%" PetscInt_FMT " %" PetscInt_FMT
              " 3\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">%s:/bodies/%s/positions</DataItem>\n",
              nframes, vis->nv_global, base, name);
      fprintf(fp, "     </DataItem>\n    </Geometry>\n   </Grid>\n");
    }
    fprintf(fp, "  </Grid>\n");
  }
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
  PetscCheck(!rename(tmpname, xmfname), PETSC_COMM_SELF, PETSC_ERR_FILE_WRITE, "Cannot rename '%s' to '%s'", tmpname,
             xmfname);
  PetscFunctionReturn(0);
}
