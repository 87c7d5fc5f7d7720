/*
 * book_forms.c - the forms of a polynomial the printer tries (book.h):
 * expanded in ascending order, factored, collected by the powers of one
 * variable, in the Bernstein basis of a param, and in powers of sin^2
 * with cos^2 = 1 - sin^2.  book_render keeps the form with the fewest
 * leaves (ties: factored, then expanded, then the collected form of the
 * shorter text; keep_better), applied to coefficients and factors up to
 * MAX_DEPTH levels, within a work budget per output (RENDER_WORK),
 * remembered in the memo.
 *
 * Factoring is most of the printing time: polyfactor.h's proofs of
 * irreducibility skip FLINT's factoring where they can (factor_known),
 * the rest runs in a ring of only the variables used, and deep inside a
 * form only a cheap partial factoring is tried (form_factored_cheap).
 * In the printer: polynomials in, models (book_model.c) out, for
 * book_write.c and book_eq.c.
 */
#include "compiler/print/book_int.h"

#include <stdlib.h>
#include <string.h>

#include <flint/fmpz_mpoly_factor.h>
#include <flint/fmpz_vec.h>

#include "base/mem.h"
#include "compiler/algebra/polyfactor.h"
#include "compiler/algebra/ring.h"
#include "compiler/print/absform.h"

/* ---- the forms of a polynomial ------------------------------------------ */

/* the total degree of p's term k */
static slong term_degree(const fmpz_mpoly_t p, slong k, const Ctx *c)
{
    const Ring *r = c->r;
    ulong *e = pc_xmalloc(sizeof(ulong) * (size_t)(r->nvars ? r->nvars : 1));
    fmpz_mpoly_get_term_exp_ui(e, p, k, r->ctx);
    slong d = 0;
    for (slong v = 0; v < r->nvars; v++)
        d += (slong)e[v];
    pc_free(e);
    return d;
}

/* expanded, ascending (the reverse of FLINT's degrevlex) */
PSum *book_form_expanded(const fmpz_mpoly_t p, const Ctx *c)
{
    const Ring *r = c->r;
    PSum *s = book_sum_new(c);
    slong len = fmpz_mpoly_length(p, r->ctx);
    ulong *e = pc_xmalloc(sizeof(ulong) * (size_t)(r->nvars ? r->nvars : 1));
    for (slong kk = len - 1; kk >= 0; kk--) {
        slong k = kk;
        if (c->is_abs) {
            /* |t| - 2*|t - 1| + |t - 2|: the terms of one degree in
             * the order of their vars (the kernels' order of creation) */
            slong deg = term_degree(p, kk, c), lo = kk;
            while (lo > 0 && term_degree(p, lo - 1, c) == deg)
                lo--;
            for (slong j = lo; j <= kk; j++) {
                PTerm *t = book_sum_push(s);
                fmpz_mpoly_get_term_coeff_fmpz(t->coeff, p, j, r->ctx);
                t->neg = fmpz_sgn(t->coeff) < 0;
                fmpz_abs(t->coeff, t->coeff);
                fmpz_mpoly_get_term_exp_ui(e, p, j, r->ctx);
                for (slong v = 0; v < r->nvars; v++)
                    if (e[v])
                        book_term_push(
                            t, (Atom){AT_VAR, v, NULL, NULL, NULL, e[v]});
            }
            kk = lo;
            continue;
        }
        PTerm *t = book_sum_push(s);
        fmpz_mpoly_get_term_coeff_fmpz(t->coeff, p, k, r->ctx);
        t->neg = fmpz_sgn(t->coeff) < 0;
        fmpz_abs(t->coeff, t->coeff);
        fmpz_mpoly_get_term_exp_ui(e, p, k, r->ctx);
        for (slong v = 0; v < r->nvars; v++)
            if (e[v])
                book_term_push(t, (Atom){AT_VAR, v, NULL, NULL, NULL, e[v]});
    }
    pc_free(e);
    book_sum_finish(s, p, c);
    return s;
}

/* is p = s*(1 - x) for a param or const x and a sign s?  returns x or -1 */
static slong bar_var(const fmpz_mpoly_t p, const Ctx *c, int *sign)
{
    const Ring *r = c->r;
    if (fmpz_mpoly_length(p, r->ctx) != 2 ||
        fmpz_mpoly_total_degree_si(p, r->ctx) != 1)
        return -1;
    for (slong v = 0; v < c->nparams + c->nconsts && v < r->nvars; v++) {
        if (fmpz_mpoly_degree_si(p, v, r->ctx) != 1)
            continue;
        fmpz_mpoly_t q;
        fmpz_mpoly_init(q, r->ctx);
        fmpz_mpoly_gen(q, v, r->ctx);
        fmpz_mpoly_neg(q, q, r->ctx);
        fmpz_mpoly_add_si(q, q, 1, r->ctx);
        int s = fmpz_mpoly_equal(p, q, r->ctx) ? 1 : 0;
        if (!s) {
            fmpz_mpoly_neg(q, q, r->ctx);
            s = fmpz_mpoly_equal(p, q, r->ctx) ? -1 : 0;
        }
        fmpz_mpoly_clear(q, r->ctx);
        if (s) {
            *sign = s;
            return v;
        }
    }
    return -1;
}

/* p as one factor raised to e, appended to t: an atom x, 1 - x, or a
 * parenthesised sum with its first term positive (the sign goes to t) */
