/*
 * ratfun_size.c - size guards (ratfun.h: ratfun_log2_bits_*): estimates,
 * before an operation, of the bits of its result.
 *
 * From the operands' shapes (length, largest coefficient, degrees) an
 * upper estimate of log2 of the result's size in bits: the callers
 * (kernel_reduce.c, meet_ff.c, solve.c ...) refuse a product or a power
 * beyond their limit before FLINT would spend minutes or gigabytes on it.
 */
#define _DEFAULT_SOURCE // lgamma_r (lgamma writes the process-wide signgam)
#include "compiler/algebra/ratfun.h"

#include <math.h>

/* A polynomial's shape for the estimates: log2 of its length, its largest
 * coefficient's bits, its degree in every variable (degs: nvars slots). */
typedef struct Shape {
    double llen; // log2(length); -1 for the zero polynomial
    double bits; // largest coefficient, bits
    slong *degs; // borrowed buffer
    int huge;    // degrees beyond a slong
} Shape;

static void shape_of(Shape *s, const fmpz_mpoly_t p, slong *degs, const Ring *r)
{
    slong len = fmpz_mpoly_length(p, r->ctx);
    s->degs = degs;
    s->llen = len ? log2((double)len) : -1;
    s->bits = (double)FLINT_ABS(fmpz_mpoly_max_bits(p));
    s->huge = !fmpz_mpoly_degrees_fit_si(p, r->ctx);
    if (!s->huge)
        fmpz_mpoly_degrees_si(degs, p, r->ctx);
}

/* log2 of the bits of a*b at most */
static double prod_bits(const Shape *a, const Shape *b, slong nv)
{
    if (a->llen < 0 || b->llen < 0)
        return 0;
    if (a->huge || b->huge)
        return INFINITY;
    double lterms = 0;
    for (slong v = 0; v < nv; v++)
        lterms += log2((double)a->degs[v] + (double)b->degs[v] + 1);
    if (a->llen + b->llen < lterms)
        lterms = a->llen + b->llen;
    double shorter = a->llen < b->llen ? a->llen : b->llen;
    return lterms + log2(a->bits + b->bits + shorter + 1);
}

/* log2 of binomial(n, k) (lgamma_r: lgamma sets the process-wide signgam,
 * a data race between threads) */
static double log2_binomial(double n, double k)
{
    int sg;
    return (lgamma_r(n + 1, &sg) - lgamma_r(k + 1, &sg) -
            lgamma_r(n - k + 1, &sg)) /
           log(2.0);
}

/* log2 of the number of terms of a^e at most: the multinomial count
 * binomial(len + e - 1, e) (the monomials of degree e in len symbols) and
 * the box of the degrees, whichever is smaller */
static double pow_lterms(const Shape *a, double e, slong nv)
{
    double box = 0;
    for (slong v = 0; v < nv; v++)
        box += log2(e * (double)a->degs[v] + 1);
    double len = exp2(a->llen);
    double multi = log2_binomial(len + e - 1, e);
    return multi < box ? multi : box;
}

/* log2 of the bits of a^e at most (e >= 0) */
static double pow_bits(const Shape *a, double e, slong nv)
{
    if (a->llen < 0 || e == 0)
        return 0;
    if (a->huge)
        return INFINITY;
    return pow_lterms(a, e, nv) + log2(e * (a->bits + a->llen + 1) + 1);
}

static double max2(double a, double b)
{
    return a > b ? a : b;
}

/* the shapes of a RatFun's numerator and denominator (own degree buffer) */
typedef struct Shapes {
    Shape n, d;
    slong *degs; // owned, 2 * nvars
} Shapes;

static void shapes_init(Shapes *s, const RatFun x, const Ring *r)
{
    slong nv = r->ctx->minfo->nvars;
    s->degs = flint_malloc(2 * (size_t)nv * sizeof(slong));
    shape_of(&s->n, x->num, s->degs, r);
    shape_of(&s->d, x->den, s->degs + nv, r);
}

static void shapes_clear(Shapes *s)
{
    flint_free(s->degs);
}

double ratfun_poly_log2_bits_mul(const fmpz_mpoly_t a, const fmpz_mpoly_t b,
                                 const Ring *r)
{
    slong nv = r->ctx->minfo->nvars;
    slong *degs = flint_malloc((size_t)(2 * nv) * sizeof(slong));
    Shape sa, sb;
    shape_of(&sa, a, degs, r);
    shape_of(&sb, b, degs + nv, r);
    double bits = prod_bits(&sa, &sb, nv);
    flint_free(degs);
    return bits;
}

double ratfun_log2_bits_product(const RatFun x, const RatFun y, const Ring *r)
{
    slong nv = r->ctx->minfo->nvars;
    Shapes a, b;
    shapes_init(&a, x, r);
    shapes_init(&b, y, r);
    double m = max2(max2(prod_bits(&a.n, &b.n, nv), prod_bits(&a.d, &b.d, nv)),
                    max2(prod_bits(&a.n, &b.d, nv), prod_bits(&a.d, &b.n, nv)));
    shapes_clear(&b);
    shapes_clear(&a);
    return m;
}

double ratfun_log2_bits_pow(const RatFun x, slong e, const Ring *r)
{
    slong nv = r->ctx->minfo->nvars;
    Shapes a;
    shapes_init(&a, x, r);
    double ae = fabs((double)e);
    double m = max2(pow_bits(&a.n, ae, nv), pow_bits(&a.d, ae, nv));
    shapes_clear(&a);
    return m;
}

double ratfun_log2_bits_compose(const RatFun x, slong var, const RatFun s,
                                const Ring *r)
{
    slong nv = r->ctx->minfo->nvars;
    Shapes a, b;
    shapes_init(&a, x, r);
    shapes_init(&b, s, r);
    double m = INFINITY;
    if (!a.n.huge && !a.d.huge && !b.n.huge && !b.d.huge) {
        /* every term of x times a power of s of degree <= e, over the
         * common denominator: terms <= len(x) * terms(s^e), coefficient
         * bits <= bits(x) + e (bits(s) + log2 len(s)) + log2 len(x) */
        double e = (double)(a.n.degs[var] > a.d.degs[var] ? a.n.degs[var]
                                                          : a.d.degs[var]);
        double lx = max2(max2(a.n.llen, a.d.llen), 0);
        double bx = max2(a.n.bits, a.d.bits);
        double ls =
            e > 0 ? max2(pow_lterms(&b.n, e, nv), pow_lterms(&b.d, e, nv)) : 0;
        double bs =
            e * (max2(b.n.bits, b.d.bits) + max2(b.n.llen, b.d.llen) + 1);
        m = lx + ls + log2(bx + bs + lx + 1);
    }
    shapes_clear(&b);
    shapes_clear(&a);
    return m;
}
