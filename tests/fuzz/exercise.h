/*
 * exercise.h - what the robustness tests do with a scheme that derived:
 * every back end, so that mutated schemes reach them too (test_fuzz.c,
 * fuzz_derive.c).  Output goes to a memory stream and is thrown away; only
 * a crash, a sanitizer report or a leak can fail.
 */
#ifndef PC_TESTS_EXERCISE_H
#define PC_TESTS_EXERCISE_H

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

#include "base/budget.h"
#include "codegen/emit_c.h"
#include "codegen/lower.h"
#include "compiler/analyze/analyze.h"
#include "compiler/derive.h"
#include "compiler/print/format.h"
#include "runtime/eval.h"
#include "runtime/plot.h"

/* The work budget of one input of the fuzz targets and test_fuzz: the
 * derivation's (DeriveOptions.max_seconds) and the back ends'
 * (budget_deadline_set: printing, lowering and the C stop at their next
 * step once it has passed).  An input past either is abandoned cleanly,
 * with the budget's error; test_budget.c tests that it is. */
#ifndef FUZZ_DERIVE_SECONDS
#define FUZZ_DERIVE_SECONDS 1.0
#endif
#ifndef FUZZ_BACKEND_SECONDS
#define FUZZ_BACKEND_SECONDS 1.0
#endif

/* the largest total degree of d's outputs' equations */
static inline slong exercise_degree(const Derived *d)
{
    slong deg = 0;
    for (slong i = 0; i < d->noutputs; i++) {
        const DerivedOutput *o = d->outputs + i;
        if (o->kind == KIND_SCALAR)
            continue;
        deg =
            FLINT_MAX(deg, fmpz_mpoly_total_degree_si(o->eq->den, d->ring.ctx));
        for (slong k = 0; k < o->eq->len; k++)
            deg = FLINT_MAX(deg, fmpz_mpoly_total_degree_si(o->eq->terms[k].num,
                                                            d->ring.ctx));
    }
    return deg;
}

/* analyze (docs/analyze.md) as text and JSON, then with every const at 1/3
 * and coordinates (i, i^2 - 1) for point i: the curvature and arc length
 * too.  Only up to degree 24, which keeps a mutated scheme quick (the
 * command line bounds the analysis by its time budget instead). */
static inline void exercise_analyze(FILE *m, const Derived *d)
{
    if (exercise_degree(d) > 24)
        return;
    Analysis *a = analyze_derived(d, NULL, 0, NULL);
    analyze_print_text(m, a);
    analyze_print_json(m, a);
    analyze_print_latex(m, a);
    analysis_free(a);
    unsigned char *given = calloc((size_t)d->nconsts + 1, 1);
    fmpq *value = calloc((size_t)d->nconsts + 1, sizeof *value);
    double *xy = calloc(2 * (size_t)d->npoints + 1, sizeof *xy);
    const double **pt = calloc((size_t)d->npoints + 1, sizeof *pt);
    for (slong k = 0; k < d->nconsts; k++) {
        given[k] = 1;
        fmpq_init(value + k);
        fmpq_set_si(value + k, 1, 3);
    }
    for (slong i = 0; i < d->npoints; i++) {
        xy[2 * i] = (double)i;
        xy[2 * i + 1] = (double)(i * i - 1);
        pt[i] = xy + 2 * i;
    }
    AnSet set = {given, value, 2, pt, NULL};
    a = analyze_derived(d, NULL, 0, &set);
    analyze_print_text(m, a);
    analyze_print_json(m, a);
    analysis_free(a);
    for (slong k = 0; k < d->nconsts; k++)
        fmpq_clear(value + k);
    free(pt);
    free(xy);
    free(value);
    free(given);
}

/* what the light fuzz target does with d (fuzz_light.c): the text printer,
 * lowering and the C, within FUZZ_BACKEND_SECONDS */
static inline void exercise_light(const Derived *d)
{
    char *text = NULL;
    size_t len = 0;
    FILE *m = open_memstream(&text, &len);
    budget_deadline_set(FUZZ_BACKEND_SECONDS);
    format_derived(m, d, FMT_TEXT, -1);
    Plan *p = lower_derived(d, m);
    if (p) {
        emit_c(m, p, NULL, d->filename);
        plan_free(p);
    }
    budget_deadline_set(0);
    fclose(m);
    free(text);
}

