/* FCScene: reads the scene options (-scene_bodies, -time_step, -time_steps, -gravity, -output_*,
   -quiet, -restart, -energy_growth_limit: each described by its help string below and in
   docs/options.md), creates the bodies and owns the time loop. The options of the objects the scene
   creates are read where those objects live: the contact pairs and the detection (-contact_*:
   src/collision/pairs.c), the constraint scheme and its contact solver (-constraint_scheme,
   -newton_*, -pgs_*, -contact_solver, -contact_memory_limit: src/scheme/, src/contact/solver.c), the
   compliance builder of each FE body in a contact pair (-compliance_*: src/compliance/), each body
   (-<name>_*: src/body/), step control (-time_step_control, -time_step_*: stepcontrol.c). One step
   (step.c; docs/method.md, section 2): free motion of every body (eq. 5), then integration (eq. 2);
   contact resolution slots in between. A restart continues from the newest
   complete restart state of a file (docs/output.md, /restart) at its stored time, with this run's time
   step. */
#include "sceneimpl.h"
#include <signal.h>
#include <stdlib.h>

static PetscErrorCode SceneCreate(MPI_Comm comm, FCScene *scene)
{
  FCScene s;

  PetscFunctionBegin;
  PetscCall(FCInitializePackage());
  PetscCall(PetscNew(&s));
  PetscCall(FCInputsReset()); /* the files this scene reads, by identity: no output may be one */
  PetscCall(FCInputsAddOptionsFiles());
  s->comm       = comm;
  s->h          = 0.01;
  s->nsteps     = 100;
  s->every      = 1;
  s->gravity[2] = -9.81;
  PetscCall(PetscStrncpy(s->output_file, "fecontact.h5", sizeof(s->output_file)));
  *scene = s;
  PetscFunctionReturn(0);
}

/* collective failure: an error on one rank is raised on every rank (FCErrorAgree) */
PetscErrorCode FCSceneCreate(MPI_Comm comm, FCScene *scene)
{
  PetscFunctionBegin;
  FCValidPointer(scene, 2);
  PetscCall(FCErrorAgree(comm, SceneCreate(comm, scene)));
  PetscFunctionReturn(0);
}

/* The bodies of -scene_bodies (n names), each with its options, and the output's fields */
static PetscErrorCode CreateBodies(FCScene s, PetscBool set, PetscInt n, char *names[], const char fields[])
{
  PetscFunctionBegin;
  PetscCheck(set && n > 0, s->comm, PETSC_ERR_USER_INPUT,
             "No bodies: give -scene_bodies name1,name2,... (see docs/options.md)");
  PetscCheck(s->h > 0.0, s->comm, PETSC_ERR_USER_INPUT, "Option -time_step must be > 0, got %g", (double)s->h);
  PetscCall(FCOutputFieldsParse(s->comm, fields, &s->fields));
  for (PetscInt i = 0; i < n; i++) {
    for (PetscInt j = 0; j < i; j++)
      PetscCheck(strcmp(names[i], names[j]), s->comm, PETSC_ERR_USER_INPUT, "Body '%s' appears twice in -scene_bodies",
                 names[i]);
    PetscCall(FCBodyCreate(s->comm, names[i], &s->bodies[i]));
    s->nbodies++;
    PetscCall(FCBodySetFromOptions(s->bodies[i]));
  }
  PetscFunctionReturn(0);
}