static void push_factor(PTerm *t, const fmpz_mpoly_t p, ulong e, int depth,
                        const Ctx *c)
{
    const Ring *r = c->r;
    int sign = 1;
    slong v = bar_var(p, c, &sign);
    if (v >= 0) {
        if (sign < 0 && (e & 1))
            t->neg ^= 1;
        book_term_push(t, (Atom){AT_BAR, v, NULL, NULL, NULL, e});
        return;
    }
    PSum *s = book_render(p, depth, c);
    if (s->n == 1) {
        /* a monomial (or a constant): its pieces, to the power e */
        PTerm *u = &s->t[0];
        if (u->neg && (e & 1))
            t->neg ^= 1;
        fmpz_t pw;
        fmpz_init(pw);
        fmpz_pow_ui(pw, u->coeff, e);
        fmpz_mul(t->coeff, t->coeff, pw);
        fmpz_clear(pw);
        for (slong i = 0; i < u->n; i++) {
            Atom a = u->a[i];
            a.exp *= e;
            book_term_push(t, a);
        }
        pc_free(u->a);
        u->a = NULL;
        u->n = 0;
        book_sum_free(s, c);
        return;
    }
    if (s->t[0].neg) {
        book_sum_neg(s, c);
        if (e & 1)
            t->neg ^= 1;
    }
    (void)r;
    book_term_push(t, (Atom){AT_SUM, -1, s, NULL, NULL, e});
}

/* the proofs above, for the unit tests (book.h) */
int book_test_surely_irreducible(const fmpz_mpoly_t p, const Ring *r)
{
    return polyfactor_surely_irreducible(p, r);
}

int book_test_irreducible_mod_small_prime(const fmpz_poly_t u)
{
    return polyfactor_irreducible_mod_small_prime(u);
}

int book_test_quadratic_irreducible(const fmpz_poly_t u)
{
    return polyfactor_quadratic_irreducible(u);
}

/* FLINT's factorisation of p (ring_factor), or what form_factored makes
 * of it, when p is a constant times a monomial times powers of x - 1 (x a
 * param or const) times a polynomial q that polyfactor_surely_irreducible
 * proves irreducible (or 1), without FLINT's factoring (most of the
 * printing time).  FLINT's factoring first takes out the integer content (with
 * the sign of p's leading term), then the powers of the variables in their
 * order (fmpz_mpoly_factor_content), then splits the rest:
 *   - without the powers of x - 1, the rest, q, stays whole, in both of
 *     ring_factor's ways: the same factors in the same order;
 *   - with them, when ring_factor factors fully (ring_factor_affordable):
 *     the same factors, up to their order after the monomials; an order
 *     form_factored does not see, as a power of x - 1 is an atom (\bar{x})
 *     and only q is rendered (the squarefree way might keep a product of
 *     them whole: not taken).
 * 0: no such proof (f untouched). */
static int factor_known(fmpz_mpoly_factor_t f, const fmpz_mpoly_t p,
                        const Ctx *c)
{
    const Ring *r = c->r;
    enum { SQUAREFREE_MAX_TERMS = 4096 }; /* ring_factor's: beyond, it fails */
    slong len = fmpz_mpoly_length(p, r->ctx), nv = r->ctx->minfo->nvars;
    if (len < 2 || len > SQUAREFREE_MAX_TERMS ||
        !fmpz_mpoly_degrees_fit_si(p, r->ctx))
        return 0;
    fmpz_t g;
    fmpz_init(g);
    _fmpz_vec_content(g, p->coeffs, len);
    if (fmpz_sgn(p->coeffs + 0) < 0)
        fmpz_neg(g, g);
    ulong *lo = pc_xmalloc(sizeof(ulong) * (size_t)nv);
    ulong *e = pc_xmalloc(sizeof(ulong) * (size_t)nv);
    for (slong k = 0; k < len; k++) {
        fmpz_mpoly_get_term_exp_ui(e, p, k, r->ctx);
        for (slong v = 0; v < nv; v++)
            lo[v] = k == 0 || e[v] < lo[v] ? e[v] : lo[v];
    }
    fmpz_mpoly_t q;
    fmpz_mpoly_init(q, r->ctx);
    fmpz_t cq;
    fmpz_init(cq);
    for (slong k = 0; k < len; k++) {
        fmpz_mpoly_get_term_exp_ui(e, p, k, r->ctx);
        for (slong v = 0; v < nv; v++)
            e[v] -= lo[v];
        fmpz_divexact(cq, p->coeffs + k, g);
        fmpz_mpoly_push_term_fmpz_ui(q, cq, e, r->ctx);
    }
    /* (the same order: dividing by a monomial keeps degrevlex's) */
    /* powers of x - 1, when FLINT factors fully */
    ulong *bars = pc_xcalloc((size_t)nv, sizeof(ulong));
    int nbars = 0;
    if (ring_factor_affordable(p, r)) {
        fmpz_mpoly_t bar, quo;
        fmpz_mpoly_init(bar, r->ctx);
        fmpz_mpoly_init(quo, r->ctx);
        for (slong v = 0; v < c->nparams + c->nconsts && v < nv; v++) {
            fmpz_mpoly_gen(bar, v, r->ctx);
            fmpz_mpoly_sub_ui(bar, bar, 1, r->ctx);
            while (fmpz_mpoly_degree_si(q, v, r->ctx) > 0 &&
                   polyfactor_vanishes_at_ones(q, r) &&
                   fmpz_mpoly_divides(quo, q, bar, r->ctx)) {
                fmpz_mpoly_swap(q, quo, r->ctx);
                bars[v]++;
            }
            nbars += bars[v] > 0;
        }
        fmpz_mpoly_clear(quo, r->ctx);
        fmpz_mpoly_clear(bar, r->ctx);
    }
    /* q: 1 (only with powers of x - 1: p is not linear), or irreducible */
    int unit = fmpz_mpoly_is_one(q, r->ctx);
    int ok = unit ? nbars > 0 : polyfactor_surely_irreducible(q, r);
    if (ok) {
        slong n = 1 + nbars;
        for (slong v = 0; v < nv; v++)
            n += lo[v] > 0;
        fmpz_mpoly_factor_fit_length(f, n, r->ctx);
        fmpz_swap(f->constant, g);
        f->num = 0;
        for (slong v = 0; v < nv; v++)
            if (lo[v] > 0) {
                fmpz_mpoly_gen(f->poly + f->num, v, r->ctx);
                fmpz_set_ui(f->exp + f->num, lo[v]);
                f->num++;
            }
        for (slong v = 0; v < nv; v++)
            if (bars[v] > 0) {
                fmpz_mpoly_gen(f->poly + f->num, v, r->ctx);
                fmpz_mpoly_sub_ui(f->poly + f->num, f->poly + f->num, 1,
                                  r->ctx);
                fmpz_set_ui(f->exp + f->num, bars[v]);
                f->num++;
            }
        if (!unit) {
            fmpz_mpoly_swap(f->poly + f->num, q, r->ctx);
            fmpz_one(f->exp + f->num);
            f->num++;
        }
    }
    pc_free(bars);
    fmpz_clear(cq);
    fmpz_mpoly_clear(q, r->ctx);
    pc_free(e);
    pc_free(lo);
    fmpz_clear(g);
    return ok;
}

