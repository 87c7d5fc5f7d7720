/*
 * cmd_plot.c - `pointcalc plot FILE --at A=x,y ... -o OUT.svg`: the curves of
 * the point outputs as SVG, with the construction at --at-param
 * (docs/plot.md; the drawing is runtime/plot_sample.c and runtime/svg.c).
 *
 *   cli_derive_file_steps (with the steps for --at-param) -> lower the
 *   outputs, the params' declared ranges and the construction's points
 *   -> checks against the plan -> plot_svg -> outfile_write
 *
 * Checks happen in eval's order: option syntax (exit 2), the scheme
 * (exit 1), names and values against the scheme (exit 2); only then is the
 * SVG written (whole or not at all, when -o names a file).
 */
#include "driver/cli/cli.h"

#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

#include "base/mem.h"
#include "base/numfmt.h"
#include "codegen/lower.h"
#include "driver/cli/args.h"
#include "driver/cli/outfile.h"
#include "runtime/eval.h"
#include "runtime/plot.h"
#include "runtime/sample.h"

static const char *usage; // help_usage("plot")

/* args_usage_error with the message formatted in the C locale */
static int usage_error(FILE *err, const char *fmt, ...) PC_PRINTF(2, 3);
static int usage_error(FILE *err, const char *fmt, ...)
{
    char msg[1024];
    va_list ap;
    va_start(ap, fmt);
    pc_vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    return args_usage_error(err, usage, "%s", msg);
}

typedef struct PlotArgs {
    EvalArgs ea;       // --at, --set, --param, --output (args.h)
    const char *opath; // -o
    Assign atp;        // --at-param (name NULL: none)
    NameList aux;      // --aux NAME[,NAME...]
    int aux_given;
    const char *view, *tangents, *window, *size;
    double tangent_scale, comb_scale;
    int comb, teeth;
    long max_samples;
} PlotArgs;

static void args_clear(PlotArgs *a)
{
    eval_args_clear(&a->ea);
    pc_free(a->atp.name);
    args_names_clear(&a->aux);
}

/* a strict positive integer <= max */
static int parse_count(const char *s, long max, long *v)
{
    char *end;
    errno = 0;
    long n = strtol(s, &end, 10);
    if (end == s || *end || errno || n < 1 || n > max)
        return -1;
    *v = n;
    return 0;
}

/* plot's own options after eval's; as ArgsOption */
static int plot_option(void *ctx, int argc, char **argv, int i, FILE *err)
{
    PlotArgs *a = ctx;
    int used = eval_args_option(&a->ea, argc, argv, i, usage, err);
    if (used != 0)
        return used;
    const char *o = argv[i], *v = args_value(argc, argv, i);
    if (strcmp(o, "--comb") == 0) {
        a->comb = 1;
        return 1;
    }
    if (!v)
        return 0; // an option without its value: "incomplete"
    if (strcmp(o, "-o") == 0) {
        a->opath = v;
    } else if (strcmp(o, "--at-param") == 0) {
        const char *eq = strchr(v, '=');
        if (a->atp.name) {
            usage_error(err, "--at-param given twice");
            return -1;
        }
        if (!eq || eq == v) {
            usage_error(err, "--at-param expects PARAM=VALUE, found '%s'", v);
            return -1;
        }
        a->atp.name = pc_xstrndup(v, (size_t)(eq - v));
        a->atp.text = eq + 1;
    } else if (strcmp(o, "--aux") == 0) {
        a->aux_given = 1;
        if (*v && args_names_add(&a->aux, v) != 0) {
            usage_error(err, "--aux '%s': expected names separated by commas",
                        v);
            return -1;
        }
    } else if (strcmp(o, "--view") == 0) {
        a->view = v;
    } else if (strcmp(o, "--tangents") == 0) {
        a->tangents = v;
    } else if (strcmp(o, "--tangent-scale") == 0 ||
               strcmp(o, "--comb-scale") == 0) {
        double x;
        if (sample_number(v, &x) != 0 || !(x > 0)) {
            usage_error(err, "%s '%s': expected a positive number", o, v);
            return -1;
        }
        if (o[2] == 't')
            a->tangent_scale = x;
        else
            a->comb_scale = x;
    } else if (strcmp(o, "--comb-teeth") == 0) {
        long n;
        if (parse_count(v, PLOT_MAX_TEETH, &n) != 0) {
            usage_error(err,
                        "--comb-teeth '%s': expected a whole number from 1 "
                        "to %d",
                        v, PLOT_MAX_TEETH);
            return -1;
        }
        a->teeth = (int)n;
        a->comb = 1;
    } else if (strcmp(o, "--size") == 0) {
        a->size = v;
    } else if (strcmp(o, "--window") == 0) {
        a->window = v;
    } else if (strcmp(o, "--max-samples") == 0) {
        if (parse_count(v, PLOT_SAMPLES_LIMIT, &a->max_samples) != 0 ||
            a->max_samples < 2) {
            usage_error(err,
                        "--max-samples '%s': expected a whole number from 2 "
                        "to %d",
                        v, PLOT_SAMPLES_LIMIT);
            return -1;
        }
    } else {
        return 0;
    }
    return 2;
}