static PetscErrorCode SceneSetFromOptions(FCScene s)
{
  char           fields[256]          = "displacement,velocity,von_mises";
  char          *names[FC_MAX_BODIES] = {NULL};
  PetscInt       n                    = FC_MAX_BODIES;
  PetscBool      set;
  PetscErrorCode ierr;

  PetscFunctionBegin;
  PetscOptionsBegin(s->comm, NULL, "Scene options", "FCScene");
  PetscCall(PetscOptionsStringArray("-scene_bodies", "Comma-separated body names", NULL, names, &n, &set));
  PetscCall(FCOptionsReal(PetscOptionsObject, "-time_step", "Time step h (s)", &s->h, NULL));
  PetscCall(
      FCOptionsIntRange(PetscOptionsObject, "-time_steps", "Number of time steps", 0, PETSC_MAX_INT, &s->nsteps, NULL));
  PetscCall(FCOptionsRealArray(PetscOptionsObject, "-gravity", "Gravity gx,gy,gz (m/s^2)", 3, s->gravity, NULL));
  PetscCall(PetscOptionsString("-output_file", "HDF5 output file", NULL, s->output_file, s->output_file,
                               sizeof(s->output_file), NULL));
  PetscCall(FCOptionsIntRange(PetscOptionsObject, "-output_every", "Write body positions every k steps", 1,
                              PETSC_MAX_INT, &s->every, NULL));
  /* -output_fields: which fields each frame holds (names in src/io/fields.c); a field not named is never computed */
  PetscCall(PetscOptionsString("-output_fields",
                               "Fields of the frames: displacement,velocity,von_mises,energy_density or none", NULL,
                               fields, fields, sizeof(fields), NULL));
  PetscCall(FCOptionsBool(PetscOptionsObject, "-quiet", "No progress line and no summary", &s->quiet, NULL));
  {
    const char *ti[] = {"euler", "static"};
    PetscInt    k    = s->quasistatic ? 1 : 0;
    PetscCall(FCOptionsEList(PetscOptionsObject, "-time_integration",
                             "euler: implicit Euler (eq. 5); static: no inertia, each step the equilibrium of its time",
                             ti, 2, &k, NULL));
    s->quasistatic = k == 1 ? PETSC_TRUE : PETSC_FALSE;
  }
  PetscCall(PetscOptionsString("-restart", "Continue from the last complete output step of this HDF5 file", NULL,
                               s->restart, s->restart, sizeof(s->restart), NULL));
  PetscOptionsEnd();
  ierr = CreateBodies(s, set, n, names, fields); /* the names are freed after an error too */
  for (PetscInt i = 0; i < FC_MAX_BODIES; i++) PetscCall(PetscFree(names[i]));
  PetscCall(ierr);
  PetscCall(FCCollisionCreate(s->comm, s->nbodies, s->bodies, &s->collision));
  PetscCall(FCCollisionSetFromOptions(s->collision));
  s->pairs = FCCollisionGetPairs(s->collision);
  PetscCall(FCEnergyGuardSetFromOptions(&s->guard, s->comm));
  PetscCall(FCStepControlSetFromOptions(&s->control, s->comm, s->h));
  PetscCall(FCSettleSetFromOptions(&s->settle, s->comm));
  PetscFunctionReturn(0);
}

/* collective failure: an error on one rank is raised on every rank (FCErrorAgree) */
PetscErrorCode FCSceneSetFromOptions(FCScene s)
{
  PetscFunctionBegin;
  FCValidPointer(s, 1);
  PetscCall(FCErrorAgree(s->comm, SceneSetFromOptions(s)));
  PetscFunctionReturn(0);
}

/* The state of the current step as a frame (positions, with the step rows before it) and then
   as the restart state, each flushed: if a write fails, the restart state is never ahead of the
   frames and rows (docs/output.md) */
PetscErrorCode FCSceneWriteOutputStep(FCScene s)
{
  PetscFunctionBegin;
  PetscCall(FCOutputWriteFrame(s->output, s->step, s->t, s->nbodies, s->bodies));
  {
    PetscReal control[3];
    FCStepControlGetState(&s->control, control);
    PetscCall(FCOutputWriteRestart(s->output, s->step, s->t, control, s->nbodies, s->bodies, &s->previous));
  }
  s->written = s->step;
  PetscFunctionReturn(0);
}

