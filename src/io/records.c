/* The per-step records of the output (docs/output.md): a row per completed step in /steps (time,
   energy, timings, the FE bodies' inverted elements, and with contact pairs the contact solver's
   statistics and accuracy measures), the centroid, rotation, energy and (FE bodies) inverted
   elements of every body in /bodies/<name>, and every contact of every step in /contacts. Rows are
   buffered on rank 0 and appended at each flush (each output step). */
#include "ioimpl.h"
#include <stddef.h>

_Static_assert(sizeof(PetscReal) == 8, "the contact records are written as 8-byte columns");

/* The bodies' factorizations, Krylov and Newton iterations so far, summed (/steps takes their
   increments) */
static PetscErrorCode SolverTotals(PetscInt nbodies, FCBody bodies[], PetscInt tot[FC_SOLVER_COUNTS])
{
  PetscFunctionBegin;
  for (int k = 0; k < FC_SOLVER_COUNTS; k++) tot[k] = 0;
  for (PetscInt i = 0; i < nbodies; i++) {
    PetscInt n[FC_SOLVER_COUNTS];
    PetscCall(FCBodyGetSolverCounts(bodies[i], &n[0], &n[1], &n[2]));
    for (int k = 0; k < FC_SOLVER_COUNTS; k++) tot[k] += n[k];
  }
  PetscFunctionReturn(0);
}

