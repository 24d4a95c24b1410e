/* Rigid body: 6 DOFs (velocity of the centre of mass, angular velocity), state x (centre of
   mass) and a unit quaternion q. Mass and inertia come from the shape and -<body>_density.
   Implicit Euler with A = generalized mass (eq. 3, A = diag(m I, J_world)):
       m dv = h m g,   J dw = h (- w x J w)      (gyroscopic torque taken at the start)
   then v += dv, w += dw, x += h v, q <- exp(h w / 2) q.
   The state is replicated on every rank (identical arithmetic): a rigid body is 6 numbers.
   Options: -<body>_shape and the shape's options, -<body>_density (> 0). */
#include "pose.h"

typedef struct {
  FCPose     pose; /* first: the shared pose ops of pose.c read body->data as an FCPose */
  PetscReal  mass, dv[3], dw[3];
  PetscReal  dv0[3], dw0[3]; /* dv_free kept by the recursive schemes */
  PetscInt   ncols, *cols;   /* constraint rows touching this body in the step */
  PetscReal *AiJT;           /* A^-1 J_b^T (6 x ncols), kept for the correction */
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
  r->mass    = body->density * r->pose.volume;
  body->mass = r->mass;
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
  for (int d = 0; d < 3; d++) {
    PetscReal w   = r->pose.w[d] + r->dw[d];
    r->pose.xf[d] = r->pose.x[d] + body->h * (r->pose.v[d] + r->dv[d]);
    tau[d]        = w;
  }
  FCQuatIntegrate(r->pose.q, tau, body->h, r->pose.qf);
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

/* Row of J_b for direction e at world offset r from the centre of mass: e.(v + w x r) =
   [e, r x e] . (v, w). W_b = J A^-1 J^T with A = diag(m I, J_world) (closed form). */
static PetscErrorCode AddCompliance_Rigid(FCBody body, PetscInt self, const FCContactSet *set, const FCRows *rows,
                                          PetscReal W[])
{
  Rigid    *rb = (Rigid *)body->data;
  PetscReal Jw[9], Jinv[9], R[9], *J;
  PetscInt  n = 0, M = set->nrows, r0 = rows ? rows->r0 : 0, r1 = rows ? rows->r1 : M;

  PetscFunctionBegin;
  PetscCall(PetscFree(rb->cols));
  PetscCall(PetscFree(rb->AiJT));
  rb->ncols = 0;
  for (PetscInt k = 0; k < set->n; k++)
    for (PetscInt s = 0; s < 2; s++)
      if (set->c[k].body[s] == self) n += set->c[k].dim;
  if (!n) PetscFunctionReturn(0);
  PetscCall(PetscMalloc1(n, &rb->cols));
  PetscCall(PetscMalloc1(6 * n, &rb->AiJT));
  PetscCall(PetscMalloc1(6 * n, &J));
  WorldInertia(rb, body->density, Jw);
  PetscCall(FCMat3Inverse(Jw, Jinv));
  FCQuatToMat3(rb->pose.q, R);
  n = 0;
  for (PetscInt k = 0; k < set->n; k++)
    for (PetscInt s = 0; s < 2; s++) {
      const FCContact *c = &set->c[k];
      PetscReal        rw[3];
      if (c->body[s] != self) continue;
      FCMat3Vec(R, c->prox[s].r, rw);
      for (PetscInt a = 0; a < c->dim; a++, n++) {
        const PetscReal *f = a == 0 ? c->n : (a == 1 ? c->t1 : c->t2);
        PetscReal        e[3], rxe[3], tmp[3];
        for (int i = 0; i < 3; i++) e[i] = (s == 0 ? 1.0 : -1.0) * f[i];
        FCCross(rw, e, rxe);
        rb->cols[n] = c->row + a;
        for (int i = 0; i < 3; i++) {
          J[6 * n + i]     = e[i];
          J[6 * n + 3 + i] = rxe[i];
        }
        FCMat3Vec(Jinv, rxe, tmp);
        for (int i = 0; i < 3; i++) {
          rb->AiJT[6 * n + i]     = e[i] / rb->mass;
          rb->AiJT[6 * n + 3 + i] = tmp[i];
        }
      }
    }
  rb->ncols = n;
  for (PetscInt i = 0; i < n; i++) {
    if (rb->cols[i] < r0 || rb->cols[i] >= r1) continue; /* another rank's row */
    for (PetscInt j = 0; j < n; j++) {
      PetscReal w = 0.0;
      for (int d = 0; d < 6; d++) w += J[6 * i + d] * rb->AiJT[6 * j + d];
      W[(rb->cols[i] - r0) * M + rb->cols[j]] += w;
    }
  }
  PetscCall(PetscFree(J));
  PetscFunctionReturn(0);
}

static PetscErrorCode SaveFree_Rigid(FCBody body)
{
  Rigid *r = (Rigid *)body->data;
  PetscFunctionBegin;
  for (int d = 0; d < 3; d++) {
    r->dv0[d] = r->dv[d];
    r->dw0[d] = r->dw[d];
  }
  PetscFunctionReturn(0);
}

static PetscErrorCode RestoreFree_Rigid(FCBody body)
{
  Rigid *r = (Rigid *)body->data;
  PetscFunctionBegin;
  for (int d = 0; d < 3; d++) {
    r->dv[d] = r->dv0[d];
    r->dw[d] = r->dw0[d];
  }
  PetscFunctionReturn(0);
}

/* rank 0 adds the body-frame point at the trial pose x + h (v + dv), exp(h (w + dw)) q */
static PetscErrorCode TrialPosition_Rigid(FCBody body, const FCProximity *p, PetscReal x[3])
{
  Rigid      *r = (Rigid *)body->data;
  PetscMPIInt rank;
  PetscReal   w[3], q[4], R[9], y[3];

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_rank(body->comm, &rank));
  if (rank) PetscFunctionReturn(0);
  for (int d = 0; d < 3; d++) w[d] = r->pose.w[d] + r->dw[d];
  FCQuatIntegrate(r->pose.q, w, body->h, q);
  FCQuatToMat3(q, R);
  FCMat3Vec(R, p->r, y);
  for (int d = 0; d < 3; d++) x[d] += y[d] + r->pose.x[d] + body->h * (r->pose.v[d] + r->dv[d]);
  PetscFunctionReturn(0);
}

