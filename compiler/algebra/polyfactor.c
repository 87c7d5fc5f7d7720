/*
 * polyfactor.c - cheap factoring and irreducibility proofs for the
 * printer's factored forms (print/book_forms.c), out of the printer.
 *
 * FLINT's multivariate factoring is most of the printing time, and most
 * polynomials the printer looks at are irreducible.  What is here lets it
 * skip that work or make it smaller: factoring in a ring of only the
 * variables a polynomial uses (polyfactor_compact), and proofs of
 * irreducibility by a univariate image (polyfactor_surely_irreducible)
 * that settle most cases without factoring at all.  Every answer is exact: a
 * proof is a proof, and "no proof" only sends the caller to FLINT's factoring.
 */
#include "compiler/algebra/polyfactor.h"

#include <stdlib.h>
#include <string.h>

#include <flint/fmpq_vec.h>
#include <flint/fmpz_poly_factor.h>
#include <flint/fmpz_vec.h>
#include <flint/nmod_poly.h>

#include "base/mem.h"

/* B's terms with variable v renamed map[v] (each used variable mapped to a
 * distinct one of A's context): a cheap change of ring */
static void remap_vars(fmpz_mpoly_t A, const fmpz_mpoly_t B, const slong *map,
                       const fmpz_mpoly_ctx_t ctxB, const fmpz_mpoly_ctx_t ctxA)
{
    slong nb = ctxB->minfo->nvars, na = ctxA->minfo->nvars;
    ulong *eb = pc_xmalloc(sizeof(ulong) * (size_t)nb);
    ulong *ea = pc_xmalloc(sizeof(ulong) * (size_t)na);
    fmpz_t c;
    fmpz_init(c);
    fmpz_mpoly_zero(A, ctxA);
    for (slong k = 0; k < fmpz_mpoly_length(B, ctxB); k++) {
        fmpz_mpoly_get_term_exp_ui(eb, B, k, ctxB);
        fmpz_mpoly_get_term_coeff_fmpz(c, B, k, ctxB);
        memset(ea, 0, sizeof(ulong) * (size_t)na);
        for (slong v = 0; v < nb; v++)
            if (eb[v])
                ea[map[v]] = eb[v];
        fmpz_mpoly_push_term_fmpz_ui(A, c, ea, ctxA);
    }
    fmpz_mpoly_sort_terms(A, ctxA);
    fmpz_clear(c);
    pc_free(ea);
    pc_free(eb);
}

/* ring_factor(f, p) done in a ring of only the variables p uses: FLINT's
 * factoring walks every variable of its context, and a scheme's ring has
 * many (every function's slot) */
int polyfactor_compact(fmpz_mpoly_factor_t f, const fmpz_mpoly_t p,
                       const Ring *r)
{
    slong nv = r->ctx->minfo->nvars, used = 0;
    if (!fmpz_mpoly_degrees_fit_si(p, r->ctx))
        return 0;
    slong *deg = pc_xmalloc(sizeof(slong) * (size_t)nv);
    slong *to_small = pc_xmalloc(sizeof(slong) * (size_t)nv);
    slong *to_big = pc_xmalloc(sizeof(slong) * (size_t)nv);
    fmpz_mpoly_degrees_si(deg, p, r->ctx);
    for (slong v = 0; v < nv; v++) {
        to_small[v] = deg[v] > 0 ? used : -1;
        if (deg[v] > 0)
            to_big[used++] = v;
    }
    int ok;
    if (used == nv || used == 0) {
        ok = ring_factor(f, p, r);
    } else {
        Ring small;
        fmpz_mpoly_ctx_init(small.ctx, used, ORD_DEGREVLEX);
        small.nvars = used;
        small.names = NULL;
        small.latex = NULL;
        fmpz_mpoly_t q;
        fmpz_mpoly_init(q, small.ctx);
        remap_vars(q, p, to_small, r->ctx, small.ctx);
        fmpz_mpoly_factor_t g;
        fmpz_mpoly_factor_init(g, small.ctx);
        ok = ring_factor(g, q, &small);
        if (ok) {
            fmpz_mpoly_factor_fit_length(f, g->num, r->ctx);
            fmpz_set(f->constant, g->constant);
            for (slong i = 0; i < g->num; i++) {
                remap_vars(f->poly + i, g->poly + i, to_big, small.ctx, r->ctx);
                fmpz_set(f->exp + i, g->exp + i);
            }
            f->num = g->num;
        }
        fmpz_mpoly_factor_clear(g, small.ctx);
        fmpz_mpoly_clear(q, small.ctx);
        fmpz_mpoly_ctx_clear(small.ctx);
    }
    pc_free(deg);
    pc_free(to_small);
    pc_free(to_big);
    return ok;
}