static PSum *form_factored(const fmpz_mpoly_t p, int depth, const Ctx *c)
{
    const Ring *r = c->r;
    if (fmpz_mpoly_total_degree_si(p, r->ctx) <= 1) {
        /* linear: irreducible but for its integer content */
        fmpz_t g;
        fmpz_init(g);
        _fmpz_vec_content(g, p->coeffs, fmpz_mpoly_length(p, r->ctx));
        PSum *s = NULL;
        if (!fmpz_is_one(g)) {
            fmpz_mpoly_t q;
            fmpz_mpoly_init(q, r->ctx);
            fmpz_mpoly_scalar_divexact_fmpz(q, p, g, r->ctx);
            s = book_sum_new(c);
            PTerm *t = book_sum_push(s);
            fmpz_set(t->coeff, g);
            push_factor(t, q, 1, depth + 1, c);
            book_sum_finish(s, p, c);
            fmpz_mpoly_clear(q, r->ctx);
        }
        fmpz_clear(g);
        return s;
    }
    fmpz_mpoly_factor_t f;
    fmpz_mpoly_factor_init(f, r->ctx);
    if (!factor_known(f, p, c) && !polyfactor_compact(f, p, r)) {
        fmpz_mpoly_factor_clear(f, r->ctx);
        return NULL;
    }
    /* trivial: p itself, irreducible and primitive */
    if (f->num == 0 ||
        (f->num == 1 && fmpz_is_pm1(f->constant) && fmpz_is_one(f->exp))) {
        fmpz_mpoly_factor_clear(f, r->ctx);
        return NULL;
    }
    PSum *s = book_sum_new(c);
    PTerm *t = book_sum_push(s);
    t->neg = fmpz_sgn(f->constant) < 0;
    fmpz_abs(t->coeff, f->constant);
    for (slong i = 0; i < f->num; i++)
        push_factor(t, f->poly + i, fmpz_get_ui(f->exp + i), depth + 1, c);
    fmpz_mpoly_factor_clear(f, r->ctx);
    book_sum_finish(s, p, c);
    return s;
}

/* appends coefficient k (a polynomial free of x) times the atoms of x to
 * s: the coefficient's best form, merged when it is one term */
static void push_collected(PSum *s, const fmpz_mpoly_t coef, Atom *xs, int nx,
                           int depth, const Ctx *c)
{
    PSum *cs = book_render(coef, depth + 1, c);
    int bare = 1;
    for (int i = 0; i < nx; i++)
        bare &= xs[i].exp == 0;
    if (bare && cs->n > 1) {
        /* x^0: the coefficient's terms join the sum */
        for (slong i = 0; i < cs->n; i++) {
            PTerm *t = book_sum_push(s);
            book_term_absorb(t, &cs->t[i]);
        }
        book_sum_free(cs, c);
        return;
    }
    PTerm *t = book_sum_push(s);
    if (cs->n == 1) {
        book_term_absorb(t, &cs->t[0]);
        book_sum_free(cs, c);
    } else {
        if (cs->t[0].neg) {
            book_sum_neg(cs, c);
            t->neg ^= 1;
        }
        book_term_push(t, (Atom){AT_SUM, -1, cs, NULL, NULL, 1});
    }
    for (int i = 0; i < nx; i++)
        if (xs[i].exp)
            book_term_push(t, xs[i]);
}

