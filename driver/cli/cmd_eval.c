/*
 * cmd_eval.c - `pointcalc eval FILE --at A=x,y ... [--set k=SPEC ...]
 * --param t=SPEC ... [--output NAMES] [--format csv|json]`: the outputs'
 * numbers at every sample of the grid (docs/eval.md).
 *
 *   cli_plan_file -> eval_setup -> per block of rows: plan_eval per
 *   output -> statuses reported on err -> table_row on out
 *
 * Rows are evaluated in blocks that share the consts' values (a swept
 * const changes only between blocks) and fit in about 8 MB of
 * coordinates per output.
 */
#include "driver/cli/cli.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/mem.h"
#include "base/numfmt.h"
#include "driver/cli/args.h"
#include "driver/cli/table.h"
#include "runtime/eval.h"

/* rows per block: up to CHUNK, fewer for high dimensions */
enum { CHUNK = 4096, CHUNK_VALUES = 1 << 20, MAX_MESSAGES = 10 };

typedef struct EvalOptions {
    EvalArgs args;
    TableFormat format;
    const char *usage;
} EvalOptions;

/* one block of rows */
typedef struct Block {
    size_t cap;          // rows it holds
    double **pv;         // per param: cap values
    double *consts;      // per const: the block's values
    double **res;        // per selected output: cap * columns values
    unsigned char **st;  // per selected output: cap statuses
    double *row;         // one row's params
    const double **vals; // per selected output: one row's coordinates
    unsigned char *rst;  // per selected output: one row's status
} Block;

/* samples that are not finite, by sort */
typedef struct Counts {
    size_t poles, nonfinite, domain;
} Counts;

static int eval_option(void *ctx, int argc, char **argv, int i, FILE *err)
{
    EvalOptions *o = ctx;
    int used = eval_args_option(&o->args, argc, argv, i, o->usage, err);
    const char *v = args_value(argc, argv, i);
    if (used != 0 || !v || strcmp(argv[i], "--format") != 0)
        return used;
    if (strcmp(v, "csv") == 0)
        o->format = TABLE_CSV;
    else if (strcmp(v, "json") == 0)
        o->format = TABLE_JSON;
    else {
        args_usage_error(err, o->usage,
                         "unknown format '%s'; expected csv or json", v);
        return -1;
    }
    return 2;
}

static void block_init(Block *b, const Plan *p, const EvalSetup *s)
{
    b->cap = s->dim > 0 && CHUNK_VALUES / (size_t)s->dim < CHUNK
                 ? CHUNK_VALUES / (size_t)s->dim
                 : CHUNK;
    if (b->cap == 0) // more than CHUNK_VALUES coordinates a point
        b->cap = 1;
    b->pv = pc_xmalloc(sizeof *b->pv * (size_t)(p->nparams + 1));
    b->res = pc_xmalloc(sizeof *b->res * (size_t)(s->nsel + 1));
    b->st = pc_xmalloc(sizeof *b->st * (size_t)(s->nsel + 1));
    b->row = pc_xmalloc(sizeof *b->row * (size_t)(p->nparams + 1));
    b->consts = pc_xmalloc(sizeof *b->consts * (size_t)(p->nconsts + 1));
    b->vals = pc_xmalloc(sizeof *b->vals * (size_t)(s->nsel + 1));
    b->rst = pc_xmalloc((size_t)s->nsel + 1);
    memcpy(b->consts, s->consts, sizeof *b->consts * (size_t)p->nconsts);
    for (int i = 0; i < p->nparams; i++)
        b->pv[i] = pc_xmalloc(sizeof **b->pv * b->cap);
    for (int j = 0; j < s->nsel; j++) {
        size_t nc = (size_t)table_columns(p, s->sel[j], s->dim);
        b->res[j] = pc_xmalloc(sizeof **b->res * b->cap * (nc ? nc : 1));
        b->st[j] = pc_xmalloc(b->cap);
    }
}

static void block_clear(Block *b, const Plan *p, const EvalSetup *s)
{
    for (int i = 0; i < p->nparams; i++)
        pc_free(b->pv[i]);
    for (int j = 0; j < s->nsel; j++) {
        pc_free(b->res[j]);
        pc_free(b->st[j]);
    }
    pc_free(b->pv);
    pc_free(b->res);
    pc_free(b->st);
    pc_free(b->row);
    pc_free(b->consts);
    pc_free(b->vals);
    pc_free(b->rst);
}

