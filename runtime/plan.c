/*
 * plan.c - building, pruning and dumping Plans (see plan.h).
 *
 * The builder is a hash-consing constructor in the style of a value-numbering
 * pass: every request (op, a, b) is looked up in an open-addressing table of
 * existing instructions before a new one is appended, so common
 * subexpressions of all weights of all outputs are shared for free.  Before
 * the lookup, requests are normalised (commutative operands ordered,
 * constants folded, x*1 / x+0 / -(-x) simplified) so that equal values
 * built in different ways still meet.
 */
#include "runtime/plan.h"

#include "base/mem.h"
#include "base/numfmt.h"
#include "runtime/natural.h"

#include <assert.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

static char **copy_names(int n, const char *const *names)
{
    char **v = pc_xmalloc(sizeof *v * (size_t)n);
    for (int i = 0; i < n; i++)
        v[i] = pc_xstrdup(names[i]);
    return v;
}

static void free_names(int n, char **v)
{
    for (int i = 0; i < n; i++)
        pc_free(v[i]);
    pc_free(v);
}

static const struct {
    const char *name;
    int nargs;
} op_info[] = {
#define PLAN_INFO(name, nargs, cop) {#name, nargs},
    PLAN_OPS(PLAN_INFO)
#undef PLAN_INFO
};

/* the names in lower case, as the dumps write them: a constant table (no
 * state to build, so any thread may read it) kept in the order of PLAN_OPS
 * by the assertion below and by test_plan's dumps */
static const char *const op_lower[] = {
    "const", "input", "neg",  "add",  "sub",   "mul",
    "div",   "powi",  "pole", "fn",   "atan2", "domain",
    "dist",  "coord", "natx", "naty", "isnan",
};
_Static_assert(sizeof op_lower / sizeof *op_lower == PLAN_NOPS,
               "op_lower: one name per PLAN_OPS entry");

const char *plan_op_name(PlanOp op)
{
    assert(op < PLAN_NOPS);
    return op_lower[op];
}

int plan_op_nargs(PlanOp op)
{
    assert(op < PLAN_NOPS);
    return op_info[op].nargs;
}

Plan *plan_new(const char *name, int nparams, const char *const *params,
               int nconsts, const char *const *consts, int npoints,
               const char *const *points)
{
    Plan *p = pc_xmalloc(sizeof *p);
    memset(p, 0, sizeof *p);
    p->name = pc_xstrdup(name);
    p->nparams = nparams;
    p->nconsts = nconsts;
    p->npoints = npoints;
    p->params = copy_names(nparams, params);
    p->consts = copy_names(nconsts, consts);
    p->points = copy_names(npoints, points);
    return p;
}

static void collapse_output_clear(CollapseOutput *o)
{
    pc_free(o->name);
    pc_free(o->why);
    pc_free(o->point);
    pc_free(o->a);
    pc_free(o->b);
}

void collapse_free(Collapse *c)
{
    if (!c)
        return;
    for (int i = 0; i < c->n; i++)
        collapse_output_clear(&c->o[i]);
    pc_free(c->o);
    pc_free(c);
}

static void output_clear(PlanOutput *o)
{
    pc_free(o->name);
    pc_free(o->point);
    pc_free(o->reg);
}

void plan_free(Plan *p)
{
    if (!p)
        return;
    pc_free(p->name);
    free_names(p->nparams, p->params);
    free_names(p->nconsts, p->consts);
    free_names(p->npoints, p->points);
    for (int o = 0; o < p->noutputs; o++)
        output_clear(&p->outputs[o]);
    pc_free(p->outputs);
    for (int i = 0; p->bound && i < p->nparams + p->nconsts; i++)
        pc_free(p->bound[i].text);
    pc_free(p->bound);
    collapse_free(p->collapse);
    pc_free(p->ins);
    pc_free(p->k);
    pc_free(p->hash);
    pc_free(p);
}

