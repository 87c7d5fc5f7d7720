/*
 * book_write.c - models written out (book_int.h), as text or LaTeX: names
 * (subscripts, Greek letters, \mathit words; book.h's rule), variables and
 * the scheme's named powers, kernels as the book writes them (sqrt(X),
 * \sin^{2}\varphi), |x|, products, sums and a fraction.
 *
 * Nothing here chooses a form, with one exception: a kernel's argument is
 * written in its best form (book_forms.c) or expanded as kernel.c named
 * it, whichever text is shorter.  In the printer: after book_forms.c has
 * made the model of each polynomial, for book_eq.c's equations.
 */
#include "compiler/print/book_int.h"

#include <ctype.h>
#include <stdlib.h>
#include <string.h>

#include "base/budget.h"
#include "base/mem.h"
#include "compiler/print/absform.h"

/* ---- names ------------------------------------------------------------ */

char *book_latex_name(const char *name)
{
    StrBuf b = {0};
    poly_print_latex_name(&b, name);
    return sb_take(&b);
}

/* ---- writing ------------------------------------------------------------ */

static void put_var(StrBuf *b, slong v, const Ctx *c)
{
    const Ring *r = c->r;
    if (c->latex && r->latex && r->latex[v])
        sb_puts(b, r->latex[v]);
    else if (c->latex)
        poly_print_latex_name(b, r->names[v]);
    else
        sb_puts(b, r->names[v]);
}

void book_put_point(StrBuf *b, const char *p, const Ctx *c)
{
    if (c->latex)
        poly_print_latex_name(b, p);
    else
        sb_puts(b, p);
}

void book_put_exp(StrBuf *b, ulong e, const Ctx *c)
{
    if (e <= 1)
        return;
    sb_puts(b, c->latex ? "^{" : "^");
    sb_ulong(b, e);
    if (c->latex)
        sb_puts(b, "}");
}

/* the part of a kernel's text between open and close (its argument as
 * kernel.c wrote it: expanded), malloc'd, or NULL */
static char *inner_text(const char *name, const char *open, const char *close)
{
    const char *o = strstr(name, open);
    size_t n = strlen(name), lc = strlen(close);
    if (!o || n < lc || strcmp(name + n - lc, close) != 0)
        return NULL;
    const char *a = o + strlen(open), *e = name + n - lc;
    if (e < a)
        return NULL;
    return pc_xstrndup(a, (size_t)(e - a));
}

/* s led by its first positive term (sqrt(a^2 - b^2), not sqrt(-b^2 +
 * a^2)) */
static void arg_lead(PSum *s)
{
    slong i = 0;
    while (i < s->n && s->t[i].neg)
        i++;
    if (i > 0 && i < s->n) {
        PTerm t = s->t[i];
        memmove(s->t + 1, s->t, sizeof(PTerm) * (size_t)i);
        s->t[0] = t;
    }
}

/* a kernel's argument x: its best form (expanded: its terms only), a
 * positive term first (sqrt(a^2 - b^2), not sqrt(-b^2 + a^2)) */
static void put_arg(StrBuf *b, const RatFun x, int expanded, const Ctx *c)
{
    PSum *s =
        expanded ? book_form_expanded(x->num, c) : book_render(x->num, 0, c);
    arg_lead(s);
    if (fmpz_mpoly_is_one(x->den, c->r->ctx)) {
        book_put_sum(b, s, c);
        book_sum_free(s, c);
        return;
    }
    /* a quotient: both parts lead with a positive term, as written
     * (sqrt((rho^2 - b^2)/(a^2 - b^2))) */
    PSum *d =
        expanded ? book_form_expanded(x->den, c) : book_render(x->den, 0, c);
    arg_lead(d);
    StrBuf n = {0};
    book_put_sum(&n, s, c);
    book_put_frac(b, n.s, (int)s->n, d, c);
    pc_free(n.s);
    book_sum_free(d, c);
    book_sum_free(s, c);
}

/* the argument of kernel k in its best form (book_forms.c), or expanded as
 * kernel.c names it when that is shorter in text: sqrt(a^2*sin(phi)^2 +
 * b^2*cos(phi)^2) for sqrt(a^2*sin(phi)^2 - b^2*sin(phi)^2 + b^2) */
