/*
 * collapse.c - the collapsed kernel of emit-c, its exact analysis:
 * which outputs collapse, their exact coefficients in a centred monomial
 * basis and the emit-time conditioning bound (collapse.h; docs/codegen.md
 * "The collapsed kernel").  lower_collapse (lower.c) runs it on the
 * Derived weights (FLINT) right after lowering and attaches the result,
 * plain data, to the Plan; the C it leads to is written from the Plan by
 * collapse_emit.c.
 */
#include "codegen/collapse.h"
#include "base/mem.h"
#include "base/numfmt.h"
#include "codegen/lower.h"

#include <float.h>
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

#include <flint/fmpq.h>
#include <flint/fmpq_poly.h>

enum {
    KAPPA_PIECES = 32,  // [a, b] is first cut into this many pieces
    KAPPA_DEPTH = 40,   // each halved at most this often
    KAPPA_WORK = 40000, // subintervals looked at, at most
};

/* ---- exact analysis ------------------------------------------------------ */

/* r = x / c */
static void q_div_si(fmpq_t r, const fmpq_t x, slong c)
{
    fmpz_t z;
    fmpz_init_set_si(z, c);
    fmpq_div_fmpz(r, x, z);
    fmpz_clear(z);
}

/* r = v exactly (v finite) */
static void q_set_d(fmpq_t r, double v)
{
    int e;
    double f = frexp(v, &e); // v = f 2^e, 1/2 <= |f| < 1
    fmpq_set_si(r, (slong)ldexp(f, 53), 1);
    e -= 53;
    if (e >= 0)
        fmpq_mul_2exp(r, r, (ulong)e);
    else
        fmpq_div_2exp(r, r, (ulong)-e);
}

/* the variables p depends on: dep[v] = 1 */
static void mark_vars(unsigned char *dep, const fmpz_mpoly_t p, const Ring *r)
{
    slong nv = fmpz_mpoly_ctx_nvars(r->ctx);
    slong *deg = pc_xmalloc(sizeof *deg * (size_t)nv);
    fmpz_mpoly_degrees_si(deg, p, r->ctx);
    for (slong v = 0; v < nv; v++)
        if (deg[v] > 0)
            dep[v] = 1;
    pc_free(deg);
}

/* res = p as a polynomial in variable v (p depends on no other) */
static void to_poly(fmpq_poly_t res, const fmpz_mpoly_t p, slong v,
                    const Ring *r)
{
    fmpz_t c;
    fmpz_init(c);
    fmpq_poly_zero(res);
    for (slong i = 0; i < fmpz_mpoly_length(p, r->ctx); i++) {
        fmpz_mpoly_get_term_coeff_fmpz(c, p, i, r->ctx);
        fmpq_poly_set_coeff_fmpz(
            res, fmpz_mpoly_get_term_var_exp_si(p, i, v, r->ctx), c);
    }
    fmpz_clear(c);
}

/* res = the polynomial with coefficients |p_j| (deriv: j |p_j|, x^(j-1)) */
static void abs_poly(fmpq_poly_t res, const fmpq_poly_t p, int deriv)
{
    fmpq_t c;
    fmpq_init(c);
    fmpq_poly_zero(res);
    for (slong j = deriv; j < fmpq_poly_length(p); j++) {
        fmpq_poly_get_coeff_fmpq(c, p, j);
        fmpq_abs(c, c);
        if (deriv)
            fmpq_mul_si(c, c, j);
        fmpq_poly_set_coeff_fmpq(res, j - deriv, c);
    }
    fmpq_clear(c);
}

/* an upper bound of q (a double >= q) */
static double q_up(const fmpq_t q)
{
    double v = fmpq_get_d(q); // FLINT 2.9 truncates: within 1 ulp
    return nextafter(nextafter(v, INFINITY), INFINITY);
}

typedef struct Piece {
    fmpq_t x0, x1;
    int depth;
} Piece;

/* An upper bound of max over [x0, x1] of F(|x|) / sum_k |p_k(x)| (F with
 * non-negative coefficients, so increasing in |x|; dp[k] = the absolute
 * derivative of p_k, a bound of |p_k'| on [-X, X] at X).  On a piece with
 * centre c and radius h: F <= F(X), X = max |x|, and |p_k| >= |p_k(c)| -
 * dp_k(X) h.  Pieces are halved until that lower bound is at least half
 * of the sum at c.  Returns INFINITY when some piece cannot be bounded
 * (a common zero, or too much work); stops early, *atleast = 1, with a
 * value reached at a point once it exceeds cut. */