int plan_out_of_bounds(const Plan *p, int i, double x)
{
    if (!p->bound || i < 0 || i >= p->nparams + p->nconsts)
        return 0;
    const PlanBound *b = &p->bound[i];
    if ((b->flags & PLAN_BOUND_LO) &&
        (b->flags & PLAN_BOUND_LO_OPEN ? !(x > b->lo) : !(x >= b->lo)))
        return 1;
    if ((b->flags & PLAN_BOUND_HI) &&
        (b->flags & PLAN_BOUND_HI_OPEN ? !(x < b->hi) : !(x <= b->hi)))
        return 1;
    return 0;
}

/* ---- hash-consing ------------------------------------------------------ */

/* The key of an instruction: its op and operands, for CONST the value's
 * bits (so equal constants share one register whatever their pool slot). */
static uint64_t key_of(const Plan *p, PlanOp op, int32_t a, int32_t b)
{
    uint64_t h = (uint64_t)op * 0x9E3779B97F4A7C15u;
    if (op == PLAN_CONST) {
        uint64_t bits;
        memcpy(&bits, &p->k[a], sizeof bits);
        h ^= bits;
    } else {
        h ^= (uint64_t)(uint32_t)a * 0xC2B2AE3D27D4EB4Fu;
        h ^= (uint64_t)(uint32_t)b * 0x165667B19E3779F9u;
    }
    h ^= h >> 29;
    h *= 0xBF58476D1CE4E5B9u;
    h ^= h >> 32;
    return h;
}

static int same(const Plan *p, const PlanIns *x, PlanOp op, int32_t a,
                int32_t b)
{
    if (x->op != op)
        return 0;
    if (op == PLAN_CONST)
        return memcmp(&p->k[x->a], &p->k[a], sizeof(double)) == 0;
    return x->a == a && x->b == b;
}

static void rehash(Plan *p, int cap)
{
    pc_free(p->hash);
    p->hcap = cap;
    p->hash = pc_xmalloc(sizeof *p->hash * (size_t)cap);
    for (int i = 0; i < cap; i++)
        p->hash[i] = -1;
    for (int i = 0; i < p->nins; i++) {
        const PlanIns *x = &p->ins[i];
        uint64_t h = key_of(p, (PlanOp)x->op, x->a, x->b);
        int s = (int)(h & (uint64_t)(cap - 1));
        while (p->hash[s] >= 0)
            s = (s + 1) & (cap - 1);
        p->hash[s] = i;
    }
}

/* Finds (op, a, b) or appends it.  For CONST, a is a pool slot that is
 * released again when the constant already exists. */
static int intern(Plan *p, PlanOp op, int32_t a, int32_t b)
{
    if (!p->hash || 2 * (p->nins + 1) > p->hcap)
        rehash(p, p->hcap ? 2 * p->hcap : 64);
    uint64_t h = key_of(p, op, a, b);
    int s = (int)(h & (uint64_t)(p->hcap - 1));
    for (; p->hash[s] >= 0; s = (s + 1) & (p->hcap - 1))
        if (same(p, &p->ins[p->hash[s]], op, a, b)) {
            if (op == PLAN_CONST)
                p->nk--; // the slot just pushed is not needed
            return p->hash[s];
        }
    if (p->nins == p->ains) {
        p->ains = p->ains ? 2 * p->ains : 64;
        p->ins = pc_xrealloc(p->ins, sizeof *p->ins * (size_t)p->ains);
    }
    PlanIns *x = &p->ins[p->nins];
    x->op = (uint8_t)op;
    x->a = a;
    x->b = b;
    x->line = p->line;
    switch (op) {
    case PLAN_CONST:
        x->uniform = 1;
        break;
    case PLAN_INPUT:
        x->uniform = a >= p->nparams;
        break;
    case PLAN_DIST:
    case PLAN_COORD:
        x->uniform = 1;
        break;
    default:
        x->uniform =
            p->ins[a].uniform && (plan_op_nargs(op) < 2 || p->ins[b].uniform);
    }
    p->hash[s] = p->nins;
    return p->nins++;
}

/* ---- builder ----------------------------------------------------------- */

