/* Kinematic body: a shape moved by a prescribed constant twist, never solved for: it turns with
   -<body>_angular_velocity w about -<body>_pivot c (default: its centre) and translates with
   -<body>_velocity v:
       x(t) = c + v t + R(w t) (x0 - c),   q(t) = exp(t w / 2) q0   (exact, no drift). */
#include "pose.h"

typedef struct {
  FCPose    pose;
  PetscReal pivot[3];
} Kinematic;

static PetscErrorCode SetFromOptions_Kinematic(FCBody body)
{
  Kinematic *k = (Kinematic *)body->data;
  PetscBool  set;

  PetscFunctionBegin;
  PetscOptionsBegin(body->comm, body->prefix, "Kinematic body options", "FCBody");
  PetscCall(FCOptionsRealArray(PetscOptionsObject, "-pivot", "Point the angular velocity turns the body about", 3,
                               k->pivot, &set));
  PetscOptionsEnd();
  if (!set) k->pivot[0] = PETSC_MAX_REAL; /* the centre, known after set-up */
  PetscFunctionReturn(0);
}

/* Pose at time t */
static void PoseAt(Kinematic *k, PetscReal t, PetscReal x[3], PetscReal q[4])
{
  FCPose   *P = &k->pose;
  PetscReal dq[4], R[9], r[3], Rr[3], n = PetscSqrtReal(FCDot(P->w, P->w));
  FCQuatFromAxisAngle(P->w, n * t, dq);
  FCQuatMult(dq, P->q0, q);
  FCQuatNormalize(q);
  FCQuatToMat3(dq, R);
  for (int d = 0; d < 3; d++) r[d] = P->x0[d] - k->pivot[d];
  FCMat3Vec(R, r, Rr);
  for (int d = 0; d < 3; d++) x[d] = k->pivot[d] + P->v[d] * t + Rr[d];
}

static PetscErrorCode SetUp_Kinematic(FCBody body)
{
  Kinematic *k = (Kinematic *)body->data;

  PetscFunctionBegin;
  PetscCall(FCPoseSetUp(body, &k->pose));
  if (k->pivot[0] == PETSC_MAX_REAL)
    for (int d = 0; d < 3; d++) k->pivot[d] = k->pose.x0[d];
  { /* the pivot is a point of the body (it moves with -velocity only): in the body frame */
    PetscReal R[9], d[3];
    FCQuatToMat3(k->pose.q0, R);
    for (int i = 0; i < 3; i++) d[i] = k->pivot[i] - k->pose.x0[i];
    FCMat3TVec(R, d, k->pose.pivot_body);
  }
  PetscFunctionReturn(0);
}

static PetscErrorCode Integrate_Kinematic(FCBody body, PetscReal t)
{
  Kinematic *k = (Kinematic *)body->data;

  PetscFunctionBegin;
  PoseAt(k, t + body->h, k->pose.x, k->pose.q);
  PetscFunctionReturn(0);
}

/* The pose at the end of the step, which the free motion of the others is compared with */
static PetscErrorCode FreeMotion_Kinematic(FCBody body, PetscReal t)
{
  Kinematic *k = (Kinematic *)body->data;

  PetscFunctionBegin;
  PoseAt(k, t + body->h, k->pose.xf, k->pose.qf);
  PetscFunctionReturn(0);
}

/* rank 0 adds the point at the end-of-step pose (the motion is prescribed) */
static PetscErrorCode TrialPosition_Kinematic(FCBody body, const FCProximity *p, PetscReal x[3])
{
  PetscMPIInt rank;
  PetscReal   y[3];

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_rank(body->comm, &rank));
  if (rank) PetscFunctionReturn(0);
  PetscCall(FCPoseProximityPosition(body, p, FC_AT_FREE, y));
  for (int d = 0; d < 3; d++) x[d] += y[d];
  PetscFunctionReturn(0);
}

/* the velocity v of x(t) moves the pivot */
static PetscErrorCode GetVisualField_Kinematic(FCBody body, FCVisualField field, PetscReal out[], PetscBool *has)
{
  Kinematic *k = (Kinematic *)body->data;

  PetscFunctionBegin;
  PetscCall(FCPoseVisualField(body, &k->pose, k->pivot, field, out, has));
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
  body->prescribed             = PETSC_TRUE;
  body->state_cols             = 13; /* x, q, v, w */
  body->data                   = k;
  body->ops.setfromoptions     = SetFromOptions_Kinematic;
  body->ops.setup              = SetUp_Kinematic;
  body->ops.integrate          = Integrate_Kinematic;
  body->ops.getcentroid        = FCPoseGetCentroid;
  body->ops.getrotation        = FCPoseGetRotation;
  body->ops.getvisualpositions = FCPoseGetVisualPositions;
  body->ops.getvisualfield     = GetVisualField_Kinematic;
  body->ops.getstate           = FCPoseGetState;
  body->ops.setstate           = FCPoseSetState;
  body->ops.destroy            = Destroy_Kinematic;
  body->ops.tobody             = FCPoseToBody;
  body->ops.steprotation       = FCPoseStepRotation;
  body->ops.partialposition    = FCPosePartialPosition;
  body->ops.trialposition      = TrialPosition_Kinematic;
  body->ops.freemotion         = FreeMotion_Kinematic;
  body->ops.contactpoints      = FCPoseContactPoints;
  body->ops.proximityposition  = FCPoseProximityPosition;
  body->ops.shapedistance      = FCPoseShapeDistance;
  body->ops.shapedistancefree  = FCPoseShapeDistanceFree;
  PetscFunctionReturn(0);
}