static char *kernel_arg(const Kernel *k, const char *open, const char *close,
                        const Ctx *c)
{
    char *own = inner_text(k->name, open, close);
    if (!own)
        return NULL;
    Ctx t = *c;
    t.latex = 0;
    t.is_abs = NULL;
    t.mode = 0;
    /* past the caller's deadline (budget.h), which discards the text: the
     * name as kernel.c wrote it (in LaTeX too), with no rendering, which
     * doubles at each level of nested functions (a tower of 10 sin(x) +
     * cos(i*x) took a minute in LaTeX) */
    if (budget_late())
        return own;
    StrBuf bk = {0};
    put_arg(&bk, k->arg, 0, &t);
    int book = bk.len < strlen(own); /* ties: as kernel.c named it */
    if (!c->latex) {
        if (book) {
            pc_free(own);
            return sb_take(&bk);
        }
        pc_free(bk.s);
        return own;
    }
    pc_free(own);
    pc_free(bk.s);
    t.latex = 1;
    StrBuf lb = {0};
    put_arg(&lb, k->arg, !book, &t);
    return sb_take(&lb);
}

/* kernel k to the power e, as the book writes it: sqrt(X) with X in its
 * best form; in LaTeX \sin^{2}\varphi (a one-name argument without
 * parentheses, the power on the function's name), \sqrt{X}^{2} */
static int put_kernel(StrBuf *b, const Kernel *k, ulong e, const Ctx *c)
{
    const char *const *lx = kernel_fn_latex;
    char *a;
    if (k->fn == KF_SQRT) {
        a = kernel_arg(k, "sqrt(", ")", c);
        if (!a)
            return 0;
        sb_puts(b, c->latex ? "\\sqrt{" : "sqrt(");
        sb_puts(b, a);
        sb_puts(b, c->latex ? "}" : ")");
        book_put_exp(b, e, c);
        pc_free(a);
        return 1;
    }
    /* the functions with an operator name; sign has its own form */
    if (k->fn >= KF_COUNT || !lx[k->fn] || k->fn == KF_SIGN)
        return 0;
    char open[16];
    snprintf(open, sizeof open, "%s(", kernel_fn_names[k->fn]);
    a = kernel_arg(k, open, ")", c);
    if (!a)
        return 0;
    if (!c->latex) {
        sb_puts(b, open);
        sb_puts(b, a);
        sb_puts(b, ")");
        book_put_exp(b, e, c);
        pc_free(a);
        return 1;
    }
    sb_puts(b, lx[k->fn]);
    if (e > 1 && k->fn != KF_ASIN && k->fn != KF_ACOS && k->fn != KF_ATAN)
        book_put_exp(b, e, c);
    slong v;
    int one = fmpz_mpoly_is_one(k->arg->den, c->r->ctx) &&
              fmpz_mpoly_length(k->arg->num, c->r->ctx) == 1 &&
              fmpz_mpoly_total_degree_si(k->arg->num, c->r->ctx) == 1 &&
              fmpz_is_one(k->arg->num->coeffs);
    for (v = 0; one && v < c->r->nvars; v++)
        if (fmpz_mpoly_degree_si(k->arg->num, v, c->r->ctx) > 0)
            break;
    one = one && !kernels_of_var(c->K, v);
    if (one) {
        sb_puts(b, a[0] == '\\' ? "" : " ");
        sb_puts(b, a);
    } else {
        sb_puts(b, "\\left(");
        sb_puts(b, a);
        sb_puts(b, "\\right)");
    }
    if (e > 1 && (k->fn == KF_ASIN || k->fn == KF_ACOS || k->fn == KF_ATAN))
        book_put_exp(b, e,
                     c); /* \arcsin^{2} would read as a power of the map */
    pc_free(a);
    return 1;
}