/* the one variable p uses (-1: none or several); *lo its lowest power */
static slong one_var(const fmpz_mpoly_t p, ulong *lo, const Ring *r)
{
    slong nv = r->ctx->minfo->nvars, x = -1;
    for (slong v = 0; v < nv; v++)
        if (fmpz_mpoly_degree_si(p, v, r->ctx) > 0) {
            if (x >= 0)
                return -1;
            x = v;
        }
    if (x < 0)
        return -1;
    *lo = fmpz_mpoly_get_term_var_exp_ui(p, 0, x, r->ctx);
    for (slong k = 1; k < fmpz_mpoly_length(p, r->ctx); k++) {
        ulong e = fmpz_mpoly_get_term_var_exp_ui(p, k, x, r->ctx);
        *lo = e < *lo ? e : *lo;
    }
    return x;
}

int polyfactor_split_linear(fmpz_mpoly_factor_t f, const fmpz_mpoly_t p,
                            const Ring *r)
{
    /* a prime of 16 bits (a small one: finding the roots costs powers of
     * x to about P): fractions of numerator and denominator up to 180 come
     * back from their residues (others are left to FLINT) */
    static const ulong P = 65521;
    slong len = fmpz_mpoly_length(p, r->ctx);
    ulong lo;
    slong x = one_var(p, &lo, r);
    if (x < 0 || len < 2 || !ring_factor_affordable(p, r))
        return 0;
    slong n = fmpz_mpoly_degree_si(p, x, r->ctx) - (slong)lo;
    if (n < 2)
        return 0;
    fmpz_t g, m;
    fmpz_init(g);
    fmpz_init_set_ui(m, P);
    _fmpz_vec_content(g, p->coeffs, len);
    if (fmpz_sgn(p->coeffs + 0) < 0) /* the sign of the leading term */
        fmpz_neg(g, g);
    fmpz_poly_t u, w, lin;
    fmpz_poly_init(u);
    fmpz_poly_init(w);
    fmpz_poly_init(lin);
    fmpz_t c;
    fmpz_init(c);
    for (slong k = 0; k < len; k++) { /* u = p/(g x^lo), in x */
        fmpz_divexact(c, p->coeffs + k, g);
        fmpz_poly_set_coeff_fmpz(
            u, (slong)(fmpz_mpoly_get_term_var_exp_ui(p, k, x, r->ctx) - lo),
            c);
    }
    nmod_poly_t um;
    nmod_poly_init(um, P);
    fmpz_poly_get_nmod_poly(um, u);
    ulong *root = pc_xmalloc(sizeof(ulong) * (size_t)n);
    fmpq *q = _fmpq_vec_init(n);
    int ok = nmod_poly_degree(um) == n &&
             nmod_poly_find_distinct_nonzero_roots(root, um);
    fmpz_poly_one(w);
    for (slong i = 0; ok && i < n; i++) { /* each root a fraction b/a */
        fmpz_set_ui(c, root[i]);
        ok = fmpq_reconstruct_fmpz(q + i, c, m);
        fmpz_poly_set_coeff_fmpz(lin, 1, fmpq_denref(q + i));
        fmpz_neg(c, fmpq_numref(q + i));
        fmpz_poly_set_coeff_fmpz(lin, 0, c);
        fmpz_poly_mul(w, w, lin);
    }
    ok = ok && fmpz_poly_equal(w, u); /* the proof: u = prod (a x - b) */
    if (ok) {
        fmpz_mpoly_factor_fit_length(f, n + 1, r->ctx);
        fmpz_swap(f->constant, g);
        f->num = 0;
        if (lo > 0) {
            fmpz_mpoly_gen(f->poly + f->num, x, r->ctx);
            fmpz_set_ui(f->exp + f->num++, lo);
        }
        for (slong i = 0; i < n; i++) {
            fmpz_mpoly_struct *h = f->poly + f->num;
            fmpz_mpoly_gen(h, x, r->ctx);
            fmpz_mpoly_scalar_mul_fmpz(h, h, fmpq_denref(q + i), r->ctx);
            fmpz_mpoly_sub_fmpz(h, h, fmpq_numref(q + i), r->ctx);
            fmpz_one(f->exp + f->num++);
        }
    }
    _fmpq_vec_clear(q, n);
    pc_free(root);
    nmod_poly_clear(um);
    fmpz_clear(c);
    fmpz_poly_clear(lin);
    fmpz_poly_clear(w);
    fmpz_poly_clear(u);
    fmpz_clear(m);
    fmpz_clear(g);
    return ok;
}