static double kappa_bound(const fmpq_poly_t F, const fmpq_poly_struct *p,
                          const fmpq_poly_struct *dp, slong K, const fmpq_t lo,
                          const fmpq_t hi, double cut, int *atleast)
{
    double best = 0;
    *atleast = 0;
    int cap = KAPPA_PIECES + 2 * KAPPA_DEPTH + 8, n = 0, work = 0;
    Piece *st = pc_xmalloc(sizeof *st * (size_t)cap);
    fmpq_t c, h, X, v, Gc, Glo, Fx, t;
    fmpq_init(c);
    fmpq_init(h);
    fmpq_init(X);
    fmpq_init(v);
    fmpq_init(Gc);
    fmpq_init(Glo);
    fmpq_init(Fx);
    fmpq_init(t);
    /* the first pieces, pushed so that the leftmost is looked at first */
    for (int i = KAPPA_PIECES - 1; i >= 0; i--) {
        Piece *q = &st[n++];
        fmpq_init(q->x0);
        fmpq_init(q->x1);
        q->depth = 0;
        /* x0 = lo + (hi - lo) i / PIECES */
        fmpq_sub(t, hi, lo);
        fmpq_mul_si(q->x0, t, i);
        q_div_si(q->x0, q->x0, KAPPA_PIECES);
        fmpq_add(q->x0, q->x0, lo);
        fmpq_mul_si(q->x1, t, i + 1);
        q_div_si(q->x1, q->x1, KAPPA_PIECES);
        fmpq_add(q->x1, q->x1, lo);
    }
    while (n > 0) {
        Piece *q = &st[n - 1];
        if (++work > KAPPA_WORK) {
            best = INFINITY;
            break;
        }
        fmpq_add(c, q->x0, q->x1);
        q_div_si(c, c, 2);
        fmpq_sub(h, q->x1, q->x0);
        q_div_si(h, h, 2);
        fmpq_abs(X, q->x0);
        fmpq_abs(t, q->x1);
        if (fmpq_cmp(t, X) > 0)
            fmpq_set(X, t);
        fmpq_zero(Gc);
        fmpq_zero(Glo);
        for (slong k = 0; k < K; k++) {
            fmpq_poly_evaluate_fmpq(v, p + k, c);
            fmpq_abs(v, v);
            fmpq_add(Gc, Gc, v);
            fmpq_poly_evaluate_fmpq(t, dp + k, X);
            fmpq_mul(t, t, h);
            fmpq_sub(v, v, t);
            if (fmpq_sgn(v) > 0)
                fmpq_add(Glo, Glo, v);
        }
        /* a value at a point: a lower bound of the maximum */
        if (fmpq_sgn(Gc) > 0) {
            fmpq_abs(t, c);
            fmpq_poly_evaluate_fmpq(Fx, F, t);
            fmpq_div(t, Fx, Gc);
            double at = fmpq_get_d(t);
            if (at > cut) {
                best = at;
                *atleast = 1;
                break;
            }
        }
        fmpq_mul_si(t, Glo, 2);
        int tight = fmpq_sgn(Glo) > 0 && fmpq_cmp(t, Gc) >= 0;
        if (tight || (q->depth >= KAPPA_DEPTH && fmpq_sgn(Glo) > 0)) {
            fmpq_poly_evaluate_fmpq(Fx, F, X);
            fmpq_div(t, Fx, Glo);
            double up = q_up(t);
            if (up > best)
                best = up;
            fmpq_clear(q->x0);
            fmpq_clear(q->x1);
            n--;
            continue;
        }
        if (q->depth >= KAPPA_DEPTH) { // a zero of every p_k, or near one
            best = INFINITY;
            break;
        }
        /* halve: [c, x1] below [x0, c] on the stack */
        if (n + 1 > cap) {
            cap *= 2;
            st = pc_xrealloc(st, sizeof *st * (size_t)cap);
            q = &st[n - 1];
        }
        Piece *r = &st[n++];
        fmpq_init(r->x0);
        fmpq_init(r->x1);
        fmpq_set(r->x0, q->x0);
        fmpq_set(r->x1, c);
        fmpq_set(q->x0, c);
        r->depth = ++q->depth;
    }
    for (int i = 0; i < n; i++) {
        fmpq_clear(st[i].x0);
        fmpq_clear(st[i].x1);
    }
    pc_free(st);
    fmpq_clear(c);
    fmpq_clear(h);
    fmpq_clear(X);
    fmpq_clear(v);
    fmpq_clear(Gc);
    fmpq_clear(Glo);
    fmpq_clear(Fx);
    fmpq_clear(t);
    return best;
}

