/*
 * book_eq.c - writing one output, the end of the printer (book.h): a
 * scalar as num/den, a point or vector equation over its one denominator
 * (items, each a point times its numerator, a factor common to every
 * numerator in front, the signs of book.h's rules), the same relative to
 * an origin point, and the whole display: "M = ..." in text, \[ ... \] or
 * a multline* environment broken between its terms in LaTeX.  Each
 * polynomial's form comes from book_forms.c, each un-rationalised
 * alternative from book_unroot.c; the public book_rhs and book_output are
 * here.
 */
#include "compiler/print/book_int.h"

#include <stdlib.h>
#include <string.h>

#include "base/budget.h"
#include "base/mem.h"
#include "compiler/print/absform.h"
#include "compiler/print/latexbreak.h"

/* ---- equations ------------------------------------------------------------
 */

/* A numerator over the denominator: its sum, the item's atoms around the
 * point (or the point alone) */
/* a sum whose first term is negative, made to lead with a positive term
 * with the fewest minus signs: negated (1 for s's positive terms: returns
 * 1, the caller writes the minus) or its leading negative terms moved to
 * the end (s's negative terms: -c + a*cos(phi) as a*cos(phi) - c, not
 * -(c - a*cos(phi)); -1 + t + t^2 as t + t^2 - 1); 0 otherwise */
/* s's leading negative terms moved to its end (t + t^2 - 1 for -1 + t +
 * t^2) when it has no more negative terms than positive ones: 1 when
 * moved */
static int sum_rotate(PSum *s)
{
    if (s->n == 0 || !s->t[0].neg || s->keep_order)
        return 0;
    slong pos = 0, first = -1;
    for (slong i = 0; i < s->n; i++)
        if (!s->t[i].neg) {
            pos++;
            if (first < 0)
                first = i;
        }
    if (first <= 0 || s->n - pos > pos)
        return 0;
    PTerm *head = pc_xmalloc(sizeof(PTerm) * (size_t)first);
    memcpy(head, s->t, sizeof(PTerm) * (size_t)first);
    memmove(s->t, s->t + first, sizeof(PTerm) * (size_t)(s->n - first));
    memcpy(s->t + s->n - first, head, sizeof(PTerm) * (size_t)first);
    pc_free(head);
    return 1;
}

static int all_negative(const PSum *s)
{
    for (slong i = 0; i < s->n; i++)
        if (!s->t[i].neg)
            return 0;
    return s->n > 0;
}

/* 1 when term t has an |x| (or the x written beside it) */
static int term_has_abs(const PTerm *t, const Ctx *c)
{
    for (slong i = 0; i < t->n; i++)
        if (t->a[i].kind == AT_KNOT || t->a[i].kind == AT_ABS ||
            (t->a[i].kind == AT_VAR && c->is_abs && c->is_abs[t->a[i].var]))
            return 1;
    return 0;
}

/* a knot-collected sum whose free part (its terms without |x|, first) is
 * all negative, followed by a positive term: the free part moved to the
 * end, abs(t - 1) + abs(t - 3) - 2, not -(2 - abs(t - 1) - abs(t - 3));
 * a free part with positive terms stays whole (the sum is negated
 * instead); 1 when moved */
static int free_part_last(PSum *s, const Ctx *c)
{
    slong k = 0;
    while (k < s->n && s->t[k].neg && !term_has_abs(&s->t[k], c))
        k++;
    if (k == 0 || k == s->n || s->t[k].neg || !term_has_abs(&s->t[k], c))
        return 0;
    PTerm *head = pc_xmalloc(sizeof(PTerm) * (size_t)k);
    memcpy(head, s->t, sizeof(PTerm) * (size_t)k);
    memmove(s->t, s->t + k, sizeof(PTerm) * (size_t)(s->n - k));
    memcpy(s->t + s->n - k, head, sizeof(PTerm) * (size_t)k);
    pc_free(head);
    return 1;
}

static int sum_lead(PSum *s, const Ctx *c)
{
    if (s->n == 0 || !s->t[0].neg || sum_rotate(s) ||
        (s->keep_order && free_part_last(s, c)))
        return 0;
    book_sum_neg(s, c);
    return 1;
}

