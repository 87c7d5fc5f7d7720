/*
 * args.c - option parsing shared by the commands (see args.h).
 *
 * Parsing is in two steps: args_parse and eval_args_option only read the
 * command line (nothing about the scheme is known yet, so option syntax is
 * reported before the scheme is derived); eval_setup then checks the names
 * and values against the Plan, before anything is written.
 */
#include "driver/cli/args.h"

#include <stdarg.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "base/mem.h"
#include "base/numfmt.h"
#include "runtime/eval.h"

int args_usage_error(FILE *err, const char *usage, const char *fmt, ...)
{
    va_list ap;
    fputs("pointcalc: ", err);
    va_start(ap, fmt);
    pc_vfprintf(err, fmt, ap);
    va_end(ap);
    fprintf(err, "\n%s", usage);
    return 2;
}

const char *args_value(int argc, char **argv, int i)
{
    return i + 1 < argc ? argv[i + 1] : NULL;
}

int args_scan(int argc, char **argv, const char *usage, BudgetOptions *b,
              const char **file, ArgsOption *opt, void *ctx, FILE *err)
{
    budget_options_default(b);
    if (file)
        *file = NULL;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        int used = budget_parse_option(b, argc, argv, i, err);
        if (used == 0 && opt)
            used = opt(ctx, argc, argv, i, err);
        if (used < 0)
            return 2;
        if (used > 0)
            i += used - 1;
        else if (a[0] == '-' && a[1] != '\0')
            return args_usage_error(err, usage,
                                    "unknown or incomplete option '%s'", a);
        else if (!file)
            return args_usage_error(err, usage, "%s takes no FILE, found '%s'",
                                    argv[0], a);
        else if (*file)
            return args_usage_error(err, usage, "%s takes one FILE, found '%s'",
                                    argv[0], a);
        else
            *file = a;
    }
    return 0;
}

int args_parse(int argc, char **argv, const char *usage, BudgetOptions *b,
               const char **file, ArgsOption *opt, void *ctx, FILE *err)
{
    int rc = args_scan(argc, argv, usage, b, file, opt, ctx, err);
    if (rc == 0 && !*file)
        return args_usage_error(err, usage, "%s needs a scheme FILE", argv[0]);
    return rc;
}

/* ---- --output NAME[,NAME...] ------------------------------------------ */

int args_names_add(NameList *l, const char *list)
{
    for (const char *c = list;;) {
        size_t len = strcspn(c, ",");
        if (len == 0)
            return -1;
        l->v = pc_xrealloc(l->v, sizeof *l->v * (size_t)(l->n + 1));
        l->v[l->n++] = pc_xstrndup(c, len);
        if (c[len] == '\0')
            return 0;
        c += len + 1;
    }
}

void args_names_clear(NameList *l)
{
    for (int i = 0; i < l->n; i++)
        pc_free(l->v[i]);
    pc_free(l->v);
    l->v = NULL;
    l->n = 0;
}

const char *args_name_list(char *const *names, int n, char *buf, size_t size)
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

/* the outputs' names, for a message */
static const char *output_list(const Plan *p, char *buf, size_t size)
{
    char **names = pc_xmalloc(sizeof *names * (size_t)(p->noutputs + 1));
    for (int k = 0; k < p->noutputs; k++)
        names[k] = p->outputs[k].name;
    args_name_list(names, p->noutputs, buf, size);
    pc_free(names);
    return buf;
}

int args_select_outputs(int *sel, const NameList *l, const Plan *p,
                        const char *usage, FILE *err)
{
    char list[512];
    int n = 0;
    if (l->n == 0)
        for (int o = 0; o < p->noutputs; o++)
            sel[n++] = o;
    for (int i = 0; i < l->n; i++) {
        int o = plan_find_output(p, l->v[i]);
        if (o < 0) {
            args_usage_error(err, usage,
                             "--output '%s' is not an output of the scheme "
                             "(outputs: %s)",
                             l->v[i], output_list(p, list, sizeof list));
            return -1;
        }
        for (int j = 0; j < n; j++)
            if (sel[j] == o) {
                args_usage_error(err, usage, "--output '%s' is given twice",
                                 l->v[i]);
                return -1;
            }
        sel[n++] = o;
    }
    return n;
}

/* ---- eval's options --------------------------------------------------- */

void eval_args_init(EvalArgs *a)
{
    memset(a, 0, sizeof *a);
}

static void assigns_clear(Assign *list, int n)
{
    for (int i = 0; i < n; i++)
        pc_free(list[i].name);
    pc_free(list);
}

