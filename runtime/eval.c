/*
 * eval.c - interpreting a Plan in blocks of samples.
 *
 * A call prepares the program once: it keeps only the instructions the
 * output needs, splits them into uniform ones (evaluated once, as scalars,
 * then broadcast) and varying ones, and gives every varying register a slot
 * of PLAN_BLOCK doubles by linear scan, reusing slots whose value is dead
 * (a slot is freed only after the instruction that reads it last has got
 * its own slot, so destination and operands never overlap - which is what
 * the `restrict` kernels below promise the compiler).
 *
 * Each block then runs one tight, fixed-length loop per instruction; with
 * restrict and a constant trip count gcc -O2 vectorises them.  The tail of
 * the input is padded with zeros; padded lanes are computed and dropped.
 */
#define _POSIX_C_SOURCE 200809L // in case the build does not say so

#include "runtime/eval.h"

#include <assert.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "base/mem.h"

enum { BL = PLAN_BLOCK };

/* ---- block kernels ----------------------------------------------------- */

static void k_neg(double *restrict d, const double *restrict a)
{
    for (int j = 0; j < BL; j++)
        d[j] = -a[j];
}

static void k_add(double *restrict d, const double *restrict a,
                  const double *restrict b)
{
    for (int j = 0; j < BL; j++)
        d[j] = a[j] + b[j];
}

static void k_sub(double *restrict d, const double *restrict a,
                  const double *restrict b)
{
    for (int j = 0; j < BL; j++)
        d[j] = a[j] - b[j];
}

static void k_mul(double *restrict d, const double *restrict a,
                  const double *restrict b)
{
    for (int j = 0; j < BL; j++)
        d[j] = a[j] * b[j];
}

static void k_div(double *restrict d, const double *restrict a,
                  const double *restrict b)
{
    for (int j = 0; j < BL; j++)
        d[j] = a[j] / b[j];
}

static void k_pole(double *restrict d, const double *restrict a)
{
    for (int j = 0; j < BL; j++)
        d[j] = (double)(a[j] == 0); // not ?: (see codegen/emit_weights.c)
}

static void k_powi(double *restrict d, const double *restrict a, int e)
{
    for (int j = 0; j < BL; j++)
        d[j] = pow(a[j], (double)e);
}

/* acc = w * c  /  acc += w * c  /  sum of a block (pole flags) */
static void k_scale(double *restrict acc, const double *restrict w, double c)
{
    for (int j = 0; j < BL; j++)
        acc[j] = w[j] * c;
}

static void k_axpy(double *restrict acc, const double *restrict w, double c)
{
    for (int j = 0; j < BL; j++)
        acc[j] += w[j] * c;
}

/* interleave 2 or 3 columns into rows: fixed trip count, so vectorised */
static void k_store2(double *restrict o, const double *restrict a,
                     const double *restrict b)
{
    for (int j = 0; j < BL; j++) {
        o[2 * j] = a[j];
        o[2 * j + 1] = b[j];
    }
}

static void k_store3(double *restrict o, const double *restrict a,
                     const double *restrict b, const double *restrict c)
{
    for (int j = 0; j < BL; j++) {
        o[3 * j] = a[j];
        o[3 * j + 1] = b[j];
        o[3 * j + 2] = c[j];
    }
}

static double k_sum(const double *restrict a)
{
    double s = 0;
    for (int j = 0; j < BL; j++)
        s += a[j];
    return s;
}

/* ---- preparation ------------------------------------------------------- */

typedef struct Prog {
    int nv;       // varying instructions, in order
    int *v;       // their instruction indices
    int *slot;    // slot of every register (-1: not needed)
    int nslots;   // slots of BL doubles
    double *rf;   // register file: nslots * BL, 64-byte aligned
    int *root;    // per weight slot: the register actually read
    double *coef; // per weight slot: its sign (plan_peel), on the points
} Prog;