static int find_name(char *const *names, int n, const char *s)
{
    for (int i = 0; i < n; i++)
        if (strcmp(names[i], s) == 0)
            return i;
    return -1;
}

/* ---- the run --------------------------------------------------------- */

typedef struct Run {
    Derived *d;
    Plan *p;
    int nout;     // the scheme's outputs: plan outputs 0..nout-1
    int *range_o; // per param: plan output of lo (hi = lo + 1), or -1
    int *step_o;  // per step: plan output of its value, or -1
    int *arg_o;   // per step: plan output of its first arg (the others
                  // follow), or -1
    int nsel, *sel;
    int dim;
    double **pt; // per base point (owned) or NULL
    double *consts, *params;
    int sweep;
    double lo, hi;
    long initial;
    int have_at;
    double at;
    double *tangents;
    int ntangents;
    double window[4];
    int has_window;
    int width, height;
    PlotView view;
} Run;

static void run_clear(Run *r)
{
    if (r->pt)
        for (int i = 0; r->p && i < r->p->npoints; i++)
            pc_free(r->pt[i]);
    pc_free(r->pt);
    pc_free(r->range_o);
    pc_free(r->step_o);
    pc_free(r->arg_o);
    pc_free(r->sel);
    pc_free(r->consts);
    pc_free(r->params);
    pc_free(r->tangents);
    plan_free(r->p);
    derived_free(r->d);
}

/* Lowers the scheme's outputs and after them, as further outputs, the
 * declared ranges of its params (scalars) and the construction: every
 * step's value and the points it was built from. */
static Plan *lower_all(Run *r, FILE *err)
{
    Derived *d = r->d;
    slong n = d->noutputs, cap = n + 2 * d->nparams;
    for (slong i = 0; i < d->nsteps; i++)
        cap += 1 + d->steps[i].nargs;
    DerivedOutput *all = pc_xcalloc((size_t)cap + 1, sizeof *all);
    memcpy(all, d->outputs, sizeof *all * (size_t)n);
    slong m = n;
    r->range_o = pc_xmalloc(sizeof *r->range_o * (size_t)(d->nparams + 1));
    for (slong i = 0; i < d->nparams; i++) {
        r->range_o[i] = -1;
        if (!d->has_range || !d->has_range[i])
            continue;
        r->range_o[i] = (int)m;
        for (int k = 0; k < 2; k++) {
            DerivedOutput *o = &all[m++];
            o->name = d->params[i];
            o->kind = KIND_SCALAR;
            o->scalar[0] = d->range[2 * i + k];
            o->line = 1;
        }
    }
    r->step_o = pc_xmalloc(sizeof *r->step_o * (size_t)(d->nsteps + 1));
    r->arg_o = pc_xmalloc(sizeof *r->arg_o * (size_t)(d->nsteps + 1));
    for (slong i = 0; i < d->nsteps; i++) {
        const DerivedStep *st = &d->steps[i];
        r->step_o[i] = r->arg_o[i] = -1;
        if (st->pending || st->value.kind != KIND_POINT)
            continue;
        r->step_o[i] = (int)m;
        all[m++] = st->value;
        r->arg_o[i] = (int)m;
        for (slong k = 0; k < st->nargs; k++)
            all[m++] = st->args[k];
    }
    DerivedOutput *keep = d->outputs;
    d->outputs = all;
    d->noutputs = m;
    Plan *p = lower_derived(d, err);
    d->outputs = keep;
    d->noutputs = n;
    pc_free(all);
    r->nout = (int)n;
    return p;
}

