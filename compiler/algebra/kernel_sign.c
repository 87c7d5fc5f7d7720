/*
 * kernel_sign.c - what is known of the sign of a value (kernel.h).
 *
 * The sign of a rational function is proved by interval arithmetic over Q:
 * every variable has an interval it is known to lie in, and the interval
 * of a polynomial is the sum over its terms of coefficient times the
 * product of its variables' intervals raised to their powers.  The
 * intervals are
 *
 *   - declared: `param t in [lo, hi]`, `const e in (0, 1)`, `const a > 0`,
 *     `const k < 1` (kernels_set_range; ends open or closed);
 *   - intrinsic to a kernel: sin, cos and sign in [-1, 1], exp and dist
 *     in (0, inf), cosh in [1, inf), sqrt and even roots in [0, inf)
 *     ((0, inf) when their argument is provably > 0), pi, asin, acos,
 *     atan and atan2 in rational enclosures of their ranges.
 *
 * Interval arithmetic cannot see that t - t^2 >= 0 on [0, 1] (the two
 * terms are bounded independently); where the sum is not decided, a
 * polynomial that factors (cheaply: ring_factor_affordable) is decided
 * factor by factor.  Every answer is sound: "unknown" (0) is always
 * allowed, a sign is returned only when it holds on the whole box.
 *
 * An end is open or closed, so that strict signs are proved where they
 * hold: sign(e^2 - 1) = -1 for e in (0, 1).  A declared interval that
 * decides a sign is recorded (kernels_assumed): the result then holds only
 * on the declared range, and the numeric side checks it (docs/eval.md).
 */
#include "compiler/algebra/kernel.h"

#include <stdlib.h>

#include <flint/fmpq.h>

#include "base/mem.h"
#include "base/stack.h"

/* one end of an interval: a rational value, or -inf/+inf (inf = -1/+1) */
typedef struct End {
    fmpq_t v;
    int inf;  // -1: -infinity, +1: +infinity, 0: v
    int open; // the end is not attained
} End;

typedef struct QI {
    End lo, hi;
} QI;

static void end_init(End *e)
{
    fmpq_init(e->v);
    e->inf = 0;
    e->open = 0;
}

static void end_set(End *d, const End *s)
{
    fmpq_set(d->v, s->v);
    d->inf = s->inf;
    d->open = s->open;
}

static void qi_init(QI *x)
{
    end_init(&x->lo);
    end_init(&x->hi);
}

static void qi_clear(QI *x)
{
    fmpq_clear(x->lo.v);
    fmpq_clear(x->hi.v);
}

static void qi_set(QI *d, const QI *s)
{
    end_set(&d->lo, &s->lo);
    end_set(&d->hi, &s->hi);
}

/* (-inf, inf) */
static void qi_line(QI *x)
{
    x->lo.inf = -1;
    x->hi.inf = 1;
    x->lo.open = x->hi.open = 1;
}

/* [a/b, c/d] (closed), or with the given openness */
static void qi_set_ends(QI *x, slong a, ulong b, slong c, ulong d, int lo_open,
                        int hi_open)
{
    fmpq_set_si(x->lo.v, a, b);
    fmpq_set_si(x->hi.v, c, d);
    x->lo.inf = x->hi.inf = 0;
    x->lo.open = lo_open;
    x->hi.open = hi_open;
}

/* the sign of an end: -1, 0, +1 */
static int end_sgn(const End *e)
{
    return e->inf ? e->inf : fmpq_sgn(e->v);
}

/* e1 < e2 : -1, equal: 0, > : +1 (values only) */
static int end_cmp(const End *a, const End *b)
{
    if (a->inf || b->inf)
        return a->inf == b->inf ? 0 : a->inf < b->inf ? -1 : 1;
    return fmpq_cmp(a->v, b->v);
}

/* d = a * b, where a zero end that is attained makes an attained 0 */
static void end_mul(End *d, const End *a, const End *b)
{
    int za = !a->inf && fmpq_is_zero(a->v), zb = !b->inf && fmpq_is_zero(b->v);
    if (za || zb) {
        fmpq_zero(d->v);
        d->inf = 0;
        d->open = !((za && !a->open) || (zb && !b->open));
        return;
    }
    if (a->inf || b->inf) {
        d->inf = end_sgn(a) * end_sgn(b);
        d->open = 1;
        return;
    }
    fmpq_mul(d->v, a->v, b->v);
    d->inf = 0;
    d->open = a->open || b->open;
}

