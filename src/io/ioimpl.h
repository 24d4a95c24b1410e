/* Private definitions of the output files of src/io/ (schema in docs/output.md):
     output.c   the file: creation, header (attributes, /frames, /bodies), frames, flush, destroy
     records.c  the per-step records: /steps (and per-body centroid, rotation, energy), /contacts
     restart.c  the restart format /restart/slot0|1: creating, writing and reading it
     h5util.c   HDF5 helpers shared by these
     fields.c   the fields of the frames (-output_fields): /bodies/<name>/<field>
     xdmf.c     the XDMF index of the frames and its per-frame views /xdmf/frame<k> */
#pragma once

#include "../fcimpl.h"
#include <hdf5.h>
#include <errno.h>

/* Every HDF5 call of the output goes through FCH5Check, and every failure is collective: the
   outcome of the call is reduced over the output file's communicator at once (FCH5Agree), so that
   all ranks leave the same call with the same error, PETSC_ERR_FILE_WRITE, whose message names the
   file and the cause (errno, else the innermost message of HDF5's error stack, of the first rank
   that failed); none is left waiting in the next collective call. Outside an output file
   (FCH5ContextSet not called) a failure is this rank's alone. */
#define FCH5Check(call, msg)                                                                                           \
  do {                                                                                                                 \
    int fc_ok_, fc_errno_;                                                                                             \
    errno     = 0;                                                                                                     \
    fc_ok_    = (call) >= 0;                                                                                           \
    fc_errno_ = errno;                                                                                                 \
    PetscCall(FCH5Agree(fc_ok_, fc_errno_, msg));                                                                      \
  } while (0)

/* The output file whose writes FCH5Check makes collective (one at a time in a process) */
PETSC_INTERN PetscErrorCode FCH5ContextSet(MPI_Comm, const char filename[]);
PETSC_INTERN PetscErrorCode FCH5ContextClear(void);
/* ok: this rank's outcome, err: its errno right after the call; collective in a context */
PETSC_INTERN PetscErrorCode FCH5Agree(int ok, int err, const char what[]);
/* The same for a failure outside HDF5 (disk space not reserved, the XDMF index): HDF5 holds
   nothing unwritten then, and the file can still be closed */
PETSC_INTERN PetscErrorCode FCH5AgreeClean(int ok, int err, const char what[]);
/* Whether a write of the current output file has failed (then nothing more is written to it), and
   whether it failed inside HDF5 (then the file cannot be closed: FCOutputDestroy) */
PETSC_INTERN PetscBool FCH5Failed(void);
PETSC_INTERN PetscBool FCH5FailedInside(void);

/* Disk space (reserve.c): `bytes` beyond HDF5's end of allocation of the open file h5 (-1: beyond
   the file's end), allocated as part of the file by rank 0 before HDF5 writes (collective;
   failure: FCH5AgreeClean); Release cuts the file back to its end of allocation after the close */
PETSC_INTERN PetscErrorCode FCH5Reserve(MPI_Comm, const char file[], hid_t h5, size_t bytes, const char what[]);
PETSC_INTERN PetscErrorCode FCH5Release(MPI_Comm, const char file[]);

/* HDF5 helpers (h5util.c) */
/* An extendible dataset of rows of shape rowdims[0..rank-2], chunked by `chunkrows` rows */
PETSC_INTERN PetscErrorCode FCH5CreateRows(hid_t loc, const char name[], hid_t type, int rank, const hsize_t rowdims[],
                                           hsize_t chunkrows, hid_t *dset);
/* Appends n rows (collective extend): rank 0 writes data, the others take part with nothing */
PETSC_INTERN PetscErrorCode FCH5AppendRows(PetscMPIInt rank, hid_t dset, hid_t memtype, hsize_t n, const void *data);
/* A fixed-size dataset (rows x cols, or a list of rows with cols 0) written by ranges: each rank
   its [start, start + n) rows */
PETSC_INTERN PetscErrorCode FCH5WriteDistributed(hid_t loc, const char name[], hid_t filetype, hid_t memtype,
                                                 hsize_t rows, hsize_t cols, hsize_t start, hsize_t n,
                                                 const void *data);
PETSC_INTERN PetscErrorCode FCH5AttrString(hid_t loc, const char name[], const char value[]);
PETSC_INTERN PetscErrorCode FCH5AttrReals(hid_t loc, const char name[], hsize_t n, const double v[]);
PETSC_INTERN PetscErrorCode FCH5AttrInt(hid_t loc, const char name[], long long v);

/* The restart state's writer (restart.c): creates /restart in an open output file, writes a state
   into the older of its two slots */
typedef struct _p_FCRestartWriter *FCRestartWriter;
PETSC_INTERN PetscErrorCode FCRestartWriterCreate(MPI_Comm, hid_t file, PetscInt nbodies, FCBody[], FCRestartWriter *);
PETSC_INTERN PetscErrorCode FCRestartWriterBegin(FCRestartWriter); /* the next slot's step := -1 */
/* control: the step control's state (src/scene/stepcontrol.c: h, the sub-step in use, its successes) */
PETSC_INTERN PetscErrorCode FCRestartWriterWrite(FCRestartWriter, PetscInt step, PetscReal t,
                                                 const PetscReal control[3], PetscInt nbodies, FCBody[],
                                                 const FCContactSet *previous);
PETSC_INTERN PetscErrorCode FCRestartWriterDestroy(FCRestartWriter *);

