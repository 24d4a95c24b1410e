/* FCBody: one body of the scene, of type fem, rigid or kinematic (-<body>_type, a registry). The
   generic part holds the placement and initial motion options shared by every type (-<body>_center,
   -rotate, -translate, -velocity, -angular_velocity; help strings below and docs/options.md). */
#include "bodyimpl.h"
#include <ctype.h>

PetscFunctionList FCBodyList = NULL;

PetscErrorCode FCBodyRegister(const char name[], PetscErrorCode (*create)(FCBody))
{
  PetscFunctionBegin;
  FCValidPointer(name, 1);
  FCValidPointer(create, 2);
  PetscCall(PetscFunctionListAdd(&FCBodyList, name, create));
  PetscFunctionReturn(0);
}

/* The built-in body types: a new type is one file with its create function, declared and registered here */
PETSC_INTERN PetscErrorCode FCBodyCreate_FEM(FCBody);
PETSC_INTERN PetscErrorCode FCBodyCreate_Rigid(FCBody);
PETSC_INTERN PetscErrorCode FCBodyCreate_Kinematic(FCBody);

PetscErrorCode FCBodyRegisterAll(void)
{
  PetscFunctionBegin;
  PetscCall(FCBodyRegister(FCBODYFEM, FCBodyCreate_FEM));
  PetscCall(FCBodyRegister(FCBODYRIGID, FCBodyCreate_Rigid));
  PetscCall(FCBodyRegister(FCBODYKINEMATIC, FCBodyCreate_Kinematic));
  PetscFunctionReturn(0);
}

PetscErrorCode FCBodyCreate(MPI_Comm comm, const char name[], FCBody *body)
{
  FCBody b;
  size_t len;

  PetscFunctionBegin;
  FCValidPointer(name, 2);
  FCValidPointer(body, 3);
  PetscCall(FCInitializePackage());
  PetscCall(PetscStrlen(name, &len));
  PetscCheck(len > 0 && len < FC_MAX_NAME - 1, comm, PETSC_ERR_USER_INPUT,
             "Body name '%s' must have 1 to %d characters", name, FC_MAX_NAME - 2);
  for (size_t i = 0; i < len; i++)
    PetscCheck(isalnum((unsigned char)name[i]) || name[i] == '_', comm, PETSC_ERR_USER_INPUT,
               "Body name '%s' may only contain letters, digits and '_'", name);
  PetscCheck(!isdigit((unsigned char)name[0]), comm, PETSC_ERR_USER_INPUT, "Body name '%s' must not start with a digit",
             name);
  PetscCall(PetscNew(&b));
  b->comm = comm;
  PetscCall(PetscStrncpy(b->name, name, sizeof(b->name)));
  PetscCall(PetscSNPrintf(b->prefix, sizeof(b->prefix), "%s_", name));
  b->rotate[2] = 1.0; /* axis z, angle 0 */
  b->h         = 0.01;
  *body        = b;
  PetscFunctionReturn(0);
}

PetscErrorCode FCBodySetType(FCBody body, FCBodyType type)
{
  PetscErrorCode (*create)(FCBody) = NULL;

  PetscFunctionBegin;
  FCValidPointer(body, 1);
  FCValidPointer(type, 2);
  PetscCheck(!body->data, body->comm, PETSC_ERR_ORDER, "Body '%s' already has a type", body->name);
  {
    char option[FC_MAX_NAME + 8];
    PetscCall(PetscSNPrintf(option, sizeof(option), "-%stype", body->prefix));
    PetscCall(FCRegistryFind(body->comm, FCBodyList, "body type", option, type, (void (**)(void)) & create));
  }
  PetscCall(PetscStrncpy(body->type, type, sizeof(body->type)));
  PetscCall((*create)(body));
  PetscFunctionReturn(0);
}

PetscErrorCode FCBodyGetType(FCBody body, FCBodyType *type)
{
  PetscFunctionBegin;
  FCValidPointer(body, 1);
  FCValidPointer(type, 2);
  *type = body->type;
  PetscFunctionReturn(0);
}

PetscErrorCode FCBodyGetName(FCBody body, const char **name)
{
  PetscFunctionBegin;
  FCValidPointer(body, 1);
  FCValidPointer(name, 2);
  *name = body->name;
  PetscFunctionReturn(0);
}

