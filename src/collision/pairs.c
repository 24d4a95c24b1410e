/* FCCollision: the contact pairs of a scene (-contact_pairs, -contact_mu) and the options of their
   detection (-contact_*), read here, each described by its help string and in docs/options.md;
   then, per step, the detection of the contacts (FCCollisionDetect, collision.c), their gaps at the
   end of the step (FCCollisionEndGaps) and the points left inside another body
   (FCCollisionCountIntersections, intersection.c). */
#include "collisionimpl.h"

struct _p_FCCollision {
  MPI_Comm        comm;
  PetscInt        nbodies;
  FCBody         *bodies; /* the scene's, borrowed */
  FCContactPairs  pairs;
  FCCrossingAudit audit;
};

PetscErrorCode FCCollisionCreate(MPI_Comm comm, PetscInt nbodies, FCBody bodies[], FCCollision *collision)
{
  FCCollision c;

  PetscFunctionBegin;
  PetscCall(PetscNew(&c));
  c->comm    = comm;
  c->nbodies = nbodies;
  c->bodies  = bodies;
  PetscCall(PetscCalloc1(nbodies + 1, &c->pairs.topo));
  *collision = c;
  PetscFunctionReturn(0);
}

static PetscErrorCode BodyIndex(FCCollision s, const char name[], const char pair[], PetscInt *idx)
{
  PetscFunctionBegin;
  *idx = -1;
  for (PetscInt i = 0; i < s->nbodies; i++)
    if (!strcmp(FCBodyName(s->bodies[i]), name)) *idx = i;
  PetscCheck(*idx >= 0, s->comm, PETSC_ERR_USER_INPUT,
             "Contact pair '%s' in -contact_pairs names unknown body '%s' (bodies: -scene_bodies)", pair, name);
  PetscFunctionReturn(0);
}

