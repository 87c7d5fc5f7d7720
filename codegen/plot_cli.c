/*
 * plot_cli.c - `pointcalc plot`: options, the scheme, and runtime/plot.c.
 *
 *   derive_file -> (outputs + param ranges + construction steps) ->
 *   lower_derived -> plot_svg -> OUT.svg
 *
 * Checks happen in eval's order: option syntax (exit 2), the scheme
 * (exit 1), names and values against the scheme (exit 2); only then is the
 * SVG written (atomically, when -o names a file).
 */
#include "codegen/plot_cli.h"

#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "codegen/lower.h"
#include "compiler/budget.h"
#include "compiler/derive.h"
#include "compiler/mem.h"
#include "compiler/numfmt.h"
#include "runtime/eval.h"
#include "runtime/plot.h"
#include "runtime/sample.h"

const char plot_usage[] =
    "usage: pointcalc plot FILE --at A=x,y[,z...] ... [--set k=VALUE ...]\n"
    "                      [--param t=LO:HI[:N] | u=VALUE ...] "
    "[--output NAME[,NAME...]] ...\n"
    "                      [-o OUT.svg] [--at-param t=VALUE [--aux "
    "NAME[,NAME...]]]\n"
    "                      [--view xy|xz|yz|iso|AZ,EL]"
    "\n"
    "                      [--tangents SPEC] [--tangent-scale S] [--comb] "
    "[--comb-teeth N]\n"
    "                      [--comb-scale S] [--size W[xH]] "
    "[--window X0,Y0,X1,Y1] [--max-samples N]\n";

const char plot_help_text[] =
    "\n"
    "Draws the curves of the point outputs over the swept param's range as "
    "SVG,\n"
    "the base points labelled, and at --at-param the construction.\n"
    "\n"
    "  --at A=x,y,...      the coordinates of base point A (every point the "
    "same\n"
    "                      dimension; 3 and more are projected, see --view)\n"
    "  --set k=VALUE       the value of const k\n"
    "  --param t=LO:HI[:N] the swept param and its range (default: the range "
    "the\n"
    "                      scheme declares; N initial segments, default 64)\n"
    "  --param u=VALUE     the value of a param that is not swept\n"
    "  --output NAMES      which point outputs, repeatable or comma-separated "
    "(default:\n"
    "                      all)\n"
    "  -o OUT.svg          write the SVG there (default: stdout)\n"
    "  --at-param t=VALUE  draw the construction there: its points and "
    "lines\n"
    "  --aux NAMES         which of its points (default: every point "
    "definition)\n"
    "  --view V            xy, xz, yz, iso (default in 3D) or "
    "AZIMUTH,ELEVATION\n"
    "  --tangents SPEC     tangent vectors dM/dt at these param values\n"
    "  --tangent-scale S   drawn as S*dM/dt (default 1)\n"
    "  --comb              the curvature comb (--comb-teeth N, default 100; "
    "--comb-scale S)\n"
    "  --size W[xH]        pixels (default 720 wide)\n"
    "  --window X0,Y0,X1,Y1  the window in projected coordinates (default: "
    "fitted)\n"
    "  --max-samples N     the sample budget per curve (default 4000)\n"
    "\nPoles are cut, never joined (docs/plot.md).\n";

static int usage_error(FILE *err, const char *fmt, ...) PC_PRINTF(2, 3);
static int usage_error(FILE *err, const char *fmt, ...)
{
    va_list ap;
    fputs("pointcalc: ", err);
    va_start(ap, fmt);
    pc_vfprintf(err, fmt, ap); /* numbers in the C locale */
    va_end(ap);
    fprintf(err, "\n%s", plot_usage);
    return 2;
}

typedef struct Assign {
    char *name;       // owned
    const char *text; // after '=' (argv)
} Assign;