static void push_item(PSum *eq, const fmpz_mpoly_t num, Atom pt, const Ctx *c)
{
    PSum *s = book_render(num, 0, c);
    PTerm *t = book_sum_push(eq);
    if (s->n == 1) {
        book_term_absorb(t, &s->t[0]);
        book_sum_free(s, c);
    } else {
        if (sum_lead(s, c))
            t->neg = 1;
        book_term_push(t, (Atom){AT_SUM, -1, s, NULL, NULL, 1});
    }
    book_term_push(t, pt);
    book_term_sort(t, c);
}

/* the denominator's form with its first term positive; *flip = 1 when
 * that negated it */
static PSum *render_den(const fmpz_mpoly_t den, const Ctx *c, int *flip)
{
    PSum *d = book_render(den, 0, c);
    *flip = d->t[0].neg;
    if (*flip)
        book_sum_neg(d, c);
    return d;
}

/* writes items / den: an all-minus numerator as -(...)/den */
static void put_quotient(StrBuf *b, PSum *items, const PSum *den, const Ctx *c)
{
    /* and a sum in the order of its knots that starts with a minus:
     * -(abs(t) - abs(t - 1) - ...)/2, unless the minus is its free part's */
    int minus =
        all_negative(items) || (items->keep_order && items->n > 1 &&
                                items->t[0].neg && !free_part_last(items, c));
    if (minus)
        for (slong i = 0; i < items->n; i++)
            items->t[i].neg ^= 1;
    else if (den)
        sum_rotate(items); /* (a*cos(phi) - c)/d, not (-c + a*cos(phi))/d */
    StrBuf n = {0};
    book_put_sum(&n, items, c);
    if (minus)
        sb_puts(b, "-");
    if (!den)
        sb_puts(b, n.s);
    else
        book_put_frac(b, n.s, (int)items->n, den, c);
    pc_free(n.s);
}

/* num/den as a scalar */
static void rhs_frac(StrBuf *b, const fmpz_mpoly_t xnum,
                     const fmpz_mpoly_t xden, const Ctx *c)
{
    const Ring *r = c->r;
    int flip = 0;
    PSum *den = NULL;
    fmpz_mpoly_t num;
    fmpz_mpoly_init(num, r->ctx);
    fmpz_mpoly_set(num, xnum, r->ctx);
    if (!fmpz_mpoly_is_one(xden, r->ctx)) {
        den = render_den(xden, c, &flip);
        if (flip)
            fmpz_mpoly_neg(num, num, r->ctx);
    }
    PSum *s = book_render(num, 0, c);
    if (!den)
        book_put_sum(b, s, c);
    else
        put_quotient(b, s, den, c);
    book_sum_free(s, c);
    book_sum_free(den, c);
    fmpz_mpoly_clear(num, r->ctx);
}

/* the length of what put(b, num, den, c) writes in text */
typedef void (*PutFrac)(StrBuf *b, const fmpz_mpoly_t num,
                        const fmpz_mpoly_t den, const void *arg, const Ctx *c);

/* puts num/den, or the un-rationalised form whose text is shortest */
static void put_best(StrBuf *b, const fmpz_mpoly_t num, const fmpz_mpoly_t den,
                     const fmpz_mpoly_struct *const *H, slong nh, PutFrac put,
                     const void *arg, const Ctx *c)
{
    Cand *cs;
    const fmpz_mpoly_struct *np = num;
    slong nc = book_unroot_cands(&cs, &np, 1, den, H, nh, c);
    slong best = -1;
    if (nc > 0) {
        Ctx t = *c;
        t.latex = 0;
        StrBuf m = {0};
        put(&m, num, den, arg, &t);
        size_t bl = m.len;
        for (slong i = 0; i < nc; i++) {
            m.len = 0;
            put(&m, cs[i].num, cs[i].den, arg, &t);
            if (m.len < bl) {
                bl = m.len;
                best = i;
            }
        }
        pc_free(m.s);
    }
    if (best < 0)
        put(b, num, den, arg, c);
    else
        put(b, cs[best].num, cs[best].den, arg, c);
    for (slong i = 0; i < nc; i++)
        book_cand_clear(&cs[i], c);
    pc_free(cs);
}

