/*
 * fit_scheme.c - `pointcalc fit FILE`: the fit statements of a scheme
 * (`fit X to f on [LO, HI] [samples M]`, docs/fit.md).
 *
 *   FILE -> parse, expand, sema (the statements, their names and kinds)
 *        -> per fit: the scheme again with its outputs replaced by
 *           X, f, diff(f, p) and diff(X, p) for every param p -> Derived
 *        -> x = the one param f depends on, t the one X depends on
 *        -> phi_k(t_i) from X's Plan at unit vectors; the check that X
 *           interpolates its base points (grid + Gauss-Newton)
 *        -> fit_new_from (fit.c) -> report (cmd_fit.c runs and prints)
 *
 * The nodes are the scheme's base points in declaration order; the first
 * and the last are LO and HI.  The replaced outputs are blanked in place,
 * so every diagnostic keeps its line and column.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/mem.h"
#include "base/numfmt.h"
#include "codegen/numsolve.h"
#include "compiler/expand.h"
#include "compiler/print/book.h"
#include "compiler/sema.h"
#include "driver/cli/fit.h"
#include "grammar/parse.h"
#include "runtime/eval.h"

enum { FIT_GRID = 1001, FIT_NEWTON = 50 };
#define FIT_INTERP_TOL 1e-9

/* one fit statement, read off the checked AST */
typedef struct FitStmt {
    Span span;
    Span xs, fs; // the names X and f as written
    double lo, hi;
    int samples; // 0: the default
    char *data;  // `to data "FILE.csv"`: the file, relative to the scheme's
                 // folder (owned), or NULL: the target is the name f
} FitStmt;

/* the value of a constant number (sema checked its shape) */
static double const_value(const Node *n)
{
    switch (n->kind) {
    case ND_NUM:
        return pc_strtod(n->text, NULL);
    case ND_NEG:
        return -const_value(n->lhs);
    case ND_ADD:
        return const_value(n->lhs) + const_value(n->rhs);
    case ND_SUB:
        return const_value(n->lhs) - const_value(n->rhs);
    case ND_MUL:
        return const_value(n->lhs) * const_value(n->rhs);
    default:
        return const_value(n->lhs) / const_value(n->rhs);
    }
}

typedef struct FitFront {
    char *text; // the file (owned)
    size_t len;
    FitStmt *fits;
    int nfits;
    char **params; // the params' names (owned)
    int nparams, nconsts;
    Span *outputs; // the output statements, to blank
    int noutputs;
} FitFront;

static void front_clear(FitFront *F)
{
    for (int j = 0; j < F->nparams; j++)
        pc_free(F->params[j]);
    pc_free(F->params);
    for (int i = 0; i < F->nfits; i++)
        pc_free(F->fits[i].data);
    pc_free(F->fits);
    pc_free(F->outputs);
    pc_free(F->text);
}

static char *read_text(const char *path, size_t *len, FILE *err)
{
    FILE *f = fopen(path, "rb");
    if (!f) {
        fprintf(err, "%s: error: cannot open the file\n", path);
        return NULL;
    }
    size_t cap = 4096, n = 0, got;
    char *s = pc_xmalloc(cap);
    while ((got = fread(s + n, 1, cap - n, f)) > 0) {
        n += got;
        if (n == cap && cap < DERIVE_MAX_SOURCE)
            s = pc_xrealloc(s, cap *= 2);
        else if (n == cap)
            break;
    }
    fclose(f);
    *len = n;
    return s;
}

/* a statement's data file: as written when absolute, else in the folder
 * of the scheme (owned) */
static char *data_path(const char *scheme, const char *file)
{
    const char *slash = strrchr(scheme, '/');
    if (file[0] == '/' || !slash)
        return pc_xasprintf("%s", file);
    return pc_xasprintf("%.*s/%s", (int)(slash - scheme), scheme, file);
}