PetscErrorCode FCBodyReadPlacement(FCBody body)
{
  PetscFunctionBegin;
  PetscOptionsBegin(body->comm, body->prefix, "Body placement and initial motion", "FCBody");
  PetscCall(
      FCOptionsRealArray(PetscOptionsObject, "-center", "Centre of rotation", 3, body->center, &body->center_set));
  PetscCall(FCOptionsRealArray(PetscOptionsObject, "-rotate", "Initial rotation: axis x,y,z and angle in degrees", 4,
                               body->rotate, NULL));
  PetscCall(FCOptionsRealArray(PetscOptionsObject, "-translate", "Initial translation", 3, body->translate, NULL));
  PetscCall(
      FCOptionsRealArray(PetscOptionsObject, "-velocity", "Initial (or prescribed) velocity", 3, body->velocity, NULL));
  PetscCall(FCOptionsRealArray(PetscOptionsObject, "-angular_velocity",
                               "Initial (or prescribed) angular velocity about the centre, rad/s", 3,
                               body->angular_velocity, NULL));
  PetscOptionsEnd();
  PetscCheck(body->rotate[3] == 0.0 || FCDot(body->rotate, body->rotate) > 0.0, body->comm, PETSC_ERR_USER_INPUT,
             "Option -%srotate: the rotation axis must be non-zero", body->prefix);
  PetscFunctionReturn(0);
}

void FCBodyPlacementRotation(FCBody body, PetscReal R[9])
{
  PetscReal q[4];
  FCQuatFromAxisAngle(body->rotate, body->rotate[3] * PETSC_PI / 180.0, q);
  FCQuatToMat3(q, R);
}

PetscErrorCode FCBodySetFromOptions(FCBody body)
{
  char      type[FC_MAX_NAME] = "";
  PetscBool set;

  PetscFunctionBegin;
  FCValidPointer(body, 1);
  PetscOptionsBegin(body->comm, body->prefix, "Body options", "FCBody");
  PetscCall(PetscOptionsFList("-type", "Body type", "FCBodySetType", FCBodyList, body->type, type, sizeof(type), &set));
  PetscOptionsEnd();
  if (set) PetscCall(FCBodySetType(body, type));
  PetscCheck(body->data || body->type[0], body->comm, PETSC_ERR_USER_INPUT,
             "Body '%s' needs -%stype (fem, rigid or kinematic)", body->name, body->prefix);
  PetscCall(FCBodyReadPlacement(body));
  if (body->ops.setfromoptions) PetscCall((*body->ops.setfromoptions)(body));
  PetscFunctionReturn(0);
}

PetscErrorCode FCBodySetTimeStep(FCBody body, PetscReal h)
{
  PetscFunctionBegin;
  FCValidPointer(body, 1);
  PetscCheck(!body->setupcalled, body->comm, PETSC_ERR_ORDER, "Set the time step of body '%s' before FCBodySetUp()",
             body->name);
  body->h = h;
  PetscFunctionReturn(0);
}

PetscErrorCode FCBodyChangeTimeStep(FCBody body, PetscReal h)
{
  PetscFunctionBegin;
  if (h == body->h) PetscFunctionReturn(0);
  body->h = h;
  if (body->setupcalled && body->ops.changetimestep) PetscCall((*body->ops.changetimestep)(body));
  PetscFunctionReturn(0);
}

/* Quasi-static analysis (-time_integration static, read by the scene): no inertia, each step the
   equilibrium of its time; only FE and kinematic bodies take part */
PetscErrorCode FCBodySetQuasiStatic(FCBody body, PetscBool quasistatic)
{
  PetscFunctionBegin;
  FCValidPointer(body, 1);
  PetscCheck(!body->setupcalled, body->comm, PETSC_ERR_ORDER, "Set the analysis of body '%s' before FCBodySetUp()",
             body->name);
  body->quasistatic = quasistatic;
  PetscFunctionReturn(0);
}

/* The scene's bodies (by name, for -<name>_attach), before FCBodySetUp() */
PetscErrorCode FCBodySetSceneBodies(FCBody body, PetscInt n, FCBody bodies[])
{
  PetscFunctionBegin;
  FCValidPointer(body, 1);
  body->nscene = n;
  body->scene  = bodies;
  PetscFunctionReturn(0);
}

/* The scene's contact set, whose contacts and forces are those of the last step, and this body's
   index in the scene (for the fields that show them) */
PetscErrorCode FCBodySetStepContacts(FCBody body, PetscInt self, const FCContactSet *set)
{
  PetscFunctionBegin;
  body->self     = self;
  body->contacts = set;
  PetscFunctionReturn(0);
}

/* The scene's time before a step (0 at set-up, the stored time at a restart) */
PetscErrorCode FCBodySetTime(FCBody body, PetscReal t)
{
  PetscFunctionBegin;
  FCValidPointer(body, 1);
  if (body->ops.settime) PetscCall((*body->ops.settime)(body, t));
  PetscFunctionReturn(0);
}