static double gamma_k(double k)
{
    const double u = 0x1p-53;
    return k * u / (1 - k * u);
}

/* the bound of collapse.h; INFINITY when the denominator's is >= 1/2 */
static double error_bound(double kappa, double kappa_d, int deg, int K,
                          int den_const)
{
    const double u = 0x1p-53;
    double gA = gamma_k(K + 3.0 * deg + 1), gD = gamma_k(3.0 * deg + 1);
    if (den_const) // no division: coefficients a_jk / d exact, then rounded
        return gA * kappa * (1 + 1e-9);
    double r = gD * kappa_d;
    if (!(r < 0.5))
        return INFINITY;
    double e = gA * kappa * (1 + r) / (1 - r) * (1 + u) * (1 + u) +
               r / (1 - r) + 3 * u;
    return e * (1 + 1e-9); // the double arithmetic above, generously
}

/* the double nearest q when it is normal (or 0); 0 if none */
static int q_double(double *res, const fmpq_t q)
{
    if (lower_q_to_double(res, q) != LOWER_OK)
        return 0;
    return *res == 0 || fabs(*res) >= DBL_MIN;
}

/* *res = the smallest double >= q (up) or the largest <= q */
static int q_bound(double *res, const fmpq_t q, int up)
{
    if (!q_double(res, q))
        return 0;
    fmpq_t t;
    fmpq_init(t);
    for (int i = 0; i < 2; i++) {
        q_set_d(t, *res);
        int c = fmpq_cmp(t, q);
        if (up && c < 0)
            *res = nextafter(*res, INFINITY);
        else if (!up && c > 0)
            *res = nextafter(*res, -INFINITY);
    }
    fmpq_clear(t);
    return isfinite(*res);
}

/* the one param output o depends on, or -1 with co->why set */
static slong the_param(CollapseOutput *co, const Derived *d,
                       const DerivedOutput *o)
{
    const Ring *r = &d->ring;
    const PointEqStruct *eq = o->eq;
    slong nv = fmpz_mpoly_ctx_nvars(r->ctx);
    if (o->kind == KIND_SCALAR) {
        co->why = pc_xasprintf("a scalar output");
        return -1;
    }
    if (eq->len == 0) {
        co->why = pc_xasprintf("identically zero");
        return -1;
    }
    unsigned char *dep = pc_xcalloc((size_t)nv + 1, 1);
    for (slong k = 0; k < eq->len; k++)
        mark_vars(dep, eq->terms[k].num, r);
    mark_vars(dep, eq->den, r);
    slong var = -1, ndep = 0;
    for (slong v = 0; v < nv; v++)
        if (dep[v]) {
            ndep++;
            var = v;
        }
    pc_free(dep);
    if (ndep == 0) {
        co->why = pc_xasprintf("depends on no param");
        return -1;
    }
    if (ndep > 1 || var >= d->nparams) {
        co->why =
            pc_xasprintf("depends on %s", ndep > 1 ? "more than one variable"
                                          : var < d->nparams + d->nconsts
                                              ? "a const only"
                                              : "a function or an unknown");
        return -1;
    }
    return var;
}

/* the centre: co->mid (m: the double nearest the midpoint of [lo, hi]),
 * co->lo, co->hi, *e (2^e >= the half-width) and co->scale = 2^-e; 0 when
 * the range of param pname is not within doubles */