/* d = x * y: the extremes of the four corner products; an extreme is
 * attained when a corner reaching it is */
static void qi_mul(QI *d, const QI *x, const QI *y)
{
    End c[4], lo, hi;
    const End *xs[2] = {&x->lo, &x->hi}, *ys[2] = {&y->lo, &y->hi};
    for (int i = 0; i < 4; i++) {
        end_init(&c[i]);
        end_mul(&c[i], xs[i / 2], ys[i % 2]);
    }
    end_init(&lo);
    end_init(&hi);
    end_set(&lo, &c[0]);
    end_set(&hi, &c[0]);
    for (int i = 1; i < 4; i++) {
        int cl = end_cmp(&c[i], &lo), ch = end_cmp(&c[i], &hi);
        if (cl < 0)
            end_set(&lo, &c[i]);
        else if (cl == 0)
            lo.open &= c[i].open;
        if (ch > 0)
            end_set(&hi, &c[i]);
        else if (ch == 0)
            hi.open &= c[i].open;
    }
    end_set(&d->lo, &lo);
    end_set(&d->hi, &hi);
    for (int i = 0; i < 4; i++)
        fmpq_clear(c[i].v);
    fmpq_clear(lo.v);
    fmpq_clear(hi.v);
}

/* d = e^k (k >= 1) of an end that is >= 0 or of any end for odd k */
static void end_pow(End *d, const End *e, ulong k)
{
    if (e->inf) {
        d->inf = (k % 2 == 0) ? 1 : e->inf;
        d->open = 1;
        return;
    }
    fmpq_pow_si(d->v, e->v, (slong)k);
    d->inf = 0;
    d->open = e->open;
}

/* d = x^k, k >= 1 */
static void qi_pow(QI *d, const QI *x, ulong k)
{
    if (k % 2 == 1) {
        QI t;
        qi_init(&t);
        end_pow(&t.lo, &x->lo, k);
        end_pow(&t.hi, &x->hi, k);
        qi_set(d, &t);
        qi_clear(&t);
        return;
    }
    /* |x|, then its power (monotone on [0, inf)) */
    QI a;
    qi_init(&a);
    int slo = end_sgn(&x->lo), shi = end_sgn(&x->hi);
    if (slo >= 0) {
        qi_set(&a, x);
    } else if (shi <= 0) {
        end_set(&a.lo, &x->hi);
        end_set(&a.hi, &x->lo);
        fmpq_neg(a.lo.v, a.lo.v);
        fmpq_neg(a.hi.v, a.hi.v);
        a.lo.inf = -a.lo.inf;
        a.hi.inf = -a.hi.inf;
    } else { /* lo < 0 < hi: 0 is attained */
        End nl;
        end_init(&nl);
        end_set(&nl, &x->lo);
        fmpq_neg(nl.v, nl.v);
        nl.inf = -nl.inf;
        int c = end_cmp(&nl, &x->hi);
        end_set(&a.hi, c > 0 ? &nl : &x->hi);
        if (c == 0)
            a.hi.open = nl.open && x->hi.open;
        fmpq_zero(a.lo.v);
        a.lo.inf = 0;
        a.lo.open = 0;
        fmpq_clear(nl.v);
    }
    end_pow(&d->lo, &a.lo, k);
    end_pow(&d->hi, &a.hi, k);
    qi_clear(&a);
}

/* d = a + b for ends of the same side */
static void end_add(End *d, const End *a, const End *b)
{
    if (a->inf || b->inf) {
        d->inf = a->inf ? a->inf : b->inf;
        d->open = 1;
        return;
    }
    fmpq_add(d->v, a->v, b->v);
    d->inf = 0;
    d->open = a->open || b->open;
}

static void qi_add(QI *d, const QI *x, const QI *y)
{
    end_add(&d->lo, &x->lo, &y->lo);
    end_add(&d->hi, &x->hi, &y->hi);
}

/* d = c * x for an integer c != 0 */
static void qi_scale(QI *d, const QI *x, const fmpz_t c)
{
    QI t;
    qi_init(&t);
    qi_set(&t, x);
    fmpq_mul_fmpz(t.lo.v, t.lo.v, c);
    fmpq_mul_fmpz(t.hi.v, t.hi.v, c);
    if (fmpz_sgn(c) < 0) {
        End s;
        end_init(&s);
        end_set(&s, &t.lo);
        end_set(&t.lo, &t.hi);
        end_set(&t.hi, &s);
        t.lo.inf = -t.lo.inf;
        t.hi.inf = -t.hi.inf;
        /* after the swap, lo holds the old hi negated: its inf flips */
        fmpq_clear(s.v);
    }
    qi_set(d, &t);
    qi_clear(&t);
}

