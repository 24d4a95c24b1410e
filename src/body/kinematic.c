/* Kinematic body: a shape moved by a prescribed motion, never solved for. Either a constant twist:
   it turns with -<body>_angular_velocity w about -<body>_pivot c (default: its centre) and
   translates with -<body>_velocity v,
       x(t) = c + v t + R(w t) (x0 - c),   q(t) = exp(t w / 2) q0   (exact, no drift),
   or -<body>_trajectory, a table of t, x, y, z[, qw, qx, qy, qz] (src/util/table.c): the centre
   piecewise linear in t and the orientation by slerp between rows (else the placement's), held
   after the last row. Either way the contacts see the pose at the end of each step, so the
   velocity over a step is that of the table between its two poses.
   A program may steer it instead (FCBodySetKinematicPose, FCBodySetKinematicVelocity): from the
   current time t0, a pose to reach at t0 + h (at constant velocity and angular velocity over the
   step, as a table's rows; held after it), or a constant velocity and angular velocity about its
   centre. */
#include "pose.h"

typedef enum { COMMAND_NONE, COMMAND_POSE, COMMAND_VELOCITY } CommandMode;

typedef struct {
  CommandMode mode;
  PetscReal   t0, h, x0[3], q0[4]; /* the time of the command, the time step, the pose then */
  PetscReal   x1[3], q1[4];        /* COMMAND_POSE: the pose at t0 + h */
  PetscReal   v[3], w[3];          /* COMMAND_VELOCITY */
} Command;

typedef struct {
  FCPose    pose;
  PetscReal pivot[3];
  char     *trajectory; /* -trajectory as given (allocated: an inline table has any length) */
  FCTable   table;      /* -trajectory */
  PetscReal tnow;       /* the time of the pose x, q: the end of the last step */
  Command   command;    /* a program's, which replaces the options' motion */
} Kinematic;

static PetscErrorCode SetFromOptions_Kinematic(FCBody body)
{
  Kinematic *k = (Kinematic *)body->data;
  PetscBool  set;

  PetscFunctionBegin;
  PetscOptionsBegin(body->comm, body->prefix, "Kinematic body options", "FCBody");
  PetscCall(FCOptionsRealArray(PetscOptionsObject, "-pivot", "Point the angular velocity turns the body about", 3,
                               k->pivot, &set));
  PetscCall(FCOptionsStringAlloc(PetscOptionsObject, "-trajectory",
                                 "Table of t,x,y,z[,qw,qx,qy,qz]: the centre (and orientation) over time",
                                 &k->trajectory, NULL));
  PetscOptionsEnd();
  if (k->trajectory[0]) {
    char      what[FC_MAX_NAME + 32];
    PetscBool v, w;
    PetscCall(PetscSNPrintf(what, sizeof(what), "option -%strajectory", body->prefix));
    PetscCall(FCTableCreate(body->comm, k->trajectory, 3, 7, what, &k->table));
    PetscCheck(FCTableColumns(k->table) == 3 || FCTableColumns(k->table) == 7, body->comm, PETSC_ERR_USER_INPUT,
               "Option -%strajectory: rows of t,x,y,z or t,x,y,z,qw,qx,qy,qz, got %" PetscInt_FMT " values after t",
               body->prefix, FCTableColumns(k->table));
    PetscCall(PetscOptionsHasName(NULL, body->prefix, "-velocity", &v));
    PetscCall(PetscOptionsHasName(NULL, body->prefix, "-angular_velocity", &w));
    PetscCheck(!v && !w && !set, body->comm, PETSC_ERR_USER_INPUT,
               "Body '%s': -%strajectory gives its motion; -%svelocity, -%sangular_velocity and -%spivot cannot be "
               "given with it",
               body->name, body->prefix, body->prefix, body->prefix, body->prefix);
    /* the table gives the centre's position (and, with 7 columns, the orientation): a placement
       that moves the centre, or turns a body whose orientation the table gives, would be ignored */
    PetscCall(PetscOptionsHasName(NULL, body->prefix, "-translate", &v));
    PetscCall(PetscOptionsHasName(NULL, body->prefix, "-center", &w));
    PetscCheck(!v && !w, body->comm, PETSC_ERR_USER_INPUT,
               "Body '%s': -%strajectory gives its centre's position; -%stranslate and -%scenter cannot be given with "
               "it",
               body->name, body->prefix, body->prefix, body->prefix);
    if (FCTableColumns(k->table) == 7) {
      PetscInt         nrow;
      const PetscReal *row = FCTableValues(k->table, &nrow);
      PetscCall(PetscOptionsHasName(NULL, body->prefix, "-rotate", &v));
      PetscCheck(!v, body->comm, PETSC_ERR_USER_INPUT,
                 "Body '%s': -%strajectory gives its orientation (qw,qx,qy,qz); -%srotate cannot be given with it",
                 body->name, body->prefix, body->prefix);
      for (PetscInt r = 0; r < nrow; r++) { /* a quaternion is normalized at use: it cannot be zero */
        const PetscReal *q = &row[7 * r + 3];
        PetscCheck(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3] > 0.0, body->comm, PETSC_ERR_USER_INPUT,
                   "Option -%strajectory, row %" PetscInt_FMT ": the quaternion qw,qx,qy,qz is zero", body->prefix,
                   r + 1);
      }
    }
  }
  if (!set) k->pivot[0] = PETSC_MAX_REAL; /* the centre, known after set-up */
  PetscFunctionReturn(0);
}