/* the value of scalar plan output o at the fixed params and consts */
static double scalar_value(const Run *r, int o)
{
    const Plan *p = r->p;
    double **cols = pc_xmalloc(sizeof *cols * (size_t)(p->nparams + 1));
    for (int i = 0; i < p->nparams; i++)
        cols[i] = &r->params[i];
    double v = NAN;
    unsigned char st = 0;
    plan_eval(p, o, 1, (const double *const *)cols, r->consts,
              (const double *const *)r->pt, r->dim ? r->dim : 1, &v, &st);
    pc_free(cols);
    return st ? NAN : v;
}

/* 1 when plan output o reads const k */
static int uses_const(const Plan *p, int o, int k)
{
    unsigned char *live = pc_xmalloc((size_t)p->nins + 1);
    plan_live(p, o, live);
    int used = 0;
    for (int i = 0; i < p->nins && !used; i++)
        used = live[i] && p->ins[i].op == PLAN_INPUT &&
               p->ins[i].a == p->nparams + k;
    pc_free(live);
    return used;
}

/* the curves: the selected point outputs into r->sel */
static int setup_curves(Run *r, const PlotArgs *a, FILE *err)
{
    const Plan *p = r->p;
    /* the curves: point outputs (the scheme's outputs are the plan's first
     * nout; what lower_all adds after them is not selectable) */
    r->sel = pc_xcalloc((size_t)p->noutputs + 1, sizeof *r->sel);
    Plan view = *p;
    view.noutputs = r->nout;
    int nsel = args_select_outputs(r->sel, &a->ea.outputs, &view, usage, err);
    if (nsel < 0)
        return 2;
    for (int j = 0; j < nsel; j++) {
        int o = r->sel[j];
        if (p->outputs[o].kind == KIND_POINT)
            r->sel[r->nsel++] = o;
        else if (a->ea.outputs.n > 0)
            return usage_error(err,
                               "--output '%s' is a %s: plot draws point "
                               "outputs as curves (see --tangents for "
                               "derivatives)",
                               p->outputs[o].name,
                               kind_name(p->outputs[o].kind));
    }
    if (r->nsel == 0)
        return usage_error(err, "the scheme has no point output to draw "
                                "(its outputs are scalars or vectors)");
    return 0;
}

/* the base points (--at), one dimension for all, and the ones the curves
 * need */
static int setup_points(Run *r, const PlotArgs *a, FILE *err)
{
    const Plan *p = r->p;
    char list[512];
    /* points */
    r->pt = pc_xcalloc((size_t)p->npoints + 1, sizeof *r->pt);
    for (int i = 0; i < a->ea.nat; i++) {
        int k = find_name(p->points, p->npoints, a->ea.at[i].name);
        if (k < 0)
            return usage_error(
                err,
                "--at %s: '%s' is not a base point of the scheme (points: %s)",
                a->ea.at[i].name, a->ea.at[i].name,
                args_name_list(p->points, p->npoints, list, sizeof list));
        if (r->pt[k])
            return usage_error(err, "--at %s given twice", a->ea.at[i].name);
        long n = sample_numbers(a->ea.at[i].text, &r->pt[k]);
        if (n < 0)
            return usage_error(err,
                               "--at %s=%s: malformed coordinates; expected "
                               "numbers separated by commas",
                               a->ea.at[i].name, a->ea.at[i].text);
        if (r->dim && n != r->dim)
            return usage_error(err,
                               "--at %s has %ld coordinates but the points "
                               "before it have %d: every point must have the "
                               "same dimension",
                               a->ea.at[i].name, n, r->dim);
        r->dim = (int)n;
    }
    for (int j = 0; j < r->nsel; j++)
        for (int k = 0; k < p->npoints; k++)
            if (!r->pt[k] && plan_output_uses_point(p, r->sel[j], k))
                return usage_error(err,
                                   "missing --at %s=x,y,...: output %s "
                                   "depends on base point %s",
                                   p->points[k], p->outputs[r->sel[j]].name,
                                   p->points[k]);
    for (int j = 0; j < r->nsel; j++) {
        int pt, need = plan_output_min_dim(p, r->sel[j], &pt);
        if (need > r->dim)
            return usage_error(
                err,
                "output %s reads coordinate %d of base point %s "
                "(coord(%s, %d)), but the points have %d: give every --at "
                "point at least %d coordinates",
                p->outputs[r->sel[j]].name, need, p->points[pt], p->points[pt],
                need, r->dim, need);
    }
    return 0;
}