static double scalar_op(const Plan *p, const PlanIns *x, const double *val)
{
    switch ((PlanOp)x->op) {
    case PLAN_NEG:
        return -val[x->a];
    case PLAN_ADD:
        return val[x->a] + val[x->b];
    case PLAN_SUB:
        return val[x->a] - val[x->b];
    case PLAN_MUL:
        return val[x->a] * val[x->b];
    case PLAN_DIV:
        return val[x->a] / val[x->b];
    case PLAN_POWI:
        return pow(val[x->a], (double)x->b);
    case PLAN_POLE:
        return val[x->a] == 0 ? 1.0 : 0.0;
    case PLAN_FN:
        return plan_fn_eval(x->b, val[x->a]);
    case PLAN_ATAN2:
        return atan2(val[x->a], val[x->b]);
    case PLAN_DOMAIN:
        return plan_domain_eval(x->b, val[x->a]);
    case PLAN_NATX:
    case PLAN_NATY:
        return plan_natural_eval(x->op == PLAN_NATY, p->k + x->b, val[x->a]);
    case PLAN_ISNAN:
        return isnan(val[x->a]) ? 1.0 : 0.0;
    default:
        (void)p;
        assert(0 && "not a computing op");
        return 0;
    }
}

/* Keeps what output o needs, evaluates the uniform part, assigns slots. */
static void prog_init(Prog *g, const Plan *p, int o, const double *consts,
                      const double *const *points, int dim)
{
    int n = p->nins;
    unsigned char *live = pc_xmalloc((size_t)n);
    int *last = pc_xmalloc(sizeof *last * (size_t)n);
    double *uval = pc_xmalloc(sizeof *uval * (size_t)n);
    /* peephole (plan_peel): a weight -x is read as x, and the sign goes to
     * the point's coordinates once per call instead of every sample;
     * liveness then starts from those roots */
    const PlanOutput *po = &p->outputs[o];
    g->root = pc_xmalloc(sizeof *g->root * (size_t)(po->nterms + 1));
    g->coef = pc_xmalloc(sizeof *g->coef * (size_t)(po->nterms + 1));
    memset(live, 0, (size_t)n);
    for (int k = 0; k < po->nterms; k++) {
        int sign;
        int r = plan_peel(p, po->reg[k], &sign);
        g->root[k] = r;
        g->coef[k] = sign;
        live[r] = 1;
    }
    if (po->bad >= 0)
        live[po->bad] = 1;
    plan_live_close(p, live);
    /* the uniform registers this output needs, once per call */
    for (int i = 0; i < n; i++) {
        const PlanIns *x = &p->ins[i];
        if (!live[i] || !x->uniform)
            continue;
        if (x->op == PLAN_CONST)
            uval[i] = p->k[x->a];
        else if (x->op == PLAN_INPUT)
            uval[i] = consts[x->a - p->nparams];
        else if (x->op == PLAN_DIST)
            uval[i] = plan_dist_eval(points[x->a], points[x->b], dim);
        else if (x->op == PLAN_COORD)
            uval[i] = plan_coord_eval(points[x->a], x->b, dim);
        else
            uval[i] = scalar_op(p, x, uval);
    }
    g->v = pc_xmalloc(sizeof *g->v * (size_t)n);
    g->slot = pc_xmalloc(sizeof *g->slot * (size_t)n);
    g->nv = 0;
    /* last use of every varying register */
    for (int i = 0; i < n; i++) {
        const PlanIns *x = &p->ins[i];
        g->slot[i] = -1;
        last[i] = -1;
        if (!live[i] || x->uniform)
            continue;
        int nargs = plan_op_nargs((PlanOp)x->op);
        if (nargs >= 1)
            last[x->a] = g->nv;
        if (nargs >= 2)
            last[x->b] = g->nv;
        g->v[g->nv++] = i;
    }
    for (int k = 0; k < po->nterms; k++)
        last[g->root[k]] = INT32_MAX;
    if (po->bad >= 0)
        last[po->bad] = INT32_MAX;
    /* slots: uniform registers that varying code reads (or that are
     * results) get a broadcast slot; varying ones share by linear scan */
    int *free_slots = pc_xmalloc(sizeof *free_slots * (size_t)(n + 1));
    int nfree = 0, nslots = 0;
    for (int i = 0; i < n; i++)
        if (live[i] && p->ins[i].uniform &&
            (last[i] >= 0 || last[i] == INT32_MAX))
            g->slot[i] = nslots++;
    int *uniform_slots = pc_xmalloc(sizeof *uniform_slots * (size_t)(n + 1));
    int nu = 0;
    for (int i = 0; i < n; i++)
        if (g->slot[i] >= 0)
            uniform_slots[nu++] = i;
    for (int vi = 0; vi < g->nv; vi++) {
        int i = g->v[vi];
        const PlanIns *x = &p->ins[i];
        g->slot[i] = nfree ? free_slots[--nfree] : nslots++;
        int nargs = plan_op_nargs((PlanOp)x->op);
        int ops[2] = {x->a, x->b};
        for (int k = 0; k < nargs; k++) {
            int r = ops[k];
            if (!p->ins[r].uniform && last[r] == vi &&
                (k == 0 || ops[0] != ops[1]))
                free_slots[nfree++] = g->slot[r];
        }
        if (last[i] < 0) // computed but never read: free at once
            free_slots[nfree++] = g->slot[i];
    }
    g->nslots = nslots;
    size_t bytes = sizeof(double) * BL * (size_t)(nslots ? nslots : 1);
    g->rf = pc_xaligned_alloc(64, bytes);
    for (int u = 0; u < nu; u++) {
        double *d = g->rf + (size_t)g->slot[uniform_slots[u]] * BL;
        for (int j = 0; j < BL; j++)
            d[j] = uval[uniform_slots[u]];
    }
    pc_free(uniform_slots);
    pc_free(free_slots);
    pc_free(uval);
    pc_free(last);
    pc_free(live);
}