static int centre(CollapseOutput *co, fmpq_t m, int *e, const fmpq_t lo,
                  const fmpq_t hi, const char *pname)
{
    fmpq_t half, t;
    fmpq_init(half);
    fmpq_init(t);
    int ok = 0;
    /* m: the double nearest the midpoint; 2^e >= the half-width */
    fmpq_add(m, lo, hi);
    q_div_si(m, m, 2);
    if (!q_double(&co->mid, m) || !q_bound(&co->lo, lo, 1) ||
        !q_bound(&co->hi, hi, 0) || co->lo > co->hi) {
        co->why = pc_xasprintf("the range of %s is not within doubles", pname);
        goto done;
    }
    q_set_d(m, co->mid);
    fmpq_sub(half, hi, m);
    fmpq_sub(t, m, lo);
    if (fmpq_cmp(t, half) > 0)
        fmpq_set(half, t);
    if (!fmpq_is_zero(half)) {
        /* the smallest e with 2^e >= half */
        *e = (int)fmpz_bits(fmpq_numref(half)) -
             (int)fmpz_bits(fmpq_denref(half)) - 2;
        for (;;) {
            fmpq_one(t);
            if (*e >= 0)
                fmpq_mul_2exp(t, t, (ulong)*e);
            else
                fmpq_div_2exp(t, t, (ulong) - *e);
            if (fmpq_cmp(t, half) >= 0)
                break;
            (*e)++;
        }
    }
    if (*e > 1000 || *e < -1000) {
        co->why = pc_xasprintf("the range of %s is not within doubles", pname);
        goto done;
    }
    co->scale = ldexp(1.0, -*e);
    ok = 1;
done:
    fmpq_clear(half);
    fmpq_clear(t);
    return ok;
}

/* np[k], dpoly = the numerators and the denominator of eq in tau (t = m +
 * 2^e tau), scaled so that the denominator's largest coefficient is about
 * 1; 1 when the denominator is a constant (then exactly 1) */
static int to_tau(fmpq_poly_struct *np, fmpq_poly_t dpoly,
                  const PointEqStruct *eq, slong var, const Ring *r,
                  const fmpq_t m, int e)
{
    slong K = eq->len;
    fmpq_t t;
    fmpq_init(t);
    fmpq_poly_t lin;
    fmpq_poly_init(lin);
    /* t = m + 2^e tau */
    fmpq_poly_set_coeff_fmpq(lin, 0, m);
    fmpq_one(t);
    if (e >= 0)
        fmpq_mul_2exp(t, t, (ulong)e);
    else
        fmpq_div_2exp(t, t, (ulong)-e);
    fmpq_poly_set_coeff_fmpq(lin, 1, t);
    for (slong k = 0; k < K; k++) {
        to_poly(np + k, eq->terms[k].num, var, r);
        fmpq_poly_compose(np + k, np + k, lin);
    }
    to_poly(dpoly, eq->den, var, r);
    fmpq_poly_compose(dpoly, dpoly, lin);
    int den_const = fmpq_poly_degree(dpoly) <= 0;
    /* scaled so that the denominator's largest coefficient is about 1 (a
     * constant one: exactly 1, the numerators divided by it) */
    {
        fmpq_t big;
        fmpq_init(big);
        for (slong j = 0; j < fmpq_poly_length(dpoly); j++) {
            fmpq_poly_get_coeff_fmpq(t, dpoly, j);
            fmpq_abs(t, t);
            if (fmpq_cmp(t, big) > 0)
                fmpq_set(big, t);
        }
        if (fmpq_is_zero(big))
            fmpq_one(big);
        for (slong k = 0; k < K; k++)
            fmpq_poly_scalar_div_fmpq(np + k, np + k, big);
        fmpq_poly_scalar_div_fmpq(dpoly, dpoly, big);
        if (den_const) { // its sign too
            fmpq_poly_get_coeff_fmpq(t, dpoly, 0);
            for (slong k = 0; k < K; k++)
                fmpq_poly_scalar_div_fmpq(np + k, np + k, t);
            fmpq_poly_scalar_div_fmpq(dpoly, dpoly, t);
        }
        fmpq_clear(big);
    }
    fmpq_poly_clear(lin);
    fmpq_clear(t);
    return den_const;
}

/* co->point, co->a, co->b: the coefficients as doubles; 0 when one is
 * beyond the normal doubles */