/* The detection options (read only in a scene with contact pairs) */
static PetscErrorCode ReadDetection(FCCollision s, PetscOptionItems *PetscOptionsObject, PetscReal mu[], PetscInt *nmu,
                                    PetscBool *setmu, char detection[16])
{
  PetscFunctionBegin;
  PetscCall(FCOptionsReal(PetscOptionsObject, "-contact_distance", "Alarm distance", &s->pairs.distance, NULL));
  PetscCall(FCOptionsIntRange(PetscOptionsObject, "-contact_fe_passes",
                              "Detection passes between two meshed bodies (1 or 2)", 1, 2, &s->pairs.passes, NULL));
  PetscCall(FCOptionsReal(PetscOptionsObject, "-contact_fe_pass2_drop",
                          "With 2 passes: drop a second-pass contact whose vertex has a weight > w in a first-pass "
                          "contact of the pair (< 0: keep all)",
                          &s->pairs.pass2_drop, NULL));
  PetscCall(
      FCOptionsReal(PetscOptionsObject, "-contact_fe_pass2_dormant",
                    "With 2 passes: a second-pass contact whose vertex has a weight > w in a first-pass contact "
                    "is dormant, solved only where the solution without it leaves the vertex inside; a self pair: "
                    "a self-contact whose vertex has a weight > w in one whose vertex comes first (< 0: off)",
                    &s->pairs.pass2_dormant, NULL));
  PetscCall(FCOptionsReal(PetscOptionsObject, "-contact_dormant_depth",
                          "Depth inside the other body at which a dormant contact wakes (m)", &s->pairs.dormant_depth,
                          NULL));
  PetscCall(FCOptionsBool(PetscOptionsObject, "-contact_facing",
                          "A vertex lands only on triangles that face its own surface", &s->pairs.facing, NULL));
  PetscCall(FCOptionsBool(PetscOptionsObject, "-contact_facing_face",
                          "An FE vertex near an edge of a bounded shape, over the shape's face that faces it, is a "
                          "contact against that face's plane",
                          &s->pairs.facing_face, NULL));
  PetscCall(FCOptionsRealList(PetscOptionsObject, "-contact_mu", "Friction coefficient: one value, or one per pair",
                              FC_MAX_BODIES, mu, nmu, setmu));
  PetscCall(PetscOptionsString("-contact_detection", "Contact detection: continuous or discrete", NULL, detection,
                               detection, 16, NULL));
  PetscCall(FCOptionsBool(PetscOptionsObject, "-contact_edge_edge", "Edge-edge contacts between two meshed bodies",
                          &s->pairs.edges, NULL));
  PetscCall(FCOptionsReal(PetscOptionsObject, "-contact_edge_angle",
                          "Edge-edge contacts: the edges whose two triangles turn by more than this angle (degrees; 0: "
                          "every edge)",
                          &s->pairs.edge_angle, NULL));
  PetscCall(FCOptionsInt(PetscOptionsObject, "-contact_self_ring",
                         "Self-contact (a pair a:a): a vertex leaves out the triangles that touch the surface vertices "
                         "fewer than this many edges from it",
                         &s->pairs.self_ring, NULL));
  PetscCall(FCOptionsBool(PetscOptionsObject, "-contact_shape_points",
                          "A bounded shape's points against the triangles of an FE body too", &s->pairs.shape_points,
                          NULL));
  {
    const char *kinds[] = {"picture", "exact"};
    PetscInt    kind    = 1;
    PetscCall(FCOptionsEList(PetscOptionsObject, "-contact_rounded_surface",
                             "A sphere or a capsule against an FE surface: its picture's points or the exact nearest",
                             kinds, 2, &kind, NULL));
    s->pairs.rounded_exact = kind == 1 ? PETSC_TRUE : PETSC_FALSE;
  }
  PetscCall(FCOptionsReal(PetscOptionsObject, "-contact_separation_speed",
                          "Largest speed at which bodies that start inside each other are pushed apart (m/s)",
                          &s->pairs.separation_speed, NULL));
  PetscCall(FCOptionsReal(PetscOptionsObject, "-contact_intersection_depth",
                          "Depth inside another body that counts as an intersection (m)", &s->pairs.intersection_depth,
                          NULL));
  PetscCall(FCOptionsBool(PetscOptionsObject, "-contact_fail_on_intersection",
                          "Stop the run at the first intersection or kept crossing", &s->pairs.fail_on_intersection,
                          NULL));
  {
    const char *modes[] = {"off", "count", "redo"};
    PetscCall(FCOptionsEList(PetscOptionsObject, "-contact_crossings",
                             "What went through another body's surface over a step's motion: count it, redo the step "
                             "smaller (step control), or no audit",
                             modes, 3, &s->pairs.crossings, NULL));
  }
  PetscCall(FCOptionsIntRange(PetscOptionsObject, "-contact_crossings_cuts",
                              "With -contact_crossings redo: how many times a step with crossings is halved before it "
                              "is kept with them counted",
                              0, 30, &s->pairs.crossing_cuts, NULL));
  /* the end-of-step check (src/contact/measures.c): a step whose contacts miss these on the real end-of-step
     geometry gets a warning on its progress line and is counted in the summary */
  PetscCall(FCOptionsReal(PetscOptionsObject, "-contact_check_cone",
                          "End-of-step check: a contact's force outside its friction cone by more than this fraction "
                          "of the step's largest contact force is reported",
                          &s->pairs.check_cone, NULL));
  s->pairs.check_complementarity = 0.01 * s->pairs.distance;
  PetscCall(FCOptionsReal(PetscOptionsObject, "-contact_check_complementarity",
                          "End-of-step check: a contact whose natural-map error is above this length is reported (m; "
                          "default 1/100 of -contact_distance)",
                          &s->pairs.check_complementarity, NULL));
  PetscFunctionReturn(0);
}