static void prog_clear(Prog *g)
{
    pc_free(g->v);
    pc_free(g->slot);
    pc_free(g->root);
    pc_free(g->coef);
    pc_free(g->rf);
}

static double *reg(const Prog *g, int r)
{
    return g->rf + (size_t)g->slot[r] * BL;
}

/* ---- evaluation -------------------------------------------------------- */

static void run_block(const Prog *g, const Plan *p, const double *const *params,
                      size_t i0, size_t m)
{
    for (int vi = 0; vi < g->nv; vi++) {
        int i = g->v[vi];
        const PlanIns *x = &p->ins[i];
        double *d = reg(g, i);
        switch ((PlanOp)x->op) {
        case PLAN_INPUT: {
            const double *src = params[x->a] + i0;
            size_t j;
            for (j = 0; j < m; j++)
                d[j] = src[j];
            for (; j < BL; j++)
                d[j] = 0;
            break;
        }
        case PLAN_NEG:
            k_neg(d, reg(g, x->a));
            break;
        case PLAN_ADD:
            k_add(d, reg(g, x->a), reg(g, x->b));
            break;
        case PLAN_SUB:
            k_sub(d, reg(g, x->a), reg(g, x->b));
            break;
        case PLAN_MUL:
            k_mul(d, reg(g, x->a), reg(g, x->b));
            break;
        case PLAN_DIV:
            k_div(d, reg(g, x->a), reg(g, x->b));
            break;
        case PLAN_POWI:
            k_powi(d, reg(g, x->a), x->b);
            break;
        case PLAN_POLE:
            k_pole(d, reg(g, x->a));
            break;
        case PLAN_FN: {
            const double *a = reg(g, x->a);
            for (int j = 0; j < BL; j++)
                d[j] = plan_fn_eval(x->b, a[j]);
            break;
        }
        case PLAN_ATAN2: {
            const double *a = reg(g, x->a), *b = reg(g, x->b);
            for (int j = 0; j < BL; j++)
                d[j] = atan2(a[j], b[j]);
            break;
        }
        case PLAN_DOMAIN: {
            const double *a = reg(g, x->a);
            for (int j = 0; j < BL; j++)
                d[j] = plan_domain_eval(x->b, a[j]);
            break;
        }
        case PLAN_NATX:
        case PLAN_NATY: {
            const double *a = reg(g, x->a);
            for (int j = 0; j < BL; j++)
                d[j] = plan_natural_eval(x->op == PLAN_NATY, p->k + x->b, a[j]);
            break;
        }
        case PLAN_ISNAN: {
            const double *a = reg(g, x->a);
            for (int j = 0; j < BL; j++)
                d[j] = isnan(a[j]) ? 1.0 : 0.0;
            break;
        }
        default:
            assert(0 && "uniform op in the varying list");
        }
    }
}