static PetscErrorCode ApplyCorrection_Rigid(FCBody body, PetscInt self, const FCContactSet *set,
                                            const PetscReal lambda[])
{
  Rigid *rb = (Rigid *)body->data;

  PetscFunctionBegin;
  for (PetscInt i = 0; i < rb->ncols; i++) {
    PetscReal l = body->h * lambda[rb->cols[i]];
    for (int d = 0; d < 3; d++) {
      rb->dv[d] += l * rb->AiJT[6 * i + d];
      rb->dw[d] += l * rb->AiJT[6 * i + 3 + d];
    }
  }
  PetscFunctionReturn(0);
}

static PetscErrorCode GetVisualField_Rigid(FCBody body, FCVisualField field, PetscReal out[], PetscBool *has)
{
  PetscFunctionBegin;
  PetscCall(FCPoseVisualField(body, &((Rigid *)body->data)->pose, NULL, field, out, has));
  PetscFunctionReturn(0);
}

static PetscErrorCode Destroy_Rigid(FCBody body)
{
  PetscFunctionBegin;
  PetscCall(PetscFree(((Rigid *)body->data)->cols));
  PetscCall(PetscFree(((Rigid *)body->data)->AiJT));
  PetscCall(FCPoseDestroy(&((Rigid *)body->data)->pose));
  PetscCall(PetscFree(body->data));
  PetscFunctionReturn(0);
}

PetscErrorCode FCBodyCreate_Rigid(FCBody body)
{
  Rigid *r;

  PetscFunctionBegin;
  PetscCall(PetscNew(&r));
  body->state_cols             = 13; /* x, q, v, w */
  body->data                   = r;
  body->ops.setfromoptions     = SetFromOptions_Rigid;
  body->ops.setup              = SetUp_Rigid;
  body->ops.freemotion         = FreeMotion_Rigid;
  body->ops.integrate          = Integrate_Rigid;
  body->ops.getcentroid        = FCPoseGetCentroid;
  body->ops.getvelocity        = FCPoseGetVelocity;
  body->ops.getrotation        = FCPoseGetRotation;
  body->ops.getenergy          = GetEnergy_Rigid;
  body->ops.getvisualpositions = FCPoseGetVisualPositions;
  body->ops.getvisualfield     = GetVisualField_Rigid;
  body->ops.getstate           = FCPoseGetState;
  body->ops.setstate           = FCPoseSetState;
  body->ops.checkstate         = CheckState_Rigid;
  body->ops.destroy            = Destroy_Rigid;
  body->ops.tobody             = FCPoseToBody;
  body->ops.steprotation       = FCPoseStepRotation;
  body->ops.partialposition    = FCPosePartialPosition;
  body->ops.contactpoints      = FCPoseContactPoints;
  body->ops.proximityposition  = FCPoseProximityPosition;
  body->ops.shapedistance      = FCPoseShapeDistance;
  body->ops.shapedistancefree  = FCPoseShapeDistanceFree;
  body->ops.addcompliance      = AddCompliance_Rigid;
  body->ops.applycorrection    = ApplyCorrection_Rigid;
  body->ops.savefree           = SaveFree_Rigid;
  body->ops.restorefree        = RestoreFree_Rigid;
  body->ops.trialposition      = TrialPosition_Rigid;
  PetscFunctionReturn(0);
}