/* The initial_energy attribute, /steps and, with contact pairs, /contacts */
PetscErrorCode FCOutputRecordsCreate(FCOutput out, PetscInt nbodies, FCBody bodies[], PetscBool contacts)
{
  hid_t  g, gt;
  size_t nrow = 64;

  PetscFunctionBegin;
  out->elast = 0.0; /* the total energy at t = 0: the reference of /steps/energy_change */
  for (PetscInt i = 0; i < nbodies; i++) {
    FCEnergy E;
    PetscCall(FCBodyGetEnergy(bodies[i], &E));
    out->elast += E.kinetic + E.elastic + E.gravity;
  }
  {
    PetscReal e0 = out->elast;
    PetscCall(FCH5AttrReals(out->file, "initial_energy", 1, &e0));
  }
  g = H5Gcreate2(out->file, "steps", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  PetscCall(FCH5CreateRows(g, "time", H5T_NATIVE_DOUBLE, 1, NULL, 256, &out->time));
  PetscCall(FCH5CreateRows(g, "step", H5T_NATIVE_LLONG, 1, NULL, 256, &out->step));
  PetscCall(FCH5CreateRows(g, "energy", H5T_NATIVE_DOUBLE, 1, NULL, 256, &out->energy));
  PetscCall(FCH5CreateRows(g, "energy_change", H5T_NATIVE_DOUBLE, 1, NULL, 256, &out->denergy));
  PetscCall(FCH5CreateRows(g, "wall_time", H5T_NATIVE_DOUBLE, 1, NULL, 256, &out->wall));
  PetscCall(FCH5CreateRows(g, "factorizations", H5T_NATIVE_LLONG, 1, NULL, 256, &out->s_solve[0]));
  PetscCall(FCH5CreateRows(g, "krylov_iterations", H5T_NATIVE_LLONG, 1, NULL, 256, &out->s_solve[1]));
  PetscCall(FCH5CreateRows(g, "free_motion_iterations", H5T_NATIVE_LLONG, 1, NULL, 256, &out->s_solve[2]));
  PetscCall(FCH5CreateRows(g, "substeps", H5T_NATIVE_LLONG, 1, NULL, 256, &out->s_sub));
  PetscCall(FCH5CreateRows(g, "substep_min", H5T_NATIVE_DOUBLE, 1, NULL, 256, &out->s_hsub));
  PetscCall(SolverTotals(nbodies, bodies, out->lastsolve));
  out->s_inverted[0] = out->s_inverted[1] = -1;
  { /* the FE bodies' inverted elements: scenes with an FE body */
    PetscBool fe = PETSC_FALSE;
    for (PetscInt i = 0; i < nbodies; i++) {
      FCInverted inv;
      PetscBool  has;
      PetscCall(FCBodyGetInverted(bodies[i], &inv, &has));
      fe = (PetscBool)(fe || has);
    }
    if (fe) {
      PetscCall(FCH5CreateRows(g, "inverted_elements", H5T_NATIVE_LLONG, 1, NULL, 256, &out->s_inverted[0]));
      PetscCall(FCH5CreateRows(g, "min_volume_ratio", H5T_NATIVE_DOUBLE, 1, NULL, 256, &out->s_inverted[1]));
    }
  }
  gt = H5Gcreate2(g, "timing", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  for (int p = 0; p < FC_PHASE_NUM; p++)
    PetscCall(FCH5CreateRows(gt, FCPhaseNames[p], H5T_NATIVE_DOUBLE, 1, NULL, 256, &out->timing[p]));
  H5Gclose(gt);
  H5Gclose(g);
  if (contacts) {
    hid_t gc         = H5Gcreate2(out->file, "contacts", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
          gs         = H5Gopen2(out->file, "steps", H5P_DEFAULT);
    hsize_t   two[1] = {2}, three[1] = {3};
    long long zero = 0;
    out->contacts  = PETSC_TRUE;
    PetscCall(FCH5CreateRows(gc, "offset", H5T_NATIVE_LLONG, 1, NULL, 256, &out->c_offset));
    PetscCall(FCH5CreateRows(gc, "bodies", H5T_NATIVE_LLONG, 2, two, 1024, &out->c_bodies));
    PetscCall(FCH5CreateRows(gc, "point", H5T_NATIVE_DOUBLE, 2, three, 1024, &out->c_point));
    PetscCall(FCH5CreateRows(gc, "normal", H5T_NATIVE_DOUBLE, 2, three, 1024, &out->c_normal));
    PetscCall(FCH5CreateRows(gc, "force", H5T_NATIVE_DOUBLE, 2, three, 1024, &out->c_force));
    PetscCall(FCH5CreateRows(gc, "gap", H5T_NATIVE_DOUBLE, 1, NULL, 1024, &out->c_gap));
    PetscCall(FCH5CreateRows(gc, "gap_end", H5T_NATIVE_DOUBLE, 1, NULL, 1024, &out->c_gapend));
    PetscCall(FCH5CreateRows(gc, "state", H5T_NATIVE_LLONG, 1, NULL, 1024, &out->c_state));
    PetscCall(FCH5CreateRows(gc, "point_end", H5T_NATIVE_DOUBLE, 2, three, 1024, &out->c_pointend));
    PetscCall(FCH5CreateRows(gc, "force_world", H5T_NATIVE_DOUBLE, 2, three, 1024, &out->c_fworld));
    PetscCall(FCH5CreateRows(gc, "force_tangential", H5T_NATIVE_DOUBLE, 1, NULL, 1024, &out->c_ftan));
    PetscCall(FCH5CreateRows(gs, "contacts", H5T_NATIVE_LLONG, 1, NULL, 256, &out->s_contacts));
    PetscCall(FCH5CreateRows(gs, "constraint_rows", H5T_NATIVE_LLONG, 1, NULL, 256, &out->s_rows));
    PetscCall(FCH5CreateRows(gs, "pgs_iterations", H5T_NATIVE_LLONG, 1, NULL, 256, &out->s_sweeps));
    PetscCall(FCH5CreateRows(gs, "residual", H5T_NATIVE_DOUBLE, 1, NULL, 256, &out->s_residual));
    PetscCall(FCH5CreateRows(gs, "max_penetration", H5T_NATIVE_DOUBLE, 1, NULL, 256, &out->s_maxpen));
    PetscCall(FCH5CreateRows(gs, "newton_iterations", H5T_NATIVE_LLONG, 1, NULL, 256, &out->s_newton));
    PetscCall(FCH5CreateRows(gs, "violation", H5T_NATIVE_DOUBLE, 1, NULL, 256, &out->s_violation));
    PetscCall(FCH5CreateRows(gs, "rms_penetration", H5T_NATIVE_DOUBLE, 1, NULL, 256, &out->s_rmspen));
    PetscCall(FCH5CreateRows(gs, "complementarity", H5T_NATIVE_DOUBLE, 1, NULL, 256, &out->s_compl));
    PetscCall(FCH5CreateRows(gs, "cone_violation", H5T_NATIVE_DOUBLE, 1, NULL, 256, &out->s_cone));
    PetscCall(FCH5CreateRows(gs, "intersections", H5T_NATIVE_LLONG, 1, NULL, 256, &out->s_intersections));
    PetscCall(FCH5CreateRows(gs, "contacts_beyond_check", H5T_NATIVE_LLONG, 1, NULL, 256, &out->s_beyond));
    PetscCall(FCH5CreateRows(gs, "max_complementarity", H5T_NATIVE_DOUBLE, 1, NULL, 256, &out->s_maxcompl));
    PetscCall(FCH5CreateRows(gs, "crossings", H5T_NATIVE_LLONG, 1, NULL, 256, &out->s_crossings));
    PetscCall(FCH5CreateRows(gs, "crossing_depth", H5T_NATIVE_DOUBLE, 1, NULL, 256, &out->s_crossdepth));
    PetscCall(FCH5AppendRows(out->rank, out->c_offset, H5T_NATIVE_LLONG, 1, &zero));
    H5Gclose(gs);
    H5Gclose(gc);
  }
  out->maxrows = (PetscInt)nrow;
  PetscCall(PetscMalloc1(FC_SOLVER_COUNTS * nrow, &out->rsolve));
  PetscCall(PetscMalloc2(nrow, &out->rsub, nrow, &out->rhsub));
  PetscCall(PetscMalloc5(nrow, &out->rtime, nrow, &out->renergy, nrow * (FC_PHASE_NUM + 1), &out->rtiming,
                         nrow * nbodies * FC_BODY_ROW + 1, &out->rbody, nrow, &out->rstep));
  PetscFunctionReturn(0);
}

/* One row per completed step (buffered until the next flush) */
PetscErrorCode FCOutputRecordStep(FCOutput out, PetscInt step, PetscReal t, const PetscReal timing[FC_PHASE_NUM],
                                  PetscReal wall, PetscInt substeps, PetscReal hsub, PetscInt nbodies, FCBody bodies[])
{
  PetscInt r    = out->nrows;
  double   etot = 0.0;

  PetscFunctionBegin;
  if (r == out->maxrows) {
    double   *a, *b, *c, *d;
    PetscInt *e, n = 2 * out->maxrows;
    PetscCall(PetscMalloc5(n, &a, n, &b, n * (FC_PHASE_NUM + 1), &c, n * nbodies * FC_BODY_ROW + 1, &d, n, &e));
    PetscCall(PetscArraycpy(a, out->rtime, r));
    PetscCall(PetscArraycpy(b, out->renergy, r));
    PetscCall(PetscArraycpy(c, out->rtiming, r * (FC_PHASE_NUM + 1)));
    PetscCall(PetscArraycpy(d, out->rbody, r * nbodies * FC_BODY_ROW));
    PetscCall(PetscArraycpy(e, out->rstep, r));
    {
      long long *f;
      PetscCall(PetscMalloc1(FC_SOLVER_COUNTS * n, &f));
      PetscCall(PetscArraycpy(f, out->rsolve, FC_SOLVER_COUNTS * r));
      PetscCall(PetscFree(out->rsolve));
      out->rsolve = f;
    }
    {
      long long *f;
      double    *g;
      PetscCall(PetscMalloc2(n, &f, n, &g));
      PetscCall(PetscArraycpy(f, out->rsub, r));
      PetscCall(PetscArraycpy(g, out->rhsub, r));
      PetscCall(PetscFree2(out->rsub, out->rhsub));
      out->rsub  = f;
      out->rhsub = g;
    }
    PetscCall(PetscFree5(out->rtime, out->renergy, out->rtiming, out->rbody, out->rstep));
    out->rtime   = a;
    out->renergy = b;
    out->rtiming = c;
    out->rbody   = d;
    out->rstep   = e;
    for (PetscInt i = 0; i < nbodies; i++) {
      BodyOut *bo = &out->bo[i];
      if (!bo->nreact) continue;
      PetscCall(PetscMalloc1(6 * bo->nreact * n, &a));
      PetscCall(PetscArraycpy(a, bo->rreact, 6 * bo->nreact * r));
      PetscCall(PetscFree(bo->rreact));
      bo->rreact = a;
    }
    out->maxrows = n;
  }
  out->rtime[r] = t;
  out->rstep[r] = step;
  out->rsub[r]  = substeps;
  out->rhsub[r] = hsub;
  {
    PetscInt tot[FC_SOLVER_COUNTS];
    PetscCall(SolverTotals(nbodies, bodies, tot));
    for (int k = 0; k < FC_SOLVER_COUNTS; k++) {
      out->rsolve[FC_SOLVER_COUNTS * r + k] = tot[k] - out->lastsolve[k];
      out->lastsolve[k]                     = tot[k];
    }
  }
  for (int p = 0; p < FC_PHASE_NUM; p++) out->rtiming[r * (FC_PHASE_NUM + 1) + p] = timing[p];
  out->rtiming[r * (FC_PHASE_NUM + 1) + FC_PHASE_NUM] = wall;
  for (PetscInt i = 0; i < nbodies; i++) {
    double   *row = &out->rbody[(r * nbodies + i) * FC_BODY_ROW];
    FCEnergy  E;
    PetscBool has;
    PetscCall(FCBodyGetCentroid(bodies[i], row));
    PetscCall(FCBodyGetRotation(bodies[i], row + 3, &has));
    PetscCall(FCBodyGetEnergy(bodies[i], &E));
    if (out->bo[i].nreact) {
      const PetscReal *R;
      PetscInt         n;
      PetscCall(FCBodyGetReactions(bodies[i], &n, NULL, &R));
      PetscCall(PetscArraycpy(&out->bo[i].rreact[6 * n * r], R, 6 * n));
    }
    row[7] = E.kinetic;
    row[8] = E.elastic;
    row[9] = E.gravity;
    {
      FCInverted inv;
      PetscCall(FCBodyGetInverted(bodies[i], &inv, &has));
      row[10] = has ? (double)inv.count : 0.0;
      row[11] = has ? (double)inv.min_J : PETSC_MAX_REAL; /* no J: not in the scene's smallest */
    }
    etot += E.kinetic + E.elastic + E.gravity;
  }
  out->renergy[r] = etot;
  out->nrows++;
  PetscFunctionReturn(0);
}

PetscErrorCode FCOutputRecordContacts(FCOutput out, const struct _FCContactSetView *v)
{
  const FCContactSet *set = v->set;

  PetscFunctionBegin;
  if (out->ns == out->maxs) {
    void *tmp;
    out->maxs = PetscMax(64, 2 * out->maxs);
    PetscCall(PetscMalloc(out->maxs * sizeof(*out->sbuf), &tmp));
    if (out->ns) PetscCall(PetscMemcpy(tmp, out->sbuf, out->ns * sizeof(*out->sbuf)));
    PetscCall(PetscFree(out->sbuf));
    out->sbuf = tmp;
  }
  if (out->nc + set->n > out->maxc) {
    void *tmp;
    out->maxc = PetscMax(2 * out->maxc, out->nc + set->n + 256);
    PetscCall(PetscMalloc(out->maxc * sizeof(*out->cbuf), &tmp));
    if (out->nc) PetscCall(PetscMemcpy(tmp, out->cbuf, out->nc * sizeof(*out->cbuf)));
    PetscCall(PetscFree(out->cbuf));
    out->cbuf = tmp;
  }
  for (PetscInt k = 0; k < set->n; k++) {
    const FCContact *c           = &set->c[k];
    out->cbuf[out->nc].bodies[0] = c->body[0];
    out->cbuf[out->nc].bodies[1] = c->body[1];
    out->cbuf[out->nc].state     = c->state;
    for (int i = 0; i < 3; i++) {
      out->cbuf[out->nc].point[i]  = c->p0[0][i];
      out->cbuf[out->nc].normal[i] = c->n[i];
      out->cbuf[out->nc].force[i]  = c->force[i];
    }
    out->cbuf[out->nc].gap     = c->gap0;
    out->cbuf[out->nc].gap_end = c->gap_end;
    for (int i = 0; i < 3; i++) out->cbuf[out->nc].point_end[i] = c->p_end[i];
    FCContactForceWorld(c, out->cbuf[out->nc].force_world);
    out->cbuf[out->nc].force_tangential = PetscSqrtReal(c->force[1] * c->force[1] + c->force[2] * c->force[2]);
    out->nc++;
  }
  out->ctotal += set->n;
  out->clast                       = set->n;
  out->sbuf[out->ns].contacts      = set->n;
  out->sbuf[out->ns].rows          = v->stats->rows;
  out->sbuf[out->ns].sweeps        = v->stats->sweeps;
  out->sbuf[out->ns].residual      = v->stats->residual;
  out->sbuf[out->ns].m             = *v->measures;
  out->sbuf[out->ns].newton        = v->stats->newton;
  out->sbuf[out->ns].intersections = v->measures->intersections;
  out->sbuf[out->ns].beyond        = v->measures->beyond;
  out->sbuf[out->ns].crossings     = v->measures->crossings;
  out->sbuf[out->ns].offset        = out->ctotal;
  out->ns++;
  PetscFunctionReturn(0);
}

/* One column of n buffered records: ncomp 8-byte values (long long or double) at `offset` in
   records of `stride` bytes, gathered into buf and appended to dset */
static PetscErrorCode AppendColumn(FCOutput out, hid_t dset, hid_t memtype, PetscInt n, const void *rec, size_t stride,
                                   size_t offset, int ncomp, char *buf)
{
  PetscFunctionBegin;
  for (PetscInt k = 0; k < n; k++)
    PetscCall(PetscMemcpy(buf + 8 * ncomp * k, (const char *)rec + k * stride + offset, 8 * ncomp));
  PetscCall(FCH5AppendRows(out->rank, dset, memtype, n, buf));
  PetscFunctionReturn(0);
}

static PetscErrorCode FlushContacts(FCOutput out)
{
  const size_t cs = sizeof(FCContactRecord), ss = sizeof(FCStepRecord);
  const struct {
    hid_t  dset, type;
    int    steps; /* a column of the step records, else of the contact records */
    size_t offset;
    int    ncomp;
  } col[] = {
      {out->c_bodies, H5T_NATIVE_LLONG, 0, offsetof(FCContactRecord, bodies), 2},
      {out->c_point, H5T_NATIVE_DOUBLE, 0, offsetof(FCContactRecord, point), 3},
      {out->c_normal, H5T_NATIVE_DOUBLE, 0, offsetof(FCContactRecord, normal), 3},
      {out->c_force, H5T_NATIVE_DOUBLE, 0, offsetof(FCContactRecord, force), 3},
      {out->c_gap, H5T_NATIVE_DOUBLE, 0, offsetof(FCContactRecord, gap), 1},
      {out->c_gapend, H5T_NATIVE_DOUBLE, 0, offsetof(FCContactRecord, gap_end), 1},
      {out->c_state, H5T_NATIVE_LLONG, 0, offsetof(FCContactRecord, state), 1},
      {out->c_pointend, H5T_NATIVE_DOUBLE, 0, offsetof(FCContactRecord, point_end), 3},
      {out->c_fworld, H5T_NATIVE_DOUBLE, 0, offsetof(FCContactRecord, force_world), 3},
      {out->c_ftan, H5T_NATIVE_DOUBLE, 0, offsetof(FCContactRecord, force_tangential), 1},
      {out->c_offset, H5T_NATIVE_LLONG, 1, offsetof(FCStepRecord, offset), 1},
      {out->s_contacts, H5T_NATIVE_LLONG, 1, offsetof(FCStepRecord, contacts), 1},
      {out->s_rows, H5T_NATIVE_LLONG, 1, offsetof(FCStepRecord, rows), 1},
      {out->s_sweeps, H5T_NATIVE_LLONG, 1, offsetof(FCStepRecord, sweeps), 1},
      {out->s_residual, H5T_NATIVE_DOUBLE, 1, offsetof(FCStepRecord, residual), 1},
      {out->s_maxpen, H5T_NATIVE_DOUBLE, 1, offsetof(FCStepRecord, m.max_penetration), 1},
      {out->s_newton, H5T_NATIVE_LLONG, 1, offsetof(FCStepRecord, newton), 1},
      {out->s_violation, H5T_NATIVE_DOUBLE, 1, offsetof(FCStepRecord, m.violation), 1},
      {out->s_rmspen, H5T_NATIVE_DOUBLE, 1, offsetof(FCStepRecord, m.rms_penetration), 1},
      {out->s_compl, H5T_NATIVE_DOUBLE, 1, offsetof(FCStepRecord, m.complementarity), 1},
      {out->s_cone, H5T_NATIVE_DOUBLE, 1, offsetof(FCStepRecord, m.cone_violation), 1},
      {out->s_intersections, H5T_NATIVE_LLONG, 1, offsetof(FCStepRecord, intersections), 1},
      {out->s_beyond, H5T_NATIVE_LLONG, 1, offsetof(FCStepRecord, beyond), 1},
      {out->s_maxcompl, H5T_NATIVE_DOUBLE, 1, offsetof(FCStepRecord, m.max_complementarity), 1},
      {out->s_crossings, H5T_NATIVE_LLONG, 1, offsetof(FCStepRecord, crossings), 1},
      {out->s_crossdepth, H5T_NATIVE_DOUBLE, 1, offsetof(FCStepRecord, m.crossing_depth), 1},
  };
  char *buf;

  PetscFunctionBegin;
  if (!out->contacts) PetscFunctionReturn(0);
  PetscCall(PetscMalloc1(8 * 3 * (out->nc + out->ns) + 8, &buf));
  for (size_t i = 0; i < sizeof(col) / sizeof(col[0]); i++)
    PetscCall(AppendColumn(out, col[i].dset, col[i].type, col[i].steps ? out->ns : out->nc,
                           col[i].steps ? (const void *)out->sbuf : (const void *)out->cbuf, col[i].steps ? ss : cs,
                           col[i].offset, col[i].ncomp, buf));
  PetscCall(PetscFree(buf));
  out->nc = out->ns = 0;
  PetscFunctionReturn(0);
}

/* Appends the buffered step rows and contacts */
PetscErrorCode FCOutputRecordsFlush(FCOutput out)
{
  PetscInt n = out->nrows, nb = out->nbodies;
  double  *tmp;

  PetscFunctionBegin;
  if (n) {
    long long *steps;
    PetscCall(PetscMalloc2(n * 6 + 1, &tmp, n, &steps));
    for (PetscInt r = 0; r < n; r++) steps[r] = out->rstep[r];
    PetscCall(FCH5AppendRows(out->rank, out->time, H5T_NATIVE_DOUBLE, n, out->rtime));
    PetscCall(FCH5AppendRows(out->rank, out->step, H5T_NATIVE_LLONG, n, steps));
    for (int k = 0; k < FC_SOLVER_COUNTS; k++) {
      for (PetscInt r = 0; r < n; r++) steps[r] = out->rsolve[FC_SOLVER_COUNTS * r + k];
      PetscCall(FCH5AppendRows(out->rank, out->s_solve[k], H5T_NATIVE_LLONG, n, steps));
    }
    PetscCall(FCH5AppendRows(out->rank, out->s_sub, H5T_NATIVE_LLONG, n, out->rsub));
    PetscCall(FCH5AppendRows(out->rank, out->s_hsub, H5T_NATIVE_DOUBLE, n, out->rhsub));
    PetscCall(FCH5AppendRows(out->rank, out->energy, H5T_NATIVE_DOUBLE, n, out->renergy));
    for (PetscInt r = 0; r < n; r++) { /* energy change over each step: a scheme adding energy shows here */
      tmp[r]     = out->renergy[r] - out->elast;
      out->elast = out->renergy[r];
    }
    PetscCall(FCH5AppendRows(out->rank, out->denergy, H5T_NATIVE_DOUBLE, n, tmp));
    for (int p = 0; p <= FC_PHASE_NUM; p++) { /* the phases, then the wall time */
      for (PetscInt r = 0; r < n; r++) tmp[r] = out->rtiming[r * (FC_PHASE_NUM + 1) + p];
      PetscCall(FCH5AppendRows(out->rank, p < FC_PHASE_NUM ? out->timing[p] : out->wall, H5T_NATIVE_DOUBLE, n, tmp));
    }
    for (PetscInt i = 0; i < nb; i++) {
      for (PetscInt r = 0; r < n; r++)
        for (int k = 0; k < 3; k++) tmp[3 * r + k] = out->rbody[(r * nb + i) * FC_BODY_ROW + k];
      PetscCall(FCH5AppendRows(out->rank, out->bo[i].centroid, H5T_NATIVE_DOUBLE, n, tmp));
      for (PetscInt r = 0; r < n; r++)
        for (int k = 0; k < 3; k++) tmp[3 * r + k] = out->rbody[(r * nb + i) * FC_BODY_ROW + 7 + k];
      PetscCall(FCH5AppendRows(out->rank, out->bo[i].energy, H5T_NATIVE_DOUBLE, n, tmp));
      for (PetscInt k = 0; k < out->bo[i].nreact; k++) {
        PetscInt nr = out->bo[i].nreact;
        for (PetscInt r = 0; r < n; r++)
          for (int j = 0; j < 6; j++) tmp[6 * r + j] = out->bo[i].rreact[6 * nr * r + 6 * k + j];
        PetscCall(FCH5AppendRows(out->rank, out->bo[i].react[k], H5T_NATIVE_DOUBLE, n, tmp));
      }
      if (out->bo[i].rotation >= 0) {
        for (PetscInt r = 0; r < n; r++)
          for (int k = 0; k < 4; k++) tmp[4 * r + k] = out->rbody[(r * nb + i) * FC_BODY_ROW + 3 + k];
        PetscCall(FCH5AppendRows(out->rank, out->bo[i].rotation, H5T_NATIVE_DOUBLE, n, tmp));
      }
      if (out->bo[i].inverted[0] >= 0) {
        for (PetscInt r = 0; r < n; r++) steps[r] = (long long)out->rbody[(r * nb + i) * FC_BODY_ROW + 10];
        PetscCall(FCH5AppendRows(out->rank, out->bo[i].inverted[0], H5T_NATIVE_LLONG, n, steps));
        for (PetscInt r = 0; r < n; r++) tmp[r] = out->rbody[(r * nb + i) * FC_BODY_ROW + 11];
        PetscCall(FCH5AppendRows(out->rank, out->bo[i].inverted[1], H5T_NATIVE_DOUBLE, n, tmp));
      }
    }
    if (out->s_inverted[0] >= 0) { /* the scene's: the FE bodies' counts summed, their smallest J */
      for (PetscInt r = 0; r < n; r++) {
        steps[r] = 0;
        tmp[r]   = PETSC_MAX_REAL;
        for (PetscInt i = 0; i < nb; i++) {
          steps[r] += (long long)out->rbody[(r * nb + i) * FC_BODY_ROW + 10];
          tmp[r] = PetscMin(tmp[r], out->rbody[(r * nb + i) * FC_BODY_ROW + 11]);
        }
      }
      PetscCall(FCH5AppendRows(out->rank, out->s_inverted[0], H5T_NATIVE_LLONG, n, steps));
      PetscCall(FCH5AppendRows(out->rank, out->s_inverted[1], H5T_NATIVE_DOUBLE, n, tmp));
    }
    out->laststep = PetscMax(out->laststep, (long long)out->rstep[n - 1]);
    PetscCall(PetscFree2(tmp, steps));
    out->nrows = 0;
  }
  PetscCall(FlushContacts(out));
  PetscFunctionReturn(0);
}

PetscErrorCode FCOutputRecordsDestroy(FCOutput out)
{
  PetscFunctionBegin;
  if (FCH5FailedInside()) goto release; /* after a failed write nothing is closed (output.c, FCOutputDestroy) */
  H5Dclose(out->time);
  H5Dclose(out->step);
  H5Dclose(out->energy);
  H5Dclose(out->denergy);
  H5Dclose(out->wall);
  for (int k = 0; k < FC_SOLVER_COUNTS; k++) H5Dclose(out->s_solve[k]);
  H5Dclose(out->s_sub);
  H5Dclose(out->s_hsub);
  for (int k = 0; k < 2; k++)
    if (out->s_inverted[k] >= 0) H5Dclose(out->s_inverted[k]);
  for (int p = 0; p < FC_PHASE_NUM; p++) H5Dclose(out->timing[p]);
  if (out->contacts) {
    hid_t ds[] = {out->c_offset,    out->c_bodies,   out->c_point,  out->c_normal,        out->c_force,
                  out->c_gap,       out->c_gapend,   out->c_state,  out->s_contacts,      out->s_rows,
                  out->s_sweeps,    out->s_residual, out->s_maxpen, out->s_newton,        out->s_violation,
                  out->s_rmspen,    out->s_compl,    out->s_cone,   out->s_intersections, out->c_pointend,
                  out->c_fworld,    out->c_ftan,     out->s_beyond, out->s_maxcompl,      out->s_crossings,
                  out->s_crossdepth};
    for (size_t i = 0; i < sizeof(ds) / sizeof(ds[0]); i++) H5Dclose(ds[i]);
  }
release:
  PetscCall(PetscFree(out->cbuf));
  PetscCall(PetscFree(out->sbuf));
  PetscCall(PetscFree5(out->rtime, out->renergy, out->rtiming, out->rbody, out->rstep));
  PetscCall(PetscFree(out->rsolve));
  PetscCall(PetscFree2(out->rsub, out->rhsub));
  for (PetscInt i = 0; i < out->nbodies && out->bo; i++) PetscCall(PetscFree(out->bo[i].rreact));
  PetscFunctionReturn(0);
}
