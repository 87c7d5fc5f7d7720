/*
 * api.c - libpointcalc.h: the pipeline as a library.
 *
 * A pc_scheme wraps a Derived, a pc_plan a Plan.  Diagnostics are captured
 * with memory streams so nothing is printed; every returned string is a
 * malloc'ed copy (FLINT's strings are copied out of flint_malloc memory),
 * taken off the memory budget's count (mem_disown) as it is handed over:
 * the caller frees it with free().
 */
#include "libpointcalc.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <flint/flint.h>

#include "base/budget.h"
#include "base/diag.h"
#include "base/mem.h"
#include "codegen/emit_c.h"
#include "codegen/lower.h"
#include "codegen/numsolve.h"
#include "compiler/derive.h"
#include "driver/cli/budget.h"
#include "runtime/eval.h"
#include "runtime/natural.h"

struct pc_scheme {
    Derived *d;         // owned
    double max_seconds; // pc_options.max_seconds: also each pc_compile's and
                        // pc_emit_c's budget (budget_deadline_set)
};

struct pc_plan {
    Plan *p; // owned
};

static char *copy_str(const char *s)
{
    size_t n = strlen(s) + 1;
    char *r = pc_xmalloc(n);
    memcpy(r, s, n);
    return mem_disown(r);
}

/* wraps d; the captured diagnostics go to *diagnostics on failure */
static pc_scheme *wrap(Derived *d, double max_seconds, char *msg,
                       char **diagnostics)
{
    if (diagnostics && !d) {
        *diagnostics = mem_disown(msg);
    } else {
        if (diagnostics)
            *diagnostics = NULL;
        pc_free(msg);
    }
    if (!d)
        return NULL;
    pc_scheme *s = pc_xmalloc(sizeof *s);
    if (!s) {
        derived_free(d);
        return NULL;
    }
    s->d = d;
    s->max_seconds = max_seconds;
    return s;
}

static DeriveOptions derive_options(const pc_options *opt)
{
    DeriveOptions o = {.max_seconds = BUDGET_DEFAULT_SECONDS,
                       .numeric = numsolve_run};
    if (opt != NULL) {
        o.max_seconds = opt->max_seconds;
        o.defines = opt->defines;
        o.ndefines = opt->defines ? opt->ndefines : 0;
    }
    return o;
}

pc_scheme *pc_scheme_parse_opts(const char *name, const char *text, size_t len,
                                const pc_options *opt, char **diagnostics)
{
    char *msg = NULL;
    size_t mlen = 0;
    DeriveOptions o = derive_options(opt);
    FILE *m = pc_xopen_memstream(&msg, &mlen);
    Derived *d =
        derive_source_ex(name ? name : "<string>", text, len, m, NULL, &o);
    pc_xclose_memstream(m);
    return wrap(d, o.max_seconds, msg, diagnostics);
}

pc_scheme *pc_scheme_parse(const char *name, const char *text, size_t len,
                           char **diagnostics)
{
    return pc_scheme_parse_opts(name, text, len, NULL, diagnostics);
}

pc_scheme *pc_scheme_load_opts(const char *path, const pc_options *opt,
                               char **diagnostics)
{
    char *msg = NULL;
    size_t mlen = 0;
    DeriveOptions o = derive_options(opt);
    FILE *m = pc_xopen_memstream(&msg, &mlen);
    Derived *d = derive_file_ex(path, m, NULL, &o);
    pc_xclose_memstream(m);
    return wrap(d, o.max_seconds, msg, diagnostics);
}

pc_scheme *pc_scheme_load(const char *path, char **diagnostics)
{
    return pc_scheme_load_opts(path, NULL, diagnostics);
}

void pc_use_memory_budget(size_t bytes)
{
    mem_use_for_gmp_flint();
    mem_set_limit(bytes);
}

void pc_scheme_free(pc_scheme *s)
{
    if (!s)
        return;
    derived_free(s->d);
    pc_free(s);
}

const char *pc_scheme_name(const pc_scheme *s)
{
    return s->d->scheme;
}

int pc_npoints(const pc_scheme *s)
{
    return (int)s->d->npoints;
}

const char *pc_point_name(const pc_scheme *s, int i)
{
    return i >= 0 && i < s->d->npoints ? s->d->points[i] : NULL;
}

int pc_nparams(const pc_scheme *s)
{
    return (int)s->d->nparams;
}

const char *pc_param_name(const pc_scheme *s, int i)
{
    return i >= 0 && i < s->d->nparams ? s->d->params[i] : NULL;
}

int pc_nconsts(const pc_scheme *s)
{
    return (int)s->d->nconsts;
}