/* the statements of the scheme's checked AST into F */
static void collect(FitFront *F, const Scheme *sc, const SemaInfo *I,
                    const char *path)
{
    for (const Stmt *st = sc->stmts; st; st = st->next) {
        if (st->kind == ST_OUTPUT) {
            F->outputs = pc_xrealloc(F->outputs, sizeof *F->outputs *
                                                     (size_t)(F->noutputs + 1));
            F->outputs[F->noutputs++] = st->span;
        }
        if (st->kind != ST_FIT)
            continue;
        F->fits =
            pc_xrealloc(F->fits, sizeof *F->fits * (size_t)(F->nfits + 1));
        FitStmt *s = &F->fits[F->nfits++];
        s->span = st->span;
        s->xs = st->names->span;
        s->fs = st->data ? st->span : st->names->next->span;
        s->data = st->data ? data_path(path, st->data) : NULL;
        s->lo = const_value(st->lo);
        s->hi = const_value(st->hi);
        s->samples = st->expr ? (int)const_value(st->expr) : 0;
    }
    F->nparams = I->nparams;
    F->nconsts = I->nconsts;
    F->params =
        pc_xcalloc((size_t)(I->nparams ? I->nparams : 1), sizeof *F->params);
    for (int j = 0; j < I->nparams; j++)
        F->params[j] = pc_xasprintf("%s", I->params[j]->name);
}

/* parse, expand and check the scheme; 0 or 1 after reporting */
static int front(FitFront *F, const char *path, const FitOptions *o, FILE *err)
{
    Arena arena;
    Source src;
    Diag diag;
    memset(F, 0, sizeof *F);
    F->text = read_text(path, &F->len, err);
    if (!F->text)
        return 1;
    arena_init(&arena);
    source_init(&src, path, F->text, F->len);
    diag_init(&diag, &src, err);
    diag_hold(&diag);
    Scheme *sc = parse_scheme(&src, &arena, &diag);
    /* an unused define is reported by the derivation (run_one) */
    char *used = pc_xcalloc((size_t)o->ndefines + 1, 1);
    if (diag.nerrors == 0)
        expand_scheme(sc, &arena, &diag, o->defines, o->ndefines, used);
    pc_free(used);
    SemaInfo *I = diag.nerrors == 0 ? sema_check(sc, &arena, &diag) : NULL;
    if (diag.nerrors == 0)
        collect(F, sc, I, path);
    int rc = diag.nerrors ? 1 : 0;
    diag_flush(&diag);
    source_clear(&src);
    arena_reset(&arena);
    return rc;
}

/* the scheme with its outputs blanked and X, f and their derivatives by
 * every param appended as the outputs */
static char *fit_text(const FitFront *F, const FitStmt *s, size_t *len)
{
    char *t = pc_xmalloc(F->len + 1);
    memcpy(t, F->text, F->len);
    t[F->len] = '\0';
    for (int i = 0; i < F->noutputs; i++)
        for (int b = F->outputs[i].start; b < F->outputs[i].end; b++)
            if (t[b] != '\n')
                t[b] = ' ';
    int xl = s->xs.end - s->xs.start, fl = s->fs.end - s->fs.start;
    const char *X = F->text + s->xs.start, *f = F->text + s->fs.start;
    /* a data target: a stand-in f (the data replace it, run_one) */
    char *all = pc_xasprintf(s->data ? "%s\n__fit_data = 0\n" : "%s\n", t);
    if (s->data) {
        f = "__fit_data";
        fl = (int)strlen(f);
    }
    pc_free(t);
    for (int j = 0; j < F->nparams; j++) {
        char *next = pc_xasprintf(
            "%s__fit_f%d = diff(%.*s, %s)\n__fit_x%d = diff(%.*s, %s)\n", all,
            j, fl, f, F->params[j], j, xl, X, F->params[j]);
        pc_free(all);
        all = next;
    }
    char *next = pc_xasprintf("%soutput %.*s, %.*s", all, xl, X, fl, f);
    pc_free(all);
    all = next;
    for (int w = 0; w < 2; w++)
        for (int j = 0; j < F->nparams; j++) {
            next = pc_xasprintf("%s, __fit_%c%d", all, w ? 'x' : 'f', j);
            pc_free(all);
            all = next;
        }
    next = pc_xasprintf("%s\n", all);
    pc_free(all);
    *len = strlen(next);
    return next;
}