/* Their ranges, and the friction: one value for every pair or one per pair (default 0) */
static PetscErrorCode CheckDetection(FCCollision s, PetscInt np, PetscReal mu[], PetscInt *nmu, PetscBool setmu,
                                     const char detection[])
{
  PetscFunctionBegin;
  PetscCheck(!strcmp(detection, "continuous") || !strcmp(detection, "discrete"), s->comm, PETSC_ERR_USER_INPUT,
             "Option -contact_detection must be continuous or discrete, got '%s'", detection);
  s->pairs.continuous = strcmp(detection, "continuous") ? PETSC_FALSE : PETSC_TRUE;
  PetscCheck(s->pairs.separation_speed > 0.0, s->comm, PETSC_ERR_USER_INPUT,
             "Option -contact_separation_speed must be > 0, got %g", (double)s->pairs.separation_speed);
  PetscCheck(s->pairs.intersection_depth >= 0.0, s->comm, PETSC_ERR_USER_INPUT,
             "Option -contact_intersection_depth must be >= 0, got %g", (double)s->pairs.intersection_depth);
  if (!setmu) {
    *nmu  = 1;
    mu[0] = 0.0;
  }
  PetscCheck(*nmu == 1 || *nmu == np, s->comm, PETSC_ERR_USER_INPUT,
             "Option -contact_mu needs one value or one per pair (%" PetscInt_FMT " pairs), got %" PetscInt_FMT, np,
             *nmu);
  for (PetscInt i = 0; i < *nmu; i++)
    PetscCheck(mu[i] >= 0.0 && PetscIsNormalReal(mu[i] + 1.0), s->comm, PETSC_ERR_USER_INPUT,
               "Option -contact_mu: entry %" PetscInt_FMT " must be a finite number >= 0, got %g", i, (double)mu[i]);
  PetscCheck(s->pairs.edge_angle >= 0.0 && s->pairs.edge_angle < 180.0, s->comm, PETSC_ERR_USER_INPUT,
             "Option -contact_edge_angle must be in [0, 180) degrees, got %g", (double)s->pairs.edge_angle);
  PetscCheck(s->pairs.self_ring >= 1, s->comm, PETSC_ERR_USER_INPUT,
             "Option -contact_self_ring must be >= 1 (1: a vertex's own triangles), got %" PetscInt_FMT,
             s->pairs.self_ring);
  PetscCheck(s->pairs.passes == 1 || s->pairs.passes == 2, s->comm, PETSC_ERR_USER_INPUT,
             "Option -contact_fe_passes must be 1 or 2, got %" PetscInt_FMT, s->pairs.passes);
  PetscCheck(s->pairs.pass2_drop < 1.0 && PetscIsNormalReal(s->pairs.pass2_drop + 2.0), s->comm, PETSC_ERR_USER_INPUT,
             "Option -contact_fe_pass2_drop must be a finite number < 1 (a barycentric weight; < 0 keeps every "
             "contact), got %g",
             (double)s->pairs.pass2_drop);
  PetscCheck(s->pairs.pass2_dormant < 1.0 && PetscIsNormalReal(s->pairs.pass2_dormant + 2.0), s->comm,
             PETSC_ERR_USER_INPUT,
             "Option -contact_fe_pass2_dormant must be a finite number < 1 (a barycentric weight; < 0: none dormant), "
             "got %g",
             (double)s->pairs.pass2_dormant);
  PetscCheck(s->pairs.dormant_depth >= 0.0 && PetscIsNormalReal(s->pairs.dormant_depth + 1.0), s->comm,
             PETSC_ERR_USER_INPUT, "Option -contact_dormant_depth must be a finite length >= 0, got %g",
             (double)s->pairs.dormant_depth);
  PetscCheck(s->pairs.distance >= 0.0, s->comm, PETSC_ERR_USER_INPUT, "Option -contact_distance must be >= 0, got %g",
             (double)s->pairs.distance);
  PetscCheck(s->pairs.check_cone >= 0.0 && PetscIsNormalReal(s->pairs.check_cone + 1.0), s->comm, PETSC_ERR_USER_INPUT,
             "Option -contact_check_cone must be a finite number >= 0, got %g", (double)s->pairs.check_cone);
  PetscCheck(s->pairs.check_complementarity >= 0.0 && PetscIsNormalReal(s->pairs.check_complementarity + 1.0), s->comm,
             PETSC_ERR_USER_INPUT, "Option -contact_check_complementarity must be a finite length >= 0, got %g",
             (double)s->pairs.check_complementarity);
  PetscFunctionReturn(0);
}

