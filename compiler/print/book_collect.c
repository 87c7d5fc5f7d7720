/*
 * book_collect.c - the collected forms of a polynomial (book.h): by the
 * powers of one variable, in the Bernstein basis of a param, and in powers
 * of sin^2 with cos^2 = 1 - sin^2.  Each is built term by term and given
 * up as soon as it has more leaves than the best form so far (the caller's
 * limit), so a form that cannot win costs little whatever the degree.
 */
#include "compiler/print/book_int.h"

#include <stdlib.h>
#include <string.h>

#include <flint/fmpz_vec.h>

#include "base/mem.h"

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

/* the nonzero coefficients of p in powers of x: p = sum_j a[j] x^e[j],
 * e ascending (p's terms are read, not its degree: t^6000 has two) */
typedef struct Coeffs {
    slong n;
    ulong *e;
    fmpz_mpoly_struct *a;
} Coeffs;

static int cmp_ulong(const void *x, const void *y)
{
    ulong a = *(const ulong *)x, b = *(const ulong *)y;
    return (a > b) - (a < b);
}

static void coeffs_init(Coeffs *k, const fmpz_mpoly_t p, slong x, const Ctx *c)
{
    const Ring *r = c->r;
    slong len = fmpz_mpoly_length(p, r->ctx);
    k->e = pc_xmalloc(sizeof(ulong) * (size_t)(len ? len : 1));
    for (slong i = 0; i < len; i++)
        k->e[i] = fmpz_mpoly_get_term_var_exp_ui(p, i, x, r->ctx);
    qsort(k->e, (size_t)len, sizeof(ulong), cmp_ulong);
    k->n = 0;
    for (slong i = 0; i < len; i++)
        if (k->n == 0 || k->e[k->n - 1] != k->e[i])
            k->e[k->n++] = k->e[i];
    k->a = pc_xmalloc(sizeof(fmpz_mpoly_struct) * (size_t)(k->n ? k->n : 1));
    for (slong j = 0; j < k->n; j++) {
        fmpz_mpoly_init(k->a + j, r->ctx);
        fmpz_mpoly_get_coeff_vars_ui(k->a + j, p, &x, k->e + j, 1, r->ctx);
    }
}

static void coeffs_clear(Coeffs *k, const Ctx *c)
{
    for (slong j = 0; j < k->n; j++)
        fmpz_mpoly_clear(k->a + j, c->r->ctx);
    pc_free(k->a);
    pc_free(k->e);
}

/* s, being built, with more leaves to come (at least more), would have
 * more leaves than limit: it cannot win (book_render keeps a form with
 * fewer leaves); s is freed */
static int beyond(PSum **s, slong more, slong limit, const Ctx *c)
{
    slong have = (*s)->n ? book_sum_leaves(*s) : 0;
    if (have + more <= limit)
        return 0;
    book_sum_free(*s, c);
    *s = NULL;
    return 1;
}

/* more[j]: a lower bound on the leaves that a[j..n) will make as
 * coefficients at depth (book_leaves_lower; more[n] = 0) */
static slong *leaves_to_come(const fmpz_mpoly_struct *a, slong n, int depth,
                             const Ctx *c)
{
    slong *more = pc_xmalloc(sizeof(slong) * (size_t)(n + 1));
    more[n] = 0;
    for (slong j = n - 1; j >= 0; j--)
        more[j] = more[j + 1] + (fmpz_mpoly_is_zero(a + j, c->r->ctx)
                                     ? 0
                                     : book_leaves_lower(a + j, depth, c));
    return more;
}

PSum *book_form_powers(const fmpz_mpoly_t p, slong x, int depth, slong limit,
                       const Ctx *c)
{
    Coeffs k;
    coeffs_init(&k, p, x, c);
    PSum *s = book_sum_new(c);
    slong *more = k.n <= limit ? leaves_to_come(k.a, k.n, depth + 1, c) : NULL;
    if (!more)
        beyond(&s, k.n, limit, c);
    for (slong j = 0; s && j < k.n && !beyond(&s, more[j], limit, c); j++) {
        Atom xa = {AT_VAR, x, NULL, NULL, NULL, k.e[j]};
        push_collected(s, k.a + j, &xa, 1, depth, c);
    }
    if (s)
        beyond(&s, 0, limit, c);
    pc_free(more);
    coeffs_clear(&k, c);
    if (s)
        book_sum_finish(s, p, c);
    return s;
}

/* A Bernstein basis of degree n: p = sum_k b_k u^k v^(n-k) with p =
 * sum_j a_j u^(e_j) (u + v = 1), b_k = sum_{e_j <= k} a_j C(n - e_j, k -
 * e_j) (without binomials).  The binomials are carried from one k to the
 * next (C(m, i + 1) = C(m, i) (m - i)/(i + 1)): n steps of one product per
 * nonzero a_j, not n^2 binomials.  u is var u of kind AT_VAR, v var v of
 * kind vkind, both raised to scale times their power.  NULL past limit. */
