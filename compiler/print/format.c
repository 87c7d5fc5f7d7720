/*
 * format.c - the printers' entry points (format.h): derive's output in
 * text and LaTeX through the book printer (book.h), one memo of chosen
 * forms shared by a scheme's outputs, and JSON through format_json.c
 * (format_int.h); the --standalone LaTeX document around them.
 *
 * Also the small printer of weights as re-readable expressions
 * (format_weight: factored, '*' for every product, abs(x) for x*sign(x))
 * that JSON and --steps use.  Polynomials expanded are algebra/poly_print.c's.
 */
#include "compiler/print/format.h"

#include <ctype.h>
#include <stdlib.h>
#include <string.h>

#include <flint/fmpz_mpoly_factor.h>

#include "base/budget.h"
#include "base/mem.h"
#include "base/stack.h"
#include "base/strbuf.h"
#include "compiler/print/absform.h"
#include "compiler/print/book.h"
#include "compiler/print/format_int.h"

/* ---- names ----------------------------------------------------------- */

static void latex_name(StrBuf *b, const char *name)
{
    poly_print_latex_name(b, name);
}

/* ---- polynomials ------------------------------------------------------ */

/* is p (up to the sign s) exactly 1 - v for a variable v?  returns v or -1 */
static slong one_minus_var(const fmpz_mpoly_t p, const Ring *r)
{
    if (fmpz_mpoly_length(p, r->ctx) != 2 ||
        fmpz_mpoly_total_degree_si(p, r->ctx) != 1)
        return -1;
    for (slong v = 0; v < r->nvars; v++) {
        fmpz_mpoly_t q;
        fmpz_mpoly_init(q, r->ctx);
        fmpz_mpoly_gen(q, v, r->ctx);
        fmpz_mpoly_neg(q, q, r->ctx);
        fmpz_mpoly_add_si(q, q, 1, r->ctx);
        int eq = fmpz_mpoly_equal(p, q, r->ctx);
        fmpz_mpoly_clear(q, r->ctx);
        if (eq)
            return v;
    }
    return -1;
}

/* a polynomial's factor for printing */
typedef struct Factor {
    fmpz_mpoly_struct *poly; // borrowed from the factorisation
    ulong exp;
    slong len;
    int flipped; // negated to make its constant term positive
} Factor;

/* the order of a product's factors (docs/language.md, "derive"): by the
 * number of terms (monomials first), then by total degree, then by FLINT's
 * fixed order of polynomials (fmpz_mpoly_cmp) from the last, compared as
 * FLINT's factoring returns them (primitive, leading coefficient
 * positive): monomials in the ring's order of variables, as FLINT's
 * factoring puts them, and sums as the book orders its sums (book_model.c:
 * 4t - 1 before 4t - 3 before t - 1).  A total order on the factors, so a
 * product prints the same however its factors were found (shared among
 * weights or not). */
static int factor_before(const fmpz_mpoly_t a, const fmpz_mpoly_t b,
                         const Ring *r)
{
    slong la = fmpz_mpoly_length(a, r->ctx), lb = fmpz_mpoly_length(b, r->ctx);
    if (la != lb)
        return la < lb;
    slong da = fmpz_mpoly_total_degree_si(a, r->ctx);
    slong db = fmpz_mpoly_total_degree_si(b, r->ctx);
    if (da != db)
        return da < db;
    return fmpz_mpoly_cmp(a, b, r->ctx) > 0;
}

/* p's factoring (ring_factor's, through the factors shared by the
 * scheme's weights when share is given: book_factor), its factors in
 * factor_before's order (an insertion sort: a few); none past the caller's
 * deadline (budget.h: p is then written unfactored, in linear time) */
static int factor_ordered(fmpz_mpoly_factor_t f, const fmpz_mpoly_t p,
                          const Ring *r, const FormatShare *share)
{
    if (budget_late() || !(share ? book_factor(f, p, share->d, share->memo)
                                 : ring_factor(f, p, r)))
        return 0;
    for (slong i = 1; i < f->num; i++)
        for (slong j = i;
             j > 0 && factor_before(f->poly + j, f->poly + j - 1, r); j--) {
            fmpz_mpoly_swap(f->poly + j, f->poly + j - 1, r->ctx);
            fmpz_swap(f->exp + j, f->exp + j - 1);
        }
    return 1;
}

