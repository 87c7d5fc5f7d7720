/*
 * cmd_fit.c - `pointcalc fit --target 'EXPR' --on LO,HI --nodes N
 * [--samples M] [--starts K] [--format text|json]`, `pointcalc fit
 * --data FILE.csv ...` and `pointcalc fit SCHEME.pcs` (its fit
 * statements, fit_scheme.c): the interpolation
 * curve through N nodes on the target whose inner nodes' abscissas give
 * the least mean squared deviation (monograph chapter 5, docs/fit.md).
 *
 *   options -> fit_new (derive target and curve, fit.c) -> fit_run (LM
 *   from every start) -> the nodes, MSE, max error and x(t), y(t)
 *
 * A fit that does not converge is an error (exit 1) that says what was
 * reached; nothing is written to stdout then.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/json.h"
#include "base/mem.h"
#include "base/numfmt.h"
#include "driver/cli/args.h"
#include "driver/cli/fit.h"

typedef enum FitFormat { FIT_TEXT, FIT_JSON } FitFormat;

typedef struct FitArgs {
    const char *target;
    const char *file;                     // the scheme form: pointcalc fit FILE
    const char *data;                     // --data FILE.csv
    const char *plot;                     // --plot FILE.svg
    const char *sets[BUDGET_MAX_DEFINES]; // --set NAME=VALUE (scheme form)
    int nsets;
    int has_on, has_nodes;
    FitOptions o;
    FitFormat format;
    const char *usage;
} FitArgs;

/* a whole-field integer into *v; -1 when it is not one */
static int parse_int(const char *s, int *v)
{
    char *end;
    long l = strtol(s, &end, 10);
    if (end == s || *end || l < -1000000000L || l > 1000000000L)
        return -1;
    *v = (int)l;
    return 0;
}

static int parse_on(const char *s, FitOptions *o)
{
    char *end, *end2;
    o->lo = pc_strtod(s, &end);
    if (end == s || *end != ',')
        return -1;
    o->hi = pc_strtod(end + 1, &end2);
    return end2 == end + 1 || *end2 ? -1 : 0;
}

/* fit's own options: as ArgsOption */
static int fit_option(FitArgs *a, int argc, char **argv, int i, FILE *err)
{
    const char *opt = argv[i], *v = args_value(argc, argv, i);
    int bad = 0;
    if (strcmp(opt, "--target") && strcmp(opt, "--on") &&
        strcmp(opt, "--nodes") && strcmp(opt, "--samples") &&
        strcmp(opt, "--starts") && strcmp(opt, "--max-iter") &&
        strcmp(opt, "--format") && strcmp(opt, "--data") &&
        strcmp(opt, "--plot") && strcmp(opt, "--set"))
        return 0;
    if (!v) {
        args_usage_error(err, a->usage, "%s needs a value", opt);
        return -1;
    }
    if (strcmp(opt, "--data") == 0) {
        a->data = v;
    } else if (strcmp(opt, "--plot") == 0) {
        a->plot = v;
    } else if (strcmp(opt, "--set") == 0) {
        const char *eq = strchr(v, '=');
        char *end = NULL;
        double val = eq ? pc_strtod(eq + 1, &end) : 0;
        if (!eq || eq == v || !end || end == eq + 1 || *end || !isfinite(val) ||
            a->nsets == BUDGET_MAX_DEFINES) {
            args_usage_error(err, a->usage,
                             "bad value '%s' for --set (expected NAME=NUMBER, "
                             "at most %d)",
                             v, BUDGET_MAX_DEFINES);
            return -1;
        }
        a->sets[a->nsets++] = v;
    } else if (strcmp(opt, "--target") == 0) {
        a->target = v;
        bad = v[strcspn(v, "\n\r")] != '\0' || !v[strspn(v, " \t")];
    } else if (strcmp(opt, "--on") == 0) {
        a->has_on = 1;
        bad = parse_on(v, &a->o);
    } else if (strcmp(opt, "--nodes") == 0) {
        a->has_nodes = 1;
        bad = parse_int(v, &a->o.nodes);
    } else if (strcmp(opt, "--samples") == 0) {
        bad = parse_int(v, &a->o.samples);
    } else if (strcmp(opt, "--starts") == 0) {
        bad = parse_int(v, &a->o.starts);
    } else if (strcmp(opt, "--max-iter") == 0) {
        bad = parse_int(v, &a->o.max_iter) || a->o.max_iter < 1;
    } else if (strcmp(v, "text") == 0 || strcmp(v, "json") == 0) {
        a->format = strcmp(v, "json") == 0 ? FIT_JSON : FIT_TEXT;
    } else {
        args_usage_error(err, a->usage,
                         "unknown format '%s'; expected text or json", v);
        return -1;
    }
    if (bad) {
        args_usage_error(err, a->usage, "bad value '%s' for %s%s", v, opt,
                         strcmp(opt, "--on") == 0 ? " (expected LO,HI)"
                         : strcmp(opt, "--target") == 0
                             ? " (expected one expression in x, one line)"
                             : " (expected an integer)");
        return -1;
    }
    return 2;
}

