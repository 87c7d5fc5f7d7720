/*
 * book_unroot.c - roots where the user put them.  The normal form
 * rationalises denominators; the candidates made here undo it, exact
 * rewritings of n numerators over one denominator (Cand) with the root
 * back in the denominator, which book_eq.c prints instead when their text
 * is shorter.  The rule, and the multipliers tried, are in the comment
 * below.  In the printer: between the derived equation and book_eq.c's
 * choice of the form to write.
 */
#include "compiler/print/book_int.h"

#include <stdlib.h>

#include <flint/fmpz_mpoly_factor.h>
#include <flint/fmpz_vec.h>

#include "base/mem.h"
#include "compiler/algebra/polyfactor.h"
#include "compiler/algebra/ring.h"

/* ---- roots where the user put them ----------------------------------------
 */

/* The normal form rationalises: b*cos(phi)/sqrt(X) is kept as
 * b*cos(phi)*sqrt(X)/X, and 1/(a - c*cos(phi)) (c a root) as
 * (a + c*cos(phi))/(a^2 - c^2*cos(phi)^2) reduced.  The printer undoes it
 * where that is shorter: for a root kernel s (s^2 = X) and a multiplier
 * Lb = P - Q*s (the conjugate of L = P + Q*s),
 *     N/D = reduce(N*Lb)/(D*Lb),
 * and G = reduce(L*Lb) = P^2 - Q^2*X (free of s) cancels when it divides D
 * and every reduce(N*Lb): the weight becomes M/(D1*Lb), D = G*D1.  The
 * multipliers tried: s itself (P = 0: N*s/X -> N/s), and the conjugates of
 * the numerators' factors of degree 1 in s.  Every candidate is exactly
 * equal (the relations are identities); the shortest text wins. */

/* p modulo the kernels' relations v^q = rel, for polynomial rels; 0 when
 * a relation with a denominator would be needed (p then unusable) */
static int reduce_rel(fmpz_mpoly_t p, const Ctx *c)
{
    const Ring *r = c->r;
    const Kernels *K = c->K;
    if (!K)
        return 1;
    int ok = 1;
    fmpz_mpoly_t res, cj, rp, m;
    fmpz_mpoly_init(res, r->ctx);
    fmpz_mpoly_init(cj, r->ctx);
    fmpz_mpoly_init(rp, r->ctx);
    fmpz_mpoly_init(m, r->ctx);
    /* later kernels first: a relation uses only earlier variables */
    for (slong i = K->n - 1; i >= 0 && ok; i--) {
        const Kernel *k = &K->k[i];
        slong v = k->var, q = k->deg;
        if (q < 2 || fmpz_mpoly_degree_si(p, v, r->ctx) < q)
            continue;
        if (!fmpz_mpoly_is_one(k->rel->den, r->ctx)) {
            ok = 0;
            break;
        }
        slong n = fmpz_mpoly_degree_si(p, v, r->ctx);
        fmpz_mpoly_zero(res, r->ctx);
        for (slong j = 0; j <= n; j++) {
            ulong e = (ulong)j;
            fmpz_mpoly_get_coeff_vars_ui(cj, p, &v, &e, 1, r->ctx);
            if (fmpz_mpoly_is_zero(cj, r->ctx))
                continue;
            /* v^j = v^(j mod q) * rel^(j div q) */
            fmpz_mpoly_pow_ui(rp, k->rel->num, (ulong)(j / q), r->ctx);
            fmpz_mpoly_gen(m, v, r->ctx);
            fmpz_mpoly_pow_ui(m, m, (ulong)(j % q), r->ctx);
            fmpz_mpoly_mul(rp, rp, m, r->ctx);
            fmpz_mpoly_mul(rp, rp, cj, r->ctx);
            fmpz_mpoly_add(res, res, rp, r->ctx);
            if (fmpz_mpoly_length(res, r->ctx) > 4096)
                ok = 0;
        }
        fmpz_mpoly_swap(p, res, r->ctx);
    }
    fmpz_mpoly_clear(m, r->ctx);
    fmpz_mpoly_clear(rp, r->ctx);
    fmpz_mpoly_clear(cj, r->ctx);
    fmpz_mpoly_clear(res, r->ctx);
    return ok;
}

/* res = L with s replaced by -s */
static void conj_root(fmpz_mpoly_t res, const fmpz_mpoly_t L, slong s,
                      const Ctx *c)
{
    const Ring *r = c->r;
    ulong *e = pc_xmalloc(sizeof(ulong) * (size_t)(r->nvars ? r->nvars : 1));
    fmpz_t k;
    fmpz_init(k);
    fmpz_mpoly_zero(res, r->ctx);
    for (slong i = 0; i < fmpz_mpoly_length(L, r->ctx); i++) {
        fmpz_mpoly_get_term_exp_ui(e, L, i, r->ctx);
        fmpz_mpoly_get_term_coeff_fmpz(k, L, i, r->ctx);
        if (e[s] & 1)
            fmpz_neg(k, k);
        fmpz_mpoly_push_term_fmpz_ui(res, k, e, r->ctx);
    }
    fmpz_mpoly_sort_terms(res, r->ctx);
    fmpz_mpoly_combine_like_terms(res, r->ctx);
    fmpz_clear(k);
    pc_free(e);
}