/* Slerp from a to b (unit quaternions), the shorter way */
static void Slerp(const PetscReal a[4], const PetscReal b[4], PetscReal s, PetscReal q[4])
{
  PetscReal c = 0.0, bb[4], th, wa, wb;
  for (int i = 0; i < 4; i++) c += a[i] * b[i];
  for (int i = 0; i < 4; i++) bb[i] = c < 0.0 ? -b[i] : b[i];
  c = PetscAbsReal(c);
  if (c > 1.0 - 1e-12) {
    wa = 1.0 - s;
    wb = s;
  } else {
    th = PetscAcosReal(c);
    wa = PetscSinReal((1.0 - s) * th) / PetscSinReal(th);
    wb = PetscSinReal(s * th) / PetscSinReal(th);
  }
  for (int i = 0; i < 4; i++) q[i] = wa * a[i] + wb * bb[i];
  FCQuatNormalize(q);
}

/* The pose of a constant twist t after (x0, q0): turning with w about the point c (which moves with v),
   x = c + v t + R(w t) (x0 - c), q = exp(t w / 2) q0 */
static void Twist(const PetscReal x0[3], const PetscReal q0[4], const PetscReal c[3], const PetscReal v[3],
                  const PetscReal w[3], PetscReal t, PetscReal x[3], PetscReal q[4])
{
  PetscReal dq[4], R[9], r[3], Rr[3], n = PetscSqrtReal(FCDot(w, w));
  FCQuatFromAxisAngle(w, n * t, dq);
  FCQuatMult(dq, q0, q);
  FCQuatNormalize(q);
  FCQuatToMat3(dq, R);
  for (int d = 0; d < 3; d++) r[d] = x0[d] - c[d];
  FCMat3Vec(R, r, Rr);
  for (int d = 0; d < 3; d++) x[d] = c[d] + v[d] * t + Rr[d];
}

/* The commanded pose at time t >= t0: the step to the pose (s within round-off of 0 or 1 is that end
   exactly: the step's end time is t0 + h give or take an ulp), or the constant twist about the centre */
