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
 * The factored forms are book_factor.c's, the collected ones
 * book_collect.c's (each given up once it has more leaves than the best
 * so far, so a form that cannot win costs little at any degree).
 * In the printer: polynomials in, models (book_model.c) out, for
 * book_write.c and book_eq.c.
 */
#include "compiler/print/book_int.h"

#include <stdlib.h>
#include <string.h>

#include <flint/fmpz_mpoly_factor.h>
#include <flint/fmpz_vec.h>

#include "base/budget.h"
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

/* the best form so far: its model (NULL while it is the expanded form,
 * which is built only if it wins: most polynomials have a better one), its
 * leaves, its rank (R_FACTORED ...) and its text length ((size_t)-1 until
 * measured) */
enum { R_FACTORED, R_EXPANDED, R_BERNSTEIN, R_POWERS };
typedef struct Best {
    PSum *s;
    slong leaves;
    int rank;
    size_t len;
    slong pos; // the var a collected form is by: the first wins a tie
} Best;

/* keeps the better of b and cand: fewer leaves; then factored before
 * expanded before collected; among collected forms the shorter text, then
 * Bernstein before powers; then the one by the earlier variable.  Lengths
 * are those
 * of the text form whatever the style, so text and LaTeX agree (the
 * expanded form never needs its length: it ranks alone). */
static void keep_better(Best *b, PSum *cand, int rank, slong pos, const Ctx *c)
{
    if (!cand)
        return;
    size_t len = (size_t)-1;
    slong lc = book_sum_leaves(cand);
    int kb = b->rank < 2 ? b->rank : 2;
    int kc = rank < 2 ? rank : 2;
    int better = lc < b->leaves || (lc == b->leaves && kc < kb);
    if (lc == b->leaves && kc == kb && kc == 2) {
        if (b->len == (size_t)-1)
            b->len = text_len(b->s, c);
        len = text_len(cand, c);
        better = len < b->len ||
                 (len == b->len &&
                  (rank < b->rank || (rank == b->rank && pos < b->pos)));
    }
    if (!better) {
        book_sum_free(cand, c);
        return;
    }
    book_sum_free(b->s, c);
    b->s = cand;
    b->leaves = lc;
    b->rank = rank;
    b->len = len;
    b->pos = pos;
}

static PSum *render_new(const fmpz_mpoly_t p, int depth, const Ctx *c);

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

/* a hash of p (its length, coefficients and degrees in each variable:
 * equal polynomials may pack their exponents differently, so not the
 * packed words), the depth and the mode */
static ulong memo_key(const fmpz_mpoly_t p, slong len, int depth, const Ctx *c)
{
    ulong h = (ulong)len * 0x9E3779B97F4A7C15u ^ (ulong)depth ^ c->mode << 8;
    for (slong i = 0; i < len; i++) {
        const fmpz *x = p->coeffs + i;
        ulong w = !COEFF_IS_MPZ(*x) ? (ulong)*x
                                    : (ulong)mpz_get_ui(COEFF_TO_PTR(*x)) ^
                                          (ulong)mpz_sgn(COEFF_TO_PTR(*x));
        h = (h ^ w) * 0x100000001B3u;
    }
    enum { FEW_VARS = 16 };
    slong nv = c->r->nvars, deg[FEW_VARS];
    if (nv > 0 && nv <= FEW_VARS && fmpz_mpoly_degrees_fit_si(p, c->r->ctx)) {
        fmpz_mpoly_degrees_si(deg, p, c->r->ctx);
        for (slong v = 0; v < nv; v++)
            h = (h ^ (ulong)deg[v]) * 0x100000001B3u;
    }
    return h ^ h >> 29;
}

/* the memo's entry for p at depth (in c's mode), or NULL; *key: its key */
static const MemoEntry *memo_find(const fmpz_mpoly_t p, slong len, int depth,
                                  const Ctx *c, ulong *key)
{
    const Memo *m = c->memo;
    *key = memo_key(p, len, depth, c);
    if (!m->slot)
        return NULL;
    for (ulong i = *key & (MEMO_SLOTS - 1);; i = (i + 1) & (MEMO_SLOTS - 1)) {
        slong j = m->slot[i] - 1;
        if (j < 0)
            return NULL;
        const MemoEntry *e = &m->e[j];
        if (e->key == *key && e->depth == depth && e->mode == c->mode &&
            fmpz_mpoly_equal(e->poly, p, c->r->ctx))
            return e;
    }
}

/* remembers s as p's form at depth (the first MEMO_MAX only) */
static void memo_add(const fmpz_mpoly_t p, ulong key, int depth, const PSum *s,
                     const Ctx *c)
{
    Memo *m = c->memo;
    if (m->n >= MEMO_MAX)
        return;
    if (!m->slot)
        m->slot = pc_xcalloc(MEMO_SLOTS, sizeof(slong));
    if (m->n == m->alloc) {
        m->alloc = m->alloc ? 2 * m->alloc : 32;
        m->e = pc_xrealloc(m->e, sizeof(MemoEntry) * (size_t)m->alloc);
    }
    MemoEntry *e = &m->e[m->n++];
    fmpz_mpoly_init(e->poly, c->r->ctx);
    fmpz_mpoly_set(e->poly, p, c->r->ctx);
    e->key = key;
    e->depth = depth;
    e->mode = c->mode;
    e->sum = book_sum_copy(s, c);
    ulong i = key & (MEMO_SLOTS - 1);
    while (m->slot[i])
        i = (i + 1) & (MEMO_SLOTS - 1);
    m->slot[i] = m->n;
}

