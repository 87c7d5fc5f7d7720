/*
 * collapse.c - the collapsed kernel of emit-c: exact coefficients in a
 * centred monomial basis, the emit-time conditioning bound, and the C
 * (collapse.h; docs/codegen.md "The collapsed kernel").
 */
#include "codegen/collapse.h"
#include "codegen/cwrite.h"
#include "codegen/lower.h"
#include "base/mem.h"
#include "base/numfmt.h"

#include <float.h>
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

#include <flint/fmpq.h>
#include <flint/fmpq_poly.h>

enum {
    BLOCK = 64,          // samples per block, as emit_c.c's batch code
    KAPPA_PIECES = 32,   // [a, b] is first cut into this many pieces
    KAPPA_DEPTH = 40,    // each halved at most this often
    KAPPA_WORK = 40000,  // subintervals looked at, at most
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
    free(deg);
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
        fmpq_poly_set_coeff_fmpz(res,
                                 fmpz_mpoly_get_term_var_exp_si(p, i, v, r->ctx),
                                 c);
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
                          const fmpq_poly_struct *dp, slong K,
                          const fmpq_t lo, const fmpq_t hi, double cut,
                          int *atleast)
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
    free(st);
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

/* output o of d (the plan's output po), or why not */
static void analyse(CollapseOutput *co, const Derived *d, const DerivedOutput *o)
{
    const Ring *r = &d->ring;
    const PointEqStruct *eq = o->eq;
    slong nv = fmpz_mpoly_ctx_nvars(r->ctx);
    if (o->kind == KIND_SCALAR) {
        co->why = pc_xasprintf("a scalar output");
        return;
    }
    if (eq->len == 0) {
        co->why = pc_xasprintf("identically zero");
        return;
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
    free(dep);
    if (ndep == 0) {
        co->why = pc_xasprintf("depends on no param");
        return;
    }
    if (ndep > 1 || var >= d->nparams) {
        co->why = pc_xasprintf("depends on %s", ndep > 1 ? "more than one variable"
                                      : var < d->nparams + d->nconsts
                                          ? "a const only"
                                          : "a function or an unknown");
        return;
    }
    co->param = (int)var;
    fmpq_t lo, hi;
    fmpq_init(lo);
    fmpq_init(hi);
    if (!d->has_range[var] ||
        !ratfun_get_fmpq(lo, d->range + 2 * var, r) ||
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
        co->why = pc_xasprintf("degree %ld, above %d", (long)deg, COLLAPSE_MAX_DEGREE);
        fmpq_clear(lo);
        fmpq_clear(hi);
        return;
    }
    slong K = eq->len;
    fmpq_t m, half, t;
    fmpq_init(m);
    fmpq_init(half);
    fmpq_init(t);
    fmpq_poly_t lin, dpoly, F, Fd;
    fmpq_poly_init(lin);
    fmpq_poly_init(dpoly);
    fmpq_poly_init(F);
    fmpq_poly_init(Fd);
    fmpq_poly_struct *np = pc_xmalloc(sizeof *np * (size_t)(K + 1));
    fmpq_poly_struct *dn = pc_xmalloc(sizeof *dn * (size_t)(K + 1));
    for (slong k = 0; k <= K; k++) {
        fmpq_poly_init(np + k);
        fmpq_poly_init(dn + k);
    }
    int e = 0;
    /* m: the double nearest the midpoint; 2^e >= the half-width */
    fmpq_add(m, lo, hi);
    q_div_si(m, m, 2);
    if (!q_double(&co->mid, m) || !q_bound(&co->lo, lo, 1) ||
        !q_bound(&co->hi, hi, 0) || co->lo > co->hi) {
        co->why = pc_xasprintf("the range of %s is not within doubles",
                      d->params[var]);
        goto done;
    }
    q_set_d(m, co->mid);
    fmpq_sub(half, hi, m);
    fmpq_sub(t, m, lo);
    if (fmpq_cmp(t, half) > 0)
        fmpq_set(half, t);
    if (!fmpq_is_zero(half)) {
        /* the smallest e with 2^e >= half */
        e = (int)fmpz_bits(fmpq_numref(half)) -
            (int)fmpz_bits(fmpq_denref(half)) - 2;
        for (;;) {
            fmpq_one(t);
            if (e >= 0)
                fmpq_mul_2exp(t, t, (ulong)e);
            else
                fmpq_div_2exp(t, t, (ulong)-e);
            if (fmpq_cmp(t, half) >= 0)
                break;
            e++;
        }
    }
    if (e > 1000 || e < -1000) {
        co->why = pc_xasprintf("the range of %s is not within doubles",
                      d->params[var]);
        goto done;
    }
    co->scale = ldexp(1.0, -e);
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
                co->why = pc_xasprintf("a coefficient beyond the normal doubles");
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
            co->kappa_d =
                kappa_bound(Fd, dpoly, dn + K, 1, tlo, thi,
                            0.5 / gamma_k(3.0 * deg + 1), &atleast_d);
        }
        co->bound = error_bound(co->kappa, co->kappa_d, (int)deg, (int)K,
                                den_const);
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
                co->why = pc_xasprintf("monomial basis refused: kappa <= %.3g, "
                              "kappa_d <= %.3g, error bound %.3g above %g",
                              co->kappa, co->kappa_d, co->bound,
                              COLLAPSE_TOL);
            goto done;
        }
    }
    co->ok = 1;
    co->why = pc_xasprintf("monomial basis in %s = (%s - %.17g) * 2^%d, degree %d; "
                  "kappa <= %.3g, kappa_d <= %.3g, error bound %.3g",
                  "tau", d->params[var], co->mid, -e, co->deg, co->kappa,
                  co->kappa_d, co->bound);