void eval_args_clear(EvalArgs *a)
{
    assigns_clear(a->at, a->nat);
    assigns_clear(a->set, a->nset);
    assigns_clear(a->param, a->nparam);
    args_names_clear(&a->outputs);
    eval_args_init(a);
}

/* NAME=TEXT appended to list; -1 when there is no '=' or no name */
static int push_assign(Assign **list, int *n, const char *arg)
{
    const char *eq = strchr(arg, '=');
    if (!eq || eq == arg)
        return -1;
    *list = pc_xrealloc(*list, sizeof **list * (size_t)(*n + 1));
    Assign *x = &(*list)[(*n)++];
    x->name = pc_xstrndup(arg, (size_t)(eq - arg));
    x->text = eq + 1;
    return 0;
}

int eval_args_option(EvalArgs *a, int argc, char **argv, int i,
                     const char *usage, FILE *err)
{
    const char *o = argv[i], *v = args_value(argc, argv, i);
    Assign **list = NULL;
    int *n = NULL;
    if (!v)
        return 0; // an option without its value: "incomplete"
    if (strcmp(o, "--at") == 0)
        list = &a->at, n = &a->nat;
    else if (strcmp(o, "--set") == 0)
        list = &a->set, n = &a->nset;
    else if (strcmp(o, "--param") == 0)
        list = &a->param, n = &a->nparam;
    else if (strcmp(o, "--output") == 0) {
        if (args_names_add(&a->outputs, v) == 0)
            return 2;
        args_usage_error(err, usage,
                         "--output '%s': expected output names separated "
                         "by commas",
                         v);
        return -1;
    } else
        return 0;
    if (push_assign(list, n, v) == 0)
        return 2;
    args_usage_error(err, usage, "%s expects NAME=VALUE, found '%s'", o, v);
    return -1;
}

/* ---- eval's options against a Plan ------------------------------------ */

static int find_name(char *const *names, int n, const char *s)
{
    for (int i = 0; i < n; i++)
        if (strcmp(names[i], s) == 0)
            return i;
    return -1;
}

void eval_setup_clear(EvalSetup *s)
{
    if (s->pt)
        for (int i = 0; i < s->npoints; i++)
            pc_free(s->pt[i]);
    pc_free(s->pt);
    pc_free(s->sel);
    pc_free(s->consts);
    for (int i = 0; i < s->naxes; i++)
        sample_clear(&s->axes[i].spec);
    pc_free(s->axes);
    memset(s, 0, sizeof *s);
}

/* --at: the coordinates, one dimension for all */
static int setup_points(EvalSetup *s, const EvalArgs *a, const Plan *p,
                        const char *usage, FILE *err)
{
    char list[512];
    for (int i = 0; i < a->nat; i++) {
        const Assign *x = &a->at[i];
        int k = find_name(p->points, p->npoints, x->name);
        if (k < 0)
            return args_usage_error(
                err, usage,
                "--at %s: '%s' is not a base point of the scheme (points: %s)",
                x->name, x->name,
                args_name_list(p->points, p->npoints, list, sizeof list));
        if (s->pt[k])
            return args_usage_error(err, usage, "--at %s given twice", x->name);
        long n = sample_numbers(x->text, &s->pt[k]);
        if (n < 0)
            return args_usage_error(err, usage,
                                    "--at %s=%s: malformed coordinates; "
                                    "expected numbers separated by commas",
                                    x->name, x->text);
        if (s->dim && n != s->dim)
            return args_usage_error(err, usage,
                                    "--at %s has %ld coordinates but the "
                                    "points before it have %d: every point "
                                    "must have the same dimension",
                                    x->name, n, s->dim);
        s->dim = (int)n;
    }
    return 0;
}

/* every point a selected output reads (its weights' and its distances')
 * is given, and a point output has a dimension */
static int check_points(const EvalSetup *s, const Plan *p, const char *usage,
                        FILE *err)
{
    for (int j = 0; j < s->nsel; j++)
        for (int k = 0; k < p->npoints; k++)
            if (!s->pt[k] && plan_output_uses_point(p, s->sel[j], k))
                return args_usage_error(
                    err, usage,
                    "missing --at %s=x,y,...: output %s "
                    "depends on base point %s",
                    p->points[k], p->outputs[s->sel[j]].name, p->points[k]);
    for (int j = 0; j < s->nsel; j++) {
        int pt, need = plan_output_min_dim(p, s->sel[j], &pt);
        if (need > s->dim)
            return args_usage_error(
                err, usage,
                "output %s reads coordinate %d of base point %s "
                "(coord(%s, %d)), but the points have %d: give every --at "
                "point at least %d coordinates",
                p->outputs[s->sel[j]].name, need, p->points[pt], p->points[pt],
                need, s->dim, need);
    }
    for (int j = 0; j < s->nsel && s->dim == 0; j++) {
        const PlanOutput *o = &p->outputs[s->sel[j]];
        if (o->kind != KIND_SCALAR)
            return args_usage_error(err, usage,
                                    "output %s is the zero vector (it depends "
                                    "on no base point): give at least one "
                                    "--at to set the dimension",
                                    o->name);
    }
    return 0;
}

