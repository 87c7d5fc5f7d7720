/*
 * cmd_analyze.c - `pointcalc analyze FILE [--output NAME[,NAME...]]
 * [--format text|json]`: what each output curve is, found exactly from its
 * derived equation (compiler/analyze/analyze.h, docs/analyze.md): its
 * ends, degree and order, poles, stop points, inflections, the base points
 * it passes through, the implicit equation of a plane curve, and the
 * poles of every definition; with --at, the curvature and the arc
 * length.
 */
#include "driver/cli/cli.h"

#include <stdlib.h>
#include <string.h>

#include "base/mem.h"
#include "compiler/analyze/analyze.h"
#include "driver/cli/args.h"
#include "runtime/sample.h"

typedef struct AnalyzeArgs {
    int json;         // --format json (1) or latex (2)
    NameList outputs; // --output
    NameList set;     // --set NAME=VALUE, as typed
    EvalArgs ev;      // --at A=x,y,... (eval's parsing; only at is used)
    const char *usage;
} AnalyzeArgs;

/* --format text|json, --output NAMES, --set k=VALUE */
static int analyze_option(void *ctx, int argc, char **argv, int i, FILE *err)
{
    AnalyzeArgs *a = ctx;
    const char *v = args_value(argc, argv, i);
    if (!v)
        return 0;
    if (strcmp(argv[i], "--output") == 0) {
        if (args_names_add(&a->outputs, v) < 0) {
            args_usage_error(err, a->usage, "--output '%s': an empty name", v);
            return -1;
        }
        return 2;
    }
    if (strcmp(argv[i], "--at") == 0)
        return eval_args_option(&a->ev, argc, argv, i, a->usage, err);
    if (strcmp(argv[i], "--set") == 0) {
        if (!strchr(v, '=') || v[0] == '=') {
            args_usage_error(err, a->usage, "--set '%s': expected NAME=VALUE",
                             v);
            return -1;
        }
        a->set.v =
            pc_xrealloc(a->set.v, (size_t)(a->set.n + 1) * sizeof *a->set.v);
        a->set.v[a->set.n++] = pc_xstrdup(v);
        return 2;
    }
    if (strcmp(argv[i], "--format") != 0)
        return 0;
    if (strcmp(v, "text") == 0)
        a->json = 0;
    else if (strcmp(v, "json") == 0)
        a->json = 1;
    else if (strcmp(v, "latex") == 0)
        a->json = 2;
    else {
        args_usage_error(err, a->usage,
                         "unknown format '%s'; expected text, json or latex",
                         v);
        return -1;
    }
    return 2;
}

/* --output's names as indices of d's outputs into sel; the count, or -1
 * after a usage error */
static int select_outputs(int *sel, const AnalyzeArgs *a, const Derived *d,
                          FILE *err)
{
    int n = 0;
    if (a->outputs.n == 0)
        for (slong o = 0; o < d->noutputs; o++)
            sel[n++] = (int)o;
    for (int i = 0; i < a->outputs.n; i++) {
        slong o = derived_find_output(d, a->outputs.v[i]);
        if (o < 0) {
            args_usage_error(err, a->usage,
                             "--output '%s' is not an output of the scheme",
                             a->outputs.v[i]);
            return -1;
        }
        for (int j = 0; j < n; j++)
            if (sel[j] == o) {
                args_usage_error(err, a->usage, "--output '%s' is given twice",
                                 a->outputs.v[i]);
                return -1;
            }
        sel[n++] = (int)o;
    }
    return n;
}

/* --set's values against d's consts, exact (ratfun_set_str: 1/3, 0.25,
 * -2); 0, or 2 after a usage error */
static int set_values(unsigned char *given, fmpq *value, const AnalyzeArgs *a,
                      const Derived *d, FILE *err)
{
    int rc = 0;
    RatFun x;
    ratfun_init(x, &d->ring);
    for (int i = 0; i < a->set.n && !rc; i++) {
        char *name = pc_xstrdup(a->set.v[i]);
        char *eq = strchr(name, '=');
        *eq = 0;
        slong k = 0;
        while (k < d->nconsts && strcmp(d->consts[k], name) != 0)
            k++;
        if (k == d->nconsts)
            rc = args_usage_error(err, a->usage,
                                  "--set '%s': '%s' is not a const of the "
                                  "scheme",
                                  a->set.v[i], name);
        else if (given[k])
            rc = args_usage_error(err, a->usage, "--set '%s' is given twice",
                                  name);
        else if (ratfun_set_str(x, eq + 1, &d->ring) != RATFUN_OK ||
                 !ratfun_get_fmpq(value + k, x, &d->ring))
            rc = args_usage_error(err, a->usage,
                                  "--set '%s': expected a number such as "
                                  "1/3 or 0.25",
                                  a->set.v[i]);
        else
            given[k] = 1;
        pc_free(name);
    }
    ratfun_clear(x, &d->ring);
    return rc;
}

/* --at's coordinates against d's points into pt (npoints, NULL: not
 * given); *dim their dimension.  0, or 2 after a usage error */
static int coordinates(double **pt, int *dim, const AnalyzeArgs *a,
                       const Derived *d, FILE *err)
{
    for (int i = 0; i < a->ev.nat; i++) {
        const Assign *x = a->ev.at + i;
        slong k = derived_find_point(d, x->name);
        if (k < 0)
            return args_usage_error(err, a->usage,
                                    "--at %s: '%s' is not a base point of "
                                    "the scheme",
                                    x->name, x->name);
        if (pt[k])
            return args_usage_error(err, a->usage, "--at %s given twice",
                                    x->name);
        long n = sample_numbers(x->text, pt + k);
        if (n < 0)
            return args_usage_error(err, a->usage,
                                    "--at %s=%s: malformed coordinates; "
                                    "expected numbers separated by commas",
                                    x->name, x->text);
        if (*dim && n != *dim)
            return args_usage_error(err, a->usage,
                                    "--at %s has %ld coordinates but the "
                                    "points before it have %d: every point "
                                    "must have the same dimension",
                                    x->name, n, *dim);
        *dim = (int)n;
    }
    return 0;
}