done:
    for (slong k = 0; k <= K; k++) {
        fmpq_poly_clear(np + k);
        fmpq_poly_clear(dn + k);
    }
    free(np);
    free(dn);
    fmpq_poly_clear(lin);
    fmpq_poly_clear(dpoly);
    fmpq_poly_clear(F);
    fmpq_poly_clear(Fd);
    fmpq_clear(m);
    fmpq_clear(half);
    fmpq_clear(t);
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
            free(co->point);
            free(co->a);
            free(co->b);
            co->point = NULL;
            co->a = co->b = NULL;
        }
    }
    return c;
}

void collapse_free(Collapse *c)
{
    if (!c)
        return;
    for (int i = 0; i < c->n; i++) {
        free(c->o[i].name);
        free(c->o[i].why);
        free(c->o[i].point);
        free(c->o[i].a);
        free(c->o[i].b);
    }
    free(c->o);
    free(c);
}

/* ---- the C ---------------------------------------------------------------- */


/* the definition's first line(s); restr: the param arrays and out are
 * restrict (compatible with the header's prototype, which has no
 * restrict: gcc honours restrict on parameters, not on local pointers) */
static void signature(FILE *out, const CollapseNames *N, const char *fn,
                      int is_static, int restr)
{
    char *head = pc_xasprintf("%ssize_t %s(", is_static ? "static " : "", fn);
    cwrite_params(out, head, N->in, N->nparams, N->nin, N->pt, N->npt, 1, 1,
                  restr);
    free(head);
}

/* is coefficient j of the numerators non-zero for some point? */
static int nz(const CollapseOutput *o, int j)
{
    for (int k = 0; k < o->nterms; k++)
        if (o->a[j * o->nterms + k] != 0)
            return 1;
    return 0;
}

/* sum_k a_jk P_k[idx] */
static void coef_expr(FILE *out, const CollapseOutput *o,
                      const CollapseNames *N, int j, const char *idx)
{
    int any = 0;
    for (int k = 0; k < o->nterms; k++) {
        double a = o->a[j * o->nterms + k];
        if (a == 0)
            continue;
        if (any)
            fputs(" + ", out);
        if (a == 1) {
            fprintf(out, "%s[%s]", N->pt[o->point[k]], idx);
        } else {
            cwrite_double(out, a);
            fprintf(out, " * %s[%s]", N->pt[o->point[k]], idx);
        }
        any = 1;
    }
    if (!any)
        fputs("0.0", out);
}

/* Horner in x0 of the numerator coefficients called HEADj (HEAD "k0_":
 * k0_0, k0_1 ...) or, HEAD NULL, of the denominator's literals */
