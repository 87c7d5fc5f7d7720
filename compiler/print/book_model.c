/*
 * book_model.c - the model of a printed polynomial (book_int.h): sums
 * (PSum) of signed products (PTerm) of atoms (Atom: a variable, 1 - x, a
 * parenthesised sum, a point or a difference of two, |x|), and what every
 * stage of the printer does with them: make, copy and free them, order the
 * atoms of a product (book.h's order: a difference of points, consts, the
 * point, params, functions, then sums; a total order), and count their
 * leaves, the size the forms of a polynomial compete on.
 *
 * In the printer: book_forms.c builds a model for each polynomial,
 * book_write.c writes models as text or LaTeX, book_eq.c puts them
 * together into an equation.  The memo of forms already chosen (BookMemo,
 * shared by a scheme's outputs) is made and cleared here.
 */
#include "compiler/print/book_int.h"

#include <limits.h>
#include <stdlib.h>

#include "base/mem.h"

static void term_init(PTerm *t)
{
    t->neg = 0;
    fmpz_init_set_ui(t->coeff, 1);
    t->n = 0;
    t->a = NULL;
}

static void term_clear(PTerm *t, const Ctx *c)
{
    for (slong i = 0; i < t->n; i++)
        if (t->a[i].kind == AT_SUM)
            book_sum_free(t->a[i].sum, c);
    pc_free(t->a);
    fmpz_clear(t->coeff);
}

PSum *book_sum_new(const Ctx *c)
{
    PSum *s = pc_xcalloc(1, sizeof *s);
    fmpz_mpoly_init(s->poly, c->r->ctx);
    return s;
}

void book_sum_free(PSum *s, const Ctx *c)
{
    if (!s)
        return;
    for (slong i = 0; i < s->n; i++)
        term_clear(&s->t[i], c);
    pc_free(s->t);
    fmpz_mpoly_clear(s->poly, c->r->ctx);
    pc_free(s);
}

PTerm *book_sum_push(PSum *s)
{
    if (s->n == s->alloc) { /* by doubling: an expanded form of 10^5 terms
                               was quadratic in the copies */
        s->alloc = s->alloc ? 2 * s->alloc : 4;
        s->t = pc_xrealloc(s->t, sizeof(PTerm) * (size_t)s->alloc);
    }
    term_init(&s->t[s->n]);
    return &s->t[s->n++];
}

static void term_copy(PTerm *dst, const PTerm *src, const Ctx *c)
{
    dst->neg = src->neg;
    fmpz_set(dst->coeff, src->coeff);
    dst->n = src->n;
    dst->a = pc_xmalloc(sizeof(Atom) * (size_t)(src->n ? src->n : 1));
    for (slong i = 0; i < src->n; i++) {
        dst->a[i] = src->a[i];
        if (src->a[i].kind == AT_SUM)
            dst->a[i].sum = book_sum_copy(src->a[i].sum, c);
    }
}

PSum *book_sum_copy(const PSum *s, const Ctx *c)
{
    PSum *r = book_sum_new(c);
    r->alloc = s->n ? s->n : 1;
    r->t = pc_xmalloc(sizeof(PTerm) * (size_t)r->alloc);
    for (slong i = 0; i < s->n; i++) {
        term_init(&r->t[i]);
        term_copy(&r->t[i], &s->t[i], c);
    }
    r->n = s->n;
    fmpz_mpoly_set(r->poly, s->poly, c->r->ctx);
    r->has_param = s->has_param;
    r->keep_order = s->keep_order;
    return r;
}

void book_memo_clear(Memo *m, const Ctx *c)
{
    for (slong i = 0; i < m->n; i++) {
        fmpz_mpoly_clear(m->e[i].poly, c->r->ctx);
        book_sum_free(m->e[i].sum, c);
    }
    pc_free(m->e);
    m->e = NULL;
    m->n = m->alloc = 0;
    pc_free(m->slot);
    m->slot = NULL;
    for (slong i = 0; i < m->nfac; i++)
        fmpz_mpoly_clear(m->fac + i, c->r->ctx);
    pc_free(m->fac);
    m->fac = NULL;
    m->nfac = m->facalloc = 0;
}

/* appends an atom; no path multiplies two powers of one variable (the
 * factors of a factorisation are distinct, a collected coefficient is free
 * of its variable), so atoms are not merged */
void book_term_push(PTerm *t, Atom a)
{
    t->a = pc_xrealloc(t->a, sizeof(Atom) * (size_t)(t->n + 1));
    t->a[t->n++] = a;
}

int book_is_param(const Ctx *c, slong v)
{
    return v < c->nparams;
}

/* the name to write var^e through: a definition before the one printed
 * whose value is var^k, k dividing e (the largest such k), or NULL */
static const DerivedName *named_for_line(slong var, ulong e, int line,
                                         const Ctx *c)
{
    const DerivedName *best = NULL;
    for (slong i = 0; i < c->nnamed; i++) {
        const DerivedName *nm = &c->named[i];
        if (nm->var == var && nm->line < line && nm->exp <= e &&
            e % nm->exp == 0 && (!best || nm->exp > best->exp))
            best = nm;
    }
    return best;
}