/* q(1, ..., 1) == 0: necessary for x - 1 to divide q (a cheap test
 * before fmpz_mpoly_divides) */
int polyfactor_vanishes_at_ones(const fmpz_mpoly_t q, const Ring *r)
{
    fmpz_t s;
    fmpz_init(s);
    for (slong k = 0; k < fmpz_mpoly_length(q, r->ctx); k++)
        fmpz_add(s, s, q->coeffs + k);
    int z = fmpz_is_zero(s);
    fmpz_clear(s);
    return z;
}

/* u = c2 x^2 + c1 x + c0 (c2 != 0) is irreducible over Q: exactly when
 * its discriminant is not a square (what fmpz_poly_factor would say,
 * content aside, for much less) */
int polyfactor_quadratic_irreducible(const fmpz_poly_t u)
{
    fmpz_t d, t;
    fmpz_init(d);
    fmpz_init(t);
    fmpz_mul(d, u->coeffs + 1, u->coeffs + 1);
    fmpz_mul(t, u->coeffs + 0, u->coeffs + 2);
    fmpz_submul_ui(d, t, 4);
    int irr = !fmpz_is_square(d);
    fmpz_clear(t);
    fmpz_clear(d);
    return irr;
}

/* a proof that u (primitive, of degree n >= 1) is irreducible over Q:
 * irreducible modulo a small prime not dividing its leading coefficient
 * (a factorisation over Z would reduce to one of the same degrees).  A
 * root modulo the prime (looked for first, by evaluation: the cheap
 * refutation, as a reducible u has linear factors most often) rules the
 * prime out; of degree <= 3, no root is irreducibility.
 * 0: no proof (u may still be irreducible, or not). */
int polyfactor_irreducible_mod_small_prime(const fmpz_poly_t u)
{
    enum { MAX_DEG = 32 };
    static const ulong primes[] = {3, 5, 7, 11, 13};
    slong n = fmpz_poly_degree(u);
    if (n < 1 || n > MAX_DEG)
        return 0;
    ulong cm[MAX_DEG + 1];
    int irr = 0;
    for (size_t i = 0; i < sizeof primes / sizeof primes[0] && !irr; i++) {
        ulong q = primes[i];
        if (fmpz_fdiv_ui(u->coeffs + n, q) == 0)
            continue;
        for (slong k = 0; k <= n; k++)
            cm[k] = fmpz_fdiv_ui(u->coeffs + k, q);
        int root = 0;
        for (ulong z = 0; z < q && !root; z++) {
            ulong y = 0;
            for (slong k = n; k >= 0; k--)
                y = (y * z + cm[k]) % q;
            root = y == 0;
        }
        if (root)
            continue;
        if (n <= 3) {
            irr = 1;
            break;
        }
        nmod_poly_t m;
        nmod_poly_init(m, q);
        fmpz_poly_get_nmod_poly(m, u);
        irr = nmod_poly_is_irreducible(m);
        nmod_poly_clear(m);
    }
    return irr;
}

/* p = a*x + b (of degree 1 in x): its content in x is gcd(a, b); 1 when
 * that gcd is a constant (0 also when FLINT's gcd fails) */