static void horner(FILE *out, const CollapseOutput *o, const char *head)
{
    int top = -1;
    for (int j = 0; j <= o->deg; j++)
        if (head ? nz(o, j) : o->b[j] != 0)
            top = j;
    if (top < 0) {
        fputs("0.0", out);
        return;
    }
    for (int j = 0; j < top; j++)
        fputc('(', out);
    for (int j = top; j >= 0; j--) {
        int has = head ? nz(o, j) : o->b[j] != 0;
        if (j < top) {
            fputs(" * x0", out);
            if (has)
                fputs(" + ", out);
        }
        if (has) {
            if (head)
                fprintf(out, "%s%d", head, j);
            else
                cwrite_double(out, o->b[j]);
        }
        if (j < top)
            fputc(')', out);
    }
}

static int den_const(const CollapseOutput *o)
{
    for (int j = 1; j <= o->deg; j++)
        if (o->b[j] != 0)
            return 0;
    return 1;
}

/* tau, the denominator and the flags of sample j (t = p<pi>[j]): x0, r1
 * (1/denominator, or 1.0 for a constant one) and fb[j] = pole + 0.5
 * overflow + 4 per failed range test.  The range tests use == only (with
 * fabs): quiet comparisons, which gcc -O2 vectorises under the default
 * -ftrapping-math, where it does not vectorise t >= lo. */
/* x0 = tau, r2 = t - lo, r3 = hi - t and (dc 0) r0 = the denominator,
 * r1 = 1/r0 of sample j */
static void sample_values(FILE *out, const CollapseOutput *o, int pi, int dc,
                          const char *ind, int line)
{
    fprintf(out, "%sconst double x0 = (p%d[j] - ", ind, pi);
    cwrite_double(out, o->mid);
    fputs(") * ", out);
    cwrite_double(out, o->scale);
    fputs(";\n", out);
    fprintf(out, "%sconst double r2 = p%d[j] - ", ind, pi);
    cwrite_double(out, o->lo);
    fprintf(out, ", r3 = ");
    cwrite_double(out, o->hi);
    fprintf(out, " - p%d[j];\n", pi);
    if (!dc) {
        fprintf(out, "%sconst double r0 = ", ind);
        horner(out, o, NULL);
        fprintf(out, "; /* line %d: denominator */\n", line);
        fprintf(out, "%sconst double r1 = 1.0 / r0;\n", ind);
    }
}

static void sample(FILE *out, const CollapseOutput *o, int pi, int dc,
                   const char *ind, int line)
{
    sample_values(out, o, pi, dc, ind, line);
    fprintf(out,
            "%sfb[j] = %s4.0 * ((double)(r2 != fabs(r2)) + (double)(r3 != "
            "fabs(r3)));\n",
            ind,
            dc ? "" : "(double)(r0 == 0.0) + 0.5 * (double)(r1 == 0.0) + ");
}

/* the coordinates of row j for dim 3 or 2 from x0 and r1 */
static void row(FILE *out, const CollapseOutput *o, int dim, int dc,
                const char *ind)
{
    fprintf(out, "%sdouble *o = out + (i0 + j) * %d;\n", ind, dim);
    for (int c = 0; c < dim; c++) {
        char head[16];
        snprintf(head, sizeof head, "k%d_", c);
        fprintf(out, "%so[%d] = ", ind, c);
        if (!dc)
            fputc('(', out);
        horner(out, o, head);
        fputs(dc ? ";\n" : ") * r1;\n", out);
    }
}

/* The fast path of a full block for dim 3 or 2 (no bad input): one
 * loop of fixed length that computes each sample and writes its row
 * straight to out (t and out are restrict parameters, so gcc vectorises it
 * at -O2 and without an alias check at -O3), and chk[j] = 0 when sample j
 * is in [lo, hi] and its coordinates and denominator are finite; else
 * negative or NaN: (v - v) is NaN for v not finite, (r - fabs(r)) is
 * negative for r < 0 (quiet operations only, which vectorise under
 * -ftrapping-math).  Every value that the general code would flag (a pole:
 * 1/0 in every coordinate; an overflow: an infinite denominator; a
 * coordinate not finite; outside the range, NaN) makes chk[j] non-zero. */