/* the coefficients a[0..n] of p in powers of x (caller clears) */
static fmpz_mpoly_struct *coeffs_in(const fmpz_mpoly_t p, slong x, slong n,
                                    const Ctx *c)
{
    fmpz_mpoly_struct *a =
        pc_xmalloc(sizeof(fmpz_mpoly_struct) * (size_t)(n + 1));
    for (slong i = 0; i <= n; i++) {
        fmpz_mpoly_init(a + i, c->r->ctx);
        fmpz_mpoly_get_coeff_vars_ui(a + i, p, &x, (ulong *)&i, 1, c->r->ctx);
    }
    return a;
}

static void coeffs_clear(fmpz_mpoly_struct *a, slong n, const Ctx *c)
{
    for (slong i = 0; i <= n; i++)
        fmpz_mpoly_clear(a + i, c->r->ctx);
    pc_free(a);
}

/* p = sum_k c_k x^k, ascending */
static PSum *form_powers(const fmpz_mpoly_t p, slong x, int depth, const Ctx *c)
{
    slong n = fmpz_mpoly_degree_si(p, x, c->r->ctx);
    fmpz_mpoly_struct *a = coeffs_in(p, x, n, c);
    PSum *s = book_sum_new(c);
    for (slong k = 0; k <= n; k++) {
        if (fmpz_mpoly_is_zero(a + k, c->r->ctx))
            continue;
        Atom xa = {AT_VAR, x, NULL, NULL, NULL, (ulong)k};
        push_collected(s, a + k, &xa, 1, depth, c);
    }
    coeffs_clear(a, n, c);
    book_sum_finish(s, p, c);
    return s;
}

/* bk = sum_{i <= k} a[stride*i] C(n - i, k - i): the k-th Bernstein
 * coefficient (without binomials) of the polynomial whose coefficients are
 * a[0], a[stride], ... (tmp and bin: scratch) */
static void bernstein_coeff(fmpz_mpoly_t bk, const fmpz_mpoly_struct *a,
                            slong stride, slong n, slong k, fmpz_mpoly_t tmp,
                            fmpz_t bin, const Ring *r)
{
    fmpz_mpoly_zero(bk, r->ctx);
    for (slong i = 0; i <= k; i++) {
        fmpz_bin_uiui(bin, (ulong)(n - i), (ulong)(k - i));
        fmpz_mpoly_scalar_mul_fmpz(tmp, a + stride * i, bin, r->ctx);
        fmpz_mpoly_add(bk, bk, tmp, r->ctx);
    }
}

/* p = sum_k b_k x^k (1 - x)^(n-k), n = deg_x p: the Bernstein basis of
 * the param x (without binomials), b_k = sum_{i<=k} a_i C(n-i, k-i) */
static PSum *form_bernstein(const fmpz_mpoly_t p, slong x, int depth,
                            const Ctx *c)
{
    const Ring *r = c->r;
    slong n = fmpz_mpoly_degree_si(p, x, r->ctx);
    fmpz_mpoly_struct *a = coeffs_in(p, x, n, c);
    PSum *s = book_sum_new(c);
    fmpz_mpoly_t bk, tmp;
    fmpz_mpoly_init(bk, r->ctx);
    fmpz_mpoly_init(tmp, r->ctx);
    fmpz_t bin;
    fmpz_init(bin);
    for (slong k = 0; k <= n; k++) {
        bernstein_coeff(bk, a, 1, n, k, tmp, bin, r);
        if (fmpz_mpoly_is_zero(bk, r->ctx))
            continue;
        Atom xs[2] = {{AT_VAR, x, NULL, NULL, NULL, (ulong)k},
                      {AT_BAR, x, NULL, NULL, NULL, (ulong)(n - k)}};
        push_collected(s, bk, xs, 2, depth, c);
    }
    fmpz_clear(bin);
    fmpz_mpoly_clear(tmp, r->ctx);
    fmpz_mpoly_clear(bk, r->ctx);
    coeffs_clear(a, n, c);
    book_sum_finish(s, p, c);
    return s;
}

/* the cos kernel of the same argument as sin kernel var v (its companion:
 * cos^2 = 1 - sin^2), or -1 */
slong book_cos_companion(slong v, const Ctx *c)
{
    const Kernel *k = kernels_of_var(c->K, v);
    if (!k || k->fn != KF_SIN)
        return -1;
    for (slong i = 0; i < c->K->n; i++) {
        const Kernel *w = &c->K->k[i];
        if (w->fn == KF_COS && ratfun_equal(w->arg, k->arg, c->r))
            return w->var;
    }
    return -1;
}

/* p (even in s = sin(x), free of w = cos(x)) as a polynomial in y = s^2,
 * in the basis y^k (1 - y)^(n-k) with 1 - y = cos(x)^2: the book's
 * a^2*sin(phi)^2 + b^2*cos(phi)^2 for the normal form's b^2 - b^2*sin(phi)^2
 * + a^2*sin(phi)^2 (form_bernstein in y); NULL when p is not such */