const DerivedName *book_named_for(slong var, ulong e, const Ctx *c)
{
    return named_for_line(var, e, c->line, c);
}

/* the place of an atom in a product: a difference of points, consts (x
 * and 1 - x), the point, params, functions, then parenthesised sums (those
 * free of params first) */
static int atom_class(const Ctx *c, const Atom *a)
{
    switch (a->kind) {
    case AT_VAR:
    case AT_BAR:
        if (book_is_param(c, a->var))
            return 2;
        if (a->kind == AT_VAR && named_for_line(a->var, a->exp, INT_MAX, c))
            return 0; /* a named scalar: with the consts (B*a*t); the
                       * same place wherever it is written by its name
                       * (forms are shared by a scheme's outputs) */
        return a->var < c->nparams + c->nconsts ? 0 : 3;
    case AT_KNOT:
    case AT_ABS: /* last, as the book writes c_k(t)*(t - t_k)*|t - t_k| */
        return 6;
    case AT_POINT:
        return a->point2 ? -1 : 1; /* (A - C)*kp*..., as the book */
    case AT_SUM:
        return a->sum->has_param ? 5 : 4;
    }
    return 6;
}

static int atom_cmp(const Ctx *c, const Atom *a, const Atom *b)
{
    int ka = atom_class(c, a), kb = atom_class(c, b);
    if (ka != kb)
        return ka < kb ? -1 : 1;
    if (a->kind == AT_VAR || a->kind == AT_BAR || a->kind == AT_ABS ||
        a->kind == AT_KNOT) {
        if (a->var != b->var)
            return a->var < b->var ? -1 : 1;
        if (a->kind != b->kind) /* (t - 1)*abs(t - 1): the knot first */
            return a->kind == AT_KNOT   ? -1
                   : b->kind == AT_KNOT ? 1
                   : a->kind < b->kind  ? -1
                                        : 1;
        return 0;
    }
    if (a->kind == AT_SUM) {
        slong da = fmpz_mpoly_total_degree_si(a->sum->poly, c->r->ctx);
        slong db = fmpz_mpoly_total_degree_si(b->sum->poly, c->r->ctx);
        if (da != db)
            return da < db ? -1 : 1;
        slong la = fmpz_mpoly_length(a->sum->poly, c->r->ctx);
        slong lb = fmpz_mpoly_length(b->sum->poly, c->r->ctx);
        if (la != lb)
            return la < lb ? -1 : 1;
        int k = fmpz_mpoly_cmp(a->sum->poly, b->sum->poly, c->r->ctx);
        if (k)
            return k;
        return a->exp < b->exp ? -1 : a->exp > b->exp;
    }
    return 0;
}

/* a total order: equal keys are equal atoms, so the result does not depend
 * on the sort (an insertion sort: products have a few atoms, and no global
 * state, so printing is thread-safe) */
void book_term_sort(PTerm *t, const Ctx *c)
{
    for (slong i = 1; i < t->n; i++) {
        Atom x = t->a[i];
        slong j = i;
        for (; j > 0 && atom_cmp(c, &t->a[j - 1], &x) > 0; j--)
            t->a[j] = t->a[j - 1];
        t->a[j] = x;
    }
}

/* moves every atom and the coefficient of src into dst (src is left
 * empty) */
void book_term_absorb(PTerm *dst, PTerm *src)
{
    fmpz_mul(dst->coeff, dst->coeff, src->coeff);
    dst->neg ^= src->neg;
    for (slong i = 0; i < src->n; i++)
        book_term_push(dst, src->a[i]);
    pc_free(src->a);
    src->a = NULL;
    src->n = 0;
}

/* ---- measuring --------------------------------------------------------- */

static slong term_leaves(const PTerm *t)
{
    slong n = 1;
    for (slong i = 0; i < t->n; i++)
        if (t->a[i].kind == AT_SUM)
            n += book_sum_leaves(t->a[i].sum) - 1;
    return n;
}

slong book_sum_leaves(const PSum *s)
{
    slong n = 0;
    for (slong i = 0; i < s->n; i++)
        n += term_leaves(&s->t[i]);
    return n ? n : 1;
}

/* negates every term of s (and its poly) */
void book_sum_neg(PSum *s, const Ctx *c)
{
    for (slong i = 0; i < s->n; i++)
        s->t[i].neg ^= 1;
    fmpz_mpoly_neg(s->poly, s->poly, c->r->ctx);
}

void book_sum_finish(PSum *s, const fmpz_mpoly_t p, const Ctx *c)
{
    fmpz_mpoly_set(s->poly, p, c->r->ctx);
    s->has_param = 0;
    for (slong v = 0; v < c->nparams && !s->has_param; v++)
        s->has_param = fmpz_mpoly_degree_si(p, v, c->r->ctx) > 0;
    for (slong i = 0; i < s->n; i++)
        book_term_sort(&s->t[i], c);
}

BookMemo *book_memo_new(void)
{
    return pc_xcalloc(1, sizeof(Memo));
}

void book_memo_free(BookMemo *m, const Derived *d)
{
    if (!m)
        return;
    Ctx c = {0};
    c.r = &d->ring;
    book_memo_clear(m, &c);
    pc_free(m);
}