/* the consts given (--set); cseen[k]: const k was given */
static int setup_consts(Run *r, const PlotArgs *a, FILE *err,
                        unsigned char *cseen)
{
    const Plan *p = r->p;
    for (int i = 0; i < a->ea.nset; i++) {
        int k = find_name(p->consts, p->nconsts, a->ea.set[i].name);
        int rc = 0;
        if (k < 0)
            rc = usage_error(
                err,
                find_name(p->params, p->nparams, a->ea.set[i].name) >= 0
                    ? "--set %s: '%s' is a param; give it with "
                      "--param"
                    : "--set %s: '%s' is not a const of the "
                      "scheme",
                a->ea.set[i].name, a->ea.set[i].name);
        else if (cseen[k]++)
            rc = usage_error(err, "--set %s given twice", a->ea.set[i].name);
        else if (sample_number(a->ea.set[i].text, &r->consts[k]) != 0)
            rc = usage_error(err, "--set %s=%s: malformed number",
                             a->ea.set[i].name, a->ea.set[i].text);
        if (rc)
            return rc;
    }
    return 0;
}

/* the params given (--param): a value each, or the swept range;
 * pseen[k]: param k was given */
static int setup_params(Run *r, const PlotArgs *a, FILE *err,
                        unsigned char *pseen)
{
    const Plan *p = r->p;
    int rc = 0;
    for (int i = 0; i < a->ea.nparam && !rc; i++) {
        const char *name = a->ea.param[i].name, *text = a->ea.param[i].text;
        int k = find_name(p->params, p->nparams, name);
        if (k < 0) {
            rc = usage_error(
                err,
                find_name(p->consts, p->nconsts, name) >= 0
                    ? "--param %s: '%s' is a const; give it with --set"
                    : "--param %s: '%s' is not a param of the scheme",
                name, name);
            break;
        }
        if (pseen[k]++) {
            rc = usage_error(err, "--param %s given twice", name);
            break;
        }
        if (strchr(text, ':')) {
            /* LO:HI or LO:HI:N */
            char *t1 = pc_xstrdup(text), *c1 = strchr(t1, ':');
            *c1 = '\0';
            char *c2 = strchr(c1 + 1, ':');
            if (c2)
                *c2 = '\0';
            long n = PLOT_INITIAL;
            int ok = sample_number(t1, &r->lo) == 0 &&
                     sample_number(c1 + 1, &r->hi) == 0 &&
                     (!c2 || parse_count(c2 + 1, 100000, &n) == 0);
            pc_free(t1);
            if (!ok)
                rc = usage_error(err,
                                 "--param %s=%s: expected LO:HI or LO:HI:N "
                                 "(N initial segments, 1 to 100000)",
                                 name, text);
            else if (!(r->lo < r->hi))
                rc = usage_error(err,
                                 "--param %s=%s: the range must have LO < HI",
                                 name, text);
            else if (r->sweep >= 0)
                rc = usage_error(err,
                                 "--param %s=%s: only one param is swept "
                                 "(%s is already a range)",
                                 name, text, p->params[r->sweep]);
            else {
                r->sweep = k;
                r->initial = n;
            }
        } else if (sample_number(text, &r->params[k]) != 0) {
            rc = usage_error(err,
                             "--param %s=%s: expected a number or a range "
                             "LO:HI[:N]",
                             name, text);
        }
    }
    return rc;
}

/* the swept param when none was given a range: the one param not given
 * a value, with a declared range; else every param needs a value */
