/*
 * implicit.c - the implicit equation of a plane rational curve over three
 * base points, in barycentric coordinates (x, y, z) of A_1, A_2, A_3.
 *
 * M = (n_1 A_1 + n_2 A_2 + n_3 A_3)/d is the point with coordinates
 * proportional to (n_1, n_2, n_3).  With x = 1 (no loss: n_1 is not zero,
 * and a curve of order >= 2 is not the line x = 0):
 *
 *     R(y, z) = Res_t(n_2(t) - y n_1(t), n_3(t) - z n_1(t)) = c F(1, y, z)^k
 *
 * k the index (times the parametrization traces the curve), F irreducible;
 * the square-free factorisation of R gives F(1, y, z), homogenised to the
 * order of the curve.  The degree of F is checked against that order
 * (analyze.h): a mismatch leaves no equation rather than a wrong one.
 */
#include "compiler/analyze/analyze.h"

#include <stdlib.h>

#include <flint/fmpq_mat.h>
#include <flint/fmpz_mpoly_factor.h>
#include <flint/fmpz_vec.h>

#include "base/mem.h"
#include "base/strbuf.h"
#include "compiler/algebra/poly_print.h"

/* a = n_j(t) - v n_1(t) in Z[t, y, z] (variable 0 is t) */
static void line_pencil(fmpz_mpoly_t a, const fmpz_poly_t nj,
                        const fmpz_poly_t n1, slong v,
                        const fmpz_mpoly_ctx_t ctx)
{
    fmpz_mpoly_t b, g;
    fmpz_mpoly_init(b, ctx);
    fmpz_mpoly_init(g, ctx);
    fmpz_mpoly_set_fmpz_poly(a, nj, 0, ctx);
    fmpz_mpoly_set_fmpz_poly(b, n1, 0, ctx);
    fmpz_mpoly_gen(g, v, ctx);
    fmpz_mpoly_mul(b, b, g, ctx);
    fmpz_mpoly_sub(a, a, b, ctx);
    fmpz_mpoly_clear(g, ctx);
    fmpz_mpoly_clear(b, ctx);
}

/* F(1, y, z) of R = c F^k: the one non-constant square-free factor */
static int the_factor(fmpz_mpoly_t F, const fmpz_mpoly_t R,
                      const fmpz_mpoly_ctx_t ctx)
{
    fmpz_mpoly_factor_t f;
    fmpz_mpoly_factor_init(f, ctx);
    int ok = fmpz_mpoly_factor_squarefree(f, R, ctx) && f->num == 1;
    if (ok)
        fmpz_mpoly_swap(F, f->poly + 0, ctx);
    fmpz_mpoly_factor_clear(f, ctx);
    return ok;
}

/* H(x, y, z) = x^m F(1, y/x, z/x) in the points' ring hr; 0 when F's
 * degree is not m */
static int homogenise(fmpz_mpoly_t H, const fmpz_mpoly_t F, slong m,
                      const fmpz_mpoly_ctx_t ctx, const Ring *hr)
{
    if (fmpz_mpoly_total_degree_si(F, ctx) != m)
        return 0;
    ulong in[3], out[3];
    fmpz_mpoly_zero(H, hr->ctx);
    for (slong i = 0; i < fmpz_mpoly_length(F, ctx); i++) {
        fmpz_mpoly_get_term_exp_ui(in, F, i, ctx);
        out[0] = (ulong)m - in[1] - in[2];
        out[1] = in[1];
        out[2] = in[2];
        fmpz_mpoly_push_term_fmpz_ui(H, F->coeffs + i, out, hr->ctx);
    }
    fmpz_mpoly_sort_terms(H, hr->ctx);
    fmpz_mpoly_combine_like_terms(H, hr->ctx);
    if (fmpz_sgn(H->coeffs + 0) < 0)
        fmpz_mpoly_neg(H, H, hr->ctx);
    return 1;
}

/* L[i] = the barycentric coordinate of point i as a polynomial in x, y,
 * over a common denominator (dropped: H is homogeneous), from the inverse
 * of [[x_1, x_2, x_3], [y_1, y_2, y_3], [1, 1, 1]] (its adjugate); 0 when
 * the three points are collinear */
static int bary_of_xy(fmpz_mpoly_struct *L, const fmpq *const P[3],
                      const Ring *xy)
{
    fmpq_mat_t m, inv;
    fmpq_mat_init(m, 3, 3);
    fmpq_mat_init(inv, 3, 3);
    for (int j = 0; j < 3; j++) {
        fmpq_set(fmpq_mat_entry(m, 0, j), P[j] + 0);
        fmpq_set(fmpq_mat_entry(m, 1, j), P[j] + 1);
        fmpq_one(fmpq_mat_entry(m, 2, j));
    }
    int ok = fmpq_mat_inv(inv, m);
    if (ok) {
        fmpz_t den, v;
        fmpz_init_set_ui(den, 1);
        fmpz_init(v);
        for (int i = 0; i < 3; i++)
            for (int k = 0; k < 3; k++)
                fmpz_lcm(den, den, fmpq_denref(fmpq_mat_entry(inv, i, k)));
        for (int i = 0; i < 3; i++) {
            fmpz_mpoly_zero(L + i, xy->ctx);
            for (int k = 0; k < 3; k++) { /* row i . (x, y, 1) */
                const fmpq *q = fmpq_mat_entry(inv, i, k);
                fmpz_divexact(v, den, fmpq_denref(q));
                fmpz_mul(v, v, fmpq_numref(q));
                fmpz_mpoly_t g;
                fmpz_mpoly_init(g, xy->ctx);
                if (k < 2)
                    fmpz_mpoly_gen(g, k, xy->ctx);
                else
                    fmpz_mpoly_one(g, xy->ctx);
                fmpz_mpoly_scalar_mul_fmpz(g, g, v, xy->ctx);
                fmpz_mpoly_add(L + i, L + i, g, xy->ctx);
                fmpz_mpoly_clear(g, xy->ctx);
            }
        }
        fmpz_clear(v);
        fmpz_clear(den);
    }
    fmpq_mat_clear(inv);
    fmpq_mat_clear(m);
    return ok;
}