/* The same, closing the output if it fails (the failure is collective: src/io/h5util.c) */
static PetscErrorCode WriteOutputStepOrClose(FCScene s)
{
  PetscErrorCode ierr = FCSceneWriteOutputStep(s);

  PetscFunctionBegin;
  if (ierr) {
    (void)FCOutputDestroy(&s->output);
    return ierr;
  }
  PetscFunctionReturn(0);
}

/* At set-up, once the start state is known (a restart's included), before the first free motion:
   a body whose first factorization depends on its contact DOFs (the condensed builder's Schur
   block) gets the contacts of a discrete proximity query at the start positions. A body that starts in contact is then
   factored once in its first step, not a plain factorization and, at the first contacts, a second one with them. */
static PetscErrorCode ExpectContacts(FCScene s)
{
  PetscBool any = PETSC_FALSE;

  PetscFunctionBegin;
  for (PetscInt i = 0; i < s->nbodies; i++) any = (PetscBool)(any || FCBodyExpectsContacts(s->bodies[i]));
  if (!any) PetscFunctionReturn(0);
  PetscCall(FCPhaseBegin(FC_PHASE_COLLISION));
  PetscCall(FCCollisionDetect(s->collision, PETSC_FALSE, &s->set)); /* the free motion is not known yet */
  for (PetscInt i = 0; i < s->nbodies; i++) PetscCall(FCBodyExpectContacts(s->bodies[i], i, &s->set));
  PetscCall(FCContactSetReset(&s->set));
  PetscCall(FCPhaseEnd(FC_PHASE_COLLISION));
  PetscFunctionReturn(0);
}

static PetscErrorCode SceneSetUp(FCScene s)
{
  PetscFunctionBegin;
  if (s->setupcalled) PetscFunctionReturn(0);
  for (PetscInt i = 0; i < s->nbodies; i++) {
    PetscCall(FCBodySetTimeStep(s->bodies[i], s->h));
    PetscCall(FCBodySetQuasiStatic(s->bodies[i], s->quasistatic));
    PetscCall(FCBodySetSceneBodies(s->bodies[i], s->nbodies, s->bodies));
    PetscCall(FCBodySetStepContacts(s->bodies[i], i, &s->set));
    PetscCall(FCBodySetGravity(s->bodies[i], s->gravity));
    PetscCall(FCBodySetUp(s->bodies[i]));
  }
  if (s->pairs->n) {
    for (PetscInt i = 0; i < s->nbodies; i++) { /* bodies named in a contact pair: their response */
      PetscBool paired = PETSC_FALSE;
      for (PetscInt p = 0; p < s->pairs->n; p++)
        paired = paired || s->pairs->body[p][0] == i || s->pairs->body[p][1] == i;
      if (paired) PetscCall(FCBodySetUpContact(s->bodies[i]));
    }
    PetscCall(FCSchemeCreate(s->comm, s->nbodies, s->bodies, &s->scheme));
    PetscCall(FCSchemeSetFromOptions(s->scheme));
  }
  PetscCall(FCOptionsCheckUnused(s->comm)); /* after every object has read its options */
  if (s->restart[0]) { /* an input, by identity: FCOutputCreate refuses to write over it (src/util/inputs.c) */
    PetscCall(FCInputsAdd(s->restart, "restart file (-restart)"));
    PetscReal control[3];
    PetscCall(FCRestartLoad(s->comm, s->restart, s->nbodies, s->bodies, &s->previous, &s->step, &s->t, control));
    FCStepControlSetState(&s->control, control);
    PetscCall(FCRestartCheckScene(s->comm, s->restart, s->nbodies, s->bodies));
    PetscCheck(s->step <= s->nsteps, s->comm, PETSC_ERR_USER_INPUT,
               "-restart %s is at step %" PetscInt_FMT ", beyond -time_steps %" PetscInt_FMT, s->restart, s->step,
               s->nsteps);
    /* the run continues at the stored time, with this run's -time_step (which may differ from the
       earlier run's): step k is at t0 + (k - step0) h, kinematic bodies go on from where they were */
    s->t0    = s->t;
    s->step0 = s->step;
  }
  for (PetscInt i = 0; i < s->nbodies; i++) PetscCall(FCBodySetTime(s->bodies[i], s->t));
  if (s->pairs->n) PetscCall(ExpectContacts(s));
  PetscCall(FCStepControlSetUp(&s->control, s->nbodies, s->bodies));
  PetscCall(FCEnergyGuardSetUp(&s->guard, s->comm, s->nbodies, s->bodies, s->h, s->nsteps - s->step,
                               s->pairs->n ? s->pairs->separation_speed : 0.0));
  PetscCall(FCOutputCreate(s->comm, s->output_file, &s->output));
  PetscCall(FCOutputSetFields(s->output, s->fields));
  { /* a failed write (collective, src/io/h5util.c) closes the file on every rank before returning */
    PetscErrorCode ierr = FCOutputWriteHeader(s->output, s->nbodies, s->bodies, s->h, s->nsteps, s->every,
                                              s->pairs->n ? PETSC_TRUE : PETSC_FALSE);
    if (!ierr) ierr = FCSceneWriteOutputStep(s);
    if (ierr) {
      (void)FCOutputDestroy(&s->output);
      return ierr;
    }
  }
  PetscCall(FCPhaseResetTimes()); /* the phases, and the first step's wall time, count from here */
  PetscCall(PetscTime(&s->tmark));
  s->setupcalled = PETSC_TRUE;
  PetscFunctionReturn(0);
}

