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

/* The pose at the end of the step, which the free motion of the others is compared with */
static PetscErrorCode FreeMotion_Kinematic(FCBody body, PetscReal t)
{
  FCPose *P = &((Kinematic *)body->data)->pose;

  PetscFunctionBegin;
  for (int d = 0; d < 3; d++) P->xf[d] = P->x0[d] + (t + body->h) * P->v[d];
  FCQuatIntegrate(P->q0, P->w, t + body->h, P->qf);
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
  body->ops.getcentroid        = FCPoseGetCentroid;
  body->ops.getrotation        = FCPoseGetRotation;
  body->ops.getvisualpositions = FCPoseGetVisualPositions;
  body->ops.destroy            = Destroy_Kinematic;
  body->ops.tobody             = FCPoseToBody;
  body->ops.partialposition    = FCPosePartialPosition;
  body->ops.freemotion         = FreeMotion_Kinematic;
  body->ops.contactpoints      = FCPoseContactPoints;
  body->ops.proximityposition  = FCPoseProximityPosition;
  body->ops.shapedistance      = FCPoseShapeDistance;
  PetscFunctionReturn(0);
}
