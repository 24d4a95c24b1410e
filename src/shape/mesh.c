/* A rigid (or kinematic) body whose shape is a tetrahedral mesh: -<body>_dm_plex_filename.
   Mass properties are integrated over the tetrahedra; the centre is the mesh centroid. */
#include "../fcimpl.h"

static PetscErrorCode SetUp_Mesh(FCShape s, MPI_Comm comm, const char prefix[], const char bodyname[])
{
  FCMesh *mesh;

  PetscFunctionBegin;
  PetscCall(PetscNew(&mesh));
  PetscCall(FCMeshLoad(comm, prefix, bodyname, mesh));
  PetscCall(FCMeshCheckCells(mesh, bodyname));
  s->data = mesh;
  PetscFunctionReturn(0);
}

/* About the centroid; the centroid itself is moved to the body origin by the rigid body */
static PetscErrorCode MassProperties_Mesh(FCShape s, PetscReal *V, PetscReal J[9])
{
  PetscReal c[3];

  PetscFunctionBegin;
  PetscCall(FCMeshComputeMassProperties((FCMesh *)s->data, V, c, J));
  PetscFunctionReturn(0);
}

static PetscErrorCode Destroy_Mesh(FCShape s)
{
  PetscFunctionBegin;
  if (s->data) PetscCall(FCMeshDestroy((FCMesh *)s->data));
  PetscCall(PetscFree(s->data));
  PetscFunctionReturn(0);
}

PetscErrorCode FCShapeCreate_Mesh(FCShape s)
{
  PetscFunctionBegin;
  s->setup          = SetUp_Mesh;
  s->massproperties = MassProperties_Mesh;
  s->destroy        = Destroy_Mesh;
  PetscFunctionReturn(0);
}