static void CommandPoseAt(const Command *c, PetscReal t, PetscReal x[3], PetscReal q[4])
{
  if (c->mode == COMMAND_POSE) {
    PetscReal s = (t - c->t0) / c->h;
    s           = s < 1e-9 ? 0.0 : (s > 1.0 - 1e-9 ? 1.0 : s);
    for (int d = 0; d < 3; d++) x[d] = (1.0 - s) * c->x0[d] + s * c->x1[d];
    Slerp(c->q0, c->q1, s, q);
    return;
  }
  Twist(c->x0, c->q0, c->x0, c->v, c->w, t - c->t0, x, q);
}

/* Pose at time t */
static void PoseAt(Kinematic *k, PetscReal t, PetscReal x[3], PetscReal q[4])
{
  FCPose *P = &k->pose;
  if (k->command.mode != COMMAND_NONE) {
    CommandPoseAt(&k->command, t, x, q);
    return;
  }
  if (k->table) {
    const PetscReal *a, *b;
    PetscReal        s, qa[4], qb[4];
    FCTableBracket(k->table, t, &a, &b, &s);
    for (int d = 0; d < 3; d++) x[d] = (1.0 - s) * a[d] + s * b[d];
    if (FCTableColumns(k->table) == 7) {
      for (int i = 0; i < 4; i++) {
        qa[i] = a[3 + i];
        qb[i] = b[3 + i];
      }
      FCQuatNormalize(qa);
      FCQuatNormalize(qb);
      Slerp(qa, qb, s, q);
    } else
      for (int i = 0; i < 4; i++) q[i] = P->q0[i];
    return;
  }
  Twist(P->x0, P->q0, k->pivot, P->v, P->w, t, x, q);
}

static PetscErrorCode SetUp_Kinematic(FCBody body)
{
  Kinematic *k = (Kinematic *)body->data;

  PetscFunctionBegin;
  PetscCall(FCPoseSetUp(body, &k->pose));
  if (k->table) { /* placed at the table's pose at t = 0 */
    FCPose *P = &k->pose;
    PoseAt(k, 0.0, P->x0, P->q0);
    for (int d = 0; d < 3; d++) P->xf[d] = P->x[d] = P->x0[d];
    for (int d = 0; d < 4; d++) P->qf[d] = P->q[d] = P->q0[d];
    PetscCall(FCPoseVisualPositions(body, P, body->visual.reference));
    for (int d = 0; d < 3; d++) body->center[d] = P->x0[d];
  }
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
  k->tnow = t + body->h;
  PetscFunctionReturn(0);
}

/* A trajectory's velocity over the step [t, t + h] (the pictures' velocity field) */
static void TrajectoryVelocity(Kinematic *k, PetscReal t, PetscReal h)
{
  FCPose   *P = &k->pose;
  PetscReal x0[3], q0[4], x1[3], q1[4], qc[4], dq[4], s, a;
  PoseAt(k, t, x0, q0);
  PoseAt(k, t + h, x1, q1);
  for (int d = 0; d < 3; d++) P->v[d] = (x1[d] - x0[d]) / h;
  qc[0] = q0[0];
  for (int d = 1; d < 4; d++) qc[d] = -q0[d];
  FCQuatMult(q1, qc, dq);
  if (dq[0] < 0.0)
    for (int d = 0; d < 4; d++) dq[d] = -dq[d];
  s = PetscSqrtReal(dq[1] * dq[1] + dq[2] * dq[2] + dq[3] * dq[3]);
  a = 2.0 * PetscAtan2Real(s, dq[0]);
  for (int d = 0; d < 3; d++) P->w[d] = s > 0.0 ? dq[1 + d] / s * a / h : 0.0;
  for (int d = 0; d < 3; d++) k->pivot[d] = x1[d]; /* the centre the field is taken about, at t + h */
}