static int to_doubles(CollapseOutput *co, const PointEqStruct *eq,
                      const fmpq_poly_struct *np, const fmpq_poly_t dpoly,
                      slong deg)
{
    slong K = eq->len;
    int ok = 0;
    fmpq_t t;
    fmpq_init(t);
    co->deg = (int)deg;
    co->nterms = (int)K;
    co->point = pc_xmalloc(sizeof *co->point * (size_t)K);
    co->a = pc_xcalloc((size_t)((deg + 1) * K), sizeof *co->a);
    co->b = pc_xcalloc((size_t)deg + 1, sizeof *co->b);
    for (slong k = 0; k < K; k++) {
        co->point[k] = (int)eq->terms[k].point;
        for (slong j = 0; j <= deg; j++) {
            fmpq_poly_get_coeff_fmpq(t, np + k, j);
            if (!q_double(&co->a[j * K + k], t)) {
                co->why =
                    pc_xasprintf("a coefficient beyond the normal doubles");
                goto done;
            }
        }
    }
    for (slong j = 0; j <= deg; j++) {
        fmpq_poly_get_coeff_fmpq(t, dpoly, j);
        if (!q_double(&co->b[j], t)) {
            co->why = pc_xasprintf("a coefficient beyond the normal doubles");
            goto done;
        }
    }
    ok = 1;
done:
    fmpq_clear(t);
    return ok;
}

/* co->kappa, co->kappa_d and co->bound: the conditioning over tau in
 * [(lo - m) 2^-e, (hi - m) 2^-e] (collapse.h); 0, with co->why, when the
 * bound is above COLLAPSE_TOL */
static int conditioning(CollapseOutput *co, const fmpq_poly_struct *np,
                        const fmpq_poly_t dpoly, slong K, slong deg, int e,
                        int den_const, const fmpq_t lo, const fmpq_t hi)
{
    int ok = 1;
    fmpq_t t;
    fmpq_init(t);
    fmpq_poly_t F, Fd;
    fmpq_poly_init(F);
    fmpq_poly_init(Fd);
    fmpq_poly_struct *dn = pc_xmalloc(sizeof *dn * (size_t)(K + 1));
    for (slong k = 0; k <= K; k++)
        fmpq_poly_init(dn + k);
    /* the conditioning over tau in [(lo - m) 2^-e, (hi - m) 2^-e] */
    {
        fmpq_t tlo, thi;
        fmpq_init(tlo);
        fmpq_init(thi);
        q_set_d(t, co->mid);
        fmpq_sub(tlo, lo, t);
        fmpq_sub(thi, hi, t);
        if (e >= 0) {
            fmpq_div_2exp(tlo, tlo, (ulong)e);
            fmpq_div_2exp(thi, thi, (ulong)e);
        } else {
            fmpq_mul_2exp(tlo, tlo, (ulong)-e);
            fmpq_mul_2exp(thi, thi, (ulong)-e);
        }
        /* F = sum_k |n_k| coefficientwise */
        for (slong k = 0; k < K; k++) {
            abs_poly(dn + K, np + k, 0);
            fmpq_poly_add(F, F, dn + K);
            abs_poly(dn + k, np + k, 1);
        }
        int atleast = 0, atleast_d = 0;
        /* the kappa above which the bound fails anyway */
        double cut = COLLAPSE_TOL / gamma_k(K + 3.0 * deg + 1) * 1.01;
        co->kappa = kappa_bound(F, np, dn, K, tlo, thi, cut, &atleast);
        co->kappa_d = 1;
        if (!den_const && !atleast && isfinite(co->kappa)) {
            abs_poly(Fd, dpoly, 0);
            abs_poly(dn + K, dpoly, 1);
            co->kappa_d = kappa_bound(Fd, dpoly, dn + K, 1, tlo, thi,
                                      0.5 / gamma_k(3.0 * deg + 1), &atleast_d);
        }
        co->bound =
            error_bound(co->kappa, co->kappa_d, (int)deg, (int)K, den_const);
        if (atleast || atleast_d)
            co->bound = INFINITY;
        fmpq_clear(tlo);
        fmpq_clear(thi);
        if (!(co->bound <= COLLAPSE_TOL)) {
            if (atleast || atleast_d || !isfinite(co->kappa) ||
                !isfinite(co->kappa_d))
                co->why = pc_xasprintf(
                    "monomial basis refused: kappa %s %.3g, kappa_d %s %.3g "
                    "over [%.17g, %.17g]: the error bound is above %g",
                    atleast ? ">=" : "<=", co->kappa,
                    atleast_d ? ">=" : "<=", co->kappa_d, co->lo, co->hi,
                    COLLAPSE_TOL);
            else
                co->why = pc_xasprintf(
                    "monomial basis refused: kappa <= %.3g, "
                    "kappa_d <= %.3g, error bound %.3g above %g",
                    co->kappa, co->kappa_d, co->bound, COLLAPSE_TOL);
            ok = 0;
        }
    }
    for (slong k = 0; k <= K; k++)
        fmpq_poly_clear(dn + k);
    pc_free(dn);
    fmpq_poly_clear(F);
    fmpq_poly_clear(Fd);
    fmpq_clear(t);
    return ok;
}