typedef struct Basis {
    slong u, v;
    AtomKind vkind;
    ulong scale;
} Basis;

static PSum *bernstein(const Coeffs *k, ulong n, const Basis *B, int depth,
                       slong limit, const Ctx *c)
{
    const Ring *r = c->r;
    fmpz *bin = _fmpz_vec_init(k->n);
    fmpz_mpoly_struct *b =
        pc_xmalloc(sizeof(fmpz_mpoly_struct) * (size_t)(n + 1));
    fmpz_mpoly_t tmp;
    fmpz_mpoly_init(tmp, r->ctx);
    for (ulong kk = 0; kk <= n; kk++) {
        fmpz_mpoly_init(b + kk, r->ctx);
        for (slong j = 0; j < k->n && k->e[j] <= kk; j++) {
            ulong m = n - k->e[j], i = kk - k->e[j];
            if (i == 0) {
                fmpz_one(bin + j);
            } else { /* C(m, i) from C(m, i - 1) */
                fmpz_mul_ui(bin + j, bin + j, m - (i - 1));
                fmpz_divexact_ui(bin + j, bin + j, i);
            }
            fmpz_mpoly_scalar_mul_fmpz(tmp, k->a + j, bin + j, r->ctx);
            fmpz_mpoly_add(b + kk, b + kk, tmp, r->ctx);
        }
    }
    fmpz_mpoly_clear(tmp, r->ctx);
    _fmpz_vec_clear(bin, k->n);
    /* each b_k != 0 makes a term: given up before any is rendered when
     * they are too many */
    PSum *s = book_sum_new(c);
    slong nz = 0;
    for (ulong kk = 0; kk <= n; kk++)
        nz += !fmpz_mpoly_is_zero(b + kk, r->ctx);
    slong *more =
        nz <= limit ? leaves_to_come(b, (slong)n + 1, depth + 1, c) : NULL;
    if (!more)
        beyond(&s, nz, limit, c);
    for (ulong kk = 0; kk <= n && s && !beyond(&s, more[kk], limit, c); kk++) {
        if (fmpz_mpoly_is_zero(b + kk, r->ctx))
            continue;
        Atom xs[2] = {{AT_VAR, B->u, NULL, NULL, NULL, B->scale * kk},
                      {B->vkind, B->v, NULL, NULL, NULL, B->scale * (n - kk)}};
        push_collected(s, b + kk, xs, 2, depth, c);
    }
    if (s)
        beyond(&s, 0, limit, c);
    pc_free(more);
    for (ulong kk = 0; kk <= n; kk++)
        fmpz_mpoly_clear(b + kk, r->ctx);
    pc_free(b);
    return s;
}

/* the cost of bernstein() in limb operations, roughly: n steps, each a
 * product per coefficient term of a binomial of up to n bits */
static int bernstein_affordable(ulong n, const fmpz_mpoly_t p, const Ctx *c)
{
    enum { MAX_COST = 20000000 };
    double len = (double)fmpz_mpoly_length(p, c->r->ctx);
    return (double)n * len * ((double)n / 64.0 + 1.0) <= MAX_COST;
}

PSum *book_form_bernstein(const fmpz_mpoly_t p, slong x, int depth, slong limit,
                          const Ctx *c)
{
    slong n = fmpz_mpoly_degree_si(p, x, c->r->ctx);
    if (!bernstein_affordable((ulong)n, p, c))
        return NULL;
    Coeffs k;
    coeffs_init(&k, p, x, c);
    Basis B = {x, x, AT_BAR, 1};
    PSum *s = bernstein(&k, (ulong)n, &B, depth, limit, c);
    coeffs_clear(&k, c);
    if (s)
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

PSum *book_form_sin2(const fmpz_mpoly_t p, slong s, slong w, int depth,
                     slong limit, const Ctx *c)
{
    const Ring *r = c->r;
    slong n2 = fmpz_mpoly_degree_si(p, s, r->ctx);
    if (n2 < 2 || (n2 & 1) || fmpz_mpoly_degree_si(p, w, r->ctx) > 0 ||
        !bernstein_affordable((ulong)n2 / 2, p, c))
        return NULL;
    Coeffs k;
    coeffs_init(&k, p, s, c);
    PSum *sum = NULL;
    int even = 1;
    for (slong j = 0; j < k.n; j++) {
        even &= !(k.e[j] & 1);
        k.e[j] /= 2; /* powers of y = s^2 */
    }
    if (even) {
        Basis B = {s, w, AT_VAR, 2};
        sum = bernstein(&k, (ulong)n2 / 2, &B, depth, limit, c);
    }
    coeffs_clear(&k, c);
    if (sum)
        book_sum_finish(sum, p, c);
    return sum;
}