/* rows r0 .. r0+m-1 of the grid, evaluated */
static void block_eval(Block *b, const Plan *p, const EvalSetup *s, size_t r0,
                       size_t m)
{
    for (size_t r = 0; r < m; r++) {
        eval_setup_row(s, r0 + r, b->row, b->consts);
        for (int i = 0; i < p->nparams; i++)
            b->pv[i][r] = b->row[i];
    }
    for (int j = 0; j < s->nsel; j++)
        plan_eval(p, s->sel[j], m, (const double *const *)b->pv, b->consts,
                  (const double *const *)s->pt, s->dim, b->res[j], b->st[j]);
}

/* " at t=0.5, k=2" for row r of the block (nothing without an axis) */
static void where(FILE *err, const Plan *p, const EvalSetup *s, const Block *b,
                  size_t r)
{
    int first = 1;
    for (int pass = 0; pass < 2; pass++)
        for (int i = 0; i < s->naxes; i++) {
            const EvalAxis *x = &s->axes[i];
            if ((x->param >= 0) != (pass == 0))
                continue;
            pc_fprintf(err, "%s %s=%.17g", first ? " at" : ",",
                       x->param >= 0 ? p->params[x->param] : p->consts[x->cnst],
                       x->param >= 0 ? b->pv[x->param][r] : b->consts[x->cnst]);
            first = 0;
        }
}

static const char *status_message(unsigned char st)
{
    switch (st) {
    case PLAN_STATUS_POLE:
        return ": a denominator of its equation vanishes; written as nan\n";
    case PLAN_STATUS_DOMAIN:
        return " is undefined: a function's argument is outside its domain "
               "(sqrt of a negative number, ln of one <= 0, asin or acos "
               "beyond [-1, 1], natx or naty of a phase turning more than "
               "32768 radians); written as nan\n";
    case PLAN_STATUS_OVERFLOW:
        return " is not finite in double precision (a denominator of its "
               "equation overflows); written as nan\n";
    default:
        return " is not finite in double precision (overflow in its "
               "equation's terms)\n";
    }
}

/* counts the status of output j at row r of the block, and reports the
 * first MAX_MESSAGES on err */
static void report(FILE *err, const Plan *p, const EvalSetup *s, const Block *b,
                   int j, size_t r, Counts *n)
{
    unsigned char st = b->st[j][r];
    size_t k = n->poles + n->nonfinite + n->domain;
    if (st == PLAN_STATUS_POLE)
        n->poles++;
    else if (st == PLAN_STATUS_DOMAIN)
        n->domain++;
    else
        n->nonfinite++;
    if (k >= MAX_MESSAGES)
        return;
    fprintf(err, "pointcalc: eval: %s%s",
            st == PLAN_STATUS_POLE ? "pole of " : "",
            p->outputs[s->sel[j]].name);
    where(err, p, s, b, r);
    /* outside a declared range that the derivation assumed? */
    for (int i = 0;
         st == PLAN_STATUS_DOMAIN && p->bound && i < p->nparams + p->nconsts;
         i++) {
        double x = i < p->nparams ? b->pv[i][r] : b->consts[i - p->nparams];
        if (plan_out_of_bounds(p, i, x)) {
            fprintf(err,
                    " is undefined: %s is outside %s, its declared range, "
                    "on which the derivation simplified the equation; "
                    "written as nan\n",
                    i < p->nparams ? p->params[i] : p->consts[i - p->nparams],
                    p->bound[i].text ? p->bound[i].text : "its range");
            return;
        }
    }
    fputs(status_message(st), err);
}

static int finite_row(const double *v, int n)
{
    for (int c = 0; c < n; c++)
        if (!isfinite(v[c]))
            return 0;
    return 1;
}

/* row r of the block: statuses settled and reported, then written; a
 * non-finite value without a status (a numerator's terms overflowed)
 * becomes TABLE_STATUS_TERMS */
