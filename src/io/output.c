/* output.c: the fields of a result: the mesh, vertex and cell fields (once, or per load step) in HDF5 and the XDMF
   file beside it, committed together. */
#include "io/ioimpl.h"
#include <petscviewerhdf5.h>

typedef struct {
  DM              dm;
  PetscInt        nv, nc;
  Vec            *vf, *cf;
  PetscReal       magnification;
  PetscInt        nsteps; /* 0: one set of fields; else the load steps steps[] filled by fill */
  const PetscInt *steps;
  SgOutputFill    fill;
  void           *fctx;
} FieldsCtx;

/* VecView of v under the name <its name>_step<step> (the name restored after) */
static PetscErrorCode ViewStep(Vec v, PetscInt step, PetscViewer viewer)
{
  const char *name;
  char        base[256], sname[300];

  PetscFunctionBeginUser;
  PetscCall(PetscObjectGetName((PetscObject)v, &name));
  PetscCall(PetscStrncpy(base, name, sizeof(base)));
  PetscCall(PetscSNPrintf(sname, sizeof(sname), "%s_step%" PetscInt_FMT, base, step));
  PetscCall(PetscObjectSetName((PetscObject)v, sname));
  PetscCall(VecView(v, viewer));
  PetscCall(PetscObjectSetName((PetscObject)v, base));
  PetscFunctionReturn(0);
}

static PetscErrorCode WriteFieldsH5(PetscViewer viewer, void *ctx)
{
  FieldsCtx *f = (FieldsCtx *)ctx;

  PetscFunctionBeginUser;
  PetscCall(PetscViewerPushFormat(viewer, PETSC_VIEWER_HDF5_VIZ));
  PetscCall(DMView(f->dm, viewer));
  if (!f->nsteps) {
    for (PetscInt i = 0; i < f->nv; i++) PetscCall(VecView(f->vf[i], viewer));
    for (PetscInt i = 0; i < f->nc; i++) PetscCall(VecView(f->cf[i], viewer));
  }
  for (PetscInt k = 0; k < f->nsteps; k++) {
    PetscCall(f->fill(f->fctx, k, f->nv, f->vf, f->nc, f->cf));
    for (PetscInt i = 0; i < f->nv; i++) PetscCall(ViewStep(f->vf[i], f->steps[k], viewer));
    for (PetscInt i = 0; i < f->nc; i++) PetscCall(ViewStep(f->cf[i], f->steps[k], viewer));
  }
  PetscCall(PetscViewerHDF5WriteAttribute(viewer, "/", "magnification", PETSC_REAL, &f->magnification));
  PetscCall(PetscViewerPopFormat(viewer));
  PetscFunctionReturn(0);
}

static PetscErrorCode OutputWrite(SgElasticity p, const char h5name[], FieldsCtx *ctx, const PetscReal times[])
{
  char           xname[PETSC_MAX_PATH_LEN + 8], msg[PETSC_MAX_PATH_LEN + 256];
  PetscBool      ok;
  PetscErrorCode ierr;
  MPI_Comm       comm;

  PetscFunctionBeginUser;
  PetscCall(SgElasticityGetComm(p, &comm));
  PetscCall(SgElasticityGetDMs(p, &ctx->dm, NULL, NULL, NULL));
  PetscCall(PetscLogEventBegin(SG_Output, 0, 0, 0, 0));
  PetscCall(SgOutputXdmfName(h5name, xname, sizeof(xname))); /* refuses a name ParaView could not read, before writing */
  PetscCall(SgFileWriteHDF5(comm, "-output_file", h5name, WriteFieldsH5, ctx, PETSC_FALSE, &ok, msg, sizeof(msg)));
  PetscCheck(ok, comm, PETSC_ERR_FILE_WRITE, "%s", msg);
  ierr = SgOutputWriteXDMF(p, h5name, xname, ctx->nsteps, ctx->steps, times, ctx->nv, ctx->vf, ctx->nc, ctx->cf, ctx->magnification);
  if (ierr) PetscCall(SgFileAbandon(comm, h5name)); /* the .xmf.part is gone already */
  PetscCall(ierr);
  PetscCall(SgFileCommit(comm, h5name));
  PetscCall(SgFileCommit(comm, xname));
  PetscCall(PetscLogEventEnd(SG_Output, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

/* Write mesh, vertex fields (first: displacement, on the full mesh with Dirichlet values) and cell fields to
   <name>.h5 and the matching <name>.xmf. Both are written as ".part" first and renamed together, so that a failure of
   either leaves neither new file (and the previous pair intact). */
PetscErrorCode SgOutputWrite(SgElasticity p, const char h5name[], PetscInt nv, Vec vf[], PetscInt nc, Vec cf[], PetscReal magnification)
{
  FieldsCtx ctx = {NULL, nv, nc, vf, cf, magnification, 0, NULL, NULL, NULL};

  PetscFunctionBeginUser;
  PetscCall(OutputWrite(p, h5name, &ctx, NULL));
  PetscFunctionReturn(0);
}

/* The same for load steps: fill(fctx, k, ...) puts the fields of the k-th of the nsteps steps into vf and cf, stored
   as <name>_step<steps[k]>; the .xmf is a temporal collection with the time values times[k] (the load factors). */
PetscErrorCode SgOutputWriteSteps(SgElasticity p, const char h5name[], PetscInt nsteps, const PetscInt steps[], const PetscReal times[], SgOutputFill fill, void *fctx, PetscInt nv, Vec vf[], PetscInt nc, Vec cf[], PetscReal magnification)
{
  FieldsCtx ctx = {NULL, nv, nc, vf, cf, magnification, nsteps, steps, fill, fctx};

  PetscFunctionBeginUser;
  PetscCall(OutputWrite(p, h5name, &ctx, times));
  PetscFunctionReturn(0);
}
