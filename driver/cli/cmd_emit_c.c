/*
 * cmd_emit_c.c - `pointcalc emit-c FILE [-o OUT.c] [--header OUT.h]
 * [--prefix NAME] [--output NAMES] [--functions LIST] [--kernel K]
 * [--dump-plan]`: C99
 * for the outputs
 * (codegen/emit_c.h, contract section 5).
 *
 * The C and the header are formed in memory first and written whole
 * (outfile.h), both files at once: when one fails, neither is changed and
 * stdout stays empty.
 */
#include "driver/cli/cli.h"

#include <stdlib.h>
#include <string.h>

#include "base/mem.h"
#include "codegen/collapse.h"
#include "codegen/emit_c.h"
#include "driver/cli/args.h"
#include "driver/cli/outfile.h"

typedef struct EmitArgs {
    const char *cpath, *hpath, *prefix; // NULL: stdout, none, the scheme's
    unsigned functions;                 // EMIT_C_* bits
    int dump;                           // --dump-plan
    int collapsed;                      // --kernel collapsed
    BudgetOptions budget;
    NameList outputs; // --output (none: all)
    const char *usage;
} EmitArgs;

/* --functions LIST */
static int parse_functions(EmitArgs *a, const char *v, FILE *err)
{
    const char *bad = NULL;
    a->functions = emit_c_parse_functions(v, &bad);
    if (a->functions != 0)
        return 2;
    args_usage_error(err, a->usage,
                     "--functions '%s': '%.*s' is not one of plain, checked, "
                     "batch, batch_checked, all",
                     v, (int)strcspn(bad, ","), bad);
    return -1;
}

/* --kernel weights|collapsed */
static int parse_kernel(EmitArgs *a, const char *v, FILE *err)
{
    if (strcmp(v, "weights") == 0 || strcmp(v, "collapsed") == 0) {
        a->collapsed = v[0] == 'c';
        return 2;
    }
    args_usage_error(err, a->usage,
                     "--kernel '%s': expected weights or collapsed", v);
    return -1;
}

static int emit_option(void *ctx, int argc, char **argv, int i, FILE *err)
{
    EmitArgs *a = ctx;
    const char *o = argv[i], *v = args_value(argc, argv, i);
    if (strcmp(o, "--dump-plan") == 0) {
        a->dump = 1;
        return 1;
    }
    if (!v)
        return 0;
    if (strcmp(o, "-o") == 0)
        a->cpath = v;
    else if (strcmp(o, "--header") == 0)
        a->hpath = v;
    else if (strcmp(o, "--prefix") == 0)
        a->prefix = v;
    else if (strcmp(o, "--functions") == 0)
        return parse_functions(a, v, err);
    else if (strcmp(o, "--kernel") == 0)
        return parse_kernel(a, v, err);
    else if (strcmp(o, "--output") != 0)
        return 0;
    else if (args_names_add(&a->outputs, v) != 0) {
        args_usage_error(err, a->usage,
                         "--output '%s': expected output names separated by "
                         "commas",
                         v);
        return -1;
    }
    return 2;
}

/* the prefix is an identifier C leaves to us; no output file is the scheme
 * or the other output */
static int check_names(const EmitArgs *a, const char *file, FILE *err)
{
    const char *pre = a->prefix;
    if (pre && !emit_c_valid_prefix(pre))
        return args_usage_error(
            err, a->usage, "--prefix '%s' is not a usable C identifier%s", pre,
            pre[0] == '_' ? " (names beginning with _ are reserved for the C "
                            "implementation at file scope)"
                          : "");
    if (a->cpath && outfile_same(a->cpath, file))
        return args_usage_error(err, a->usage,
                                "-o '%s' is the scheme itself; it would be "
                                "overwritten",
                                a->cpath);
    if (a->hpath && outfile_same(a->hpath, file))
        return args_usage_error(err, a->usage,
                                "--header '%s' is the scheme itself; it would "
                                "be overwritten",
                                a->hpath);
    if (a->cpath && a->hpath && outfile_same(a->cpath, a->hpath))
        return args_usage_error(
            err, a->usage, "-o and --header name the same file '%s'", a->cpath);
    return 0;
}

/* the C (or the plan dump) and the header, then the files */
static int write_outputs(const EmitArgs *a, const Plan *p, const char *file,
                         FILE *out, FILE *err)
{
    char *ctext = NULL, *htext = NULL;
    size_t clen = 0, hlen = 0;
    FILE *m = pc_xopen_memstream(&ctext, &clen);
    if (a->dump)
        plan_dump(m, p);
    else if (a->collapsed)
        emit_c_kernel(m, p, a->prefix, file, a->functions);
    else
        emit_c_ex(m, p, a->prefix, file, a->functions);
    pc_xclose_memstream(m);
    if (a->hpath) {
        m = pc_xopen_memstream(&htext, &hlen);
        emit_c_header_ex(m, p, a->prefix, file, a->functions);
        pc_xclose_memstream(m);
    }
    budget_disarm(); /* the C is made: writing the files is not cut off */
    /* both temporaries before either rename: a failure leaves neither */
    OutFile f[2] = {{a->hpath, htext, hlen}, {a->cpath, ctext, clen}};
    int rc = a->hpath ? outfile_write_all(f, 2, out, err)
                      : outfile_write_all(f + 1, 1, out, err);
    pc_free(ctext);
    pc_free(htext);
    return rc;
}

/* --output: only the outputs named, in that order (the names are checked
 * for clashes among all outputs first: emit_c_check reports at the
 * derivation's outputs, which the plan's indices name) */
static int select_outputs(const EmitArgs *a, Plan *p, FILE *err)
{
    if (a->outputs.n == 0)
        return 0;
    int *sel = pc_xmalloc(sizeof *sel * (size_t)(p->noutputs + 1));
    int n = args_select_outputs(sel, &a->outputs, p, a->usage, err);
    if (n >= 0)
        plan_keep_outputs(p, sel, n);
    pc_free(sel);
    return n < 0 ? 2 : 0;
}

static int emit(const EmitArgs *a, const char *file, FILE *out, FILE *err)
{
    Derived *d = NULL;
    int rc;
    Plan *p = cli_plan_file(file, &a->budget, err, &rc, &d);
    if (!p) {
        budget_disarm();
        return rc;
    }
    if (!a->dump && emit_c_check(p, d, a->prefix, err) != 0)
        rc = 1;
    if (!rc)
        rc = select_outputs(a, p, err);
    if (!rc && a->collapsed) /* only the outputs written are analysed */
        lower_collapse(p, d);
    derived_free(d); /* the C is written from the Plan alone */
    if (!rc)
        rc = write_outputs(a, p, file, out, err);
    budget_disarm();
    plan_free(p);
    return rc;
}

int cli_emit_c(int argc, char **argv, FILE *out, FILE *err)
{
    EmitArgs a = {.functions = EMIT_C_ALL, .usage = help_usage("emit-c")};
    const char *file;
    int rc =
        args_parse(argc, argv, a.usage, &a.budget, &file, emit_option, &a, err);
    if (!rc)
        rc = check_names(&a, file, err);
    if (!rc)
        rc = emit(&a, file, out, err);
    args_names_clear(&a.outputs);
    return rc;
}