static int setup_sweep(Run *r, FILE *err, const unsigned char *pseen)
{
    const Plan *p = r->p;
    char list[512];
    int rc = 0;
    if (r->sweep < 0) {
        /* the one param not given a value */
        int nfree = 0;
        char **free_names =
            pc_xmalloc(sizeof *free_names * (size_t)(p->nparams + 1));
        for (int k = 0; k < p->nparams; k++)
            if (!pseen[k]) {
                free_names[nfree++] = p->params[k];
                r->sweep = k;
            }
        if (nfree > 1)
            rc = usage_error(
                err,
                "params %s have no value: one is swept (give "
                "it as --param NAME=LO:HI, or leave only it "
                "out), the others need --param NAME=VALUE",
                args_name_list(free_names, nfree, list, sizeof list));
        pc_free(free_names);
        if (!rc && r->sweep < 0)
            rc = usage_error(err, p->nparams == 0
                                      ? "the scheme has no param to sweep"
                                      : "no param is swept: give one as "
                                        "--param NAME=LO:HI");
        if (!rc && r->range_o[r->sweep] < 0)
            rc = usage_error(err,
                             "missing --param %s=LO:HI: the scheme declares "
                             "no range for %s",
                             p->params[r->sweep], p->params[r->sweep]);
    } else {
        for (int k = 0; k < p->nparams && !rc; k++)
            if (!pseen[k])
                rc = usage_error(err, "missing --param %s=VALUE", p->params[k]);
    }
    return rc;
}

/* a const that what is drawn reads (the curves, the range) and that was
 * not given */
static int setup_needed_consts(Run *r, FILE *err, const unsigned char *cseen,
                               const unsigned char *pseen)
{
    const Plan *p = r->p;
    int rc = 0;
    /* consts that what is drawn reads (the curves, the range) */
    for (int k = 0; k < p->nconsts && !rc; k++) {
        if (cseen[k])
            continue;
        int used = 0;
        for (int j = 0; j < r->nsel && !used; j++)
            used = uses_const(p, r->sel[j], k);
        if (!used && pseen[r->sweep] == 0 && r->range_o[r->sweep] >= 0)
            used = uses_const(p, r->range_o[r->sweep], k) ||
                   uses_const(p, r->range_o[r->sweep] + 1, k);
        if (used)
            rc = usage_error(err, "missing --set %s=VALUE", p->consts[k]);
    }
    return rc;
}

/* --at-param, the view, the tangents, the window and the canvas */
static int setup_figure(Run *r, const PlotArgs *a, FILE *err)
{
    const Plan *p = r->p;
    char msg[300];
    /* --at-param */
    if (a->atp.name) {
        if (strcmp(a->atp.name, p->params[r->sweep]) != 0)
            return usage_error(err,
                               "--at-param %s: expected the swept param %s",
                               a->atp.name, p->params[r->sweep]);
        if (sample_number(a->atp.text, &r->at) != 0)
            return usage_error(err, "--at-param %s=%s: malformed number",
                               a->atp.name, a->atp.text);
        r->have_at = 1;
    }
    /* the view, the tangents, the canvas */
    if (a->view && plot_view_parse(&r->view, a->view, msg, sizeof msg) != 0)
        return usage_error(err, "--view '%s': %s", a->view, msg);
    if (!a->view)
        plot_view_default(&r->view, r->dim);
    if (a->tangents) {
        Spec sp;
        if (sample_parse(&sp, a->tangents, msg, sizeof msg) != 0)
            return usage_error(err, "--tangents %s: %s", a->tangents, msg);
        if (sp.n > PLOT_MAX_TANGENTS) {
            sample_clear(&sp);
            return usage_error(err, "--tangents %s: at most %d values",
                               a->tangents, PLOT_MAX_TANGENTS);
        }
        r->ntangents = (int)sp.n;
        r->tangents = pc_xmalloc(sizeof *r->tangents * (sp.n + 1));
        for (size_t i = 0; i < sp.n; i++)
            r->tangents[i] = sample_value(&sp, i);
        sample_clear(&sp);
    }
    if (a->window) {
        double *v = NULL;
        long n = sample_numbers(a->window, &v);
        int ok = n == 4 && v[0] < v[2] && v[1] < v[3] &&
                 isfinite(v[2] - v[0]) && isfinite(v[3] - v[1]);
        if (ok)
            memcpy(r->window, v, sizeof r->window);
        pc_free(v);
        if (!ok)
            return usage_error(err,
                               "--window '%s': expected XMIN,YMIN,XMAX,YMAX "
                               "with XMIN < XMAX and YMIN < YMAX",
                               a->window);
        r->has_window = 1;
    }
    r->width = 720;
    if (a->size) {
        char *x = strchr(a->size, 'x');
        char *w =
            pc_xstrndup(a->size, x ? (size_t)(x - a->size) : strlen(a->size));
        long W, H = 0;
        int ok = parse_count(w, 10000, &W) == 0 && W >= 16 &&
                 (!x || (parse_count(x + 1, 10000, &H) == 0 && H >= 16));
        pc_free(w);
        if (!ok)
            return usage_error(err,
                               "--size '%s': expected W or WxH in pixels, "
                               "16 to 10000",
                               a->size);
        r->width = (int)W;
        r->height = (int)H;
    }
    return 0;
}

