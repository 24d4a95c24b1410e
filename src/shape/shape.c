/* Shapes of rigid and kinematic bodies: -<body>_shape plane|sphere|box|capsule|cylinder|mesh.
   Each shape lives in its own file, reads its own options and provides its mass properties
   (per unit density, about its centre, in the body frame) and a triangulated surface for
   pictures. The body frame has its origin at the shape's centre. */
#include "../fcimpl.h"

PetscFunctionList FCShapeList = NULL;

/* The built-in shapes: a new shape is one file with its create function, declared and registered here */
PETSC_INTERN PetscErrorCode FCShapeCreate_Plane(FCShape);
PETSC_INTERN PetscErrorCode FCShapeCreate_Sphere(FCShape);
PETSC_INTERN PetscErrorCode FCShapeCreate_Box(FCShape);
PETSC_INTERN PetscErrorCode FCShapeCreate_Capsule(FCShape);
PETSC_INTERN PetscErrorCode FCShapeCreate_Cylinder(FCShape);
PETSC_INTERN PetscErrorCode FCShapeCreate_Mesh(FCShape);

PetscErrorCode FCShapeRegister(const char name[], PetscErrorCode (*create)(FCShape))
{
  PetscFunctionBegin;
  FCValidPointer(name, 1);
  FCValidPointer(create, 2);
  PetscCall(PetscFunctionListAdd(&FCShapeList, name, create));
  PetscFunctionReturn(0);
}

PetscErrorCode FCShapeRegisterAll(void)
{
  PetscFunctionBegin;
  PetscCall(FCShapeRegister(FCSHAPEPLANE, FCShapeCreate_Plane));
  PetscCall(FCShapeRegister(FCSHAPESPHERE, FCShapeCreate_Sphere));
  PetscCall(FCShapeRegister(FCSHAPEBOX, FCShapeCreate_Box));
  PetscCall(FCShapeRegister(FCSHAPECAPSULE, FCShapeCreate_Capsule));
  PetscCall(FCShapeRegister(FCSHAPECYLINDER, FCShapeCreate_Cylinder));
  PetscCall(FCShapeRegister(FCSHAPEMESH, FCShapeCreate_Mesh));
  PetscFunctionReturn(0);
}

/* Options (prefix <body>_): -shape, read here, and each shape's own (-radius, -half_extents, -length,
   -normal) in its file: their help strings and docs/options.md. Capsule and cylinder axes are the
   body-frame z axis. */
PetscErrorCode FCShapeCreateFromOptions(MPI_Comm comm, const char prefix[], const char bodyname[], FCShape *shape)
{
  char      type[FC_MAX_NAME] = "";
  PetscBool set;
  PetscErrorCode (*create)(FCShape) = NULL;
  FCShape s;

  PetscFunctionBegin;
  PetscOptionsBegin(comm, prefix, "Shape options", "FCShape");
  PetscCall(PetscOptionsFList("-shape", "Shape of a rigid or kinematic body", NULL, FCShapeList, type, type,
                              sizeof(type), &set));
  PetscOptionsEnd();
  PetscCheck(set, comm, PETSC_ERR_USER_INPUT,
             "Body '%s' needs -%sshape (plane, sphere, box, capsule, cylinder or mesh)", bodyname, prefix);
  {
    char option[FC_MAX_NAME + 8];
    PetscCall(PetscSNPrintf(option, sizeof(option), "-%sshape", prefix));
    PetscCall(FCRegistryFind(comm, FCShapeList, "shape", option, type, (void (**)(void)) & create));
  }
  PetscCall(PetscNew(&s));
  PetscCall(PetscStrncpy(s->type, type, sizeof(s->type)));
  s->bounded = PETSC_TRUE;
  PetscCall((*create)(s));
  if (s->setfromoptions) {
    PetscOptionsBegin(comm, prefix, "Shape options", "FCShape");
    PetscCall((*s->setfromoptions)(PetscOptionsObject, s, bodyname));
    PetscOptionsEnd();
  }
  if (s->setup) PetscCall((*s->setup)(s, comm, prefix, bodyname));
  *shape = s;
  PetscFunctionReturn(0);
}

PetscErrorCode FCShapeDestroy(FCShape *shape)
{
  PetscFunctionBegin;
  if (!*shape) PetscFunctionReturn(0);
  if ((*shape)->destroy) PetscCall((*(*shape)->destroy)(*shape));
  PetscCall(PetscFree(*shape));
  PetscFunctionReturn(0);
}