/* A prescribed body's pose at any time */
PetscErrorCode FCBodyGetPoseAt(FCBody body, PetscReal t, PetscReal x[3], PetscReal q[4])
{
  PetscFunctionBegin;
  FCValidPointer(body, 1);
  FCValidPointer(x, 3);
  FCValidPointer(q, 4);
  PetscCheck(body->ops.poseat, body->comm, PETSC_ERR_SUP, "Body '%s' (type %s) has no prescribed pose", body->name,
             body->type);
  PetscCall((*body->ops.poseat)(body, t, x, q));
  PetscFunctionReturn(0);
}

PetscErrorCode FCBodySetGravity(FCBody body, const PetscReal g[3])
{
  PetscFunctionBegin;
  FCValidPointer(body, 1);
  FCValidPointer(g, 2);
  for (int i = 0; i < 3; i++) body->gravity[i] = g[i];
  PetscFunctionReturn(0);
}

PetscErrorCode FCBodySetUp(FCBody body)
{
  PetscFunctionBegin;
  FCValidPointer(body, 1);
  if (body->setupcalled) PetscFunctionReturn(0);
  PetscCheck(body->type[0], body->comm, PETSC_ERR_ORDER, "Body '%s' has no type", body->name);
  PetscCheck(!body->quasistatic || body->deformable || body->prescribed, body->comm, PETSC_ERR_USER_INPUT,
             "-time_integration static: body '%s' is %s, which has no static equilibrium of its own; make it kinematic "
             "(-%stype kinematic) or run -time_integration euler",
             body->name, body->type, body->prefix);
  PetscCall((*body->ops.setup)(body));
  body->setupcalled = PETSC_TRUE;
  PetscFunctionReturn(0);
}

PetscErrorCode FCBodyComputeFreeMotion(FCBody body, PetscReal t)
{
  PetscFunctionBegin;
  FCValidPointer(body, 1);
  if (body->ops.freemotion) PetscCall((*body->ops.freemotion)(body, t));
  PetscFunctionReturn(0);
}

PetscErrorCode FCBodyIntegrate(FCBody body, PetscReal t)
{
  PetscFunctionBegin;
  FCValidPointer(body, 1);
  PetscCall(FCPhaseBegin(FC_PHASE_INTEGRATION));
  PetscCall((*body->ops.integrate)(body, t));
  PetscCall(FCPhaseEnd(FC_PHASE_INTEGRATION));
  PetscFunctionReturn(0);
}

PetscErrorCode FCBodyGetCentroid(FCBody body, PetscReal c[3])
{
  PetscFunctionBegin;
  FCValidPointer(body, 1);
  FCValidPointer(c, 2);
  PetscCall((*body->ops.getcentroid)(body, c));
  PetscFunctionReturn(0);
}

PetscErrorCode FCBodyGetRotation(FCBody body, PetscReal q[4], PetscBool *has)
{
  PetscFunctionBegin;
  FCValidPointer(body, 1);
  FCValidPointer(q, 2);
  FCValidPointer(has, 3);
  *has = PETSC_FALSE;
  if (body->ops.getrotation) PetscCall((*body->ops.getrotation)(body, q, has));
  PetscFunctionReturn(0);
}

/* The work of the body's prescribed motions and loads so far, in magnitude (0: none) */
PetscErrorCode FCBodyGetExternalWork(FCBody body, PetscReal *w)
{
  PetscFunctionBegin;
  FCValidPointer(body, 1);
  FCValidPointer(w, 2);
  *w = 0.0;
  if (body->ops.getexternalwork) PetscCall((*body->ops.getexternalwork)(body, w));
  PetscFunctionReturn(0);
}

PetscErrorCode FCBodyGetSolverCounts(FCBody body, PetscInt *nfactor, PetscInt *nkrylov, PetscInt *nnewton)
{
  PetscFunctionBegin;
  FCValidPointer(body, 1);
  FCValidPointer(nfactor, 2);
  FCValidPointer(nkrylov, 3);
  FCValidPointer(nnewton, 4);
  *nfactor = *nkrylov = *nnewton = 0;
  if (body->ops.getsolvercounts) PetscCall((*body->ops.getsolvercounts)(body, nfactor, nkrylov, nnewton));
  PetscFunctionReturn(0);
}

PetscErrorCode FCBodyGetInverted(FCBody body, FCInverted *inv, PetscBool *has)
{
  PetscFunctionBegin;
  FCValidPointer(body, 1);
  FCValidPointer(inv, 2);
  FCValidPointer(has, 3);
  *has = PETSC_FALSE;
  if (body->ops.getinverted) PetscCall((*body->ops.getinverted)(body, inv, has));
  PetscFunctionReturn(0);
}

/* Bytes this rank holds for the body's contact compliance: W_b, Sigma / C and its factorization
   (MUMPS' own count) */