/* The pairs "a:b" of -contact_pairs: two bodies of the scene, not both kinematic; a:a, self-contact, an FE body */
static PetscErrorCode SetPairs(FCCollision s, PetscInt np, char *pairs[], const PetscReal mu[], PetscInt nmu)
{
  PetscFunctionBegin;
  s->pairs.n = np;
  PetscCall(PetscMalloc3(np, &s->pairs.body, np, &s->pairs.mu, np, &s->pairs.self_inside));
  for (PetscInt p = 0; p < np; p++) {
    char *colon = strchr(pairs[p], ':');
    PetscCheck(colon && colon != pairs[p] && colon[1], s->comm, PETSC_ERR_USER_INPUT,
               "Contact pair '%s' in -contact_pairs must read body1:body2", pairs[p]);
    *colon = 0;
    PetscCall(BodyIndex(s, pairs[p], pairs[p], &s->pairs.body[p][0]));
    PetscCall(BodyIndex(s, colon + 1, pairs[p], &s->pairs.body[p][1]));
    PetscCheck(s->pairs.body[p][0] != s->pairs.body[p][1] || FCBodyIsDeformable(s->bodies[s->pairs.body[p][0]]),
               s->comm, PETSC_ERR_USER_INPUT,
               "Contact pair '%s:%s' pairs body '%s' with itself: self-contact is for FE bodies (a rigid or kinematic "
               "body cannot touch itself)",
               pairs[p], colon + 1, pairs[p]);
    PetscCheck(
        !(FCBodyIsPrescribed(s->bodies[s->pairs.body[p][0]]) && FCBodyIsPrescribed(s->bodies[s->pairs.body[p][1]])),
        s->comm, PETSC_ERR_USER_INPUT, "Contact pair '%s:%s' joins two kinematic bodies: nothing can respond", pairs[p],
        colon + 1);
    for (PetscInt q = 0; q < p; q++) /* a pair given twice would make every contact of it twice */
      PetscCheck(!((s->pairs.body[q][0] == s->pairs.body[p][0] && s->pairs.body[q][1] == s->pairs.body[p][1]) ||
                   (s->pairs.body[q][0] == s->pairs.body[p][1] && s->pairs.body[q][1] == s->pairs.body[p][0])),
                 s->comm, PETSC_ERR_USER_INPUT,
                 "Option -contact_pairs: the pair '%s:%s' is given twice (pairs %" PetscInt_FMT " and %" PetscInt_FMT
                 ")",
                 pairs[p], colon + 1, q + 1, p + 1);
    s->pairs.mu[p]          = mu[nmu == 1 ? 0 : p];
    s->pairs.self_inside[p] = PETSC_TRUE;
  }
  for (PetscInt p = 0; p < np; p++) PetscCall(PetscFree(pairs[p]));
  PetscFunctionReturn(0);
}