static int setup(Run *r, const PlotArgs *a, FILE *err)
{
    const Plan *p = r->p;
    int rc = setup_curves(r, a, err);
    if (rc)
        return rc;
    rc = setup_points(r, a, err);
    if (rc)
        return rc;
    /* consts */
    r->consts = pc_xcalloc((size_t)p->nconsts + 1, sizeof *r->consts);
    unsigned char *cseen = pc_xcalloc((size_t)p->nconsts + 1, 1);
    rc = setup_consts(r, a, err, cseen);
    if (rc) {
        pc_free(cseen);
        return rc;
    }
    /* params: one swept (LO:HI[:N], or the one not given and declared with
     * a range), the others one value each */
    r->params = pc_xcalloc((size_t)p->nparams + 1, sizeof *r->params);
    unsigned char *pseen = pc_xcalloc((size_t)p->nparams + 1, 1);
    r->sweep = -1;
    r->initial = PLOT_INITIAL;
    rc = setup_params(r, a, err, pseen);
    if (!rc)
        rc = setup_sweep(r, err, pseen);
    if (!rc)
        rc = setup_needed_consts(r, err, cseen, pseen);
    pc_free(cseen);
    if (!rc && !pseen[r->sweep]) {
        r->lo = scalar_value(r, r->range_o[r->sweep]);
        r->hi = scalar_value(r, r->range_o[r->sweep] + 1);
        if (!(isfinite(r->lo) && isfinite(r->hi) && r->lo < r->hi))
            rc = usage_error(err,
                             "the declared range of %s is [%.17g, %.17g] "
                             "here; give --param %s=LO:HI with LO < HI",
                             p->params[r->sweep], r->lo, r->hi,
                             p->params[r->sweep]);
    }
    pc_free(pseen);
    if (rc)
        return rc;
    if (r->dim == 0)
        return usage_error(err, "give the base points with --at A=x,y,...");
    return setup_figure(r, a, err);
}

typedef struct Construction {
    PlotMark *marks;
    int nmarks;
    PlotLine *lines;
    int nlines;
    double *xyz; // the marks' coordinates, dim each (owned)
} Construction;

static void construction_clear(Construction *c)
{
    pc_free(c->marks);
    pc_free(c->lines);
    pc_free(c->xyz);
}

/* 1 when every base point plan output o reads is given */
static int points_given(const Run *r, int o)
{
    for (int k = 0; k < r->p->npoints; k++)
        if (!r->pt[k] && plan_output_uses_point(r->p, o, k))
            return 0;
    return plan_output_min_dim(r->p, o, NULL) <= r->dim;
}

static int find_mark(const Construction *c, const char *name)
{
    for (int i = 0; i < c->nmarks; i++)
        if (c->marks[i].name && strcmp(c->marks[i].name, name) == 0)
            return i;
    return -1;
}

/* a mark at plan output o's value at --at-param; -1 when it is not
 * drawable there */
static int add_mark(Construction *c, const Run *r, const PlotEnv *env, int o,
                    const char *name, PlotMarkKind kind, int curve)
{
    double *P = c->xyz + (size_t)c->nmarks * (size_t)r->dim;
    if (!points_given(r, o) || plot_jet(env, o, r->at, P, NULL, NULL) != 0)
        return -1;
    PlotMark *m = &c->marks[c->nmarks];
    m->name = name;
    m->at = P;
    m->kind = kind;
    m->curve = curve;
    return c->nmarks++;
}