static void cand_init(Cand *x, slong n, const Ctx *c)
{
    x->n = n;
    x->num = pc_xmalloc(sizeof(fmpz_mpoly_struct) * (size_t)(n ? n : 1));
    for (slong i = 0; i < n; i++)
        fmpz_mpoly_init(x->num + i, c->r->ctx);
    fmpz_mpoly_init(x->den, c->r->ctx);
}

void book_cand_clear(Cand *x, const Ctx *c)
{
    for (slong i = 0; i < x->n; i++)
        fmpz_mpoly_clear(x->num + i, c->r->ctx);
    pc_free(x->num);
    fmpz_mpoly_clear(x->den, c->r->ctx);
}

/* N/D with the multiplier lb of root kernel s (above): 1 and *out when G
 * cancels */
static int unroot_with(Cand *out, const fmpz_mpoly_struct *const *N, slong n,
                       const fmpz_mpoly_t D, const fmpz_mpoly_t lb, slong s,
                       const Ctx *c)
{
    const Ring *r = c->r;
    fmpz_mpoly_t L, G, q;
    fmpz_mpoly_init(L, r->ctx);
    fmpz_mpoly_init(G, r->ctx);
    fmpz_mpoly_init(q, r->ctx);
    conj_root(L, lb, s, c);
    fmpz_mpoly_mul(G, L, lb, r->ctx);
    int ok = reduce_rel(G, c) && !fmpz_mpoly_is_fmpz(G, r->ctx) &&
             fmpz_mpoly_degree_si(G, s, r->ctx) == 0;
    if (ok) {
        fmpz_t g;
        fmpz_init(g);
        _fmpz_vec_content(g, G->coeffs, fmpz_mpoly_length(G, r->ctx));
        fmpz_mpoly_scalar_divexact_fmpz(G, G, g, r->ctx);
        fmpz_clear(g);
        cand_init(out, n, c);
        ok = fmpz_mpoly_divides(q, D, G, r->ctx);
        if (ok)
            fmpz_mpoly_mul(out->den, q, lb, r->ctx);
        for (slong i = 0; i < n && ok; i++) {
            fmpz_mpoly_mul(q, N[i], lb, r->ctx);
            ok = reduce_rel(q, c) &&
                 fmpz_mpoly_divides(out->num + i, q, G, r->ctx);
        }
        if (!ok)
            book_cand_clear(out, c);
    }
    fmpz_mpoly_clear(q, r->ctx);
    fmpz_mpoly_clear(G, r->ctx);
    fmpz_mpoly_clear(L, r->ctx);
    return ok;
}

enum { MAX_UNROOT = 6, MAX_UNROOT_TERMS = 200 };

/* the multipliers P -+ Q*s read off D (unroot_cands), tried; returns the
 * number of candidates put in cs (at most room) */
static slong den_cands(Cand *cs, slong room, const fmpz_mpoly_struct *const *N,
                       slong n, const fmpz_mpoly_t D, const Kernel *k,
                       const Ctx *c)
{
    const Ring *r = c->r;
    slong s = k->var, nc = 0;
    slong nv = r->nvars;
    fmpz_mpoly_t Dp, Q, T, P, lb, m;
    fmpz_mpoly_init(Dp, r->ctx);
    fmpz_mpoly_init(Q, r->ctx);
    fmpz_mpoly_init(T, r->ctx);
    fmpz_mpoly_init(P, r->ctx);
    fmpz_mpoly_init(lb, r->ctx);
    fmpz_mpoly_init(m, r->ctx);
    fmpz_t g;
    fmpz_init(g);
    _fmpz_vec_content(g, D->coeffs, fmpz_mpoly_length(D, r->ctx));
    fmpz_mpoly_scalar_divexact_fmpz(Dp, D, g, r->ctx);
    for (slong q = -1; q < nv && nc < room; q++) {
        if (q == s)
            continue;
        if (q >= 0) {
            int in_d = fmpz_mpoly_degree_si(D, q, r->ctx) > 0;
            slong cw = -1;
            for (slong v = 0; v < nv && cw < 0; v++)
                if (fmpz_mpoly_degree_si(D, v, r->ctx) > 0 &&
                    book_cos_companion(v, c) == q)
                    cw = q;
            if (!in_d && cw < 0)
                continue;
            fmpz_mpoly_gen(Q, q, r->ctx);
        } else {
            fmpz_mpoly_one(Q, r->ctx);
        }
        for (int sg = 0; sg < 2 && nc < room; sg++) {
            /* T = Q^2*X + D (D = Q^2*X - P^2 ... up to sign) */
            fmpz_mpoly_mul(T, Q, Q, r->ctx);
            fmpz_mpoly_mul(T, T, k->rel->num, r->ctx);
            if (sg)
                fmpz_mpoly_sub(T, T, Dp, r->ctx);
            else
                fmpz_mpoly_add(T, T, Dp, r->ctx);
            if (!reduce_rel(T, c) || fmpz_mpoly_is_zero(T, r->ctx) ||
                fmpz_mpoly_degree_si(T, s, r->ctx) > 0 ||
                !fmpz_mpoly_sqrt(P, T, r->ctx))
                continue;
            /* lb = P - Q*s, then P + Q*s */
            for (int pm = 0; pm < 2 && nc < room; pm++) {
                fmpz_mpoly_gen(m, s, r->ctx);
                fmpz_mpoly_mul(m, m, Q, r->ctx);
                if (pm)
                    fmpz_mpoly_add(lb, P, m, r->ctx);
                else
                    fmpz_mpoly_sub(lb, P, m, r->ctx);
                if (unroot_with(&cs[nc], N, n, D, lb, s, c))
                    nc++;
            }
        }
    }
    fmpz_clear(g);
    fmpz_mpoly_clear(m, r->ctx);
    fmpz_mpoly_clear(lb, r->ctx);
    fmpz_mpoly_clear(P, r->ctx);
    fmpz_mpoly_clear(T, r->ctx);
    fmpz_mpoly_clear(Q, r->ctx);
    fmpz_mpoly_clear(Dp, r->ctx);
    return nc;
}