PetscErrorCode FCBodyGetContactMemory(FCBody body, PetscReal bytes[3])
{
  PetscFunctionBegin;
  bytes[0] = bytes[1] = bytes[2] = 0.0;
  if (body->ops.getcontactmemory) PetscCall((*body->ops.getcontactmemory)(body, bytes));
  PetscFunctionReturn(0);
}

/* The body's constrained regions and their reactions of the last step (none: n = 0) */
PetscErrorCode FCBodyGetReactions(FCBody body, PetscInt *n, const char ***names, const PetscReal **values)
{
  PetscFunctionBegin;
  FCValidPointer(body, 1);
  FCValidPointer(n, 2);
  *n = 0;
  if (names) *names = NULL;
  if (values) *values = NULL;
  if (body->ops.getreactions) PetscCall((*body->ops.getreactions)(body, n, names, values));
  PetscFunctionReturn(0);
}

/* What identifies the body's regions from one run to the next (a restart's check): n entries,
   names "kind:region" separated by '\n', 4 values each (a constraint's vertex count and their
   reference centroid); none: n = 0, names "". Collective; the caller PetscFrees names and values */
PetscErrorCode FCBodyGetRegions(FCBody body, PetscInt *n, char **names, PetscReal **values)
{
  PetscFunctionBegin;
  if (body->ops.getregions) {
    PetscCall((*body->ops.getregions)(body, n, names, values));
    PetscFunctionReturn(0);
  }
  *n = 0;
  PetscCall(PetscStrallocpy("", names));
  PetscCall(PetscCalloc1(1, values));
  PetscFunctionReturn(0);
}

PetscErrorCode FCBodyGetEnergy(FCBody body, FCEnergy *E)
{
  PetscFunctionBegin;
  FCValidPointer(body, 1);
  FCValidPointer(E, 2);
  E->kinetic = E->elastic = E->gravity = 0.0;
  if (body->ops.getenergy) PetscCall((*body->ops.getenergy)(body, E));
  PetscFunctionReturn(0);
}

PetscErrorCode FCBodyGetVisual(FCBody body, const FCBodyVisual **vis)
{
  PetscFunctionBegin;
  FCValidPointer(body, 1);
  FCValidPointer(vis, 2);
  *vis = &body->visual;
  PetscFunctionReturn(0);
}

PetscErrorCode FCBodyGetVisualPositions(FCBody body, PetscReal x[])
{
  PetscFunctionBegin;
  FCValidPointer(body, 1);
  FCValidPointer(x, 2);
  PetscCall((*body->ops.getvisualpositions)(body, x));
  PetscFunctionReturn(0);
}

/* A state with NaN or Inf stops the run with the step and the body named */
PetscErrorCode FCBodyCheckState(FCBody body, PetscInt step)
{
  PetscFunctionBegin;
  FCValidPointer(body, 1);
  if (body->ops.checkstate) PetscCall((*body->ops.checkstate)(body, step));
  PetscFunctionReturn(0);
}

/* Pictures of analytic shapes: the tessellation lives on rank 0 of the body's communicator */
PetscErrorCode FCBodyVisualFromShape(FCBody body, FCShape shape)
{
  PetscMPIInt   rank;
  FCBodyVisual *vis = &body->visual;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_rank(body->comm, &rank));
  vis->nvpc = 3;
  if (rank == 0) {
    PetscInt nt;
    PetscCall((*shape->tessellate)(shape, &vis->nv, &vis->reference, &nt, &vis->cells));
    vis->nc = nt;
  }
  PetscCallMPI(MPI_Bcast(&vis->nv, 1, MPIU_INT, 0, body->comm));
  PetscCallMPI(MPI_Bcast(&vis->nc, 1, MPIU_INT, 0, body->comm));
  vis->nv_global = vis->nv;
  vis->nc_global = vis->nc;
  if (rank) vis->nv = vis->nc = 0;
  vis->vstart = vis->cstart = 0;
  PetscFunctionReturn(0);
}

PetscErrorCode FCBodyVisualDestroy(FCBodyVisual *vis)
{
  PetscFunctionBegin;
  PetscCall(PetscFree(vis->cells));
  PetscCall(PetscFree(vis->reference));
  PetscCall(PetscFree(vis->origin));
  PetscFunctionReturn(0);
}

PetscErrorCode FCBodyDestroy(FCBody *body)
{
  PetscFunctionBegin;
  FCValidPointer(body, 1);
  if (!*body) PetscFunctionReturn(0);
  if ((*body)->ops.destroy) PetscCall((*(*body)->ops.destroy)(*body));
  PetscCall(FCBodyVisualDestroy(&(*body)->visual));
  PetscCall(PetscFree(*body));
  PetscFunctionReturn(0);
}