#define FC_MAX_REACTIONS 16
#define FC_SOLVER_COUNTS 3 /* /steps: factorizations, krylov_iterations, free_motion_iterations */
#define FC_BODY_ROW 12     /* per step and body: centroid 3, quaternion 4, energy 3, inverted elements, smallest J */
typedef struct {
  hid_t    group, centroid, rotation, energy, positions;
  hid_t    inverted[2]; /* FE bodies: /bodies/<name>/inverted/elements and min_volume_ratio (else -1) */
  PetscInt nreact;      /* constrained regions: /bodies/<name>/reactions/<region> */
  hid_t    react[FC_MAX_REACTIONS];
  double  *rreact; /* buffered rows (rank 0): 6 values per region */
} BodyOut;

/* Buffered rows of /contacts (one per contact) and of the contact columns of /steps (one per
   step); 8-byte fields only: each is written as a column by records.c */
typedef struct {
  long long bodies[2], state;
  double    point[3], normal[3], force[3], gap, gap_end;
  double    point_end[3], force_world[3], force_tangential;
} FCContactRecord;
typedef struct {
  long long         contacts, rows, sweeps, offset, newton, intersections, beyond, crossings;
  double            residual;
  FCContactMeasures m;
} FCStepRecord;

struct _p_FCOutput {
  MPI_Comm    comm;
  PetscMPIInt rank;
  char        filename[PETSC_MAX_PATH_LEN], xdmfname[PETSC_MAX_PATH_LEN];
  hid_t       file, time, step, energy, denergy, wall, timing[FC_PHASE_NUM], ftime, fstep;
  PetscInt    nbodies;
  FCBody     *bodies;
  BodyOut    *bo;
  /* rows buffered since the last flush (rank 0) */
  PetscInt nrows, maxrows;
  double  *rtime, *renergy, *rtiming, *rbody; /* rtiming: per row the phases, then the wall time; rbody: per row,
                                                per body FC_BODY_ROW values */
  PetscInt  *rstep;
  long long *rsolve; /* per row: factorizations, Krylov and Newton iterations of the step (all bodies) */
  PetscInt   lastsolve[FC_SOLVER_COUNTS]; /* the bodies' totals at the last row */
  hid_t      s_solve[FC_SOLVER_COUNTS];
  long long *rsub;  /* per row: the sub-steps of the step (step control; 1 when none failed) */
  double    *rhsub; /* per row: the smallest of them (s) */
  hid_t      s_sub, s_hsub;
  hid_t      s_inverted[2]; /* /steps/inverted_elements, min_volume_ratio: scenes with an FE body (else -1) */
  double     elast;         /* total energy of the last recorded step (initial energy before step 1) */
  PetscInt   nframes, xdmfwritten;
  hid_t      complete;         /* /complete: the last step, and the frames, that a flush has put on disk */
  long long  laststep;         /* the last step whose rows or frame have been written (flushed or not) */
  size_t     lastsize, growth; /* HDF5's end of allocation after the last output step, largest growth over one
                                  (the next reservation, reserve.c) */
  /* contacts (scenes with contact pairs only) */
  PetscBool contacts;
  hid_t     c_offset, c_bodies, c_point, c_normal, c_force, c_gap, c_gapend, c_state, c_pointend, c_fworld, c_ftan;
  hid_t     s_contacts, s_rows, s_sweeps, s_residual, s_maxpen, s_newton, s_violation, s_rmspen, s_compl, s_cone,
      s_intersections, s_beyond, s_maxcompl, s_crossings, s_crossdepth;
  long long        ctotal;             /* contacts recorded so far */
  long long        clast;              /* contacts of the last recorded step */
  PetscInt         nc, maxc, ns, maxs; /* buffered contact records and per-step rows */
  FCContactRecord *cbuf;
  FCStepRecord    *sbuf;
  double          *frametimes;
  PetscInt         maxframes;
  FCRestartWriter  restart;
  /* fields of the frames (fields.c): the -output_fields mask, per body the dataset of each field
     (-1: not written) */
  PetscInt fieldmask;
  hid_t (*fields)[FC_FIELD_NUM];
  /* the XDMF index (xdmf.c): per frame, its time and its step's contacts (the last xcount records) */
  PetscInt   xframes, xmax;
  double    *xtime;
  long long *xfirst, *xcount;
  hid_t      xvertex; /* /xdmf/vertex: 0, 1, 2, ... (the contact point sets' vertex cells) */
  long long  xnvertex;
};

/* Fields of the frames (fields.c): Create (with the header) makes a dataset per body and requested
   field the body has, Write appends the frame's row, Destroy closes them */
PETSC_INTERN PetscErrorCode FCOutputFieldsCreate(FCOutput);
PETSC_INTERN PetscErrorCode FCOutputFieldsWrite(FCOutput);
PETSC_INTERN PetscErrorCode FCOutputFieldsDestroy(FCOutput);
/* The XDMF index (xdmf.c): AddFrame (collective, after the frame's datasets are written) creates the
   frame's views /xdmf/frame<k> and remembers what FCXdmfWrite (rank 0) indexes */
PETSC_INTERN PetscErrorCode FCXdmfAddFrame(FCOutput, PetscReal t);
PETSC_INTERN PetscErrorCode FCXdmfDestroy(FCOutput);

/* The per-step records (records.c): the initial_energy attribute, /steps and /contacts are created
   by FCOutputRecordsCreate (in FCOutputWriteHeader, before /frames and /bodies); the per-body
   centroid, rotation and energy datasets belong to the header's /bodies. Flush writes the buffered
   rows; Destroy closes what Create opened. */
PETSC_INTERN PetscErrorCode FCOutputRecordsCreate(FCOutput, PetscInt nbodies, FCBody[], PetscBool contacts);
PETSC_INTERN PetscErrorCode FCOutputRecordsFlush(FCOutput);
PETSC_INTERN PetscErrorCode FCOutputRecordsDestroy(FCOutput);
