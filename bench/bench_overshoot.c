/*
 * bench_overshoot.c - how far past its time budget each phase of the
 * library stops (issue 23), beside bench/budget_overshoot.sh's table of
 * the command line.  The library has no timer: every bound below is the
 * clock read between steps, and what one step costs past the deadline is
 * the overshoot.
 *
 * For each row: a reproducer that spends its budget in that phase, run
 * ROUNDS times; the wall time from the call to its return (median and
 * range) against the budget, and what the call returned.
 *
 *   derive, last look      timeout-meet-rational-power (the meet derives,
 *                          then its weights' reductions: no clock inside)
 *   derive, meet           timeout-meet-big-result unmutated (the meet's
 *                          products: test_api_budget_inside_meet)
 *   analyze, 40 curves     analyze_derived_within, 40 plane curves of
 *                          degree about 10 (an implicit equation each)
 *   analyze, one resultant one curve of degree 30: its resultant is one
 *                          FLINT call (about 8 s) - the overshoot left
 *   printing, LaTeX        format_derived of the derivative of a tower of
 *                          10 x_i = sin(x_(i-1)) + cos(i x_(i-1)) under
 *                          budget_deadline_set (57.8 s, 29 MB before)
 *   printing, steps        steps_print of the same in LaTeX
 *   printing, JSON         600 products of two polynomials, whose factors
 *                          JSON looks for (1.8 s on 0.3 s before)
 *   pc_weight_str          a weight with a coefficient of 10^7 digits (one
 *                          FLINT call: the clock is read when it ends)
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <flint/flint.h>

#include "bench/bench_util.h"

#include "base/budget.h"
#include "base/mem.h"
#include "compiler/analyze/analyze.h"
#include "compiler/derive.h"
#include "compiler/print/format.h"
#include "compiler/print/steps.h"
#include "libpointcalc.h"

enum { ROUNDS = 3 };

/* one row: the median and range of t[] (ms) against budget (s) */
static void row(const char *phase, double budget, const double *t,
                const char *result)
{
    double med, lo, hi;
    bench_stats(t, ROUNDS, &med, &lo, &hi);
    printf("| %s | %g s | %.2f s (%.2f-%.2f) | %+.2f s | %s |\n", phase, budget,
           med / 1e3, lo / 1e3, hi / 1e3, med / 1e3 - budget, result);
    fflush(stdout);
}

static char *read_file(const char *path)
{
    size_t len;
    char *t = bench_read_scheme(path, &len);
    if (t)
        t[len] = 0;
    return t;
}

/* the scheme at path, or `inline` (path NULL) */
static void derive_row(const char *phase, const char *path, const char *inl,
                       double budget)
{
    char *text = path ? read_file(path) : strdup(inl);
    if (!path)
        path = "inline.pcs";
    if (!text) {
        printf("| %s | cannot read %s |\n", phase, path);
        return;
    }
    double t[ROUNDS];
    int ok = 0;
    for (int i = 0; i < ROUNDS; i++) {
        DeriveOptions o = {.max_seconds = budget};
        double t0 = bench_now_ms();
        Derived *d = derive_source_ex(path, text, strlen(text), NULL, NULL, &o);
        t[i] = bench_now_ms() - t0;
        ok += d != NULL;
        derived_free(d);
    }
    row(phase, budget, t, ok ? "derived (past the budget)" : "located error");
    free(text);
}

/* n plane curves of degree about `deg` over A, B, C */
static char *curves(int n, int deg)
{
    char *text = malloc((size_t)n * 128 + 256), *p = text;
    p += sprintf(p, "point A, B, C\nparam t in [0, 1]\n");
    for (int i = 1; i <= n; i++)
        p += sprintf(p,
                     "M%d = along(along(A, B, t^%d + %d*t - 1), C, "
                     "(t^%d + 3*t + %d)/(t^2 + %d))\n",
                     i, deg - 1 + i % 3, i, deg - 3 + i % 2, i, i);
    p += sprintf(p, "output M1");
    for (int i = 2; i <= n; i++)
        p += sprintf(p, ", M%d", i);
    sprintf(p, "\n");
    return text;
}

static void analyze_row(const char *phase, int n, int deg, double budget)
{
    char *text = curves(n, deg);
    DeriveOptions o = {.max_seconds = 60, .keep_steps = 1};
    Derived *d = derive_source_ex("a.pcs", text, strlen(text), NULL, NULL, &o);
    double t[ROUNDS];
    int ok = 0;
    for (int i = 0; i < ROUNDS && d; i++) {
        double t0 = bench_now_ms();
        Analysis *a = analyze_derived_within(d, NULL, 0, NULL, budget, NULL);
        t[i] = bench_now_ms() - t0;
        ok += a != NULL;
        analysis_free(a);
    }
    if (d)
        row(phase, budget, t, ok ? "analysed" : "located error");
    derived_free(d);
    free(text);
}

