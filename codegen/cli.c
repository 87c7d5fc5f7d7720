/*
 * cli.c - `pointcalc emit-c` and `pointcalc eval`: option parsing and the
 * pipeline
 *
 *   derive_file -> lower_derived -> emit_c            (emit-c)
 *   derive_file -> lower_derived -> plan_eval -> CSV  (eval)
 *
 * This is the glue that needs both compiler/ (derive) and runtime/ (the
 * interpreter), so it lives in codegen/.  Checks happen in this order:
 * option syntax (exit 2), the scheme (exit 1), names against the scheme
 * (exit 2); only then is anything written to `out`.
 */
#include "codegen/cli.h"

#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "codegen/emit_c.h"
#include "codegen/lower.h"
#include "compiler/budget.h"
#include "compiler/derive.h"
#include "compiler/mem.h"
#include "runtime/eval.h"
#include "runtime/output.h"
#include "runtime/sample.h"

static const char emit_usage[] =
    "usage: pointcalc emit-c FILE [-o OUT.c] [--header OUT.h] [--prefix NAME]"
    " [--dump-plan]\n"
    "                        [--functions plain,checked,batch,batch_checked]"
    "\n";
static const char eval_usage[] =
    "usage: pointcalc eval FILE --at A=x,y[,z...] ... [--set k=VALUE ...]\n"
    "                      --param t=SPEC ... [--output NAME[,NAME...]] ... "
    "[--format csv|json]\n"
    "       SPEC: a value 0.5, a list 0,0.25,1 or lo:hi:count\n";

static int usage_error(FILE *err, const char *usage, const char *fmt, ...)
{
    va_list ap;
    fputs("pointcalc: ", err);
    va_start(ap, fmt);
    vfprintf(err, fmt, ap);
    va_end(ap);
    fprintf(err, "\n%s", usage);
    return 2;
}

/* 1 when a and b name the same file: the same text, or the same inode */
static int same_file(const char *a, const char *b)
{
    struct stat sa, sb;
    if (strcmp(a, b) == 0)
        return 1;
    return stat(a, &sa) == 0 && stat(b, &sb) == 0 && sa.st_dev == sb.st_dev &&
           sa.st_ino == sb.st_ino;
}

/* Writes text to path (or to out when path is NULL); 0 or 1.  The file is
 * written whole to a temporary file in the same directory and renamed into
 * place, so a reader (or a concurrent pointcalc) sees the old file or the
 * new one, never a mixture, and a failed write leaves the old one alone. */
