/* Rigid body: 6 DOFs (velocity of the centre of mass, angular velocity), state x (centre of
   mass) and a unit quaternion q. Mass and inertia come from the shape and -<body>_density.
   Implicit Euler with A = generalized mass (eq. 3, A = diag(m I, J_world)):
       m dv = h m g,   J dw = h (- w x J w)      (gyroscopic torque taken at the start)
   then v += dv, w += dw, x += h v, q <- exp(h w / 2) q.
   The state is replicated on every rank (identical arithmetic): a rigid body is 6 numbers.
   Options: -<body>_shape and the shape's options, -<body>_density (> 0). */
#include "pose.h"

typedef struct {
  FCPose    pose; /* first: the shared pose ops of pose.c read body->data as an FCPose */
  PetscReal mass, dv[3], dw[3];
} Rigid;

static PetscErrorCode SetFromOptions_Rigid(FCBody body)
{
  PetscBool set;

  PetscFunctionBegin;
  PetscOptionsBegin(body->comm, body->prefix, "Rigid body options", "FCBody");
  PetscCall(FCOptionsReal(PetscOptionsObject, "-density", "Density (kg/m^3)", &body->density, &set));
  PetscOptionsEnd();
  PetscCheck(set, body->comm, PETSC_ERR_USER_INPUT, "Rigid body '%s' needs -%sdensity", body->name, body->prefix);
  PetscCall(FCCheckPositive(body->comm, body->prefix, "-density", body->density));
  PetscFunctionReturn(0);
}

static PetscErrorCode SetUp_Rigid(FCBody body)
{
  Rigid *r = (Rigid *)body->data;

  PetscFunctionBegin;
  PetscCall(FCPoseSetUp(body, &r->pose));
  PetscCheck(r->pose.shape->bounded, body->comm, PETSC_ERR_USER_INPUT,
             "Rigid body '%s' cannot be a %s (no finite mass): make it -%stype kinematic", body->name,
             r->pose.shape->type, body->prefix);
  r->mass = body->density * r->pose.volume;
  PetscFunctionReturn(0);
}

static void WorldInertia(Rigid *r, PetscReal density, PetscReal Jw[9])
{
  PetscReal R[9], T[9];
  FCQuatToMat3(r->pose.q, R);
  FCMat3Mult(R, r->pose.J, T);
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++)
      Jw[3 * i + j] = density * (T[3 * i] * R[3 * j] + T[3 * i + 1] * R[3 * j + 1] + T[3 * i + 2] * R[3 * j + 2]);
}

static PetscErrorCode FreeMotion_Rigid(FCBody body, PetscReal t)
{
  Rigid    *r = (Rigid *)body->data;
  PetscReal Jw[9], Jinv[9], Jwv[3], tau[3];

  PetscFunctionBegin;
  PetscCall(FCPhaseBegin(FC_PHASE_FREE_MOTION));
  for (int d = 0; d < 3; d++) r->dv[d] = body->h * body->gravity[d];
  WorldInertia(r, body->density, Jw);
  PetscCall(FCMat3Inverse(Jw, Jinv));
  FCMat3Vec(Jw, r->pose.w, Jwv);
  FCCross(r->pose.w, Jwv, tau);
  for (int d = 0; d < 3; d++) tau[d] *= -body->h;
  FCMat3Vec(Jinv, tau, r->dw);
  PetscCall(FCPhaseEnd(FC_PHASE_FREE_MOTION));
  PetscFunctionReturn(0);
}

static PetscErrorCode Integrate_Rigid(FCBody body, PetscReal t)
{
  Rigid *r = (Rigid *)body->data;

  PetscFunctionBegin;
  for (int d = 0; d < 3; d++) {
    r->pose.v[d] += r->dv[d];
    r->pose.w[d] += r->dw[d];
    r->pose.x[d] += body->h * r->pose.v[d];
  }
  FCQuatIntegrate(r->pose.q, r->pose.w, body->h, r->pose.q);
  PetscFunctionReturn(0);
}

static PetscErrorCode GetEnergy_Rigid(FCBody body, FCEnergy *E)
{
  Rigid    *r = (Rigid *)body->data;
  PetscReal Jw[9], Jwv[3];

  PetscFunctionBegin;
  WorldInertia(r, body->density, Jw);
  FCMat3Vec(Jw, r->pose.w, Jwv);
  E->kinetic = 0.5 * r->mass * FCDot(r->pose.v, r->pose.v) + 0.5 * FCDot(r->pose.w, Jwv);
  E->gravity = -r->mass * FCDot(body->gravity, r->pose.x);
  PetscFunctionReturn(0);
}

static PetscErrorCode CheckState_Rigid(FCBody body, PetscInt step)
{
  Rigid    *r = (Rigid *)body->data;
  PetscReal s = 0.0;

  PetscFunctionBegin;
  for (int d = 0; d < 3; d++) s += r->pose.x[d] + r->pose.v[d] + r->pose.w[d];
  PetscCheck(!PetscIsInfOrNanReal(s), body->comm, PETSC_ERR_FP,
             "Rigid body '%s' diverged at step %" PetscInt_FMT ": its state is NaN or Inf", body->name, step);
  PetscFunctionReturn(0);
}

static PetscErrorCode Destroy_Rigid(FCBody body)
{
  PetscFunctionBegin;
  PetscCall(FCPoseDestroy(&((Rigid *)body->data)->pose));
  PetscCall(PetscFree(body->data));
  PetscFunctionReturn(0);
}

PetscErrorCode FCBodyCreate_Rigid(FCBody body)
{
  Rigid *r;

  PetscFunctionBegin;
  PetscCall(PetscNew(&r));
  body->data                   = r;
  body->ops.setfromoptions     = SetFromOptions_Rigid;
  body->ops.setup              = SetUp_Rigid;
  body->ops.freemotion         = FreeMotion_Rigid;
  body->ops.integrate          = Integrate_Rigid;
  body->ops.getcentroid        = FCPoseGetCentroid;
  body->ops.getrotation        = FCPoseGetRotation;
  body->ops.getenergy          = GetEnergy_Rigid;
  body->ops.getvisualpositions = FCPoseGetVisualPositions;
  body->ops.checkstate         = CheckState_Rigid;
  body->ops.destroy            = Destroy_Rigid;
  PetscFunctionReturn(0);
}