/* used[i]: input i (params, then consts) is read by a selected output */
static unsigned char *used_inputs(const EvalSetup *s, const Plan *p)
{
    unsigned char *live = pc_xcalloc((size_t)p->nins + 1, 1);
    unsigned char *used = pc_xcalloc((size_t)(p->nparams + p->nconsts) + 1, 1);
    for (int j = 0; j < s->nsel; j++) { /* plan_live clears live */
        plan_live(p, s->sel[j], live);
        for (int i = 0; i < p->nins; i++)
            if (live[i] && p->ins[i].op == PLAN_INPUT)
                used[p->ins[i].a] = 1;
    }
    pc_free(live);
    return used;
}

static EvalAxis *new_axis(EvalSetup *s, int param, int cnst)
{
    s->axes = pc_xrealloc(s->axes, sizeof *s->axes * (size_t)(s->naxes + 1));
    EvalAxis *x = &s->axes[s->naxes++];
    memset(x, 0, sizeof *x);
    x->param = param;
    x->cnst = cnst;
    return x;
}

/* --set k=VALUE, or k=SPEC with a list or a range: a swept const */
static int setup_const(EvalSetup *s, const Assign *x, int k, const char *usage,
                       FILE *err)
{
    char msg[300];
    if (!strpbrk(x->text, ",:")) {
        if (sample_number(x->text, &s->consts[k]) == 0)
            return 0;
        return args_usage_error(err, usage, "--set %s=%s: malformed number",
                                x->name, x->text);
    }
    EvalAxis *ax = new_axis(s, -1, k);
    if (sample_parse(&ax->spec, x->text, msg, sizeof msg) == 0)
        return 0;
    return args_usage_error(err, usage, "--set %s=%s: %s", x->name, x->text,
                            msg);
}

/* --set: each const once (a param named instead is said to be one); the
 * swept ones' axes in declaration order */
static int setup_consts(EvalSetup *s, const EvalArgs *a, const Plan *p,
                        unsigned char *seen, const char *usage, FILE *err)
{
    char list[512];
    const Assign **given = pc_xcalloc((size_t)p->nconsts + 1, sizeof *given);
    int rc = 0;
    for (int i = 0; i < a->nset && !rc; i++) {
        const Assign *x = &a->set[i];
        int k = find_name(p->consts, p->nconsts, x->name);
        if (k < 0 && find_name(p->params, p->nparams, x->name) >= 0)
            rc = args_usage_error(err, usage,
                                  "--set %s: '%s' is a param; give it with "
                                  "--param %s=SPEC",
                                  x->name, x->name, x->name);
        else if (k < 0)
            rc = args_usage_error(
                err, usage,
                "--set %s: '%s' is not a const of the scheme (consts: %s)",
                x->name, x->name,
                args_name_list(p->consts, p->nconsts, list, sizeof list));
        else if (seen[k]++)
            rc = args_usage_error(err, usage, "--set %s given twice", x->name);
        else
            given[k] = x;
    }
    for (int k = 0; k < p->nconsts && !rc; k++)
        if (given[k])
            rc = setup_const(s, given[k], k, usage, err);
    pc_free(given);
    return rc;
}