/* collective failure: an error on one rank is raised on every rank (FCErrorAgree) */
PetscErrorCode FCSceneSetUp(FCScene s)
{
  PetscFunctionBegin;
  FCValidPointer(s, 1);
  PetscCall(FCErrorAgree(s->comm, SceneSetUp(s)));
  PetscFunctionReturn(0);
}

PetscErrorCode FCSceneGetBody(FCScene s, const char name[], FCBody *body)
{
  PetscFunctionBegin;
  FCValidPointer(s, 1);
  FCValidPointer(name, 2);
  FCValidPointer(body, 3);
  *body = NULL;
  for (PetscInt i = 0; i < s->nbodies; i++)
    if (!strcmp(FCBodyName(s->bodies[i]), name)) *body = s->bodies[i];
  PetscCheck(*body, s->comm, PETSC_ERR_USER_INPUT, "No body named '%s' in -scene_bodies", name);
  PetscFunctionReturn(0);
}

static PetscErrorCode PrintSummary(FCScene s, PetscLogDouble wall)
{
  PetscFunctionBegin;
  PetscCall(PetscPrintf(s->comm, "fecontact: %" PetscInt_FMT " steps of %g s (t = %g s) in %.3f s wall\n", s->step,
                        (double)s->h, (double)s->t, (double)wall));
  PetscCall(PetscPrintf(s->comm, "  time per phase (s, max over ranks):"));
  for (int p = 0; p < FC_PHASE_NUM; p++)
    PetscCall(PetscPrintf(s->comm, " %s %.3f", FCPhaseNames[p], (double)s->phase_total[p]));
  PetscCall(PetscPrintf(s->comm, "\n"));
  for (PetscInt i = 0; i < s->nbodies; i++) {
    PetscReal c[3];
    FCEnergy  E;
    PetscCall(FCBodyGetCentroid(s->bodies[i], c));
    PetscCall(FCBodyGetEnergy(s->bodies[i], &E));
    PetscCall(PetscPrintf(
        s->comm, "  body %-12s %-9s centroid (%.6g, %.6g, %.6g)  energy kinetic %.6g elastic %.6g gravity %.6g\n",
        FCBodyName(s->bodies[i]), FCBodyTypeName(s->bodies[i]), (double)c[0], (double)c[1], (double)c[2],
        (double)E.kinetic, (double)E.elastic, (double)E.gravity));
    {
      const char     **names;
      const PetscReal *R;
      PetscInt         n;
      PetscCall(FCBodyGetReactions(s->bodies[i], &n, &names, &R));
      for (PetscInt k = 0; k < n; k++)
        PetscCall(PetscPrintf(s->comm, "    reaction %-20s force (%.6g, %.6g, %.6g)  moment (%.6g, %.6g, %.6g)\n",
                              names[k], (double)R[6 * k], (double)R[6 * k + 1], (double)R[6 * k + 2],
                              (double)R[6 * k + 3], (double)R[6 * k + 4], (double)R[6 * k + 5]));
    }
    if (s->inverted[i].steps)
      PetscCall(PetscPrintf(s->comm,
                            "    elements inside out (J = det F <= 0) at the end of %" PetscInt_FMT " of %" PetscInt_FMT
                            " steps, at most %" PetscInt_FMT " at once, J down to %g\n",
                            s->inverted[i].steps, s->step - s->step0, s->inverted[i].most,
                            (double)s->inverted[i].worst));
  }
  if (s->control.cuts)
    PetscCall(PetscPrintf(s->comm,
                          "  step control: %" PetscInt_FMT " step(s) cut, %" PetscInt_FMT
                          " cut(s) in all, smallest time step %g s (/steps/substeps, /steps/substep_min)\n",
                          s->steps_cut, s->control.cuts, (double)s->control.smallest));
  if (s->pairs->n)
    PetscCall(PetscPrintf(
        s->comm,
        "  contacts: %" PetscInt_FMT " step(s) beyond the end-of-step check (worst cone violation %.3g, "
        "-contact_check_cone %g; worst natural-map error %.3g m, -contact_check_complementarity %g), "
        "%" PetscInt_FMT " step(s) with points inside another body, %" PetscInt_FMT " step(s) with crossings\n",
        s->checks.beyond, (double)s->checks.cone, (double)s->pairs->check_cone, (double)s->checks.complementarity,
        (double)s->pairs->check_complementarity, s->checks.intersecting, s->checks.crossed));
  PetscCall(PetscPrintf(s->comm, "  output: %s (open the .xmf beside it in ParaView)\n", s->output_file));
  PetscFunctionReturn(0);
}

