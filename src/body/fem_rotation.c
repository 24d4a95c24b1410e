/* FE body, the rotation of a free co-rotational body within a step (-<body>_rotation exact).

   Linearized implicit Euler moves a vertex along the tangent of its circle about the body's
   centre, x_{t+h} = x_t + h v_{t+h}: a body turning by omega h in a step is stretched by about
   (omega h)^2 / 2 every step. The co-rotational force takes that stretch as strain, so a spinning
   body gains energy at every step, the more the stiffer it is. Solving implicit Euler exactly does
   not cure it: the force then acts along the radius at the end of the step, which is not square
   to the velocity it turns, and takes (omega h)^2 of the energy each step
   (scripts/backward_euler_rotation.py).

   Here the step is taken in the frame that turns with the body (a Tisserand frame). With c the
   centre of mass, r = x_t - c, omega the mean angular velocity (I omega = L, inertia and angular
   momentum of M) and Q = exp(h [omega]x) the rotation of the step, the rigid part of the motion
   is advanced exactly and the rest by implicit Euler in the turning frame:
       v_{t+h} = v~ + D,          v~ = v_t + omega x (Q - I) r   (the turning velocity, turned)
       x_{t+h} = x_t + h v_{t+h} + delta,   delta = (Q - I) r - h omega x (Q r)
   so that a rigid motion lands exactly on c + Q r with velocity omega x Q r. The elastic force is
   linearized at the turned state x^ = x_t + (Q - I) r, where a rigid motion has none, and the
   frame's centrifugal force f_c = -M omega x (omega x Q r) acts on the body:
       A(x^) D = h (f_ext - f_int(x^) + f_c) - h B v~ - h^2 K(x^) (v_t - omega x r)
   (eq. 5 in the turning frame; dv = v_{t+h} - v_t = D + omega x (Q - I) r). The centrifugal
   force stretches a spinning body as its stress must hold it, and its torque, -omega x I omega,
   turns omega as Euler's equations do; momentum is kept. The Coriolis force on the motion
   relative to the frame (which does no work) is not modelled. A body with fixed vertices cannot
   turn freely and keeps eq. 2, as does a linear material (not rotation invariant). The contact
   points' positions after the free motion and at the trial states include delta
   (fem_contact.c). */
#include "femimpl.h"

/* Sum over the owned vertices of r x y, y a vector of the layout of u */
static PetscErrorCode MomentSum(Vec r, Vec y, PetscReal s[3])
{
  const PetscScalar *ra, *ya;
  PetscInt           n;

  PetscFunctionBegin;
  PetscCall(VecGetLocalSize(r, &n));
  PetscCall(VecGetArrayRead(r, &ra));
  PetscCall(VecGetArrayRead(y, &ya));
  for (int d = 0; d < 3; d++) s[d] = 0.0;
  for (PetscInt i = 0; i < n; i += 3) {
    PetscReal a[3], b[3], t[3];
    for (int d = 0; d < 3; d++) {
      a[d] = PetscRealPart(ra[i + d]);
      b[d] = PetscRealPart(ya[i + d]);
    }
    FCCross(a, b, t);
    for (int d = 0; d < 3; d++) s[d] += t[d];
  }
  PetscCall(VecRestoreArrayRead(r, &ra));
  PetscCall(VecRestoreArrayRead(y, &ya));
  PetscFunctionReturn(0);
}

/* y_i = a x r_i at every owned vertex */
static PetscErrorCode CrossField(const PetscReal a[3], Vec r, Vec y)
{
  const PetscScalar *ra;
  PetscScalar       *ya;
  PetscInt           n;

  PetscFunctionBegin;
  PetscCall(VecGetLocalSize(r, &n));
  PetscCall(VecGetArrayRead(r, &ra));
  PetscCall(VecGetArray(y, &ya));
  for (PetscInt i = 0; i < n; i += 3) {
    PetscReal b[3], t[3];
    for (int d = 0; d < 3; d++) b[d] = PetscRealPart(ra[i + d]);
    FCCross(a, b, t);
    for (int d = 0; d < 3; d++) ya[i + d] = t[d];
  }
  PetscCall(VecRestoreArrayRead(r, &ra));
  PetscCall(VecRestoreArray(y, &ya));
  PetscFunctionReturn(0);
}

/* Whether the body advances its rotation exactly: asked for, co-rotational, no fixed vertex */
PetscBool FCFEMRotationActive(FEM *fem)
{
  return (PetscBool)(fem->rotation_exact && fem->mat->rotation && fem->free_motion != FC_FREE_MOTION_NEWTON &&
                     fem->nfixed == 0);
}

/* The rotation of the step: omega from the state (u, v), and the vectors of the header comment:
   uhat = u + (Q - I) r, shift = delta, rvt = v~, rw = v_t - omega x r, rcf = f_c */
