/* FCBody, what a program steers and reads (include/fecontact.h): a kinematic body's pose and
   velocity set from a program, the same on every rank, and the velocities and the picture's
   positions and point velocities read back. */
#include "bodyimpl.h"

/* A program's motion of a kinematic body (n values: pose or velocities) must be the same on every rank,
   or the ranks would hold different scenes: compared collectively (largest and smallest value of
   each), and an error on every rank naming the body when they differ or one is not finite */
static PetscErrorCode CheckSameOnRanks(FCBody body, const char what[], PetscInt n, const PetscReal a[])
{
  PetscReal buf[2 * 7 + 1] = {0};

  PetscFunctionBegin;
  PetscCheck(n <= 7, PETSC_COMM_SELF, PETSC_ERR_PLIB, "%" PetscInt_FMT " values", n);
  for (PetscInt d = 0; d < n; d++) {
    if (PetscIsInfOrNanReal(a[d]))
      buf[2 * n] = 1.0;
    else {
      buf[d]     = a[d];
      buf[n + d] = -a[d];
    }
  }
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, buf, 2 * n + 1, MPIU_REAL, MPIU_MAX, body->comm));
  PetscCheck(buf[2 * n] == 0.0, body->comm, PETSC_ERR_USER_INPUT,
             "Body '%s': its %s is not finite (on at least one rank)", body->name, what);
  for (PetscInt d = 0; d < n; d++)
    PetscCheck(buf[d] == -buf[n + d], body->comm, PETSC_ERR_USER_INPUT,
               "Body '%s': its %s differs between the ranks (component %" PetscInt_FMT " from %.17g to %.17g): every "
               "rank must give the same values",
               body->name, what, d, (double)-buf[n + d], (double)buf[d]);
  PetscFunctionReturn(0);
}

PetscErrorCode FCBodySetKinematicPose(FCBody body, const PetscReal x[3], const PetscReal q[4])
{
  PetscReal n = 0.0;

  PetscFunctionBegin;
  FCValidPointer(body, 1);
  FCValidPointer(x, 2);
  FCValidPointer(q, 3);
  PetscCheck(body->ops.setkinematicpose, body->comm, PETSC_ERR_USER_INPUT,
             "Body '%s' is %s, not kinematic: only a kinematic body's pose can be set", body->name, body->type);
  PetscCheck(body->setupcalled, body->comm, PETSC_ERR_ORDER,
             "Body '%s': set the scene up (FCSceneSetUp) before setting its pose: its motion starts from its placement",
             body->name);
  {
    PetscReal xq[7] = {x[0], x[1], x[2], q[0], q[1], q[2], q[3]};
    PetscCall(CheckSameOnRanks(body, "pose (position, quaternion)", 7, xq));
  }
  for (int d = 0; d < 4; d++) n += q[d] * q[d];
  for (int d = 0; d < 3; d++)
    PetscCheck(!PetscIsInfOrNanReal(x[d]), body->comm, PETSC_ERR_USER_INPUT,
               "Body '%s': pose position %g, %g, %g is not finite", body->name, (double)x[0], (double)x[1],
               (double)x[2]);
  PetscCheck(n > 0.0 && !PetscIsInfOrNanReal(n), body->comm, PETSC_ERR_USER_INPUT,
             "Body '%s': pose quaternion %g, %g, %g, %g is not a rotation (zero or not finite)", body->name,
             (double)q[0], (double)q[1], (double)q[2], (double)q[3]);
  PetscCall((*body->ops.setkinematicpose)(body, x, q));
  PetscFunctionReturn(0);
}