/* the sign an interval proves: +2 > 0, +1 >= 0, -1 <= 0, -2 < 0, 0 none */
static int qi_sign(const QI *x)
{
    int slo = end_sgn(&x->lo), shi = end_sgn(&x->hi);
    if (slo > 0 || (slo == 0 && x->lo.open))
        return 2;
    if (slo == 0)
        return 1;
    if (shi < 0 || (shi == 0 && x->hi.open))
        return -2;
    if (shi == 0)
        return -1;
    return 0;
}

/* ---- the declared intervals --------------------------------------------- */

void kernels_set_range(Kernels *K, slong var, const fmpq_t lo, int lo_open,
                       const fmpq_t hi, int hi_open)
{
    if (var < 0 || var >= K->first)
        return;
    KRange *g = &K->range[var];
    if (lo && (!g->has_lo || fmpq_cmp(lo, g->lo) > 0 ||
               (fmpq_equal(lo, g->lo) && lo_open))) {
        fmpq_set(g->lo, lo);
        g->has_lo = 1;
        g->lo_open = (unsigned char)lo_open;
    }
    if (hi && (!g->has_hi || fmpq_cmp(hi, g->hi) < 0 ||
               (fmpq_equal(hi, g->hi) && hi_open))) {
        fmpq_set(g->hi, hi);
        g->has_hi = 1;
        g->hi_open = (unsigned char)hi_open;
    }
}

void kernels_set_sign(Kernels *K, slong var, int sign)
{
    if (sign == KSIGN_UNKNOWN)
        return;
    fmpq_t z;
    fmpq_init(z);
    kernels_set_range(K, var, z, sign == KSIGN_POS, NULL, 0);
    fmpq_clear(z);
}

int kernels_assumed(const Kernels *K, slong var)
{
    return K && var >= 0 && var < K->first ? K->used[var] : 0;
}

/* ---- the interval of a value -------------------------------------------- */

/* the declared variables a proof used, committed when it succeeds */
typedef struct Touched {
    slong *v;
    slong n, cap;
} Touched;

static void touch(Touched *t, slong v)
{
    for (slong i = 0; i < t->n; i++)
        if (t->v[i] == v)
            return;
    if (t->n == t->cap) {
        t->cap = t->cap ? 2 * t->cap : 8;
        t->v = pc_xrealloc(t->v, sizeof(slong) * (size_t)t->cap);
    }
    t->v[t->n++] = v;
}

static int sign_rf(const Kernels *K, const RatFun x, Touched *t);

/* the interval of ring variable v */
static void var_interval(const Kernels *K, slong v, QI *x, Touched *t)
{
    qi_line(x);
    if (v < K->first) {
        const KRange *g = &K->range[v];
        if (g->has_lo) {
            fmpq_set(x->lo.v, g->lo);
            x->lo.inf = 0;
            x->lo.open = g->lo_open;
        }
        if (g->has_hi) {
            fmpq_set(x->hi.v, g->hi);
            x->hi.inf = 0;
            x->hi.open = g->hi_open;
        }
        if (g->has_lo || g->has_hi)
            touch(t, v);
        return;
    }
    const Kernel *k = kernels_of_var(K, v);
    if (!k)
        return;
    switch (k->fn) {
    case KF_PI: /* 3.14159265 < pi < 3.14159266 */
        qi_set_ends(x, 314159265, 100000000, 314159266, 100000000, 1, 1);
        break;
    case KF_SIN:
    case KF_COS:
    case KF_SIGN:
        qi_set_ends(x, -1, 1, 1, 1, 0, 0);
        break;
    case KF_EXP:
    case KF_DIST:
        qi_set_ends(x, 0, 1, 0, 1, 1, 1);
        x->hi.inf = 1;
        break;
    case KF_COSH:
        qi_set_ends(x, 1, 1, 0, 1, 0, 1);
        x->hi.inf = 1;
        break;
    case KF_SQRT:
    case KF_ROOT:
        if (k->fn == KF_ROOT && k->q % 2) { /* odd: the argument's sign */
            int s = sign_rf(K, k->arg, t);
            if (s > 0) {
                qi_set_ends(x, 0, 1, 0, 1, s == 2, 1);
                x->hi.inf = 1;
            } else if (s < 0) {
                qi_set_ends(x, 0, 1, 0, 1, 1, s == -2);
                x->lo.inf = -1;
            }
            break;
        }
        qi_set_ends(x, 0, 1, 0, 1, sign_rf(K, k->arg, t) == 2, 1);
        x->hi.inf = 1;
        break;
    case KF_ASIN: /* [-pi/2, pi/2] */
        qi_set_ends(x, -8, 5, 8, 5, 0, 0);
        break;
    case KF_ACOS: /* [0, pi] */
        qi_set_ends(x, 0, 1, 16, 5, 0, 0);
        break;
    case KF_ATAN: /* (-pi/2, pi/2) */
        qi_set_ends(x, -8, 5, 8, 5, 1, 1);
        break;
    case KF_ATAN2: /* (-pi, pi] */
        qi_set_ends(x, -16, 5, 16, 5, 1, 0);
        break;
    default:
        break;
    }
}