static int write_text(const char *path, const char *text, size_t len, FILE *out,
                      FILE *err)
{
    if (!path) {
        fwrite(text, 1, len, out);
        return 0;
    }
    const char *slash = strrchr(path, '/');
    size_t dir = slash ? (size_t)(slash - path) + 1 : 0;
    char *tmp = pc_xmalloc(strlen(path) + 16);
    memcpy(tmp, path, dir);
    snprintf(tmp + dir, strlen(path) + 16 - dir, ".%s.XXXXXX", path + dir);
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
        /* mkstemp makes the file 0600; give it what a new file gets */
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

/* ---- emit-c -------------------------------------------------------------- */

int emit_c_main(int argc, char **argv, FILE *out, FILE *err)
{
    const char *file = NULL, *cpath = NULL, *hpath = NULL, *prefix = NULL;
    int dump = 0;
    unsigned functions = EMIT_C_ALL;
    BudgetOptions bo;
    budget_options_default(&bo);
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        int has = i + 1 < argc;
        int used = budget_parse_option(&bo, argc, argv, i, err);
        if (used < 0)
            return 2;
        if (used > 0)
            i += used - 1;
        else if (strcmp(a, "-o") == 0 && has)
            cpath = argv[++i];
        else if (strcmp(a, "--header") == 0 && has)
            hpath = argv[++i];
        else if (strcmp(a, "--prefix") == 0 && has)
            prefix = argv[++i];
        else if (strcmp(a, "--functions") == 0 && has) {
            const char *bad = NULL;
            functions = emit_c_parse_functions(argv[++i], &bad);
            if (functions == 0)
                return usage_error(err, emit_usage,
                                   "--functions '%s': '%.*s' is not one of "
                                   "plain, checked, batch, batch_checked, all",
                                   argv[i], (int)strcspn(bad, ","), bad);
        }
        else if (strcmp(a, "--dump-plan") == 0)
            dump = 1;
        else if (a[0] == '-' && a[1] != '\0')
            return usage_error(err, emit_usage,
                               "unknown or incomplete option '%s'", a);
        else if (!file)
            file = a;
        else
            return usage_error(err, emit_usage,
                               "emit-c takes one FILE, found '%s'", a);
    }
    if (!file)
        return usage_error(err, emit_usage, "emit-c needs a scheme FILE");
    if (prefix && !emit_c_valid_prefix(prefix))
        return usage_error(err, emit_usage,
                           "--prefix '%s' is not a usable C identifier%s",
                           prefix,
                           prefix[0] == '_' &&
                                   (prefix[1] == '_' ||
                                    (prefix[1] >= 'A' && prefix[1] <= 'Z'))
                               ? " (names beginning with __ or with _ and a "
                                 "capital letter are reserved for the C "
                                 "implementation)"
                               : "");
    if ((cpath && same_file(cpath, file)) || (hpath && same_file(hpath, file)))
        return usage_error(err, emit_usage,
                           "%s '%s' is the scheme itself; it would be "
                           "overwritten",
                           cpath && same_file(cpath, file) ? "-o" : "--header",
                           cpath && same_file(cpath, file) ? cpath : hpath);
    if (cpath && hpath && same_file(cpath, hpath))
        return usage_error(err, emit_usage,
                           "-o and --header name the same file '%s'", cpath);
    int bad_define = 0;
    DeriveOptions opt = derive_options_cli(&bo, err, &bad_define);
    budget_arm(bo.max_seconds, bo.max_memory);
    Derived *d = derive_file_ex(file, err, NULL, &opt);
    if (!d) {
        budget_disarm();
        return bad_define ? 2 : 1;
    }
    Plan *p = lower_derived(d, err);
    budget_disarm();
    if (p && !dump && emit_c_check(p, d, prefix, err)) {
        plan_free(p);
        p = NULL;
    }
    derived_free(d);
    if (!p)
        return 1;
    char *ctext = NULL, *htext = NULL;
    size_t clen = 0, hlen = 0;
    /* the header is written first: when it fails, stdout stays empty */
    FILE *m = open_memstream(&ctext, &clen);
    if (dump)
        plan_dump(m, p);
    else
        emit_c_ex(m, p, prefix, file, functions);
    fclose(m);
    if (hpath) {
        m = open_memstream(&htext, &hlen);
        emit_c_header_ex(m, p, prefix, file, functions);
        fclose(m);
    }
    plan_free(p);
    int rc = hpath ? write_text(hpath, htext, hlen, out, err) : 0;
    if (rc == 0)
        rc = write_text(cpath, ctext, clen, out, err);
    free(ctext);
    free(htext);
    return rc;
}

/* ---- eval ---------------------------------------------------------------- */

/* rows per chunk: up to CHUNK, fewer for high dimensions (about 8 MB of
 * coordinates per output at most) */
enum { CHUNK = 4096, CHUNK_VALUES = 1 << 20, MAX_POLE_MESSAGES = 10 };

/* eval's own status beyond PlanStatus: a non-finite value whose
 * denominator was finite */
enum { STATUS_TERMS = PLAN_STATUS_OVERFLOW + 1 };

typedef struct Assign {
    const char *name; // borrowed from argv (up to '=', copied)
    char *name_buf;   // owned copy of the name
    const char *text; // the value text after '='
} Assign;

typedef struct EvalArgs {
    BudgetOptions budget;
    const char *file;
    char **outputs; // --output NAME[,NAME...] (repeatable), owned copies
    int noutputs;
    OutputFormat format;
    int nat, nset, nparam;
    Assign *at, *set, *param; // owned arrays
} EvalArgs;

static void eval_args_clear(EvalArgs *a)
{
    for (int i = 0; i < a->nat; i++)
        free(a->at[i].name_buf);
    for (int i = 0; i < a->nset; i++)
        free(a->set[i].name_buf);
    for (int i = 0; i < a->nparam; i++)
        free(a->param[i].name_buf);
    free(a->at);
    free(a->set);
    free(a->param);
    for (int i = 0; i < a->noutputs; i++)
        free(a->outputs[i]);
    free(a->outputs);
}

