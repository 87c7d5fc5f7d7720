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

#include <flint/fmpz_mpoly_factor.h>

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

void analyze_implicit(AnCurve *c, const AnPolys *p, const Derived *d)
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
        StrBuf s = {0}, j = {0};
        poly_print(&s, H, &hr, FMT_TEXT);
        poly_print(&j, H, &hr, FMT_JSON);
        c->implicit = sb_take(&s);
        c->implicit_j = sb_take(&j);
    }
    fmpz_mpoly_clear(H, hr.ctx);
    ring_clear(&hr);
    fmpz_mpoly_clear(F, ctx);
    fmpz_mpoly_clear(R, ctx);
    fmpz_mpoly_clear(b, ctx);
    fmpz_mpoly_clear(a, ctx);
    fmpz_mpoly_ctx_clear(ctx);
}
