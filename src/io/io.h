/* Output (src/io/): one HDF5 file per run, an XDMF file beside it for ParaView */
#pragma once

#include "../body/body.h"

typedef struct _p_FCOutput *FCOutput;
PETSC_INTERN PetscErrorCode FCOutputCreate(MPI_Comm, const char filename[], FCOutput *);
struct _FCContactSetView; /* defined with the schemes below */
PETSC_INTERN PetscErrorCode FCOutputWriteHeader(FCOutput, PetscInt nbodies, FCBody[], PetscReal h, PetscInt nsteps,
                                                PetscInt every, PetscBool contacts);
/* The contacts of the step just recorded (only in scenes with contact pairs) */
PETSC_INTERN PetscErrorCode FCOutputRecordContacts(FCOutput, const struct _FCContactSetView *);
/* One row per requested step: its time, phases, wall time, sub-steps (step control) and their smallest h */
PETSC_INTERN PetscErrorCode FCOutputRecordStep(FCOutput, PetscInt step, PetscReal t,
                                               const PetscReal timing[FC_PHASE_NUM], PetscReal wall, PetscInt substeps,
                                               PetscReal hsub, PetscInt nbodies, FCBody[]);
PETSC_INTERN PetscErrorCode FCOutputWriteFrame(FCOutput, PetscInt step, PetscReal t, PetscInt nbodies, FCBody[]);
PETSC_INTERN PetscErrorCode FCOutputFlush(FCOutput);
/* The restart state of the end of `step` (/restart, written before the frame's flush); the
   restart format is written and read in src/io/restart.c */
PETSC_INTERN PetscErrorCode FCOutputWriteRestart(FCOutput, PetscInt step, PetscReal t, const PetscReal control[3],
                                                 PetscInt nbodies, FCBody[], const FCContactSet *previous);
/* Reads the newest complete restart state of a file into the bodies, previous contacts, step, t */
/* src/io/restartcheck.c: the options that define the scene are those of the run that wrote the file */
PETSC_INTERN PetscErrorCode FCRestartCheckScene(MPI_Comm, const char file[], PetscInt nbodies, FCBody[]);
PETSC_INTERN PetscErrorCode FCRestartLoad(MPI_Comm, const char file[], PetscInt nbodies, FCBody[],
                                          FCContactSet *previous, PetscInt *step, PetscReal *t, PetscReal control[3]);
/* /memory, /memory_phases (name): a row of ncols values per rank (this rank's row), named */
PETSC_INTERN PetscErrorCode FCOutputWriteMemory(FCOutput, const char name[], const char units[], PetscInt ncols,
                                                const char *const names[], const PetscReal row[]);
PETSC_INTERN PetscErrorCode FCOutputDestroy(FCOutput *);
PETSC_INTERN PetscErrorCode FCXdmfWrite(FCOutput);
/* -output_fields: the list of field names (FCVisualFieldNames, or "none") as a bit mask, 1 << field;
   an unknown name is an error naming the option */
PETSC_INTERN PetscErrorCode FCOutputFieldsParse(MPI_Comm, const char list[], PetscInt *mask);
PETSC_INTERN PetscErrorCode FCOutputSetFields(FCOutput, PetscInt mask); /* before FCOutputWriteHeader */
/* After a write that failed inside HDF5 the output file cannot be closed: the program must then
   leave without HDF5's clean-up in MPI_Finalize (src/main.c; src/io/output.c, FCOutputDestroy) */
PETSC_INTERN PetscBool FCOutputFileLeftOpen(void);