/* NAME=TEXT into list; -1 when there is no '=' or no name */
static int push_assign(Assign **list, int *n, const char *arg)
{
    const char *eq = strchr(arg, '=');
    if (!eq || eq == arg)
        return -1;
    *list = pc_xrealloc(*list, sizeof **list * (size_t)(*n + 1));
    Assign *x = &(*list)[(*n)++];
    size_t len = (size_t)(eq - arg);
    x->name_buf = pc_xmalloc(len + 1);
    memcpy(x->name_buf, arg, len);
    x->name_buf[len] = '\0';
    x->name = x->name_buf;
    x->text = eq + 1;
    return 0;
}

static int parse_eval_args(EvalArgs *a, int argc, char **argv, FILE *err)
{
    memset(a, 0, sizeof *a);
    a->format = OUTPUT_CSV;
    budget_options_default(&a->budget);
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
            int *n = o[2] == 'a'   ? &a->nat
                     : o[2] == 's' ? &a->nset
                                   : &a->nparam;
            if (push_assign(list, n, v) != 0)
                return usage_error(err, eval_usage,
                                   "%s expects NAME=VALUE, found '%s'", o, v);
        } else if (strcmp(o, "--output") == 0 && has) {
            /* repeatable, and a comma-separated list */
            const char *v = argv[++i];
            for (const char *c = v;;) {
                const char *e = strchr(c, ',');
                size_t len = e ? (size_t)(e - c) : strlen(c);
                if (len == 0)
                    return usage_error(err, eval_usage,
                                       "--output '%s': expected output names "
                                       "separated by commas",
                                       v);
                a->outputs = pc_xrealloc(a->outputs, sizeof *a->outputs *
                                                         (size_t)(a->noutputs + 1));
                a->outputs[a->noutputs] = pc_xmalloc(len + 1);
                memcpy(a->outputs[a->noutputs], c, len);
                a->outputs[a->noutputs++][len] = '\0';
                if (!e)
                    break;
                c = e + 1;
            }
        } else if (strcmp(o, "--format") == 0 && has) {
            const char *f = argv[++i];
            if (strcmp(f, "csv") == 0)
                a->format = OUTPUT_CSV;
            else if (strcmp(f, "json") == 0)
                a->format = OUTPUT_JSON;
            else
                return usage_error(err, eval_usage,
                                   "unknown format '%s'; expected csv or json",
                                   f);
        } else if (o[0] == '-' && o[1] != '\0') {
            return usage_error(err, eval_usage,
                               "unknown or incomplete option '%s'", o);
        } else if (!a->file) {
            a->file = o;
        } else {
            return usage_error(err, eval_usage,
                               "eval takes one FILE, found '%s'", o);
        }
    }
    if (!a->file)
        return usage_error(err, eval_usage, "eval needs a scheme FILE");
    return 0;
}

/* "A, B, C" into buf */
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

static int find_name(char *const *names, int n, const char *s)
{
    for (int i = 0; i < n; i++)
        if (strcmp(names[i], s) == 0)
            return i;
    return -1;
}

typedef struct EvalSetup {
    int nsel, *sel; // selected outputs
    int dim;        // coordinates per point (0: no point given)
    double **pt;    // per base point: coordinates or NULL (owned)
    double *consts; // per const
    Spec *specs;    // per param
} EvalSetup;

static void setup_clear(EvalSetup *s, const Plan *p)
{
    if (s->pt)
        for (int i = 0; i < p->npoints; i++)
            free(s->pt[i]);
    free(s->pt);
    free(s->sel);
    free(s->consts);
    if (s->specs)
        for (int i = 0; i < p->nparams; i++)
            sample_clear(&s->specs[i]);
    free(s->specs);
}

