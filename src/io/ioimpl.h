/* io/ioimpl.h: the summary, the history and what the files of results share; included by the files of src/io only */
#pragma once

#include "sg.h"


struct _n_SgSummary {
  PetscInt n, cap;
  char   **key, **val; /* values JSON-encoded */
};


struct _n_SgHistory {
  PetscInt      n, cap;
  SgHistoryRow *rows;
};

/* The files of a result (registry.c, file.c, hdf5.c, xdmf.c, output.c) */
/* how SgFileFinish ends a file after closing it: remove its .part, rename it, or keep it for a later SgFileCommit */
typedef enum { SG_FILE_ABANDON, SG_FILE_COMMIT, SG_FILE_KEEP } SgFileEnd;
PetscErrorCode SgFileFinish(MPI_Comm, const char[], FILE **, SgFileEnd);
void           SgFileResolve(const char[], const char **, PetscBool *);
PetscErrorCode SgFileRegister(MPI_Comm, const char[], const char[], PetscBool, PetscBool);
void           SgFileDirectory(const char[], char[PETSC_MAX_PATH_LEN]);
PetscErrorCode SgOutputWriteXDMF(SgElasticity, const char[], const char[], PetscInt, const PetscInt[], const PetscReal[], PetscInt, Vec[], PetscInt, Vec[], PetscReal);

/* What the files of the checkpoint share (checkpoint.c, checkpoint_write.c, checkpoint_read.c, fingerprint.c) */
PetscErrorCode SgCheckpointOwnedVertices(SgElasticity, PetscInt *);
PetscErrorCode SgCheckpointWriteProblem(SgCheckpointWriter, SgElasticity, SgContact);   /* the problem's fingerprint into the file */
PetscErrorCode SgCheckpointCheckProblem(SgCheckpointReader *, SgElasticity, SgContact); /* the file's against this run's; a refusal frees the reader */