typedef struct PlotArgs {
    BudgetOptions budget;
    const char *file, *opath;
    char **outputs;
    int noutputs;
    int nat, nset, nparam;
    Assign *at, *set, *param;
    Assign atp; // --at-param (name NULL: none)
    const char *view, *tangents, *window, *size;
    char **aux; // --aux NAME[,NAME...]: the construction's points drawn
    int naux, aux_given;
    double tangent_scale, comb_scale;
    int comb, teeth;
    long max_samples;
} PlotArgs;

static void args_clear(PlotArgs *a)
{
    for (int i = 0; i < a->nat; i++)
        free(a->at[i].name);
    for (int i = 0; i < a->nset; i++)
        free(a->set[i].name);
    for (int i = 0; i < a->nparam; i++)
        free(a->param[i].name);
    free(a->at);
    free(a->set);
    free(a->param);
    free(a->atp.name);
    for (int i = 0; i < a->noutputs; i++)
        free(a->outputs[i]);
    free(a->outputs);
    for (int i = 0; i < a->naux; i++)
        free(a->aux[i]);
    free(a->aux);
}

static int split_assign(Assign *x, const char *arg)
{
    const char *eq = strchr(arg, '=');
    if (!eq || eq == arg)
        return -1;
    x->name = pc_xstrndup(arg, (size_t)(eq - arg));
    x->text = eq + 1;
    return 0;
}