/* --param: each param once; the axes in declaration order */
static int setup_params(EvalSetup *s, const EvalArgs *a, const Plan *p,
                        unsigned char *seen, const char *usage, FILE *err)
{
    char list[512], msg[300];
    const Assign **given = pc_xcalloc((size_t)p->nparams + 1, sizeof *given);
    int rc = 0;
    for (int i = 0; i < a->nparam && !rc; i++) {
        const Assign *x = &a->param[i];
        int k = find_name(p->params, p->nparams, x->name);
        if (k < 0 && find_name(p->consts, p->nconsts, x->name) >= 0)
            rc = args_usage_error(err, usage,
                                  "--param %s: '%s' is a const; give it with "
                                  "--set %s=VALUE",
                                  x->name, x->name, x->name);
        else if (k < 0)
            rc = args_usage_error(
                err, usage,
                "--param %s: '%s' is not a param of the scheme (params: %s)",
                x->name, x->name,
                args_name_list(p->params, p->nparams, list, sizeof list));
        else if (seen[k]++)
            rc =
                args_usage_error(err, usage, "--param %s given twice", x->name);
        else
            given[k] = x;
    }
    for (int k = 0; k < p->nparams && !rc; k++) {
        if (!given[k])
            continue;
        EvalAxis *ax = new_axis(s, k, -1);
        if (sample_parse(&ax->spec, given[k]->text, msg, sizeof msg) != 0)
            rc = args_usage_error(err, usage, "--param %s=%s: %s",
                                  given[k]->name, given[k]->text, msg);
    }
    pc_free(given);
    return rc;
}

/* every const and param a selected output reads is given */
static int check_inputs(const EvalSetup *s, const Plan *p,
                        const unsigned char *seen, const char *usage, FILE *err)
{
    unsigned char *used = used_inputs(s, p);
    int rc = 0;
    for (int k = 0; k < p->nconsts && !rc; k++)
        if (used[p->nparams + k] && !seen[p->nparams + k])
            rc = args_usage_error(err, usage, "missing --set %s=VALUE",
                                  p->consts[k]);
    for (int k = 0; k < p->nparams && !rc; k++)
        if (used[k] && !seen[k])
            rc = args_usage_error(err, usage, "missing --param %s=SPEC",
                                  p->params[k]);
    pc_free(used);
    return rc;
}

/* rows = the product of the axes' sizes */
static int setup_rows(EvalSetup *s, const char *usage, FILE *err)
{
    s->rows = 1;
    for (int i = 0; i < s->naxes; i++) {
        size_t n = s->axes[i].spec.n;
        if (n != 0 && s->rows > (SIZE_MAX / 2) / n)
            return args_usage_error(err, usage,
                                    "the grid of samples is too large");
        s->rows *= n;
    }
    return 0;
}

int eval_setup(EvalSetup *s, const EvalArgs *a, const Plan *p,
               const char *usage, FILE *err)
{
    memset(s, 0, sizeof *s);
    s->npoints = p->npoints;
    s->nparams = p->nparams;
    s->sel = pc_xcalloc((size_t)p->noutputs + 1, sizeof *s->sel);
    s->pt = pc_xcalloc((size_t)p->npoints + 1, sizeof *s->pt);
    s->consts = pc_xcalloc((size_t)p->nconsts + 1, sizeof *s->consts);
    /* seen[i]: input i (params, then consts) is given */
    unsigned char *seen = pc_xcalloc((size_t)(p->nparams + p->nconsts) + 1, 1);
    int rc = 0;
    s->nsel = args_select_outputs(s->sel, &a->outputs, p, usage, err);
    if (s->nsel < 0) {
        s->nsel = 0;
        rc = 2;
    }
    if (!rc)
        rc = setup_points(s, a, p, usage, err);
    if (!rc)
        rc = check_points(s, p, usage, err);
    if (!rc)
        rc = setup_consts(s, a, p, seen + p->nparams, usage, err);
    /* params before the missing consts: a const given as --param is
     * reported as such, not as a missing --set */
    if (!rc)
        rc = setup_params(s, a, p, seen, usage, err);
    if (!rc)
        rc = check_inputs(s, p, seen, usage, err);
    if (!rc)
        rc = setup_rows(s, usage, err);
    pc_free(seen);
    return rc;
}

void eval_setup_row(const EvalSetup *s, size_t row, double *params,
                    double *consts)
{
    for (int i = 0; i < s->nparams; i++)
        params[i] = 0;
    for (int i = s->naxes - 1; i >= 0; i--) {
        const EvalAxis *x = &s->axes[i];
        double v = sample_value(&x->spec, row % x->spec.n);
        row /= x->spec.n;
        if (x->param >= 0)
            params[x->param] = v;
        else
            consts[x->cnst] = v;
    }
}

size_t eval_setup_run(const EvalSetup *s, size_t row)
{
    size_t inner = 1; // rows per combination of the swept consts
    for (int i = s->naxes - 1; i >= 0 && s->axes[i].param >= 0; i--)
        inner *= s->axes[i].spec.n;
    if (s->naxes == 0 || s->axes[0].param >= 0)
        return s->rows - row; // nothing swept
    return inner - row % inner;
}
