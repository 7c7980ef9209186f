/* The C side of fracas_linear_solver: sparse Cholesky (CHOLMOD) and LU (UMFPACK) on a
 * square matrix given in 1-based compressed sparse column form (Fortran's sparse_t).
 *
 * One handle per factorization owns its own cholmod_common (no state shared between
 * factors), 0-based copies of what the library keeps pointing at, the symbolic analysis
 * (reused by every numeric refactorization on the same pattern) and the solve workspaces.
 *
 *   fss_create   copy the pattern, choose the ordering, symbolic analysis (values: UMFPACK's strategy)
 *   fss_factor   numeric factorization with the current values (build and update)
 *   fss_solve    B := A^-1 B in place, nrhs columns of leading dimension ldb
 *   fss_describe one line naming the method, ordering and nnz of the factor
 *   fss_message  the last error text; fss_minor the dof whose pivot failed (1-based)
 *   fss_free     release everything
 *
 * CHOLMOD is given the upper triangle (stype = 1), as LAPACK's dpotrf('U') is.
 */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cholmod.h>
#include <umfpack.h>

enum { FSS_CHOLMOD = 1, FSS_UMFPACK = 2 };
enum { FSS_ORDER_BEST = 0, FSS_ORDER_METIS = 1, FSS_ORDER_AMD = 2 };
enum {
  FSS_OK = 0,
  FSS_NOT_POSDEF = 1,
  FSS_SINGULAR = 2,
  FSS_PATTERN_CHANGED = 3,
  FSS_FAILED = 4
};

typedef struct {
  int kind, n, nnz;
  uint64_t pattern_hash;
  int minor;        /* 1-based dof whose pivot failed in the last factorization, 0 if none */
  int metis_failed; /* METIS was asked for and failed: AMD was used */
  char message[256];
  /* CHOLMOD */
  cholmod_common common;
  cholmod_sparse *upper; /* upper triangle, 0-based, values refilled from val */
  int *upper_pos;        /* upper->x[q] = val[upper_pos[q]] */
  cholmod_factor *factor;
  cholmod_dense *x, *y, *e; /* cholmod_solve2 workspaces */
  /* UMFPACK */
  int *ap, *ai;
  double *ax;
  void *symbolic, *numeric;
  double control[UMFPACK_CONTROL], info[UMFPACK_INFO];
  int *wi;
  double *w, *xcol;
} fss_t;

/* CHOLMOD reports through a handler without user data: keep the last text here. */
static _Thread_local char cholmod_last_message[200];

static void record_cholmod_error(int status, const char *file, int line, const char *message) {
  (void)file;
  (void)line;
  snprintf(cholmod_last_message, sizeof cholmod_last_message, "%s (CHOLMOD status %d)", message,
           status);
}

static uint64_t pattern_hash(int n, const int *colptr, const int *rowind) {
  uint64_t h = 1469598103934665603ULL; /* FNV-1a over n, colptr and rowind */
  const int nnz = colptr[n] - 1;
  h = (h ^ (uint64_t)(uint32_t)n) * 1099511628211ULL;
  for (int j = 0; j <= n; j++) h = (h ^ (uint64_t)(uint32_t)colptr[j]) * 1099511628211ULL;
  for (int p = 0; p < nnz; p++) h = (h ^ (uint64_t)(uint32_t)rowind[p]) * 1099511628211ULL;
  return h;
}

void fss_free(void **handle);

static void set_message(fss_t *f, const char *text) {
  snprintf(f->message, sizeof f->message, "%s", text);
}