static void put_scalar_frac(StrBuf *b, const fmpz_mpoly_t num,
                            const fmpz_mpoly_t den, const void *arg,
                            const Ctx *c)
{
    (void)arg;
    rhs_frac(b, num, den, c);
}

static void rhs_scalar(StrBuf *b, const RatFun x, const Ctx *c)
{
    put_best(b, x->num, x->den, NULL, 0, put_scalar_frac, NULL, c);
}

/* one item of the origin form: " + (A - C)*n/d" (first: no " + ") */
typedef struct OriginItem {
    const char *point, *origin;
    int first;
} OriginItem;

static void put_origin_item(StrBuf *b, const fmpz_mpoly_t wnum,
                            const fmpz_mpoly_t wden, const void *arg,
                            const Ctx *c)
{
    const OriginItem *it = arg;
    const Ring *r = c->r;
    int flip = 0;
    PSum *den =
        fmpz_mpoly_is_one(wden, r->ctx) ? NULL : render_den(wden, c, &flip);
    fmpz_mpoly_t num;
    fmpz_mpoly_init(num, r->ctx);
    if (flip)
        fmpz_mpoly_neg(num, wnum, r->ctx);
    else
        fmpz_mpoly_set(num, wnum, r->ctx);
    Atom pa = {AT_POINT, -1, NULL, it->point, it->origin, 1};
    PSum *one = book_sum_new(c);
    push_item(one, num, pa, c);
    int neg = one->t[0].neg;
    one->t[0].neg = 0;
    sb_puts(b, it->first ? (neg ? "-" : "") : (neg ? " - " : " + "));
    StrBuf n = {0};
    book_put_term(&n, &one->t[0], c);
    if (den && c->latex) {
        /* (A - C) \frac{n}{d}: the point outside the fraction */
        StrBuf m = {0};
        PSum *s = book_render(num, 0, c);
        sum_lead(s, c);
        book_put_sum(&m, s, c);
        book_sum_free(s, c);
        book_put_atom(b, &pa, c);
        sb_puts(b, " \\frac{");
        sb_puts(b, m.s);
        sb_puts(b, "}{");
        book_put_sum(b, den, c);
        sb_puts(b, "}");
        pc_free(m.s);
    } else {
        sb_puts(b, n.s);
        if (den) {
            int pd =
                den->n > 1 || den->t[0].n + !fmpz_is_one(den->t[0].coeff) > 1;
            sb_puts(b, pd ? "/(" : "/");
            book_put_sum(b, den, c);
            if (pd)
                sb_puts(b, ")");
        }
    }
    pc_free(n.s);
    book_sum_free(one, c);
    book_sum_free(den, c);
    fmpz_mpoly_clear(num, r->ctx);
}

static void rhs_origin(StrBuf *b, const Derived *d, const DerivedOutput *o,
                       slong origin, const Ctx *c)
{
    int first = 1;
    slong nh = o->eq->len;
    const fmpz_mpoly_struct **H = pc_xmalloc(sizeof(*H) * (size_t)(nh + 1));
    for (slong i = 0; i < nh; i++)
        H[i] = o->w[i].num;
    for (slong i = 0; i < o->eq->len; i++) {
        slong pt = o->eq->terms[i].point;
        if (pt == origin)
            continue;
        OriginItem it = {d->points[pt], d->points[origin], first};
        put_best(b, o->w[i].num, o->w[i].den, H, nh, put_origin_item, &it, c);
        first = 0;
    }
    pc_free(H);
    if (o->kind == KIND_POINT) {
        sb_puts(b, first ? "" : " + ");
        book_put_point(b, d->points[origin], c);
    } else if (first) {
        sb_puts(b, "0");
    }
}

/* the equation over its one denominator: items (each a point times its
 * numerator), the denominator (NULL: 1), a common factor of the numerators
 * (NULL: none) */
typedef struct EqParts {
    PSum *items;
    PSum *den;
    PSum *common;
} EqParts;