/* Writes |p| as  [c] f1^e1 f2^e2 ... (the sign is NOT written: *negative
 * receives it).  Factors are normalised so their constant term is positive
 * (1 - t rather than t - 1), the book's habit; monomial factors come first.
 * With `positive` (a denominator), a factor of odd power is left as it was
 * when that is what keeps the whole positive: /(t - 1), not /(-(1 - t)).
 * Returns the number of items written (a constant counts as one), so that
 * callers can decide on parentheses. */
static int put_factored_ex(StrBuf *b, const fmpz_mpoly_t p, const Ring *r,
                           FormatStyle st, int *negative, int positive,
                           const FormatShare *share)
{
    fmpz_mpoly_factor_t f;
    fmpz_mpoly_factor_init(f, r->ctx);
    if (fmpz_mpoly_is_zero(p, r->ctx) || !factor_ordered(f, p, r, share)) {
        /* unfactored (too costly to factor): one item, "(1 - t^400)" */
        fmpz_mpoly_factor_clear(f, r->ctx);
        *negative = 0;
        if (fmpz_mpoly_length(p, r->ctx) == 1) {
            fmpz_mpoly_t q;
            fmpz_mpoly_init(q, r->ctx);
            *negative = fmpz_sgn(p->coeffs) < 0;
            if (*negative)
                fmpz_mpoly_neg(q, p, r->ctx);
            else
                fmpz_mpoly_set(q, p, r->ctx);
            poly_print(b, q, r, st);
            fmpz_mpoly_clear(q, r->ctx);
            return 1;
        }
        int paren = fmpz_mpoly_length(p, r->ctx) > 1;
        if (paren)
            sb_puts(b, st == FMT_LATEX ? "\\left(" : "(");
        poly_print(b, p, r, st);
        if (paren)
            sb_puts(b, st == FMT_LATEX ? "\\right)" : ")");
        return 1;
    }
    int neg = fmpz_sgn(f->constant) < 0;
    Factor *fs = pc_xmalloc(sizeof(Factor) * (size_t)(f->num ? f->num : 1));
    ulong *zero =
        pc_xcalloc((size_t)(r->nvars ? r->nvars : 1) + 1, sizeof(ulong));
    fmpz_t c;
    fmpz_init(c);
    for (slong i = 0; i < f->num; i++) {
        fmpz_mpoly_struct *q = f->poly + i;
        ulong e = fmpz_get_ui(f->exp + i);
        fmpz_mpoly_get_coeff_fmpz_ui(c, q, zero, r->ctx);
        fs[i].flipped = 0;
        if (fmpz_sgn(c) < 0) {
            fmpz_mpoly_neg(q, q, r->ctx);
            fs[i].flipped = 1;
            if (e & 1)
                neg = !neg;
        }
        fs[i].poly = q;
        fs[i].exp = e;
        fs[i].len = fmpz_mpoly_length(q, r->ctx);
    }
    for (slong i = 0; i < f->num && positive && neg; i++)
        if (fs[i].flipped && (fs[i].exp & 1)) {
            fmpz_mpoly_neg(fs[i].poly, fs[i].poly, r->ctx);
            neg = 0;
        }
    int items = 0;
    fmpz_abs(c, f->constant);
    if (!fmpz_is_one(c) || f->num == 0) {
        sb_fmpz(b, c);
        items++;
    }
    for (slong i = 0; i < f->num; i++) {
        if (items)
            sb_puts(b, st == FMT_LATEX ? " " : "*");
        items++;
        slong v = st == FMT_LATEX ? one_minus_var(fs[i].poly, r) : -1;
        if (v >= 0 && r->latex && r->latex[v])
            v = -1; /* 1 - sin(t): no bar over a function */
        int atom = fs[i].len == 1 &&
                   fmpz_mpoly_total_degree_si(fs[i].poly, r->ctx) == 1;
        if (v >= 0) {
            sb_puts(b, "\\bar{");
            latex_name(b, r->names[v]);
            sb_puts(b, "}");
        } else if (atom) {
            poly_print(b, fs[i].poly, r, st);
        } else {
            sb_puts(b, st == FMT_LATEX ? "\\left(" : "(");
            poly_print(b, fs[i].poly, r, st);
            sb_puts(b, st == FMT_LATEX ? "\\right)" : ")");
        }
        if (fs[i].exp > 1) {
            char num[32];
            snprintf(num, sizeof num, st == FMT_LATEX ? "^{%lu}" : "^%lu",
                     fs[i].exp);
            sb_puts(b, num);
        }
    }
    fmpz_clear(c);
    pc_free(zero);
    pc_free(fs);
    fmpz_mpoly_factor_clear(f, r->ctx);
    *negative = neg;
    return items;
}