static int fit_option_cb(void *ctx, int argc, char **argv, int i, FILE *err)
{
    return fit_option(ctx, argc, argv, i, err);
}

static int parse_args(FitArgs *a, BudgetOptions *b, int argc, char **argv,
                      FILE *err)
{
    int rc =
        args_scan(argc, argv, a->usage, b, &a->file, fit_option_cb, a, err);
    if (rc)
        return rc;
    if (a->file && (a->target || a->has_on || a->has_nodes))
        return args_usage_error(err, a->usage,
                                "a scheme FILE says its curve, target and "
                                "interval: no --target, --on or --nodes");
    if (a->file) {
        a->o.sets = a->sets;
        a->o.nsets = a->nsets;
        a->o.defines = b->defines;
        a->o.ndefines = b->ndefines;
        return 0;
    }
    if (a->nsets || b->ndefines)
        return args_usage_error(err, a->usage,
                                "--set and -D give a scheme FILE's consts and "
                                "ints; the --target form has none");
    if (a->target && a->data)
        return args_usage_error(err, a->usage,
                                "--target and --data: expected one target");
    if ((!a->target && !a->data) || (!a->has_on && !a->data) || !a->has_nodes)
        return args_usage_error(err, a->usage, "fit needs %s",
                                !a->target && !a->data
                                    ? "FILE, --target 'EXPR' or --data FILE"
                                : !a->has_nodes ? "--nodes N"
                                                : "--on LO,HI");
    return 0;
}

/* c[j] = the coefficient of t^j in sum_k v_k phi_k(t) */
static void poly_of(double *c, const Fit *f, const double *v)
{
    for (int j = 0; j < f->n; j++) {
        double s = 0;
        for (int k = 0; k < f->n; k++)
            s += v[k] * f->coef[k * f->n + j];
        c[j] = s;
    }
}

/* "22.886*t^5 - 57.215*t^4 + ... - 1", highest power first, zero
 * coefficients left out */
static void print_poly(FILE *out, const double *c, int n)
{
    int first = 1;
    for (int j = n - 1; j >= 0; j--) {
        if (c[j] == 0)
            continue;
        double a = first ? c[j] : c[j] < 0 ? -c[j] : c[j];
        if (!first)
            fputs(c[j] < 0 ? " - " : " + ", out);
        pc_fprintf(out, "%.9g", a);
        if (j >= 1)
            fputs(j > 1 ? "*t^" : "*t", out);
        if (j > 1)
            fprintf(out, "%d", j);
        first = 0;
    }
    if (first)
        fputc('0', out);
}

static void json_array(FILE *out, const double *v, int n)
{
    fputc('[', out);
    for (int k = 0; k < n; k++) {
        if (k)
            fputs(", ", out);
        json_number(out, v[k]);
    }
    fputc(']', out);
}

/* f at the nodes (the y_k) into y */
static void node_values(Fit *f, const FitResult *r, double *y)
{
    double *res = pc_xmalloc(sizeof *res * f->ns);
    fit_residuals_x(f, r->nodes + 1, res, NULL);
    memcpy(y, f->fx + f->ns, sizeof *y * (size_t)f->n);
    pc_free(res);
}

static void print_json(FILE *out, const FitInfo *in, Fit *f, const FitResult *r,
                       const double *y, const double *cx, const double *cy)
{
    fputs("{\"target\": ", out);
    json_string(out, in->target);
    if (in->curve) {
        fputs(", \"curve\": ", out);
        json_string(out, in->curve);
    }
    fputs(", \"on\": ", out);
    double on[2] = {f->o.lo, f->o.hi};
    json_array(out, on, 2);
    fprintf(out, ", \"samples\": %d, \"nodes\": ", f->o.samples);
    json_array(out, r->nodes, f->n);
    fputs(", \"values\": ", out);
    json_array(out, y, f->n);
    fputs(", \"mse\": ", out);
    json_number(out, r->mse);
    fputs(", \"max_error\": ", out);
    json_number(out, r->max_error);
    fputs(", \"max_error_t\": ", out);
    json_number(out, r->max_error_t);
    fprintf(out, ", \"iterations\": %d, \"evaluations\": %d, \"start\": ",
            r->lsq.iterations, r->lsq.evaluations);
    json_string(out, r->start);
    fprintf(out, ", \"starts\": %d, \"joined\": %d, \"stop\": ", r->starts_run,
            r->starts_joined);
    json_string(out, lsq_stop_text(r->lsq.stop));
    fputs(", \"start_mse\": {\"chebyshev\": ", out);
    json_number(out, r->start_mse[0]);
    fputs(", \"uniform\": ", out);
    json_number(out, r->start_mse[1]);
    fputs("}, \"chebyshev_lagrange_mse\": ", out);
    json_number(out, r->cheb_lagrange_mse);
    if (f->coef) {
        fputs(", \"x_coefficients\": ", out);
        json_array(out, cx, f->n);
        fputs(", \"y_coefficients\": ", out);
        json_array(out, cy, f->n);
    } else if (in->point_eq) {
        fputs(", \"point_equation\": ", out);
        json_string(out, in->point_eq);
    }
    fputs("}\n", out);
}