static void eq_parts(EqParts *P, const Derived *d, const DerivedOutput *o,
                     const PointEqStruct *eq, const Ctx *c)
{
    const Ring *r = c->r;
    int flip = 0;
    P->den = fmpz_mpoly_is_one(eq->den, r->ctx) ? NULL
                                                : render_den(eq->den, c, &flip);
    /* a factor common to every numerator (a vector's: a point's is 1) */
    fmpz_mpoly_t g, q;
    fmpz_mpoly_init(g, r->ctx);
    fmpz_mpoly_init(q, r->ctx);
    for (slong i = 0; i < eq->len; i++)
        if (!fmpz_mpoly_gcd(g, g, eq->terms[i].num, r->ctx))
            fmpz_mpoly_one(g, r->ctx);
    if (eq->len < 1 || fmpz_mpoly_is_zero(g, r->ctx))
        fmpz_mpoly_one(g, r->ctx);
    P->common = NULL;
    if (!fmpz_mpoly_is_one(g, r->ctx) && eq->len > 1) {
        P->common = book_render(g, 0, c);
        if (P->common->t[0].neg) { /* keep g's first term positive */
            book_sum_neg(P->common, c);
            fmpz_mpoly_neg(g, g, r->ctx);
        }
    } else {
        fmpz_mpoly_one(g, r->ctx);
    }
    P->items = book_sum_new(c);
    char *used = pc_xcalloc((size_t)eq->len + 1, 1);
    for (slong i = 0; i < eq->len; i++) {
        if (used[i])
            continue;
        fmpz_mpoly_divides(q, eq->terms[i].num, g, r->ctx);
        if (flip)
            fmpz_mpoly_neg(q, q, r->ctx);
        Atom pt = {AT_POINT, -1, NULL, d->points[eq->terms[i].point], NULL, 1};
        /* a vector's opposite weights: one difference */
        for (slong j = i + 1; j < eq->len && o->kind == KIND_VECTOR; j++) {
            fmpz_mpoly_t s;
            fmpz_mpoly_init(s, r->ctx);
            fmpz_mpoly_add(s, eq->terms[i].num, eq->terms[j].num, r->ctx);
            int opp = !used[j] && fmpz_mpoly_is_zero(s, r->ctx);
            fmpz_mpoly_clear(s, r->ctx);
            if (opp) {
                used[j] = 1;
                pt.point2 = d->points[eq->terms[j].point];
                /* the positive one first: (C - A), not -(A - C) */
                PSum *probe = book_render(q, 0, c);
                if (probe->t[0].neg) {
                    pt.point2 = pt.point;
                    pt.point = d->points[eq->terms[j].point];
                    fmpz_mpoly_neg(q, q, r->ctx);
                }
                book_sum_free(probe, c);
                break;
            }
        }
        push_item(P->items, q, pt, c);
    }
    pc_free(used);
    fmpz_mpoly_clear(q, r->ctx);
    fmpz_mpoly_clear(g, r->ctx);
}

static void eq_parts_clear(EqParts *P, const Ctx *c);
static void rhs_equation(StrBuf *b, const EqParts *P, const Ctx *c);

/* the text length of o's equation eq as printed */
static size_t eq_text_len(const Derived *d, const DerivedOutput *o,
                          const PointEqStruct *eq, const Ctx *c)
{
    Ctx t = *c;
    t.latex = 0;
    EqParts P;
    eq_parts(&P, d, o, eq, &t);
    StrBuf b = {0};
    rhs_equation(&b, &P, &t);
    eq_parts_clear(&P, &t);
    size_t n = b.len;
    pc_free(b.s);
    return n;
}

/* the form of o's equation to print: o->eq, or its un-rationalised form
 * (*tmp, the points of o->eq over a denominator with the root) when that
 * is shorter; eq_form_clear(tmp, result) after */