void book_put_atom(StrBuf *b, const Atom *a, const Ctx *c)
{
    const char *open = c->latex ? "\\left(" : "(";
    const char *close = c->latex ? "\\right)" : ")";
    switch (a->kind) {
    case AT_VAR: {
        const DerivedName *nm = book_named_for(a->var, a->exp, c);
        if (nm) {
            /* dist(A, C)^4 = a^2 for a = dist(A, C)^2 */
            if (c->latex)
                poly_print_latex_name(b, nm->name);
            else
                sb_puts(b, nm->name);
            book_put_exp(b, a->exp / nm->exp, c);
            return;
        }
        const Kernel *k = kernels_of_var(c->K, a->var);
        if (k && put_kernel(b, k, a->exp, c))
            return;
        put_var(b, a->var, c);
        break;
    }
    case AT_BAR:
        if (c->latex) {
            sb_puts(b, "\\bar{");
            put_var(b, a->var, c);
            sb_puts(b, "}");
        } else {
            sb_puts(b, "(1 - ");
            put_var(b, a->var, c);
            sb_puts(b, ")");
        }
        break;
    case AT_SUM:
        sb_puts(b, open);
        book_put_sum(b, a->sum, c);
        sb_puts(b, close);
        break;
    case AT_ABS: {
        char *x =
            absform_abs_text(kernels_of_var(c->K, a->var), c->r, c->latex);
        sb_puts(b, c->latex ? "\\left|" : "abs(");
        sb_puts(b, x);
        sb_puts(b, c->latex ? "\\right|" : ")");
        pc_free(x);
        break;
    }
    case AT_KNOT: { /* x of |x|, as |x| writes it: (t - 1), t */
        const Kernel *k = kernels_of_var(c->K, a->var);
        char *x = absform_abs_text(k, c->r, c->latex);
        const fmpz_mpoly_struct *xn = k->arg->num;
        int one = fmpz_mpoly_length(xn, c->r->ctx) == 1 &&
                  fmpz_mpoly_total_degree_si(xn, c->r->ctx) == 1 &&
                  fmpz_is_one(xn->coeffs);
        sb_puts(b, one ? "" : open);
        sb_puts(b, x);
        sb_puts(b, one ? "" : close);
        pc_free(x);
        break;
    }
    case AT_POINT:
        if (a->point2) {
            sb_puts(b, open);
            book_put_point(b, a->point, c);
            sb_puts(b, " - ");
            book_put_point(b, a->point2, c);
            sb_puts(b, close);
        } else {
            book_put_point(b, a->point, c);
        }
        break;
    }
    book_put_exp(b, a->exp, c);
}

/* the term without its sign */
void book_put_term(StrBuf *b, const PTerm *t, const Ctx *c)
{
    int any = 0;
    if (!fmpz_is_one(t->coeff) || t->n == 0) {
        sb_fmpz(b, t->coeff);
        any = 1;
    }
    for (slong i = 0; i < t->n; i++) {
        if (any)
            sb_puts(b, c->latex ? " " : "*");
        book_put_atom(b, &t->a[i], c);
        any = 1;
    }
}

void book_put_sum(StrBuf *b, const PSum *s, const Ctx *c)
{
    if (s->n == 0) {
        sb_puts(b, "0");
        return;
    }
    for (slong i = 0; i < s->n; i++) {
        const PTerm *t = &s->t[i];
        if (i > 0 && budget_late()) {
            /* past the caller's deadline (budget.h) the text is cut short
             * (the caller discards it): what is written after it is
             * bounded by one term per level of nesting */
            sb_puts(b, c->latex ? " + \\ldots" : " + ...");
            return;
        }
        if (i == 0)
            sb_puts(b, t->neg ? "-" : "");
        else
            sb_puts(b, t->neg ? " - " : " + ");
        if (!c->latex && s->n > 1 && !t->neg && t->n == 1 &&
            fmpz_is_one(t->coeff) && t->a[0].kind == AT_BAR &&
            t->a[0].exp <= 1) {
            /* 1 - v as a term of a sum needs no parentheses: (1 - v +
             * u*v), not ((1 - v) + u*v) */
            sb_puts(b, "1 - ");
            put_var(b, t->a[0].var, c);
            continue;
        }
        book_put_term(b, t, c);
    }
}

size_t book_sum_text_len(const PSum *s, const Ctx *c)
{
    StrBuf b = {0};
    book_put_sum(&b, s, c);
    size_t n = b.len;
    pc_free(b.s);
    return n;
}

void book_put_frac(StrBuf *b, const char *num, int num_items, const PSum *den,
                   const Ctx *c)
{
    if (c->latex) {
        sb_puts(b, "\\frac{");
        sb_puts(b, num);
        sb_puts(b, "}{");
        book_put_sum(b, den, c);
        sb_puts(b, "}");
        return;
    }
    int pn = num_items > 1;
    if (pn)
        sb_puts(b, "(");
    sb_puts(b, num);
    if (pn)
        sb_puts(b, ")");
    int pd = den->n > 1 || den->t[0].n + !fmpz_is_one(den->t[0].coeff) > 1;
    sb_puts(b, pd ? "/(" : "/");
    book_put_sum(b, den, c);
    if (pd)
        sb_puts(b, ")");
}