static PSum *form_sin2(const fmpz_mpoly_t p, slong s, slong w, int depth,
                       const Ctx *c)
{
    const Ring *r = c->r;
    slong n2 = fmpz_mpoly_degree_si(p, s, r->ctx);
    if (n2 < 2 || (n2 & 1) || fmpz_mpoly_degree_si(p, w, r->ctx) > 0)
        return NULL;
    fmpz_mpoly_struct *a = coeffs_in(p, s, n2, c);
    for (slong i = 1; i <= n2; i += 2)
        if (!fmpz_mpoly_is_zero(a + i, r->ctx)) {
            coeffs_clear(a, n2, c);
            return NULL;
        }
    slong n = n2 / 2;
    PSum *sum = book_sum_new(c);
    fmpz_mpoly_t bk, tmp;
    fmpz_mpoly_init(bk, r->ctx);
    fmpz_mpoly_init(tmp, r->ctx);
    fmpz_t bin;
    fmpz_init(bin);
    for (slong k = 0; k <= n; k++) {
        bernstein_coeff(bk, a, 2, n, k, tmp, bin, r);
        if (fmpz_mpoly_is_zero(bk, r->ctx))
            continue;
        Atom xs[2] = {{AT_VAR, s, NULL, NULL, NULL, (ulong)(2 * k)},
                      {AT_VAR, w, NULL, NULL, NULL, (ulong)(2 * (n - k))}};
        push_collected(sum, bk, xs, 2, depth, c);
    }
    fmpz_clear(bin);
    fmpz_mpoly_clear(tmp, r->ctx);
    fmpz_mpoly_clear(bk, r->ctx);
    coeffs_clear(a, n2, c);
    book_sum_finish(sum, p, c);
    return sum;
}

/* ---- collected by the knots: c_k(t)*|t - t_k|^p -------------------------- */

/* the knot of |x| (abs var v): x = c1*u + c0 of one variable u gives u and
 * -c0/c1 (returns 1); 0 for any other x */
static int knot_of(slong v, const Ctx *c, slong *u, fmpq_t k)
{
    const Ring *r = c->r;
    const Kernel *kn = kernels_of_var(c->K, v);
    const fmpz_mpoly_struct *x = kn->arg->num;
    slong len = fmpz_mpoly_length(x, r->ctx);
    if (!fmpz_mpoly_is_fmpz(kn->arg->den, r->ctx) || len < 1 || len > 2 ||
        fmpz_mpoly_total_degree_si(x, r->ctx) != 1)
        return 0;
    *u = -1;
    for (slong w = 0; w < r->nvars; w++) {
        slong d = fmpz_mpoly_degree_si(x, w, r->ctx);
        if (d > 0 && *u >= 0)
            return 0;
        if (d > 0)
            *u = w;
    }
    /* degrevlex: the linear term first, the constant (if any) second */
    if (len == 2)
        fmpq_set_fmpz_frac(k, x->coeffs + 1, x->coeffs + 0);
    else
        fmpq_zero(k);
    fmpq_neg(k, k);
    return 1;
}

/* the order of the knots: of one variable by their place on its axis
 * (|t| before |t - 1| before |t - 10|), then the others in the order of
 * their kernels */
static int knot_cmp(slong v, slong w, const Ctx *c)
{
    slong uv, uw;
    fmpq_t kv, kw;
    fmpq_init(kv);
    fmpq_init(kw);
    int sv = knot_of(v, c, &uv, kv), sw = knot_of(w, c, &uw, kw);
    int cmp = 0;
    if (sv != sw)
        cmp = sv ? -1 : 1;
    else if (sv && uv != uw)
        cmp = uv < uw ? -1 : 1;
    else if (sv)
        cmp = fmpq_cmp(kv, kw);
    if (cmp == 0 && v != w)
        cmp = v < w ? -1 : 1;
    fmpq_clear(kv);
    fmpq_clear(kw);
    return cmp;
}

typedef struct KnotGroup {
    ulong *ex;         // the exponents of the abs vars (in knot order)
    fmpz_mpoly_t coef; // free of them
} KnotGroup;

/* the free part first, then by the first knot used, its power, the rest */
static int group_cmp(const KnotGroup *a, const KnotGroup *b, slong na)
{
    slong fa = 0, fb = 0;
    while (fa < na && a->ex[fa] == 0)
        fa++;
    while (fb < na && b->ex[fb] == 0)
        fb++;
    if (fa != fb)
        return fa == na ? -1 : fb == na ? 1 : fa < fb ? -1 : 1;
    for (slong i = fa; i < na; i++)
        if (a->ex[i] != b->ex[i])
            return a->ex[i] < b->ex[i] ? -1 : 1;
    return 0;
}

/* a sum in ascending powers whose first term is negative is written in
 * descending powers when that leads with a positive term: 2*t - 1, not
 * -1 + 2*t (the book's (2t - 1)(t - 2)|t - 2|), t - 3 + abs(t - 3), and the
 * spline's 120*t^3 - 720*t^2 + 2078*t - 2166, not the positive terms first
 * (2078*t + 120*t^3 - 2166 - 720*t^2); -(64 - 39*t + 6*t^2) stays */
static void lead_positive(PSum *s)
{
    if (s->n < 2 || !s->t[0].neg || s->t[s->n - 1].neg)
        return;
    for (slong i = 0, j = s->n - 1; i < j; i++, j--) {
        PTerm t = s->t[i];
        s->t[i] = s->t[j];
        s->t[j] = t;
    }
}

/* p, which uses |x| of some sign kernels (c->is_abs), collected by them as
 * the composite-curve text writes its results: the part free of them,
 * then sum_k c_k*|t - t_k|^p in the order of the knots, one term per knot
 * (per product of |x|'s), its coefficient in its best form; a factor x of
 * the coefficient is written as x beside its |x| ((2*t + 1)*(t - 1)*
 * abs(t - 1)), unless only a negative number would be left.  NULL when p
 * uses none. */