/* Checks the names and values of the command line against the scheme. */
static int eval_setup(EvalSetup *s, const EvalArgs *a, const Plan *p, FILE *err)
{
    char list[512];
    memset(s, 0, sizeof *s);
    s->sel = pc_xcalloc((size_t)p->noutputs + 1, sizeof *s->sel);
    s->pt = pc_xcalloc((size_t)p->npoints + 1, sizeof *s->pt);
    s->consts = pc_xcalloc((size_t)p->nconsts + 1, sizeof *s->consts);
    s->specs = pc_xcalloc((size_t)p->nparams + 1, sizeof *s->specs);
    if (a->noutputs > 0) {
        for (int i = 0; i < a->noutputs; i++) {
            int o = plan_find_output(p, a->outputs[i]);
            if (o < 0) {
                char **names =
                    pc_xmalloc(sizeof *names * (size_t)(p->noutputs + 1));
                for (int k = 0; k < p->noutputs; k++)
                    names[k] = p->outputs[k].name;
                name_list(names, p->noutputs, list, sizeof list);
                free(names);
                return usage_error(err, eval_usage,
                                   "--output '%s' is not an output of the "
                                   "scheme (outputs: %s)",
                                   a->outputs[i], list);
            }
            for (int j = 0; j < s->nsel; j++)
                if (s->sel[j] == o)
                    return usage_error(err, eval_usage,
                                       "--output '%s' is given twice",
                                       a->outputs[i]);
            s->sel[s->nsel++] = o;
        }
    } else {
        for (int o = 0; o < p->noutputs; o++)
            s->sel[s->nsel++] = o;
    }
    /* points */
    for (int i = 0; i < a->nat; i++) {
        int k = find_name(p->points, p->npoints, a->at[i].name);
        if (k < 0)
            return usage_error(
                err, eval_usage,
                "--at %s: '%s' is not a base point of the scheme (points: %s)",
                a->at[i].name, a->at[i].name,
                name_list(p->points, p->npoints, list, sizeof list));
        if (s->pt[k])
            return usage_error(err, eval_usage, "--at %s given twice",
                               a->at[i].name);
        long n = sample_numbers(a->at[i].text, &s->pt[k]);
        if (n < 0)
            return usage_error(err, eval_usage,
                               "--at %s=%s: malformed coordinates; expected "
                               "numbers separated by commas",
                               a->at[i].name, a->at[i].text);
        if (s->dim && n != s->dim)
            return usage_error(err, eval_usage,
                               "--at %s has %ld coordinates but the points "
                               "before it have %d: every point must have the "
                               "same dimension",
                               a->at[i].name, n, s->dim);
        s->dim = (int)n;
    }
    /* the points an output reads: its weights' and its distances' */
    for (int j = 0; j < s->nsel; j++)
        for (int k = 0; k < p->npoints; k++)
            if (!s->pt[k] && plan_output_uses_point(p, s->sel[j], k))
                return usage_error(err, eval_usage,
                                   "missing --at %s=x,y,...: output %s "
                                   "depends on base point %s",
                                   p->points[k], p->outputs[s->sel[j]].name,
                                   p->points[k]);
    for (int j = 0; j < s->nsel && s->dim == 0; j++) {
        const PlanOutput *o = &p->outputs[s->sel[j]];
        if (o->kind != PLAN_SCALAR)
            return usage_error(err, eval_usage,
                               "output %s is the zero vector (it depends on "
                               "no base point): give at least one --at to "
                               "set the dimension",
                               o->name);
    }
    /* consts */
    int *seen = pc_xcalloc((size_t)(p->nconsts + p->nparams) + 1, sizeof *seen);
    int rc = 0;
    for (int i = 0; i < a->nset && !rc; i++) {
        int k = find_name(p->consts, p->nconsts, a->set[i].name);
        if (k < 0) {
            int isp = find_name(p->params, p->nparams, a->set[i].name) >= 0;
            rc = usage_error(
                err, eval_usage,
                isp ? "--set %s: '%s' is a param; give it with "
                      "--param %s=SPEC"
                    : "--set %s: '%s' is not a const of the "
                      "scheme (consts: %s)",
                a->set[i].name, a->set[i].name,
                isp ? a->set[i].name
                    : name_list(p->consts, p->nconsts, list, sizeof list));
        } else if (seen[k]++) {
            rc = usage_error(err, eval_usage, "--set %s given twice",
                             a->set[i].name);
        } else if (sample_number(a->set[i].text, &s->consts[k]) != 0) {
            rc = usage_error(err, eval_usage, "--set %s=%s: malformed number",
                             a->set[i].name, a->set[i].text);
        }
    }
    /* params (before the missing consts: a const given as --param is
     * reported as such, not as a missing --set) */
    int *pseen = seen + p->nconsts;
    for (int i = 0; i < a->nparam && !rc; i++) {
        int k = find_name(p->params, p->nparams, a->param[i].name);
        char msg[300];
        if (k < 0) {
            int isc = find_name(p->consts, p->nconsts, a->param[i].name) >= 0;
            rc = usage_error(
                err, eval_usage,
                isc ? "--param %s: '%s' is a const; give it "
                      "with --set %s=VALUE"
                    : "--param %s: '%s' is not a param of the "
                      "scheme (params: %s)",
                a->param[i].name, a->param[i].name,
                isc ? a->param[i].name
                    : name_list(p->params, p->nparams, list, sizeof list));
        } else if (pseen[k]++) {
            rc = usage_error(err, eval_usage, "--param %s given twice",
                             a->param[i].name);
        } else if (sample_parse(&s->specs[k], a->param[i].text, msg,
                                sizeof msg) != 0) {
            rc = usage_error(err, eval_usage, "--param %s=%s: %s",
                             a->param[i].name, a->param[i].text, msg);
        }
    }
    /* a const the selected outputs do not use need not be given */
    unsigned char *live = pc_xcalloc((size_t)p->nins + 1, 1);
    for (int j = 0; j < s->nsel; j++)
        plan_live(p, s->sel[j], live);
    for (int k = 0; k < p->nconsts && !rc; k++) {
        int used = 0;
        for (int i = 0; i < p->nins && !used; i++)
            used = live[i] && p->ins[i].op == PLAN_INPUT &&
                   p->ins[i].a == p->nparams + k;
        if (!seen[k] && used)
            rc = usage_error(err, eval_usage, "missing --set %s=VALUE",
                             p->consts[k]);
    }
    free(live);
    for (int k = 0; k < p->nparams && !rc; k++)
        if (!pseen[k])
            rc = usage_error(err, eval_usage, "missing --param %s=SPEC",
                             p->params[k]);
    free(seen);
    if (!rc && sample_grid_rows(s->specs, p->nparams) == (size_t)-1)
        rc = usage_error(err, eval_usage, "the parameter grid is too large");
    return rc;
}

