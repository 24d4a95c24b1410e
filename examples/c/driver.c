/* A program that drives a fecontact scene through the public C API (include/fecontact.h): the
   scene of an options file (the executable's options), stepped here, with one kinematic body
   steered by this program. Each step it moves the body along x towards a target and back (a pose
   per step, FCBodySetKinematicPose) and prints the contact force on it, read from the step's
   contacts (FCSceneGetContacts).

     driver -options_file input/finger_push.opts -driver_body tool -driver_travel 0.03
   moves the tool of input/finger_push.opts 3 cm in along -x over the first half of the run and back
   over the second half. Build it against an installed fecontact with
     cc driver.c $(pkg-config --cflags --libs fecontact) -o driver
   or with CMake (examples/c/CMakeLists.txt: find_package(fecontact)). */
#include <fecontact.h>

static const char help[] = "Drives a fecontact scene: a kinematic body moved by this program.\n";

/* The force the contacts of the last step put on body ib (a contact's force_world acts on its first body) */
static PetscErrorCode ForceOn(FCScene scene, PetscInt ib, PetscReal F[3], PetscInt *ncontacts)
{
  PetscInt       n;
  FCContactInfo *info;

  PetscFunctionBeginUser;
  PetscCall(FCSceneGetContacts(scene, &n, NULL));
  PetscCall(PetscMalloc1(n + 1, &info));
  PetscCall(FCSceneGetContacts(scene, &n, info));
  F[0] = F[1] = F[2] = 0.0;
  *ncontacts         = 0;
  for (PetscInt k = 0; k < n; k++)
    for (int s = 0; s < 2; s++)
      if (info[k].body[s] == ib) {
        for (int d = 0; d < 3; d++) F[d] += (s ? -1.0 : 1.0) * info[k].force_world[d];
        (*ncontacts)++;
      }
  PetscCall(PetscFree(info));
  PetscFunctionReturn(0);
}

static PetscErrorCode Drive(void)
{
  FCScene   scene;
  FCBody    body;
  char      name[64] = "tool";
  PetscReal travel   = 0.03, h, x0[3], q0[4];
  PetscInt  nsteps, nbodies, ib = -1;
  PetscBool has;

  PetscFunctionBeginUser;
  PetscOptionsBegin(PETSC_COMM_WORLD, NULL, "Driver options", NULL);
  PetscCall(PetscOptionsString("-driver_body", "The kinematic body this program moves", NULL, name, name, sizeof(name),
                               NULL));
  PetscCall(PetscOptionsReal("-driver_travel", "How far it moves along -x and back (m)", NULL, travel, &travel, NULL));
  PetscOptionsEnd();
  PetscCall(FCSceneCreate(PETSC_COMM_WORLD, &scene));
  PetscCall(FCSceneSetFromOptions(scene));
  PetscCall(FCSceneSetUp(scene));
  PetscCall(FCSceneGetBody(scene, name, &body));
  PetscCall(FCSceneGetNumBodies(scene, &nbodies));
  for (PetscInt i = 0; i < nbodies; i++) { /* its index, which the contacts name it by */
    FCBody b;
    PetscCall(FCSceneGetBodyByIndex(scene, i, &b));
    if (b == body) ib = i;
  }
  PetscCall(FCSceneGetTimeStep(scene, &h, &nsteps));
  PetscCall(FCBodyGetCentroid(body, x0));
  PetscCall(FCBodyGetRotation(body, q0, &has));
  for (PetscInt k = 1; k <= nsteps; k++) {
    PetscReal s = 2.0 * k / nsteps, x[3] = {x0[0] - travel * (s <= 1.0 ? s : 2.0 - s), x0[1], x0[2]}, F[3], t;
    PetscInt  step, nc;
    PetscCall(FCBodySetKinematicPose(body, x, q0)); /* where it is at the end of this step */
    PetscCall(FCSceneStep(scene));
    PetscCall(FCSceneGetTime(scene, &t, &step));
    PetscCall(ForceOn(scene, ib, F, &nc));
    PetscCall(PetscPrintf(PETSC_COMM_WORLD,
                          "step %3" PetscInt_FMT "  t %.3f  %s x %.5f  %2" PetscInt_FMT
                          " contacts  force on it (%.5g, %.5g, %.5g) N\n",
                          step, (double)t, name, (double)x[0], nc, (double)F[0], (double)F[1], (double)F[2]));
  }
  PetscCall(FCSceneFinish(scene));
  PetscCall(FCSceneDestroy(&scene));
  PetscFunctionReturn(0);
}

int main(int argc, char **argv)
{
  PetscCall(PetscInitialize(&argc, &argv, NULL, help));
  PetscCall(FCPushErrorHandler(PETSC_TRUE)); /* a wrong option: one line, not a traceback */
  PetscCall(Drive());
  PetscCall(PetscFinalize());
  return 0;
}