PetscErrorCode FCFEMRotationPredict(FCBody body)
{
  FEM         *fem = (FEM *)body->data;
  PetscInt     n, lo;
  PetscReal    s[4] = {0}, c[3], L[3], Jm[9], Iinv[9], omega[3], Q[9], q[4], angle;
  PetscScalar *ra;

  PetscFunctionBegin;
  if (!fem->rr) {
    PetscCall(VecDuplicate(fem->u, &fem->rr));
    PetscCall(VecDuplicate(fem->u, &fem->shift));
    PetscCall(VecDuplicate(fem->u, &fem->uhat));
    PetscCall(VecDuplicate(fem->u, &fem->rvt));
    PetscCall(VecDuplicate(fem->u, &fem->rw));
    PetscCall(VecDuplicate(fem->u, &fem->rcf));
  }
  PetscCall(VecGetLocalSize(fem->u, &n));
  PetscCall(VecGetOwnershipRange(fem->u, &lo, NULL));
  PetscCheck(lo % 3 == 0 && n % 3 == 0, body->comm, PETSC_ERR_PLIB, "Body '%s': DOFs not in vertex blocks", body->name);
  /* centre of mass of M: c_d = sum over the d components of M x, over the mass */
  PetscCall(VecWAXPY(fem->rr, 1.0, fem->Xg, fem->u));
  PetscCall(MatMult(fem->M, fem->rr, fem->work));
  {
    const PetscScalar *w;
    PetscCall(VecGetArrayRead(fem->work, &w));
    for (PetscInt i = 0; i < n; i++) s[i % 3] += PetscRealPart(w[i]);
    PetscCall(VecRestoreArrayRead(fem->work, &w));
  }
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, s, 3, MPIU_REAL, MPIU_SUM, body->comm));
  for (int d = 0; d < 3; d++) c[d] = s[d] / fem->mass;
  PetscCall(VecGetArray(fem->rr, &ra));
  for (PetscInt i = 0; i < n; i++) ra[i] -= c[i % 3];
  PetscCall(VecRestoreArray(fem->rr, &ra));
  /* L = sum r x (M v); I e_k = sum r x M (e_k x r) */
  PetscCall(MatMult(fem->M, fem->v, fem->work));
  PetscCall(MomentSum(fem->rr, fem->work, L));
  for (int k = 0; k < 3; k++) {
    PetscReal e[3] = {0, 0, 0}, col[3];
    e[k]           = 1.0;
    PetscCall(CrossField(e, fem->rr, fem->rw));
    PetscCall(MatMult(fem->M, fem->rw, fem->work));
    PetscCall(MomentSum(fem->rr, fem->work, col));
    for (int i = 0; i < 3; i++) Jm[3 * i + k] = col[i];
  }
  {
    PetscReal buf[12];
    for (int i = 0; i < 9; i++) buf[i] = Jm[i];
    for (int i = 0; i < 3; i++) buf[9 + i] = L[i];
    PetscCall(MPIU_Allreduce(MPI_IN_PLACE, buf, 12, MPIU_REAL, MPIU_SUM, body->comm));
    for (int i = 0; i < 9; i++) Jm[i] = buf[i];
    for (int i = 0; i < 3; i++) L[i] = buf[9 + i];
  }
  PetscCall(FCMat3Inverse(Jm, Iinv));
  FCMat3Vec(Iinv, L, omega);
  angle = body->h * PetscSqrtReal(FCDot(omega, omega));
  FCQuatFromAxisAngle(omega, angle, q);
  FCQuatToMat3(q, Q);
  /* per vertex: uhat = u + (Q r - r), shift = Q r - r - h omega x Q r, rvt = v + omega x (Q r - r),
     rw = v - omega x r, rcf = omega x (omega x Q r) (times -M below) */
  {
    const PetscScalar *r, *u, *v;
    PetscScalar       *uh, *sh, *vt, *w, *cf;
    PetscCall(VecGetArrayRead(fem->rr, &r));
    PetscCall(VecGetArrayRead(fem->u, &u));
    PetscCall(VecGetArrayRead(fem->v, &v));
    PetscCall(VecGetArray(fem->uhat, &uh));
    PetscCall(VecGetArray(fem->shift, &sh));
    PetscCall(VecGetArray(fem->rvt, &vt));
    PetscCall(VecGetArray(fem->rw, &w));
    PetscCall(VecGetArray(fem->rcf, &cf));
    for (PetscInt i = 0; i < n; i += 3) {
      PetscReal a[3], Qa[3], wQa[3], wa[3], wwQa[3];
      for (int d = 0; d < 3; d++) a[d] = PetscRealPart(r[i + d]);
      FCMat3Vec(Q, a, Qa);
      FCCross(omega, Qa, wQa);
      FCCross(omega, a, wa);
      FCCross(omega, wQa, wwQa);
      for (int d = 0; d < 3; d++) {
        uh[i + d] = u[i + d] + (Qa[d] - a[d]);
        sh[i + d] = Qa[d] - a[d] - body->h * wQa[d];
        vt[i + d] = v[i + d] + (wQa[d] - wa[d]);
        w[i + d]  = v[i + d] - wa[d];
        cf[i + d] = wwQa[d];
      }
    }
    PetscCall(VecRestoreArrayRead(fem->rr, &r));
    PetscCall(VecRestoreArrayRead(fem->u, &u));
    PetscCall(VecRestoreArrayRead(fem->v, &v));
    PetscCall(VecRestoreArray(fem->uhat, &uh));
    PetscCall(VecRestoreArray(fem->shift, &sh));
    PetscCall(VecRestoreArray(fem->rvt, &vt));
    PetscCall(VecRestoreArray(fem->rw, &w));
    PetscCall(VecRestoreArray(fem->rcf, &cf));
  }
  PetscCall(MatMult(fem->M, fem->rcf, fem->work));
  PetscCall(VecAXPBY(fem->rcf, -1.0, 0.0, fem->work));
  fem->shifted = PETSC_TRUE;
  PetscFunctionReturn(0);
}