static const PointEqStruct *eq_form(PointEqStruct *tmp, const Derived *d,
                                    const DerivedOutput *o, const Ctx *c)
{
    const PointEqStruct *eq = o->eq;
    tmp->terms = NULL;
    tmp->len = 0;
    slong n = eq->len;
    const fmpz_mpoly_struct **N = pc_xmalloc(sizeof(*N) * (size_t)(n + 1));
    for (slong i = 0; i < n; i++)
        N[i] = eq->terms[i].num;
    Cand *cs;
    slong nc = book_unroot_cands(&cs, N, n, eq->den, NULL, 0, c);
    pc_free(N);
    if (nc == 0)
        return eq;
    size_t best_len = eq_text_len(d, o, eq, c);
    slong best = -1;
    for (slong k = 0; k < nc; k++) {
        PointEqStruct e;
        e.len = n;
        e.alloc = n;
        e.terms = pc_xmalloc(sizeof(PtTerm) * (size_t)(n ? n : 1));
        for (slong i = 0; i < n; i++) {
            e.terms[i].point = eq->terms[i].point;
            e.terms[i].num[0] = cs[k].num[i]; /* borrowed: read only */
        }
        e.den[0] = cs[k].den[0];
        size_t len = eq_text_len(d, o, &e, c);
        pc_free(e.terms);
        if (len < best_len) {
            best_len = len;
            best = k;
        }
    }
    const PointEqStruct *res = eq;
    if (best >= 0) {
        /* the chosen one moves into tmp */
        tmp->len = tmp->alloc = n;
        tmp->terms = pc_xmalloc(sizeof(PtTerm) * (size_t)(n ? n : 1));
        for (slong i = 0; i < n; i++) {
            tmp->terms[i].point = eq->terms[i].point;
            fmpz_mpoly_init(tmp->terms[i].num, c->r->ctx);
            fmpz_mpoly_swap(tmp->terms[i].num, cs[best].num + i, c->r->ctx);
        }
        fmpz_mpoly_init(tmp->den, c->r->ctx);
        fmpz_mpoly_swap(tmp->den, cs[best].den, c->r->ctx);
        res = tmp;
    }
    for (slong k = 0; k < nc; k++)
        book_cand_clear(&cs[k], c);
    pc_free(cs);
    return res;
}

static void eq_form_clear(PointEqStruct *tmp, const PointEqStruct *used,
                          const Ctx *c)
{
    if (used != tmp)
        return;
    for (slong i = 0; i < tmp->len; i++)
        fmpz_mpoly_clear(tmp->terms[i].num, c->r->ctx);
    pc_free(tmp->terms);
    fmpz_mpoly_clear(tmp->den, c->r->ctx);
}

static void eq_parts_clear(EqParts *P, const Ctx *c)
{
    book_sum_free(P->items, c);
    book_sum_free(P->den, c);
    book_sum_free(P->common, c);
}

static void put_common(StrBuf *b, const PSum *common, const Ctx *c)
{
    if (!common)
        return;
    if (common->n == 1) {
        book_put_term(b, &common->t[0], c);
    } else {
        sb_puts(b, c->latex ? "\\left(" : "(");
        book_put_sum(b, common, c);
        sb_puts(b, c->latex ? "\\right)" : ")");
    }
    sb_puts(b, c->latex ? " " : "*");
}

static void rhs_equation(StrBuf *b, const EqParts *P, const Ctx *c)
{
    if (P->items->n == 0) {
        sb_puts(b, "0");
        return;
    }
    int minus = all_negative(P->items);
    if (minus)
        for (slong i = 0; i < P->items->n; i++)
            P->items->t[i].neg = 0;
    if (minus)
        sb_puts(b, "-");
    StrBuf n = {0};
    book_put_sum(&n, P->items, c);
    if (P->common) {
        put_common(b, P->common, c);
        if (!P->den) {
            int paren = P->items->n > 1;
            sb_puts(b, paren ? (c->latex ? "\\left(" : "(") : "");
            sb_puts(b, n.s);
            sb_puts(b, paren ? (c->latex ? "\\right)" : ")") : "");
        } else {
            book_put_frac(b, n.s, (int)P->items->n, P->den, c);
        }
    } else if (!P->den) {
        sb_puts(b, n.s);
    } else {
        book_put_frac(b, n.s, (int)P->items->n, P->den, c);
    }
    if (minus)
        for (slong i = 0; i < P->items->n; i++)
            P->items->t[i].neg = 1;
    pc_free(n.s);
}