static PSum *form_knots(const fmpz_mpoly_t p, int depth, const Ctx *c)
{
    const Ring *r = c->r;
    slong nv = r->nvars, na = 0;
    slong *av = pc_xmalloc(sizeof(slong) * (size_t)(nv ? nv : 1));
    for (slong v = 0; v < nv; v++)
        if (c->is_abs[v] && fmpz_mpoly_degree_si(p, v, r->ctx) > 0) {
            slong j = na++;
            for (; j > 0 && knot_cmp(av[j - 1], v, c) > 0; j--)
                av[j] = av[j - 1];
            av[j] = v;
        }
    if (na == 0) {
        pc_free(av);
        return NULL;
    }
    slong len = fmpz_mpoly_length(p, r->ctx), ng = 0;
    KnotGroup *g = pc_xmalloc(sizeof(KnotGroup) * (size_t)len);
    ulong *e = pc_xmalloc(sizeof(ulong) * (size_t)nv);
    ulong *ex = pc_xmalloc(sizeof(ulong) * (size_t)na);
    fmpz_t cf;
    fmpz_init(cf);
    for (slong k = 0; k < len; k++) {
        fmpz_mpoly_get_term_exp_ui(e, p, k, r->ctx);
        fmpz_mpoly_get_term_coeff_fmpz(cf, p, k, r->ctx);
        for (slong i = 0; i < na; i++) {
            ex[i] = e[av[i]];
            e[av[i]] = 0;
        }
        slong j = 0;
        while (j < ng && memcmp(g[j].ex, ex, sizeof(ulong) * (size_t)na))
            j++;
        if (j == ng) {
            g[ng].ex = pc_xmalloc(sizeof(ulong) * (size_t)na);
            memcpy(g[ng].ex, ex, sizeof(ulong) * (size_t)na);
            fmpz_mpoly_init(g[ng].coef, r->ctx);
            ng++;
        }
        fmpz_mpoly_push_term_fmpz_ui(g[j].coef, cf, e, r->ctx);
    }
    for (slong j = 0; j < ng; j++) {
        fmpz_mpoly_sort_terms(g[j].coef, r->ctx);
        fmpz_mpoly_combine_like_terms(g[j].coef, r->ctx);
    }
    for (slong i = 1; i < ng; i++) { /* insertion sort: a total order */
        KnotGroup x = g[i];
        slong j = i;
        for (; j > 0 && group_cmp(&g[j - 1], &x, na) > 0; j--)
            g[j] = g[j - 1];
        g[j] = x;
    }
    PSum *s = book_sum_new(c);
    Atom *xs = pc_xmalloc(sizeof(Atom) * (size_t)(na + 1));
    fmpz_mpoly_t quo;
    fmpz_mpoly_init(quo, r->ctx);
    for (slong j = 0; j < ng; j++) {
        int nx = 0;
        slong one = -1, used = 0;
        for (slong i = 0; i < na; i++)
            if (g[j].ex[i]) {
                one = av[i];
                used++;
            }
        if (used == 1) {
            const Kernel *kn = kernels_of_var(c->K, one);
            if (fmpz_mpoly_divides(quo, g[j].coef, kn->arg->num, r->ctx) &&
                !(fmpz_mpoly_is_fmpz(quo, r->ctx) &&
                  fmpz_sgn(quo->coeffs) < 0)) {
                fmpz_mpoly_swap(quo, g[j].coef, r->ctx);
                xs[nx++] = (Atom){AT_KNOT, one, NULL, NULL, NULL, 1};
            }
        }
        for (slong i = 0; i < na; i++)
            if (g[j].ex[i])
                xs[nx++] = (Atom){AT_VAR, av[i], NULL, NULL, NULL, g[j].ex[i]};
        PSum *cs = book_render(g[j].coef, depth + 1, c);
        if (nx == 0) { /* the free part first, its terms joining the sum:
                        * (t - 3 + abs(t - 3))/2, the text's Q(t, 3) */
            if (cs->n == 1 && cs->t[0].neg &&
                fmpz_mpoly_length(g[j].coef, r->ctx) > 1) {
                /* -2*(1 - t)*(1 + t) would put a minus in front of the
                 * knots: 2*t^2 - 2 (the text's t^2 - 1 + ...) */
                book_sum_free(cs, c);
                cs = book_form_expanded(g[j].coef, c);
            }
            lead_positive(cs);
            for (slong i = 0; i < cs->n; i++)
                book_term_absorb(book_sum_push(s), &cs->t[i]);
            book_sum_free(cs, c);
            continue;
        }
        PTerm *t = book_sum_push(s);
        if (cs->n == 1) {
            book_term_absorb(t, &cs->t[0]);
            book_sum_free(cs, c);
        } else {
            lead_positive(cs);
            if (cs->t[0].neg) { /* every term negative */
                book_sum_neg(cs, c);
                t->neg ^= 1;
            }
            book_term_push(t, (Atom){AT_SUM, -1, cs, NULL, NULL, 1});
        }
        for (int i = 0; i < nx; i++)
            book_term_push(t, xs[i]);
    }
    fmpz_mpoly_clear(quo, r->ctx);
    pc_free(xs);
    for (slong j = 0; j < ng; j++) {
        pc_free(g[j].ex);
        fmpz_mpoly_clear(g[j].coef, r->ctx);
    }
    fmpz_clear(cf);
    pc_free(g);
    pc_free(ex);
    pc_free(e);
    pc_free(av);
    book_sum_finish(s, p, c);
    s->keep_order = 1;
    return s;
}

/* the length of s's text form (whatever the style): measured only when a
 * tie between two collected forms needs it */