static int output_is_zero(const Derived *d, const DerivedOutput *o)
{
    if (o->kind == KIND_SCALAR)
        return ratfun_is_zero(o->scalar, &d->ring);
    for (slong i = 0; i < o->eq->len; i++)
        if (!ratfun_is_zero(&o->w[i], &d->ring))
            return 0;
    return 1;
}

/* the one param output `first + j` (j = 0..np-1) is non-zero for: what
 * the value of X or f depends on; -1 none, -2 several */
static int the_param(const Derived *d, int first, int np)
{
    int found = -1;
    for (int j = 0; j < np; j++)
        if (!output_is_zero(d, &d->outputs[first + j]))
            found = found == -1 ? j : -2;
    return found;
}

/* the weights of output out (n of them) at one t into w */
static void weights_at(const Plan *p, const double *consts, int out, int param,
                       int np, int n, double t, double *w)
{
    double *unit = pc_xcalloc((size_t)n * (size_t)n, sizeof *unit);
    const double **pts = pc_xmalloc(sizeof *pts * (size_t)n);
    const double **params = pc_xmalloc(sizeof *params * (size_t)np);
    double zero = 0;
    unsigned char st;
    for (int k = 0; k < n; k++) {
        unit[k * n + k] = 1;
        pts[k] = unit + k * n;
    }
    for (int j = 0; j < np; j++)
        params[j] = j == param ? &t : &zero;
    plan_eval(p, out, 1, params, consts, pts, n, w, &st);
    pc_free(params);
    pc_free(pts);
    pc_free(unit);
}

/* the t in [0, 1] where base point k's weight is 1 and the others 0:
 * the grid's best, then Gauss-Newton on the n residuals; returns the
 * largest residual left, tk the t */
static double node_t(const Plan *p, const double *consts, const double *grid,
                     int k, int xout, int dout, int param, int np, int n,
                     double *tk)
{
    double best = INFINITY, t = 0, w[LSQ_MAX_UNKNOWNS + 2],
           dw[LSQ_MAX_UNKNOWNS + 2], res = 0;
    for (int i = 0; i < FIT_GRID; i++) {
        double s = 0;
        for (int j = 0; j < n; j++) {
            double r = grid[i * n + j] - (j == k);
            s += r * r;
        }
        if (s < best) {
            best = s;
            t = (double)i / (FIT_GRID - 1);
        }
    }
    for (int it = 0; it <= FIT_NEWTON; it++) {
        weights_at(p, consts, xout, param, np, n, t, w);
        weights_at(p, consts, dout, param, np, n, t, dw);
        double num = 0, den = 0;
        res = 0;
        for (int j = 0; j < n; j++) {
            double r = w[j] - (j == k);
            num += r * dw[j];
            den += dw[j] * dw[j];
            res = fmax(res, fabs(r));
        }
        if (res <= 1e-15 || den == 0 || it == FIT_NEWTON)
            break;
        t = fmin(1, fmax(0, t - num / den));
    }
    *tk = t;
    return res;
}

/* X interpolates its base points: else an error at the fit naming the
 * first node that fails; *ends: node 1 at t = 0, node N at t = 1 */
static int check_interpolation(const Derived *d, const Plan *p,
                               const double *consts, const FitStmt *s,
                               int param, int np, int *ends, FILE *err)
{
    int n = (int)d->npoints, dout = 2 + np + param, rc = 0;
    double *grid = pc_xmalloc(sizeof *grid * FIT_GRID * (size_t)n);
    double t0 = 0, t1 = 0;
    fit_curve_table(grid, p, consts, 0, param, np, FIT_GRID, n);
    for (int k = 0; k < n && rc == 0; k++) {
        double tk, res = node_t(p, consts, grid, k, 0, dout, param, np, n, &tk);
        if (k == 0)
            t0 = tk;
        if (k == n - 1)
            t1 = tk;
        if (res > FIT_INTERP_TOL) {
            derived_error(d, err, s->span,
                          "'%s' is not an interpolation curve through its "
                          "nodes: no t in [0, 1] gives weight 1 to the base "
                          "point %s and 0 to the others (closest: t = %.6g, "
                          "off by %.3g)",
                          d->outputs[0].name, d->points[k], tk, res);
            rc = 1;
        }
    }
    *ends = fabs(t0) <= FIT_INTERP_TOL && fabs(t1 - 1) <= FIT_INTERP_TOL;
    pc_free(grid);
    return rc;
}