static void fast_loop(FILE *out, const CollapseOutput *o, int pi, int dc,
                      int dim, int line)
{
    const char *ind = "                ";
    fprintf(out, "            %sif (dim == %d) {\n", dim == 3 ? "" : "} else ",
            dim);
    fprintf(out, "            %sdouble *o = out + i0 * %d;\n", "    ", dim);
    fprintf(out, "                for (j = 0; j < %d; j++) {\n", BLOCK);
    ind = "                    ";
    sample_values(out, o, pi, dc, ind, line);
    for (int c = 0; c < dim; c++) {
        char head[16];
        snprintf(head, sizeof head, "k%d_", c);
        fprintf(out, "%sconst double q%d = ", ind, c);
        if (!dc)
            fputc('(', out);
        horner(out, o, head);
        fputs(dc ? ";\n" : ") * r1;\n", out);
    }
    for (int c = 0; c < dim; c++)
        fprintf(out, "%so[%d * j + %d] = q%d;\n", ind, dim, c, c);
    fprintf(out, "%s{\n%s    const double v = q0 + q1%s%s;\n", ind, ind,
            dim == 3 ? " + q2" : "", dc ? "" : " + r0");
    fprintf(out,
            "%s    chk[j] = (v - v) + ((r2 - fabs(r2)) + (r3 - fabs(r3)));\n"
            "%s}\n",
            ind, ind);
    fputs("                }\n", out);
}

