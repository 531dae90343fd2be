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
/* the suffix of an HDF5 result's temporary file, ".<8 hex digits>.part" (SgFileBeginHDF5), for its length */
#define SG_HDF5_PART_SUFFIX ".XXXXXXXX.part"
/* how SgFileFinish ends a file after closing it: remove its .part, rename it, or keep it for a later SgFileCommit */
typedef enum { SG_FILE_ABANDON,
               SG_FILE_COMMIT,
               SG_FILE_KEEP } SgFileEnd;
PetscErrorCode SgFileFinish(MPI_Comm, const char[], FILE **, SgFileEnd);
void           SgFileResolve(const char[], const char **, PetscBool *);
PetscErrorCode SgFileRegister(MPI_Comm, const char[], const char[], PetscBool, PetscBool);
void           SgFileDirectory(const char[], char[PETSC_MAX_PATH_LEN]);
PetscErrorCode SgOutputWriteXDMF(SgElasticity, const char[], const char[], PetscInt, const PetscInt[], const PetscReal[], PetscInt, Vec[], PetscInt, Vec[], PetscReal);

/* What the files of the checkpoint share (checkpoint.c, checkpoint_write.c, checkpoint_read.c, fingerprint.c, history.c) */
PetscErrorCode SgCheckpointOwnedVertices(SgElasticity, PetscInt *);
#define SG_HISTORY_NREALS 22 /* numbers per history row in the file */
void SgHistoryRowToReals(const SgHistoryRow *, PetscReal[]);
void SgHistoryRowFromReals(const PetscReal[], SgHistoryRow *);
/* the problem's fingerprint: numbers (E, nu, load and Dirichlet scales, gap sum: SgFingerprintNames, and the options
   that set them) and moments (weighted sums of the data, in groups); their comparison, the first that differs */
#define SG_FINGERPRINT_NUMBERS     6
#define SG_FINGERPRINT_MOMENTS_MAX (3 * 6 * 3 + 2 + 2 * 6)
extern const char *const SgFingerprintNames[SG_FINGERPRINT_NUMBERS], *const SgFingerprintOptions[SG_FINGERPRINT_NUMBERS], *const SgFingerprintGroups[];
PetscErrorCode SgFingerprintNumbers(SgElasticity, SgContact, PetscReal[SG_FINGERPRINT_NUMBERS]);
PetscErrorCode SgFingerprintMoments(SgElasticity, SgContact, PetscInt *, PetscReal[SG_FINGERPRINT_MOMENTS_MAX], PetscReal[SG_FINGERPRINT_MOMENTS_MAX]);
void           SgFingerprintCompare(PetscInt, PetscInt, const PetscReal[], const PetscReal[], const PetscReal[], const PetscReal[], PetscInt *, char[], size_t, PetscReal *, PetscReal *);
PetscErrorCode SgFingerprintMaterials(SgElasticity, PetscInt *, PetscReal[3 * SG_MAX_IDS]); /* several materials: ids, E, nu (3 n numbers; n = 0: one) */
PetscErrorCode SgFingerprintMaterialText(PetscInt, const PetscReal[], PetscBool, PetscReal, PetscReal, char[], size_t);