static int linear_content_one(const fmpz_mpoly_t p, slong x, const Ring *r)
{
    fmpz_mpoly_t a, b, h;
    fmpz_mpoly_init(a, r->ctx);
    fmpz_mpoly_init(b, r->ctx);
    fmpz_mpoly_init(h, r->ctx);
    ulong one = 1, zero = 0;
    fmpz_mpoly_get_coeff_vars_ui(a, p, &x, &one, 1, r->ctx);
    fmpz_mpoly_get_coeff_vars_ui(b, p, &x, &zero, 1, r->ctx);
    int single =
        fmpz_mpoly_gcd(h, a, b, r->ctx) && fmpz_mpoly_is_fmpz(h, r->ctx);
    fmpz_mpoly_clear(h, r->ctx);
    fmpz_mpoly_clear(b, r->ctx);
    fmpz_mpoly_clear(a, r->ctx);
    return single;
}

/* u = the image of p (its terms' exponents in e, nv a row) at its
 * variables other than x = small integers, distinct per variable and per
 * attempt a: v -> +-(2 + v + nv*a) */
static void image_in_x(fmpz_poly_t u, const fmpz_mpoly_t p, const ulong *e,
                       slong len, slong nv, slong x, int a)
{
    fmpz_t t, val, cur;
    fmpz_init(t);
    fmpz_init(val);
    fmpz_init(cur);
    fmpz_poly_zero(u);
    for (slong k = 0; k < len; k++) {
        fmpz_set(t, p->coeffs + k);
        for (slong v = 0; v < nv; v++) {
            ulong ev = e[k * nv + v];
            if (v == x || ev == 0)
                continue;
            slong w = 2 + v + (slong)nv * a;
            fmpz_set_si(val, (v + a) & 1 ? -w : w);
            fmpz_pow_ui(val, val, ev);
            fmpz_mul(t, t, val);
        }
        fmpz_poly_get_coeff_fmpz(cur, u, (slong)e[k * nv + x]);
        fmpz_add(cur, cur, t);
        fmpz_poly_set_coeff_fmpz(u, (slong)e[k * nv + x], cur);
    }
    fmpz_clear(cur);
    fmpz_clear(val);
    fmpz_clear(t);
}

/* the sums of the degrees of u's irreducible factors modulo its prime
 * (u squarefree; destroyed): bit d set for each d that some product of
 * them has.  A distinct-degree factorisation: gcd(x^(q^d) - x, u) is the
 * product of the factors of degree d. */
static ulong degree_sums(nmod_poly_t u)
{
    nmod_poly_t x, h, g;
    nmod_poly_init_mod(x, u->mod);
    nmod_poly_init_mod(h, u->mod);
    nmod_poly_init_mod(g, u->mod);
    nmod_poly_set_coeff_ui(x, 1, 1);
    nmod_poly_set(h, x);
    ulong bits = 1;
    for (slong d = 1; 2 * d <= nmod_poly_degree(u); d++) {
        nmod_poly_powmod_ui_binexp(h, h, u->mod.n, u);
        nmod_poly_sub(g, h, x);
        nmod_poly_gcd(g, g, u);
        for (slong m = nmod_poly_degree(g) / d; m > 0; m--)
            bits |= bits << d;
        if (nmod_poly_degree(g) > 0) {
            nmod_poly_div(u, u, g);
            nmod_poly_rem(h, h, u);
        }
    }
    if (nmod_poly_degree(u) > 0) /* what is left: one irreducible factor */
        bits |= bits << nmod_poly_degree(u);
    nmod_poly_clear(g);
    nmod_poly_clear(h);
    nmod_poly_clear(x);
    return bits;
}

/* The degrees a factor of p could have, seen modulo a prime q on the line
 * x = a + b*s (a, b: small integers per variable, per attempt k): u(s) =
 * p(a + b*s) mod q, of degree D (p's total degree).  A factorisation p =
 * g*h maps to u = g(a + b*s)*h(a + b*s), of degrees at most deg g + deg h
 * = D, so exactly those, each a sum of the degrees of u's factors mod q:
 * returns the bits of those sums (bit d: degree d possible), or 0 (no
 * information) when the degree drops or u is not squarefree mod q.  e:
 * p's exponents (nv a row). */