void collapse_emit_batch(FILE *out, const CollapseOutput *o,
                         const CollapseNames *N, int line)
{
    int dc = den_const(o);
    int pi = o->param, K = o->nterms;
    fprintf(out,
            "/* %s, collapsed kernel (emit-c --kernel collapsed): for %s in\n"
            " * [%.17g, %.17g], each coordinate one polynomial, coefficients\n"
            " * combined once per call: %s.\n"
            " * The bound is relative to max_k |P_k[c]| * sum_k |w_k|.  Other\n"
            " * values of %s (or NaN): the weights code, %s. */\n",
            N->fn, N->in[pi], o->lo, o->hi, o->why, N->in[pi], N->fallback);
    signature(out, N, N->fn, N->is_static, 1);
    fputs("\n{\n", out);
    for (int i = 0; i < N->nparams; i++)
        if (i != pi)
            fprintf(out, "    (void)%s;\n", N->in[i]);
    for (int i = 0; i < N->npt; i++) {
        int used = 0;
        for (int k = 0; k < K; k++)
            used |= o->point[k] == i;
        if (!used)
            fprintf(out, "    (void)%s;\n", N->pt[i]);
    }
    fprintf(out,
            "    double pad%d[%d]; /* %s, tail block padded */\n"
            "    double w0[%d]; /* tau = (%s - m) * scale */\n",
            pi, BLOCK, N->in[pi], BLOCK, N->in[pi]);
    if (!dc)
        fprintf(out, "    double w1[%d]; /* 1/denominator */\n", BLOCK);
    fprintf(out,
            "    double fb[%d]; /* pole flags, +0.5: overflow, +4: outside "
            "the range */\n",
            BLOCK);
    fprintf(out,
            "    double chk[%d]; /* fast path: 0 when sample j is plain */\n",
            BLOCK);
    fputs("    size_t i0, j, nbad = 0, nfull;\n    int c, bad = 0;\n", out);
    /* the coefficients of dims 3 and 2, once per call */
    for (int c = 0; c < 3; c++) {
        int first = 1;
        for (int j = 0; j <= o->deg; j++)
            if (nz(o, j)) {
                fprintf(out, "%sk%d_%d = 0.0", first ? "    double " : ", ",
                        c, j);
                first = 0;
            }
        if (!first)
            fputs(";\n", out);
    }
    fputs("    if (dim == 2 || dim == 3) { /* line ", out);
    fprintf(out, "%d: the coefficients per coordinate */\n", line);
    for (int c = 0; c < 3; c++) {
        char idx[4];
        snprintf(idx, sizeof idx, "%d", c);
        if (c == 2)
            fputs("        if (dim == 3) {\n", out);
        for (int j = 0; j <= o->deg; j++) {
            if (!nz(o, j))
                continue;
            fprintf(out, "%s        k%d_%d = ", c == 2 ? "    " : "", c, j);
            coef_expr(out, o, N, j, idx);
            fputs(";\n", out);
        }
        if (c == 2)
            fputs("        }\n", out);
    }
    fputs("    }\n", out);
    /* non-finite consts or point coordinates: every sample is status 3 */
    for (int i = N->nparams; i < N->nin; i++)
        fprintf(out, "    bad |= !(%s - %s == 0.0);\n", N->in[i], N->in[i]);
    fputs("    for (c = 0; c < dim; c++) {\n", out);
    for (int k = 0; k < K; k++)
        fprintf(out, "        bad |= !(%s[c] - %s[c] == 0.0);\n",
                N->pt[o->point[k]], N->pt[o->point[k]]);
    fputs("    }\n", out);
    /* the full blocks of dims 3 and 2 (finite inputs) try the fast path
     * first; a block where it finds anything to flag, the tail, other dims
     * and non-finite inputs: the general code below */
    fprintf(out,
            "    nfull = (dim == 3 || dim == 2) && !bad ? n - n %% %d : 0;\n",
            BLOCK);
    fprintf(out, "    for (i0 = 0; i0 < n; i0 += %d) {\n", BLOCK);
    fprintf(out,
            "        const size_t m = n - i0 < %d ? n - i0 : %d;\n"
            "        const double *p%d = %s + i0;\n"
            "        int nb = 0;\n",
            BLOCK, BLOCK, pi, N->in[pi]);
    fputs("        if (i0 < nfull) { /* the fast path */\n"
          "            double s;\n",
          out);
    fast_loop(out, o, pi, dc, 3, line);
    fast_loop(out, o, pi, dc, 2, line);
    fputs("            }\n", out);
    /* the sum of chk (0 only when every chk[j] is) */
    cwrite_chk_sum(out, "            ", "s =");
    fputs("            if (s == 0.0) {\n"
          "                if (status != NULL)\n",
          out);
    fprintf(out,
            "                    for (j = 0; j < %d; j++)\n"
            "                        status[i0 + j] = 0;\n"
            "                continue;\n"
            "            }\n"
            "            /* something to flag: the block again, by the general "
            "code */\n"
            "        }\n",
            BLOCK);
    fprintf(out,
            "        if (m < %d) {\n"
            "            for (j = 0; j < %d; j++)\n"
            "                pad%d[j] = j < m ? p%d[j] : ",
            BLOCK, BLOCK, pi, pi);
    cwrite_double(out, o->lo);
    fprintf(out, ";\n            p%d = pad%d;\n        }\n", pi, pi);
    /* tau, 1/denominator and the flags into block arrays: a loop of
     * fixed length that reads p and writes only locals (gcc -O2 vectorises
     * it without an alias check, which its cost model at -O2 refuses) */
    fprintf(out, "        for (j = 0; j < %d; j++) {\n", BLOCK);
    sample(out, o, pi, dc, "            ", line);
    fputs("            w0[j] = x0;\n", out);
    if (!dc)
        fputs("            w1[j] = r1;\n", out);
    fputs("        }\n", out);
    fprintf(out,
            "        for (j = 0; j < %d; j++)\n"
            "            nb += fb[j] != 0.0;\n"
            "        if (nb != 0) {\n"
            "            for (j = 0; j < m && fb[j] < 4.0; j++)\n"
            "                ;\n"
            "            if (j < m) { /* outside [lo, hi], or NaN: the weights "
            "code */\n"
            "                nbad += %s(m, ",
            BLOCK, N->fallback);
    for (int i = 0; i < N->nin; i++)
        fprintf(out, i == pi ? "%s + i0, " : "%s, ", N->in[i]);
    for (int i = 0; i < N->npt; i++)
        fprintf(out, "%s, ", N->pt[i]);
    fputs("dim,\n"
          "                    out + i0 * (size_t)dim, status != NULL ? status "
          "+ i0 : NULL);\n"
          "                continue;\n"
          "            }\n"
          "        }\n",
          out);
    /* the rows from w0 and w1: dims 3 and 2 with a fixed trip count in a
     * full block (the interleaved stores vectorise), any other dim
     * coordinate by coordinate */
    for (int dim = 3; dim >= 2; dim--) {
        fprintf(out, "        %sif (dim == %d) {\n", dim == 3 ? "" : "} else ",
                dim);
        for (int full = 1; full >= 0; full--) {
            fprintf(out, full ? "            if (m == %d) {\n"
                              : "            } else {\n",
                    BLOCK);
            fprintf(out, full ? "                for (j = 0; j < %d; j++) {\n"
                              : "                for (j = 0; j < m; j++) {\n",
                    BLOCK);
            fputs("                    const double x0 = w0[j];\n", out);
            if (!dc)
                fputs("                    const double r1 = w1[j];\n", out);
            row(out, o, dim, dc, "                    ");
            fputs("                }\n", out);
        }
        fputs("            }\n", out);
    }
    fputs("        } else {\n"
          "            for (c = 0; c < dim; c++) {\n",
          out);
    for (int j = 0; j <= o->deg; j++) {
        if (!nz(o, j))
            continue;
        fprintf(out, "                const double q%d = ", j);
        coef_expr(out, o, N, j, "c");
        fputs(";\n", out);
    }
    fputs("                double *o = out + i0 * (size_t)dim + (size_t)c;\n"
          "                for (j = 0; j < m; j++) {\n"
          "                    const double x0 = w0[j];\n"
          "                    o[j * (size_t)dim] = ",
          out);
    if (!dc)
        fputc('(', out);
    horner(out, o, "q");
    fputs(dc ? ";\n" : ") * w1[j];\n", out);
    fputs("                }\n"
          "            }\n"
          "        }\n",
          out);
    if (!dc) {
        fputs("        if (nb != 0) /* poles or overflows in this block: NaN "
              "rows */\n"
              "            for (j = 0; j < m; j++) {\n"
              "                if (fb[j] == 0.0)\n"
              "                    continue;\n"
              "                nbad++;\n"
              "                for (c = 0; c < dim; c++)\n"
              "                    out[(i0 + j) * (size_t)dim + (size_t)c] = "
              "(double)NAN;\n"
              "            }\n",
              out);
    }
    /* statuses: 1 and 2 from the flags; 3 where a coordinate is not
     * finite (the coordinates are looked at, in one loop over the block's
     * rows) or an input is not */
    fputs("        if (status != NULL) {\n"
          "            const double *o = out + i0 * (size_t)dim;\n",
          out);
    if (!dc)
        fputs("            for (j = 0; j < m; j++)\n"
              "                status[i0 + j] = (unsigned char)(fb[j] >= 1.0 ? "
              "1 : fb[j] != 0.0 ? 2 : 0);\n",
              out);
    else
        fputs("            for (j = 0; j < m; j++)\n"
              "                status[i0 + j] = 0;\n",
              out);
    fputs("            nb = bad;\n"
          "            for (j = 0; j < m * (size_t)dim; j++)\n"
          "                nb += !(o[j] - o[j] == 0.0);\n"
          "            if (nb != 0)\n"
          "                for (j = 0; j < m; j++) {\n"
          "                    if (status[i0 + j] != 0)\n"
          "                        continue;\n"
          "                    if (!bad) {\n"
          "                        for (c = 0; c < dim; c++)\n"
          "                            if (!(o[j * (size_t)dim + (size_t)c] - "
          "o[j * (size_t)dim + (size_t)c] == 0.0))\n"
          "                                break;\n"
          "                        if (c == dim)\n"
          "                            continue;\n"
          "                    }\n"
          "                    for (c = 0; c < dim; c++)\n"
          "                        out[(i0 + j) * (size_t)dim + (size_t)c] = "
          "(double)NAN;\n"
          "                    nbad++;\n"
          "                    status[i0 + j] = 3;\n"
          "                }\n"
          "        }\n"
          "    }\n"
          "    return nbad;\n"
          "}\n\n",
          out);
}

void collapse_banner(FILE *out, const Collapse *c)
{
    fputs("/*\n * Kernel (emit-c --kernel collapsed), per output:\n", out);
    for (int i = 0; i < c->n; i++) {
        const CollapseOutput *o = &c->o[i];
        fprintf(out, " * %s: %s%s\n", o->name,
                o->ok ? "collapsed, " : "the weights kernel: ", o->why);
    }
    fputs(" */\n\n", out);
}

int collapse_name_free(const char *name, char *const *list, int n)
{
    for (int i = 0; i < n; i++)
        if (list[i] && strcmp(list[i], name) == 0)
            return 0;
    return 1;
}