PetscErrorCode FCCollisionSetFromOptions(FCCollision s)
{
  char     *pairs[FC_MAX_BODIES];
  PetscInt  np = FC_MAX_BODIES, nmu = FC_MAX_BODIES;
  PetscReal mu[FC_MAX_BODIES];
  PetscBool set, setmu = PETSC_FALSE;
  char      detection[16] = "continuous";

  PetscFunctionBegin;
  s->pairs.distance           = 0.01;
  s->pairs.passes             = 2;
  s->pairs.pass2_drop         = -1.0;
  s->pairs.pass2_dormant      = 0.01;
  s->pairs.dormant_depth      = 1e-5;
  s->pairs.facing             = PETSC_TRUE;
  s->pairs.facing_face        = PETSC_FALSE;
  s->pairs.intersection_depth = 1e-4;
  s->pairs.edges              = PETSC_TRUE;
  s->pairs.edge_angle         = 30.0;
  s->pairs.self_ring          = 2;
  s->pairs.shape_points       = PETSC_TRUE;
  s->pairs.separation_speed   = 1.0;
  s->pairs.check_cone         = 0.01;
  s->pairs.crossings          = FC_CROSSINGS_COUNT;
  s->pairs.crossing_cuts      = 2;
  PetscOptionsBegin(s->comm, NULL, "Contact options", "FCScene");
  PetscCall(
      PetscOptionsStringArray("-contact_pairs", "Pairs of bodies that may touch: a:b,c:d", NULL, pairs, &np, &set));
  if (set && np > 0) PetscCall(ReadDetection(s, PetscOptionsObject, mu, &nmu, &setmu, detection));
  PetscOptionsEnd();
  if (!set || np == 0) PetscFunctionReturn(0);
  PetscCall(CheckDetection(s, np, mu, &nmu, setmu, detection));
  PetscCall(SetPairs(s, np, pairs, mu, nmu));
  PetscFunctionReturn(0);
}

const FCContactPairs *FCCollisionGetPairs(FCCollision c)
{
  return &c->pairs;
}

PetscErrorCode FCCollisionDetect(FCCollision c, PetscBool continuous, FCContactSet *set)
{
  FCContactPairs pairs = c->pairs;

  PetscFunctionBegin;
  pairs.continuous = (PetscBool)(pairs.continuous && continuous);
  PetscCall(FCCollisionDetectPairs(c->comm, c->nbodies, c->bodies, &pairs, set));
  PetscFunctionReturn(0);
}

PetscErrorCode FCCollisionEndGaps(FCCollision c, FCContactSet *set)
{
  PetscFunctionBegin;
  PetscCall(FCCollisionEndGapsOf(c->comm, c->nbodies, c->bodies, set));
  PetscFunctionReturn(0);
}

PetscErrorCode FCCollisionCountIntersections(FCCollision c, PetscInt *count)
{
  PetscFunctionBegin;
  PetscCall(FCCollisionCountPairIntersections(c->comm, c->nbodies, c->bodies, &c->pairs, count));
  PetscFunctionReturn(0);
}

PetscErrorCode FCCollisionAuditStart(FCCollision c)
{
  PetscFunctionBegin;
  if (c->pairs.crossings == FC_CROSSINGS_OFF || !c->pairs.n) PetscFunctionReturn(0);
  if (!c->audit) PetscCall(FCCrossingAuditCreate(c->nbodies, &c->audit));
  PetscCall(FCCrossingAuditStart(c->audit, c->comm, c->bodies, &c->pairs));
  PetscFunctionReturn(0);
}

PetscErrorCode FCCollisionCountCrossings(FCCollision c, PetscInt *count, PetscReal *deepest)
{
  PetscFunctionBegin;
  *count   = 0;
  *deepest = 0.0;
  if (c->pairs.crossings == FC_CROSSINGS_OFF || !c->audit) PetscFunctionReturn(0);
  PetscCall(FCCrossingAuditCount(c->audit, c->comm, c->bodies, &c->pairs, count, deepest));
  PetscFunctionReturn(0);
}

PetscErrorCode FCCollisionDestroy(FCCollision *c)
{
  PetscFunctionBegin;
  if (!*c) PetscFunctionReturn(0);
  PetscCall(FCCrossingAuditDestroy(&(*c)->audit));
  PetscCall(PetscFree3((*c)->pairs.body, (*c)->pairs.mu, (*c)->pairs.self_inside));
  for (PetscInt b = 0; b < (*c)->nbodies; b++) PetscCall(FCSurfaceTopologyDestroy(&(*c)->pairs.topo[b]));
  PetscCall(PetscFree((*c)->pairs.topo));
  PetscCall(PetscFree(*c));
  PetscFunctionReturn(0);
}
