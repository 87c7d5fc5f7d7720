/*
 * ends.c - the ends of a curve (analyze.h: AnEnd): the point, the first
 * derivative that is not zero and how many after it are parallel to it.
 *
 * At t = e the numerators and the denominator are shifted, n_i(e + h),
 * and divided as power series in h: M(e + h) = sum_j c_j h^j, with
 * c_j = M^(j)(e)/j!, so every derivative at the end comes from one
 * series division per base point.  2 degree + 3 terms suffice: a curve of
 * degree n that is no line meets the line of its tangent at most n times,
 * so at most n - 1 derivatives after the first can be parallel to it.
 * Without a declared range the end is t -> oo, the same with the
 * reversed polynomials h^n n_i(1/h).  A denominator that vanishes at the
 * end sends the curve to infinity, in the direction +-sum n_i(e) A_i (the
 * sign of the way it goes as t comes from inside the range).
 */
#include "compiler/analyze/analyze.h"

#include <stdlib.h>
#include <string.h>

#include <flint/fmpq_poly.h>

#include "base/mem.h"

static fmpq *vec_new(slong n)
{
    fmpq *v = pc_xmalloc((size_t)(n + 1) * sizeof *v);
    for (slong i = 0; i < n; i++)
        fmpq_init(v + i);
    return v;
}

static void vec_free(fmpq *v, slong n)
{
    if (!v)
        return;
    for (slong i = 0; i < n; i++)
        fmpq_clear(v + i);
    pc_free(v);
}

void analyze_end_clear(AnEnd *e, slong npoints)
{
    pc_free(e->t);
    vec_free(e->point, npoints);
    vec_free(e->tangent, npoints);
    pc_free(e->num);
    pc_free(e->num_tan);
    memset(e, 0, sizeof *e);
}

/* res = f(e + h) (e not NULL) or h^deg f(1/h) */
static void shifted(fmpq_poly_t res, const fmpz_poly_t f, const fmpq *e,
                    slong deg)
{
    if (!e) {
        fmpz_poly_t r;
        fmpz_poly_init(r);
        fmpz_poly_reverse(r, f, deg + 1);
        fmpq_poly_set_fmpz_poly(res, r);
        fmpz_poly_clear(r);
        return;
    }
    fmpq_poly_t g, lin;
    fmpq_poly_init(g);
    fmpq_poly_init(lin);
    fmpq_poly_set_fmpz_poly(g, f);
    fmpq_poly_set_coeff_fmpq(lin, 0, e);
    fmpq_poly_set_coeff_si(lin, 1, 1);
    fmpq_poly_compose(res, g, lin);
    fmpq_poly_clear(lin);
    fmpq_poly_clear(g);
}

/* the Taylor coefficients at the end: s[i] for term i, cap of them */
typedef struct Series {
    slong len, cap;
    fmpq_poly_struct *s;
} Series;

static int is_zero_at(const Series *S, slong j)
{
    fmpq_t c;
    fmpq_init(c);
    int z = 1;
    for (slong i = 0; i < S->len && z; i++) {
        fmpq_poly_get_coeff_fmpq(c, S->s + i, j);
        z = fmpq_is_zero(c);
    }
    fmpq_clear(c);
    return z;
}

/* coefficient j is a multiple of coefficient f (f not zero) */
static int parallel_at(const Series *S, slong j, slong f)
{
    fmpq_t a, b, x, y, u, v;
    fmpq_init(a);
    fmpq_init(b);
    fmpq_init(x);
    fmpq_init(y);
    fmpq_init(u);
    fmpq_init(v);
    slong k = 0; /* a term where coefficient f is not zero */
    for (; k < S->len; k++) {
        fmpq_poly_get_coeff_fmpq(a, S->s + k, f);
        if (!fmpq_is_zero(a))
            break;
    }
    fmpq_poly_get_coeff_fmpq(b, S->s + k, j);
    int par = 1; /* c_j = (b/a) c_f: c_j[i] a == c_f[i] b */
    for (slong i = 0; i < S->len && par; i++) {
        fmpq_poly_get_coeff_fmpq(x, S->s + i, j);
        fmpq_poly_get_coeff_fmpq(y, S->s + i, f);
        fmpq_mul(u, x, a);
        fmpq_mul(v, y, b);
        par = fmpq_equal(u, v);
    }
    fmpq_clear(v);
    fmpq_clear(u);
    fmpq_clear(y);
    fmpq_clear(x);
    fmpq_clear(b);
    fmpq_clear(a);
    return par;
}