static void interval_error(const Derived *d, FILE *err, const FitStmt *s)
{
    char lo[32], hi[32];
    pc_snprintf(lo, sizeof lo, "%.17g", s->lo);
    pc_snprintf(hi, sizeof hi, "%.17g", s->hi);
    derived_error(d, err, s->span,
                  "the fit's interval [%s, %s] is empty; expected [LO, HI] "
                  "with LO < HI",
                  lo, hi);
}

/* the curve's param and the target's, checked; -1 after reporting */
static int find_params(const Derived *d, const FitFront *F, const FitStmt *s,
                       int *xp, int *fp, FILE *err)
{
    int np = F->nparams;
    const char *X = d->outputs[0].name, *f = d->outputs[1].name;
    *fp = s->data ? 0 : the_param(d, 2, np);
    *xp = the_param(d, 2 + np, np);
    if (*xp < 0)
        derived_error(d, err, s->span,
                      "the curve '%s' depends on %s; expected a point "
                      "definition in one param",
                      X, *xp == -1 ? "no param" : "more than one param");
    else if (*fp < 0)
        derived_error(d, err, s->span,
                      "the target '%s' depends on %s; expected a scalar "
                      "definition in one param (x)",
                      f, *fp == -1 ? "no param" : "more than one param");
    else if (!(s->lo < s->hi) || !isfinite(s->lo) || !isfinite(s->hi))
        interval_error(d, err, s);
    else if (s->samples &&
             (s->samples < d->npoints || s->samples >= LSQ_MAX_RESIDUALS))
        derived_error(d, err, s->span,
                      "expected %ld .. %d samples (at least the number of "
                      "nodes); found %d",
                      (long)d->npoints, LSQ_MAX_RESIDUALS - 1, s->samples);
    else if (d->npoints < 3 || d->npoints > LSQ_MAX_UNKNOWNS + 2)
        derived_error(d, err, s->span,
                      "the curve '%s' has %ld nodes (base points); a fit "
                      "needs 3 .. %d",
                      X, (long)d->npoints, LSQ_MAX_UNKNOWNS + 2);
    else
        return 0;
    return -1;
}

/* the values of p's consts from --set NAME=VALUE into *out (NULL when
 * there are none); -1 after an error at the fit naming a const with no
 * value */
static int const_values(const Derived *d, const Plan *p, const FitStmt *s,
                        const FitOptions *o, double **out, FILE *err)
{
    *out = NULL;
    for (int i = 0; i < o->nsets; i++) {
        size_t nl = strcspn(o->sets[i], "=");
        int known = 0;
        for (int c = 0; c < p->nconsts; c++)
            known |= strlen(p->consts[c]) == nl &&
                     strncmp(o->sets[i], p->consts[c], nl) == 0;
        if (!known) {
            fprintf(err,
                    "pointcalc: --set %.*s: the scheme has no const '%.*s'\n",
                    (int)nl, o->sets[i], (int)nl, o->sets[i]);
            return -2;
        }
    }
    if (p->nconsts == 0)
        return 0;
    double *v = pc_xcalloc((size_t)p->nconsts, sizeof *v);
    for (int c = 0; c < p->nconsts; c++) {
        const char *val = NULL;
        size_t nl = strlen(p->consts[c]);
        for (int i = 0; i < o->nsets; i++)
            if (strncmp(o->sets[i], p->consts[c], nl) == 0 &&
                o->sets[i][nl] == '=')
                val = o->sets[i] + nl + 1;
        if (!val) {
            derived_error(d, err, s->span,
                          "fit needs numbers: the const '%s' has no value; "
                          "expected --set %s=VALUE",
                          p->consts[c], p->consts[c]);
            pc_free(v);
            return -1;
        }
        v[c] = pc_strtod(val, NULL);
    }
    *out = v;
    return 0;
}

