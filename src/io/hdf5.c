/* hdf5.c: an HDF5 result file written atomically; a failed write (a full disk) reported with its cause. */
#include "io/ioimpl.h"
#include <petscviewerhdf5.h>
#include <errno.h>
#include <sys/statvfs.h>
#include <unistd.h>

/* errno values a failed write sets (HDF5 leaves errno stale otherwise) */
static PetscBool WriteErrno(int e)
{
  return (PetscBool)(e == ENOSPC || e == EDQUOT || e == EFBIG || e == EROFS || e == EACCES || e == EIO);
}

/* HDF5 cannot always close a file whose write failed in the middle: PETSc's writers return on the error with their
   dataset and group open, and the close's flush fails again while the disk stays full, so the file stays open and
   HDF5's own clean-up at MPI_Finalize crashes (a checkpoint or fields file on a file system that fills during the
   write). A file system with less than this many bytes free is refused before HDF5 writes anything; a disk that fills
   during a larger write can still meet that failure. */
#define SG_HDF5_MIN_FREE (1024.0 * 1024.0)

static PetscBool SpaceBelow(const char path[], double bytes)
{
  struct statvfs sv;
  char           dir[PETSC_MAX_PATH_LEN];

  SgFileDirectory(path, dir);
  return (PetscBool)(!statvfs(dir, &sv) && (double)sv.f_bavail * (double)sv.f_frsize < bytes);
}

static PetscBool DiskFull(const char path[])
{
  return (PetscBool)!strcmp(SgFileErrorCause(0, path), "no space left on device");
}

/* A write of tmp (the .part of path) failed: the cause is judged while the disk is still full, then the file, which
   goes anyway, is emptied, so that HDF5 has the space to close it (a file left open in HDF5 crashes HDF5's clean-up
   at PetscFinalize; an unlinked file would keep its blocks while open). */
static void PartFailed(const char tmp[], const char path[], PetscBool direct, PetscMPIInt rank, int *cause)
{
  if (direct) return;
  if (!WriteErrno(*cause) && DiskFull(path)) *cause = ENOSPC;
  if (rank == 0) (void)truncate(tmp, 0);
}

/* Write the HDF5 file of a result option through body(viewer, ctx) into its ".<tag>.part" file (SgFileBeginHDF5) and
   commit it (or leave it for SgFileCommit when commit is false). A failure (a full disk, say) does not raise an error
   here: the ".part" is removed and ok = PETSC_FALSE with a message naming the option, the file and the cause, so that
   the caller can still record it in the summary. HDF5's own error stack is silenced meanwhile. */
PetscErrorCode SgFileWriteHDF5(MPI_Comm comm, const char option[], const char name[], PetscErrorCode (*body)(PetscViewer, void *), void *ctx, PetscBool commit, PetscBool *ok, char msg[], size_t len)
{
  char           tmp[PETSC_MAX_PATH_LEN];
  PetscViewer    viewer = NULL;
  PetscErrorCode ierr, ierr2;
  H5E_auto2_t    efunc;
  void          *edata;
  int            err[2];
  const char    *path;
  PetscBool      direct;
  PetscMPIInt    rank;

  PetscFunctionBeginUser;
  *ok = PETSC_TRUE;
  SgFileResolve(name, &path, &direct);
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCall(SgFileBeginHDF5(comm, name, tmp, sizeof(tmp)));
  PetscCall(PetscPushErrorHandler(PetscReturnErrorHandler, NULL));
  (void)H5Eget_auto2(H5E_DEFAULT, &efunc, &edata);
  (void)H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
  errno = 0;
  if (!direct && SpaceBelow(path, SG_HDF5_MIN_FREE)) {
    ierr  = PETSC_ERR_FILE_WRITE; /* refused before HDF5 writes anything */
    errno = ENOSPC;
  } else {
    /* not PetscCall: the error is caught, reported with its cause and the .part removed below */
    ierr = PetscViewerHDF5Open(comm, tmp, FILE_MODE_WRITE, &viewer);
  }
  /* collective MPI-IO transfers (PETSc's default is independent): every rank writes its part of each dataset in one
     collective call, which MPI-IO can aggregate on a parallel file system */
  if (!ierr) ierr = PetscViewerHDF5SetCollective(viewer, PETSC_TRUE);
  if (!ierr) ierr = body(viewer, ctx);
  err[1] = errno;
  if (viewer) {
    hid_t fid = -1;
    (void)PetscViewerHDF5GetFileId(viewer, &fid);
    if (ierr) PartFailed(tmp, path, direct, rank, &err[1]);
    ierr2 = PetscViewerDestroy(&viewer);
    if (ierr2 && !ierr) {
      ierr   = ierr2;
      err[1] = errno;
      PartFailed(tmp, path, direct, rank, &err[1]);
      if (fid >= 0) (void)H5Fclose(fid); /* the close failed (its flush): again, with the space freed */
    }
  }
  (void)H5Eset_auto2(H5E_DEFAULT, efunc, edata);
  PetscCall(PetscPopErrorHandler());
  err[0] = ierr ? 1 : 0;
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, err, 2, MPI_INT, MPI_MAX, comm));
  if (err[0]) {
    /* HDF5 leaves errno stale: trust only the codes of a failed write; the cause before the .part is removed */
    if (!WriteErrno(err[1])) err[1] = 0;
    PetscCall(PetscSNPrintf(msg, len, "%s: cannot write '%s': %s", option, name, SgFileErrorCause(err[1], path)));
    PetscCall(SgFileAbandon(comm, name));
    *ok = PETSC_FALSE;
    PetscFunctionReturn(0);
  }
  if (commit) PetscCall(SgFileCommit(comm, name));
  PetscFunctionReturn(0);
}