/* CHOLMOD symbolic analysis with the requested ordering; METIS failing falls back to AMD. */
static int cholmod_analyze_ordered(fss_t *f, int ordering) {
  cholmod_common *c = &f->common;
  c->postorder = 1;
  c->supernodal = CHOLMOD_AUTO;
  /* Supernodal only when the factorization does at least 300 flops per entry of L
   * (CHOLMOD's default: 40). Measured with Debian's reference BLAS on 2D lattices
   * (doc/benchmarks.md §4): simplicial refactorizes 2-3 times faster up to n ~ 1e4 and
   * solves faster up to 2e5 (2D: 37 flops/entry at n = 800, 281 at n = 2e5); 3D meshes
   * pass 300 early and get the supernodal (BLAS-3) factorization. */
  c->supernodal_switch = 300;
  c->final_ll = 1; /* simplicial LL^T too: a non-positive pivot stops it, as in dpotrf */
  if (ordering == FSS_ORDER_AMD) {
    c->nmethods = 1;
    c->method[0].ordering = CHOLMOD_AMD;
  } else if (ordering == FSS_ORDER_METIS) {
    c->nmethods = 1;
    c->method[0].ordering = CHOLMOD_METIS;
  } else { /* both: CHOLMOD keeps the one with the least fill */
    c->nmethods = 2;
    c->method[0].ordering = CHOLMOD_METIS;
    c->method[1].ordering = CHOLMOD_AMD;
  }
  cholmod_last_message[0] = '\0';
  f->factor = cholmod_analyze(f->upper, c);
  if (!f->factor && ordering != FSS_ORDER_AMD) {
    f->metis_failed = 1;
    c->nmethods = 1;
    c->method[0].ordering = CHOLMOD_AMD;
    c->status = CHOLMOD_OK;
    f->factor = cholmod_analyze(f->upper, c);
  }
  if (!f->factor) {
    snprintf(f->message, sizeof f->message, "CHOLMOD symbolic analysis failed: %s",
             cholmod_last_message);
    return FSS_FAILED;
  }
  return FSS_OK;
}

void *fss_create(int kind, int n, const int *colptr, const int *rowind, const double *val,
                 int ordering, int *status) {
  fss_t *f = calloc(1, sizeof *f);
  if (!f) {
    *status = FSS_FAILED;
    return NULL;
  }
  f->kind = kind;
  f->n = n;
  f->nnz = colptr[n] - 1;
  f->pattern_hash = pattern_hash(n, colptr, rowind);
  *status = FSS_OK;

  if (kind == FSS_CHOLMOD) {
    int nupper = 0, q = 0;
    cholmod_start(&f->common);
    f->common.print = 0; /* our messages, not CHOLMOD's printf */
    f->common.error_handler = record_cholmod_error;
    for (int j = 0; j < n; j++)
      for (int p = colptr[j] - 1; p < colptr[j + 1] - 1; p++)
        if (rowind[p] - 1 <= j) nupper++;
    f->upper = cholmod_allocate_sparse(n, n, nupper, 1, 1, 1, CHOLMOD_REAL, &f->common);
    f->upper_pos = malloc((size_t)(nupper > 0 ? nupper : 1) * sizeof(int));
    if (!f->upper || !f->upper_pos) {
      set_message(f, "CHOLMOD: out of memory for the matrix copy");
      *status = FSS_FAILED;
      return f;
    }
    int *up = f->upper->p, *ui = f->upper->i;
    for (int j = 0; j < n; j++) {
      up[j] = q;
      for (int p = colptr[j] - 1; p < colptr[j + 1] - 1; p++) {
        int i = rowind[p] - 1;
        if (i <= j) {
          ui[q] = i;
          f->upper_pos[q] = p;
          q++;
        }
      }
    }
    up[n] = q;
    *status = cholmod_analyze_ordered(f, ordering);
  } else if (kind == FSS_UMFPACK) {
    f->ap = malloc((size_t)(n + 1) * sizeof(int));
    f->ai = malloc((size_t)(f->nnz > 0 ? f->nnz : 1) * sizeof(int));
    f->ax = malloc((size_t)(f->nnz > 0 ? f->nnz : 1) * sizeof(double));
    f->wi = malloc((size_t)(n > 0 ? n : 1) * sizeof(int));
    f->w = malloc((size_t)(5 * n > 0 ? 5 * n : 1) * sizeof(double));
    f->xcol = malloc((size_t)(n > 0 ? n : 1) * sizeof(double));
    if (!f->ap || !f->ai || !f->ax || !f->wi || !f->w || !f->xcol) {
      set_message(f, "UMFPACK: out of memory for the matrix copy");
      *status = FSS_FAILED;
      return f;
    }
    for (int j = 0; j <= n; j++) f->ap[j] = colptr[j] - 1;
    for (int p = 0; p < f->nnz; p++) f->ai[p] = rowind[p] - 1;
    umfpack_di_defaults(f->control);
    f->control[UMFPACK_ORDERING] = ordering == FSS_ORDER_AMD     ? UMFPACK_ORDERING_AMD
                                   : ordering == FSS_ORDER_METIS ? UMFPACK_ORDERING_METIS
                                                                 : UMFPACK_ORDERING_CHOLMOD;
    /* With the values, UMFPACK sees a nonzero diagonal and picks its symmetric strategy
     * (diagonal pivots, AMD on A + A^T) for an SPD matrix. */
    int st = umfpack_di_symbolic(n, n, f->ap, f->ai, val, &f->symbolic, f->control, f->info);
    if (st != UMFPACK_OK) {
      snprintf(f->message, sizeof f->message, "UMFPACK symbolic analysis failed (status %d)", st);
      *status = FSS_FAILED;
    }
  } else {
    set_message(f, "unknown sparse factorization kind");
    *status = FSS_FAILED;
  }
  return f;
}