/* the interval of polynomial P: sum of coefficient * prod var^e */
static void poly_interval(const Kernels *K, const fmpz_mpoly_t P, QI *res,
                          Touched *t)
{
    const Ring *r = K->r;
    slong nv = r->ctx->minfo->nvars;
    ulong *e = flint_malloc(sizeof(ulong) * (size_t)(nv ? nv : 1));
    QI *vi = flint_malloc(sizeof(QI) * (size_t)(nv ? nv : 1));
    char *have = flint_calloc((size_t)(nv ? nv : 1), 1);
    fmpz_t c;
    QI term, f;
    fmpz_init(c);
    qi_init(&term);
    qi_init(&f);
    qi_set_ends(res, 0, 1, 0, 1, 0, 0);
    for (slong i = 0; i < P->length; i++) {
        fmpz_mpoly_get_term_coeff_fmpz(c, P, i, r->ctx);
        fmpz_mpoly_get_term_exp_ui(e, P, i, r->ctx);
        qi_set_ends(&term, 1, 1, 1, 1, 0, 0);
        for (slong v = 0; v < nv; v++) {
            if (!e[v])
                continue;
            if (!have[v]) {
                qi_init(&vi[v]);
                var_interval(K, v, &vi[v], t);
                have[v] = 1;
            }
            qi_pow(&f, &vi[v], e[v]);
            qi_mul(&term, &term, &f);
        }
        qi_scale(&term, &term, c);
        qi_add(res, res, &term);
        if (res->lo.inf && res->hi.inf)
            break; /* nothing more to learn */
    }
    for (slong v = 0; v < nv; v++)
        if (have[v])
            qi_clear(&vi[v]);
    qi_clear(&f);
    qi_clear(&term);
    fmpz_clear(c);
    flint_free(have);
    flint_free(vi);
    flint_free(e);
}

/* the sign a polynomial's interval proves */
static int qi_sign_poly(const Kernels *K, const fmpz_mpoly_t P, Touched *t)
{
    QI x;
    qi_init(&x);
    poly_interval(K, P, &x, t);
    int s = qi_sign(&x);
    qi_clear(&x);
    return s;
}

/* the sign of a polynomial: its interval, else its factors' */
static int poly_sign(const Kernels *K, const fmpz_mpoly_t P, Touched *t,
                     int depth)
{
    const Ring *r = K->r;
    if (P->length == 0)
        return 0;
    QI x;
    qi_init(&x);
    poly_interval(K, P, &x, t);
    int s = qi_sign(&x);
    qi_clear(&x);
    if (s || depth > 0 || P->length < 2 || P->length > 64 ||
        fmpz_mpoly_total_degree_si(P, r->ctx) < 2 ||
        !ring_factor_affordable(P, r))
        return s;
    /* the square-free factors first (gcds: cheap), the irreducible ones
     * only where those leave a factor of at most 16 terms undecided */
    fmpz_mpoly_factor_t f;
    fmpz_mpoly_factor_init(f, r->ctx);
    int ok = ring_factor_compact(f, P, 0, r);
    for (slong i = 0; ok && i < f->num; i++)
        if (f->poly[i].length <= 16 &&
            fmpz_mpoly_total_degree_si(f->poly + i, r->ctx) >= 2 &&
            qi_sign_poly(K, f->poly + i, t) == 0) {
            ok = ring_factor_compact(f, P, 1, r);
            break;
        }
    if (ok && f->num > 1) {
        s = fmpz_sgn(f->constant) * 2;
        for (slong i = 0; i < f->num && s; i++) {
            int fs = poly_sign(K, f->poly + i, t, depth + 1);
            slong ex = fmpz_get_si(f->exp + i);
            if (ex % 2 == 0) /* an even power: >= 0, > 0 where fs != 0 */
                fs = fs ? 2 : 1;
            if (fs == 0) {
                s = 0;
                break;
            }
            int strict = abs(s) == 2 && abs(fs) == 2;
            s = (s > 0) == (fs > 0) ? 1 : -1;
            s *= strict ? 2 : 1;
        }
    } else {
        s = 0;
    }
    fmpz_mpoly_factor_clear(f, r->ctx);
    return s;
}