static size_t text_len(const PSum *s, const Ctx *c)
{
    Ctx text = *c;
    text.latex = 0;
    return book_sum_text_len(s, &text);
}

/* keeps the better of *best and cand: fewer leaves; then factored before
 * expanded before collected; among collected forms the shorter text, then
 * Bernstein before powers; then the earlier candidate.  Lengths are those
 * of the text form whatever the style, so text and LaTeX agree (*best_len:
 * (size_t)-1 until measured). */
static void keep_better(PSum **best, int *best_rank, size_t *best_len,
                        PSum *cand, int rank, const Ctx *c)
{
    if (!cand)
        return;
    size_t len = (size_t)-1;
    if (*best) {
        slong lb = book_sum_leaves(*best), lc = book_sum_leaves(cand);
        int kb = *best_rank < 2 ? *best_rank : 2;
        int kc = rank < 2 ? rank : 2;
        int better = lc < lb || (lc == lb && kc < kb);
        if (lc == lb && kc == kb && kc == 2) {
            if (*best_len == (size_t)-1)
                *best_len = text_len(*best, c);
            len = text_len(cand, c);
            better = len < *best_len || (len == *best_len && rank < *best_rank);
        }
        if (!better) {
            book_sum_free(cand, c);
            return;
        }
        book_sum_free(*best, c);
    }
    *best = cand;
    *best_rank = rank;
    *best_len = len;
}

static PSum *render_new(const fmpz_mpoly_t p, int depth, const Ctx *c);

enum { MEMO_MAX = 1024 };

/* A partial factoring without FLINT's (deep inside a form, where full
 * factoring would cost more than it shows): the integer content, the
 * monomial content, powers of 1 - x of params and consts, and a perfect
 * square.  NULL when none of these is there. */
static PSum *form_factored_cheap(const fmpz_mpoly_t p, int depth, const Ctx *c)
{
    const Ring *r = c->r;
    slong nv = r->nvars;
    fmpz_mpoly_t q, m, bar, quo;
    fmpz_mpoly_init(q, r->ctx);
    fmpz_mpoly_init(m, r->ctx);
    fmpz_mpoly_init(bar, r->ctx);
    fmpz_mpoly_init(quo, r->ctx);
    PSum *s = book_sum_new(c);
    PTerm *t = book_sum_push(s);
    int found = 0;
    /* integer content, with the sign of the first (ascending) term */
    _fmpz_vec_content(t->coeff, p->coeffs, fmpz_mpoly_length(p, r->ctx));
    fmpz_mpoly_scalar_divexact_fmpz(q, p, t->coeff, r->ctx);
    found |= !fmpz_is_one(t->coeff);
    /* the monomial content */
    ulong *lo = pc_xmalloc(sizeof(ulong) * (size_t)(nv ? nv : 1));
    ulong *e = pc_xmalloc(sizeof(ulong) * (size_t)(nv ? nv : 1));
    for (slong k = 0; k < fmpz_mpoly_length(q, r->ctx); k++) {
        fmpz_mpoly_get_term_exp_ui(e, q, k, r->ctx);
        for (slong v = 0; v < nv; v++)
            lo[v] = k == 0 || e[v] < lo[v] ? e[v] : lo[v];
    }
    for (slong v = 0; v < nv; v++)
        if (lo[v]) {
            fmpz_mpoly_gen(m, v, r->ctx);
            fmpz_mpoly_pow_ui(m, m, lo[v], r->ctx);
            fmpz_mpoly_divides(q, q, m, r->ctx);
            book_term_push(t, (Atom){AT_VAR, v, NULL, NULL, NULL, lo[v]});
            found = 1;
        }
    /* (1 - x)^k */
    for (slong v = 0; v < c->nparams + c->nconsts && v < nv; v++) {
        ulong k = 0;
        fmpz_mpoly_gen(bar, v, r->ctx);
        fmpz_mpoly_neg(bar, bar, r->ctx);
        fmpz_mpoly_add_si(bar, bar, 1, r->ctx);
        while (fmpz_mpoly_degree_si(q, v, r->ctx) > 0 &&
               fmpz_mpoly_length(q, r->ctx) > 1 &&
               polyfactor_vanishes_at_ones(q, r) &&
               fmpz_mpoly_divides(quo, q, bar, r->ctx)) {
            fmpz_mpoly_swap(q, quo, r->ctx);
            k++;
        }
        if (k) {
            book_term_push(t, (Atom){AT_BAR, v, NULL, NULL, NULL, k});
            found = 1;
        }
    }
    pc_free(lo);
    pc_free(e);
    if (fmpz_mpoly_is_fmpz(q, r->ctx)) {
        /* what is left is a unit: its sign */
        if (fmpz_sgn(q->coeffs) < 0)
            t->neg ^= 1;
    } else if (fmpz_mpoly_length(q, r->ctx) > 1 &&
               fmpz_mpoly_sqrt(m, q, r->ctx)) {
        push_factor(t, m, 2, depth + 1, c);
        found = 1;
    } else if (found) {
        push_factor(t, q, 1, depth + 1, c);
    }
    fmpz_mpoly_clear(q, r->ctx);
    fmpz_mpoly_clear(m, r->ctx);
    fmpz_mpoly_clear(bar, r->ctx);
    fmpz_mpoly_clear(quo, r->ctx);
    if (!found) {
        book_sum_free(s, c);
        return NULL;
    }
    book_sum_finish(s, p, c);
    return s;
}

