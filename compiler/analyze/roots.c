/*
 * roots.c - real roots of integer polynomials (roots.h).
 *
 * p is factored over Q (fmpz_poly_factor); each irreducible factor f is
 * treated on its own, so its roots are simple and no rational point can be
 * a root of f once deg f >= 2.  Linear factors give their root exactly.
 * Every other factor gets a Sturm sequence (over Q, exact), whose sign
 * variations V count the roots in (a, b] as V(a) - V(b); the range (or the
 * Cauchy bound) is bisected until each interval holds one root, and that
 * interval is halved on the sign of f until it is narrow enough.  Every
 * comparison is exact: only the last step, the double of the midpoint, is
 * rounded.  Quadratic factors also get their roots' text, (p +- q
 * sqrt(D))/r, D square-free.
 */
#include "compiler/analyze/roots.h"

#include <stdlib.h>
#include <string.h>

#include <flint/fmpq_poly.h>
#include <flint/fmpz_factor.h>
#include <flint/fmpz_poly_factor.h>

#include "base/budget.h"
#include "base/mem.h"
#include "base/strbuf.h"

void roots_init(AnRoots *r)
{
    memset(r, 0, sizeof *r);
}

void roots_clear(AnRoots *r)
{
    for (slong i = 0; i < r->n; i++)
        pc_free(r->v[i].exact);
    pc_free(r->v);
    memset(r, 0, sizeof *r);
}

/* appends a root; consumes exact */
static void push_root(AnRoots *r, char *exact, double value, slong mult)
{
    if (r->n == r->alloc) {
        r->alloc = r->alloc ? 2 * r->alloc : 4;
        r->v = pc_xrealloc(r->v, (size_t)r->alloc * sizeof *r->v);
    }
    r->v[r->n].exact = exact;
    r->v[r->n].value = value;
    r->v[r->n].mult = mult;
    r->n++;
}

static int in_range(const fmpq_t x, const fmpq *lo, const fmpq *hi)
{
    return (!lo || fmpq_cmp(x, lo) >= 0) && (!hi || fmpq_cmp(x, hi) <= 0);
}

/* f = a t + b: its root -b/a */
static void linear_root(AnRoots *res, const fmpz_poly_t f, slong mult,
                        const fmpq *lo, const fmpq *hi)
{
    fmpq_t x;
    fmpz_t nb;
    fmpq_init(x);
    fmpz_init(nb);
    fmpz_neg(nb, f->coeffs + 0);
    fmpq_set_fmpz_frac(x, nb, f->coeffs + 1);
    if (in_range(x, lo, hi)) {
        char *s = fmpq_get_str(NULL, 10, x);
        push_root(res, pc_xstrdup(s), fmpq_get_d(x), mult);
        flint_free(s);
    }
    fmpz_clear(nb);
    fmpq_clear(x);
}

/* ---- Sturm sequences ---------------------------------------------------- */

typedef struct Sturm {
    slong len;
    fmpq_poly_struct *s; // s[0] = f, s[1] = f', s[k+1] = -rem(s[k-1], s[k])
} Sturm;

static void sturm_init(Sturm *st, const fmpz_poly_t f)
{
    slong cap = fmpz_poly_degree(f) + 1;
    st->s = pc_xmalloc((size_t)cap * sizeof *st->s);
    fmpq_poly_init(st->s + 0);
    fmpq_poly_set_fmpz_poly(st->s + 0, f);
    fmpq_poly_init(st->s + 1);
    fmpq_poly_derivative(st->s + 1, st->s + 0);
    st->len = 2;
    while (fmpq_poly_degree(st->s + st->len - 1) > 0) {
        fmpq_poly_struct *n = st->s + st->len;
        fmpq_poly_init(n);
        fmpq_poly_rem(n, st->s + st->len - 2, st->s + st->len - 1);
        fmpq_poly_neg(n, n);
        /* only the signs matter: a positive multiple keeps them, and
         * keeps the coefficients small */
        fmpq_poly_canonicalise(n);
        st->len++;
    }
}

static void sturm_clear(Sturm *st)
{
    for (slong i = 0; i < st->len; i++)
        fmpq_poly_clear(st->s + i);
    pc_free(st->s);
}

/* the number of sign changes of the sequence at x (zeros skipped) */
static slong sturm_var(const Sturm *st, const fmpq_t x)
{
    fmpq_t v;
    fmpq_init(v);
    slong changes = 0;
    int last = 0;
    for (slong i = 0; i < st->len; i++) {
        fmpq_poly_evaluate_fmpq(v, st->s + i, x);
        int sg = fmpq_sgn(v);
        if (sg && last && sg != last)
            changes++;
        if (sg)
            last = sg;
    }
    fmpq_clear(v);
    return changes;
}

static int sign_at(const fmpq_poly_t f, const fmpq_t x)
{
    fmpq_t v;
    fmpq_init(v);
    fmpq_poly_evaluate_fmpq(v, f, x);
    int s = fmpq_sgn(v);
    fmpq_clear(v);
    return s;
}

/* 1 when b - a <= 2^-60 max(1, |a|): below 1e-15, and fine enough
 * that the midpoint rounds to the double nearest the root */