/* one fit statement: derive, check, build the Fit, report */
static int run_one(const FitFront *F, const FitStmt *s, const char *path,
                   const char *data, const FitOptions *o, FitReport report,
                   void *ctx, FILE *err)
{
    size_t len;
    char *text = fit_text(F, s, &len);
    int bad_define = 0;
    if (!data) /* --data replaces the statement's target */
        data = s->data;
    DeriveOptions opt = {.max_seconds = BUDGET_DEFAULT_SECONDS,
                         .defines = o->defines,
                         .ndefines = o->ndefines,
                         .bad_define = &bad_define,
                         .numeric = numsolve_run};
    Derived *d = derive_source_ex(path, text, len, err, NULL, &opt);
    pc_free(text);
    if (bad_define) { // a usage error, as for derive
        derived_free(d);
        return 2;
    }
    Plan *p = d ? lower_derived(d, err) : NULL;
    int xp, fp, ends = 0, rc = 1, np = F->nparams;
    double *consts = NULL;
    int cv = p ? const_values(d, p, s, o, &consts, err) : 0;
    if (cv == -2)
        rc = 2;
    if (!p || cv != 0 || find_params(d, F, s, &xp, &fp, err) != 0 ||
        check_interpolation(d, p, consts, s, xp, np, &ends, err) != 0) {
        pc_free(consts);
        plan_free(p);
        derived_free(d);
        return rc;
    }
    FitOptions fo = *o;
    fo.lo = s->lo;
    fo.hi = s->hi;
    fo.nodes = (int)d->npoints;
    if (s->samples)
        fo.samples = s->samples;
    size_t ns = (size_t)fo.samples + 1, n = (size_t)fo.nodes;
    double *phi = NULL, *coef = pc_xmalloc(sizeof *coef * n * n);
    char *eq = NULL;
    if (fo.samples >= fo.nodes && fo.samples < LSQ_MAX_RESIDUALS) {
        phi = pc_xmalloc(sizeof *phi * ns * n);
        fit_curve_table(phi, p, consts, 0, xp, np, ns, fo.nodes);
    }
    if (fit_curve_coefficients(coef, d, 0, xp, fo.nodes) != 0) {
        BookOptions bo = {.origin = -1};
        pc_free(coef);
        coef = NULL;
        eq = book_output(d, &d->outputs[0], &bo);
    }
    FitTarget t = {.plan = p,
                   .consts = consts,
                   .f_out = 1,
                   .fp_out = 2 + fp,
                   .param = fp,
                   .nparams = np,
                   .label = d->outputs[1].name};
    if (data) {
        plan_free(p);
        t.plan = NULL;
        if (fit_target_data(&t, data, &fo, err) != 0) {
            pc_free(phi);
            pc_free(coef);
            pc_free(eq);
            derived_free(d);
            return 1;
        }
    }
    Fit *f = fit_new_from(&fo, &t, phi, coef, ends, err, &rc);
    if (f) {
        FitInfo info = {.curve = d->outputs[0].name,
                        .target = data ? data : d->outputs[1].name,
                        .point_eq = eq};
        rc = report(ctx, f, &info);
    }
    fit_free(f);
    pc_free(eq);
    derived_free(d);
    return rc;
}

int fit_scheme_run(const char *path, const char *data, const FitOptions *o,
                   FitReport report, void *ctx, FILE *err)
{
    FitFront F;
    int rc = front(&F, path, o, err);
    if (rc == 0 && F.nfits == 0) {
        fprintf(err,
                "%s: error: the scheme has no fit statement; expected 'fit "
                "X to f on [LO, HI]' (docs/fit.md)\n",
                path);
        rc = 1;
    }
    for (int i = 0; i < F.nfits && rc == 0; i++)
        rc = run_one(&F, &F.fits[i], path, data, o, report, ctx, err);
    front_clear(&F);
    return rc;
}