int plan_const(Plan *p, double v)
{
    if (v == 0)
        v = 0; // one zero: -0.0 and 0.0 share a register
    if (p->nk == p->ak) {
        p->ak = p->ak ? 2 * p->ak : 32;
        p->k = pc_xrealloc(p->k, sizeof *p->k * (size_t)p->ak);
    }
    p->k[p->nk] = v;
    return intern(p, PLAN_CONST, p->nk++, 0);
}

int plan_input(Plan *p, int index)
{
    assert(index >= 0 && index < p->nparams + p->nconsts);
    return intern(p, PLAN_INPUT, index, 0);
}

int plan_dist(Plan *p, int a, int b)
{
    assert(a >= 0 && a < b && b < p->npoints);
    return intern(p, PLAN_DIST, a, b);
}

int plan_coord(Plan *p, int a, int c)
{
    assert(a >= 0 && a < p->npoints && c >= 0);
    return intern(p, PLAN_COORD, a, c);
}

int plan_output_min_dim(const Plan *p, int o, int *point)
{
    int need = 0, any = 0;
    if (point)
        *point = -1;
    for (int i = 0; i < p->nins && !any; i++)
        any = p->ins[i].op == PLAN_COORD;
    if (!any)
        return 0;
    unsigned char *live = pc_xmalloc((size_t)p->nins + 1);
    plan_live(p, o, live);
    for (int i = 0; i < p->nins; i++)
        if (live[i] && p->ins[i].op == PLAN_COORD && p->ins[i].b + 1 > need) {
            need = p->ins[i].b + 1;
            if (point)
                *point = p->ins[i].a;
        }
    pc_free(live);
    return need;
}

static int is_const(const Plan *p, int r, double *v)
{
    if (p->ins[r].op != PLAN_CONST)
        return 0;
    if (v)
        *v = p->k[p->ins[r].a];
    return 1;
}

static int is_value(const Plan *p, int r, double v)
{
    double c;
    return is_const(p, r, &c) && c == v;
}

static int plan_node(Plan *p, PlanOp op, int a, int b)
{
    double x = 0, y = 0;
    int nargs = plan_op_nargs(op);
    assert(op != PLAN_CONST && op != PLAN_INPUT);
    assert(a >= 0 && a < p->nins);
    assert(nargs < 2 || (b >= 0 && b < p->nins));
    /* fold constants */
    if (is_const(p, a, &x) && (nargs < 2 || is_const(p, b, &y))) {
        switch (op) {
        case PLAN_NEG:
            return plan_const(p, -x);
        case PLAN_ADD:
            return plan_const(p, x + y);
        case PLAN_SUB:
            return plan_const(p, x - y);
        case PLAN_MUL:
            return plan_const(p, x * y);
        case PLAN_DIV:
            if (y != 0)
                return plan_const(p, x / y);
            break;
        case PLAN_POWI:
            return plan_const(p, pow(x, (double)b));
        case PLAN_POLE:
            return plan_const(p, x == 0 ? 1 : 0);
        case PLAN_FN:
            return plan_const(p, plan_fn_eval(b, x));
        case PLAN_ATAN2:
            return plan_const(p, atan2(x, y));
        case PLAN_DOMAIN:
            return plan_const(p, plan_domain_eval(b, x));
        case PLAN_NATX:
        case PLAN_NATY:
            return plan_const(p,
                              plan_natural_eval(op == PLAN_NATY, p->k + b, x));
        case PLAN_ISNAN:
            return plan_const(p, isnan(x) ? 1 : 0);
        default:
            break;
        }
    }
    /* simplify and normalise */
    switch (op) {
    case PLAN_NEG:
        if (p->ins[a].op == PLAN_NEG)
            return p->ins[a].a;
        b = 0;
        break;
    case PLAN_ADD:
        if (is_value(p, a, 0))
            return b;
        if (is_value(p, b, 0))
            return a;
        if (p->ins[b].op == PLAN_NEG)
            return plan_node(p, PLAN_SUB, a, p->ins[b].a);
        if (p->ins[a].op == PLAN_NEG)
            return plan_node(p, PLAN_SUB, b, p->ins[a].a);
        if (is_const(p, b, &y) && y < 0)
            return plan_node(p, PLAN_SUB, a, plan_const(p, -y));
        if (is_const(p, a, &x) && x < 0)
            return plan_node(p, PLAN_SUB, b, plan_const(p, -x));
        if (a > b) {
            int t = a;
            a = b;
            b = t;
        }
        break;
    case PLAN_SUB:
        if (is_value(p, b, 0))
            return a;
        if (is_value(p, a, 0))
            return plan_neg(p, b);
        if (p->ins[b].op == PLAN_NEG)
            return plan_node(p, PLAN_ADD, a, p->ins[b].a);
        if (is_const(p, b, &y) && y < 0)
            return plan_node(p, PLAN_ADD, a, plan_const(p, -y));
        break;
    case PLAN_MUL:
        if (is_value(p, a, 1))
            return b;
        if (is_value(p, b, 1))
            return a;
        if (is_value(p, a, -1))
            return plan_neg(p, b);
        if (is_value(p, b, -1))
            return plan_neg(p, a);
        if (is_value(p, a, 0) || is_value(p, b, 0))
            return plan_const(p, 0);
        if (p->ins[a].op == PLAN_NEG)
            return plan_neg(p, plan_mul(p, p->ins[a].a, b));
        if (p->ins[b].op == PLAN_NEG)
            return plan_neg(p, plan_mul(p, a, p->ins[b].a));
        if (a > b) {
            int t = a;
            a = b;
            b = t;
        }
        break;
    case PLAN_DIV:
        if (is_value(p, b, 1))
            return a;
        break;
    case PLAN_POWI:
        assert(b > PLAN_POW_CHAIN);
        break;
    case PLAN_POLE:
        if (p->ins[a].op == PLAN_NEG)
            a = p->ins[a].a;
        b = 0;
        break;
    default:
        break;
    }
    return intern(p, op, a, b);
}