/* typed ("1/3,0.25") as dim exact numbers, or NULL when it is not */
static fmpq *exact_point(const char *typed, int dim, const Derived *d)
{
    fmpq *q = pc_xmalloc((size_t)(dim + 1) * sizeof *q);
    for (int j = 0; j < dim; j++)
        fmpq_init(q + j);
    RatFun x;
    ratfun_init(x, &d->ring);
    char *text = pc_xstrdup(typed), *save = NULL;
    int n = 0, ok = 1;
    for (char *c = strtok_r(text, ",", &save); c && ok;
         c = strtok_r(NULL, ",", &save), n++)
        ok = n < dim && ratfun_set_str(x, c, &d->ring) == RATFUN_OK &&
             ratfun_get_fmpq(q + n, x, &d->ring);
    pc_free(text);
    ratfun_clear(x, &d->ring);
    if (ok && n == dim)
        return q;
    for (int j = 0; j < dim; j++)
        fmpq_clear(q + j);
    pc_free(q);
    return NULL;
}

/* --at's coordinates exactly, as typed (qpt[k]: dim values, or NULL when
 * not given or not numbers such as 1/3 or 0.25) */
static void exact_coordinates(fmpq **qpt, int dim, const AnalyzeArgs *a,
                              const Derived *d)
{
    for (int i = 0; i < a->ev.nat; i++) {
        slong k = derived_find_point(d, a->ev.at[i].name);
        qpt[k] = exact_point(a->ev.at[i].text, dim, d);
    }
}

/* the report, made in memory and written in one piece (as derive's); 1
 * when the exact analysis ran out of the time budget (reported to err at
 * the output: the timer's message would only name the file) */
static int report(FILE *out, FILE *err, const AnalyzeArgs *a, const Derived *d,
                  const int *sel, int nsel, const AnSet *set, double seconds)
{
    Analysis *an = analyze_derived_within(d, sel, nsel, set, seconds, err);
    if (!an)
        return 1;
    char *text = NULL;
    size_t len = 0;
    FILE *m = pc_xopen_memstream(&text, &len);
    analyze_numeric(an, set);
    if (a->json == 1)
        analyze_print_json(m, an);
    else if (a->json == 2)
        analyze_print_latex(m, an);
    else
        analyze_print_text(m, an);
    analysis_free(an);
    pc_xclose_memstream(m);
    fwrite(text, 1, len, out);
    pc_free(text);
    return 0;
}

static void args_clear(AnalyzeArgs *a)
{
    args_names_clear(&a->outputs);
    for (int i = 0; i < a->set.n; i++)
        pc_free(a->set.v[i]);
    pc_free(a->set.v);
    eval_args_clear(&a->ev);
}

int cli_analyze(int argc, char **argv, FILE *out, FILE *err)
{
    AnalyzeArgs a = {0, {NULL, 0}, {NULL, 0}, {0}, help_usage("analyze")};
    eval_args_init(&a.ev);
    BudgetOptions bo;
    const char *file;
    int rc =
        args_parse(argc, argv, a.usage, &bo, &file, analyze_option, &a, err);
    if (rc) {
        args_clear(&a);
        return rc;
    }
    Derived *d = cli_derive_file_steps(file, &bo, 1, err, &rc);
    if (!d) {
        args_clear(&a);
        return rc;
    }
    int *sel =
        pc_xmalloc((size_t)(d->noutputs + a.outputs.n + 1) * sizeof *sel);
    unsigned char *given = pc_xcalloc((size_t)d->nconsts + 1, 1);
    fmpq *value = pc_xmalloc((size_t)(d->nconsts + 1) * sizeof *value);
    for (slong k = 0; k < d->nconsts; k++)
        fmpq_init(value + k);
    double **pt = pc_xcalloc((size_t)d->npoints + 1, sizeof *pt);
    int dim = 0;
    int nsel = select_outputs(sel, &a, d, err);
    rc = nsel < 0 ? 2 : set_values(given, value, &a, d, err);
    if (!rc)
        rc = coordinates(pt, &dim, &a, d, err);
    fmpq **qpt = pc_xcalloc((size_t)d->npoints + 1, sizeof *qpt);
    if (!rc)
        exact_coordinates(qpt, dim, &a, d);
    if (!rc) {
        AnSet set = {given, value, dim, (const double *const *)pt,
                     (const fmpq *const *)qpt};
        /* the analysis has its own budget: root isolation and factoring
         * of a big curve are not bounded by themselves */
        budget_arm(bo.max_seconds, bo.max_memory);
        budget_phase("analysing the curves");
        rc = report(out, err, &a, d, sel, nsel, &set, bo.max_seconds);
        budget_disarm();
    }
    for (slong k = 0; k < d->npoints; k++) {
        pc_free(pt[k]);
        for (int j = 0; qpt[k] && j < dim; j++)
            fmpq_clear(qpt[k] + j);
        pc_free(qpt[k]);
    }
    pc_free(qpt);
    pc_free(pt);
    for (slong k = 0; k < d->nconsts; k++)
        fmpq_clear(value + k);
    pc_free(value);
    pc_free(given);
    pc_free(sel);
    derived_free(d);
    args_clear(&a);
    return rc;
}