static int construction(Construction *c, const Run *r, const PlotArgs *a,
                        const PlotEnv *env, FILE *err)
{
    const Plan *p = r->p;
    const Derived *d = r->d;
    memset(c, 0, sizeof *c);
    size_t cap = (size_t)p->npoints + (size_t)r->nsel + 1;
    for (slong i = 0; i < d->nsteps; i++)
        cap += 1 + (size_t)d->steps[i].nargs;
    c->marks = pc_xcalloc(cap, sizeof *c->marks);
    c->xyz = pc_xcalloc(cap * (size_t)r->dim, sizeof *c->xyz);
    c->lines = pc_xcalloc(2 * (size_t)d->nsteps + 1, sizeof *c->lines);
    /* --aux names point definitions */
    for (int i = 0; i < a->aux.n; i++) {
        int found = 0;
        for (slong k = 0; k < d->nsteps && !found; k++)
            found = r->step_o[k] >= 0 &&
                    strcmp(d->steps[k].value.name, a->aux.v[i]) == 0;
        if (!found)
            return usage_error(err,
                               "--aux '%s' is not a point definition of the "
                               "scheme",
                               a->aux.v[i]);
    }
    if (a->aux_given && !r->have_at)
        return usage_error(err, "--aux needs --at-param %s=VALUE",
                           p->params[r->sweep]);
    for (int k = 0; k < p->npoints; k++)
        if (r->pt[k]) {
            PlotMark *m = &c->marks[c->nmarks++];
            m->name = p->points[k];
            m->at = r->pt[k];
            m->kind = PLOT_BASE;
            m->curve = -1;
        }
    if (!r->have_at)
        return 0;
    for (int j = 0; j < r->nsel; j++)
        add_mark(c, r, env, r->sel[j], p->outputs[r->sel[j]].name, PLOT_CURRENT,
                 j);
    for (slong k = 0; k < d->nsteps; k++) {
        const char *name = d->steps[k].value.name;
        int want = !a->aux_given;
        for (int i = 0; i < a->aux.n && !want; i++)
            want = strcmp(a->aux.v[i], name) == 0;
        if (r->step_o[k] < 0 || !want || find_mark(c, name) >= 0)
            continue;
        if (add_mark(c, r, env, r->step_o[k], name, PLOT_AUX, -1) < 0)
            pc_fprintf(err,
                       "pointcalc: plot: %s is not drawn at %s=%.17g (%s)\n",
                       name, p->params[r->sweep], r->at,
                       points_given(r, r->step_o[k])
                           ? "a pole, undefined or not finite there"
                           : "it needs a base point not given with --at");
    }
    /* lines: along and divide (P, Q and the point), meet of two lines
     * (each line with the point) */
    for (slong k = 0; k < d->nsteps; k++) {
        const DerivedStep *st = &d->steps[k];
        int me = r->step_o[k] >= 0 ? find_mark(c, st->value.name) : -1;
        if (me < 0)
            continue;
        int groups[2][2], ng = 0;
        if ((st->op == STEP_ALONG || st->op == STEP_DIVIDE) && st->nargs == 2) {
            groups[0][0] = 0;
            groups[0][1] = 1;
            ng = 1;
        } else if (st->op == STEP_MEET && st->nfirst == 2) {
            groups[ng][0] = 0;
            groups[ng++][1] = 1;
            if (st->nargs == 4) {
                groups[ng][0] = 2;
                groups[ng++][1] = 3;
            }
        }
        for (int gi = 0; gi < ng; gi++) {
            PlotLine *L = &c->lines[c->nlines];
            L->n = 0;
            for (int e = 0; e < 2; e++) {
                const DerivedOutput *arg = &st->args[groups[gi][e]];
                int mi = find_mark(c, arg->name);
                if (mi < 0 && derived_find_point(d, arg->name) < 0 &&
                    derived_find_output(d, arg->name) < 0) {
                    /* an expression, not a name: an unlabelled point */
                    int named = 0;
                    for (slong q = 0; q < d->nsteps && !named; q++)
                        named = strcmp(d->steps[q].value.name, arg->name) == 0;
                    if (!named)
                        mi = add_mark(c, r, env, r->arg_o[k] + groups[gi][e],
                                      NULL, PLOT_AUX, -1);
                }
                if (mi >= 0)
                    L->m[L->n++] = mi;
            }
            if (L->n == 2) {
                L->m[L->n++] = me;
                c->nlines++;
            }
        }
    }
    return 0;
}