int plan_fn(Plan *p, int fn, int a)
{
    return plan_node(p, PLAN_FN, a, fn);
}

int plan_atan2(Plan *p, int y, int x)
{
    return plan_node(p, PLAN_ATAN2, y, x);
}

double plan_natural_eval(int y, const double *k, double u)
{
    double vx, vy;
    nat_law_xy(k, u, &vx, &vy);
    return y ? vy : vx;
}

int plan_natural(Plan *p, int y, int u, const double *k)
{
    int b = -1; /* a law in the pool already (4 slots from b) */
    for (int i = 0; i < p->nins && b < 0; i++)
        if ((p->ins[i].op == PLAN_NATX || p->ins[i].op == PLAN_NATY) &&
            memcmp(p->k + p->ins[i].b, k, 4 * sizeof *k) == 0)
            b = p->ins[i].b;
    if (b < 0) {
        while (p->nk + 4 > p->ak) {
            p->ak = p->ak ? 2 * p->ak : 32;
            p->k = pc_xrealloc(p->k, sizeof *p->k * (size_t)p->ak);
        }
        b = p->nk;
        memcpy(p->k + b, k, 4 * sizeof *k);
        p->nk += 4;
    }
    return plan_node(p, y ? PLAN_NATY : PLAN_NATX, u, b);
}

int plan_isnan(Plan *p, int a)
{
    return plan_node(p, PLAN_ISNAN, a, 0);
}

int plan_domain(Plan *p, int fn, int a)
{
    return plan_node(p, PLAN_DOMAIN, a, fn);
}

int plan_neg(Plan *p, int a)
{
    return plan_node(p, PLAN_NEG, a, 0);
}

int plan_add(Plan *p, int a, int b)
{
    return plan_node(p, PLAN_ADD, a, b);
}

int plan_sub(Plan *p, int a, int b)
{
    return plan_node(p, PLAN_SUB, a, b);
}

int plan_mul(Plan *p, int a, int b)
{
    return plan_node(p, PLAN_MUL, a, b);
}

int plan_div(Plan *p, int a, int b)
{
    return plan_node(p, PLAN_DIV, a, b);
}

int plan_pole(Plan *p, int den)
{
    return plan_node(p, PLAN_POLE, den, 0);
}