/* output o of d (the plan's output po), or why not */
static void analyse(CollapseOutput *co, const Derived *d,
                    const DerivedOutput *o)
{
    const Ring *r = &d->ring;
    const PointEqStruct *eq = o->eq;
    slong var = the_param(co, d, o);
    if (var < 0)
        return;
    co->param = (int)var;
    fmpq_t lo, hi;
    fmpq_init(lo);
    fmpq_init(hi);
    if (!d->has_range[var] || !ratfun_get_fmpq(lo, d->range + 2 * var, r) ||
        !ratfun_get_fmpq(hi, d->range + 2 * var + 1, r)) {
        co->why = pc_xasprintf("param %s has no declared range of numbers",
                               d->params[var]);
        fmpq_clear(lo);
        fmpq_clear(hi);
        return;
    }
    if (fmpq_cmp(lo, hi) > 0)
        fmpq_swap(lo, hi);
    slong deg = fmpz_mpoly_degree_si(eq->den, var, r->ctx);
    for (slong k = 0; k < eq->len; k++) {
        slong e = fmpz_mpoly_degree_si(eq->terms[k].num, var, r->ctx);
        if (e > deg)
            deg = e;
    }
    if (deg > COLLAPSE_MAX_DEGREE) {
        co->why = pc_xasprintf("degree %ld, above %d", (long)deg,
                               COLLAPSE_MAX_DEGREE);
        fmpq_clear(lo);
        fmpq_clear(hi);
        return;
    }
    slong K = eq->len;
    fmpq_t m;
    fmpq_init(m);
    fmpq_poly_t dpoly;
    fmpq_poly_init(dpoly);
    fmpq_poly_struct *np = pc_xmalloc(sizeof *np * (size_t)(K + 1));
    for (slong k = 0; k <= K; k++)
        fmpq_poly_init(np + k);
    int e = 0;
    if (!centre(co, m, &e, lo, hi, d->params[var]))
        goto done;
    int den_const = to_tau(np, dpoly, eq, var, r, m, e);
    if (!to_doubles(co, eq, np, dpoly, deg) ||
        !conditioning(co, np, dpoly, K, deg, e, den_const, lo, hi))
        goto done;
    co->ok = 1;
    co->why =
        pc_xasprintf("monomial basis in %s = (%s - %.17g) * 2^%d, degree %d; "
                     "kappa <= %.3g, kappa_d <= %.3g, error bound %.3g",
                     "tau", d->params[var], co->mid, -e, co->deg, co->kappa,
                     co->kappa_d, co->bound);
done:
    for (slong k = 0; k <= K; k++)
        fmpq_poly_clear(np + k);
    pc_free(np);
    fmpq_poly_clear(dpoly);
    fmpq_clear(m);
    fmpq_clear(lo);
    fmpq_clear(hi);
}

Collapse *collapse_new(const Derived *d, const Plan *p)
{
    Collapse *c = pc_xcalloc(1, sizeof *c);
    c->n = p->noutputs;
    c->o = pc_xcalloc((size_t)c->n + 1, sizeof *c->o);
    for (int i = 0; i < p->noutputs; i++) {
        CollapseOutput *co = &c->o[i];
        co->name = pc_xstrdup(p->outputs[i].name);
        slong o = derived_find_output(d, co->name);
        if (o < 0) {
            co->why = pc_xasprintf("not found");
            continue;
        }
        analyse(co, d, &d->outputs[o]);
        if (!co->ok) { // nothing half-made is kept
            pc_free(co->point);
            pc_free(co->a);
            pc_free(co->b);
            co->point = NULL;
            co->a = co->b = NULL;
        }
    }
    return c;
}