static void print_text(FILE *out, const FitInfo *in, Fit *f, const FitResult *r,
                       const double *y, const double *cx, const double *cy)
{
    if (in->curve)
        fprintf(out, "fit %s to %s\n", in->curve, in->target);
    pc_fprintf(out, "target: %s on [%.17g, %.17g], %d nodes, m = %d\n",
               in->target, f->o.lo, f->o.hi, f->n, f->o.samples);
    fputs("nodes:", out);
    for (int k = 0; k < f->n; k++)
        pc_fprintf(out, "%s %.9g", k ? "," : "", r->nodes[k]);
    pc_fprintf(out, "\nMSE: %.6g\nmax error: %.6g at t = %.6g\n", r->mse,
               r->max_error, r->max_error_t);
    pc_fprintf(out,
               "start: %s (%d starts, %d joined its basin; %d iterations, "
               "stopped: %s)\n"
               "baseline: Lagrange at %d Chebyshev nodes, MSE %.6g\n",
               r->start, r->starts_run, r->starts_joined, r->lsq.iterations,
               lsq_stop_text(r->lsq.stop), f->n, r->cheb_lagrange_mse);
    fputs("M = ", out);
    for (int k = 0; k < f->n; k++)
        fprintf(out, "%sphi_%d*M_%d", k ? " + " : "", k + 1, k + 1);
    fputs(", M_k = (x_k, f(x_k)):\n", out);
    for (int k = 0; k < f->n; k++)
        pc_fprintf(out, "  M_%d = (%.9g, %.9g)\n", k + 1, r->nodes[k], y[k]);
    if (!f->coef) {
        fprintf(out,
                "x(t), y(t): the weights are not polynomials in t; "
                "the curve:\n%s",
                in->point_eq ? in->point_eq : "?\n");
        return;
    }
    fputs("x(t) = ", out);
    print_poly(out, cx, f->n);
    fputs("\ny(t) = ", out);
    print_poly(out, cy, f->n);
    fputc('\n', out);
}

/* what a fit that did not converge reached, on err */
static void not_converged(FILE *err, const Fit *f, const FitResult *r)
{
    if (r->lsq.stop == LSQ_STOP_EVAL) {
        fputs("pointcalc: fit: no start could be evaluated: the target or "
              "its derivative is undefined on the curve\n",
              err);
        return;
    }
    pc_fprintf(err,
               "pointcalc: fit: did not converge: %s after %d iterations "
               "(best start: %s); reached MSE %.6g, max gradient %.3g, nodes",
               r->lsq.stop == LSQ_STOP_CALLER
                   ? "every start ran into two nodes merging (within 1e-8 "
                     "of the interval: fewer nodes fit better)"
                   : lsq_stop_text(r->lsq.stop),
               r->lsq.iterations, r->start, r->mse, r->lsq.gnorm);
    for (int k = 0; k < f->n; k++)
        pc_fprintf(err, "%s %.9g", k ? "," : "", r->nodes[k]);
    fputc('\n', err);
}

/* where the reports go */
typedef struct FitOut {
    FILE *out, *err;
    FitFormat format;
    const char *plot; // --plot FILE.svg: the first fit's picture; the k-th
    int nfit;         // (k >= 2) goes to FILE-k.svg
} FitOut;

/* the picture's path of the current fit */
static char *plot_path(const FitOut *o)
{
    if (o->nfit <= 1)
        return pc_xstrdup(o->plot);
    size_t n = strlen(o->plot);
    int svg = n >= 4 && strcmp(o->plot + n - 4, ".svg") == 0;
    return pc_xasprintf("%.*s-%d%s", (int)(svg ? n - 4 : n), o->plot, o->nfit,
                        svg ? ".svg" : "");
}