int plan_output_uses_point(const Plan *p, int o, int point)
{
    const PlanOutput *out = &p->outputs[o];
    for (int k = 0; k < out->nterms; k++)
        if (out->point[k] == point)
            return 1;
    /* distances (metric atoms) and coordinates read the points'
     * coordinates too */
    int uses_dist = 0;
    for (int i = 0; i < p->nins && !uses_dist; i++)
        uses_dist = (p->ins[i].op == PLAN_DIST &&
                     (p->ins[i].a == point || p->ins[i].b == point)) ||
                    (p->ins[i].op == PLAN_COORD && p->ins[i].a == point);
    if (uses_dist) {
        unsigned char *live = pc_xmalloc((size_t)p->nins + 1);
        plan_live(p, o, live);
        int used = 0;
        for (int i = 0; i < p->nins && !used; i++)
            used = live[i] &&
                   ((p->ins[i].op == PLAN_DIST &&
                     (p->ins[i].a == point || p->ins[i].b == point)) ||
                    (p->ins[i].op == PLAN_COORD && p->ins[i].a == point));
        pc_free(live);
        return used;
    }
    return 0;
}

/* output o of p at n samples with the prepared program g */
static size_t eval_prog(const Prog *g, const Plan *p, int o, size_t n,
                        const double *const *params,
                        const double *const *points, int dim, double *out,
                        unsigned char *status)
{
    const PlanOutput *po = &p->outputs[o];
    size_t nbad = 0;
    _Alignas(64) double cols[3][BL]; // dims 2, 3: columns, then interleaved
    int scalar = po->kind == KIND_SCALAR;
    int ncols = scalar ? 1 : dim;
    for (size_t i0 = 0; i0 < n; i0 += BL) {
        size_t m = n - i0 < BL ? n - i0 : BL;
        run_block(g, p, params, i0, m);
        const double *bad = po->bad >= 0 ? reg(g, po->bad) : NULL;
        int direct = m == BL && (ncols == 2 || ncols == 3);
        for (int c = 0; c < ncols; c++) {
            double *acc = direct ? cols[c] : cols[0];
            if (po->nterms == 0) {
                memset(acc, 0, sizeof cols[0]);
            } else {
                for (int k = 0; k < po->nterms; k++) {
                    double coord =
                        g->coef[k] * (scalar ? 1.0 : points[po->point[k]][c]);
                    if (k == 0)
                        k_scale(acc, reg(g, g->root[k]), coord);
                    else
                        k_axpy(acc, reg(g, g->root[k]), coord);
                }
            }
            if (direct)
                continue;
            double *dst = out + i0 * (size_t)ncols + (size_t)c;
            for (size_t j = 0; j < m; j++)
                dst[j * (size_t)ncols] = acc[j];
        }
        if (direct && ncols == 3)
            k_store3(out + i0 * 3, cols[0], cols[1], cols[2]);
        else if (direct)
            k_store2(out + i0 * 2, cols[0], cols[1]);
        /* poles: NaN rows (padded lanes may be flagged too: ignored) */
        if (bad && k_sum(bad) != 0) {
            for (size_t j = 0; j < m; j++) {
                if (bad[j] == 0)
                    continue;
                nbad++;
                for (int c = 0; c < ncols; c++)
                    out[(i0 + j) * (size_t)ncols + (size_t)c] = NAN;
            }
        }
        if (status)
            for (size_t j = 0; j < m; j++)
                status[i0 + j] = (unsigned char)(bad ? plan_status(bad[j]) : 0);
    }
    return nbad;
}

size_t plan_eval(const Plan *p, int o, size_t n, const double *const *params,
                 const double *consts, const double *const *points, int dim,
                 double *out, unsigned char *status)
{
    assert(o >= 0 && o < p->noutputs);
    Prog g;
    prog_init(&g, p, o, consts, points, dim);
    size_t nbad = eval_prog(&g, p, o, n, params, points, dim, out, status);
    prog_clear(&g);
    return nbad;
}

struct PlanProg {
    Prog g;
    const Plan *p;
    int o, dim;
    const double *const *points;
};

PlanProg *plan_prog_new(const Plan *p, int o, const double *consts,
                        const double *const *points, int dim)
{
    assert(o >= 0 && o < p->noutputs);
    PlanProg *pp = pc_xmalloc(sizeof *pp);
    prog_init(&pp->g, p, o, consts, points, dim);
    pp->p = p;
    pp->o = o;
    pp->dim = dim;
    pp->points = points;
    return pp;
}

size_t plan_prog_eval(const PlanProg *pp, size_t n, const double *const *params,
                      double *out, unsigned char *status)
{
    return eval_prog(&pp->g, pp->p, pp->o, n, params, pp->points, pp->dim, out,
                     status);
}

void plan_prog_free(PlanProg *pp)
{
    if (!pp)
        return;
    prog_clear(&pp->g);
    pc_free(pp);
}
