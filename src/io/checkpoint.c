/* checkpoint.c: the checkpoint file (-checkpoint_file, -restart_file): the problem's fingerprint, atomic writing, and a
   writer and a reader through which each owner of a state saves and loads its own (src/cont/state.c). Vertex data are
   stored with the vertex coordinates and matched by them on reading, so a restart may use another number of ranks
   (another partition) than the run that wrote the file. The writer is in checkpoint_write.c, the reader in
   checkpoint_read.c, the problem's fingerprint in fingerprint.c; here what both sides share: the vertices a rank
   owns and the history rows. */
#include "io/ioimpl.h"

#define NHIST 22   /* numbers per history row */

static void RowToReals(const SgHistoryRow *r, PetscReal a[])
{
  const PetscReal v[NHIST] = {r->kind == 's' ? 0 : 1, r->outer, r->gamma, r->it, r->active, r->entered, r->left, r->fnorm, r->r1, r->r2, r->V, r->dV, r->ksp_its, r->time, r->ssn_its, r->C1, r->C2, r->Em, r->rhoF, r->rhoC, r->infeas, r->kkt};
  for (PetscInt k = 0; k < NHIST; k++) a[k] = v[k];
}

static void RealsToRow(const PetscReal a[], SgHistoryRow *r)
{
  r->kind    = a[0] == 0 ? 's' : 'o';
  r->outer   = (PetscInt)a[1];
  r->gamma   = a[2];
  r->it      = (PetscInt)a[3];
  r->active  = (PetscInt)a[4];
  r->entered = (PetscInt)a[5];
  r->left    = (PetscInt)a[6];
  r->fnorm   = a[7];
  r->r1      = a[8];
  r->r2      = a[9];
  r->V       = a[10];
  r->dV      = a[11];
  r->ksp_its = (PetscInt)a[12];
  r->time    = a[13];
  r->ssn_its = (PetscInt)a[14];
  r->C1      = a[15];
  r->C2      = a[16];
  r->Em      = a[17];
  r->rhoF    = a[18];
  r->rhoC    = a[19];
  r->infeas  = a[20];
  r->kkt     = a[21];
}

/* ------------------------------------------------------------------ the file
   The group /checkpoint holds the vertex coordinates (by which a reader matches the vertices of any partition), the
   mesh size and the problem's fingerprint, written and checked here; beside them, whatever each owner of a state puts
   in through a writer and takes out through a reader (the controller, its type, the friction state, the load steps:
   src/cont/state.c). The file is written whole or not at all (SgFileWriteHDF5: a .part renamed). */

/* the number of vertices this rank owns (the vertices whose data it writes) */
PetscErrorCode SgCheckpointOwnedVertices(SgElasticity el, PetscInt *nown)
{
  const SgMesh *m;
  DM            dmVert;
  PetscSection  gs;

  PetscFunctionBeginUser;
  PetscCall(SgElasticityGetMesh(el, &m));
  PetscCall(SgElasticityGetDMs(el, NULL, &dmVert, NULL, NULL));
  PetscCall(DMGetGlobalSection(dmVert, &gs));
  *nown = 0;
  for (PetscInt v = 0; v < m->nv; v++) {
    PetscInt off;
    PetscCall(PetscSectionGetOffset(gs, m->vStart + v, &off));
    if (off >= 0) (*nown)++;
  }
  PetscFunctionReturn(0);
}

PetscErrorCode SgCheckpointWriterHistory(SgCheckpointWriter w, SgHistory hist)
{
  PetscInt      nh;
  SgHistoryRow *rows;
  PetscReal    *a;

  PetscFunctionBeginUser;
  PetscCall(SgHistoryGetRows(hist, &nh, &rows));
  PetscCall(PetscMalloc1(NHIST * nh + 1, &a));
  for (PetscInt i = 0; i < nh; i++) RowToReals(&rows[i], &a[i * NHIST]);
  PetscCall(SgCheckpointWriterReals(w, "history", NHIST * nh, a));
  PetscCall(PetscFree(a));
  PetscFunctionReturn(0);
}

/* the history rows (of outer steps up to maxouter) into hist */
PetscErrorCode SgCheckpointReaderHistory(SgCheckpointReader r, PetscInt maxouter, SgHistory hist)
{
  PetscReal *ha;
  PetscInt   nh;

  PetscFunctionBeginUser;
  PetscCall(SgCheckpointReaderReals(r, "history", -1, &nh, &ha));
  {
    const char *what = NULL;
    PetscReal   val  = 0;
    if (nh % NHIST) what = "the length of the history", val = nh;
    for (PetscInt i = 0; !what && i < nh / NHIST; i++) {
      const PetscReal kind = ha[i * NHIST], outer = ha[i * NHIST + 1];
      if (!(kind == 0 || kind == 1)) what = "a history row kind", val = kind;
      else if (!(outer >= 0 && outer <= maxouter && outer == PetscFloorReal(outer))) what = "a history row's outer step", val = outer;
    }
    if (what) PetscCall(PetscFree(ha));
    if (what) PetscCall(SgCheckpointReaderDamaged(&r, what, val));
  }
  PetscCall(SgHistoryReset(hist));
  for (PetscInt i = 0; i < nh / NHIST; i++) {
    SgHistoryRow row;
    RealsToRow(&ha[i * NHIST], &row);
    PetscCall(SgHistoryAdd(hist, &row));
  }
  PetscCall(PetscFree(ha));
  PetscFunctionReturn(0);
}