static int columns(const Plan *p, const PlanOutput *o, int dim)
{
    (void)p;
    return o->kind == PLAN_SCALAR ? 1 : dim;
}

static void csv_header(FILE *out, const Plan *p, const EvalSetup *s)
{
    int first = 1;
    for (int i = 0; i < p->nparams; i++, first = 0)
        fprintf(out, "%s%s", first ? "" : ",", p->params[i]);
    for (int j = 0; j < s->nsel; j++) {
        const PlanOutput *o = &p->outputs[s->sel[j]];
        if (o->kind == PLAN_SCALAR) {
            fprintf(out, "%s%s", first ? "" : ",", o->name);
            first = 0;
            continue;
        }
        for (int c = 1; c <= s->dim; c++, first = 0)
            fprintf(out, "%s%s.%d", first ? "" : ",", o->name, c);
    }
    fputc('\n', out);
}

static void json_head(FILE *out, const Plan *p, const EvalSetup *s)
{
    fputs("{\"scheme\": ", out);
    output_json_string(out, p->name);
    fputs(", \"params\": [", out);
    for (int i = 0; i < p->nparams; i++) {
        fputs(i ? ", " : "", out);
        output_json_string(out, p->params[i]);
    }
    fputs("], \"outputs\": [", out);
    for (int j = 0; j < s->nsel; j++) {
        const PlanOutput *o = &p->outputs[s->sel[j]];
        fputs(j ? ", " : "", out);
        fputs("{\"name\": ", out);
        output_json_string(out, o->name);
        fprintf(out, ", \"kind\": \"%s\", \"dim\": %d}",
                o->kind == PLAN_SCALAR  ? "scalar"
                : o->kind == PLAN_POINT ? "point"
                                        : "vector",
                o->kind == PLAN_SCALAR ? 1 : s->dim);
    }
    fputs("],\n \"samples\": [", out);
}