/* x^e by a shared multiplication chain for small e (x^3 = x^2*x and
 * x^4 = x^2*x^2 reuse x^2), one POWI above PLAN_POW_CHAIN; negative powers
 * are the lowering's business (they never reach here). */
int plan_pow(Plan *p, int a, long e)
{
    assert(e >= 0 && e <= INT32_MAX);
    if (e == 0)
        return plan_const(p, 1);
    if (e == 1)
        return a;
    if (p->ins[a].op == PLAN_NEG) {
        int r = plan_pow(p, p->ins[a].a, e);
        return e % 2 ? plan_neg(p, r) : r;
    }
    if (e > PLAN_POW_CHAIN)
        return plan_node(p, PLAN_POWI, a, (int)e);
    if (e % 2 == 0) {
        int h = plan_pow(p, a, e / 2);
        return plan_mul(p, h, h);
    }
    return plan_mul(p, plan_pow(p, a, e - 1), a);
}

int plan_peel(const Plan *p, int w, int *sign)
{
    *sign = 1;
    if (p->ins[w].uniform)
        return w;
    while (p->ins[w].op == PLAN_NEG) {
        *sign = -*sign;
        w = p->ins[w].a;
    }
    return w;
}

void plan_add_output(Plan *p, const char *name, Kind kind, int line, int nterms,
                     const int *point, const int *reg, int bad)
{
    p->outputs =
        pc_xrealloc(p->outputs, sizeof *p->outputs * (size_t)(p->noutputs + 1));
    PlanOutput *o = &p->outputs[p->noutputs++];
    o->name = pc_xstrdup(name);
    o->kind = kind;
    o->line = line;
    o->nterms = nterms;
    o->point = pc_xmalloc(sizeof *o->point * (size_t)nterms);
    o->reg = pc_xmalloc(sizeof *o->reg * (size_t)nterms);
    memcpy(o->point, point, sizeof *o->point * (size_t)nterms);
    memcpy(o->reg, reg, sizeof *o->reg * (size_t)nterms);
    o->bad = bad;
}

/* ---- passes ------------------------------------------------------------ */

static int has_reg_operand(const PlanIns *x, int which)
{
    int n = plan_op_nargs((PlanOp)x->op);
    return which < n;
}

void plan_live(const Plan *p, int o, unsigned char *live)
{
    memset(live, 0, (size_t)p->nins);
    for (int i = 0; i < p->noutputs; i++) {
        if (o >= 0 && i != o)
            continue;
        const PlanOutput *out = &p->outputs[i];
        for (int k = 0; k < out->nterms; k++)
            live[out->reg[k]] = 1;
        if (out->bad >= 0)
            live[out->bad] = 1;
    }
    plan_live_close(p, live);
}

void plan_live_close(const Plan *p, unsigned char *live)
{
    /* operands precede their users: one backward sweep suffices */
    for (int i = p->nins - 1; i >= 0; i--) {
        if (!live[i])
            continue;
        const PlanIns *x = &p->ins[i];
        if (has_reg_operand(x, 0))
            live[x->a] = 1;
        if (has_reg_operand(x, 1))
            live[x->b] = 1;
    }
}

void plan_prune(Plan *p)
{
    unsigned char *live = pc_xmalloc((size_t)p->nins);
    int *map = pc_xmalloc(sizeof *map * (size_t)p->nins);
    plan_live(p, -1, live);
    int n = 0;
    for (int i = 0; i < p->nins; i++) {
        map[i] = -1;
        if (!live[i])
            continue;
        PlanIns x = p->ins[i];
        if (has_reg_operand(&x, 0))
            x.a = map[x.a];
        if (has_reg_operand(&x, 1))
            x.b = map[x.b];
        map[i] = n;
        p->ins[n++] = x;
    }
    p->nins = n;
    for (int i = 0; i < p->noutputs; i++) {
        PlanOutput *o = &p->outputs[i];
        for (int k = 0; k < o->nterms; k++)
            o->reg[k] = map[o->reg[k]];
        if (o->bad >= 0)
            o->bad = map[o->bad];
    }
    pc_free(map);
    pc_free(live);
    pc_free(p->hash); // rebuilt on the next plan_node
    p->hash = NULL;
    p->hcap = 0;
}