static void ctx_init(Ctx *c, const Derived *d, const BookOptions *opt,
                     long *work, Memo *memo)
{
    *work = 0;
    c->work = work;
    memset(memo, 0, sizeof *memo);
    c->memo = opt->memo ? opt->memo : memo; /* shared by a scheme's outputs */
    c->r = &d->ring;
    c->nparams = d->nparams;
    c->nconsts = d->nconsts;
    c->latex = opt->latex;
    c->K = d->kernels;
    c->has_sign = absform_any(d->kernels);
    c->is_abs = NULL;
    c->mode = 0;
    c->named = d->named;
    c->nnamed = d->nnamed;
    c->line = 0; /* set per output: no names until then */
    c->exhaustive = opt->exhaustive;
}

static void rhs_into(StrBuf *b, const Derived *d, const DerivedOutput *o,
                     const BookOptions *opt, const Ctx *c)
{
    if (o->kind == KIND_SCALAR) {
        rhs_scalar(b, o->scalar, c);
    } else if (opt->origin >= 0) {
        rhs_origin(b, d, o, opt->origin, c);
    } else {
        PointEqStruct tmp;
        const PointEqStruct *eq = eq_form(&tmp, d, o, c);
        EqParts P;
        eq_parts(&P, d, o, eq, c);
        rhs_equation(b, &P, c);
        eq_parts_clear(&P, c);
        eq_form_clear(&tmp, eq, c);
    }
}

char *book_rhs(const Derived *d, const DerivedOutput *o, const BookOptions *opt)
{
    Ctx c;
    long work;
    Memo memo;
    ctx_init(&c, d, opt, &work, &memo);
    c.line = o->line;
    StrBuf b = {0};
    rhs_into(&b, d, o, opt, &c);
    book_memo_clear(&memo, &c);
    return sb_take(&b);
}

/* ---- whole outputs ---------------------------------------------------------
 */

static void put_lhs(StrBuf *b, const DerivedOutput *o, const Ctx *c)
{
    if (!c->latex) {
        sb_puts(b, o->name);
        return;
    }
    if (o->diff_of) {
        sb_puts(b, "\\frac{\\mathrm{d}");
        book_put_exp(b, (ulong)o->diff_order, c);
        poly_print_latex_name(b, o->diff_of);
        sb_puts(b, "}{\\mathrm{d}");
        poly_print_latex_name(b, o->diff_var);
        book_put_exp(b, (ulong)o->diff_order, c);
        sb_puts(b, "}");
        return;
    }
    poly_print_latex_name(b, o->name);
}

/* one line of a multline* (and the line break after it unless last),
 * itself broken where it is wider than the page (latexbreak.h); not past
 * the caller's deadline (budget.h: the text is discarded, and breaking it
 * is a pass over all of it) */
static void put_line(StrBuf *b, const char *line, int last)
{
    if (!budget_late() && latex_width(line, strlen(line)) > LATEX_LINE_UNITS) {
        char **ls;
        size_t n = latex_break(&ls, line, LATEX_LINE_UNITS);
        for (size_t i = 0; i < n; i++) {
            sb_puts(b, ls[i]);
            if (i + 1 < n)
                sb_puts(b, " \\\\\n");
        }
        latex_lines_free(ls, n);
    } else {
        sb_puts(b, line);
    }
    sb_puts(b, last ? "\n" : " \\\\\n");
}

/* LaTeX lines of at most width columns: "lhs = \frac{1}{den} \Bigl(" then
 * the items, broken before a + or -, then "\Bigr)" */
static void put_multline(StrBuf *b, const StrBuf *lhs, const EqParts *P,
                         const Ctx *c, int width)
{
    sb_puts(b, "\\begin{multline*}\n");
    StrBuf line = {0};
    sb_puts(&line, lhs->s);
    sb_puts(&line, " = ");
    int minus = all_negative(P->items);
    if (minus)
        sb_puts(&line, "-");
    int small = P->common && P->common->n == 1; /* \frac{2}{d} */
    if (!small)
        put_common(&line, P->common, c);
    if (P->den || small) {
        sb_puts(&line, "\\frac{");
        if (small)
            book_put_term(&line, &P->common->t[0], c);
        else
            sb_puts(&line, "1");
        sb_puts(&line, "}{");
        if (P->den)
            book_put_sum(&line, P->den, c);
        else
            sb_puts(&line, "1");
        sb_puts(&line, "} ");
    }
    sb_puts(&line, "\\Bigl(");
    for (slong i = 0; i < P->items->n; i++) {
        StrBuf item = {0};
        int neg = P->items->t[i].neg && !minus;
        if (i > 0 || neg)
            sb_puts(&item, i == 0 ? "-" : neg ? "- " : "+ ");
        book_put_term(&item, &P->items->t[i], c);
        if (i > 0 && (int)(line.len + item.len + 1) > width) {
            put_line(b, line.s, 0);
            line.len = 0;
            line.s[0] = '\0';
        } else if (i > 0) {
            sb_puts(&line, " ");
        }
        sb_puts(&line, item.s);
        pc_free(item.s);
    }
    sb_puts(&line, "\\Bigr)");
    put_line(b, line.s, 1);
    sb_puts(b, "\\end{multline*}\n");
    pc_free(line.s);
}