/* v[pt_i] = coefficient j of term i times scale */
static fmpq *coeff_vec(const Series *S, const AnPolys *p, slong j,
                       const fmpz_t scale, slong npoints)
{
    fmpq *v = vec_new(npoints);
    for (slong i = 0; i < S->len; i++) {
        fmpq_poly_get_coeff_fmpq(v + p->pt[i], S->s + i, j);
        fmpq_mul_fmpz(v + p->pt[i], v + p->pt[i], scale);
    }
    return v;
}

/* the derivatives at a finite end point (den(e) != 0) */
static void end_series(AnEnd *end, const AnCurve *c, const Series *S,
                       const AnPolys *p, slong npoints)
{
    fmpz_t one;
    fmpz_init_set_ui(one, 1);
    end->point = coeff_vec(S, p, 0, one, npoints);
    if (c->kind == KIND_POINT) {
        slong f = 1;
        while (f < S->cap && is_zero_at(S, f))
            f++;
        if (f < S->cap) {
            fmpz_t fact;
            fmpz_init(fact);
            fmpz_fac_ui(fact, (ulong)f);
            end->first = f;
            end->vanishing = f - 1;
            end->tangent = coeff_vec(S, p, f, fact, npoints);
            slong j = f + 1;
            while (j < S->cap && parallel_at(S, j, f))
                j++;
            end->parallel = c->dim <= 1 ? -1 : j - 1;
            fmpz_clear(fact);
        }
    }
    fmpz_clear(one);
}

/* M ~ N(e)/(c_r h^r) near the end, den(e + h) = c_r h^r + ...: the sign
 * that makes N(e) point where M goes, h < 0 at the upper end (h > 0 at
 * the lower one, and at t -> oo, s = 1/t -> 0+) */
static int infinity_sign(const fmpq_poly_t den, int upper)
{
    slong r = 0;
    while (fmpz_is_zero(den->coeffs + r))
        r++;
    int sg = fmpz_sgn(den->coeffs + r);
    return upper && r % 2 ? -sg : sg;
}

static void end_at(AnEnd *end, const AnCurve *c, const AnPolys *p,
                   const fmpq *e, int upper, slong npoints)
{
    if (e) {
        char *s = fmpq_get_str(NULL, 10, e);
        end->t = pc_xstrdup(s);
        flint_free(s);
    } else
        end->t = pc_xstrdup("oo");
    Series S = {p->len, 2 * c->degree + 3, NULL};
    S.s = pc_xmalloc((size_t)(p->len + 1) * sizeof *S.s);
    fmpq_poly_t den;
    fmpq_poly_init(den);
    shifted(den, p->den, e, c->degree);
    for (slong i = 0; i < p->len; i++) {
        fmpq_poly_init(S.s + i);
        shifted(S.s + i, p->n + i, e, c->degree);
    }
    fmpq_t d0;
    fmpq_init(d0);
    fmpq_poly_get_coeff_fmpq(d0, den, 0);
    if (fmpq_is_zero(d0)) { /* at infinity: the direction sum n_i(e) A_i */
        fmpz_t sg;
        fmpz_init_set_si(sg, infinity_sign(den, upper));
        end->infinite = 1;
        end->point = coeff_vec(&S, p, 0, sg, npoints);
        fmpz_clear(sg);
    } else {
        for (slong i = 0; i < p->len; i++)
            fmpq_poly_div_series(S.s + i, S.s + i, den, S.cap);
        end_series(end, c, &S, p, npoints);
    }
    fmpq_clear(d0);
    for (slong i = 0; i < p->len; i++)
        fmpq_poly_clear(S.s + i);
    pc_free(S.s);
    fmpq_poly_clear(den);
}

void analyze_ends(AnCurve *c, const AnPolys *p, const fmpq *lo, const fmpq *hi,
                  slong npoints)
{
    if (lo) {
        end_at(c->ends + 0, c, p, lo, 0, npoints);
        end_at(c->ends + 1, c, p, hi, 1, npoints);
        c->nends = 2;
    } else {
        end_at(c->ends + 0, c, p, NULL, 0, npoints);
        c->nends = 1;
    }
}