static int push_assign(Assign **list, int *n, const char *arg)
{
    Assign x;
    if (split_assign(&x, arg) != 0)
        return -1;
    *list = pc_xrealloc(*list, sizeof **list * (size_t)(*n + 1));
    (*list)[(*n)++] = x;
    return 0;
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

static int parse_args(PlotArgs *a, int argc, char **argv, FILE *err)
{
    memset(a, 0, sizeof *a);
    budget_options_default(&a->budget);
    a->tangent_scale = 1;
    a->max_samples = PLOT_MAX_SAMPLES;
    a->teeth = 100;
    for (int i = 1; i < argc; i++) {
        const char *o = argv[i];
        int has = i + 1 < argc;
        int used = budget_parse_option(&a->budget, argc, argv, i, err);
        if (used < 0)
            return 2;
        if (used > 0) {
            i += used - 1;
        } else if ((strcmp(o, "--at") == 0 || strcmp(o, "--set") == 0 ||
                    strcmp(o, "--param") == 0) &&
                   has) {
            const char *v = argv[++i];
            Assign **list = o[2] == 'a'   ? &a->at
                            : o[2] == 's' ? &a->set
                                          : &a->param;
            int *n = o[2] == 'a' ? &a->nat : o[2] == 's' ? &a->nset : &a->nparam;
            if (push_assign(list, n, v) != 0)
                return usage_error(err, "%s expects NAME=VALUE, found '%s'", o,
                                   v);
        } else if (strcmp(o, "--at-param") == 0 && has) {
            const char *v = argv[++i];
            if (a->atp.name)
                return usage_error(err, "--at-param given twice");
            if (split_assign(&a->atp, v) != 0)
                return usage_error(err,
                                   "--at-param expects PARAM=VALUE, found '%s'",
                                   v);
        } else if ((strcmp(o, "--output") == 0 || strcmp(o, "--aux") == 0) &&
                   has) {
            /* repeatable, and comma-separated lists */
            const char *v = argv[++i];
            int out = o[2] == 'o';
            char ***list = out ? &a->outputs : &a->aux;
            int *n = out ? &a->noutputs : &a->naux;
            a->aux_given |= !out;
            for (const char *c = v; !out || *v;) {
                const char *e = strchr(c, ',');
                size_t len = e ? (size_t)(e - c) : strlen(c);
                if (len == 0 && (out || *v))
                    return usage_error(err,
                                       "%s '%s': expected names separated "
                                       "by commas",
                                       o, v);
                if (len == 0) // --aux '': none
                    break;
                *list = pc_xrealloc(*list, sizeof **list * (size_t)(*n + 1));
                (*list)[(*n)++] = pc_xstrndup(c, len);
                if (!e)
                    break;
                c = e + 1;
            }
            if (out && !*v)
                return usage_error(err,
                                   "--output '': expected names separated "
                                   "by commas");
        } else if (strcmp(o, "-o") == 0 && has) {
            a->opath = argv[++i];
        } else if (strcmp(o, "--view") == 0 && has) {
            a->view = argv[++i];
        } else if (strcmp(o, "--tangents") == 0 && has) {
            a->tangents = argv[++i];
        } else if ((strcmp(o, "--tangent-scale") == 0 ||
                    strcmp(o, "--comb-scale") == 0) &&
                   has) {
            const char *v = argv[++i];
            double x;
            if (sample_number(v, &x) != 0 || !(x > 0))
                return usage_error(err, "%s '%s': expected a positive number",
                                   o, v);
            if (o[2] == 't')
                a->tangent_scale = x;
            else
                a->comb_scale = x;
        } else if (strcmp(o, "--comb") == 0) {
            a->comb = 1;
        } else if (strcmp(o, "--comb-teeth") == 0 && has) {
            const char *v = argv[++i];
            long n;
            if (parse_count(v, PLOT_MAX_TEETH, &n) != 0)
                return usage_error(err,
                                   "--comb-teeth '%s': expected a whole "
                                   "number from 1 to %d",
                                   v, PLOT_MAX_TEETH);
            a->teeth = (int)n;
            a->comb = 1;
        } else if (strcmp(o, "--size") == 0 && has) {
            a->size = argv[++i];
        } else if (strcmp(o, "--window") == 0 && has) {
            a->window = argv[++i];
        } else if (strcmp(o, "--max-samples") == 0 && has) {
            const char *v = argv[++i];
            if (parse_count(v, PLOT_SAMPLES_LIMIT, &a->max_samples) != 0 ||
                a->max_samples < 2)
                return usage_error(err,
                                   "--max-samples '%s': expected a whole "
                                   "number from 2 to %d",
                                   v, PLOT_SAMPLES_LIMIT);
        } else if (o[0] == '-' && o[1] != '\0') {
            return usage_error(err, "unknown or incomplete option '%s'", o);
        } else if (!a->file) {
            a->file = o;
        } else {
            return usage_error(err, "plot takes one FILE, found '%s'", o);
        }
    }
    if (!a->file)
        return usage_error(err, "plot needs a scheme FILE");
    return 0;
}

static int find_name(char *const *names, int n, const char *s)
{
    for (int i = 0; i < n; i++)
        if (strcmp(names[i], s) == 0)
            return i;
    return -1;
}

/* "A, B, C" of names[0..n-1] (or "none") into buf */
static const char *name_list(char *const *names, int n, char *buf, size_t size)
{
    size_t k = 0;
    buf[0] = '\0';
    for (int i = 0; i < n && k + 1 < size; i++)
        k += (size_t)snprintf(buf + k, size - k, "%s%s", i ? ", " : "",
                              names[i]);
    if (n == 0)
        snprintf(buf, size, "none");
    return buf;
}

/* Writes len bytes of text to path through a temporary file renamed into
 * place (or to out when path is NULL); 0 or 1. */
static int write_file(const char *path, const char *text, size_t len,
                      FILE *out, FILE *err)
{
    if (!path)
        return fwrite(text, 1, len, out) != len;
    const char *slash = strrchr(path, '/');
    size_t dir = slash ? (size_t)(slash - path) + 1 : 0;
    size_t cap = strlen(path) + 16;
    char *tmp = pc_xmalloc(cap);
    memcpy(tmp, path, dir);
    snprintf(tmp + dir, cap - dir, ".%s.XXXXXX", path + dir);
    int fd = mkstemp(tmp);
    FILE *f = fd >= 0 ? fdopen(fd, "w") : NULL;
    int ok = f != NULL && fwrite(text, 1, len, f) == len;
    int e = errno;
    if (f != NULL && fclose(f) != 0 && ok) {
        ok = 0;
        e = errno;
    } else if (f == NULL && fd >= 0) {
        close(fd);
    }
    if (ok) {
        mode_t mask = umask(0);
        umask(mask);
        chmod(tmp, 0666 & ~mask);
        if (rename(tmp, path) != 0) {
            ok = 0;
            e = errno;
        }
    }
    if (!ok) {
        fprintf(err, "pointcalc: cannot write '%s': %s\n", path, strerror(e));
        if (fd >= 0)
            unlink(tmp);
    }
    free(tmp);
    return !ok;
}

/* 1 when a and b name the same file */
static int same_file(const char *a, const char *b)
{
    struct stat sa, sb;
    if (strcmp(a, b) == 0)
        return 1;
    return stat(a, &sa) == 0 && stat(b, &sb) == 0 && sa.st_dev == sb.st_dev &&
           sa.st_ino == sb.st_ino;
}

/* ---- the run --------------------------------------------------------- */

typedef struct Run {
    Derived *d;
    Plan *p;
    int nout;      // the scheme's outputs: plan outputs 0..nout-1
    int *range_o;  // per param: plan output of lo (hi = lo + 1), or -1
    int *step_o;   // per step: plan output of its value, or -1
    int *arg_o;    // per step: plan output of its first arg (the others
                   // follow), or -1
    int nsel, *sel;
    int dim;
    double **pt;   // per base point (owned) or NULL
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
            free(r->pt[i]);
    free(r->pt);
    free(r->range_o);
    free(r->step_o);
    free(r->arg_o);
    free(r->sel);
    free(r->consts);
    free(r->params);
    free(r->tangents);
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
    free(all);
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
    free(cols);
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
    free(live);
    return used;
}

static int setup(Run *r, const PlotArgs *a, FILE *err)
{
    const Plan *p = r->p;
    char list[512], msg[300];
    /* the curves: point outputs */
    r->sel = pc_xcalloc((size_t)p->noutputs + 1, sizeof *r->sel);
    if (a->noutputs > 0) {
        for (int i = 0; i < a->noutputs; i++) {
            int o = plan_find_output(p, a->outputs[i]);
            if (o < 0 || o >= r->nout) {
                char **names = pc_xmalloc(sizeof *names * (size_t)(r->nout + 1));
                for (int k = 0; k < r->nout; k++)
                    names[k] = p->outputs[k].name;
                name_list(names, r->nout, list, sizeof list);
                free(names);
                return usage_error(err,
                                   "--output '%s' is not an output of the "
                                   "scheme (outputs: %s)",
                                   a->outputs[i], list);
            }
            if (p->outputs[o].kind != PLAN_POINT)
                return usage_error(err,
                                   "--output '%s' is a %s: plot draws point "
                                   "outputs as curves (see --tangents for "
                                   "derivatives)",
                                   a->outputs[i],
                                   p->outputs[o].kind == PLAN_SCALAR ? "scalar"
                                                                     : "vector");
            for (int j = 0; j < r->nsel; j++)
                if (r->sel[j] == o)
                    return usage_error(err, "--output '%s' is given twice",
                                       a->outputs[i]);
            r->sel[r->nsel++] = o;
        }
    } else {
        for (int o = 0; o < r->nout; o++)
            if (p->outputs[o].kind == PLAN_POINT)
                r->sel[r->nsel++] = o;
        if (r->nsel == 0)
            return usage_error(err,
                               "the scheme has no point output to draw "
                               "(its outputs are scalars or vectors)");
    }
    /* points */
    r->pt = pc_xcalloc((size_t)p->npoints + 1, sizeof *r->pt);
    for (int i = 0; i < a->nat; i++) {
        int k = find_name(p->points, p->npoints, a->at[i].name);
        if (k < 0)
            return usage_error(
                err,
                "--at %s: '%s' is not a base point of the scheme (points: %s)",
                a->at[i].name, a->at[i].name,
                name_list(p->points, p->npoints, list, sizeof list));
        if (r->pt[k])
            return usage_error(err, "--at %s given twice", a->at[i].name);
        long n = sample_numbers(a->at[i].text, &r->pt[k]);
        if (n < 0)
            return usage_error(err,
                               "--at %s=%s: malformed coordinates; expected "
                               "numbers separated by commas",
                               a->at[i].name, a->at[i].text);
        if (r->dim && n != r->dim)
            return usage_error(err,
                               "--at %s has %ld coordinates but the points "
                               "before it have %d: every point must have the "
                               "same dimension",
                               a->at[i].name, n, r->dim);
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
    /* consts */
    r->consts = pc_xcalloc((size_t)p->nconsts + 1, sizeof *r->consts);
    unsigned char *cseen = pc_xcalloc((size_t)p->nconsts + 1, 1);
    for (int i = 0; i < a->nset; i++) {
        int k = find_name(p->consts, p->nconsts, a->set[i].name);
        int rc = 0;
        if (k < 0)
            rc = usage_error(err,
                             find_name(p->params, p->nparams, a->set[i].name) >= 0
                                 ? "--set %s: '%s' is a param; give it with "
                                   "--param"
                                 : "--set %s: '%s' is not a const of the "
                                   "scheme",
                             a->set[i].name, a->set[i].name);
        else if (cseen[k]++)
            rc = usage_error(err, "--set %s given twice", a->set[i].name);
        else if (sample_number(a->set[i].text, &r->consts[k]) != 0)
            rc = usage_error(err, "--set %s=%s: malformed number",
                             a->set[i].name, a->set[i].text);
        if (rc) {
            free(cseen);
            return rc;
        }
    }
    /* params: one swept (LO:HI[:N], or the one not given and declared with
     * a range), the others one value each */
    r->params = pc_xcalloc((size_t)p->nparams + 1, sizeof *r->params);
    unsigned char *pseen = pc_xcalloc((size_t)p->nparams + 1, 1);
    r->sweep = -1;
    r->initial = PLOT_INITIAL;
    int rc = 0;
    for (int i = 0; i < a->nparam && !rc; i++) {
        const char *name = a->param[i].name, *text = a->param[i].text;
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
            free(t1);
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
    if (!rc && r->sweep < 0) {
        /* the one param not given a value */
        int nfree = 0;
        char **free_names = pc_xmalloc(sizeof *free_names *
                                       (size_t)(p->nparams + 1));
        for (int k = 0; k < p->nparams; k++)
            if (!pseen[k]) {
                free_names[nfree++] = p->params[k];
                r->sweep = k;
            }
        if (nfree > 1)
            rc = usage_error(err,
                             "params %s have no value: one is swept (give "
                             "it as --param NAME=LO:HI, or leave only it "
                             "out), the others need --param NAME=VALUE",
                             name_list(free_names, nfree, list, sizeof list));
        free(free_names);
        if (!rc && r->sweep < 0)
            rc = usage_error(err,
                             p->nparams == 0
                                 ? "the scheme has no param to sweep"
                                 : "no param is swept: give one as "
                                   "--param NAME=LO:HI");
        if (!rc && r->range_o[r->sweep] < 0)
            rc = usage_error(err,
                             "missing --param %s=LO:HI: the scheme declares "
                             "no range for %s",
                             p->params[r->sweep], p->params[r->sweep]);
    } else if (!rc) {
        for (int k = 0; k < p->nparams && !rc; k++)
            if (!pseen[k])
                rc = usage_error(err, "missing --param %s=VALUE",
                                 p->params[k]);
    }
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
    free(cseen);
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
    free(pseen);
    if (rc)
        return rc;
    if (r->dim == 0)
        return usage_error(err, "give the base points with --at A=x,y,...");
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
        free(v);
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
        char *w = pc_xstrndup(a->size, x ? (size_t)(x - a->size)
                                         : strlen(a->size));
        long W, H = 0;
        int ok = parse_count(w, 10000, &W) == 0 && W >= 16 &&
                 (!x || (parse_count(x + 1, 10000, &H) == 0 && H >= 16));
        free(w);
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

typedef struct Construction {
    PlotMark *marks;
    int nmarks;
    PlotLine *lines;
    int nlines;
    double *xyz; // the marks' coordinates, dim each (owned)
} Construction;

static void construction_clear(Construction *c)
{
    free(c->marks);
    free(c->lines);
    free(c->xyz);
}

/* 1 when every base point plan output o reads is given */
static int points_given(const Run *r, int o)
{
    for (int k = 0; k < r->p->npoints; k++)
        if (!r->pt[k] && plan_output_uses_point(r->p, o, k))
            return 0;
    return 1;
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
    for (int i = 0; i < a->naux; i++) {
        int found = 0;
        for (slong k = 0; k < d->nsteps && !found; k++)
            found = r->step_o[k] >= 0 &&
                    strcmp(d->steps[k].value.name, a->aux[i]) == 0;
        if (!found)
            return usage_error(err,
                               "--aux '%s' is not a point definition of the "
                               "scheme",
                               a->aux[i]);
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
        add_mark(c, r, env, r->sel[j], p->outputs[r->sel[j]].name,
                 PLOT_CURRENT, j);
    for (slong k = 0; k < d->nsteps; k++) {
        const char *name = d->steps[k].value.name;
        int want = !a->aux_given;
        for (int i = 0; i < a->naux && !want; i++)
            want = strcmp(a->aux[i], name) == 0;
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

int plot_main(int argc, char **argv, FILE *out, FILE *err)
{
    PlotArgs a;
    int rc = parse_args(&a, argc, argv, err);
    if (rc) {
        args_clear(&a);
        return rc;
    }
    if (a.opath && same_file(a.opath, a.file)) {
        rc = usage_error(err, "-o '%s' is the scheme itself; it would be "
                              "overwritten",
                         a.opath);
        args_clear(&a);
        return rc;
    }
    Run r;
    memset(&r, 0, sizeof r);
    int bad_define = 0;
    DeriveOptions opt = derive_options_cli(&a.budget, err, &bad_define);
    opt.keep_steps = a.atp.name != NULL; // the construction
    budget_arm(a.budget.max_seconds, a.budget.max_memory);
    r.d = derive_file_ex(a.file, err, NULL, &opt);
    if (!r.d) {
        budget_disarm();
        args_clear(&a);
        return bad_define ? 2 : 1;
    }
    r.p = lower_all(&r, err);
    budget_disarm();
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
    FILE *tm = open_memstream(&title, &tlen);
    pc_fprintf(tm, "%s: ", p->name);
    for (int j = 0; j < r.nsel; j++)
        fprintf(tm, "%s%s", j ? ", " : "", p->outputs[r.sel[j]].name);
    pc_fprintf(tm, " over %s in [%.6g, %.6g]", p->params[r.sweep], r.lo, r.hi);
    if (r.have_at)
        pc_fprintf(tm, ", construction at %s = %.6g", p->params[r.sweep], r.at);
    fclose(tm);
    s.title = title;

    char *svg = NULL;
    size_t len = 0;
    FILE *m = open_memstream(&svg, &len);
    PlotStats st;
    memset(&st, 0, sizeof st);
    plot_svg(m, &s, &st);
    fclose(m);
    rc = write_file(a.opath, svg, len, out, err);
    if (rc == 0 && st.samples == 0)
        fprintf(err, "pointcalc: plot: nothing of the curves is drawable "
                     "over the range (every sample a pole, undefined or not "
                     "finite)\n");
    free(svg);
    free(title);
    construction_clear(&c);
    run_clear(&r);
    args_clear(&a);
    return rc;
}