/* c->implicit_xy: H(x, y, z) at the barycentric coordinates of the
 * Cartesian point (x, y), made primitive with a positive leading term */
static void implicit_xy(AnCurve *c, const fmpz_mpoly_t H, const Ring *hr,
                        const AnPolys *p, const AnSet *set)
{
    if (!set || !set->qpt || set->dim != 2)
        return;
    const fmpq *P[3];
    for (int j = 0; j < 3; j++)
        if (!(P[j] = set->qpt[p->pt[j]]))
            return;
    const char *names[2] = {"x", "y"};
    Ring xy;
    ring_init(&xy, 2, names);
    fmpz_mpoly_struct L[3];
    fmpz_mpoly_struct *Lp[3] = {L + 0, L + 1, L + 2};
    for (int i = 0; i < 3; i++)
        fmpz_mpoly_init(L + i, xy.ctx);
    fmpz_mpoly_t G;
    fmpz_mpoly_init(G, xy.ctx);
    if (bary_of_xy(L, P, &xy) &&
        fmpz_mpoly_compose_fmpz_mpoly(G, H, Lp, hr->ctx, xy.ctx) &&
        !fmpz_mpoly_is_zero(G, xy.ctx)) {
        fmpz_t g;
        fmpz_init(g);
        _fmpz_vec_content(g, G->coeffs, fmpz_mpoly_length(G, xy.ctx));
        if (fmpz_sgn(G->coeffs + 0) < 0)
            fmpz_neg(g, g);
        fmpz_mpoly_scalar_divexact_fmpz(G, G, g, xy.ctx);
        fmpz_clear(g);
        StrBuf s = {0}, j = {0}, t = {0};
        poly_print(&s, G, &xy, FMT_TEXT);
        poly_print(&j, G, &xy, FMT_JSON);
        poly_print(&t, G, &xy, FMT_LATEX);
        c->implicit_xy = sb_take(&s);
        c->implicit_xy_j = sb_take(&j);
        c->implicit_xy_tex = sb_take(&t);
    }
    fmpz_mpoly_clear(G, xy.ctx);
    for (int i = 0; i < 3; i++)
        fmpz_mpoly_clear(L + i, xy.ctx);
    ring_clear(&xy);
}

void analyze_implicit(AnCurve *c, const AnPolys *p, const Derived *d,
                      const AnSet *set)
{
    fmpz_mpoly_ctx_t ctx;
    fmpz_mpoly_ctx_init(ctx, 3, ORD_LEX);
    fmpz_mpoly_t a, b, R, F;
    fmpz_mpoly_init(a, ctx);
    fmpz_mpoly_init(b, ctx);
    fmpz_mpoly_init(R, ctx);
    fmpz_mpoly_init(F, ctx);
    line_pencil(a, p->n + 1, p->n + 0, 1, ctx);
    line_pencil(b, p->n + 2, p->n + 0, 2, ctx);
    const char *names[3] = {d->points[p->pt[0]], d->points[p->pt[1]],
                            d->points[p->pt[2]]};
    Ring hr;
    ring_init(&hr, 3, names);
    fmpz_mpoly_t H;
    fmpz_mpoly_init(H, hr.ctx);
    if (fmpz_mpoly_resultant(R, a, b, 0, ctx) && !fmpz_mpoly_is_zero(R, ctx) &&
        the_factor(F, R, ctx) && homogenise(H, F, c->order, ctx, &hr)) {
        StrBuf s = {0}, j = {0}, t = {0};
        poly_print(&s, H, &hr, FMT_TEXT);
        poly_print(&j, H, &hr, FMT_JSON);
        poly_print(&t, H, &hr, FMT_LATEX);
        c->implicit = sb_take(&s);
        c->implicit_j = sb_take(&j);
        c->implicit_tex = sb_take(&t);
        implicit_xy(c, H, &hr, p, set);
    }
    fmpz_mpoly_clear(H, hr.ctx);
    ring_clear(&hr);
    fmpz_mpoly_clear(F, ctx);
    fmpz_mpoly_clear(R, ctx);
    fmpz_mpoly_clear(b, ctx);
    fmpz_mpoly_clear(a, ctx);
    fmpz_mpoly_ctx_clear(ctx);
}