char *book_output(const Derived *d, const DerivedOutput *o,
                  const BookOptions *opt)
{
    Ctx c;
    long work;
    Memo memo;
    ctx_init(&c, d, opt, &work, &memo);
    c.line = o->line;
    StrBuf b = {0}, lhs = {0}, rb = {0};
    put_lhs(&lhs, o, &c);
    int width = opt->width > 0 ? opt->width : 80;
    if (opt->latex && o->kind != KIND_SCALAR && opt->origin < 0) {
        /* the parts of the equation, once: its width (a fraction is as
         * wide as the longer of its two lines), then its lines */
        PointEqStruct tmp;
        const PointEqStruct *eq = eq_form(&tmp, d, o, &c);
        EqParts P;
        eq_parts(&P, d, o, eq, &c);
        StrBuf n = {0}, dn = {0}, cm = {0};
        book_put_sum(&n, P.items, &c);
        if (P.den)
            book_put_sum(&dn, P.den, &c);
        put_common(&cm, P.common, &c);
        size_t wide = lhs.len + 3 + cm.len + (n.len > dn.len ? n.len : dn.len);
        pc_free(n.s);
        pc_free(dn.s);
        pc_free(cm.s);
        if ((int)wide > width && P.items->n > 1) {
            put_multline(&b, &lhs, &P, &c, width);
            eq_parts_clear(&P, &c);
            eq_form_clear(&tmp, eq, &c);
            book_memo_clear(&memo, &c);
            pc_free(lhs.s);
            return sb_take(&b);
        }
        rhs_equation(&rb, &P, &c); /* on one line */
        eq_parts_clear(&P, &c);
        eq_form_clear(&tmp, eq, &c);
    } else {
        rhs_into(&rb, d, o, opt, &c);
    }
    char *rhs = sb_take(&rb);
    if (opt->latex) {
        StrBuf eq = {0};
        sb_puts(&eq, lhs.s);
        sb_puts(&eq, " = ");
        sb_puts(&eq, rhs);
        if (latex_width(eq.s, eq.len) > LATEX_LINE_UNITS) {
            /* wider than the page: broken (weights, scalars too) */
            sb_puts(&b, "\\begin{multline*}\n");
            put_line(&b, eq.s, 1);
            sb_puts(&b, "\\end{multline*}\n");
        } else {
            sb_puts(&b, "\\[ ");
            sb_puts(&b, eq.s);
            sb_puts(&b, " \\]\n");
        }
        pc_free(eq.s);
    } else {
        sb_puts(&b, lhs.s);
        sb_puts(&b, " = ");
        sb_puts(&b, rhs);
        sb_puts(&b, o->kind == KIND_VECTOR ? "    (vector)\n" : "\n");
    }
    book_memo_clear(&memo, &c);
    pc_free(rhs);
    pc_free(lhs.s);
    return sb_take(&b);
}

slong book_test_leaves(const Derived *d, const fmpz_mpoly_t p, int depth,
                       slong *lower)
{
    BookOptions opt = {.origin = -1};
    Ctx c;
    long work;
    Memo memo;
    ctx_init(&c, d, &opt, &work, &memo);
    lower[0] = book_leaves_lower(p, depth, &c);
    PSum *s = book_render(p, depth, &c);
    slong n = book_sum_leaves(s);
    lower[1] = book_leaves_lower(p, depth, &c);
    book_sum_free(s, &c);
    book_memo_clear(&memo, &c);
    return n;
}