static int narrow(const fmpq_t a, const fmpq_t b)
{
    fmpq_t w, m;
    fmpq_init(w);
    fmpq_init(m);
    fmpq_sub(w, b, a);
    fmpq_abs(m, a);
    if (fmpq_cmp_ui(m, 1) < 0)
        fmpq_one(m);
    fmpq_mul_2exp(w, w, 60);
    int ok = fmpq_cmp(w, m) <= 0;
    fmpq_clear(m);
    fmpq_clear(w);
    return ok;
}

/* (a, b] holds exactly one root of f = st->s[0], and neither end is one:
 * halve it on the sign of f; returns the midpoint's double */
static double refine(const Sturm *st, const fmpq_t a0, const fmpq_t b0)
{
    fmpq_t a, b, m;
    fmpq_init(a);
    fmpq_init(b);
    fmpq_init(m);
    fmpq_set(a, a0);
    fmpq_set(b, b0);
    int sa = sign_at(st->s + 0, a);
    while (!narrow(a, b)) {
        fmpq_add(m, a, b);
        fmpq_div_2exp(m, m, 1);
        if (sign_at(st->s + 0, m) == sa)
            fmpq_swap(a, m);
        else
            fmpq_swap(b, m);
    }
    fmpq_add(m, a, b);
    fmpq_div_2exp(m, m, 1);
    double v = fmpq_get_d(m);
    fmpq_clear(m);
    fmpq_clear(b);
    fmpq_clear(a);
    return v;
}

/* An isolated root of a quadratic factor and which of its two roots it
 * is: the one above the vertex -b/(2a) (a > 0) is (-b + sqrt D)/(2a). */
typedef struct Quad {
    const fmpz_poly_struct *f; // a t^2 + b t + c, or NULL: not quadratic
    fmpq_t vertex;
} Quad;

/* the text of root (-b +- sqrt(b^2 - 4ac))/(2a), sqrt's argument made
 * square-free */
static char *quad_text(const fmpz_poly_t f, int plus)
{
    fmpz_t p, q, r, disc, t, g;
    fmpz_init(p);
    fmpz_init(q);
    fmpz_init(r);
    fmpz_init(disc);
    fmpz_init(t);
    fmpz_init(g);
    fmpz_mul(disc, f->coeffs + 1, f->coeffs + 1);
    fmpz_mul(t, f->coeffs + 2, f->coeffs + 0);
    fmpz_submul_ui(disc, t, 4);
    fmpz_neg(p, f->coeffs + 1);
    fmpz_mul_ui(r, f->coeffs + 2, 2);
    fmpz_one(q);
    if (fmpz_bits(disc) <= 128) { /* pull the square part out */
        fmpz_factor_t fac;
        fmpz_factor_init(fac);
        fmpz_factor(fac, disc);
        fmpz_one(disc);
        for (slong i = 0; i < fac->num; i++) {
            fmpz_pow_ui(t, fac->p + i, fac->exp[i] / 2);
            fmpz_mul(q, q, t);
            if (fac->exp[i] % 2)
                fmpz_mul(disc, disc, fac->p + i);
        }
        fmpz_factor_clear(fac);
    }
    if (fmpz_sgn(r) < 0) { /* a positive denominator; the sign of q flips */
        fmpz_neg(r, r);
        fmpz_neg(p, p);
        plus = !plus;
    }
    fmpz_gcd(g, p, q);
    fmpz_gcd(g, g, r);
    fmpz_divexact(p, p, g);
    fmpz_divexact(q, q, g);
    fmpz_divexact(r, r, g);
    StrBuf b = {0};
    int paren = !fmpz_is_one(r) && !fmpz_is_zero(p);
    if (paren)
        sb_puts(&b, "(");
    if (!fmpz_is_zero(p)) {
        sb_fmpz(&b, p);
        sb_puts(&b, plus ? " + " : " - ");
    } else if (!plus)
        sb_puts(&b, "-");
    if (!fmpz_is_one(q)) {
        sb_fmpz(&b, q);
        sb_puts(&b, "*");
    }
    sb_puts(&b, "sqrt(");
    sb_fmpz(&b, disc);
    sb_puts(&b, ")");
    if (paren)
        sb_puts(&b, ")");
    if (!fmpz_is_one(r)) {
        sb_puts(&b, "/");
        sb_fmpz(&b, r);
    }
    fmpz_clear(g);
    fmpz_clear(t);
    fmpz_clear(disc);
    fmpz_clear(r);
    fmpz_clear(q);
    fmpz_clear(p);
    return sb_take(&b);
}

/* which root of a quadratic (a, b] isolates: 1 the upper one */
static int quad_upper(const Sturm *st, const Quad *qd, const fmpq_t a,
                      const fmpq_t b)
{
    if (fmpq_cmp(b, qd->vertex) <= 0)
        return 0;
    if (fmpq_cmp(a, qd->vertex) >= 0)
        return 1;
    return sturm_var(st, a) - sturm_var(st, qd->vertex) == 0;
}