static ulong line_degrees(const fmpz_mpoly_t p, const ulong *e, slong len,
                          slong nv, slong D, int k)
{
    enum { MAX_DEG = 16 };
    static const ulong primes[] = {101, 103, 107, 109, 113, 127};
    ulong q = primes[k % 6], u[MAX_DEG + 1] = {0}, t[MAX_DEG + 1];
    for (slong i = 0; i < len; i++) { /* small numbers: plain arithmetic */
        slong n = 0;
        t[0] = fmpz_fdiv_ui(p->coeffs + i, q);
        for (slong v = 0; v < nv; v++) {
            ulong a = (ulong)(5 + 17 * v + 31 * k) % q;
            ulong b = (ulong)(1 + (3 * v + 7 * k) % 11);
            for (ulong r = 0; r < e[i * nv + v]; r++, n++) { /* t *= a + b s */
                t[n + 1] = t[n] * b % q;
                for (slong j = n; j > 0; j--)
                    t[j] = (t[j] * a + t[j - 1] * b) % q;
                t[0] = t[0] * a % q;
            }
        }
        for (slong j = 0; j <= n; j++)
            u[j] = (u[j] + t[j]) % q;
    }
    if (D > MAX_DEG || u[D] == 0) /* the degree dropped */
        return 0;
    nmod_poly_t x, w, g;
    nmod_poly_init(x, q);
    nmod_poly_init(w, q);
    nmod_poly_init(g, q);
    for (slong j = 0; j <= D; j++)
        nmod_poly_set_coeff_ui(x, j, u[j]);
    ulong bits = 0;
    nmod_poly_derivative(w, x);
    nmod_poly_gcd(g, x, w);
    if (nmod_poly_degree(g) == 0) { /* squarefree */
        nmod_poly_make_monic(x, x);
        bits = degree_sums(x);
    }
    nmod_poly_clear(g);
    nmod_poly_clear(w);
    nmod_poly_clear(x);
    return bits;
}

/* p (integer content 1, no monomial factor; e, dv as above) proved
 * irreducible by its images on lines modulo primes: a factor's degree
 * must be possible in every image (line_degrees), and no degree from 1 to
 * D - 1 is.  Without a gcd: p's content in a variable would be a factor
 * too.  1: proved; -1: a degree stayed possible in every image (p is
 * most likely reducible: not worth more proofs); 0: not tried (p in one
 * variable, where a line is p itself shifted, or of a degree past 16). */
static int irreducible_on_lines(const fmpz_mpoly_t p, const ulong *e, slong len,
                                slong nv, const slong *dv)
{
    enum { LINES = 4, MAX_DEG = 16 };
    slong D = 0, used = 0;
    for (slong v = 0; v < nv; v++)
        used += dv[v] > 0;
    if (used < 2)
        return 0;
    for (slong i = 0; i < len; i++) {
        slong d = 0;
        for (slong v = 0; v < nv; v++)
            d += (slong)e[i * nv + v];
        D = d > D ? d : D;
    }
    if (D < 2 || D > MAX_DEG)
        return 0;
    ulong open = ((UWORD(1) << D) - 1) & ~UWORD(1); /* degrees 1 .. D - 1 */
    int seen = 0;
    for (int k = 0; k < LINES && open; k++) {
        ulong b = line_degrees(p, e, len, nv, D, k);
        seen += b != 0;
        if (b)
            open &= b;
    }
    return open == 0 ? 1 : seen >= 2 ? -1 : 0;
}

/* some coefficient of p in x (e: p's exponents, nv a row) is one term */
static int single_term_coeff(const ulong *e, slong len, slong nv, slong x)
{
    for (slong k = 0; k < len; k++) {
        slong n = 0;
        for (slong j = 0; j < len && n < 2; j++)
            n += e[j * nv + x] == e[k * nv + x];
        if (n == 1)
            return 1;
    }
    return 0;
}

/* A cheap proof that p (not linear) is irreducible and primitive, when
 * there is one: then factoring would give p itself and form_factored has
 * nothing to offer, so FLINT's factoring (most of the printing time) is
 * not needed.  The proof: p has integer content 1 and no monomial factor;
 * for some variable x one coefficient of a power of x is a single term, so
 * p's content in x is 1 (it would divide that term, hence every term), and
 * every factor of p involves x; then p is irreducible when its degree in x
 * is 1, or when an image p(x, others = integers) keeps that degree and is
 * irreducible over Q (a factorisation of p would map to one of the image).
 * Or, in two variables or more, by its images on lines modulo small primes
 * (irreducible_on_lines), which need no content: tried before the images
 * in one variable and the gcds, which are skipped when the lines rather
 * show p reducible.
 * 0: no proof found (p may still be irreducible). */