int cli_plot(int argc, char **argv, FILE *out, FILE *err)
{
    PlotArgs a;
    memset(&a, 0, sizeof a);
    eval_args_init(&a.ea);
    a.tangent_scale = 1;
    a.max_samples = PLOT_MAX_SAMPLES;
    a.teeth = 100;
    usage = help_usage("plot");
    BudgetOptions bo;
    const char *file;
    int rc = args_parse(argc, argv, usage, &bo, &file, plot_option, &a, err);
    if (rc) {
        args_clear(&a);
        return rc;
    }
    if (a.opath && outfile_same(a.opath, file)) {
        rc = usage_error(err,
                         "-o '%s' is the scheme itself; it would be "
                         "overwritten",
                         a.opath);
        args_clear(&a);
        return rc;
    }
    Run r;
    memset(&r, 0, sizeof r);
    /* the steps only for the construction */
    r.d = cli_derive_file_steps(file, &bo, a.atp.name != NULL, err, &rc);
    if (!r.d) {
        args_clear(&a);
        return rc;
    }
    budget_arm(bo.max_seconds, bo.max_memory);
    cli_mark_file("lowering the equations to numbers"); /* at each output */
    r.p = lower_all(&r, err);
    budget_disarm(); /* the drawing takes what the budget of samples allows */
    cli_mark_file("drawing the plot");
    if (!r.p) {
        run_clear(&r);
        args_clear(&a);
        return 1;
    }
    rc = setup(&r, &a, err);
    if (rc) {
        run_clear(&r);
        args_clear(&a);
        return rc;
    }
    const Plan *p = r.p;
    PlotSpec s;
    plot_spec_default(&s);
    s.env.plan = p;
    s.env.param = r.sweep;
    s.env.params = r.params;
    s.env.consts = r.consts;
    s.env.points = (const double *const *)r.pt;
    s.env.dim = r.dim;
    s.curves = r.sel;
    s.ncurves = r.nsel;
    s.lo = r.lo;
    s.hi = r.hi;
    s.view = r.view;
    s.lim.initial = (int)r.initial;
    s.lim.max_samples = (size_t)a.max_samples;
    if (s.lim.max_samples < (size_t)r.initial + 1)
        s.lim.initial = (int)s.lim.max_samples - 1;
    s.tangents = r.tangents;
    s.ntangents = r.ntangents;
    s.tangent_scale = a.tangent_scale;
    s.comb = a.comb ? a.teeth : 0;
    s.comb_scale = a.comb_scale;
    s.width = r.width;
    s.height = r.height;
    s.window = r.has_window ? r.window : NULL;
    /* marks: the base points given, the curves' points at --at-param, the
     * construction's points there; its lines */
    Construction c;
    rc = construction(&c, &r, &a, &s.env, err);
    if (rc) {
        construction_clear(&c);
        run_clear(&r);
        args_clear(&a);
        return rc;
    }
    PlotMark *marks = c.marks;
    int nm = c.nmarks;
    s.lines = c.lines;
    s.nlines = c.nlines;
    s.marks = marks;
    s.nmarks = nm;
    char *title = NULL;
    size_t tlen = 0;
    FILE *tm = pc_xopen_memstream(&title, &tlen);
    pc_fprintf(tm, "%s: ", p->name);
    for (int j = 0; j < r.nsel; j++)
        fprintf(tm, "%s%s", j ? ", " : "", p->outputs[r.sel[j]].name);
    pc_fprintf(tm, " over %s in [%.6g, %.6g]", p->params[r.sweep], r.lo, r.hi);
    if (r.have_at)
        pc_fprintf(tm, ", construction at %s = %.6g", p->params[r.sweep], r.at);
    pc_xclose_memstream(tm);
    s.title = title;

    char *svg = NULL;
    size_t len = 0;
    FILE *m = pc_xopen_memstream(&svg, &len);
    PlotStats st;
    memset(&st, 0, sizeof st);
    plot_svg(m, &s, &st);
    pc_xclose_memstream(m);
    rc = outfile_write(a.opath, svg, len, out, err);
    if (rc == 0 && st.samples == 0)
        fprintf(err, "pointcalc: plot: nothing of the curves is drawable "
                     "over the range (every sample a pole, undefined or not "
                     "finite)\n");
    pc_free(svg);
    pc_free(title);
    construction_clear(&c);
    run_clear(&r);
    args_clear(&a);
    return rc;
}
