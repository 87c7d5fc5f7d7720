/*
 * kernel.c - transcendental and algebraic atoms (kernel.h).
 *
 * Values stay RatFuns of one ring; a kernel only gives a meaning to one of
 * the ring's reserved variables.  Every operation here works on small
 * expressions (the conics of chapter 2 have a few dozen terms), so it uses
 * RatFun arithmetic freely and reduces once at the end.
 */
#include "compiler/kernel.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <flint/fmpz_factor.h>

#include "compiler/print/format.h"
#include "base/mem.h"

enum {
    MAX_POWER = 1000,  // exponents a kernel rewrite may make
    FACTOR_BITS = 160, // integers under a sqrt factored up to this size
};

/* 0, or the reason to stop: an intermediate polynomial beyond
 * KERNEL_MAX_WORK_TERMS terms, or the derivation's time budget spent.
 * Every loop of the normal form and of substitution asks it, so no input
 * runs unbounded inside one expression node. */
static int guard(Kernels *K, const fmpz_mpoly_struct *p)
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

static const char *const fn_names[] = {
#define X(id, name, cfn) name,
    PC_KERNEL_FNS(X)
#undef X
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
        free(k->name);
        free(k->latex);
    }
    free(K->k);
    for (slong v = 0; K->range && v < K->first; v++) {
        fmpq_clear(K->range[v].lo);
        fmpq_clear(K->range[v].hi);
    }
    free(K->range);
    free(K->used);
    free(K->cur);
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

static int poly_has(const fmpz_mpoly_t p, slong var, const Ring *r)
{
    return fmpz_mpoly_degree_si(p, var, r->ctx) > 0;
}

static int rf_has(const RatFun x, slong var, const Ring *r)
{
    return poly_has(x->num, var, r) || poly_has(x->den, var, r);
}

/* 1 when x is exactly the variable var */
static int rf_is_var(const RatFun x, slong *var, const Ring *r)
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
        if (poly_has(x->num, v, r)) {
            *var = v;
            return 1;
        }
    return 0;
}

/* sign of the leading coefficient of x's numerator (0 for zero) */
static int rf_lead_sign(const RatFun x, const Ring *r)
{
    if (fmpz_mpoly_is_zero(x->num, r->ctx))
        return 0;
    fmpz_t c;
    fmpz_init(c);
    fmpz_mpoly_get_term_coeff_fmpz(c, x->num, 0, r->ctx);
    int s = fmpz_sgn(c);
    fmpz_clear(c);
    return s;
}

static char *cat3(const char *a, const char *b, const char *c)
{
    size_t n = strlen(a) + strlen(b) + strlen(c) + 1;
    char *s = pc_xmalloc(n);
    snprintf(s, n, "%s%s%s", a, b, c);
    return s;
}

/* ---- signs --------------------------------------------------------------- */

/* ---- making kernels ----------------------------------------------------- */