/* What the end of the last step found wrong, for its progress line ("" when nothing): the points
   inside another body, the contacts beyond the end-of-step check (-contact_check_*) */
static void StepWarning(FCScene s, char buf[], size_t len)
{
  const FCContactMeasures *m = &s->measures;
  size_t                   n = 0;

  buf[0] = 0;
  if (!s->pairs->n) return;
  if (m->intersections)
    n += (size_t)snprintf(buf + n, len - n,
                          "  WARNING: %" PetscInt_FMT " point(s) inside another body (%" PetscInt_FMT
                          " step(s) so far; /steps/intersections)",
                          m->intersections, s->checks.intersecting);
  if (m->crossings && n < len)
    n += (size_t)snprintf(buf + n, len - n,
                          "  WARNING: %" PetscInt_FMT " point(s) or edge(s) went through another body's surface, the "
                          "deepest %.3g m (%" PetscInt_FMT " step(s) so far; /steps/crossings)",
                          m->crossings, (double)m->crossing_depth, s->checks.crossed);
  if (m->beyond && n < len)
    (void)snprintf(buf + n, len - n,
                   "  WARNING: %" PetscInt_FMT " of %" PetscInt_FMT
                   " contact(s) beyond the end-of-step check: cone violation %.3g (-contact_check_cone %g), "
                   "natural-map error %.3g m (-contact_check_complementarity %g) (%" PetscInt_FMT
                   " step(s) so far; /steps/contacts_beyond_check)",
                   m->beyond, s->set.n, (double)m->cone_violation, (double)s->pairs->check_cone,
                   (double)m->max_complementarity, (double)s->pairs->check_complementarity, s->checks.beyond);
}

