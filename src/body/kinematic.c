/* Kinematic body: a shape moved by a prescribed constant twist (-<body>_velocity of its centre
   and -<body>_angular_velocity about it), never solved for:
       x(t) = x0 + v t,   q(t) = exp(t w / 2) q0   (exact, no drift). */
#include "pose.h"

typedef struct {
  FCPose pose;
} Kinematic;

static PetscErrorCode SetUp_Kinematic(FCBody body)
{
  PetscFunctionBegin;
  PetscCall(FCPoseSetUp(body, &((Kinematic *)body->data)->pose));
  PetscFunctionReturn(0);
}

static PetscErrorCode Integrate_Kinematic(FCBody body, PetscReal t)
{
  FCPose   *P  = &((Kinematic *)body->data)->pose;
  PetscReal tn = t + body->h;

  PetscFunctionBegin;
  for (int d = 0; d < 3; d++) P->x[d] = P->x0[d] + tn * P->v[d];
  FCQuatIntegrate(P->q0, P->w, tn, P->q);
  PetscFunctionReturn(0);
}

static PetscErrorCode GetCentroid_Kinematic(FCBody body, PetscReal c[3])
{
  FCPose *P = &((Kinematic *)body->data)->pose;
  PetscFunctionBegin;
  for (int d = 0; d < 3; d++) c[d] = P->x[d];
  PetscFunctionReturn(0);
}

static PetscErrorCode GetRotation_Kinematic(FCBody body, PetscReal q[4], PetscBool *has)
{
  FCPose *P = &((Kinematic *)body->data)->pose;
  PetscFunctionBegin;
  for (int d = 0; d < 4; d++) q[d] = P->q[d];
  *has = PETSC_TRUE;
  PetscFunctionReturn(0);
}

static PetscErrorCode GetVisualPositions_Kinematic(FCBody body, PetscReal x[])
{
  PetscFunctionBegin;
  PetscCall(FCPoseVisualPositions(body, &((Kinematic *)body->data)->pose, x));
  PetscFunctionReturn(0);
}

static PetscErrorCode Destroy_Kinematic(FCBody body)
{
  PetscFunctionBegin;
  PetscCall(FCPoseDestroy(&((Kinematic *)body->data)->pose));
  PetscCall(PetscFree(body->data));
  PetscFunctionReturn(0);
}

PetscErrorCode FCBodyCreate_Kinematic(FCBody body)
{
  Kinematic *k;

  PetscFunctionBegin;
  PetscCall(PetscNew(&k));
  body->data                   = k;
  body->ops.setup              = SetUp_Kinematic;
  body->ops.integrate          = Integrate_Kinematic;
  body->ops.getcentroid        = GetCentroid_Kinematic;
  body->ops.getrotation        = GetRotation_Kinematic;
  body->ops.getvisualpositions = GetVisualPositions_Kinematic;
  body->ops.destroy            = Destroy_Kinematic;
  PetscFunctionReturn(0);
}
