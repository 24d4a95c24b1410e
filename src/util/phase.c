/* Phases of a time step: one PetscLogEvent each (so -log_view shows where time goes), a
   wall-clock accumulator per phase that the scene writes to /steps/timing/<phase>, and the growth
   of the process' peak RSS (getrusage's high-water mark) while each phase runs, so that the run
   can say which phase set its peak (/memory_phases). A phase begun inside another takes the growth
   while it runs; the outer one the rest of its time. */
#include "../fcimpl.h"
#include <sys/resource.h>

const char *const FCPhaseNames[] = {
    "assembly",  "factorization",    "free_motion", "collision", "compliance", "contact_solver", "correction",
    "rebuild_w", "proximity_update", "integration", "output",    "FCPhase",    "FC_PHASE_",      NULL};

static PetscLogEvent  events[FC_PHASE_NUM];
static PetscLogDouble started[FC_PHASE_NUM], total[FC_PHASE_NUM];
static PetscBool      registered = PETSC_FALSE;
static PetscReal      grown[FC_PHASE_NUM], mark; /* peak RSS growth per phase; the high-water mark at the last change */
static int            stack[16], depth;          /* the phases running, innermost last */

static PetscReal HighWater(void)
{
  struct rusage ru;
  return getrusage(RUSAGE_SELF, &ru) ? mark : 1024.0 * (PetscReal)ru.ru_maxrss; /* kB on Linux */
}
PetscLogEvent FC_EVENT_NEWTON, FC_EVENT_COMPLIANCE_SUM, FC_EVENT_CONGRUENCE_WK;

PETSC_INTERN PetscErrorCode FCPhaseRegisterEvents(PetscClassId classid)
{
  static const char *eventnames[] = {"FCAssembly", "FCFactorization", "FreeMotion", "Collision",       "BuildWH",
                                     "PGS",        "Correction",      "RebuildW",   "ProximityUpdate", "FCIntegration",
                                     "FCOutput"};

  PetscFunctionBegin;
  if (registered) PetscFunctionReturn(0);
  for (int p = 0; p < FC_PHASE_NUM; p++) PetscCall(PetscLogEventRegister(eventnames[p], classid, &events[p]));
  PetscCall(PetscLogEventRegister("NewtonIteration", classid, &FC_EVENT_NEWTON));
  PetscCall(PetscLogEventRegister("ComplianceSum", classid, &FC_EVENT_COMPLIANCE_SUM));
  PetscCall(PetscLogEventRegister("CongruenceWk", classid, &FC_EVENT_CONGRUENCE_WK));
  registered = PETSC_TRUE;
  PetscFunctionReturn(0);
}

PetscErrorCode FCPhaseBegin(FCPhase p)
{
  PetscReal hw = HighWater();

  PetscFunctionBegin;
  if (depth > 0) grown[stack[depth - 1]] += hw - mark;
  if (depth < (int)(sizeof(stack) / sizeof(stack[0]))) stack[depth++] = (int)p;
  mark = hw;
  PetscCall(PetscLogEventBegin(events[p], 0, 0, 0, 0));
  PetscCall(PetscTime(&started[p]));
  PetscFunctionReturn(0);
}

PetscErrorCode FCPhaseEnd(FCPhase p)
{
  PetscLogDouble now;

  PetscFunctionBegin;
  PetscCall(PetscTime(&now));
  total[p] += now - started[p];
  {
    PetscReal hw = HighWater();
    grown[p] += hw - mark;
    if (depth > 0 && stack[depth - 1] == (int)p) depth--;
    mark = hw;
  }
  PetscCall(PetscLogEventEnd(events[p], 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

PetscErrorCode FCPhaseGetMemoryGrowth(PetscReal g[FC_PHASE_NUM])
{
  PetscFunctionBegin;
  FCValidPointer(g, 1);
  for (int p = 0; p < FC_PHASE_NUM; p++) g[p] = grown[p];
  PetscFunctionReturn(0);
}

PetscErrorCode FCPhaseGetTimes(PetscReal t[FC_PHASE_NUM])
{
  PetscFunctionBegin;
  FCValidPointer(t, 1);
  for (int p = 0; p < FC_PHASE_NUM; p++) t[p] = (PetscReal)total[p];
  PetscFunctionReturn(0);
}

PetscErrorCode FCPhaseResetTimes(void)
{
  PetscFunctionBegin;
  for (int p = 0; p < FC_PHASE_NUM; p++) total[p] = 0.0;
  PetscFunctionReturn(0);
}
