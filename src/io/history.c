/* history.c: the per-iteration history (SSN iterations and outer steps), kept in memory and written as CSV. */
#include "io/ioimpl.h"

PetscErrorCode SgHistoryCreate(SgHistory *h)
{
  PetscFunctionBeginUser;
  PetscCall(PetscNew(h));
  PetscFunctionReturn(0);
}

PetscErrorCode SgHistoryDestroy(SgHistory *h)
{
  PetscFunctionBeginUser;
  if (!*h) PetscFunctionReturn(0);
  PetscCall(PetscFree((*h)->rows));
  PetscCall(PetscFree(*h));
  PetscFunctionReturn(0);
}

/* Every number unset (NaN, written as an empty field) */
PetscErrorCode SgHistoryRowInit(SgHistoryRow *r)
{
  PetscFunctionBeginUser;
  PetscCall(PetscMemzero(r, sizeof(*r)));
  r->gamma = r->fnorm = r->r1 = r->r2 = r->V = r->dV = r->C1 = r->C2 = r->Em = r->rhoF = r->rhoC = r->infeas = r->kkt = r->time = SG_NAN;
  r->active = r->entered = r->left = r->ksp_its = r->ssn_its = -1;
  PetscFunctionReturn(0);
}

PetscErrorCode SgHistoryAdd(SgHistory h, const SgHistoryRow *r)
{
  PetscFunctionBeginUser;
  if (h->n == h->cap) {
    SgHistoryRow *rows;
    h->cap = PetscMax(64, 2 * h->cap);
    PetscCall(PetscMalloc1(h->cap, &rows));
    PetscCall(PetscArraycpy(rows, h->rows, h->n));
    PetscCall(PetscFree(h->rows));
    h->rows = rows;
  }
  h->rows[h->n++] = *r;
  PetscFunctionReturn(0);
}

static void PutReal(FILE *fp, PetscReal v)
{
  if (PetscIsInfOrNanReal(v)) fprintf(fp, ",");
  else fprintf(fp, ",%.10e", (double)v);
}

static void PutInt(FILE *fp, PetscInt v)
{
  if (v < 0) fprintf(fp, ",");
  else fprintf(fp, ",%" PetscInt_FMT, v);
}

PetscErrorCode SgHistoryWrite(MPI_Comm comm, SgHistory h, const char option[], const char name[])
{
  FILE *fp;

  PetscFunctionBeginUser;
  if (!name[0]) PetscFunctionReturn(0);
  PetscCall(SgFileOpen(comm, option, name, &fp));
  if (fp) {
    fprintf(fp, "kind,outer,gamma,it,active,entered,left,fnorm,r1,r2,V,dVdgamma,ksp_its,time,ssn_its,C1,C2,Emodel,rhoF,rhoC,infeasibility,kkt\n");
    for (PetscInt i = 0; i < h->n; i++) {
      const SgHistoryRow *r = &h->rows[i];
      fprintf(fp, "%s,%" PetscInt_FMT, r->kind == 's' ? "ssn" : "outer", r->outer);
      PutReal(fp, r->gamma);
      PutInt(fp, r->it);
      PutInt(fp, r->active);
      PutInt(fp, r->entered);
      PutInt(fp, r->left);
      PutReal(fp, r->fnorm);
      PutReal(fp, r->r1);
      PutReal(fp, r->r2);
      PutReal(fp, r->V);
      PutReal(fp, r->dV);
      PutInt(fp, r->ksp_its);
      PutReal(fp, r->time);
      PutInt(fp, r->ssn_its);
      PutReal(fp, r->C1);
      PutReal(fp, r->C2);
      PutReal(fp, r->Em);
      PutReal(fp, r->rhoF);
      PutReal(fp, r->rhoC);
      PutReal(fp, r->infeas);
      PutReal(fp, r->kkt);
      fprintf(fp, "\n");
    }
  }
  PetscCall(SgFileClose(comm, name, &fp));
  PetscFunctionReturn(0);
}

PetscErrorCode SgHistoryGetRows(SgHistory h, PetscInt *n, SgHistoryRow **rows)
{
  PetscFunctionBeginUser;
  *n    = h->n;
  *rows = h->rows;
  PetscFunctionReturn(0);
}

PetscErrorCode SgHistoryReset(SgHistory h)
{
  PetscFunctionBeginUser;
  h->n = 0;
  PetscFunctionReturn(0);
}

/* a history row as SG_HISTORY_NREALS numbers (the checkpoint's history dataset), and back */
void SgHistoryRowToReals(const SgHistoryRow *r, PetscReal a[])
{
  const PetscReal v[SG_HISTORY_NREALS] = {r->kind == 's' ? 0 : 1, r->outer, r->gamma, r->it, r->active, r->entered, r->left, r->fnorm, r->r1, r->r2, r->V, r->dV, r->ksp_its, r->time, r->ssn_its, r->C1, r->C2, r->Em, r->rhoF, r->rhoC, r->infeas, r->kkt};
  for (PetscInt k = 0; k < SG_HISTORY_NREALS; k++) a[k] = v[k];
}

void SgHistoryRowFromReals(const PetscReal a[], SgHistoryRow *r)
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
