/* summary.c: the JSON summary of a run: keys and JSON-encoded values, written atomically. */
#include "io/ioimpl.h"

PetscErrorCode SgSummaryCreate(SgSummary *s)
{
  PetscFunctionBeginUser;
  PetscCall(PetscNew(s));
  PetscFunctionReturn(0);
}

PetscErrorCode SgSummaryDestroy(SgSummary *s)
{
  PetscFunctionBeginUser;
  if (!*s) PetscFunctionReturn(0);
  for (PetscInt i = 0; i < (*s)->n; i++) PetscCall(PetscFree2((*s)->key[i], (*s)->val[i]));
  PetscCall(PetscFree2((*s)->key, (*s)->val));
  PetscCall(PetscFree(*s));
  PetscFunctionReturn(0);
}

/* Set key to an already JSON-encoded value (replacing an earlier value of the key). */
PetscErrorCode SgSummarySetRaw(SgSummary s, const char key[], const char json[])
{
  PetscInt i;
  size_t   lk, lv;

  PetscFunctionBeginUser;
  for (i = 0; i < s->n; i++) {
    PetscBool eq;
    PetscCall(PetscStrcmp(s->key[i], key, &eq));
    if (eq) break;
  }
  if (i == s->n) {
    if (s->n == s->cap) {
      char   **k, **v;
      PetscInt cap = PetscMax(32, 2 * s->cap);
      PetscCall(PetscCalloc2(cap, &k, cap, &v));
      PetscCall(PetscArraycpy(k, s->key, s->n));
      PetscCall(PetscArraycpy(v, s->val, s->n));
      PetscCall(PetscFree2(s->key, s->val));
      s->key = k;
      s->val = v;
      s->cap = cap;
    }
    s->n++;
  } else PetscCall(PetscFree2(s->key[i], s->val[i]));
  PetscCall(PetscStrlen(key, &lk));
  PetscCall(PetscStrlen(json, &lv));
  PetscCall(PetscMalloc2(lk + 1, &s->key[i], lv + 1, &s->val[i]));
  PetscCall(PetscStrcpy(s->key[i], key));
  PetscCall(PetscStrcpy(s->val[i], json));
  PetscFunctionReturn(0);
}

static void JSONReal(char buf[], size_t len, PetscReal v)
{
  if (PetscIsInfOrNanReal(v)) snprintf(buf, len, "null");
  else snprintf(buf, len, "%.17g", (double)v);
}

PetscErrorCode SgSummarySetReal(SgSummary s, const char key[], PetscReal v)
{
  char buf[64];

  PetscFunctionBeginUser;
  JSONReal(buf, sizeof(buf), v);
  PetscCall(SgSummarySetRaw(s, key, buf));
  PetscFunctionReturn(0);
}

PetscErrorCode SgSummarySetInt(SgSummary s, const char key[], PetscInt v)
{
  char buf[64];

  PetscFunctionBeginUser;
  PetscCall(PetscSNPrintf(buf, sizeof(buf), "%" PetscInt_FMT, v));
  PetscCall(SgSummarySetRaw(s, key, buf));
  PetscFunctionReturn(0);
}

PetscErrorCode SgSummarySetBool(SgSummary s, const char key[], PetscBool v)
{
  PetscFunctionBeginUser;
  PetscCall(SgSummarySetRaw(s, key, v ? "true" : "false"));
  PetscFunctionReturn(0);
}

PetscErrorCode SgSummarySetString(SgSummary s, const char key[], const char v[])
{
  char   buf[1024];
  size_t k = 0;

  PetscFunctionBeginUser;
  buf[k++] = '"';
  for (const char *c = v; *c && k < sizeof(buf) - 3; c++) {
    if (*c == '"' || *c == '\\') buf[k++] = '\\';
    buf[k++] = (*c == '\n' || *c == '\t') ? ' ' : *c;
  }
  buf[k++] = '"';
  buf[k]   = 0;
  PetscCall(SgSummarySetRaw(s, key, buf));
  PetscFunctionReturn(0);
}

PetscErrorCode SgSummarySetRealArray(SgSummary s, const char key[], PetscInt n, const PetscReal v[])
{
  char  *buf;
  size_t len = 32 * (size_t)n + 4, k = 0;

  PetscFunctionBeginUser;
  PetscCall(PetscMalloc1(len, &buf));
  buf[k++] = '[';
  for (PetscInt i = 0; i < n; i++) {
    JSONReal(buf + k, len - k, v[i]);
    k += strlen(buf + k);
    if (i < n - 1) buf[k++] = ',';
  }
  buf[k++] = ']';
  buf[k]   = 0;
  PetscCall(SgSummarySetRaw(s, key, buf));
  PetscCall(PetscFree(buf));
  PetscFunctionReturn(0);
}

PetscErrorCode SgSummarySetIntArray(SgSummary s, const char key[], PetscInt n, const PetscInt v[])
{
  PetscReal *r;

  PetscFunctionBeginUser;
  PetscCall(PetscMalloc1(n, &r));
  for (PetscInt i = 0; i < n; i++) r[i] = (PetscReal)v[i];
  PetscCall(SgSummarySetRealArray(s, key, n, r));
  PetscCall(PetscFree(r));
  PetscFunctionReturn(0);
}

PetscErrorCode SgSummaryWrite(MPI_Comm comm, SgSummary s, const char option[], const char name[])
{
  FILE *fp;

  PetscFunctionBeginUser;
  if (!name[0]) PetscFunctionReturn(0);
  PetscCall(SgFileOpen(comm, option, name, &fp));
  if (fp) {
    fprintf(fp, "{\n");
    for (PetscInt i = 0; i < s->n; i++) fprintf(fp, "  \"%s\": %s%s\n", s->key[i], s->val[i], i < s->n - 1 ? "," : "");
    fprintf(fp, "}\n");
  }
  PetscCall(SgFileClose(comm, name, &fp));
  PetscFunctionReturn(0);
}