typedef struct Isolate {
    const Sturm *st;
    const Quad *qd;
    slong mult;
    AnRoots *res;
} Isolate;

/* the roots in (a, b], count of them: bisect until one each */
static void isolate(Isolate *is, const fmpq_t a, const fmpq_t b, slong count)
{
    if (count <= 0 || budget_late()) /* past the deadline: left (curve.c) */
        return;
    if (count == 1) {
        double v = refine(is->st, a, b);
        char *text = NULL;
        if (is->qd->f) {
            int up = quad_upper(is->st, is->qd, a, b);
            /* the upper root has + when lc > 0 */
            int lcpos = fmpz_sgn(is->qd->f->coeffs + 2) > 0;
            text = quad_text(is->qd->f, up == lcpos);
        }
        push_root(is->res, text, v, is->mult);
        return;
    }
    fmpq_t m;
    fmpq_init(m);
    fmpq_add(m, a, b);
    fmpq_div_2exp(m, m, 1);
    slong left = sturm_var(is->st, a) - sturm_var(is->st, m);
    isolate(is, a, m, left);
    isolate(is, m, b, count - left);
    fmpq_clear(m);
}

/* an integer B with every real root of f in (-B, B): 2 + max |a_i/a_n| */
static void cauchy_bound(fmpq_t B, const fmpz_poly_t f)
{
    slong n = fmpz_poly_degree(f);
    fmpz_t m, q;
    fmpz_init(m);
    fmpz_init(q);
    for (slong i = 0; i < n; i++) {
        fmpz_cdiv_q(q, f->coeffs + i, f->coeffs + n);
        fmpz_abs(q, q);
        if (fmpz_cmp(q, m) > 0)
            fmpz_set(m, q);
    }
    fmpz_add_ui(m, m, 2);
    fmpz_set(fmpq_numref(B), m);
    fmpz_one(fmpq_denref(B));
    fmpz_clear(q);
    fmpz_clear(m);
}

/* the real roots of the irreducible f (degree >= 2) in [lo, hi] */
static void factor_roots(AnRoots *res, const fmpz_poly_t f, slong mult,
                         const fmpq *lo, const fmpq *hi)
{
    Sturm st;
    sturm_init(&st, f);
    Quad qd;
    qd.f = fmpz_poly_degree(f) == 2 ? f : NULL;
    fmpq_init(qd.vertex);
    if (qd.f) { /* -b/(2a) */
        fmpz_t nb, a2;
        fmpz_init(nb);
        fmpz_init(a2);
        fmpz_neg(nb, f->coeffs + 1);
        fmpz_mul_ui(a2, f->coeffs + 2, 2);
        fmpq_set_fmpz_frac(qd.vertex, nb, a2);
        fmpz_clear(a2);
        fmpz_clear(nb);
    }
    fmpq_t a, b;
    fmpq_init(a);
    fmpq_init(b);
    cauchy_bound(b, f);
    fmpq_neg(a, b);
    if (lo && fmpq_cmp(lo, a) > 0)
        fmpq_set(a, lo);
    if (hi && fmpq_cmp(hi, b) < 0)
        fmpq_set(b, hi);
    if (fmpq_cmp(a, b) < 0) { /* f(a) != 0: no rational roots */
        Isolate is = {&st, &qd, mult, res};
        isolate(&is, a, b, sturm_var(&st, a) - sturm_var(&st, b));
    }
    fmpq_clear(b);
    fmpq_clear(a);
    fmpq_clear(qd.vertex);
    sturm_clear(&st);
}

static int cmp_root(const void *x, const void *y)
{
    double a = ((const AnRoot *)x)->value, b = ((const AnRoot *)y)->value;
    return (a > b) - (a < b);
}

void roots_real(AnRoots *res, const fmpz_poly_t p, const fmpq *lo,
                const fmpq *hi, const fmpz_poly_t excl)
{
    if (fmpz_poly_degree(p) < 1)
        return;
    fmpz_poly_factor_t fac;
    fmpz_poly_t q;
    fmpz_poly_factor_init(fac);
    fmpz_poly_init(q);
    fmpz_poly_factor(fac, p);
    for (slong i = 0; i < fac->num && !budget_late(); i++) {
        const fmpz_poly_struct *f = fac->p + i;
        if (excl && !fmpz_poly_is_zero(excl) && fmpz_poly_divides(q, excl, f))
            continue;
        if (fmpz_poly_degree(f) == 1)
            linear_root(res, f, fac->exp[i], lo, hi);
        else
            factor_roots(res, f, fac->exp[i], lo, hi);
    }
    fmpz_poly_clear(q);
    fmpz_poly_factor_clear(fac);
    if (res->n > 1) /* qsort takes no NULL, even for 0 elements */
        qsort(res->v, (size_t)res->n, sizeof *res->v, cmp_root);
}

void roots_push_value(AnRoots *r, double x, slong mult)
{
    push_root(r, NULL, x, mult);
    for (slong i = r->n - 1; i > 0 && r->v[i - 1].value > x; i--) {
        AnRoot t = r->v[i - 1];
        r->v[i - 1] = r->v[i];
        r->v[i] = t;
    }
}