static slong find(const Kernels *K, KernelFn fn, const RatFun a,
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
    char *s = format_scalar_expanded(x, r, st);
    if (st == FMT_LATEX && strncmp(s, "\\left(", 6) == 0) {
        size_t n = strlen(s);
        if (n > 13 && strcmp(s + n - 7, "\\right)") == 0) {
            /* a LaTeX group around everything: drop it when it is one */
            int depth = 0, whole = 1;
            for (size_t i = 0; i < n; i++) {
                if (strncmp(s + i, "\\left(", 6) == 0)
                    depth++;
                else if (strncmp(s + i, "\\right)", 7) == 0 &&
                         --depth == 0 && i + 7 < n)
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
    free(t);
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
        free(t);
        t = cat3("\\left|", pa, pb);
        k->latex = cat3(t, "\\right|", "");
        free(t);
        break;
    }
    case KF_COORD:
        coord_names(K, k);
        break;
    case KF_SQRT:
        k->name = cat3("sqrt(", a, ")");
        k->latex = cat3("\\sqrt{", la, "}");
        break;
    case KF_ROOT: {
        slong v;
        const Kernel *e = rf_is_var(k->arg, &v, r) ? kernels_of_var(K, v)
                                                   : NULL;
        if (e && e->fn == KF_EXP) { /* the q-th root of exp(m): exp(m/q) */
            RatFun m;
            ratfun_init(m, r);
            ratfun_set_si(m, k->q, r);
            ratfun_div(m, e->arg, m, r);
            char *ma = arg_text(m, r, FMT_TEXT);
            char *ml = arg_text(m, r, FMT_LATEX);
            k->name = cat3("exp(", ma, ")");
            k->latex = cat3("e^{", ml, "}");
            free(ma);
            free(ml);
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
        free(t);
        t = cat3("\\operatorname{atan2}\\left(", la, ", ");
        k->latex = cat3(t, lb, "\\right)");
        free(t);
        free(b);
        free(lb);
        break;
    }
    case KF_EXP:
        k->name = cat3("exp(", a, ")");
        k->latex = cat3("e^{", la, "}");
        break;
    default: {
        static const char *const lx[KF_COUNT] = {
            [KF_SIN] = "\\sin",         [KF_COS] = "\\cos",
            [KF_SINH] = "\\sinh",       [KF_COSH] = "\\cosh",
            [KF_LN] = "\\ln",           [KF_ASIN] = "\\arcsin",
            [KF_ACOS] = "\\arccos",     [KF_ATAN] = "\\arctan",
            [KF_SIGN] = "\\operatorname{sign}",
        };
        char *t = cat3(fn_names[k->fn], "(", a);
        k->name = cat3(t, ")", "");
        free(t);
        t = cat3(lx[k->fn], "\\left(", la);
        k->latex = cat3(t, "\\right)", "");
        free(t);
        break;
    }
    }
    free(a);
    free(la);
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
static int intern(Kernels *K, RatFun res, KernelFn fn, const RatFun a,
                  const RatFun b, slong q)
{
    const Ring *r = K->r;
    slong i = find(K, fn, a, b, q);
    if (i < 0) {
        int pair = fn == KF_SIN || fn == KF_COS || fn == KF_SINH ||
                   fn == KF_COSH;
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
            i = find(K, fn, a, b, q);
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

static int pi_times(Kernels *K, RatFun res, slong num, slong den)
{
    int rc = intern(K, res, KF_PI, NULL, NULL, 0);
    if (rc == 0) {
        RatFun c;
        ratfun_init(c, K->r);
        fmpq_t q;
        fmpq_init(q);
        fmpq_set_si(q, num, (ulong)den);
        ratfun_set_fmpq(c, q, K->r);
        ratfun_mul(res, res, c, K->r);
        fmpq_clear(q);
        ratfun_clear(c, K->r);
    }
    return rc;
}

/* x = c * pi with c rational?  (c returned) */
static int is_pi_multiple(const Kernels *K, const RatFun x, fmpq_t c)
{
    const Ring *r = K->r;
    if (!fmpz_mpoly_is_fmpz(x->den, r->ctx) || x->num->length != 1 ||
        fmpz_mpoly_total_degree_si(x->num, r->ctx) != 1)
        return 0;
    slong pi = find(K, KF_PI, NULL, NULL, 0);
    if (pi < 0 || !poly_has(x->num, K->k[pi].var, r))
        return 0;
    fmpz_t a, b;
    fmpz_init(a);
    fmpz_init(b);
    fmpz_mpoly_get_term_coeff_fmpz(a, x->num, 0, r->ctx);
    fmpz_mpoly_get_fmpz(b, x->den, r->ctx);
    fmpq_set_fmpz_frac(c, a, b);
    fmpz_clear(a);
    fmpz_clear(b);
    return 1;
}

static int sqrt_num(Kernels *K, RatFun res, const fmpq_t q);

/* sin(k*pi/12) for k in 0..23 where it is a simple surd: 1 and res set */
static int sin_pi12(Kernels *K, RatFun res, slong k)
{
    /* value for k in 0..6: 0, -, 1/2, sqrt2/2, sqrt3/2, -, 1 (-: not simple) */
    slong m = k % 12, sgn = k >= 12 ? -1 : 1;
    if (m > 6)
        m = 12 - m;
    fmpq_t q;
    fmpq_init(q);
    int ok = 1;
    switch (m) {
    case 0:
        ratfun_zero(res, K->r);
        break;
    case 2:
        fmpq_set_si(q, 1, 2);
        ratfun_set_fmpq(res, q, K->r);
        break;
    case 3:
    case 4:
        fmpq_set_si(q, m == 3 ? 2 : 3, 1);
        if (sqrt_num(K, res, q) != 0) {
            ok = -1;
            break;
        }
        fmpq_set_si(q, 1, 2);
        {
            RatFun h;
            ratfun_init(h, K->r);
            ratfun_set_fmpq(h, q, K->r);
            ratfun_mul(res, res, h, K->r);
            ratfun_clear(h, K->r);
        }
        break;
    case 6:
        ratfun_one(res, K->r);
        break;
    default:
        ok = 0;
    }
    fmpq_clear(q);
    if (ok == 1 && sgn < 0)
        ratfun_neg(res, res, K->r);
    return ok;
}

/* sqrt of a number q >= 0: s/d * prod sqrt(p) over the primes p of the
 * square-free part of num*den (beyond FACTOR_BITS: one kernel) */
static int sqrt_num(Kernels *K, RatFun res, const fmpq_t q)
{
    const Ring *r = K->r;
    if (fmpq_is_zero(q)) {
        ratfun_zero(res, r);
        return 0;
    }
    fmpz_t m, s, f;
    fmpz_init(m);
    fmpz_init(s);
    fmpz_init(f);
    fmpz_mul(m, fmpq_numref(q), fmpq_denref(q));
    fmpz_one(s);
    fmpz_one(f);
    RatFun acc, t;
    ratfun_init(acc, r);
    ratfun_init(t, r);
    ratfun_one(acc, r);
    int rc = 0;
    if (fmpz_bits(m) <= FACTOR_BITS) {
        fmpz_factor_t fac;
        fmpz_factor_init(fac);
        fmpz_factor(fac, m);
        for (slong i = 0; i < fac->num && rc == 0; i++) {
            ulong e = fac->exp[i];
            fmpz_t pw;
            fmpz_init(pw);
            fmpz_pow_ui(pw, fac->p + i, e / 2);
            fmpz_mul(s, s, pw);
            fmpz_clear(pw);
            if (e % 2) {
                fmpz_mpoly_set_fmpz(t->num, fac->p + i, r->ctx);
                fmpz_mpoly_one(t->den, r->ctx);
                rc = intern(K, t, KF_SQRT, t, NULL, 0);
                if (rc == 0)
                    ratfun_mul(acc, acc, t, r);
            }
        }
        fmpz_factor_clear(fac);
    } else {
        fmpz_t rem;
        fmpz_init(rem);
        fmpz_sqrtrem(s, rem, m);
        if (!fmpz_is_zero(rem)) {
            fmpz_one(s);
            fmpq_t mq;
            fmpq_init(mq);
            fmpq_set_fmpz_frac(mq, m, s);
            ratfun_set_fmpq(t, mq, r);
            fmpq_clear(mq);
            rc = intern(K, t, KF_SQRT, t, NULL, 0);
            if (rc == 0)
                ratfun_mul(acc, acc, t, r);
        }
        fmpz_clear(rem);
    }
    if (rc == 0) {
        fmpq_t c;
        fmpq_init(c);
        fmpq_set_fmpz_frac(c, s, fmpq_denref(q));
        ratfun_set_fmpq(t, c, r);
        ratfun_mul(res, acc, t, r);
        fmpq_clear(c);
    }
    ratfun_clear(t, r);
    ratfun_clear(acc, r);
    fmpz_clear(f);
    fmpz_clear(s);
    fmpz_clear(m);
    return rc;
}

/* res *= P^e (e may be negative), P a polynomial */
static void mul_poly_pow(RatFun res, const fmpz_mpoly_t P, slong e,
                         const Ring *r)
{
    RatFun t;
    ratfun_init(t, r);
    fmpz_mpoly_set(t->num, P, r->ctx);
    fmpz_mpoly_one(t->den, r->ctx);
    ratfun_canonicalise(t, r);
    ratfun_pow_si(t, t, e, r);
    ratfun_mul(res, res, t, r);
    ratfun_clear(t, r);
}

/* ---- squares modulo the relations --------------------------------------- */

/* The normal form hides squares: (1 + cos(t))^2 is 2 + 2*cos(t) - sin(t)^2,
 * cos(t)^2 is 1 - sin(t)^2, (a + sqrt(a^2 - b^2)*cos(t))^2 has no square
 * factor as a polynomial.  A square f^2 modulo the relations is found by
 * denesting, one quadratic kernel v (v^2 = R) at a time, from the last:
 * P = A + B v is (g + h v)^2 = g^2 + h^2 R + 2 g h v exactly when
 *
 *   N = A^2 - B^2 R = (g^2 - h^2 R)^2          (the norm is a square m^2)
 *   g^2 = (A + m)/2,  h^2 R = (A - m)/2,  h = B/(2 g)   (for m or -m)
 *
 * where N, g^2 and h^2 R involve only the kernels before v: the same
 * question one level down.  Without any quadratic kernel, P must be a
 * square of the rational functions, or a square times one relation R
 * (1 - sin(t)^2 = cos(t)^2: f = h v).  Whatever is found is checked:
 * f^2 reduces to P exactly, so the search can only miss, never lie. */

enum {
    SQUARE_MAX_TERMS = 10000, // larger arguments are not searched
    SQUARE_MAX_CALLS = 64,    // searches (levels and signs) in one
};

/* f = sqrt(P) in Q(vars), the relations ignored: 1 when P is a square */
static int square_plain(RatFun f, const RatFun P, const Ring *r)
{
    if (ratfun_is_zero(P, r)) {
        ratfun_zero(f, r);
        return 1;
    }
    int ok = 0;
    fmpz_t cn, cd, s;
    fmpz_init(cn);
    fmpz_init(cd);
    fmpz_init(s);
    fmpz_mpoly_t pn, pd;
    fmpz_mpoly_init(pn, r->ctx);
    fmpz_mpoly_init(pd, r->ctx);
    /* P = (cn/cd) * pn/pd, pn and pd primitive with positive leading
     * coefficients: squares exactly when cn*cd is a square and pn, pd are */
    _fmpz_vec_content(cn, P->num->coeffs, P->num->length);
    _fmpz_vec_content(cd, P->den->coeffs, P->den->length);
    fmpz_mpoly_scalar_divexact_fmpz(pn, P->num, cn, r->ctx);
    fmpz_mpoly_scalar_divexact_fmpz(pd, P->den, cd, r->ctx);
    if (fmpz_sgn(pn->coeffs) < 0) {
        fmpz_mpoly_neg(pn, pn, r->ctx);
        fmpz_neg(cn, cn);
    }
    fmpz_mul(s, cn, cd);
    if (fmpz_sgn(s) > 0 && fmpz_is_square(s) &&
        fmpz_mpoly_sqrt(pn, pn, r->ctx) && fmpz_mpoly_sqrt(pd, pd, r->ctx)) {
        /* sqrt(cn/cd) = sqrt(cn*cd)/cd */
        fmpz_sqrt(s, s);
        fmpz_mpoly_scalar_mul_fmpz(f->num, pn, s, r->ctx);
        fmpz_mpoly_scalar_mul_fmpz(f->den, pd, cd, r->ctx);
        ratfun_canonicalise(f, r);
        ok = 1;
    }
    fmpz_mpoly_clear(pd, r->ctx);
    fmpz_mpoly_clear(pn, r->ctx);
    fmpz_clear(s);
    fmpz_clear(cd);
    fmpz_clear(cn);
    return ok;
}

/* the last kernel before top with a quadratic relation that x uses, or -1;
 * -2 when x uses one in a way the search does not handle (its square in
 * the numerator, or any power in the denominator) */
static slong last_quadratic(const Kernels *K, const RatFun x, slong top)
{
    const Ring *r = K->r;
    for (slong i = top - 1; i >= 0; i--) {
        const Kernel *k = &K->k[i];
        if (k->deg != 2 || !rf_has(x, k->var, r))
            continue;
        if (poly_has(x->den, k->var, r) ||
            fmpz_mpoly_degree_si(x->num, k->var, r->ctx) > 1)
            return -2;
        return i;
    }
    return -1;
}

/* x = the coefficient of var^e in num(P), over den(P) */
static void coeff_of(RatFun x, const RatFun P, slong var, ulong e,
                     const Ring *r)
{
    fmpz_mpoly_get_coeff_vars_ui(x->num, P->num, &var, &e, 1, r->ctx);
    fmpz_mpoly_set(x->den, P->den, r->ctx);
    ratfun_canonicalise(x, r);
}

static int square_search(Kernels *K, RatFun f, const RatFun P, slong top,
                         int *work);

/* 1 when f^2 reduces to P exactly (the check of every candidate) */
static int squares_to(Kernels *K, const RatFun f, const RatFun P)
{
    RatFun s;
    ratfun_init(s, K->r);
    ratfun_mul(s, f, f, K->r);
    int rc = kernel_reduce(K, s);
    if (rc == 0)
        rc = ratfun_equal(s, P, K->r);
    ratfun_clear(s, K->r);
    return rc;
}

/* one candidate of the denesting of P = A + B v (v kernel i, v^2 = R) for
 * the root m of the norm: g^2 = (A + m)/2, h = B/(2g); or, when that is
 * 0, g = 0 and h^2 = A/R.  1 (f = g + h v squares to P), 0, or an error */
static int denest_one(Kernels *K, RatFun f, const RatFun P, const RatFun A,
                      const RatFun B, const RatFun m, slong i, int *work)
{
    const Ring *r = K->r;
    const Kernel *k = &K->k[i];
    RatFun G, g, h;
    ratfun_init(G, r);
    ratfun_init(g, r);
    ratfun_init(h, r);
    ratfun_add(G, A, m, r);
    ratfun_set_si(h, 2, r);
    ratfun_div(G, G, h, r);
    int rc = kernel_reduce(K, G);
    if (rc == 0 && ratfun_is_zero(G, r)) {
        /* g = 0: P = h^2 R */
        rc = ratfun_div(G, A, k->rel, r) == 0 ? kernel_reduce(K, G) : 1;
        if (rc == 0)
            rc = square_search(K, h, G, i, work);
        if (rc == 1) {
            ratfun_gen(f, k->var, r);
            ratfun_mul(f, f, h, r);
        } else if (rc > 0) {
            rc = 0;
        }
    } else if (rc == 0) {
        rc = square_search(K, g, G, i, work);
        if (rc == 1) {
            ratfun_mul_si(h, g, 2, r);
            rc = ratfun_div(h, B, h, r) == 0 ? kernel_reduce(K, h) : 1;
            if (rc == 0) {
                ratfun_gen(f, k->var, r);
                ratfun_mul(f, f, h, r);
                ratfun_add(f, f, g, r);
                rc = kernel_reduce(K, f);
            }
            rc = rc == 0 ? 1 : rc > 0 ? 0 : rc;
        }
    }
    if (rc == 1)
        rc = squares_to(K, f, P);
    ratfun_clear(h, r);
    ratfun_clear(g, r);
    ratfun_clear(G, r);
    return rc;
}

/* P = A + B v with v kernel i: the norm's root m, then both signs of it */
static int square_denest(Kernels *K, RatFun f, const RatFun P, slong i,
                         int *work)
{
    const Ring *r = K->r;
    const Kernel *k = &K->k[i];
    RatFun A, B, N, m;
    ratfun_init(A, r);
    ratfun_init(B, r);
    ratfun_init(N, r);
    ratfun_init(m, r);
    coeff_of(A, P, k->var, 0, r);
    coeff_of(B, P, k->var, 1, r);
    /* N = A^2 - B^2 R, a square m^2 one level down */
    ratfun_mul(N, B, B, r);
    ratfun_mul(N, N, k->rel, r);
    ratfun_mul(m, A, A, r);
    ratfun_sub(N, m, N, r);
    int rc = kernel_reduce(K, N);
    if (rc == 0)
        rc = guard(K, N->num);
    if (rc == 0)
        rc = square_search(K, m, N, i, work);
    if (rc == 1) {
        rc = denest_one(K, f, P, A, B, m, i, work);
        if (rc == 0) {
            ratfun_neg(m, m, r);
            rc = denest_one(K, f, P, A, B, m, i, work);
        }
    }
    ratfun_clear(m, r);
    ratfun_clear(N, r);
    ratfun_clear(B, r);
    ratfun_clear(A, r);
    return rc;
}

/* P = h^2 R for the relation R of a quadratic kernel v before top
 * (f = h v): 1 - sin^2 = cos^2, x = sqrt(x)^2 inside a denesting
 * ((sqrt(x) - sqrt(y))^2 needs g^2 = x).  Tried where R divides P (a
 * number R: where P is a rational square once divided by it) */
static int square_by_relation(Kernels *K, RatFun f, const RatFun P,
                              slong top, int *work)
{
    const Ring *r = K->r;
    RatFun Q, h;
    ratfun_init(Q, r);
    ratfun_init(h, r);
    fmpz_mpoly_t t, u;
    fmpz_mpoly_init(t, r->ctx);
    fmpz_mpoly_init(u, r->ctx);
    int rc = 0;
    for (slong i = top - 1; i >= 0 && rc == 0; i--) {
        const Kernel *k = &K->k[i];
        if (k->deg != 2 || k->fn == KF_SIGN)
            continue;
        if (ratfun_is_constant(k->rel, r)) {
            /* sqrt(2): P/2 a rational square */
            if (ratfun_div(Q, P, k->rel, r) != 0 || !square_plain(h, Q, r))
                continue;
        } else {
            /* R divides P modulo the relations: P/R reduced has no new
             * denominator ((w c - q s)(1 + 2 s c) reduced is no multiple
             * of w c - q s as a polynomial) */
            if (ratfun_div(Q, P, k->rel, r) != 0)
                continue;
            rc = kernel_reduce(K, Q);
            if (rc != 0)
                break;
            fmpz_mpoly_mul(t, P->den, k->rel->den, r->ctx);
            if (!fmpz_mpoly_divides(u, t, Q->den, r->ctx))
                continue;
            rc = square_search(K, h, Q, top, work);
            if (rc != 1) {
                rc = rc < 0 ? rc : 0;
                continue;
            }
        }
        ratfun_gen(f, k->var, r);
        ratfun_mul(f, f, h, r);
        rc = kernel_reduce(K, f);
        if (rc == 0)
            rc = squares_to(K, f, P);
    }
    fmpz_mpoly_clear(u, r->ctx);
    fmpz_mpoly_clear(t, r->ctx);
    ratfun_clear(h, r);
    ratfun_clear(Q, r);
    return rc;
}

/* f with f^2 = P modulo the relations of the kernels before top: 1 (found),
 * 0 (none found), or an error of the guard.  Without a quadratic kernel in
 * P: a square of the rational functions; with one: the denesting by the
 * last; then P = h^2 R for a relation R. */
static int square_search(Kernels *K, RatFun f, const RatFun P, slong top,
                         int *work)
{
    if (--*work < 0 || P->num->length + P->den->length > SQUARE_MAX_TERMS)
        return 0;
    int rc = guard(K, NULL);
    if (rc != 0)
        return rc;
    slong i = last_quadratic(K, P, top);
    if (i == -2)
        return 0;
    if (i == -1)
        rc = square_plain(f, P, K->r);
    else
        rc = square_denest(K, f, P, i, work);
    if (rc == 0)
        rc = square_by_relation(K, f, P, top, work);
    return rc;
}

/* 1 when f uses a root (sqrt, root) that x does not: f^2 = x holds only
 * where that root is real, which x does not promise (t = sqrt(t)^2, but
 * sqrt(t*u) is not sqrt(t)*sqrt(u)) */
static int adds_root(const Kernels *K, const RatFun f, const RatFun x)
{
    for (slong i = 0; i < K->n; i++) {
        const Kernel *k = &K->k[i];
        if ((k->fn == KF_SQRT || k->fn == KF_ROOT) &&
            rf_has(f, k->var, K->r) && !rf_has(x, k->var, K->r))
            return 1;
    }
    return 0;
}

/* 1 when the polynomial p is a square f^2 modulo the relations (f set),
 * 0, or an error of the guard */
static int poly_square(Kernels *K, RatFun f, const fmpz_mpoly_t p)
{
    const Ring *r = K->r;
    if (fmpz_mpoly_is_fmpz(p, r->ctx))
        return 0;
    RatFun x;
    ratfun_init(x, r);
    fmpz_mpoly_set(x->num, p, r->ctx);
    fmpz_mpoly_one(x->den, r->ctx);
    ratfun_canonicalise(x, r);
    int work = SQUARE_MAX_CALLS;
    int rc = kernel_reduce(K, x);
    if (rc == 0)
        rc = square_search(K, f, x, K->n, &work);
    if (rc == 1 && adds_root(K, f, x))
        rc = 0;
    ratfun_clear(x, r);
    return rc;
}

/* 1 when x = w g^2 modulo the relations for a root w = sqrt(R) of x
 * (so x >= 0): x w / R is a square; 2 when x = -w g^2 (x <= 0).  |W (sqrt(u) - sqrt(v))^2| = the
 * same, though reduced the product has no factor W. */
static int root_times_square(Kernels *K, const RatFun x)
{
    enum { ROOTS_TRIED = 4 };
    const Ring *r = K->r;
    RatFun q, g;
    ratfun_init(q, r);
    ratfun_init(g, r);
    int rc = 0, tried = 0;
    for (slong i = K->n - 1; i >= 0 && rc == 0 && tried < ROOTS_TRIED; i--) {
        const Kernel *k = &K->k[i];
        if (k->fn != KF_SQRT || !rf_has(x, k->var, r))
            continue;
        tried++;
        ratfun_gen(q, k->var, r);
        ratfun_mul(q, q, x, r);
        if (ratfun_div(q, q, k->rel, r) != 0)
            continue;
        rc = kernel_reduce(K, q);
        for (int sg = 1; rc == 0 && sg >= -1; sg -= 2) {
            if (sg < 0)
                ratfun_neg(q, q, r);
            int work = SQUARE_MAX_CALLS;
            rc = square_search(K, g, q, K->n, &work);
            if (rc == 1 && adds_root(K, g, q))
                rc = 0;
            if (rc == 1 && sg < 0)
                rc = 2;
        }
    }
    ratfun_clear(g, r);
    ratfun_clear(q, r);
    return rc;
}

/* the sign of the polynomial p as far as it is decided: kernel_sign, or
 * a square modulo the relations (never negative), or minus one, or a root
 * times a square: *s = 1, -1 or 0 (unknown); 0 or an error */
static int poly_abs_sign(Kernels *K, int *s, const fmpz_mpoly_t p)
{
    const Ring *r = K->r;
    RatFun x, g;
    ratfun_init(x, r);
    ratfun_init(g, r);
    fmpz_mpoly_set(x->num, p, r->ctx);
    fmpz_mpoly_one(x->den, r->ctx);
    ratfun_canonicalise(x, r);
    int rc = 0;
    *s = kernel_sign(K, x);
    *s = *s > 0 ? 1 : *s < 0 ? -1 : 0;
    if (*s == 0 && !fmpz_mpoly_is_fmpz(p, r->ctx)) {
        rc = poly_square(K, g, x->num);
        if (rc == 1) {
            *s = 1;
        } else if (rc == 0) {
            fmpz_mpoly_t q;
            fmpz_mpoly_init(q, r->ctx);
            fmpz_mpoly_neg(q, x->num, r->ctx);
            rc = poly_square(K, g, q);
            *s = rc == 1 ? -1 : 0;
            fmpz_mpoly_clear(q, r->ctx);
        }
        if (rc == 0) {
            rc = root_times_square(K, x);
            if (rc > 0)
                *s = rc == 1 ? 1 : -1;
        }
        rc = rc < 0 ? rc : 0;
    }
    ratfun_clear(g, r);
    ratfun_clear(x, r);
    return rc;
}

/* The signs a square root still owes: sqrt(f^2 g) = |f| sqrt(g) =
 * f sgn(f) sqrt(g).  They are collected over the whole root and decided
 * at once, since a square may come out in pieces that are not squares
 * (sin(t) * (sin(t) (sqrt(x) - sqrt(y))^2 ...)), then one by one. */
typedef struct SignDebt {
    slong n, alloc;
    fmpz_mpoly_struct *p;  // owned: the polynomials f
    unsigned char *split;  // 1: decided by its factors when alone
} SignDebt;

static void debt_init(SignDebt *d)
{
    d->n = d->alloc = 0;
    d->p = NULL;
    d->split = NULL;
}

static void debt_clear(SignDebt *d, const Ring *r)
{
    for (slong i = 0; i < d->n; i++)
        fmpz_mpoly_clear(d->p + i, r->ctx);
    free(d->p);
    free(d->split);
    debt_init(d);
}

static void debt_push(SignDebt *d, const fmpz_mpoly_t p, int split,
                      const Ring *r)
{
    /* a positive number owes nothing; a negative one stays (-1) */
    if (fmpz_mpoly_is_fmpz(p, r->ctx) &&
        (fmpz_mpoly_is_zero(p, r->ctx) || fmpz_sgn(p->coeffs) > 0))
        return;
    if (d->n == d->alloc) {
        d->alloc = d->alloc ? 2 * d->alloc : 4;
        d->p = pc_xrealloc(d->p, sizeof *d->p * (size_t)d->alloc);
        d->split = pc_xrealloc(d->split, (size_t)d->alloc);
    }
    fmpz_mpoly_init(d->p + d->n, r->ctx);
    fmpz_mpoly_set(d->p + d->n, p, r->ctx);
    d->split[d->n++] = (unsigned char)split;
}

/* acc *= sgn(p) for one polynomial: +-1 where poly_abs_sign decides it,
 * else sign(p) */
static int mul_sign_whole(Kernels *K, RatFun acc, const fmpz_mpoly_t p)
{
    const Ring *r = K->r;
    int s = 0, rc = poly_abs_sign(K, &s, p);
    if (rc != 0)
        return rc;
    if (s < 0)
        ratfun_neg(acc, acc, r);
    if (s != 0)
        return 0;
    RatFun x;
    ratfun_init(x, r);
    fmpz_mpoly_set(x->num, p, r->ctx);
    fmpz_mpoly_one(x->den, r->ctx);
    ratfun_canonicalise(x, r);
    rc = kernel_apply(K, x, KF_SIGN, x, NULL);
    if (rc == 0)
        ratfun_mul(acc, acc, x, r);
    ratfun_clear(x, r);
    return rc;
}

/* acc *= sgn(p), decided whole, else factor by factor (irreducible
 * factors where affordable, else the variables of the term content and
 * the rest): sgn((1 + sqrt(u))(a + cos(t))) = sign(a + cos(t)) */
static int mul_sign_split(Kernels *K, RatFun acc, const fmpz_mpoly_t p)
{
    const Ring *r = K->r;
    int s = 0, rc = poly_abs_sign(K, &s, p);
    if (rc != 0 || s != 0) {
        if (s < 0)
            ratfun_neg(acc, acc, r);
        return rc;
    }
    fmpz_mpoly_factor_t fac;
    fmpz_mpoly_factor_init(fac, r->ctx);
    if (ring_factor_affordable(p, r) && ring_factor(fac, p, r)) {
        if (fmpz_sgn(fac->constant) < 0)
            ratfun_neg(acc, acc, r);
        for (slong i = 0; i < fac->num && rc == 0; i++)
            if (fmpz_get_si(fac->exp + i) % 2)
                rc = mul_sign_whole(K, acc, fac->poly + i);
    } else {
        /* p = M q, M the monomial content */
        fmpz_mpoly_t M, q, v;
        fmpz_mpoly_init(M, r->ctx);
        fmpz_mpoly_init(q, r->ctx);
        fmpz_mpoly_init(v, r->ctx);
        fmpz_mpoly_term_content(M, p, r->ctx);
        if (!fmpz_mpoly_divides(q, p, M, r->ctx)) {
            fmpz_mpoly_one(M, r->ctx);
            fmpz_mpoly_set(q, p, r->ctx);
        }
        slong nv = r->ctx->minfo->nvars;
        for (slong i = 0; i < nv && rc == 0; i++) {
            if (fmpz_mpoly_degree_si(M, i, r->ctx) % 2 == 0)
                continue;
            fmpz_mpoly_gen(v, i, r->ctx);
            rc = mul_sign_whole(K, acc, v);
        }
        if (rc == 0)
            rc = mul_sign_whole(K, acc, q);
        fmpz_mpoly_clear(v, r->ctx);
        fmpz_mpoly_clear(q, r->ctx);
        fmpz_mpoly_clear(M, r->ctx);
    }
    fmpz_mpoly_factor_clear(fac, r->ctx);
    return rc;
}

/* acc *= the signs owed: +-1 when the product of the debts is decided
 * (a square, minus one, a root times one), else each on its own */
static int debt_settle(Kernels *K, RatFun acc, const SignDebt *d)
{
    const Ring *r = K->r;
    int rc = 0;
    if (d->n >= 2) {
        double len = 1;
        for (slong i = 0; i < d->n; i++)
            len *= (double)d->p[i].length;
        if (len <= SQUARE_MAX_TERMS) {
            fmpz_mpoly_t prod;
            fmpz_mpoly_init(prod, r->ctx);
            fmpz_mpoly_one(prod, r->ctx);
            for (slong i = 0; i < d->n; i++)
                fmpz_mpoly_mul(prod, prod, d->p + i, r->ctx);
            int s = 0;
            rc = poly_abs_sign(K, &s, prod);
            fmpz_mpoly_clear(prod, r->ctx);
            if (rc == 0 && s != 0) {
                if (s < 0)
                    ratfun_neg(acc, acc, r);
                return kernel_reduce(K, acc);
            }
        }
    }
    for (slong i = 0; i < d->n && rc == 0; i++)
        rc = d->split[i] ? mul_sign_split(K, acc, d->p + i)
                         : mul_sign_whole(K, acc, d->p + i);
    if (rc == 0)
        rc = kernel_reduce(K, acc);
    return rc;
}

/* acc *= |f|^e = f^e sgn(f)^e, the sign owed (e odd) */
static int mul_abs_pow(Kernels *K, RatFun acc, const RatFun f, slong e,
                       SignDebt *debt)
{
    RatFun x;
    ratfun_init(x, K->r);
    int rc = ratfun_pow_si(x, f, e, K->r) == 0 ? 0 : KERNEL_EZERO;
    if (rc == 0) {
        ratfun_mul(acc, acc, x, K->r);
        if (e % 2) {
            debt_push(debt, f->num, 1, K->r);
            debt_push(debt, f->den, 1, K->r);
        }
    }
    ratfun_clear(x, K->r);
    return rc;
}

/* the part p (numerator, e = 1, or denominator, e = -1) of the square-free
 * rest of a square root's argument: when p, or some of its irreducible
 * factors, is a square f^2 modulo the relations, acc *= |f|^e and the
 * square leaves p (rest = the product of what is left) */
static int squares_out_part(Kernels *K, RatFun acc, fmpz_mpoly_t p, slong e,
                            SignDebt *debt)
{
    const Ring *r = K->r;
    RatFun f;
    ratfun_init(f, r);
    int rc = poly_square(K, f, p);
    if (rc == 1) {
        rc = mul_abs_pow(K, acc, f, e, debt);
        fmpz_mpoly_one(p, r->ctx);
    } else if (rc == 0) {
        /* p = -f^2 (s^2 - 1 = -cos^2): the sign stays under the root */
        fmpz_mpoly_t q;
        fmpz_mpoly_init(q, r->ctx);
        fmpz_mpoly_neg(q, p, r->ctx);
        rc = poly_square(K, f, q);
        if (rc == 1) {
            rc = mul_abs_pow(K, acc, f, e, debt);
            fmpz_mpoly_set_si(p, -1, r->ctx);
        }
        fmpz_mpoly_clear(q, r->ctx);
    }
    fmpz_mpoly_factor_t fac;
    fmpz_mpoly_factor_init(fac, r->ctx);
    if (rc == 0 && ring_factor_affordable(p, r) && ring_factor(fac, p, r) &&
        fac->num > 1) {
        /* p = c * prod f_i^e_i: the factors that are squares leave */
        fmpz_mpoly_t left, pw;
        fmpz_mpoly_init(left, r->ctx);
        fmpz_mpoly_init(pw, r->ctx);
        fmpz_mpoly_set_fmpz(left, fac->constant, r->ctx);
        int any = 0;
        for (slong i = 0; i < fac->num && rc >= 0; i++) {
            slong ei = fmpz_get_si(fac->exp + i);
            rc = poly_square(K, f, fac->poly + i);
            if (rc == 0) {
                /* factors have a positive leading coefficient: -(2 + 2 cos
                 * - sin^2) is sin^2 - 2 cos - 2; its sign joins c */
                fmpz_mpoly_neg(pw, fac->poly + i, r->ctx);
                rc = poly_square(K, f, pw);
                if (rc == 1 && ei % 2)
                    fmpz_mpoly_neg(left, left, r->ctx);
            }
            if (rc == 1) {
                rc = mul_abs_pow(K, acc, f, e * ei, debt);
                any = 1;
                continue;
            }
            fmpz_mpoly_pow_ui(pw, fac->poly + i, (ulong)ei, r->ctx);
            fmpz_mpoly_mul(left, left, pw, r->ctx);
        }
        if (rc == 0 && any)
            fmpz_mpoly_swap(p, left, r->ctx);
        fmpz_mpoly_clear(pw, r->ctx);
        fmpz_mpoly_clear(left, r->ctx);
    }
    fmpz_mpoly_factor_clear(fac, r->ctx);
    ratfun_clear(f, r);
    return rc;
}

/* rest = the square-free part of a square root's argument (sqrt_poly):
 * the squares modulo the relations in its numerator and denominator leave
 * the root as |f| (acc *= |f|, or /= for the denominator) */
static int squares_out(Kernels *K, RatFun acc, RatFun rest, SignDebt *debt)
{
    if (K->nrel == 0)
        return 0;
    int rc = squares_out_part(K, acc, rest->num, 1, debt);
    if (rc == 0)
        rc = squares_out_part(K, acc, rest->den, -1, debt);
    if (rc == 0)
        ratfun_canonicalise(rest, K->r);
    return rc;
}

/* sqrt(x) for a non-constant x = n/d: squares pulled out as |f|^k =
 * f^k sign(f)^k, the positive numeric content as a surd */
static int sqrt_poly(Kernels *K, RatFun res, const RatFun x)
{
    const Ring *r = K->r;
    RatFun acc, rest, t;
    ratfun_init(acc, r);
    ratfun_init(rest, r);
    ratfun_init(t, r);
    ratfun_one(acc, r);
    ratfun_one(rest, r);
    fmpq_t content;
    fmpq_init(content);
    fmpq_one(content);
    SignDebt debt;
    debt_init(&debt);
    int rc = 0;
    for (int part = 0; part < 2 && rc == 0; part++) {
        const fmpz_mpoly_struct *P = part ? x->den : x->num;
        fmpz_mpoly_factor_t f;
        fmpz_mpoly_factor_init(f, r->ctx);
        if (!ring_factor_compact(f, P, 0, r)) {
            /* cannot split: keep the polynomial whole */
            fmpz_mpoly_factor_clear(f, r->ctx);
            mul_poly_pow(rest, P, part ? -1 : 1, r);
            continue;
        }
        fmpq_t k;
        fmpq_init(k);
        fmpq_set_fmpz_frac(k, f->constant, f->constant_den);
        if (part)
            fmpq_div(content, content, k);
        else
            fmpq_mul(content, content, k);
        fmpq_clear(k);
        for (slong i = 0; i < f->num && rc == 0; i++) {
            slong e = fmpz_get_si(f->exp + i), h = e / 2;
            if (e % 2)
                mul_poly_pow(rest, f->poly + i, part ? -1 : 1, r);
            if (h == 0)
                continue;
            /* |f|^h = f^h * sign(f)^h, sign(f) = +-1 where it is known */
            mul_poly_pow(acc, f->poly + i, part ? -h : h, r);
            int fs = kernel_sign_poly(K, f->poly + i);
            if (h % 2 && fs < 0)
                ratfun_neg(acc, acc, r);
            if (h % 2 && fs == 0)
                debt_push(&debt, f->poly + i, 0, r); /* owed: below */
        }
        fmpz_mpoly_factor_clear(f, r->ctx);
    }
    if (rc == 0) {
        /* the numeric content: sqrt(|c|), its sign stays under the root */
        if (fmpq_sgn(content) < 0) {
            fmpq_neg(content, content);
            ratfun_neg(rest, rest, r);
        }
        rc = sqrt_num(K, t, content);
        if (rc == 0)
            ratfun_mul(acc, acc, t, r);
    }
    if (rc == 0)
        rc = squares_out(K, acc, rest, &debt);
    if (rc == 0)
        rc = debt_settle(K, acc, &debt);
    if (rc == 0) {
        fmpq_t c;
        fmpq_init(c);
        if (ratfun_get_fmpq(c, rest, r)) {
            /* only -1 can remain: sqrt of a negative number */
            if (fmpq_sgn(c) < 0) {
                K->why = "square root of a negative number";
                rc = KERNEL_EDOMAIN;
            }
        } else {
            rc = intern(K, t, KF_SQRT, rest, NULL, 0);
            if (rc == 0)
                ratfun_mul(acc, acc, t, r);
        }
        fmpq_clear(c);
    }
    if (rc == 0)
        ratfun_swap(res, acc, r);
    debt_clear(&debt, r);
    fmpq_clear(content);
    ratfun_clear(t, r);
    ratfun_clear(rest, r);
    ratfun_clear(acc, r);
    return rc;
}

/* exp of x: a sum over a constant denominator splits into a product of
 * exp(monomial/q)^p; exp(k*ln(y)) = y^k */
static int exp_split(Kernels *K, RatFun res, const RatFun x)
{
    const Ring *r = K->r;
    if (!fmpz_mpoly_is_fmpz(x->den, r->ctx))
        return intern(K, res, KF_EXP, x, NULL, 0);
    fmpz_t d, c;
    fmpz_init(d);
    fmpz_init(c);
    fmpz_mpoly_get_fmpz(d, x->den, r->ctx);
    RatFun acc, t;
    ratfun_init(acc, r);
    ratfun_init(t, r);
    ratfun_one(acc, r);
    fmpz_mpoly_t m;
    fmpz_mpoly_init(m, r->ctx);
    int rc = 0;
    for (slong i = 0; i < x->num->length && rc == 0; i++) {
        fmpz_mpoly_get_term_coeff_fmpz(c, x->num, i, r->ctx);
        fmpz_mpoly_get_term_monomial(m, x->num, i, r->ctx);
        fmpq_t pq;
        fmpq_init(pq);
        fmpq_set_fmpz_frac(pq, c, d);
        if (!fmpz_fits_si(fmpq_numref(pq)) ||
            fmpz_bits(fmpq_numref(pq)) > 10 /* |p| >= 1024 */) {
            /* a huge multiple: keep it inside the exponential */
            fmpz_mpoly_scalar_mul_fmpz(t->num, m, fmpq_numref(pq), r->ctx);
            fmpz_mpoly_set_fmpz(t->den, fmpq_denref(pq), r->ctx);
            ratfun_canonicalise(t, r);
            rc = intern(K, t, KF_EXP, t, NULL, 0);
            if (rc == 0)
                ratfun_mul(acc, acc, t, r);
            fmpq_clear(pq);
            continue;
        }
        slong p = fmpz_get_si(fmpq_numref(pq));
        fmpz_mpoly_set(t->num, m, r->ctx);
        fmpz_mpoly_set_fmpz(t->den, fmpq_denref(pq), r->ctx);
        fmpq_clear(pq);
        ratfun_canonicalise(t, r);
        slong v;
        const Kernel *lk;
        if (rf_is_var(t, &v, r) && (lk = kernels_of_var(K, v)) &&
            lk->fn == KF_LN) {
            ratfun_set(t, lk->arg, r); /* exp(p*ln(y)) = y^p */
        } else {
            /* exp(m*p/q) = exp(m/q)^p, and exp(m/q) is the q-th root of
             * exp(m) (one kernel for every q: exp(t/2)^2 = exp(t)) */
            slong q = 1;
            if (!fmpz_mpoly_is_one(t->den, r->ctx)) {
                fmpz_t qq;
                fmpz_init(qq);
                fmpz_mpoly_get_fmpz(qq, t->den, r->ctx);
                q = fmpz_fits_si(qq) ? fmpz_get_si(qq) : 0;
                fmpz_clear(qq);
                fmpz_mpoly_one(t->den, r->ctx);
            }
            if (q <= 0 || q > MAX_POWER) {
                K->why = "exp() of a number with a denominator over 1000";
                rc = KERNEL_EBIG;
            } else {
                rc = intern(K, t, KF_EXP, t, NULL, 0);
                if (rc == 0 && q > 1)
                    rc = intern(K, t, KF_ROOT, t, NULL, q);
            }
        }
        if (rc == 0) {
            if (ratfun_pow_si(t, t, p, r) != 0) {
                K->why = "exp() of a logarithm of zero";
                rc = KERNEL_EDOMAIN;
            } else {
                ratfun_mul(acc, acc, t, r);
            }
        }
    }
    if (rc == 0)
        ratfun_swap(res, acc, r);
    fmpz_mpoly_clear(m, r->ctx);
    ratfun_clear(t, r);
    ratfun_clear(acc, r);
    fmpz_clear(c);
    fmpz_clear(d);
    return rc;
}

/* the value of a function at a number, where it is exact: 1 (res set),
 * 0 (not exact: make a kernel), or an error */
static int fold_number(Kernels *K, RatFun res, KernelFn f, const fmpq_t q)
{
    const Ring *r = K->r;
    int zero = fmpq_is_zero(q), one = fmpq_is_one(q);
    fmpq_t h;
    fmpq_init(h);
    fmpq_set_si(h, 1, 2);
    int half = fmpq_equal(h, q);
    fmpq_clear(h);
    int cmp1 = fmpz_cmpabs(fmpq_numref(q), fmpq_denref(q)); /* |q| vs 1 */
    switch (f) {
    case KF_SQRT:
        if (fmpq_sgn(q) < 0) {
            K->why = "square root of a negative number";
            return KERNEL_EDOMAIN;
        }
        return sqrt_num(K, res, q) == 0 ? 1 : KERNEL_EFULL;
    case KF_SIN:
    case KF_SINH:
    case KF_ATAN:
    case KF_ASIN:
        if (f == KF_ASIN && cmp1 > 0) {
            K->why = "asin() of a number outside [-1, 1]";
            return KERNEL_EDOMAIN;
        }
        if (zero) {
            ratfun_zero(res, r);
            return 1;
        }
        if (f == KF_ASIN && (one || half))
            return pi_times(K, res, 1, one ? 2 : 6) == 0 ? 1 : KERNEL_EFULL;
        if (f == KF_ATAN && one)
            return pi_times(K, res, 1, 4) == 0 ? 1 : KERNEL_EFULL;
        return 0;
    case KF_COS:
    case KF_COSH:
    case KF_EXP:
        if (zero) {
            ratfun_one(res, r);
            return 1;
        }
        return 0;
    case KF_LN:
        if (fmpq_sgn(q) <= 0) {
            K->why = "logarithm of a number that is not positive";
            return KERNEL_EDOMAIN;
        }
        if (one) {
            ratfun_zero(res, r);
            return 1;
        }
        return 0;
    case KF_ACOS:
        if (cmp1 > 0) {
            K->why = "acos() of a number outside [-1, 1]";
            return KERNEL_EDOMAIN;
        }
        if (one) {
            ratfun_zero(res, r);
            return 1;
        }
        if (zero || half)
            return pi_times(K, res, 1, zero ? 2 : 3) == 0 ? 1 : KERNEL_EFULL;
        return 0;
    case KF_SIGN:
        ratfun_set_si(res, fmpq_sgn(q), r);
        return 1;
    default:
        return 0;
    }
}

static int is_odd(KernelFn f)
{
    return f == KF_SIN || f == KF_SINH || f == KF_ASIN || f == KF_ATAN ||
           f == KF_SIGN;
}

static int is_even(KernelFn f)
{
    return f == KF_COS || f == KF_COSH;
}

int kernel_apply(Kernels *K, RatFun res, KernelFn f, const RatFun x,
                 const RatFun y)
{
    const Ring *r = K->r;
    int rc;
    if (f == KF_PI)
        return intern(K, res, KF_PI, NULL, NULL, 0);
    RatFun a;
    ratfun_init(a, r);
    ratfun_set(a, x, r);
    fmpq_t q;
    fmpq_init(q);
    if (f == KF_ATAN2) {
        fmpq_t qx;
        fmpq_init(qx);
        if (ratfun_is_zero(a, r) && ratfun_get_fmpq(qx, y, r) &&
            fmpq_sgn(qx) > 0) {
            ratfun_zero(res, r);
            rc = 0;
        } else if (ratfun_is_zero(a, r) && ratfun_is_zero(y, r)) {
            K->why = "atan2(0, 0) is undefined";
            rc = KERNEL_EDOMAIN;
        } else {
            rc = intern(K, res, KF_ATAN2, a, y, 0);
        }
        fmpq_clear(qx);
        goto done;
    }
    if (ratfun_get_fmpq(q, a, r)) {
        rc = fold_number(K, res, f, q);
        if (rc != 0) {
            rc = rc == 1 ? 0 : rc;
            goto done;
        }
    }
    /* sin, cos at multiples of pi/12 where the value is a simple surd */
    if (f == KF_SIN || f == KF_COS) {
        fmpq_t c;
        fmpq_init(c);
        if (is_pi_multiple(K, a, c)) {
            fmpz_t k12;
            fmpz_init(k12);
            fmpz_mul_ui(k12, fmpq_numref(c), 12);
            if (fmpz_divisible(k12, fmpq_denref(c))) {
                fmpz_divexact(k12, k12, fmpq_denref(c));
                fmpz_fdiv_r(k12, k12, (fmpz[]){24});
                slong k = fmpz_get_si(k12);
                if (f == KF_COS)
                    k = (k + 6) % 24;
                int ok = sin_pi12(K, res, k);
                if (ok != 0) {
                    fmpz_clear(k12);
                    fmpq_clear(c);
                    rc = ok < 0 ? KERNEL_EFULL : 0;
                    goto done;
                }
            }
            fmpz_clear(k12);
        }
        fmpq_clear(c);
    }
    /* sin, cos of x + c*pi with 2c an integer: +-sin(x), +-cos(x) */
    if (f == KF_SIN || f == KF_COS) {
        slong pi = find(K, KF_PI, NULL, NULL, 0);
        RatFun c, xr;
        ratfun_init(c, r);
        ratfun_init(xr, r);
        fmpq_t cq;
        fmpq_init(cq);
        int done_shift = 0;
        if (pi >= 0 && rf_has(a, K->k[pi].var, r)) {
            /* c = d(arg)/d(pi): a number when arg = x + c*pi */
            ratfun_derivative(c, a, K->k[pi].var, r);
            fmpz_t k2;
            fmpz_init(k2);
            if (ratfun_get_fmpq(cq, c, r)) {
                fmpz_mul_ui(k2, fmpq_numref(cq), 2);
                if (fmpz_divisible(k2, fmpq_denref(cq))) {
                    fmpz_divexact(k2, k2, fmpq_denref(cq));
                    fmpz_fdiv_r(k2, k2, (fmpz[]){4});
                    slong k = fmpz_get_si(k2);
                    /* the rest x = arg - c*pi */
                    ratfun_gen(xr, K->k[pi].var, r);
                    ratfun_mul(xr, xr, c, r);
                    ratfun_sub(xr, a, xr, r);
                    if (!ratfun_is_zero(xr, r)) {
                        /* sin(x + k pi/2) = sin, cos, -sin, -cos (k = 0..3);
                         * cos(x + k pi/2) = cos, -sin, -cos, sin */
                        int use_cos = (f == KF_SIN) == (k % 2 == 1);
                        int negr = f == KF_SIN ? k >= 2 : (k == 1 || k == 2);
                        rc = kernel_apply(K, res, use_cos ? KF_COS : KF_SIN,
                                          xr, NULL);
                        if (rc == 0 && negr)
                            ratfun_neg(res, res, r);
                        done_shift = 1;
                    }
                }
            }
            fmpz_clear(k2);
        }
        fmpq_clear(cq);
        ratfun_clear(xr, r);
        ratfun_clear(c, r);
        if (done_shift)
            goto done;
    }
    /* sin, cos of x + asin(y), x + acos(y), x + atan(y) (also minus):
     * the addition formulas, so that angle() results combine
     * algebraically (cos(acos(y)) = y, sin(acos(y)) = sqrt(1 - y^2)) */
    if ((f == KF_SIN || f == KF_COS) && fmpz_mpoly_is_fmpz(a->den, r->ctx)) {
        fmpz_t dd, cc;
        fmpz_init(dd);
        fmpz_init(cc);
        fmpz_mpoly_get_fmpz(dd, a->den, r->ctx);
        slong iv = -1, sgn = 0;
        fmpz_mpoly_t cpoly;
        fmpz_mpoly_init(cpoly, r->ctx);
        for (slong i = 0; i < K->n && iv < 0; i++) {
            KernelFn g = K->k[i].fn;
            slong kv = K->k[i].var;
            ulong one = 1;
            if ((g != KF_ASIN && g != KF_ACOS && g != KF_ATAN) ||
                fmpz_mpoly_degree_si(a->num, kv, r->ctx) != 1)
                continue;
            /* the term must be exactly +-d*v: its coefficient a number */
            fmpz_mpoly_get_coeff_vars_ui(cpoly, a->num, &kv, &one, 1, r->ctx);
            if (!fmpz_mpoly_is_fmpz(cpoly, r->ctx))
                continue;
            fmpz_mpoly_get_fmpz(cc, cpoly, r->ctx);
            if (fmpz_cmpabs(cc, dd) == 0) {
                iv = i;
                sgn = fmpz_sgn(cc);
            }
        }
        fmpz_mpoly_clear(cpoly, r->ctx);
        /* arg = +-v alone: the rules for sin(asin(y)) ... below apply */
        if (iv >= 0 && a->num->length == 1)
            iv = -1;
        if (iv >= 0) {
            RatFun xr, v, sx, cx, sv, cv;
            ratfun_init(xr, r);
            ratfun_init(v, r);
            ratfun_init(sx, r);
            ratfun_init(cx, r);
            ratfun_init(sv, r);
            ratfun_init(cv, r);
            /* x = arg - sgn*v */
            ratfun_gen(v, K->k[iv].var, r);
            if (sgn < 0)
                ratfun_neg(v, v, r);
            ratfun_sub(xr, a, v, r);
            ratfun_gen(v, K->k[iv].var, r);
            rc = kernel_apply(K, sx, KF_SIN, xr, NULL);
            if (rc == 0)
                rc = kernel_apply(K, cx, KF_COS, xr, NULL);
            if (rc == 0)
                rc = kernel_apply(K, sv, KF_SIN, v, NULL);
            if (rc == 0)
                rc = kernel_apply(K, cv, KF_COS, v, NULL);
            if (rc == 0) {
                if (sgn < 0)
                    ratfun_neg(sv, sv, r);
                /* sin(x + w) = sin x cos w + cos x sin w;
                 * cos(x + w) = cos x cos w - sin x sin w */
                if (f == KF_SIN) {
                    ratfun_mul(sx, sx, cv, r);
                    ratfun_mul(cx, cx, sv, r);
                    ratfun_add(res, sx, cx, r);
                } else {
                    ratfun_mul(cx, cx, cv, r);
                    ratfun_mul(sx, sx, sv, r);
                    ratfun_sub(res, cx, sx, r);
                }
            }
            ratfun_clear(cv, r);
            ratfun_clear(sv, r);
            ratfun_clear(cx, r);
            ratfun_clear(sx, r);
            ratfun_clear(v, r);
            ratfun_clear(xr, r);
            fmpz_clear(cc);
            fmpz_clear(dd);
            goto done;
        }
        fmpz_clear(cc);
        fmpz_clear(dd);
    }
    /* odd and even functions see a canonical sign: sin(-a) = -sin(a) */
    int neg = rf_lead_sign(a, r) < 0 &&
              (is_odd(f) || is_even(f) || f == KF_ACOS);
    if (neg)
        ratfun_neg(a, a, r);
    slong v;
    const Kernel *in = rf_is_var(a, &v, r) ? kernels_of_var(K, v) : NULL;
    if (f == KF_SIGN && abs(kernel_sign(K, a)) == 2) {
        ratfun_set_si(res, kernel_sign(K, a) > 0 ? 1 : -1, r);
        rc = 0;
        goto odd;
    }
    /* sin(asin(x)) = x, cos(acos(x)) = x, cos(asin(x)) = sin(acos(x)) =
     * sqrt(1 - x^2), sin(atan(x)) = x/sqrt(1 + x^2), cos(atan(x)) =
     * 1/sqrt(1 + x^2) */
    if ((f == KF_SIN || f == KF_COS) && in &&
        (in->fn == KF_ASIN || in->fn == KF_ACOS || in->fn == KF_ATAN)) {
        RatFun yv, w;
        ratfun_init(yv, r);
        ratfun_init(w, r);
        ratfun_set(yv, in->arg, r);
        ratfun_mul(w, yv, yv, r);
        if (in->fn == KF_ATAN) {
            ratfun_set_si(res, 1, r);
            ratfun_add(w, res, w, r);
            rc = kernel_apply(K, w, KF_SQRT, w, NULL);
            if (rc == 0)
                ratfun_div(res, f == KF_SIN ? yv : res, w, r);
        } else if ((f == KF_SIN) == (in->fn == KF_ASIN)) {
            ratfun_set(res, yv, r);
            rc = 0;
        } else {
            ratfun_set_si(res, 1, r);
            ratfun_sub(w, res, w, r);
            rc = kernel_apply(K, res, KF_SQRT, w, NULL);
        }
        ratfun_clear(w, r);
        ratfun_clear(yv, r);
        goto odd;
    }
    /* arguments that are provably outside the domain on the declared
     * signs and ranges: -t^2 - 1, or -t with t in [1, 2] */
    if (f == KF_SQRT || f == KF_LN) {
        int sg = kernel_sign(K, a);
        if (sg == -2 || (f == KF_LN && sg < 0)) {
            K->why = f == KF_SQRT
                         ? "square root of an expression that is negative "
                           "for every value of its params and consts (on "
                           "their declared ranges and signs)"
                         : "logarithm of an expression that is never "
                           "positive (on the declared ranges and signs)";
            rc = KERNEL_EDOMAIN;
            goto done;
        }
    }
    switch (f) {
    case KF_SQRT:
        rc = sqrt_poly(K, res, a);
        goto done;
    case KF_EXP:
        rc = exp_split(K, res, a);
        goto done;
    case KF_LN:
        if (in && in->fn == KF_EXP) { /* ln(exp(y)) = y */
            ratfun_set(res, in->arg, r);
            rc = 0;
            goto done;
        }
        break;
    default:
        break;
    }
    rc = intern(K, res, f, a, NULL, 0);
odd:
    if (rc == 0 && neg && is_odd(f))
        ratfun_neg(res, res, r);
    if (rc == 0 && neg && f == KF_ACOS) { /* acos(-y) = pi - acos(y) */
        RatFun p;
        ratfun_init(p, r);
        rc = intern(K, p, KF_PI, NULL, NULL, 0);
        if (rc == 0)
            ratfun_sub(res, p, res, r);
        ratfun_clear(p, r);
    }
done:
    fmpq_clear(q);
    ratfun_clear(a, r);
    if (rc == 0)
        rc = kernel_reduce(K, res);
    return rc;
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
    slong i = find(K, KF_DIST, NULL, NULL, q);
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

int kernel_pow_q(Kernels *K, RatFun res, const RatFun x, slong p, slong q)
{
    const Ring *r = K->r;
    RatFun t;
    ratfun_init(t, r);
    int rc;
    if (q == 2) {
        rc = kernel_apply(K, t, KF_SQRT, x, NULL);
    } else {
        fmpq_t c;
        fmpq_init(c);
        rc = 0;
        if (ratfun_get_fmpq(c, x, r)) {
            /* an exact root of a number folds */
            fmpz_t a, b;
            fmpz_init(a);
            fmpz_init(b);
            if (fmpq_sgn(c) < 0 && q % 2 == 0) {
                K->why = "even root of a negative number";
                rc = KERNEL_EDOMAIN;
            } else if (fmpz_root(a, fmpq_numref(c), q) &&
                       fmpz_root(b, fmpq_denref(c), q)) {
                fmpq_t v;
                fmpq_init(v);
                fmpq_set_fmpz_frac(v, a, b);
                ratfun_set_fmpq(t, v, r);
                fmpq_clear(v);
                rc = 1;
            }
            fmpz_clear(a);
            fmpz_clear(b);
        }
        fmpq_clear(c);
        if (rc == 0)
            rc = intern(K, t, KF_ROOT, x, NULL, q);
        else if (rc == 1)
            rc = 0;
    }
    if (rc == 0 && ratfun_pow_si(t, t, p, r) != 0) {
        K->why = "negative power of zero";
        rc = KERNEL_EDOMAIN;
    }
    if (rc == 0) {
        ratfun_swap(res, t, r);
        rc = kernel_reduce(K, res);
    }
    ratfun_clear(t, r);
    return rc;
}

int kernel_abs(Kernels *K, RatFun res, const RatFun x)
{
    int known = kernel_sign(K, x);
    if (known) {
        if (known > 0)
            ratfun_set(res, x, K->r);
        else
            ratfun_neg(res, x, K->r);
        return 0;
    }
    RatFun s;
    ratfun_init(s, K->r);
    int rc = kernel_apply(K, s, KF_SIGN, x, NULL);
    if (rc == 0) {
        ratfun_mul(res, x, s, K->r);
        rc = kernel_reduce(K, res);
    }
    ratfun_clear(s, K->r);
    return rc;
}

/* ---- normal form -------------------------------------------------------- */

/* res = P with var^k (k >= q) rewritten by var^q = rel, as a RatFun */
static int reduce_poly(Kernels *K, RatFun res, const fmpz_mpoly_t P,
                       const Kernel *k)
{
    const Ring *r = K->r;
    slong d = fmpz_mpoly_degree_si(P, k->var, r->ctx);
    if (d < k->deg) {
        fmpz_mpoly_set(res->num, P, r->ctx);
        fmpz_mpoly_one(res->den, r->ctx);
        return 0;
    }
    if (ratfun_log2_bits_pow(k->rel, d / k->deg, r) > RATFUN_MAX_LOG2_BITS) {
        K->why = "expression too large for the functions' identities";
        return KERNEL_EBIG;
    }
    int rc = 0;
    RatFun acc, term, relp;
    fmpz_mpoly_t C;
    ratfun_init(acc, r);
    ratfun_init(term, r);
    ratfun_init(relp, r);
    fmpz_mpoly_init(C, r->ctx);
    slong var = k->var;
    for (slong j = 0; j <= d && rc == 0; j++) {
        ulong ju = (ulong)j;
        fmpz_mpoly_get_coeff_vars_ui(C, P, &var, &ju, 1, r->ctx);
        if (fmpz_mpoly_is_zero(C, r->ctx))
            continue;
        /* C * rel^(j / q) * var^(j % q) */
        fmpz_mpoly_gen(term->num, var, r->ctx);
        fmpz_mpoly_pow_ui(term->num, term->num, (ulong)(j % k->deg), r->ctx);
        fmpz_mpoly_mul(term->num, term->num, C, r->ctx);
        fmpz_mpoly_one(term->den, r->ctx);
        ratfun_canonicalise(term, r);
        if (j >= k->deg) {
            ratfun_pow_si(relp, k->rel, j / k->deg, r);
            if (ratfun_log2_bits_product(term, relp, r) >
                RATFUN_MAX_LOG2_BITS) {
                K->why = "expression too large for the functions' identities";
                rc = KERNEL_EBIG;
                break;
            }
            ratfun_mul(term, term, relp, r);
        }
        ratfun_add(acc, acc, term, r);
        rc = guard(K, acc->num);
    }
    if (rc == 0)
        ratfun_swap(res, acc, r);
    fmpz_mpoly_clear(C, r->ctx);
    ratfun_clear(relp, r);
    ratfun_clear(term, r);
    ratfun_clear(acc, r);
    return rc;
}

int kernel_uses(const Kernels *K, const RatFun x, int any)
{
    if (!K)
        return 0;
    for (slong i = 0; i < K->n; i++)
        if ((any || K->k[i].deg) && rf_has(x, K->k[i].var, K->r))
            return 1;
    return 0;
}

int kernel_uses_pteq(const Kernels *K, const PointEq x, int any)
{
    if (!K)
        return 0;
    for (slong i = 0; i < K->n; i++) {
        if (!any && !K->k[i].deg)
            continue;
        if (poly_has(x->den, K->k[i].var, K->r))
            return 1;
        for (slong j = 0; j < x->len; j++)
            if (poly_has(x->terms[j].num, K->k[i].var, K->r))
                return 1;
    }
    return 0;
}

int kernel_reduce(Kernels *K, RatFun x)
{
    if (!K || K->nrel == 0)
        return 0;
    const Ring *r = K->r;
    RatFun n, d, A, B;
    ratfun_init(n, r);
    ratfun_init(d, r);
    ratfun_init(A, r);
    ratfun_init(B, r);
    int rc = 0;
    for (slong i = K->n - 1; i >= 0 && rc == 0; i--) {
        const Kernel *k = &K->k[i];
        if (!k->deg || !rf_has(x, k->var, r))
            continue;
        rc = reduce_poly(K, n, x->num, k);
        if (rc == 0)
            rc = reduce_poly(K, d, x->den, k);
        if (rc != 0)
            break;
        if (ratfun_div(x, n, d, r) != 0) {
            rc = KERNEL_EZERO;
            break;
        }
        if (k->deg != 2 || !poly_has(x->den, k->var, r))
            continue;
        /* den = A + B v: multiply by A - B v; den becomes A^2 - B^2 rel */
        slong var = k->var;
        ulong e0 = 0, e1 = 1;
        fmpz_mpoly_get_coeff_vars_ui(A->num, x->den, &var, &e0, 1, r->ctx);
        fmpz_mpoly_one(A->den, r->ctx);
        fmpz_mpoly_get_coeff_vars_ui(B->num, x->den, &var, &e1, 1, r->ctx);
        fmpz_mpoly_one(B->den, r->ctx);
        ratfun_canonicalise(A, r);
        ratfun_canonicalise(B, r);
        RatFun conj, v;
        ratfun_init(conj, r);
        ratfun_init(v, r);
        ratfun_gen(v, var, r);
        ratfun_mul(conj, B, v, r);
        ratfun_sub(conj, A, conj, r);
        /* new numerator: num * conj (a polynomial), reduced */
        fmpz_mpoly_set(n->num, x->num, r->ctx);
        fmpz_mpoly_one(n->den, r->ctx);
        ratfun_canonicalise(n, r);
        ratfun_mul(n, n, conj, r);
        {
            RatFun red;
            ratfun_init(red, r);
            rc = reduce_poly(K, red, n->num, k);
            ratfun_swap(n, red, r);
            ratfun_clear(red, r);
        }
        /* new denominator: A^2 - B^2 rel */
        ratfun_mul(A, A, A, r);
        ratfun_mul(B, B, B, r);
        ratfun_mul(B, B, k->rel, r);
        ratfun_sub(d, A, B, r);
        ratfun_clear(v, r);
        ratfun_clear(conj, r);
        if (rc == 0 && ratfun_div(x, n, d, r) != 0)
            rc = KERNEL_EZERO;
        if (rc == 0)
            rc = guard(K, x->num);
    }
    ratfun_clear(B, r);
    ratfun_clear(A, r);
    ratfun_clear(d, r);
    ratfun_clear(n, r);
    if (rc == KERNEL_EZERO)
        K->why = "a denominator vanishes identically by the functions' "
                 "identities";
    return rc;
}

/* applies f to every weight of x and rebuilds x over one denominator */
typedef int (*WeightFn)(Kernels *K, RatFun w, void *ctx);

static int map_weights(Kernels *K, PointEq res, const PointEq x, WeightFn f,
                       void *ctx)
{
    const Ring *r = K->r;
    slong n = x->len;
    RatFunStruct *w = ratfun_vec_init(n, r);
    slong *pts = pc_xmalloc(sizeof(slong) * (size_t)(n ? n : 1));
    pteq_get_weights(w, x, r);
    int rc = 0;
    for (slong i = 0; i < n && rc == 0; i++) {
        pts[i] = x->terms[i].point;
        rc = f(K, w + i, ctx);
    }
    if (rc == 0)
        pteq_set_weights(res, pts, w, n, r);
    free(pts);
    ratfun_vec_clear(w, n, r);
    return rc;
}

static int reduce_one(Kernels *K, RatFun w, void *ctx)
{
    (void)ctx;
    return kernel_reduce(K, w);
}

int kernel_reduce_pteq(Kernels *K, PointEq x)
{
    if (!K || K->nrel == 0 || !kernel_uses_pteq(K, x, 0))
        return 0;
    return map_weights(K, x, x, reduce_one, NULL);
}

/* ---- dependence, derivatives ------------------------------------------- */

static int kernel_arg_depends(const Kernels *K, const Kernel *k, slong var)
{
    if (k->fn == KF_PI || k->fn == KF_DIST || k->fn == KF_COORD)
        return 0;
    return kernel_depends(K, k->arg, var) ||
           (k->fn == KF_ATAN2 && kernel_depends(K, k->arg2, var));
}

int kernel_depends(const Kernels *K, const RatFun x, slong var)
{
    if (rf_has(x, var, K ? K->r : NULL))
        return 1;
    if (!K)
        return 0;
    for (slong i = 0; i < K->n; i++)
        if (rf_has(x, K->k[i].var, K->r) &&
            kernel_arg_depends(K, &K->k[i], var))
            return 1;
    return 0;
}

/* does kernel i measure base point `point`? */
static int kernel_measures(const Kernels *K, slong i, slong point)
{
    const Kernel *k = &K->k[i];
    if (k->fn == KF_DIST)
        return k->pa == point || k->pb == point;
    for (slong j = 0; j < i; j++)
        if ((rf_has(k->arg, K->k[j].var, K->r) ||
             rf_has(k->arg2, K->k[j].var, K->r)) &&
            kernel_measures(K, j, point))
            return 1;
    return 0;
}

int kernel_measures_point(const Kernels *K, const PointEq x, slong point)
{
    for (slong i = 0; K && i < K->n; i++) {
        int used = poly_has(x->den, K->k[i].var, K->r);
        for (slong j = 0; j < x->len && !used; j++)
            used = poly_has(x->terms[j].num, K->k[i].var, K->r);
        if (used && kernel_measures(K, i, point))
            return 1;
    }
    return 0;
}

/* res = d k / d var for kernel k whose argument depends on var */
static int kernel_dk(Kernels *K, RatFun res, const Kernel *k0, slong var)
{
    const Ring *r = K->r;
    /* K->k never moves (cap slots allocated at once), but the values are
     * copied: kernel_apply below adds kernels */
    KernelFn fn = k0->fn;
    slong kv = k0->var, q = k0->q;
    RatFun a, b, da, db, t, u;
    ratfun_init(a, r);
    ratfun_init(b, r);
    ratfun_init(da, r);
    ratfun_init(db, r);
    ratfun_init(t, r);
    ratfun_init(u, r);
    ratfun_set(a, k0->arg, r);
    ratfun_set(b, k0->arg2, r);
    int rc = kernel_derivative(K, da, a, var);
    if (rc == 0 && fn == KF_ATAN2)
        rc = kernel_derivative(K, db, b, var);
    if (rc != 0)
        goto done;
    ratfun_gen(t, kv, r); /* the kernel itself */
    switch (fn) {
    case KF_SIN:
    case KF_SINH:
        rc = kernel_apply(K, u, fn == KF_SIN ? KF_COS : KF_COSH, a, NULL);
        ratfun_mul(res, u, da, r);
        break;
    case KF_COS:
    case KF_COSH:
        rc = kernel_apply(K, u, fn == KF_COS ? KF_SIN : KF_SINH, a, NULL);
        if (fn == KF_COS)
            ratfun_neg(u, u, r);
        ratfun_mul(res, u, da, r);
        break;
    case KF_EXP:
        ratfun_mul(res, t, da, r);
        break;
    case KF_LN:
        ratfun_div(res, da, a, r);
        break;
    case KF_SQRT:
    case KF_ROOT: /* v' = v a' / (q a) */
        ratfun_mul(res, t, da, r);
        ratfun_div(res, res, a, r);
        ratfun_set_si(u, fn == KF_SQRT ? 2 : q, r);
        ratfun_div(res, res, u, r);
        break;
    case KF_ASIN:
    case KF_ACOS: /* +-a' / sqrt(1 - a^2) */
        ratfun_mul(u, a, a, r);
        ratfun_neg(u, u, r);
        ratfun_set_si(t, 1, r);
        ratfun_add(u, u, t, r);
        rc = kernel_apply(K, u, KF_SQRT, u, NULL);
        if (rc == 0 && ratfun_div(res, da, u, r) != 0)
            rc = KERNEL_EZERO;
        if (fn == KF_ACOS)
            ratfun_neg(res, res, r);
        break;
    case KF_ATAN: /* a' / (1 + a^2) */
        ratfun_mul(u, a, a, r);
        ratfun_set_si(t, 1, r);
        ratfun_add(u, u, t, r);
        ratfun_div(res, da, u, r);
        break;
    case KF_ATAN2: /* (x y' - y x') / (x^2 + y^2), y = a, x = b */
        ratfun_mul(t, b, da, r);
        ratfun_mul(u, a, db, r);
        ratfun_sub(t, t, u, r);
        ratfun_mul(u, a, a, r);
        ratfun_mul(da, b, b, r);
        ratfun_add(u, u, da, r);
        if (ratfun_div(res, t, u, r) != 0)
            rc = KERNEL_EZERO;
        break;
    case KF_SIGN:
    case KF_PI:
    default:
        ratfun_zero(res, r);
        break;
    }
done:
    ratfun_clear(u, r);
    ratfun_clear(t, r);
    ratfun_clear(db, r);
    ratfun_clear(da, r);
    ratfun_clear(b, r);
    ratfun_clear(a, r);
    return rc;
}

int kernel_derivative(Kernels *K, RatFun res, const RatFun x, slong var)
{
    const Ring *r = K->r;
    RatFun acc, part, dk;
    ratfun_init(acc, r);
    ratfun_init(part, r);
    ratfun_init(dk, r);
    ratfun_derivative(acc, x, var, r);
    int rc = 0;
    slong n = K->n; /* kernels made while deriving do not occur in x */
    for (slong i = 0; i < n && rc == 0; i++) {
        slong kv = K->k[i].var;
        if (!rf_has(x, kv, r) || !kernel_arg_depends(K, &K->k[i], var))
            continue;
        rc = kernel_dk(K, dk, &K->k[i], var);
        if (rc != 0)
            break;
        ratfun_derivative(part, x, kv, r);
        ratfun_mul(part, part, dk, r);
        ratfun_add(acc, acc, part, r);
    }
    if (rc == 0) {
        ratfun_swap(res, acc, r);
        rc = kernel_reduce(K, res);
    }
    ratfun_clear(dk, r);
    ratfun_clear(part, r);
    ratfun_clear(acc, r);
    return rc;
}

typedef struct DerivCtx {
    slong var;
} DerivCtx;

static int derive_one(Kernels *K, RatFun w, void *ctx)
{
    return kernel_derivative(K, w, w, ((DerivCtx *)ctx)->var);
}

int kernel_derivative_pteq(Kernels *K, PointEq res, const PointEq x,
                           slong var)
{
    DerivCtx c = {var};
    return map_weights(K, res, x, derive_one, &c);
}

/* ---- substitution ------------------------------------------------------- */

/* res = P with the variables v where img[v] != NULL replaced by img[v],
 * simultaneously (over the product of the images' denominators) */
static int compose_poly(Kernels *K, RatFun res, const fmpz_mpoly_t P,
                        RatFunStruct *const *img)
{
    const Ring *r = K->r;
    int rc = 0;
    slong nv = r->ctx->minfo->nvars;
    slong *deg = flint_malloc(sizeof(slong) * (size_t)nv);
    ulong *e = flint_malloc(sizeof(ulong) * (size_t)nv);
    fmpz_mpoly_degrees_si(deg, P, r->ctx);
    fmpz_mpoly_t sum, term, pw, L;
    fmpz_mpoly_init(sum, r->ctx);
    fmpz_mpoly_init(term, r->ctx);
    fmpz_mpoly_init(pw, r->ctx);
    fmpz_mpoly_init(L, r->ctx);
    fmpz_mpoly_one(L, r->ctx);
    for (slong v = 0; v < nv; v++)
        if (img[v] && deg[v] > 0) {
            fmpz_mpoly_pow_ui(pw, img[v]->den, (ulong)deg[v], r->ctx);
            fmpz_mpoly_mul(L, L, pw, r->ctx);
        }
    fmpz_t c;
    fmpz_init(c);
    for (slong v = 0; v < nv && rc == 0; v++) /* the size of one term */
        if (img[v] && deg[v] > 0 &&
            (ratfun_log2_bits_pow(img[v], deg[v], r) > RATFUN_MAX_LOG2_BITS ||
             (double)deg[v] * (double)(img[v]->num->length +
                                       img[v]->den->length) >
                 (double)KERNEL_MAX_WORK_TERMS)) {
            K->why = "expression too large for the functions' identities";
            rc = KERNEL_EBIG;
        }
    for (slong i = 0; i < P->length && rc == 0; i++) {
        fmpz_mpoly_get_term_coeff_fmpz(c, P, i, r->ctx);
        fmpz_mpoly_get_term_exp_ui(e, P, i, r->ctx);
        fmpz_mpoly_set_fmpz(term, c, r->ctx);
        for (slong v = 0; v < nv; v++) {
            if (!img[v]) {
                if (e[v]) {
                    fmpz_mpoly_gen(pw, v, r->ctx);
                    fmpz_mpoly_pow_ui(pw, pw, e[v], r->ctx);
                    fmpz_mpoly_mul(term, term, pw, r->ctx);
                }
                continue;
            }
            if (deg[v] <= 0)
                continue;
            if (e[v]) {
                fmpz_mpoly_pow_ui(pw, img[v]->num, e[v], r->ctx);
                fmpz_mpoly_mul(term, term, pw, r->ctx);
            }
            if ((ulong)deg[v] > e[v]) {
                fmpz_mpoly_pow_ui(pw, img[v]->den, (ulong)deg[v] - e[v],
                                  r->ctx);
                fmpz_mpoly_mul(term, term, pw, r->ctx);
            }
        }
        fmpz_mpoly_add(sum, sum, term, r->ctx);
        rc = guard(K, sum);
        if (rc == 0)
            rc = guard(K, term);
    }
    fmpz_clear(c);
    if (rc == 0) {
        fmpz_mpoly_swap(res->num, sum, r->ctx);
        fmpz_mpoly_swap(res->den, L, r->ctx);
        ratfun_canonicalise(res, r);
    }
    fmpz_mpoly_clear(L, r->ctx);
    fmpz_mpoly_clear(pw, r->ctx);
    fmpz_mpoly_clear(term, r->ctx);
    fmpz_mpoly_clear(sum, r->ctx);
    flint_free(e);
    flint_free(deg);
    return rc;
}

static int compose_img(Kernels *K, RatFun res, const RatFun x,
                       RatFunStruct *const *img)
{
    const Ring *r = K->r;
    RatFun n, d;
    ratfun_init(n, r);
    ratfun_init(d, r);
    int rc = compose_poly(K, n, x->num, img);
    if (rc == 0)
        rc = compose_poly(K, d, x->den, img);
    if (rc == 0)
        rc = ratfun_div(res, n, d, r) == 0 ? 0 : RATFUN_EPOLE;
    ratfun_clear(d, r);
    ratfun_clear(n, r);
    return rc;
}

/* the images of var := s and of every kernel depending on var; NULL
 * entries stay */
static int build_images(Kernels *K, RatFunStruct **img, slong var,
                        const RatFun s)
{
    const Ring *r = K->r;
    img[var] = ratfun_vec_init(1, r);
    ratfun_set(img[var], s, r);
    slong n = K->n;
    int rc = 0;
    RatFun a, b;
    ratfun_init(a, r);
    ratfun_init(b, r);
    for (slong i = 0; i < n && rc == 0; i++) {
        if (!kernel_arg_depends(K, &K->k[i], var))
            continue;
        KernelFn fn = K->k[i].fn;
        slong q = K->k[i].q, kv = K->k[i].var;
        rc = compose_img(K, a, K->k[i].arg, img);
        if (rc == 0 && fn == KF_ATAN2)
            rc = compose_img(K, b, K->k[i].arg2, img);
        if (rc == 0)
            rc = kernel_reduce(K, a);
        if (rc != 0)
            break;
        RatFunStruct *v = ratfun_vec_init(1, r);
        if (fn == KF_ROOT)
            rc = kernel_pow_q(K, v, a, 1, q);
        else
            rc = kernel_apply(K, v, fn, a, fn == KF_ATAN2 ? b : NULL);
        img[kv] = v;
    }
    ratfun_clear(b, r);
    ratfun_clear(a, r);
    return rc;
}

static void free_images(RatFunStruct **img, slong nv, const Ring *r)
{
    for (slong v = 0; v < nv; v++)
        if (img[v])
            ratfun_vec_clear(img[v], 1, r);
    free(img);
}

int kernel_compose(Kernels *K, RatFun res, const RatFun x, slong var,
                   const RatFun s)
{
    const Ring *r = K->r;
    slong nv = r->ctx->minfo->nvars;
    RatFunStruct **img = pc_xcalloc((size_t)nv, sizeof *img);
    int rc = build_images(K, img, var, s);
    if (rc == 0)
        rc = compose_img(K, res, x, img);
    if (rc == 0)
        rc = kernel_reduce(K, res);
    free_images(img, nv, r);
    return rc;
}

typedef struct ComposeCtx {
    RatFunStruct **img;
} ComposeCtx;

static int compose_one(Kernels *K, RatFun w, void *ctx)
{
    int rc = compose_img(K, w, w, ((ComposeCtx *)ctx)->img);
    return rc ? rc : kernel_reduce(K, w);
}

int kernel_compose_pteq(Kernels *K, PointEq res, const PointEq x, slong var,
                        const RatFun s)
{
    const Ring *r = K->r;
    slong nv = r->ctx->minfo->nvars;
    RatFunStruct **img = pc_xcalloc((size_t)nv, sizeof *img);
    int rc = build_images(K, img, var, s);
    ComposeCtx c = {img};
    if (rc == 0)
        rc = map_weights(K, res, x, compose_one, &c);
    free_images(img, nv, r);
    return rc;
}

/* ---- coordinates --------------------------------------------------------- */

slong kernels_coord_slots(slong nindices, slong npoints)
{
    return nindices * npoints;
}

int kernel_coord(Kernels *K, RatFun res, slong a, slong k)
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
            rc = guard(K, acc->num);
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

/* the images of every coord(A_point, k) that x uses (x a RatFun, or a
 * PointEq when xp is not NULL): coord(P, k); and of every kernel whose
 * argument depends on one.  *any = 0 when x uses none. */
static int coord_images(Kernels *K, RatFunStruct **img, const RatFun x,
                        const PointEq xp, slong point, const PointEq P,
                        int *any)
{
    const Ring *r = K->r;
    slong n = K->n; /* the coordinates of P's points are made below */
    int rc = 0;
    *any = 0;
    for (slong i = 0; i < n && rc == 0; i++) {
        const Kernel *k = &K->k[i];
        if (k->fn != KF_COORD || k->pa != point)
            continue;
        int used = 0;
        if (xp) {
            for (slong j = 0; j < xp->len && !used; j++) {
                RatFunStruct w;
                pteq_weight_view(&w, xp, j);
                used = kernel_depends(K, &w, k->var);
            }
        } else {
            used = kernel_depends(K, x, k->var);
        }
        if (!used)
            continue;
        for (slong j = 0; j < P->len && rc == 0; j++)
            if (P->terms[j].point >= K->npoints) {
                K->why = "coord() of an unknown point: this replacement "
                         "has an unsolved unknown point, and the expression "
                         "uses coordinates of the point it replaces; solve "
                         "it first";
                rc = KERNEL_EDOMAIN;
            }
        if (rc != 0)
            break;
        *any = 1;
        slong kv = k->var, kk = k->pb;
        img[kv] = ratfun_vec_init(1, r);
        rc = kernel_coord_pteq(K, img[kv], P, kk);
    }
    /* the kernels over them, in order (their arguments use earlier
     * variables only) */
    RatFun a, b;
    ratfun_init(a, r);
    ratfun_init(b, r);
    for (slong i = 0; i < n && rc == 0 && *any; i++) {
        const Kernel *k = &K->k[i];
        int dep = 0;
        if (k->fn == KF_PI || k->fn == KF_DIST || k->fn == KF_COORD)
            continue;
        for (slong j = 0; j < i && !dep; j++)
            dep = img[K->k[j].var] &&
                  (rf_has(k->arg, K->k[j].var, r) ||
                   rf_has(k->arg2, K->k[j].var, r));
        if (!dep)
            continue;
        KernelFn fn = k->fn;
        slong q = k->q, kv = k->var;
        rc = compose_img(K, a, k->arg, img);
        if (rc == 0 && fn == KF_ATAN2)
            rc = compose_img(K, b, k->arg2, img);
        if (rc == 0)
            rc = kernel_reduce(K, a);
        if (rc != 0)
            break;
        RatFunStruct *v = ratfun_vec_init(1, r);
        img[kv] = v;
        if (fn == KF_ROOT)
            rc = kernel_pow_q(K, v, a, 1, q);
        else
            rc = kernel_apply(K, v, fn, a, fn == KF_ATAN2 ? b : NULL);
    }
    ratfun_clear(b, r);
    ratfun_clear(a, r);
    return rc;
}

int kernel_subst_coords(Kernels *K, RatFun res, const RatFun x, slong point,
                        const PointEq P)
{
    const Ring *r = K->r;
    slong nv = r->ctx->minfo->nvars;
    RatFunStruct **img = pc_xcalloc((size_t)nv, sizeof *img);
    int any;
    int rc = coord_images(K, img, x, NULL, point, P, &any);
    if (rc == 0 && any)
        rc = compose_img(K, res, x, img);
    else if (rc == 0)
        ratfun_set(res, x, r);
    if (rc == 0 && any)
        rc = kernel_reduce(K, res);
    free_images(img, nv, r);
    return rc;
}

int kernel_subst_coords_pteq(Kernels *K, PointEq res, const PointEq x,
                             slong point, const PointEq P)
{
    const Ring *r = K->r;
    slong nv = r->ctx->minfo->nvars;
    RatFunStruct **img = pc_xcalloc((size_t)nv, sizeof *img);
    int any;
    int rc = coord_images(K, img, NULL, x, point, P, &any);
    ComposeCtx c = {img};
    if (rc == 0 && any)
        rc = map_weights(K, res, x, compose_one, &c);
    else if (rc == 0)
        pteq_set(res, x, r);
    free_images(img, nv, r);
    return rc;
}