static int sign_rf(const Kernels *K, const RatFun x, Touched *t)
{
    /* sqrt(sqrt(...)) recurses through var_interval; where the stack runs
     * low the sign is left unproved (0: always sound) */
    if (ratfun_is_zero(x, K->r) || stack_low())
        return 0;
    int n = poly_sign(K, x->num, t, 0);
    int d = n ? poly_sign(K, x->den, t, 0) : 0;
    if (n == 0 || d == 0)
        return 0;
    int s = (n > 0) == (d > 0) ? 1 : -1;
    /* strict when the numerator is (the denominator is never 0) */
    return s * (abs(n) == 2 ? 2 : 1);
}

/* the sign of x (a RatFun, or the polynomial p when x is NULL) */
static int prove(const Kernels *K, const RatFun x, const fmpz_mpoly_t p,
                 Touched *t)
{
    return x ? sign_rf(K, x, t) : poly_sign(K, p, t, 0);
}

/* s, the sign proved for x (or p), after recording the declared ends its
 * proof rests on: each end of each declared interval it read is dropped in
 * turn, and kept only where the proof needs it (abs(t) = t for t in [0, 1]
 * needs t >= 0, not t <= 1) */
static int commit(const Kernels *K, int s, const RatFun x, const fmpz_mpoly_t p,
                  Touched *t)
{
    for (slong i = 0; s && i < t->n; i++) {
        KRange *g = &K->range[t->v[i]];
        for (int end = 0; end < 2; end++) {
            unsigned char *has = end ? &g->has_hi : &g->has_lo;
            if (!*has)
                continue;
            *has = 0;
            Touched u = {NULL, 0, 0};
            int still = prove(K, x, p, &u) == s;
            pc_free(u.v);
            *has = 1;
            if (!still) { /* needed: an assumption now */
                K->used[t->v[i]] |= (unsigned char)(end ? 2 : 1);
                K->cur[t->v[i]] |= (unsigned char)(end ? 2 : 1);
            }
        }
    }
    pc_free(t->v);
    return s;
}

int kernel_sign(const Kernels *K, const RatFun x)
{
    if (!K || ratfun_is_zero(x, K->r))
        return 0;
    Touched t = {NULL, 0, 0};
    return commit(K, sign_rf(K, x, &t), x, NULL, &t);
}

int kernel_sign_poly(const Kernels *K, const fmpz_mpoly_t p)
{
    if (!K || p->length == 0)
        return 0;
    Touched t = {NULL, 0, 0};
    return commit(K, poly_sign(K, p, &t, 0), NULL, p, &t);
}

int kernel_bounds(const Kernels *K, const RatFun x, fmpq_t lo, int *lo_open,
                  fmpq_t hi, int *hi_open)
{
    const Ring *r = K->r;
    if (!fmpz_mpoly_is_fmpz(x->den, r->ctx))
        return 0;
    for (slong v = 0; v < K->first; v++)
        if (fmpz_mpoly_degree_si(x->num, v, r->ctx) > 0)
            return 0;
    Touched t = {NULL, 0, 0};
    QI q;
    qi_init(&q);
    poly_interval(K, x->num, &q, &t);
    pc_free(t.v);
    fmpz_t d;
    fmpz_init(d);
    fmpz_mpoly_get_fmpz(d, x->den, r->ctx); /* > 0: canonical */
    int found = 0;
    if (!q.lo.inf) {
        fmpq_div_fmpz(lo, q.lo.v, d);
        *lo_open = q.lo.open;
        found |= 1;
    }
    if (!q.hi.inf) {
        fmpq_div_fmpz(hi, q.hi.v, d);
        *hi_open = q.hi.open;
        found |= 2;
    }
    fmpz_clear(d);
    qi_clear(&q);
    return found;
}