/* The pose at the end of the step, which the free motion of the others is compared with */
static PetscErrorCode FreeMotion_Kinematic(FCBody body, PetscReal t)
{
  Kinematic *k = (Kinematic *)body->data;

  PetscFunctionBegin;
  PoseAt(k, t + body->h, k->pose.xf, k->pose.qf);
  if (k->table || k->command.mode != COMMAND_NONE) TrajectoryVelocity(k, t, body->h);
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

/* The fastest motion (the energy guard's scale): the twist, or a trajectory's fastest rows
   (|dq/dt| = |w| / 2 for a unit quaternion) */
static void PrescribedMotion_Kinematic(FCBody body, PetscReal v[3], PetscReal w[3])
{
  Kinematic *k = (Kinematic *)body->data;
  for (int d = 0; d < 3; d++) {
    v[d] = k->table ? (d ? 0.0 : FCTableMaxRate(k->table, 0, 3)) : body->velocity[d];
    w[d] = k->table ? (d || FCTableColumns(k->table) < 7 ? 0.0 : 2.0 * FCTableMaxRate(k->table, 3, 7))
                    : body->angular_velocity[d];
  }
}

static PetscErrorCode PoseAt_Kinematic(FCBody body, PetscReal t, PetscReal x[3], PetscReal q[4])
{
  PetscFunctionBegin;
  PoseAt((Kinematic *)body->data, t, x, q);
  PetscFunctionReturn(0);
}

/* The scene's time at set-up or a restart: that of the pose */
static PetscErrorCode SetTime_Kinematic(FCBody body, PetscReal t)
{
  PetscFunctionBegin;
  ((Kinematic *)body->data)->tnow = t;
  PetscFunctionReturn(0);
}

/* A command from the current pose, at the current time */
static void CommandStart(FCBody body, CommandMode mode)
{
  Kinematic *k = (Kinematic *)body->data;
  Command   *c = &k->command;

  c->mode = mode;
  c->t0   = k->tnow;
  c->h    = body->h;
  for (int d = 0; d < 3; d++) c->x0[d] = k->pose.x[d];
  for (int d = 0; d < 4; d++) c->q0[d] = k->pose.q[d];
}

static PetscErrorCode SetPose_Kinematic(FCBody body, const PetscReal x[3], const PetscReal q[4])
{
  Command *c = &((Kinematic *)body->data)->command;

  PetscFunctionBegin;
  CommandStart(body, COMMAND_POSE);
  for (int d = 0; d < 3; d++) c->x1[d] = x[d];
  for (int d = 0; d < 4; d++) c->q1[d] = q[d];
  FCQuatNormalize(c->q1);
  PetscFunctionReturn(0);
}

static PetscErrorCode SetVelocity_Kinematic(FCBody body, const PetscReal v[3], const PetscReal w[3])
{
  Command *c = &((Kinematic *)body->data)->command;

  PetscFunctionBegin;
  CommandStart(body, COMMAND_VELOCITY);
  for (int d = 0; d < 3; d++) {
    c->v[d] = v[d];
    c->w[d] = w[d];
  }
  PetscFunctionReturn(0);
}

static PetscErrorCode Destroy_Kinematic(FCBody body)
{
  PetscFunctionBegin;
  PetscCall(FCPoseDestroy(&((Kinematic *)body->data)->pose));
  PetscCall(FCTableDestroy(&((Kinematic *)body->data)->table));
  PetscCall(PetscFree(((Kinematic *)body->data)->trajectory));
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
  body->ops.poseat             = PoseAt_Kinematic;
  body->ops.settime            = SetTime_Kinematic;
  body->ops.setkinematicpose   = SetPose_Kinematic;
  body->ops.setkinematicvel    = SetVelocity_Kinematic;
  body->ops.getvelocity        = FCPoseGetVelocity;
  body->ops.prescribedmotion   = PrescribedMotion_Kinematic;
  body->ops.contactpoints      = FCPoseContactPoints;
  body->ops.proximityposition  = FCPoseProximityPosition;
  body->ops.shapedistance      = FCPoseShapeDistance;
  body->ops.shapedistancefree  = FCPoseShapeDistanceFree;
  PetscFunctionReturn(0);
}