/* writes a denominator after the fraction bar (text/json): "/2", "/t",
 * "/(2*t^2 - 2*t + 1)", "/(t*(1-t))" */
static void put_den(StrBuf *b, const fmpz_mpoly_t den, const Ring *r,
                    FormatStyle st, const FormatShare *share)
{
    StrBuf d = {0};
    int neg;
    int items = put_factored_ex(&d, den, r, st, &neg, 1, share);
    char *ds = sb_take(&d);
    int wrap = items > 1 || neg; /* "/(...)^2" and "/t^2" need no more */
    sb_puts(b, "/");
    if (wrap)
        sb_puts(b, "(");
    if (neg)
        sb_puts(b, "-");
    sb_puts(b, ds);
    if (wrap)
        sb_puts(b, ")");
    pc_free(ds);
}

static int is_den_one(const RatFun w, const Ring *r)
{
    return fmpz_mpoly_is_one(w->den, r->ctx);
}

static int poly_has(const fmpz_mpoly_t p, slong var, const Ring *r)
{
    return fmpz_mpoly_degree_si(p, var, r->ctx) > 0;
}

/* 1 when kernel k is a function of one argument whose argument uses a
 * sign kernel, directly or inside another function: its name then shows
 * x*sign(x) that format_weight_k writes as abs(x) */
static int arg_has_sign(const Kernels *K, const Kernel *k, int depth)
{
    switch (k->fn) {
    case KF_SQRT:
    case KF_SIN:
    case KF_COS:
    case KF_SINH:
    case KF_COSH:
    case KF_EXP:
    case KF_LN:
    case KF_ASIN:
    case KF_ACOS:
    case KF_ATAN:
        break;
    default:
        return 0;
    }
    const Ring *r = K->r;
    if (depth > 64) /* kernels nest as deep as sema lets an expression */
        return 0;
    for (slong i = 0; i < K->n; i++) {
        const Kernel *a = &K->k[i];
        if ((poly_has(k->arg->num, a->var, r) ||
             poly_has(k->arg->den, a->var, r)) &&
            (a->fn == KF_SIGN || arg_has_sign(K, a, depth + 1)))
            return 1;
    }
    return 0;
}

/* w's num and den with x*sign(x) read as |x| (absform.h), in a copy of
 * r whose names of those sign kernels are abs(x), and whose names of
 * functions of such arguments are written again with abs:
 * sin(pi*abs(t - 1)/4), not sin((t*pi*sign(t - 1) - pi*sign(t - 1))/4) */
static char *weight_text(const RatFun w, const Ring *r,
                         const FormatShare *share)
{
    StrBuf b = {0};
    StrBuf n = {0};
    int neg;
    put_factored_ex(&n, w->num, r, FMT_JSON, &neg, 0, share);
    if (neg)
        sb_puts(&b, "-");
    sb_puts(&b, n.s);
    pc_free(n.s);
    if (!is_den_one(w, r))
        put_den(&b, w->den, r, FMT_JSON, share);
    return sb_take(&b);
}

