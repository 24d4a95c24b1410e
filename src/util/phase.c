/* Phases of a time step: one PetscLogEvent each (so -log_view shows where time goes) and a
   wall-clock accumulator per phase that the scene writes to /steps/timing/<phase>. */
#include "../fcimpl.h"

const char *const FCPhaseNames[] = {
    "assembly",  "factorization",    "free_motion", "collision", "compliance", "contact_solver", "correction",
    "rebuild_w", "proximity_update", "integration", "output",    "FCPhase",    "FC_PHASE_",      NULL};

static PetscLogEvent  events[FC_PHASE_NUM];
static PetscLogDouble started[FC_PHASE_NUM], total[FC_PHASE_NUM];
static PetscBool      registered = PETSC_FALSE;
PetscLogEvent         FC_EVENT_NEWTON, FC_EVENT_COMPLIANCE_SUM, FC_EVENT_CONGRUENCE_WK;

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
  PetscFunctionBegin;
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
  PetscCall(PetscLogEventEnd(events[p], 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

PetscErrorCode FCPhaseGetTimes(PetscReal t[FC_PHASE_NUM])
{
  PetscFunctionBegin;
  for (int p = 0; p < FC_PHASE_NUM; p++) t[p] = (PetscReal)total[p];
  PetscFunctionReturn(0);
}

PetscErrorCode FCPhaseResetTimes(void)
{
  PetscFunctionBegin;
  for (int p = 0; p < FC_PHASE_NUM; p++) total[p] = 0.0;
  PetscFunctionReturn(0);
}