int polyfactor_surely_irreducible(const fmpz_mpoly_t p, const Ring *r)
{
    enum { MAX_IMAGES = 4 };
    slong len = fmpz_mpoly_length(p, r->ctx);
    slong nv = r->ctx->minfo->nvars;
    if (len < 2 || nv < 1 || !fmpz_mpoly_degrees_fit_si(p, r->ctx))
        return 0;
    int ok = 0, images = 0;
    fmpz_t g;
    fmpz_init(g);
    _fmpz_vec_content(g, p->coeffs, len);
    ulong *e = pc_xmalloc(sizeof(ulong) * (size_t)(len * nv));
    slong *deg = pc_xmalloc(sizeof(slong) * (size_t)nv);
    slong *cnt = NULL;
    fmpz_poly_t u;
    fmpz_poly_init(u);
    if (!fmpz_is_one(g))
        goto done;
    for (slong k = 0; k < len; k++)
        fmpz_mpoly_get_term_exp_ui(e + k * nv, p, k, r->ctx);
    for (slong v = 0; v < nv; v++) {
        ulong lo = e[v], hi = e[v];
        for (slong k = 1; k < len; k++) {
            ulong x = e[k * nv + v];
            lo = x < lo ? x : lo;
            hi = x > hi ? x : hi;
        }
        if (lo > 0)
            goto done; /* a monomial factor */
        deg[v] = (slong)hi;
    }
    /* first a variable of degree 1 with a coefficient of one term (a
     * proof without an image), then the images on lines (when they
     * rather show p reducible: no proof), then the variables with a
     * coefficient of one term, then (pass 1) those of degree 1 by a gcd */
    for (slong x = 0; x < nv && !ok; x++)
        ok = deg[x] == 1 && single_term_coeff(e, len, nv, x);
    int lines = ok ? 1 : irreducible_on_lines(p, e, len, nv, deg);
    ok = lines == 1;
    for (slong xx = 0; xx < 2 * nv && !ok && lines == 0 && images < MAX_IMAGES;
         xx++) {
        slong x = xx % nv, pass = xx / nv;
        if (deg[x] < 1 || (pass == 1 && deg[x] != 1))
            continue;
        /* a coefficient in x of one term: p's content in x is 1 */
        cnt = pc_xrealloc(cnt, sizeof(slong) * (size_t)(deg[x] + 1));
        memset(cnt, 0, sizeof(slong) * (size_t)(deg[x] + 1));
        for (slong k = 0; k < len; k++)
            cnt[e[k * nv + x]]++;
        int single = 0;
        for (slong i = 0; i <= deg[x]; i++)
            single |= cnt[i] == 1;
        if (single == (pass == 1))
            continue; /* pass 0: one term; pass 1: the others */
        if (!single && deg[x] == 1) {
            single = linear_content_one(p, x, r);
            images++; /* a gcd costs about as much as an image */
        }
        if (!single)
            continue;
        if (deg[x] == 1) {
            ok = 1;
            break;
        }
        /* p in x alone: its image is p itself, the same for every a, and
         * factoring it is what FLINT would do anyway (a reducible p, as
         * the Bernstein forms' often are, would pay twice): only cheap
         * proofs, by one image */
        int alone = 1;
        for (slong v = 0; v < nv; v++)
            alone &= v == x || deg[v] == 0;
        for (int a = 0; a < (alone ? 1 : 2) && !ok && images < MAX_IMAGES;
             a++) {
            image_in_x(u, p, e, len, nv, x, a);
            if (fmpz_poly_degree(u) != deg[x])
                continue;
            images++;
            if (deg[x] == 2) {
                ok = polyfactor_quadratic_irreducible(u);
            } else if (alone) {
                ok = polyfactor_irreducible_mod_small_prime(u);
            } else {
                fmpz_poly_factor_t uf;
                fmpz_poly_factor_init(uf);
                fmpz_poly_factor(uf, u);
                ok = uf->num == 1 && uf->exp[0] == 1;
                fmpz_poly_factor_clear(uf);
            }
        }
    }
done:
    fmpz_poly_clear(u);
    pc_free(cnt);
    pc_free(deg);
    pc_free(e);
    fmpz_clear(g);
    return ok;
}