static char *weight_k(const RatFun w, const Ring *r, const Kernels *K,
                      const FormatShare *share)
{
    /* it recurses into nested functions' arguments: where the stack runs
     * low (stack.h), the weight as it is, with sign() (equal, and short) */
    if (!absform_any(K) || stack_low())
        return weight_text(w, r, share);
    size_t nv = (size_t)(r->nvars ? r->nvars : 1);
    unsigned char *mask = pc_xcalloc(nv, 1);
    RatFun x;
    fmpz_mpoly_init(x->num, r->ctx);
    fmpz_mpoly_init(x->den, r->ctx);
    slong n = absform_rewrite(x->num, mask, w->num, K, r);
    n += absform_rewrite(x->den, mask, w->den, K, r);
    if (n == 0) {
        fmpz_mpoly_set(x->num, w->num, r->ctx);
        fmpz_mpoly_set(x->den, w->den, r->ctx);
    }
    for (slong i = 0; i < K->n; i++) { /* 2: a function named again */
        const Kernel *k = &K->k[i];
        if (!mask[k->var] &&
            (poly_has(x->num, k->var, r) || poly_has(x->den, k->var, r)) &&
            arg_has_sign(K, k, 0)) {
            mask[k->var] = 2;
            n++;
        }
    }
    char *res;
    if (n == 0) {
        res = weight_text(w, r, share);
    } else {
        Ring ra = *r; /* read-only: the same FLINT context */
        const char **names = pc_xmalloc(sizeof(char *) * nv);
        for (slong v = 0; v < r->nvars; v++) {
            names[v] = r->names[v];
            const Kernel *k = mask[v] ? kernels_of_var(K, v) : NULL;
            char *a = !k             ? NULL
                      : mask[v] == 1 ? absform_arg_text(k, 0)
                                     : weight_k(k->arg, r, K, share);
            if (!a)
                continue;
            const char *f = mask[v] == 1 ? "abs" : kernel_fn_names[k->fn];
            size_t lf = strlen(f), la = strlen(a);
            char *t = pc_xmalloc(lf + la + 3);
            memcpy(t, f, lf);
            t[lf] = '(';
            memcpy(t + lf + 1, a, la);
            memcpy(t + lf + 1 + la, ")", 2);
            pc_free(a);
            names[v] = t;
        }
        ra.names = names;
        res = weight_text(x, &ra, share);
        for (slong v = 0; v < r->nvars; v++)
            if (mask[v])
                pc_free((char *)names[v]);
        pc_free(names);
    }
    fmpz_mpoly_clear(x->den, r->ctx);
    fmpz_mpoly_clear(x->num, r->ctx);
    pc_free(mask);
    return res;
}

char *format_weight_k(const RatFun w, const Ring *r, const Kernels *K)
{
    return weight_k(w, r, K, NULL);
}

char *format_weight_share(const RatFun w, const FormatShare *share)
{
    return weight_k(w, &share->d->ring, share->d->kernels, share);
}

char *format_weight(const RatFun w, const Ring *r)
{
    return weight_text(w, r, NULL);
}

char *format_output_rhs(const Derived *d, const DerivedOutput *o,
                        FormatStyle st, slong origin)
{
    BookOptions opt = {
        .latex = st == FMT_LATEX, .width = 0, .origin = origin, .memo = NULL};
    return book_rhs(d, o, &opt);
}

void format_derived(FILE *out, const Derived *d, FormatStyle st, slong origin)
{
    format_derived_width(out, d, st, origin, 0);
}

void format_latex_begin(FILE *out, const Derived *d)
{
    fputs("\\documentclass{article}\n"
          "\\usepackage{amsmath}\n"
          "\\begin{document}\n"
          "\\section*{",
          out);
    /* the scheme's name as text: escape what LaTeX would read */
    for (const char *p = d->scheme; *p; p++) {
        if (*p == '\\')
            fputs("\\textbackslash{}", out);
        else if (*p == '^')
            fputs("\\textasciicircum{}", out);
        else if (*p == '~')
            fputs("\\textasciitilde{}", out);
        else if (strchr("#$%&_{}", *p))
            fprintf(out, "\\%c", *p);
        else
            fputc(*p, out);
    }
    fputs("}\n", out);
}

void format_latex_end(FILE *out)
{
    fputs("\\end{document}\n", out);
}

void format_derived_width(FILE *out, const Derived *d, FormatStyle st,
                          slong origin, int width)
{
    if (st == FMT_JSON) {
        format_json(out, d);
        return;
    }
    BookOptions opt = {.latex = st == FMT_LATEX,
                       .width = width,
                       .origin = origin,
                       .memo = book_memo_new()};
    for (slong i = 0; i < d->noutputs; i++) {
        derived_mark(d, i); /* blamed if a budget runs out */
        char *line = book_output(d, &d->outputs[i], &opt);
        fputs(line, out);
        pc_free(line);
    }
    budget_statement(NULL, (Span){0, 0}); /* printed: no output to blame */
    book_memo_free(opt.memo, d);
}