int fss_factor(void *handle, const int *colptr, const int *rowind, const double *val) {
  fss_t *f = handle;
  f->minor = 0;
  if (colptr[f->n] - 1 != f->nnz || pattern_hash(f->n, colptr, rowind) != f->pattern_hash) {
    snprintf(f->message, sizeof f->message,
             "the matrix pattern differs from the analysed one (nnz %d, analysed %d)",
             colptr[f->n] - 1, f->nnz);
    return FSS_PATTERN_CHANGED;
  }
  if (f->kind == FSS_CHOLMOD) {
    double *ux = f->upper->x;
    const size_t nupper = (size_t)((int *)f->upper->p)[f->n];
    for (size_t q = 0; q < nupper; q++) ux[q] = val[f->upper_pos[q]];
    cholmod_last_message[0] = '\0';
    f->common.status = CHOLMOD_OK;
    int ok = cholmod_factorize(f->upper, f->factor, &f->common);
    if (f->common.status == CHOLMOD_NOT_POSDEF) {
      /* L->minor counts in the permuted order: name the dof of the matrix as given. */
      const int step = (int)f->factor->minor;
      const int *perm = f->factor->Perm;
      f->minor = (perm ? perm[step] : step) + 1;
      snprintf(f->message, sizeof f->message,
               "matrix not positive definite (pivot of dof %d, elimination step %d of %d)",
               f->minor, step + 1, f->n);
      return FSS_NOT_POSDEF;
    }
    if (!ok || f->common.status < CHOLMOD_OK) {
      snprintf(f->message, sizeof f->message, "CHOLMOD numeric factorization failed: %s",
               cholmod_last_message);
      return FSS_FAILED;
    }
    return FSS_OK;
  }
  memcpy(f->ax, val, (size_t)f->nnz * sizeof(double));
  if (f->numeric) umfpack_di_free_numeric(&f->numeric);
  int st = umfpack_di_numeric(f->ap, f->ai, f->ax, f->symbolic, &f->numeric, f->control, f->info);
  if (st == UMFPACK_WARNING_singular_matrix) {
    snprintf(f->message, sizeof f->message,
             "matrix singular (zero pivot in the LU factors of a %d x %d matrix)", f->n, f->n);
    return FSS_SINGULAR;
  }
  if (st != UMFPACK_OK) {
    snprintf(f->message, sizeof f->message, "UMFPACK numeric factorization failed (status %d)",
             st);
    return FSS_FAILED;
  }
  return FSS_OK;
}

int fss_solve(void *handle, double *b, int ldb, int nrhs) {
  fss_t *f = handle;
  if (f->n == 0 || nrhs == 0) return FSS_OK;
  if (f->kind == FSS_CHOLMOD) {
    cholmod_dense rhs = {0};
    rhs.nrow = (size_t)f->n;
    rhs.ncol = (size_t)nrhs;
    rhs.nzmax = (size_t)ldb * (size_t)nrhs;
    rhs.d = (size_t)ldb;
    rhs.x = b;
    rhs.xtype = CHOLMOD_REAL;
    rhs.dtype = CHOLMOD_DOUBLE;
    if (!cholmod_solve2(CHOLMOD_A, f->factor, &rhs, NULL, &f->x, NULL, &f->y, &f->e, &f->common)) {
      snprintf(f->message, sizeof f->message, "CHOLMOD solve failed: %s", cholmod_last_message);
      return FSS_FAILED;
    }
    const double *x = f->x->x;
    for (int k = 0; k < nrhs; k++)
      memcpy(b + (size_t)k * (size_t)ldb, x + (size_t)k * f->x->d, (size_t)f->n * sizeof(double));
    return FSS_OK;
  }
  for (int k = 0; k < nrhs; k++) {
    double *bk = b + (size_t)k * (size_t)ldb;
    int st = umfpack_di_wsolve(UMFPACK_A, f->ap, f->ai, f->ax, f->xcol, bk, f->numeric, f->control,
                               f->info, f->wi, f->w);
    if (st != UMFPACK_OK) {
      snprintf(f->message, sizeof f->message, "UMFPACK solve failed (status %d)", st);
      return FSS_FAILED;
    }
    memcpy(bk, f->xcol, (size_t)f->n * sizeof(double));
  }
  return FSS_OK;
}