/* runs f and prints what it found (a FitReport) */
static int run_and_print(void *ctx, Fit *f, const FitInfo *info)
{
    FitOut *o = ctx;
    FitResult r;
    o->nfit++;
    int rc = fit_run(f, &r);
    if (rc) {
        not_converged(o->err, f, &r);
    } else {
        double *y = pc_xmalloc(sizeof *y * (size_t)f->n * 3);
        double *cx = y + f->n, *cy = cx + f->n;
        node_values(f, &r, y);
        if (f->coef) {
            poly_of(cx, f, r.nodes);
            poly_of(cy, f, y);
        }
        if (o->plot) { // before stdout: a picture that fails is exit 1
            char *path = plot_path(o);
            rc = fit_plot_svg(path, f, &r, y, cx, cy, o->err);
            pc_free(path);
        }
        if (rc == 0 && o->format == FIT_JSON)
            print_json(o->out, info, f, &r, y, cx, cy);
        else if (rc == 0)
            print_text(o->out, info, f, &r, y, cx, cy);
        pc_free(y);
    }
    fit_result_clear(&r);
    return rc;
}

int cli_fit(int argc, char **argv, FILE *out, FILE *err)
{
    FitArgs a = {.o = {.samples = 100, .starts = 8, .lo = NAN, .hi = NAN},
                 .format = FIT_TEXT,
                 .usage = help_usage("fit")};
    BudgetOptions b;
    int rc = parse_args(&a, &b, argc, argv, err);
    if (rc)
        return rc;
    FitOut fo = {out, err, a.format, a.plot, 0};
    budget_arm(b.max_seconds, b.max_memory);
    if (a.file) {
        rc = fit_scheme_run(a.file, a.data, &a.o, run_and_print, &fo, err);
        budget_disarm();
        return rc;
    }
    Fit *f = NULL;
    if (a.data) {
        FitTarget t;
        double *phi = NULL, *coef = NULL;
        rc = 1;
        if (fit_target_data(&t, a.data, &a.o, err) == 0 &&
            (rc = fit_check_options(&a.o, err) ? 2 : 1) == 1 &&
            fit_lagrange_curve(a.o.nodes, (size_t)a.o.samples + 1, &phi, &coef,
                               err) == 0)
            f = fit_new_from(&a.o, &t, phi, coef, 1, err, &rc);
        else {
            fit_spline_free(t.spline);
            pc_free(phi);
            pc_free(coef);
        }
    } else {
        f = fit_new(a.target, &a.o, err, &rc);
    }
    budget_disarm();
    if (!f)
        return rc;
    FitInfo info = {.target = a.data ? a.data : a.target};
    rc = run_and_print(&fo, f, &info);
    fit_free(f);
    return rc;
}

const char fit_help[] = FIT_USAGE
    "\n"
    "Approximation with optimal nodes (monograph chapter 5, docs/fit.md): the\n"
    "interpolation curve through N nodes M_k = (x_k, f(x_k)) at t = k/(N-1),\n"
    "x(t) = sum x_k phi_k(t), y(t) = sum f(x_k) phi_k(t), whose inner nodes'\n"
    "abscissas minimise the MSE  sum (f(x(t_i)) - y(t_i))^2 / (m + 1)  over\n"
    "t_i = i/m, i = 0..m; the end nodes are LO and HI.  Levenberg-Marquardt\n"
    "with the exact Jacobian (f' by diff), from Chebyshev, uniform and K\n"
    "seeded random starts; the best wins.\n"
    "\n"
    "  SCHEME.pcs          run the scheme's statements 'fit X to f on [LO, "
    "HI]\n"
    "                      [samples M]': X its curve through its base points,\n"
    "                      f a scalar definition in one param\n"
    "  --target 'EXPR'     f, a scalar expression in x (1/(1 + 25*x^2))\n"
    "  --data FILE.csv     f, the natural cubic spline through x,y rows "
    "(header\n"
    "                      optional, x increasing); --on defaults to its "
    "ends\n"
    "  --on LO,HI          the interval; f must be defined on all of it\n"
    "  --nodes N           N >= 3 nodes (the curve has order N - 1)\n"
    "  --samples M         m (default 100)\n"
    "  --starts K          random starts after the two fixed ones (default "
    "8)\n"
    "  --max-iter I        Levenberg-Marquardt iterations a start (default "
    "3000)\n"
    "  --set NAME=VALUE    a value for the scheme's const NAME (repeatable;\n"
    "                      every const needs one); -D NAME=INT sets an int\n"
    "  --plot FILE.svg     the picture: f, the curve and its nodes (a "
    "scheme's\n"
    "                      second fit statement to FILE-2.svg, and so on)\n"
    "  --format text|json  text: nodes, MSE, max error, x(t) and y(t); json:\n"
    "                      \"nodes\", \"mse\", \"max_error\", \"iterations\", "
    "\"start\", ...\n"
    "  --max-seconds S, --max-memory SIZE  the budget of the derivations\n"
    "\nExit status: 0 success, 1 an error in the target or a fit that does "
    "not\nconverge, 2 a usage error.\n";