PetscErrorCode FCBodySetKinematicVelocity(FCBody body, const PetscReal v[3], const PetscReal w[3])
{
  PetscFunctionBegin;
  FCValidPointer(body, 1);
  FCValidPointer(v, 2);
  FCValidPointer(w, 3);
  PetscCheck(body->ops.setkinematicvel, body->comm, PETSC_ERR_USER_INPUT,
             "Body '%s' is %s, not kinematic: only a kinematic body's velocity can be set", body->name, body->type);
  PetscCheck(body->setupcalled, body->comm, PETSC_ERR_ORDER,
             "Body '%s': set the scene up (FCSceneSetUp) before setting its velocity: its motion starts from its "
             "placement",
             body->name);
  {
    PetscReal vw[6] = {v[0], v[1], v[2], w[0], w[1], w[2]};
    PetscCall(CheckSameOnRanks(body, "velocity (linear, angular)", 6, vw));
  }
  for (int d = 0; d < 3; d++)
    PetscCheck(!PetscIsInfOrNanReal(v[d]) && !PetscIsInfOrNanReal(w[d]), body->comm, PETSC_ERR_USER_INPUT,
               "Body '%s': velocity %g, %g, %g or angular velocity %g, %g, %g is not finite", body->name, (double)v[0],
               (double)v[1], (double)v[2], (double)w[0], (double)w[1], (double)w[2]);
  PetscCall((*body->ops.setkinematicvel)(body, v, w));
  PetscFunctionReturn(0);
}

PetscErrorCode FCBodyGetVelocity(FCBody body, PetscReal v[3], PetscReal w[3])
{
  PetscFunctionBegin;
  FCValidPointer(body, 1);
  FCValidPointer(v, 2);
  FCValidPointer(w, 3);
  PetscCheck(body->ops.getvelocity, body->comm, PETSC_ERR_USER_INPUT,
             "Body '%s' is %s: its vertices' velocities are FCBodyGetVelocities", body->name, body->type);
  PetscCall((*body->ops.getvelocity)(body, v, w));
  PetscFunctionReturn(0);
}

/* This rank's values of the picture (positions, or a point field), or all of them on every rank in
   the global order */
static PetscErrorCode PictureValues(FCBody body, PetscBool velocity, PetscBool gathered, PetscInt *n, PetscReal x[])
{
  const FCBodyVisual *vis = &body->visual;
  PetscReal          *mine;
  PetscBool           has = PETSC_TRUE;

  PetscFunctionBegin;
  *n = gathered ? vis->nv_global : vis->nv;
  if (!x) PetscFunctionReturn(0);
  PetscCall(PetscMalloc1(3 * vis->nv + 1, &mine));
  if (velocity)
    PetscCall(FCBodyGetVisualField(body, FC_FIELD_VELOCITY, mine, &has));
  else
    PetscCall(FCBodyGetVisualPositions(body, mine));
  PetscCheck(has, body->comm, PETSC_ERR_USER_INPUT, "Body '%s' has no vertex velocities", body->name);
  if (gathered) { /* the owned ranges tile the global numbering in rank order */
    PetscReal *all;
    PetscInt   total;
    PetscCall(FCAllgatherRecords(body->comm, vis->nv, 3 * sizeof(PetscReal), mine, &total, (void **)&all));
    PetscCall(PetscArraycpy(x, all, 3 * total));
    PetscCall(PetscFree(all));
  } else
    PetscCall(PetscArraycpy(x, mine, 3 * vis->nv));
  PetscCall(PetscFree(mine));
  PetscFunctionReturn(0);
}

PetscErrorCode FCBodyGetPositions(FCBody body, PetscBool gathered, PetscInt *n, PetscReal x[])
{
  PetscFunctionBegin;
  FCValidPointer(body, 1);
  FCValidPointer(n, 3);
  PetscCall(PictureValues(body, PETSC_FALSE, gathered, n, x));
  PetscFunctionReturn(0);
}

PetscErrorCode FCBodyGetVelocities(FCBody body, PetscBool gathered, PetscInt *n, PetscReal v[])
{
  PetscFunctionBegin;
  FCValidPointer(body, 1);
  FCValidPointer(n, 3);
  PetscCall(PictureValues(body, PETSC_TRUE, gathered, n, v));
  PetscFunctionReturn(0);
}