static const char *cholmod_ordering_name(int ordering) {
  switch (ordering) {
    case CHOLMOD_NATURAL: return "natural";
    case CHOLMOD_GIVEN: return "given";
    case CHOLMOD_AMD: return "AMD";
    case CHOLMOD_METIS: return "METIS";
    case CHOLMOD_NESDIS: return "NESDIS";
    case CHOLMOD_COLAMD: return "COLAMD";
    case CHOLMOD_POSTORDERED: return "natural (postordered)";
    default: return "unknown";
  }
}

static const char *umfpack_ordering_name(double used) {
  switch ((int)used) {
    case UMFPACK_ORDERING_AMD: return "AMD/COLAMD";
    case UMFPACK_ORDERING_METIS: return "METIS";
    case UMFPACK_ORDERING_GIVEN: return "given";
    case UMFPACK_ORDERING_NONE: return "natural";
    case UMFPACK_ORDERING_CHOLMOD: return "CHOLMOD's choice";
    default: return "unknown";
  }
}

/* Which ordering was used, as a code: 1 METIS, 2 AMD, 0 other. */
int fss_ordering_used(void *handle) {
  fss_t *f = handle;
  int used = -1;
  if (f->kind == FSS_CHOLMOD && f->factor) used = f->factor->ordering;
  if (f->kind == FSS_CHOLMOD) return used == CHOLMOD_METIS ? 1 : used == CHOLMOD_AMD ? 2 : 0;
  used = (int)f->info[UMFPACK_ORDERING_USED];
  return used == UMFPACK_ORDERING_METIS ? 1 : used == UMFPACK_ORDERING_AMD ? 2 : 0;
}

/* Entries of the factors: nnz(L) (CHOLMOD, from the analysis) or nnz(L) + nnz(U) - n. */
double fss_factor_nnz(void *handle) {
  fss_t *f = handle;
  if (f->kind == FSS_CHOLMOD) return f->common.lnz;
  return f->info[UMFPACK_LNZ] + f->info[UMFPACK_UNZ] - f->n;
}

void fss_describe(void *handle, char *buf, int len) {
  fss_t *f = handle;
  if (f->kind == FSS_CHOLMOD && f->factor) {
    snprintf(buf, (size_t)len, "CHOLMOD %s %s, %s ordering%s, n = %d, nnz(L) = %.0f",
             f->factor->is_super ? "supernodal" : "simplicial", f->factor->is_ll ? "LL^T" : "LDL^T",
             cholmod_ordering_name(f->factor->ordering),
             f->metis_failed ? " (METIS failed)" : "", f->n, f->common.lnz);
  } else if (f->kind == FSS_UMFPACK) {
    snprintf(buf, (size_t)len, "UMFPACK LU, %s strategy, %s ordering, n = %d, nnz(L+U) = %.0f",
             (int)f->info[UMFPACK_STRATEGY_USED] == UMFPACK_STRATEGY_SYMMETRIC ? "symmetric"
                                                                              : "unsymmetric",
             umfpack_ordering_name(f->info[UMFPACK_ORDERING_USED]), f->n,
             fss_factor_nnz(handle));
  } else {
    snprintf(buf, (size_t)len, "(no sparse factor)");
  }
}

void fss_message(void *handle, char *buf, int len) {
  fss_t *f = handle;
  snprintf(buf, (size_t)len, "%s", f ? f->message : "no factor");
}

int fss_minor(void *handle) { return ((fss_t *)handle)->minor; }

void fss_free(void **handle) {
  fss_t *f = *handle;
  if (!f) return;
  if (f->kind == FSS_CHOLMOD) {
    cholmod_free_factor(&f->factor, &f->common);
    cholmod_free_sparse(&f->upper, &f->common);
    cholmod_free_dense(&f->x, &f->common);
    cholmod_free_dense(&f->y, &f->common);
    cholmod_free_dense(&f->e, &f->common);
    cholmod_finish(&f->common);
    free(f->upper_pos);
  } else if (f->kind == FSS_UMFPACK) {
    if (f->numeric) umfpack_di_free_numeric(&f->numeric);
    if (f->symbolic) umfpack_di_free_symbolic(&f->symbolic);
    free(f->ap);
    free(f->ai);
    free(f->ax);
    free(f->wi);
    free(f->w);
    free(f->xcol);
  }
  free(f);
  *handle = NULL;
}