/* the tower x_i = sin(x_(i-1)) + cos(i x_(i-1)), i = 1..n, differentiated */
static char *tower(int n)
{
    char *text = malloc((size_t)n * 64 + 256), *p = text;
    p += sprintf(p, "point A, B\nparam t\nx0 = t\n");
    for (int i = 1; i <= n; i++)
        p += sprintf(p, "x%d = sin(x%d) + cos(%d*x%d)\n", i, i - 1, i, i - 1);
    sprintf(p, "y = diff(x%d, t)\nM = along(A, B, y)\n", n);
    return text;
}

static void print_row(const char *phase, int steps, double budget)
{
    char *text = tower(10);
    DeriveOptions o = {.max_seconds = 60, .keep_steps = steps};
    Derived *d = derive_source_ex("t.pcs", text, strlen(text), NULL, NULL, &o);
    double t[ROUNDS];
    int late = 0;
    size_t len = 0;
    for (int i = 0; i < ROUNDS && d; i++) {
        char *buf = NULL;
        FILE *m = pc_xopen_memstream(&buf, &len);
        budget_deadline_set(budget);
        double t0 = bench_now_ms();
        if (steps)
            steps_print(m, d, FMT_LATEX, -1);
        else
            format_derived(m, d, FMT_LATEX, -1);
        t[i] = bench_now_ms() - t0;
        late += budget_late();
        budget_deadline_set(0);
        pc_xclose_memstream(m);
        pc_free(buf);
    }
    char what[64];
    snprintf(what, sizeof what, "%s, %zu bytes (discarded)",
             late ? "cut short" : "whole", len);
    if (d)
        row(phase, budget, t, what);
    derived_free(d);
    free(text);
}

/* JSON of n products of two polynomials (factored, sharing factors) */
static void json_row(const char *phase, int n, double budget)
{
    char *text = malloc((size_t)n * 128 + 64), *p = text;
    p += sprintf(p, "param t, u\n");
    for (int i = 1; i <= n; i++)
        p += sprintf(p,
                     "s%d = (t^9 + u^7 + t^2*u^3 + t*u + %d)*(t^7*u^4 + u^9 + "
                     "t^3*u + t + %d)\n",
                     i, i, 2 * i + 1);
    p += sprintf(p, "output s1");
    for (int i = 2; i <= n; i++)
        p += sprintf(p, ", s%d", i);
    sprintf(p, "\n");
    DeriveOptions o = {.max_seconds = 60};
    Derived *d = derive_source_ex("j.pcs", text, strlen(text), NULL, NULL, &o);
    double t[ROUNDS];
    int late = 0;
    for (int i = 0; i < ROUNDS && d; i++) {
        char *buf = NULL;
        size_t len = 0;
        FILE *m = pc_xopen_memstream(&buf, &len);
        budget_deadline_set(budget);
        double t0 = bench_now_ms();
        format_derived(m, d, FMT_JSON, -1);
        t[i] = bench_now_ms() - t0;
        late += budget_late();
        budget_deadline_set(0);
        pc_xclose_memstream(m);
        pc_free(buf);
    }
    if (d)
        row(phase, budget, t, late ? "the rest expanded (discarded)" : "whole");
    derived_free(d);
    free(text);
}

static void weight_row(const char *phase, double budget)
{
    const char *text = "point A, B\nparam t\nx = 1e1000^1000\n"
                       "M = along(A, B, t*x^10)\n";
    pc_options o = {.max_seconds = budget};
    pc_scheme *s = pc_scheme_parse_opts("w.pcs", text, strlen(text), &o, NULL);
    double t[ROUNDS];
    int ok = 0;
    for (int i = 0; i < ROUNDS && s; i++) {
        double t0 = bench_now_ms();
        char *w = pc_weight_str(s, 0, 1);
        t[i] = bench_now_ms() - t0;
        ok += w != NULL;
        free(w);
    }
    if (s)
        row(phase, budget, t, ok ? "the text" : "NULL");
    pc_scheme_free(s);
}

int main(void)
{
    pc_use_memory_budget(0);
    printf("| phase (library) | budget | wall to return | overshoot | "
           "result |\n|---|---|---|---|---|\n");
    derive_row("derive, last look at the clock",
               "tests/fuzz/regressions/timeout-meet-rational-power.pcs", NULL,
               0.25);
    derive_row("derive, inside meet", NULL,
               "point A, B, C\nparam t, u\nconst k, h\n"
               "a = (t + u + k + h)^30\nb = (t / u + k - h)^40\n"
               "M = meet(line(A, along(B, C, a)), line(B, along(C, A, b)))\n",
               0.25);
    analyze_row("analyze, 40 curves of degree 10", 40, 10, 0.25);
    analyze_row("analyze, one resultant (degree 30)", 1, 30, 1);
    print_row("printing LaTeX, 10-level tower", 0, 1);
    print_row("printing LaTeX --steps, 10-level tower", 1, 1);
    json_row("printing JSON, 600 factored products", 600, 0.3);
    weight_row("pc_weight_str, 10^7 digits", 1);
    pc_cleanup();
    return 0;
}