void plan_keep_outputs(Plan *p, const int *sel, int n)
{
    PlanOutput *kept = pc_xcalloc((size_t)n + 1, sizeof *kept);
    unsigned char *keep = pc_xcalloc((size_t)p->noutputs + 1, 1);
    for (int i = 0; i < n; i++) {
        kept[i] = p->outputs[sel[i]]; // its arrays move
        keep[sel[i]] = 1;
    }
    Collapse *c = p->collapse; /* its forms follow their outputs */
    CollapseOutput *ck = c ? pc_xcalloc((size_t)n + 1, sizeof *ck) : NULL;
    for (int i = 0; c && i < n; i++)
        ck[i] = c->o[sel[i]]; // its arrays move too
    for (int o = 0; o < p->noutputs; o++)
        if (!keep[o]) {
            output_clear(&p->outputs[o]);
            if (c)
                collapse_output_clear(&c->o[o]);
        }
    pc_free(keep);
    pc_free(p->outputs);
    p->outputs = kept;
    if (c) {
        pc_free(c->o);
        c->o = ck;
        c->n = n;
    }
    p->noutputs = n;
    plan_prune(p);
}

int plan_find_output(const Plan *p, const char *name)
{
    for (int i = 0; i < p->noutputs; i++)
        if (strcmp(p->outputs[i].name, name) == 0)
            return i;
    return -1;
}

static void dump_names(FILE *out, const char *what, int n, char **names)
{
    fprintf(out, " %s", what);
    if (n == 0)
        fputs(" -", out);
    for (int i = 0; i < n; i++)
        fprintf(out, " %s", names[i]);
    fputc(';', out);
}

void plan_dump(FILE *out, const Plan *p)
{
    fprintf(out, "plan %s:", p->name);
    dump_names(out, "params", p->nparams, p->params);
    dump_names(out, "consts", p->nconsts, p->consts);
    dump_names(out, "points", p->npoints, p->points);
    fputc('\n', out);
    for (int i = 0; i < p->nins; i++) {
        const PlanIns *x = &p->ins[i];
        fprintf(out, "  r%d = %s", i, plan_op_name((PlanOp)x->op));
        switch ((PlanOp)x->op) {
        case PLAN_CONST:
            pc_fprintf(out, " %.17g", p->k[x->a]);
            break;
        case PLAN_INPUT:
            fprintf(out, " %s",
                    x->a < p->nparams ? p->params[x->a]
                                      : p->consts[x->a - p->nparams]);
            break;
        case PLAN_POWI:
            fprintf(out, " r%d %d", x->a, x->b);
            break;
        case PLAN_FN:
        case PLAN_DOMAIN:
            fprintf(out, " r%d fn%d", x->a, x->b);
            break;
        case PLAN_DIST:
            fprintf(out, " %s %s", p->points[x->a], p->points[x->b]);
            break;
        case PLAN_COORD:
            fprintf(out, " %s %d", p->points[x->a], x->b);
            break;
        case PLAN_NATX:
        case PLAN_NATY:
            pc_fprintf(out, " r%d law %.17g %.17g %.17g %.17g", x->a,
                       p->k[x->b], p->k[x->b + 1], p->k[x->b + 2],
                       p->k[x->b + 3]);
            break;
        default:
            fprintf(out, " r%d", x->a);
            if (plan_op_nargs((PlanOp)x->op) == 2)
                fprintf(out, " r%d", x->b);
        }
        fprintf(out, "%s  # line %d\n", x->uniform ? " uniform" : "", x->line);
    }
    for (int i = 0; i < p->noutputs; i++) {
        const PlanOutput *o = &p->outputs[i];
        fprintf(out, "  output %s %s line %d:", o->name, kind_name(o->kind),
                o->line);
        for (int k = 0; k < o->nterms; k++)
            fprintf(out, " %s=r%d",
                    o->point[k] < 0 ? "value" : p->points[o->point[k]],
                    o->reg[k]);
        if (o->bad >= 0)
            fprintf(out, "; pole r%d", o->bad);
        fputc('\n', out);
    }
}