const char *pc_const_name(const pc_scheme *s, int i)
{
    return i >= 0 && i < s->d->nconsts ? s->d->consts[i] : NULL;
}

int pc_noutputs(const pc_scheme *s)
{
    return (int)s->d->noutputs;
}

const char *pc_output_name(const pc_scheme *s, int i)
{
    return i >= 0 && i < s->d->noutputs ? s->d->outputs[i].name : NULL;
}

pc_kind pc_output_kind(const pc_scheme *s, int i)
{
    if (i < 0 || i >= s->d->noutputs)
        return PC_NOKIND;
    switch (s->d->outputs[i].kind) {
    case KIND_SCALAR:
        return PC_SCALAR;
    case KIND_POINT:
        return PC_POINT;
    default:
        return PC_VECTOR;
    }
}

int pc_output_line(const pc_scheme *s, int i)
{
    if (i < 0 || i >= s->d->noutputs)
        return -1;
    return s->d->outputs[i].line;
}

int pc_find_output(const pc_scheme *s, const char *name)
{
    return (int)derived_find_output(s->d, name);
}

int pc_find_point(const pc_scheme *s, const char *name)
{
    return (int)derived_find_point(s->d, name);
}

char *pc_weight_str(const pc_scheme *s, int output, int point)
{
    const Derived *d = s->d;
    if (output < 0 || output >= d->noutputs)
        return NULL;
    const DerivedOutput *o = &d->outputs[output];
    const RatFunStruct *w;
    if (o->kind == KIND_SCALAR) {
        if (point != -1)
            return NULL;
        w = o->scalar;
    } else {
        if (point < 0 || point >= d->npoints)
            return NULL;
        slong k = 0;
        while (k < o->eq->len && o->eq->terms[k].point != point)
            k++;
        if (k == o->eq->len)
            return copy_str("0");
        w = o->w + k;
    }
    /* one FLINT call per polynomial writes it, not interrupted: the
     * scheme's budget, counted from the call, is looked at when it ends */
    budget_deadline_set(s->max_seconds);
    char *f = ratfun_get_str(w, &d->ring);
    int late = budget_late();
    budget_deadline_set(0);
    char *r = late ? NULL : copy_str(f);
    flint_free(f);
    return r;
}

/* *diagnostics = what was written to m (closed here: only then is *msg
 * final), or NULL when ok */
static void hand_over(FILE *m, char **msg, int ok, char **diagnostics)
{
    pc_xclose_memstream(m);
    if (diagnostics && !ok) {
        *diagnostics = mem_disown(*msg);
        return;
    }
    if (diagnostics)
        *diagnostics = NULL;
    pc_free(*msg);
}

pc_plan *pc_compile(const pc_scheme *s, char **diagnostics)
{
    char *msg = NULL;
    size_t mlen = 0;
    FILE *m = pc_xopen_memstream(&msg, &mlen);
    budget_deadline_set(s->max_seconds);
    Plan *p = lower_derived(s->d, m);
    budget_deadline_set(0);
    hand_over(m, &msg, p != NULL, diagnostics);
    if (!p)
        return NULL;
    pc_plan *r = pc_xmalloc(sizeof *r);
    if (!r) {
        plan_free(p);
        return NULL;
    }
    r->p = p;
    return r;
}

void pc_plan_free(pc_plan *p)
{
    if (!p)
        return;
    plan_free(p->p);
    pc_free(p);
}

char *pc_plan_dump(const pc_plan *p)
{
    char *text = NULL;
    size_t len = 0;
    FILE *m = pc_xopen_memstream(&text, &len);
    plan_dump(m, p->p);
    pc_xclose_memstream(m);
    return mem_disown(text);
}

int pc_eval(const pc_plan *p, int output, size_t n, const double *const *params,
            const double *consts, const double *const *points, int dim,
            double *out, unsigned char *status, size_t *npoles)
{
    const Plan *pl = p->p;
    if (output < 0 || output >= pl->noutputs)
        return PC_EINVAL;
    if (n == 0) { /* nothing to do, as the generated batch: nothing read */
        if (npoles)
            *npoles = 0;
        return PC_OK;
    }
    if (!out || (pl->nparams && n && !params) || (pl->nconsts && !consts))
        return PC_EINVAL;
    const PlanOutput *o = &pl->outputs[output];
    if (o->kind != KIND_SCALAR && dim < 1)
        return PC_EINVAL;
    /* the points it reads: its weights' and its distances' (a scalar that
     * measures points reads them too) */
    for (int k = 0; k < pl->npoints; k++)
        if (plan_output_uses_point(pl, output, k) &&
            (!points || !points[k] || dim < 1))
            return PC_EINVAL;
    for (int i = 0; i < pl->nparams && n; i++)
        if (!params[i])
            return PC_EINVAL;
    if (plan_output_min_dim(pl, output, NULL) > dim) /* coord(P, k), k > dim */
        return PC_EINVAL;
    size_t np =
        plan_eval(pl, output, n, params, consts, points, dim, out, status);
    if (npoles)
        *npoles = np;
    return PC_OK;
}