/* the un-rationalised forms of N/D (at most MAX_UNROOT): returns their
 * number, *out malloc'd (book_cand_clear each, then free) */
slong book_unroot_cands(Cand **out, const fmpz_mpoly_struct *const *N, slong n,
                        const fmpz_mpoly_t D, const fmpz_mpoly_struct *const *H,
                        slong nh, const Ctx *c)
{
    const Ring *r = c->r;
    const Kernels *K = c->K;
    *out = NULL;
    if (!K || fmpz_mpoly_is_fmpz(D, r->ctx) || c->is_abs)
        return 0;
    slong len = fmpz_mpoly_length(D, r->ctx);
    for (slong i = 0; i < n; i++)
        len += fmpz_mpoly_length(N[i], r->ctx);
    if (len > MAX_UNROOT_TERMS)
        return 0;
    Cand *cs = pc_xmalloc(sizeof(Cand) * MAX_UNROOT);
    slong nc = 0;
    fmpz_mpoly_t lb;
    fmpz_mpoly_init(lb, r->ctx);
    for (slong ki = 0; ki < K->n && nc < MAX_UNROOT; ki++) {
        const Kernel *k = &K->k[ki];
        slong s = k->var;
        if (k->fn != KF_SQRT || k->deg != 2)
            continue;
        int used = 0;
        for (slong i = 0; i < n; i++)
            used |= fmpz_mpoly_degree_si(N[i], s, r->ctx) > 0;
        if (!used)
            continue;
        /* s itself */
        fmpz_mpoly_gen(lb, s, r->ctx);
        if (unroot_with(&cs[nc], N, n, D, lb, s, c))
            nc++;
        /* the conjugates of the numerators' factors linear in s (of N,
         * then of the hints: the other weights of the equation) */
        for (slong i = 0; i < n + nh && nc < MAX_UNROOT; i++) {
            const fmpz_mpoly_struct *x = i < n ? N[i] : H[i - n];
            if (fmpz_mpoly_degree_si(x, s, r->ctx) != 1 ||
                fmpz_mpoly_length(x, r->ctx) > MAX_UNROOT_TERMS ||
                !ring_factor_affordable(x, r))
                continue;
            fmpz_mpoly_factor_t f;
            fmpz_mpoly_factor_init(f, r->ctx);
            if (polyfactor_compact(f, x, r))
                for (slong j = 0; j < f->num && nc < MAX_UNROOT; j++) {
                    if (fmpz_mpoly_degree_si(f->poly + j, s, r->ctx) != 1 ||
                        fmpz_mpoly_length(f->poly + j, r->ctx) < 2)
                        continue;
                    conj_root(lb, f->poly + j, s, c);
                    if (unroot_with(&cs[nc], N, n, D, lb, s, c))
                        nc++;
                }
            fmpz_mpoly_factor_clear(f, r->ctx);
        }
        /* from the denominator: D = +-(P^2 - Q^2*X) up to its content,
         * for Q = 1 or a variable of D (or the cos of a sin of D): P the
         * square root of reduce(Q^2*X -+ D); 1/(a - c*cos(phi)) of a
         * focal conic, whose numerators need not show a - c*cos(phi) */
        if (fmpz_mpoly_is_one(k->rel->den, r->ctx) &&
            fmpz_mpoly_length(D, r->ctx) <= MAX_UNROOT_TERMS / 4)
            nc += den_cands(cs + nc, MAX_UNROOT - nc, N, n, D, k, c);
    }
    fmpz_mpoly_clear(lb, r->ctx);
    if (nc == 0) {
        pc_free(cs);
        return 0;
    }
    *out = cs;
    return nc;
}