/* Runs the remaining steps. If a step fails, or SIGINT/SIGTERM arrives, the output file is
   closed cleanly first, so that every completed step stays readable, and the run stops with a
   line saying at which step and why. */
static PetscErrorCode SceneRun(FCScene s)
{
  PetscFunctionBegin;
  PetscCall(FCSceneSetUp(s));
  PetscCall(FCSignalsInstall());
  PetscCall(FCProgressStart(&s->progress, s->quiet));
  while (s->step < s->nsteps) {
    PetscInt       done = s->step;
    PetscErrorCode ierr = FCSceneStep(s);
    int            sig;
    if (ierr == PETSC_ERR_FILE_WRITE) { /* the output failed (on every rank alike): the file is closed */
      (void)FCOutputDestroy(&s->output);
      (void)PetscPrintf(s->comm,
                        "fecontact: the output of step %" PetscInt_FMT
                        " could not be written; %s holds the steps up to "
                        "%" PetscInt_FMT " (its last complete output step: frames, step rows and restart state; "
                        "-restart from it continues the run)\n",
                        s->step, s->output_file, s->written);
      return ierr;
    }
    if (ierr) {
      (void)FCOutputDestroy(&s->output);
      (void)PetscPrintf(s->comm,
                        "fecontact: step %" PetscInt_FMT " (t = %g s) failed; %s holds the %" PetscInt_FMT
                        " completed steps\n",
                        done + 1, (double)(s->t0 + (done + 1 - s->step0) * s->h), s->output_file, done);
      return ierr;
    }
    {
      char warning[512];
      StepWarning(s, warning, sizeof(warning));
      PetscCall(FCProgressUpdate(&s->progress, s->comm, s->step, s->nsteps, s->t, warning));
    }
    if (s->pairs->fail_on_intersection && (s->measures.intersections || s->measures.crossings)) {
      if (s->step % s->every && s->step < s->nsteps) PetscCall(WriteOutputStepOrClose(s)); /* its frame, then close */
      PetscCall(FCOutputDestroy(&s->output));
      SETERRQ(s->comm, PETSC_ERR_NOT_CONVERGED,
              "step %" PetscInt_FMT " (t = %g s) ends with %" PetscInt_FMT
              " point(s) deeper than -contact_intersection_depth %g inside another body and %" PetscInt_FMT
              " point(s) or edge(s) that went through another body's surface (the deepest %g m), and "
              "-contact_fail_on_intersection is set; %s is closed and holds the %" PetscInt_FMT " completed steps",
              s->step, (double)s->t, s->measures.intersections, (double)s->pairs->intersection_depth,
              s->measures.crossings, (double)s->measures.crossing_depth, s->output_file, s->step);
    }
    PetscCall(FCSignalsPending(s->comm, &sig));
    if (sig && s->step < s->nsteps) { /* the last step's frame and restart state, then close */
      if (s->step % s->every) PetscCall(WriteOutputStepOrClose(s));
      PetscCall(FCOutputDestroy(&s->output));
      SETERRQ(s->comm, PETSC_ERR_SIG,
              "interrupted by %s after step %" PetscInt_FMT " (t = %g s); %s is closed and holds the %" PetscInt_FMT
              " completed steps",
              sig == SIGINT ? "SIGINT" : "SIGTERM", s->step, (double)s->t, s->output_file, s->step);
    }
  }
  PetscCall(FCSceneFinish(s));
  PetscFunctionReturn(0);
}

/* collective failure: an error on one rank is raised on every rank (FCErrorAgree) */
PetscErrorCode FCSceneRun(FCScene s)
{
  PetscFunctionBegin;
  FCValidPointer(s, 1);
  PetscCall(FCErrorAgree(s->comm, SceneRun(s)));
  PetscFunctionReturn(0);
}

static PetscErrorCode SceneFinish(FCScene s)
{
  PetscFunctionBegin;
  PetscCall(FCSceneSetUp(s));
  if (!s->quiet) PetscCall(PrintSummary(s, s->wall));
  PetscCall(FCMemoryReport(s->comm, s->memory, (PetscBool)!s->quiet, s->output));
  PetscFunctionReturn(0);
}