static void block_row(FILE *out, FILE *err, TableFormat f, const Plan *p,
                      const EvalSetup *s, Block *b, size_t r, size_t index,
                      Counts *n)
{
    for (int j = 0; j < s->nsel; j++) {
        int nc = table_columns(p, s->sel[j], s->dim);
        b->vals[j] = b->res[j] + r * (size_t)nc;
        if (b->st[j][r] == PLAN_STATUS_OK && !finite_row(b->vals[j], nc))
            b->st[j][r] = TABLE_STATUS_TERMS;
        if (b->st[j][r] != PLAN_STATUS_OK)
            report(err, p, s, b, j, r, n);
        b->rst[j] = b->st[j][r];
    }
    for (int i = 0; i < p->nparams; i++)
        b->row[i] = b->pv[i][r];
    TableRow row = {b->row, b->consts, b->vals, b->rst};
    table_row(out, f, p, s, &row, index);
}

/* the count after the first MAX_MESSAGES messages */
static void summary(FILE *err, const Counts *n)
{
    if (n->poles + n->nonfinite + n->domain <= MAX_MESSAGES)
        return;
    if (n->domain)
        fprintf(err,
                "pointcalc: eval: ... %zu poles, %zu non-finite and %zu "
                "undefined samples in all\n",
                n->poles, n->nonfinite, n->domain);
    else
        fprintf(err,
                "pointcalc: eval: ... %zu poles and %zu non-finite samples "
                "in all\n",
                n->poles, n->nonfinite);
}

/* every row of the grid; 1 when some sample is not finite */
static int eval_rows(FILE *out, FILE *err, TableFormat f, const Plan *p,
                     const EvalSetup *s)
{
    Block b;
    Counts n = {0, 0, 0};
    block_init(&b, p, s);
    table_head(out, f, p, s);
    for (size_t r0 = 0, m; r0 < s->rows; r0 += m) {
        size_t run = eval_setup_run(s, r0);
        m = run < b.cap ? run : b.cap;
        block_eval(&b, p, s, r0, m);
        for (size_t r = 0; r < m; r++)
            block_row(out, err, f, p, s, &b, r, r0 + r, &n);
    }
    table_tail(out, f, s->rows);
    summary(err, &n);
    block_clear(&b, p, s);
    return n.poles + n.nonfinite + n.domain > 0;
}

/* out gets the rows only once all of them are written: they go to a
 * temporary file first (a counted memory stream where none can be made),
 * so that a budget that runs out on the way (its handler ends the process)
 * leaves nothing on stdout, as for every exit 1 of a scheme
 * (docs/language.md).  The table can be larger than memory; the file
 * holds it. */
static int eval_committed(FILE *out, FILE *err, TableFormat f, const Plan *p,
                          const EvalSetup *s)
{
    char *text = NULL;
    size_t len = 0;
    FILE *tmp = tmpfile();
    FILE *t = tmp ? tmp : pc_xopen_memstream(&text, &len);
    int rc = eval_rows(t, err, f, p, s);
    if (!tmp) {
        pc_xclose_memstream(t);
        fwrite(text, 1, len, out);
        pc_free(text);
        return rc;
    }
    char buf[8192];
    size_t n;
    int bad = fflush(tmp) != 0 || ferror(tmp);
    rewind(tmp);
    while (!bad && (n = fread(buf, 1, sizeof buf, tmp)) > 0)
        bad = fwrite(buf, 1, n, out) != n;
    bad = bad || ferror(tmp);
    fclose(tmp);
    if (bad) {
        fprintf(err, "pointcalc: cannot write the output: %s\n",
                strerror(errno));
        return 1;
    }
    return rc;
}

int cli_eval(int argc, char **argv, FILE *out, FILE *err)
{
    EvalOptions o = {.format = TABLE_CSV, .usage = help_usage("eval")};
    BudgetOptions bo;
    const char *file;
    eval_args_init(&o.args);
    int rc = args_parse(argc, argv, o.usage, &bo, &file, eval_option, &o, err);
    Plan *p = rc ? NULL : cli_plan_file(file, &bo, err, &rc, NULL);
    budget_disarm(); /* evaluation takes what the grid asks for */
    if (p) {
        EvalSetup s;
        rc = eval_setup(&s, &o.args, p, o.usage, err);
        if (!rc)
            rc = eval_committed(out, err, o.format, p, &s);
        eval_setup_clear(&s);
        plan_free(p);
    }
    eval_args_clear(&o.args);
    return rc;
}