/* " at t=0.5, u=1" for row r (nothing without params) */
static void where(FILE *err, const Plan *p, double *const *pv, size_t r)
{
    for (int i = 0; i < p->nparams; i++)
        fprintf(err, "%s %s=%.17g", i ? "," : " at", p->params[i], pv[i][r]);
}

static int finite_row(const double *v, int n)
{
    for (int c = 0; c < n; c++)
        if (!isfinite(v[c]))
            return 0;
    return 1;
}

int eval_main(int argc, char **argv, FILE *out, FILE *err)
{
    EvalArgs a;
    int rc = parse_eval_args(&a, argc, argv, err);
    if (rc) {
        eval_args_clear(&a);
        return rc;
    }
    int bad_define = 0;
    DeriveOptions opt = derive_options_cli(&a.budget, err, &bad_define);
    budget_arm(a.budget.max_seconds, a.budget.max_memory);
    Derived *d = derive_file_ex(a.file, err, NULL, &opt);
    if (!d) {
        budget_disarm();
        eval_args_clear(&a);
        return bad_define ? 2 : 1;
    }
    Plan *p = lower_derived(d, err);
    budget_disarm(); /* evaluation takes what the grid asks for */
    derived_free(d);
    if (!p) {
        eval_args_clear(&a);
        return 1;
    }
    EvalSetup s;
    rc = eval_setup(&s, &a, p, err);
    if (rc) {
        setup_clear(&s, p);
        plan_free(p);
        eval_args_clear(&a);
        return rc;
    }

    size_t rows = sample_grid_rows(s.specs, p->nparams);
    size_t chunk = s.dim > 0 && CHUNK_VALUES / (size_t)s.dim < CHUNK
                       ? CHUNK_VALUES / (size_t)s.dim
                       : CHUNK;
    if (chunk == 0)
        chunk = 1;
    int np = p->nparams;
    double **pv = pc_xmalloc(sizeof *pv * (size_t)(np + 1));
    double **res = pc_xmalloc(sizeof *res * (size_t)(s.nsel + 1));
    unsigned char **st = pc_xmalloc(sizeof *st * (size_t)(s.nsel + 1));
    double *row = pc_xmalloc(sizeof *row * (size_t)(np + 1));
    for (int i = 0; i < np; i++)
        pv[i] = pc_xmalloc(sizeof **pv * chunk);
    for (int j = 0; j < s.nsel; j++) {
        int nc = columns(p, &p->outputs[s.sel[j]], s.dim);
        res[j] = pc_xmalloc(sizeof **res * chunk * (size_t)(nc ? nc : 1));
        st[j] = pc_xmalloc(chunk);
    }
    size_t npoles = 0, noverflows = 0, ndomain = 0;
    if (a.format == OUTPUT_CSV)
        csv_header(out, p, &s);
    else
        json_head(out, p, &s);
    for (size_t r0 = 0; r0 < rows; r0 += chunk) {
        size_t m = rows - r0 < chunk ? rows - r0 : chunk;
        for (size_t r = 0; r < m; r++) {
            sample_grid_row(s.specs, np, r0 + r, row);
            for (int i = 0; i < np; i++)
                pv[i][r] = row[i];
        }
        for (int j = 0; j < s.nsel; j++)
            plan_eval(p, s.sel[j], m, (const double *const *)pv, s.consts,
                      (const double *const *)s.pt, s.dim, res[j], st[j]);
        for (size_t r = 0; r < m; r++) {
            /* poles and numbers that double precision cannot hold, on
             * err; a non-finite value without a status (a numerator's
             * terms overflowed) becomes STATUS_TERMS */
            for (int j = 0; j < s.nsel; j++) {
                int nc = columns(p, &p->outputs[s.sel[j]], s.dim);
                if (st[j][r] == PLAN_STATUS_OK &&
                    !finite_row(res[j] + r * (size_t)nc, nc))
                    st[j][r] = STATUS_TERMS;
                if (st[j][r] == PLAN_STATUS_OK)
                    continue;
                int pole = st[j][r] == PLAN_STATUS_POLE;
                int domain = st[j][r] == PLAN_STATUS_DOMAIN;
                size_t k = npoles + noverflows + ndomain;
                if (pole)
                    npoles++;
                else if (domain)
                    ndomain++;
                else
                    noverflows++;
                if (k >= MAX_POLE_MESSAGES)
                    continue;
                fprintf(err, "pointcalc: eval: %s%s", pole ? "pole of " : "",
                        p->outputs[s.sel[j]].name);
                where(err, p, pv, r);
                fputs(pole ? ": a denominator of its equation vanishes; "
                             "written as nan\n"
                      : domain
                          ? " is undefined: a function's argument is "
                            "outside its domain (sqrt of a negative number, "
                            "ln of one <= 0, asin or acos beyond [-1, 1]); written "
                            "as nan\n"
                      : st[j][r] == PLAN_STATUS_OVERFLOW
                          ? " is not finite in double precision (a "
                            "denominator of its equation overflows); "
                            "written as nan\n"
                          : " is not finite in double precision (overflow "
                            "in its equation's terms)\n",
                      err);
            }
            if (a.format == OUTPUT_JSON)
                fputs(r0 + r ? ",\n  {" : "\n  {", out);
            for (int i = 0; i < np; i++) {
                if (a.format == OUTPUT_JSON) {
                    fputs(i ? ", " : "", out);
                    output_json_string(out, p->params[i]);
                    fputs(": ", out);
                } else if (i) {
                    fputc(',', out);
                }
                output_number(out, pv[i][r], a.format);
            }
            for (int j = 0; j < s.nsel; j++) {
                const PlanOutput *o = &p->outputs[s.sel[j]];
                int nc = columns(p, o, s.dim);
                int vec = o->kind != PLAN_SCALAR;
                if (a.format == OUTPUT_JSON) {
                    fputs(np || j ? ", " : "", out);
                    output_json_string(out, o->name);
                    fputs(vec ? ": [" : ": ", out);
                }
                for (int c = 0; c < nc; c++) {
                    if (a.format == OUTPUT_JSON)
                        fputs(c ? ", " : "", out);
                    else if (np || j || c)
                        fputc(',', out);
                    output_number(out, res[j][r * (size_t)nc + (size_t)c],
                                  a.format);
                }
                if (a.format == OUTPUT_JSON && vec)
                    fputc(']', out);
            }
            if (a.format == OUTPUT_JSON) {
                for (int kind = 0; kind < 3; kind++) {
                    int first = 1;
                    for (int j = 0; j < s.nsel; j++) {
                        int sk = st[j][r] == PLAN_STATUS_POLE     ? 0
                                 : st[j][r] == PLAN_STATUS_DOMAIN ? 2
                                                                  : 1;
                        if (st[j][r] == PLAN_STATUS_OK || sk != kind)
                            continue;
                        fputs(!first       ? ", "
                              : kind == 0 ? ", \"poles\": ["
                              : kind == 1 ? ", \"nonfinite\": ["
                                          : ", \"domain\": [",
                              out);
                        output_json_string(out, p->outputs[s.sel[j]].name);
                        first = 0;
                    }
                    if (!first)
                        fputc(']', out);
                }
                fputc('}', out);
            } else {
                fputc('\n', out);
            }
        }
    }
    if (a.format == OUTPUT_JSON)
        fputs(rows ? "\n]}\n" : "]}\n", out);
    if (npoles + noverflows + ndomain > MAX_POLE_MESSAGES) {
        if (ndomain)
            fprintf(err,
                    "pointcalc: eval: ... %zu poles, %zu non-finite and %zu "
                    "undefined samples in all\n",
                    npoles, noverflows, ndomain);
        else
            fprintf(err,
                    "pointcalc: eval: ... %zu poles and %zu non-finite "
                    "samples in all\n",
                    npoles, noverflows);
    }
    if (npoles || noverflows || ndomain)
        rc = 1;

    for (int i = 0; i < np; i++)
        free(pv[i]);
    for (int j = 0; j < s.nsel; j++) {
        free(res[j]);
        free(st[j]);
    }
    free(pv);
    free(res);
    free(st);
    free(row);
    setup_clear(&s, p);
    plan_free(p);
    eval_args_clear(&a);
    return rc;
}
