/*
 * book_factor.c - the factored forms of a polynomial (book.h): FLINT's
 * factoring where nothing cheaper settles it, and a cheap partial
 * factoring deep inside a form (book_form_factored_cheap).
 *
 * Factoring is most of the printing time: polyfactor.h's proofs of
 * irreducibility skip FLINT's factoring where they can (factor_known),
 * the factors met before in the scheme (its numerators and denominators
 * share them) are divided out first (factor_by_known), and the rest runs
 * in a ring of only the variables used.  In the printer: polynomials in,
 * models (book_model.c) out.
 */
#include "compiler/print/book_int.h"

#include <stdlib.h>
#include <string.h>

#include <flint/fmpz_mpoly_factor.h>
#include <flint/fmpz_vec.h>

#include "base/mem.h"
#include "compiler/algebra/polyfactor.h"
#include "compiler/algebra/ring.h"
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

/* p = g * x^lo * q: g its integer content with the sign of its leading
 * term, x^lo its monomial content (lo: one per variable of the ring) */
static void primitive_split(fmpz_mpoly_t q, fmpz_t g, ulong *lo,
                            const fmpz_mpoly_t p, const Ctx *c)
{
    const Ring *r = c->r;
    slong len = fmpz_mpoly_length(p, r->ctx), nv = r->ctx->minfo->nvars;
    _fmpz_vec_content(g, p->coeffs, len);
    if (fmpz_sgn(p->coeffs + 0) < 0)
        fmpz_neg(g, g);
    ulong *e = pc_xmalloc(sizeof(ulong) * (size_t)nv);
    for (slong k = 0; k < len; k++) {
        fmpz_mpoly_get_term_exp_ui(e, p, k, r->ctx);
        for (slong v = 0; v < nv; v++)
            lo[v] = k == 0 || e[v] < lo[v] ? e[v] : lo[v];
    }
    fmpz_t cq;
    fmpz_init(cq);
    fmpz_mpoly_zero(q, r->ctx);
    for (slong k = 0; k < len; k++) {
        fmpz_mpoly_get_term_exp_ui(e, p, k, r->ctx);
        for (slong v = 0; v < nv; v++)
            e[v] -= lo[v];
        fmpz_divexact(cq, p->coeffs + k, g);
        fmpz_mpoly_push_term_fmpz_ui(q, cq, e, r->ctx);
    }
    /* (the same order: dividing by a monomial keeps degrevlex's) */
    fmpz_clear(cq);
    pc_free(e);
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
    ulong *lo = pc_xmalloc(sizeof(ulong) * (size_t)nv);
    fmpz_mpoly_t q;
    fmpz_mpoly_init(q, r->ctx);
    primitive_split(q, g, lo, p, c);
    /* powers of x - 1, when FLINT factors fully */
    ulong *bars = pc_xcalloc((size_t)nv, sizeof(ulong));
    int nbars = 0;
    if (ring_factor_affordable(p, r)) {
        fmpz_mpoly_t bar, quo;
        fmpz_mpoly_init(bar, r->ctx);
        fmpz_mpoly_init(quo, r->ctx);
        int ones = polyfactor_vanishes_at_ones(q, r);
        for (slong v = 0; ones && v < c->nparams + c->nconsts && v < nv; v++) {
            if (fmpz_mpoly_degree_si(q, v, r->ctx) < 1)
                continue;
            fmpz_mpoly_gen(bar, v, r->ctx);
            fmpz_mpoly_sub_ui(bar, bar, 1, r->ctx);
            while (fmpz_mpoly_degree_si(q, v, r->ctx) > 0 &&
                   polyfactor_vanishes_at_ones(q, r) &&
                   fmpz_mpoly_divides(quo, q, bar, r->ctx)) {
                fmpz_mpoly_swap(q, quo, r->ctx);
                bars[v]++;
            }
            nbars += bars[v] > 0;
            if (bars[v] > 0)
                ones = polyfactor_vanishes_at_ones(q, r);
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
    fmpz_mpoly_clear(q, r->ctx);
    pc_free(lo);
    fmpz_clear(g);
    return ok;
}

/* remembers f's factors that are not monomials (f: p's full factoring) */
static void remember_factors(const fmpz_mpoly_factor_t f, const Ctx *c)
{
    enum { MAX_FACTORS = 256 };
    Memo *m = c->memo;
    const Ring *r = c->r;
    for (slong i = 0; i < f->num && m->nfac < MAX_FACTORS; i++) {
        const fmpz_mpoly_struct *h = f->poly + i;
        if (fmpz_mpoly_length(h, r->ctx) < 2)
            continue;
        slong j = 0;
        while (j < m->nfac && !fmpz_mpoly_equal(m->fac + j, h, r->ctx))
            j++;
        if (j < m->nfac)
            continue;
        if (m->nfac == m->facalloc) {
            m->facalloc = m->facalloc ? 2 * m->facalloc : 16;
            m->fac = pc_xrealloc(m->fac, sizeof(fmpz_mpoly_struct) *
                                             (size_t)m->facalloc);
        }
        fmpz_mpoly_init(m->fac + m->nfac, r->ctx);
        fmpz_mpoly_set(m->fac + m->nfac, h, r->ctx);
        m->nfac++;
    }
}

/* h's degrees within q's (h could divide q) */
static int degrees_within(const fmpz_mpoly_t h, const slong *dq, slong *dh,
                          const Ring *r)
{
    fmpz_mpoly_degrees_si(dh, h, r->ctx);
    for (slong v = 0; v < r->ctx->minfo->nvars; v++)
        if (dh[v] > dq[v])
            return 0;
    return 1;
}

/* q divided by the remembered factors as often as they divide it; their
 * powers to e (1: some factor divides q) */
static int divide_known(fmpz_mpoly_t q, ulong *e, const Ctx *c)
{
    const Ring *r = c->r;
    const Memo *m = c->memo;
    slong nv = r->ctx->minfo->nvars;
    slong *dq = pc_xmalloc(sizeof(slong) * (size_t)nv);
    slong *dh = pc_xmalloc(sizeof(slong) * (size_t)nv);
    fmpz_mpoly_t quo;
    fmpz_mpoly_init(quo, r->ctx);
    fmpz_mpoly_degrees_si(dq, q, r->ctx);
    int found = 0;
    for (slong j = 0; j < m->nfac; j++) {
        e[j] = 0;
        if (!degrees_within(m->fac + j, dq, dh, r))
            continue;
        while (fmpz_mpoly_length(q, r->ctx) > 1 &&
               fmpz_mpoly_divides(quo, q, m->fac + j, r->ctx)) {
            fmpz_mpoly_swap(q, quo, r->ctx);
            e[j]++;
            found = 1;
        }
        if (e[j])
            fmpz_mpoly_degrees_si(dq, q, r->ctx);
    }
    fmpz_mpoly_clear(quo, r->ctx);
    pc_free(dh);
    pc_free(dq);
    return found;
}

/* p's full factoring through the factors remembered from the polynomials
 * factored before (c->memo: a scheme's weights and denominators share
 * them): its content, its monomial content, the remembered factors that
 * divide it, and the rest factored (by factor_known or FLINT, its factors
 * remembered in turn).  The factoring into irreducibles is unique up to
 * units and order, and every factor here is primitive with a positive
 * leading coefficient as FLINT's are, so f has FLINT's factors, in
 * another order (which form_factored does not see: book_sum_finish sorts
 * a product's atoms).  Only where FLINT factors fully
 * (ring_factor_affordable).  0: no remembered factor divides p. */
static int factor_by_known(fmpz_mpoly_factor_t f, const fmpz_mpoly_t p,
                           const Ctx *c)
{
    const Ring *r = c->r;
    const Memo *m = c->memo;
    if (!m || m->nfac == 0 || !ring_factor_affordable(p, r))
        return 0;
    slong nv = r->ctx->minfo->nvars;
    fmpz_t g;
    fmpz_init(g);
    ulong *lo = pc_xmalloc(sizeof(ulong) * (size_t)nv);
    ulong *e = pc_xmalloc(sizeof(ulong) * (size_t)m->nfac);
    fmpz_mpoly_t q;
    fmpz_mpoly_init(q, r->ctx);
    primitive_split(q, g, lo, p, c);
    fmpz_mpoly_factor_t fq;
    fmpz_mpoly_factor_init(fq, r->ctx);
    int ok = divide_known(q, e, c);
    if (ok && !fmpz_mpoly_is_one(q, r->ctx))
        ok = ring_factor_affordable(q, r) &&
             (factor_known(fq, q, c) || polyfactor_compact(fq, q, r));
    if (ok) {
        fmpz_mpoly_factor_fit_length(f, nv + m->nfac + fq->num, r->ctx);
        fmpz_mul(f->constant, g, fq->constant);
        f->num = 0;
        for (slong v = 0; v < nv; v++)
            if (lo[v] > 0) {
                fmpz_mpoly_gen(f->poly + f->num, v, r->ctx);
                fmpz_set_ui(f->exp + f->num++, lo[v]);
            }
        for (slong j = 0; j < m->nfac; j++)
            if (e[j] > 0) {
                fmpz_mpoly_set(f->poly + f->num, m->fac + j, r->ctx);
                fmpz_set_ui(f->exp + f->num++, e[j]);
            }
        remember_factors(fq, c);
        for (slong i = 0; i < fq->num; i++) {
            fmpz_mpoly_swap(f->poly + f->num, fq->poly + i, r->ctx);
            fmpz_set(f->exp + f->num++, fq->exp + i);
        }
    }
    fmpz_mpoly_factor_clear(fq, r->ctx);
    fmpz_mpoly_clear(q, r->ctx);
    pc_free(e);
    pc_free(lo);
    fmpz_clear(g);
    return ok;
}

/* p's factoring as ring_factor makes it (ring_factor.h), up to the order
 * of the factors, with the irreducible factors of a full factoring
 * remembered in c->memo and divided out of later polynomials first
 * (those proved irreducible without FLINT too: the five-point conic's
 * coefficients are products of them) */
static int factor_shared(fmpz_mpoly_factor_t f, const fmpz_mpoly_t p,
                         const Ctx *c)
{
    if (factor_known(f, p, c)) {
        if (c->memo && ring_factor_affordable(p, c->r))
            remember_factors(f, c);
        return 1;
    }
    if (factor_by_known(f, p, c))
        return 1;
    if (!polyfactor_split_linear(f, p, c->r) && !polyfactor_compact(f, p, c->r))
        return 0;
    if (c->memo && ring_factor_affordable(p, c->r))
        remember_factors(f, c);
    return 1;
}

int book_factor(fmpz_mpoly_factor_t f, const fmpz_mpoly_t p, const Derived *d,
                BookMemo *m)
{
    Ctx c = {0};
    c.r = &d->ring;
    c.nparams = d->nparams;
    c.nconsts = d->nconsts;
    c.memo = m;
    return factor_shared(f, p, &c);
}

PSum *book_form_factored(const fmpz_mpoly_t p, int depth, const Ctx *c)
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
    if (!factor_shared(f, p, c)) {
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

/* A partial factoring without FLINT's (deep inside a form, where full
 * factoring would cost more than it shows): the integer content, the
 * monomial content, powers of 1 - x of params and consts, and a perfect
 * square.  NULL when none of these is there. */
PSum *book_form_factored_cheap(const fmpz_mpoly_t p, int depth, const Ctx *c)
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
    /* the integer content (positive) and the monomial content: q =
     * p/(content*monomial) */
    ulong *lo = pc_xmalloc(sizeof(ulong) * (size_t)(r->ctx->minfo->nvars + 1));
    primitive_split(q, t->coeff, lo, p, c);
    if (fmpz_sgn(t->coeff) < 0) {
        fmpz_neg(t->coeff, t->coeff);
        fmpz_mpoly_neg(q, q, r->ctx);
    }
    found |= !fmpz_is_one(t->coeff);
    for (slong v = 0; v < nv; v++)
        if (lo[v]) {
            book_term_push(t, (Atom){AT_VAR, v, NULL, NULL, NULL, lo[v]});
            found = 1;
        }
    /* (1 - x)^k (none unless q(1, ..., 1) = 0) */
    int ones = polyfactor_vanishes_at_ones(q, r);
    for (slong v = 0; ones && v < c->nparams + c->nconsts && v < nv; v++) {
        ulong k = 0;
        if (fmpz_mpoly_degree_si(q, v, r->ctx) < 1)
            continue;
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
            ones = polyfactor_vanishes_at_ones(q, r);
        }
    }
    pc_free(lo);
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