/* collective failure: an error on one rank is raised on every rank (FCErrorAgree) */
PetscErrorCode FCSceneFinish(FCScene s)
{
  PetscFunctionBegin;
  FCValidPointer(s, 1);
  PetscCall(FCErrorAgree(s->comm, SceneFinish(s)));
  PetscFunctionReturn(0);
}

PetscErrorCode FCSceneDestroy(FCScene *scene)
{
  PetscFunctionBegin;
  FCValidPointer(scene, 1);
  if (!*scene) PetscFunctionReturn(0);
  PetscCall(FCOutputDestroy(&(*scene)->output));
  PetscCall(FCSchemeDestroy(&(*scene)->scheme));
  PetscCall(FCContactSetDestroy(&(*scene)->set));
  PetscCall(FCContactSetDestroy(&(*scene)->previous));
  PetscCall(FCSettleDestroy(&(*scene)->settle));
  PetscCall(FCStepControlDestroy(&(*scene)->control));
  PetscCall(FCCollisionDestroy(&(*scene)->collision));
  for (PetscInt i = 0; i < (*scene)->nbodies; i++) PetscCall(FCBodyDestroy(&(*scene)->bodies[i]));
  PetscCall(PetscFree(*scene));
  PetscCall(FCInputsReset());
  PetscFunctionReturn(0);
}

PetscErrorCode FCSceneGetTime(FCScene s, PetscReal *t, PetscInt *step)
{
  PetscFunctionBegin;
  FCValidPointer(s, 1);
  if (t) *t = s->t;
  if (step) *step = s->step;
  PetscFunctionReturn(0);
}

PetscErrorCode FCSceneGetTimeStep(FCScene s, PetscReal *h, PetscInt *nsteps)
{
  PetscFunctionBegin;
  FCValidPointer(s, 1);
  if (h) *h = s->h;
  if (nsteps) *nsteps = s->nsteps;
  PetscFunctionReturn(0);
}

PetscErrorCode FCSceneGetNumBodies(FCScene s, PetscInt *n)
{
  PetscFunctionBegin;
  FCValidPointer(s, 1);
  FCValidPointer(n, 2);
  *n = s->nbodies;
  PetscFunctionReturn(0);
}

PetscErrorCode FCSceneGetBodyByIndex(FCScene s, PetscInt i, FCBody *body)
{
  PetscFunctionBegin;
  FCValidPointer(s, 1);
  FCValidPointer(body, 3);
  PetscCheck(i >= 0 && i < s->nbodies, s->comm, PETSC_ERR_USER_INPUT,
             "Body index %" PetscInt_FMT " out of range: the scene has %" PetscInt_FMT " bodies", i, s->nbodies);
  *body = s->bodies[i];
  PetscFunctionReturn(0);
}

/* The contacts of the last step, as the output records them (src/io/records.c) */
PetscErrorCode FCSceneGetContacts(FCScene s, PetscInt *n, FCContactInfo info[])
{
  PetscFunctionBegin;
  FCValidPointer(s, 1);
  FCValidPointer(n, 2);
  *n = s->pairs && s->pairs->n ? s->set.n : 0;
  if (!info) PetscFunctionReturn(0);
  for (PetscInt k = 0; k < *n; k++) {
    const FCContact *c = &s->set.c[k];
    info[k].body[0]    = c->body[0];
    info[k].body[1]    = c->body[1];
    info[k].gap        = c->gap0;
    info[k].gap_end    = c->gap_end;
    info[k].state      = c->state;
    for (int i = 0; i < 3; i++) {
      info[k].point[i]  = c->p0[0][i];
      info[k].normal[i] = c->n[i];
      info[k].force[i]  = c->force[i];
    }
    FCContactForceWorld(c, info[k].force_world);
  }
  PetscFunctionReturn(0);
}