static PSum *render_memo(const fmpz_mpoly_t p, int depth, const Ctx *c)
{
    slong len = fmpz_mpoly_length(p, c->r->ctx);
    if (len < 2 || !c->memo)
        return render_new(p, depth, c);
    ulong key;
    const MemoEntry *e = memo_find(p, len, depth, c, &key);
    if (e)
        return book_sum_copy(e->sum, c);
    PSum *s = render_new(p, depth, c);
    memo_add(p, key, depth, s, c);
    return s;
}

/* could p (two terms or more) be c*m*(1 - x)^e*(1 - y)^f*..., a number
 * times a monomial times powers of 1 - x of params and consts: a form of
 * one leaf?  0 when surely not: its coefficients do not sum to 0 (p
 * would vanish at x = 1), a var other than those has two exponents, or
 * the count of its terms is not the product of the exponent ranges
 * (e + 1)(f + 1)...  1 otherwise (perhaps). */
static int bar_monomial_possible(const fmpz_mpoly_t p, slong len, const Ctx *c)
{
    if (!polyfactor_vanishes_at_ones(p, c->r))
        return 0;
    enum { FEW_VARS = 16 };
    slong nv = c->r->nvars;
    if (nv > FEW_VARS || !fmpz_mpoly_degrees_fit_si(p, c->r->ctx))
        return 1;
    ulong e[FEW_VARS], lo[FEW_VARS], hi[FEW_VARS];
    for (slong k = 0; k < len; k++) {
        fmpz_mpoly_get_term_exp_ui(e, p, k, c->r->ctx);
        for (slong v = 0; v < nv; v++) {
            lo[v] = k == 0 || e[v] < lo[v] ? e[v] : lo[v];
            hi[v] = k == 0 || e[v] > hi[v] ? e[v] : hi[v];
        }
    }
    double terms = 1;
    for (slong v = 0; v < nv; v++) {
        if (v >= c->nparams + c->nconsts && lo[v] != hi[v])
            return 0;
        terms *= (double)(hi[v] - lo[v] + 1);
    }
    return terms == (double)len;
}

slong book_leaves_lower(const fmpz_mpoly_t p, int depth, const Ctx *c)
{
    slong len = fmpz_mpoly_length(p, c->r->ctx);
    if (len < 2 || c->has_sign || c->is_abs || c->exhaustive)
        return 1; /* (through |x|, one leaf may write a sum: (t - 1)*|t - 1|) */
    if (c->memo) { /* chosen already: exactly */
        ulong key;
        const MemoEntry *e = memo_find(p, len, depth, c, &key);
        if (e)
            return book_sum_leaves(e->sum);
    }
    /* a sum sits in a product only with two terms or more (book_model.c),
     * so a form of one leaf is one product of vars and 1 - x's */
    return bar_monomial_possible(p, len, c) ? 1 : 2;
}

/* the leaves a collected form must not exceed to compete with b: b's,
 * or one fewer when b is factored or expanded, which win a tie (none in
 * the tests' exhaustive search) */
static slong limit(const Best *b, const Ctx *c)
{
    if (c->exhaustive)
        return WORD_MAX;
    return b->rank < R_BERNSTEIN ? b->leaves - 1 : b->leaves;
}

/* b's form, built now if it is the expanded one */
static PSum *best_take(Best *b, const fmpz_mpoly_t p, const Ctx *c)
{
    return b->s ? b->s : book_form_expanded(p, c);
}

static PSum *render_new(const fmpz_mpoly_t p, int depth, const Ctx *c)
{
    const Ring *r = c->r;
    slong len = fmpz_mpoly_length(p, r->ctx);
    if (c->is_abs) { /* |x| in it: by the knots, as the text writes it */
        PSum *k = form_knots(p, depth, c);
        if (k) {
            *c->work += len;
            return k;
        }
    }
    if (len == 0 || fmpz_mpoly_is_fmpz(p, r->ctx))
        return book_form_expanded(p, c);
    Best b = {NULL, len, R_EXPANDED, (size_t)-1, -1};
    *c->work += len;
    if (len < 2)
        return best_take(&b, p, c); /* a monomial: expanded is factored */
    if (budget_late()) /* the caller's deadline (budget.h): no search */
        return best_take(&b, p, c);
    if (depth < CHEAP_FACTOR_DEPTH &&
        (depth == 0 ||
         (*c->work < RENDER_WORK && len <= MAX_FACTOR_TERMS_NESTED))) {
        *c->work += FACTOR_WORK + 20 * len;
        keep_better(&b, book_form_factored(p, depth, c), R_FACTORED, -1, c);
    } else if (depth >= CHEAP_FACTOR_DEPTH) {
        *c->work += 4 * len;
        keep_better(&b, book_form_factored_cheap(p, depth, c), R_FACTORED, -1,
                    c);
    }
    if (depth >= MAX_DEPTH || len > MAX_COLLECT_TERMS || len < 2)
        return best_take(&b, p, c);
    for (slong v = 0; v < r->nvars && *c->work < RENDER_WORK && !budget_late();
         v++) {
        if (fmpz_mpoly_degree_si(p, v, r->ctx) < 1)
            continue;
        *c->work += 2 * len;
        /* the powers first: the Bernstein form (dearer) is then given up
         * against them the sooner (the order does not change the choice:
         * Bernstein wins a tie of leaves and length by its rank) */
        keep_better(&b, book_form_powers(p, v, depth, limit(&b, c), c),
                    R_POWERS, v, c);
        if (book_is_param(c, v))
            keep_better(&b, book_form_bernstein(p, v, depth, limit(&b, c), c),
                        R_BERNSTEIN, v, c);
        slong w = c->K ? book_cos_companion(v, c) : -1;
        if (w >= 0)
            keep_better(&b, book_form_sin2(p, v, w, depth, limit(&b, c), c),
                        R_BERNSTEIN, v, c);
    }
    return best_take(&b, p, c);
}