char *pc_emit_c(const pc_scheme *s, const char *prefix, char **diagnostics)
{
    char *msg = NULL;
    size_t mlen = 0;
    FILE *m = pc_xopen_memstream(&msg, &mlen);
    Plan *p = NULL;
    budget_deadline_set(s->max_seconds);
    if (prefix && !emit_c_valid_prefix(prefix))
        fprintf(m, "pointcalc: prefix '%s' is not a usable C identifier\n",
                prefix);
    else
        p = lower_derived(s->d, m);
    if (p && emit_c_check(p, s->d, prefix, m)) {
        plan_free(p);
        p = NULL;
    }
    char *text = NULL;
    size_t len = 0;
    if (p) {
        FILE *c = pc_xopen_memstream(&text, &len);
        emit_c(c, p, prefix, s->d->filename);
        pc_xclose_memstream(c);
        plan_free(p);
    }
    /* the C is written in one pass, then given up if the budget ran out */
    if (text && budget_late()) {
        char secs[48];
        budget_format_seconds(secs, sizeof secs, s->max_seconds);
        diag_fput_escaped(m, s->d->filename);
        fprintf(m,
                ": error: the time budget of %s ran out while writing the "
                "C; raise it with --max-seconds\n",
                secs);
        pc_free(text);
        text = NULL;
    }
    budget_deadline_set(0);
    hand_over(m, &msg, text != NULL, diagnostics);
    return text ? mem_disown(text) : NULL;
}

void pc_cleanup(void)
{
    flint_cleanup_master();
}

void pc_thread_cleanup(void)
{
    flint_cleanup();
}

/* ---- curves in natural parametrization ---------------------------------- */

static NatSegment nat_of(const pc_natural_segment *g)
{
    NatSegment s = {g->x0, g->y0, g->phi0, {0}, g->degree, g->length};
    for (int j = 0; j <= g->degree && j <= NAT_MAX_DEGREE; j++)
        s.k[j] = g->k[j];
    return s;
}

int pc_natural_fit(const double *pts, const unsigned char *has_angle, int n,
                   int law, pc_natural_segment *out, int *bad)
{
    if (bad)
        *bad = -1;
    if (!pts || !out || n < 2 || n > NAT_MAX_POINTS ||
        law < PC_NATURAL_LINEAR || law > PC_NATURAL_CUBIC)
        return PC_EINVAL;
    NatPoint *p = pc_xcalloc((size_t)n, sizeof *p);
    int rc = PC_OK;
    for (int i = 0; i < n && rc == PC_OK; i++) {
        p[i] = (NatPoint){pts[3 * i], pts[3 * i + 1], pts[3 * i + 2],
                          has_angle ? has_angle[i] != 0 : 1};
        if (!(fabs(p[i].x) <= NAT_MAX_COORD) ||
            !(fabs(p[i].y) <= NAT_MAX_COORD) ||
            (p[i].has_th && !isfinite(p[i].th)) ||
            (i > 0 &&
             hypot(p[i].x - p[i - 1].x, p[i].y - p[i - 1].y) < NAT_MIN_CHORD) ||
            (i > 0 && p[i].x == p[i - 1].x && p[i].y == p[i - 1].y))
            rc = PC_EINVAL;
    }
    NatCurve c;
    int which;
    if (rc == PC_OK &&
        nat_composite(p, n, &(NatChain){.law = (NatLaw)law}, &c, &which) != 0) {
        rc = PC_ENOFIT;
        if (bad)
            *bad = which;
    }
    if (rc == PC_OK)
        for (int i = 0; i < n - 1; i++) {
            const NatSegment *g = &c.seg[i];
            out[i] = (pc_natural_segment){g->x0, g->y0,     g->phi0,
                                          {0},   g->degree, g->length};
            memcpy(out[i].k, g->k, sizeof g->k);
        }
    if (rc != PC_EINVAL)
        nat_curve_free(&c);
    pc_free(p);
    return rc;
}

void pc_natural_point(const pc_natural_segment *g, double s, double xy[2])
{
    NatSegment seg = nat_of(g);
    nat_point(&seg, s, &xy[0], &xy[1]);
}
