/*
 * kernel.c - transcendental and algebraic atoms (kernel.h): the table of
 * kernels, their slots, names and relations.
 *
 * Values stay RatFuns of one ring; a kernel only gives a meaning to one of
 * the ring's reserved variables.  Every operation works on small
 * expressions (the conics of chapter 2 have a few dozen terms), so it uses
 * RatFun arithmetic freely and reduces once at the end.  This file makes
 * and names the kernels (with the relations cos^2 = 1 - sin^2, sqrt(a)^2
 * = a ...), the metric atoms dist(A, B) and the coordinates coord(A, k);
 * kernel_int.h lists the files that apply, reduce and derive them.
 */
#include "compiler/algebra/kernel_int.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "base/mem.h"
#include "compiler/algebra/poly_print.h"

/* 0, or the reason to stop: an intermediate polynomial beyond
 * KERNEL_MAX_WORK_TERMS terms, or the derivation's time budget spent.
 * Every loop of the normal form and of substitution asks it, so no input
 * runs unbounded inside one expression node. */
int kernel_guard(Kernels *K, const fmpz_mpoly_struct *p)
{
    if (p && p->length > KERNEL_MAX_WORK_TERMS) {
        K->why = "expression too large for the functions' identities";
        return KERNEL_EBIG;
    }
    if (K->deadline > 0) {
        struct timespec ts;
        clock_gettime(CLOCK_MONOTONIC, &ts);
        if ((double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec > K->deadline)
            return KERNEL_ETIME;
    }
    return 0;
}

/* 1 when a kernel slot is left for one more kernel; else 0, with the
 * reason and K->full set (a derivation retries with more slots) */
static int slot_left(Kernels *K)
{
    if (K->n + 1 <= K->cap)
        return 1;
    K->why = "too many distinct functions in one scheme";
    K->full = 1;
    return 0;
}

const char *const kernel_fn_names[KF_COUNT] = {
#define PC_FUNCTION(ID, name, ar, lang, k, p, c, latex, dom)                   \
    PC_WHEN(k)([KF_##ID] = name, )
#include "base/functions.def"
#undef PC_FUNCTION
    [KF_DIST] = "dist",
    [KF_COORD] = "coord",
    [KF_NATX] = "natx",
    [KF_NATY] = "naty",
};

const char *const kernel_fn_latex[KF_COUNT] = {
#define PC_FUNCTION(ID, name, ar, lang, k, p, c, latex, dom)                   \
    PC_WHEN(k)([KF_##ID] = latex, )
#include "base/functions.def"
#undef PC_FUNCTION
};

slong kernels_metric_slots(slong metric, slong npoints)
{
    if (metric == 0)
        return 0;
    /* every pair's distance, and per call a sqrt and an acos */
    return npoints * (npoints - 1) / 2 + 3 * metric;
}

slong kernels_slots(slong calls, slong ops, slong pis)
{
    if (calls == 0 && pis == 0)
        return 0;
    /* each call can make a pair (sin, cos) and, through its symmetry or
     * folding, a pi and a few square roots; each subst or diff can make one
     * more kernel per kernel, which the first try does not reserve: a
     * derivation that runs out is done again with twice the slots */
    slong n = 4 + 2 * calls + (pis > 0) + 2 * ops;
    return n < KERNELS_MAX_SLOTS ? n : KERNELS_MAX_SLOTS;
}

void kernels_init(Kernels *K, Ring *r, slong first, slong cap)
{
    K->r = r;
    K->first = first;
    K->cap = cap;
    K->n = 0;
    K->k = cap ? pc_xcalloc((size_t)cap, sizeof(Kernel)) : NULL;
    K->nrel = 0;
    K->full = 0;
    K->deadline = 0;
    K->why = NULL;
    K->range = pc_xcalloc((size_t)(first > 0 ? first : 1), sizeof(KRange));
    for (slong v = 0; v < first; v++) {
        fmpq_init(K->range[v].lo);
        fmpq_init(K->range[v].hi);
    }
    K->used = pc_xcalloc((size_t)(first > 0 ? first : 1), 1);
    K->cur = pc_xcalloc((size_t)(first > 0 ? first : 1), 1);
    K->points = NULL;
    K->npoints = 0;
    K->laws = NULL;
    K->nlaws = 0;
    if (cap > 0 && !r->latex)
        r->latex = flint_calloc((size_t)(r->nvars ? r->nvars : 1),
                                sizeof(const char *));
}

void kernels_clear(Kernels *K)
{
    for (slong i = 0; i < K->n; i++) {
        Kernel *k = &K->k[i];
        ratfun_clear(k->arg, K->r);
        ratfun_clear(k->arg2, K->r);
        ratfun_clear(k->rel, K->r);
        pc_free(k->name);
        pc_free(k->latex);
    }
    pc_free(K->k);
    for (slong i = 0; i < K->nlaws * KERNEL_LAW_LEN; i++)
        fmpq_clear(K->laws + i);
    pc_free(K->laws);
    K->laws = NULL;
    K->nlaws = 0;
    for (slong v = 0; K->range && v < K->first; v++) {
        fmpq_clear(K->range[v].lo);
        fmpq_clear(K->range[v].hi);
    }
    pc_free(K->range);
    pc_free(K->used);
    pc_free(K->cur);
    K->cur = NULL;
    K->range = NULL;
    K->used = NULL;
    K->k = NULL;
    K->n = K->cap = 0;
}

const Kernel *kernels_of_var(const Kernels *K, slong var)
{
    if (!K || var < K->first || var >= K->first + K->n)
        return NULL;
    return &K->k[var - K->first];
}
/* ---- small helpers ------------------------------------------------------ */

int kernel_poly_has(const fmpz_mpoly_t p, slong var, const Ring *r)
{
    return fmpz_mpoly_degree_si(p, var, r->ctx) > 0;
}

int kernel_rf_has(const RatFun x, slong var, const Ring *r)
{
    return kernel_poly_has(x->num, var, r) || kernel_poly_has(x->den, var, r);
}

/* 1 when x is exactly the variable var */
int kernel_rf_is_var(const RatFun x, slong *var, const Ring *r)
{
    if (!fmpz_mpoly_is_one(x->den, r->ctx) || x->num->length != 1 ||
        fmpz_mpoly_total_degree_si(x->num, r->ctx) != 1)
        return 0;
    fmpz_t c;
    fmpz_init(c);
    fmpz_mpoly_get_term_coeff_fmpz(c, x->num, 0, r->ctx);
    int one = fmpz_is_one(c);
    fmpz_clear(c);
    if (!one)
        return 0;
    for (slong v = 0; v < r->ctx->minfo->nvars; v++)
        if (kernel_poly_has(x->num, v, r)) {
            *var = v;
            return 1;
        }
    return 0;
}
static char *cat3(const char *a, const char *b, const char *c)
{
    size_t n = strlen(a) + strlen(b) + strlen(c) + 1;
    char *s = pc_xmalloc(n);
    snprintf(s, n, "%s%s%s", a, b, c);
    return s;
}

/* ---- making kernels ----------------------------------------------------- */

slong kernels_find(const Kernels *K, KernelFn fn, const RatFun a,
                   const RatFun b, slong q)
{
    for (slong i = 0; i < K->n; i++) {
        const Kernel *k = &K->k[i];
        if (k->fn != fn || k->q != q)
            continue;
        if (fn == KF_PI || fn == KF_DIST) /* KF_DIST: q is the pair */
            return i;
        if (!ratfun_equal(k->arg, a, K->r))
            continue;
        if (fn == KF_ATAN2 && !ratfun_equal(k->arg2, b, K->r))
            continue;
        return i;
    }
    return -1;
}

/* s without one pair of parentheses around the whole of it */
static char *unwrap(char *s)
{
    size_t n = strlen(s);
    if (n < 2 || s[0] != '(' || s[n - 1] != ')')
        return s;
    int depth = 0;
    for (size_t i = 0; i < n; i++) {
        depth += s[i] == '(' ? 1 : s[i] == ')' ? -1 : 0;
        if (depth == 0 && i < n - 1)
            return s; /* "(a)*(b)" */
    }
    memmove(s, s + 1, n - 2);
    s[n - 2] = '\0';
    return s;
}

static char *arg_text(const RatFun x, const Ring *r, FormatStyle st)
{
    /* expanded: factoring every argument (the printer's form) costs more
     * than the whole derivation of a conic, and reads no better: the book
     * writes sqrt(a^2 - b^2) */
    char *s = poly_print_ratfun(x, r, st);
    if (st == FMT_LATEX && strncmp(s, "\\left(", 6) == 0) {
        size_t n = strlen(s);
        if (n > 13 && strcmp(s + n - 7, "\\right)") == 0) {
            /* a LaTeX group around everything: drop it when it is one */
            int depth = 0, whole = 1;
            for (size_t i = 0; i < n; i++) {
                if (strncmp(s + i, "\\left(", 6) == 0)
                    depth++;
                else if (strncmp(s + i, "\\right)", 7) == 0 && --depth == 0 &&
                         i + 7 < n)
                    whole = 0;
            }
            if (whole) {
                memmove(s, s + 6, n - 13);
                s[n - 13] = '\0';
            }
        }
        return s;
    }
    return st == FMT_TEXT ? unwrap(s) : s;
}

/* coord(A, k): x_{A}, y_{A}, z_{A} for k = 1, 2, 3, A_{k} beyond */
static void coord_names(const Kernels *K, Kernel *k)
{
    const char *p = K->points[k->pa];
    char buf[32];
    snprintf(buf, sizeof buf, ", %ld)", (long)k->pb);
    char *t = cat3("coord(", p, "");
    k->name = cat3(t, buf, "");
    pc_free(t);
    if (k->pb <= 3) {
        static const char *const xyz[] = {"x_{", "y_{", "z_{"};
        k->latex = cat3(xyz[k->pb - 1], p, "}");
    } else {
        snprintf(buf, sizeof buf, "_{%ld}", (long)k->pb);
        k->latex = cat3(p, buf, "");
    }
}

static void set_names(Kernels *K, Kernel *k)
{
    const Ring *r = K->r;
    int noarg = k->fn == KF_PI || k->fn == KF_DIST || k->fn == KF_COORD;
    char *a = noarg ? NULL : arg_text(k->arg, r, FMT_TEXT);
    char *la = noarg ? NULL : arg_text(k->arg, r, FMT_LATEX);
    char buf[48];
    switch (k->fn) {
    case KF_PI:
        k->name = pc_xstrdup("pi");
        k->latex = pc_xstrdup("\\pi");
        break;
    case KF_DIST: {
        const char *pa = K->points[k->pa], *pb = K->points[k->pb];
        char *t = cat3("dist(", pa, ", ");
        k->name = cat3(t, pb, ")");
        pc_free(t);
        t = cat3("\\left|", pa, pb);
        k->latex = cat3(t, "\\right|", "");
        pc_free(t);
        break;
    }
    case KF_COORD:
        coord_names(K, k);
        break;
    case KF_NATX:
    case KF_NATY:
        kernel_natural_names(K, k, a, la);
        break;
    case KF_SQRT:
        k->name = cat3("sqrt(", a, ")");
        k->latex = cat3("\\sqrt{", la, "}");
        break;
    case KF_ROOT: {
        slong v;
        const Kernel *e =
            kernel_rf_is_var(k->arg, &v, r) ? kernels_of_var(K, v) : NULL;
        if (e && e->fn == KF_EXP) { /* the q-th root of exp(m): exp(m/q) */
            RatFun m;
            ratfun_init(m, r);
            ratfun_set_si(m, k->q, r);
            ratfun_div(m, e->arg, m, r);
            char *ma = arg_text(m, r, FMT_TEXT);
            char *ml = arg_text(m, r, FMT_LATEX);
            k->name = cat3("exp(", ma, ")");
            k->latex = cat3("e^{", ml, "}");
            pc_free(ma);
            pc_free(ml);
            ratfun_clear(m, r);
            break;
        }
        snprintf(buf, sizeof buf, ", %ld)", (long)k->q);
        k->name = cat3("root(", a, buf);
        snprintf(buf, sizeof buf, "\\sqrt[%ld]{", (long)k->q);
        k->latex = cat3(buf, la, "}");
        break;
    }
    case KF_ATAN2: {
        char *b = arg_text(k->arg2, r, FMT_TEXT);
        char *lb = arg_text(k->arg2, r, FMT_LATEX);
        char *t = cat3("atan2(", a, ", ");
        k->name = cat3(t, b, ")");
        pc_free(t);
        t = cat3("\\operatorname{atan2}\\left(", la, ", ");
        k->latex = cat3(t, lb, "\\right)");
        pc_free(t);
        pc_free(b);
        pc_free(lb);
        break;
    }
    case KF_EXP:
        k->name = cat3("exp(", a, ")");
        k->latex = cat3("e^{", la, "}");
        break;
    default: {
        const char *const *lx = kernel_fn_latex;
        char *t = cat3(kernel_fn_names[k->fn], "(", a);
        k->name = cat3(t, ")", "");
        pc_free(t);
        t = cat3(lx[k->fn], "\\left(", la);
        k->latex = cat3(t, "\\right)", "");
        pc_free(t);
        break;
    }
    }
    pc_free(a);
    pc_free(la);
    K->r->names[k->var] = k->name;
    K->r->latex[k->var] = k->latex;
}

/* a new kernel (slot checked by the caller) */
static Kernel *add(Kernels *K, KernelFn fn, const RatFun a, const RatFun b,
                   slong q)
{
    Kernel *k = &K->k[K->n];
    k->fn = fn;
    k->var = K->first + K->n;
    k->q = q;
    ratfun_init(k->arg, K->r);
    ratfun_init(k->arg2, K->r);
    ratfun_init(k->rel, K->r);
    k->deg = 0;
    if (a)
        ratfun_set(k->arg, a, K->r);
    if (b)
        ratfun_set(k->arg2, b, K->r);
    K->n++;
    set_names(K, k);
    return k;
}

/* res = the kernel variable of fn(a[, b]) (made if new); pairs are made
 * together: sin with cos, sinh with cosh */
int kernels_intern(Kernels *K, RatFun res, KernelFn fn, const RatFun a,
                   const RatFun b, slong q)
{
    const Ring *r = K->r;
    slong i = kernels_find(K, fn, a, b, q);
    if (i < 0) {
        int pair =
            fn == KF_SIN || fn == KF_COS || fn == KF_SINH || fn == KF_COSH;
        if (K->n + (pair ? 2 : 1) > K->cap) {
            K->why = "too many distinct functions in one scheme";
            K->full = 1;
            return KERNEL_EFULL;
        }
        if (pair) {
            int hyp = fn == KF_SINH || fn == KF_COSH;
            Kernel *s = add(K, hyp ? KF_SINH : KF_SIN, a, NULL, 0);
            slong sv = s->var;
            Kernel *c = add(K, hyp ? KF_COSH : KF_COS, a, NULL, 0);
            /* cos^2 = 1 - sin^2, cosh^2 = 1 + sinh^2 */
            c->deg = 2;
            ratfun_gen(c->rel, sv, r);
            ratfun_mul(c->rel, c->rel, c->rel, r);
            if (!hyp)
                ratfun_neg(c->rel, c->rel, r);
            RatFun one;
            ratfun_init(one, r);
            ratfun_one(one, r);
            ratfun_add(c->rel, c->rel, one, r);
            ratfun_clear(one, r);
            K->nrel++;
            i = kernels_find(K, fn, a, b, q);
        } else {
            Kernel *k = add(K, fn, a, b, q);
            if (fn == KF_SQRT || fn == KF_ROOT) {
                k->deg = fn == KF_SQRT ? 2 : q;
                ratfun_set(k->rel, a, r);
                K->nrel++;
            } else if (fn == KF_SIGN) {
                k->deg = 2;
                ratfun_one(k->rel, r);
                K->nrel++;
            }
            i = K->n - 1;
        }
    }
    ratfun_gen(res, K->k[i].var, r);
    return 0;
}

int kernel_dist(Kernels *K, RatFun res, slong a, slong b)
{
    if (a == b) {
        ratfun_zero(res, K->r);
        return 0;
    }
    if (a > b) {
        slong t = a;
        a = b;
        b = t;
    }
    slong q = a * (K->npoints + 1) + b;
    slong i = kernels_find(K, KF_DIST, NULL, NULL, q);
    if (i < 0) {
        if (!slot_left(K))
            return KERNEL_EFULL;
        Kernel *k = &K->k[K->n];
        k->pa = a; /* set before add() names it */
        k->pb = b;
        k = add(K, KF_DIST, NULL, NULL, q);
        i = K->n - 1;
    }
    ratfun_gen(res, K->k[i].var, K->r);
    return 0;
}

/* ---- coordinates --------------------------------------------------------- */

slong kernels_coord_slots(slong nindices, slong npoints)
{
    return nindices * npoints;
}

/* res = coord(A_a, k), k >= 1 */
static int kernel_coord(Kernels *K, RatFun res, slong a, slong k)
{
    slong i;
    for (i = 0; i < K->n; i++)
        if (K->k[i].fn == KF_COORD && K->k[i].pa == a && K->k[i].pb == k)
            break;
    if (i == K->n) {
        if (!slot_left(K))
            return KERNEL_EFULL;
        Kernel *c = &K->k[K->n];
        c->pa = a; /* set before add() names it */
        c->pb = k;
        add(K, KF_COORD, NULL, NULL, 0);
    }
    ratfun_gen(res, K->k[i].var, K->r);
    return 0;
}

int kernel_coord_pteq(Kernels *K, RatFun res, const PointEq P, slong k)
{
    const Ring *r = K->r;
    RatFun acc, c;
    ratfun_init(acc, r);
    ratfun_init(c, r);
    int rc = 0;
    /* (sum_i n_i coord(A_i, k)) / d: polynomial products, one division */
    for (slong i = 0; i < P->len && rc == 0; i++) {
        rc = kernel_coord(K, c, P->terms[i].point, k);
        if (rc == 0) {
            fmpz_mpoly_mul(c->num, c->num, P->terms[i].num, r->ctx);
            fmpz_mpoly_add(acc->num, acc->num, c->num, r->ctx);
            rc = kernel_guard(K, acc->num);
        }
    }
    if (rc == 0) {
        fmpz_mpoly_set(acc->den, P->den, r->ctx);
        ratfun_canonicalise(acc, r);
        ratfun_swap(res, acc, r);
        rc = kernel_reduce(K, res);
    }
    ratfun_clear(c, r);
    ratfun_clear(acc, r);
    return rc;
}