/* formats d three ways (and relative to its first point), lowers it, emits
 * C and a header, evaluates every output at a few samples in 2D, and plots
 * the point outputs (a small sample budget) */
static inline void exercise_backends(const Derived *d)
{
    char *text = NULL;
    size_t len = 0;
    FILE *m = open_memstream(&text, &len);
    budget_deadline_set(FUZZ_BACKEND_SECONDS);
    format_derived(m, d, FMT_TEXT, -1);
    format_derived(m, d, FMT_LATEX, -1);
    format_derived(m, d, FMT_JSON, -1);
    if (d->npoints > 0)
        format_derived(m, d, FMT_TEXT, 0);
    Plan *p = lower_derived(d, m);
    if (p) {
        int o1, o2;
        char *clash = NULL;
        if (emit_c_clash(p, NULL, &o1, &o2, &clash))
            free(clash);
        emit_c(m, p, NULL, d->filename);
        emit_c_header(m, p, "x", d->filename);
        plan_dump(m, p);
        enum { N = 5, DIM = 2 };
        double t[N] = {-1, 0, 0.5, 1, 3}, out[N * DIM];
        unsigned char st[N];
        const double **prm = calloc((size_t)p->nparams + 1, sizeof *prm);
        const double **pts = calloc((size_t)p->npoints + 1, sizeof *pts);
        double *cst = calloc((size_t)p->nconsts + 1, sizeof *cst);
        double *coords = calloc(DIM * (size_t)p->npoints + 1, sizeof *coords);
        for (int i = 0; i < p->nparams; i++)
            prm[i] = t;
        for (int i = 0; i < p->nconsts; i++)
            cst[i] = 0.25 + i;
        for (int i = 0; i < p->npoints; i++) {
            coords[DIM * i] = i;
            coords[DIM * i + 1] = i * i - 1;
            pts[i] = coords + DIM * i;
        }
        for (int o = 0; o < p->noutputs; o++)
            (void)plan_eval(p, o, N, prm, cst, pts, DIM, out, st);
        int *curves = calloc((size_t)p->noutputs + 1, sizeof *curves);
        int nc = 0;
        for (int o = 0; o < p->noutputs && p->nparams > 0; o++)
            if (p->outputs[o].kind == KIND_POINT)
                curves[nc++] = o;
        if (nc > 0) {
            double pv[8] = {0.5, 0.5, 0.5, 0.5, 0.5, 0.5, 0.5, 0.5};
            double *pvals = calloc((size_t)p->nparams + 1, sizeof *pvals);
            for (int i = 0; i < p->nparams; i++)
                pvals[i] = pv[i % 8];
            PlotSpec ps;
            plot_spec_default(&ps);
            ps.env.plan = p;
            ps.env.param = 0;
            ps.env.params = pvals;
            ps.env.consts = cst;
            ps.env.points = pts;
            ps.env.dim = DIM;
            ps.curves = curves;
            ps.ncurves = nc;
            ps.lo = -1;
            ps.hi = 3;
            ps.lim.initial = 8;
            ps.lim.max_samples = 40;
            ps.ntangents = 1;
            ps.tangents = pv;
            ps.comb = 8;
            (void)plot_svg(m, &ps, NULL);
            free(pvals);
        }
        free(curves);
        free(coords);
        free(cst);
        free(pts);
        free(prm);
        plan_free(p);
    }
    exercise_analyze(m, d);
    budget_deadline_set(0);
    fclose(m);
    free(text);
}

/* one fuzz input: derived under FUZZ_DERIVE_SECONDS, a NULL derivation
 * without an error (or an error with a derivation) aborts, then exercise
 * runs on what derived (the body of both libFuzzer targets) */
static inline int fuzz_one_input(const uint8_t *data, size_t size,
                                 void (*exercise)(const Derived *))
{
    int nerr = -1;
    DeriveOptions opt = {.max_seconds = FUZZ_DERIVE_SECONDS};
    Derived *d = derive_source_ex("fuzz.pcs", (const char *)data, size, NULL,
                                  &nerr, &opt);
    if ((d != NULL) != (nerr == 0))
        abort();
    if (d)
        exercise(d);
    derived_free(d);
    return 0;
}

#endif