/* p in its best form (see book.h), remembered per output */
static PSum *render_memo(const fmpz_mpoly_t p, int depth, const Ctx *c);

/* the atoms of s (and of its sums) that are vars marked in is_abs become
 * |x| */
static void mark_abs(PSum *s, const unsigned char *is_abs, const Ctx *c)
{
    for (slong i = 0; i < s->n; i++) {
        int any = 0;
        for (slong j = 0; j < s->t[i].n; j++) {
            Atom *a = &s->t[i].a[j];
            if (a->kind == AT_VAR && is_abs[a->var]) {
                a->kind = AT_ABS;
                any = 1;
            } else if (a->kind == AT_SUM) {
                mark_abs(a->sum, is_abs, c);
            }
        }
        if (any) /* |x| goes last in its product (book_model.c) */
            book_term_sort(&s->t[i], c);
    }
}

/* p in its best form; a p with x*sign(x) in it is written through |x|
 * (absform.h) */
PSum *book_render(const fmpz_mpoly_t p, int depth, const Ctx *c)
{
    if (!c->has_sign || c->is_abs)
        return render_memo(p, depth, c);
    const Ring *r = c->r;
    unsigned char *mask = pc_xcalloc((size_t)(r->nvars ? r->nvars : 1), 1);
    fmpz_mpoly_t q;
    fmpz_mpoly_init(q, r->ctx);
    PSum *s;
    if (absform_rewrite_num(q, mask, p, c->K, r) > 0) {
        Ctx a = *c;
        a.is_abs = mask;
        a.mode = 1;
        for (slong v = 0; v < r->nvars; v++)
            a.mode = a.mode * 31 + mask[v];
        a.mode |= 1;
        s = render_memo(q, depth, &a);
        mark_abs(s, mask, c);
    } else {
        s = render_memo(p, depth, c);
    }
    fmpz_mpoly_clear(q, r->ctx);
    pc_free(mask);
    return s;
}

static PSum *render_memo(const fmpz_mpoly_t p, int depth, const Ctx *c)
{
    Memo *m = c->memo;
    slong len = fmpz_mpoly_length(p, c->r->ctx);
    if (len < 2 || !m)
        return render_new(p, depth, c);
    for (slong i = 0; i < m->n; i++)
        if (m->e[i].depth == depth && m->e[i].mode == c->mode &&
            fmpz_mpoly_length(m->e[i].poly, c->r->ctx) == len &&
            fmpz_mpoly_equal(m->e[i].poly, p, c->r->ctx))
            return book_sum_copy(m->e[i].sum, c);
    PSum *s = render_new(p, depth, c);
    if (m->n < MEMO_MAX) {
        if (m->n == m->alloc) {
            m->alloc = m->alloc ? 2 * m->alloc : 32;
            m->e = pc_xrealloc(m->e, sizeof(MemoEntry) * (size_t)m->alloc);
        }
        MemoEntry *e = &m->e[m->n++];
        fmpz_mpoly_init(e->poly, c->r->ctx);
        fmpz_mpoly_set(e->poly, p, c->r->ctx);
        e->depth = depth;
        e->mode = c->mode;
        e->sum = book_sum_copy(s, c);
    }
    return s;
}

static PSum *render_new(const fmpz_mpoly_t p, int depth, const Ctx *c)
{
    enum { R_FACTORED, R_EXPANDED, R_BERNSTEIN, R_POWERS };
    const Ring *r = c->r;
    slong len = fmpz_mpoly_length(p, r->ctx);
    if (c->is_abs) { /* |x| in it: by the knots, as the text writes it */
        PSum *k = form_knots(p, depth, c);
        if (k) {
            *c->work += len;
            return k;
        }
    }
    PSum *best = book_form_expanded(p, c);
    if (len == 0 || fmpz_mpoly_is_fmpz(p, r->ctx))
        return best;
    int rank = R_EXPANDED;
    size_t blen = (size_t)-1;
    *c->work += len;
    if (len < 2)
        return best; /* a monomial: expanded is factored */
    if (depth < CHEAP_FACTOR_DEPTH &&
        (depth == 0 ||
         (*c->work < RENDER_WORK && len <= MAX_FACTOR_TERMS_NESTED))) {
        *c->work += FACTOR_WORK + 20 * len;
        keep_better(&best, &rank, &blen, form_factored(p, depth, c), R_FACTORED,
                    c);
    } else if (depth >= CHEAP_FACTOR_DEPTH) {
        *c->work += 4 * len;
        keep_better(&best, &rank, &blen, form_factored_cheap(p, depth, c),
                    R_FACTORED, c);
    }
    if (depth >= MAX_DEPTH || len > MAX_COLLECT_TERMS || len < 2)
        return best;
    for (slong v = 0; v < r->nvars && *c->work < RENDER_WORK; v++) {
        if (fmpz_mpoly_degree_si(p, v, r->ctx) < 1)
            continue;
        *c->work += 2 * len;
        if (book_is_param(c, v))
            keep_better(&best, &rank, &blen, form_bernstein(p, v, depth, c),
                        R_BERNSTEIN, c);
        slong w = c->K ? book_cos_companion(v, c) : -1;
        if (w >= 0)
            keep_better(&best, &rank, &blen, form_sin2(p, v, w, depth, c),
                        R_BERNSTEIN, c);
        keep_better(&best, &rank, &blen, form_powers(p, v, depth, c), R_POWERS,
                    c);
    }
    return best;
}
