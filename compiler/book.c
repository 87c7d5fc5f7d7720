#include "compiler/print/book.h"

#include <ctype.h>
#include <limits.h>
#include <stdlib.h>
#include <string.h>

#include <flint/fmpz_mpoly_factor.h>
#include <flint/fmpz_vec.h>

#include "compiler/print/absform.h"
#include "compiler/kernel.h"
#include "compiler/polyfactor.h"
#include "compiler/print/latexbreak.h"
#include "base/mem.h"
#include "compiler/ring.h"
#include "base/strbuf.h"

/* ---- names ------------------------------------------------------------ */

static const char *const greek[] = {
    "alpha", "beta",   "gamma", "delta", "epsilon", "zeta",   "eta",
    "theta", "iota",   "kappa", "lambda", "mu",     "nu",     "xi",
    "pi",    "rho",    "sigma", "tau",   "upsilon", "phi",    "chi",
    "psi",   "omega",  "Gamma", "Delta", "Theta",   "Lambda", "Xi",
    "Pi",    "Sigma",  "Phi",   "Psi",   "Omega",
};

static int all_digits(const char *s)
{
    if (!*s)
        return 0;
    for (; *s; s++)
        if (!isdigit((unsigned char)*s))
            return 0;
    return 1;
}

static void latex_name(StrBuf *b, const char *name)
{
    size_t n = strlen(name);
    const char *under = strchr(name, '_');
    if (under && under != name && under[1]) {
        char *stem = pc_xstrndup(name, (size_t)(under - name));
        StrBuf st = {0};
        latex_name(&st, stem);
        free(stem);
        char *s = sb_take(&st);
        size_t sl = strlen(s);
        if (sl > 0 && s[sl - 1] == '}' && strstr(s, "_{")) {
            /* the stem has its subscript already: one subscript,
             * M116_abc -> M_{116,abc} (TeX has no double subscript) */
            sb_putn(b, s, sl - 1);
            sb_puts(b, ",");
        } else {
            sb_puts(b, s);
            sb_puts(b, "_{");
        }
        free(s);
        sb_puts(b, under + 1);
        sb_puts(b, "}");
        return;
    }
    size_t alpha = 0;
    while (alpha < n && isalpha((unsigned char)name[alpha]))
        alpha++;
    for (size_t g = 0; g < sizeof greek / sizeof greek[0]; g++) {
        size_t gl = strlen(greek[g]);
        if (gl == alpha && strncmp(greek[g], name, gl) == 0 &&
            (name[gl] == '\0' || all_digits(name + gl))) {
            sb_puts(b, "\\");
            /* the book's (and most texts') angle: \varphi */
            sb_puts(b, strcmp(greek[g], "phi") == 0 ? "varphi" : greek[g]);
            if (name[gl]) {
                sb_puts(b, "_{");
                sb_puts(b, name + gl);
                sb_puts(b, "}");
            }
            return;
        }
    }
    if (n == 1) {
        sb_puts(b, name);
        return;
    }
    /* one-letter stem, then capitals or digits: A1, fP, pD, d2M */
    int sub = isalpha((unsigned char)name[0]);
    for (size_t i = 1; i < n && sub; i++)
        sub = isupper((unsigned char)name[i]) ||
              isdigit((unsigned char)name[i]);
    if (sub) {
        sb_putn(b, name, 1);
        sb_puts(b, "_{");
        sb_puts(b, name + 1);
        sb_puts(b, "}");
        return;
    }
    sb_puts(b, "\\mathit{");
    sb_puts(b, name);
    sb_puts(b, "}");
}

char *book_latex_name(const char *name)
{
    StrBuf b = {0};
    latex_name(&b, name);
    return sb_take(&b);
}

/* ---- the print model: sums of products of atoms ------------------------ */

typedef enum AtomKind {
    AT_VAR,   // a ring variable: param, const, function
    AT_BAR,   // 1 - x of a param or const
    AT_SUM,   // a parenthesised sum
    AT_POINT, // a point name, or a difference of two (point2)
    AT_ABS,   // |x| of the sign kernel var = sign(x) (absform.h)
} AtomKind;

typedef struct PSum PSum;

typedef struct Atom {
    AtomKind kind;
    slong var;         // AT_VAR, AT_BAR
    PSum *sum;         // AT_SUM (owned)
    const char *point; // AT_POINT (borrowed)
    const char *point2; // AT_POINT: point - point2, or NULL
    ulong exp;
} Atom;

typedef struct PTerm {
    int neg;
    fmpz_t coeff; // >= 1
    slong n;
    Atom *a;
} PTerm;

struct PSum {
    slong n;
    PTerm *t;
    fmpz_mpoly_t poly; // what the sum is, up to sign (for the total order)
    int has_param;     // it involves a param
};

typedef struct Ctx {
    const Ring *r;
    slong nparams, nconsts; // vars < nparams are params; < nparams+nconsts
                            // consts; the rest functions and extras
    int latex;
    long *work; // the printing work spent on this output (RENDER_WORK)
    struct Memo *memo; // forms already chosen: this output's, or the
                       // scheme's (BookOptions.memo)
    const Kernels *K;  // the functions (NULL: none)
    int has_sign;      // K has a sign kernel: polynomials are read for |x|
    const unsigned char *is_abs; // rendering a polynomial rewritten by
                                 // absform_rewrite: its vars meaning |x|
    ulong mode; // 0, or a key of is_abs (memo entries differ by it)
    const DerivedName *named; // the scheme's named kernel powers, and the
    slong nnamed;             // line of the definition being printed:
    int line;                 // names defined before it print for them
} Ctx;

/* render() of a polynomial at a depth, kept: the same coefficients and
 * factors come up in every collection */
typedef struct MemoEntry {
    fmpz_mpoly_t poly;
    int depth;
    ulong mode; // Ctx.mode it was rendered in
    struct PSum *sum;
} MemoEntry;

typedef struct Memo {
    MemoEntry *e;
    slong n, alloc;
} Memo; /* = BookMemo (book.h) */

enum {
    MAX_DEPTH = 2,          // levels of collection (factors and coefficients)
    MAX_COLLECT_TERMS = 60, // larger polynomials: expanded or factored only
    RENDER_WORK = 60000,    // per output, in terms looked at (a factoring
                            // counts FACTOR_WORK + 20 per term): beyond it,
                            // polynomials are written expanded, or factored
                            // at the top level only
    FACTOR_WORK = 200,
    MAX_FACTOR_TERMS_NESTED = 24, // factors and coefficients factored only
                                  // when this short
    CHEAP_FACTOR_DEPTH = 2,       // from this depth on: form_factored_cheap
};

static void sum_free(PSum *s, const Ctx *c);

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
            sum_free(t->a[i].sum, c);
    free(t->a);
    fmpz_clear(t->coeff);
}

static PSum *sum_new(const Ctx *c)
{
    PSum *s = pc_xcalloc(1, sizeof *s);
    fmpz_mpoly_init(s->poly, c->r->ctx);
    return s;
}

static void sum_free(PSum *s, const Ctx *c)
{
    if (!s)
        return;
    for (slong i = 0; i < s->n; i++)
        term_clear(&s->t[i], c);
    free(s->t);
    fmpz_mpoly_clear(s->poly, c->r->ctx);
    free(s);
}

static PTerm *sum_push(PSum *s)
{
    s->t = pc_xrealloc(s->t, sizeof(PTerm) * (size_t)(s->n + 1));
    term_init(&s->t[s->n]);
    return &s->t[s->n++];
}

static PSum *sum_copy(const PSum *s, const Ctx *c);

static void term_copy(PTerm *dst, const PTerm *src, const Ctx *c)
{
    dst->neg = src->neg;
    fmpz_set(dst->coeff, src->coeff);
    dst->n = src->n;
    dst->a = pc_xmalloc(sizeof(Atom) * (size_t)(src->n ? src->n : 1));
    for (slong i = 0; i < src->n; i++) {
        dst->a[i] = src->a[i];
        if (src->a[i].kind == AT_SUM)
            dst->a[i].sum = sum_copy(src->a[i].sum, c);
    }
}

static PSum *sum_copy(const PSum *s, const Ctx *c)
{
    PSum *r = sum_new(c);
    r->t = pc_xmalloc(sizeof(PTerm) * (size_t)(s->n ? s->n : 1));
    for (slong i = 0; i < s->n; i++) {
        term_init(&r->t[i]);
        term_copy(&r->t[i], &s->t[i], c);
    }
    r->n = s->n;
    fmpz_mpoly_set(r->poly, s->poly, c->r->ctx);
    r->has_param = s->has_param;
    return r;
}

static void memo_clear(Memo *m, const Ctx *c)
{
    for (slong i = 0; i < m->n; i++) {
        fmpz_mpoly_clear(m->e[i].poly, c->r->ctx);
        sum_free(m->e[i].sum, c);
    }
    free(m->e);
    m->e = NULL;
    m->n = m->alloc = 0;
}

/* appends an atom; no path multiplies two powers of one variable (the
 * factors of a factorisation are distinct, a collected coefficient is free
 * of its variable), so atoms are not merged */
static void term_push(PTerm *t, Atom a)
{
    t->a = pc_xrealloc(t->a, sizeof(Atom) * (size_t)(t->n + 1));
    t->a[t->n++] = a;
}

static int is_param(const Ctx *c, slong v)
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

static const DerivedName *named_for(slong var, ulong e, const Ctx *c)
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
        if (is_param(c, a->var))
            return 2;
        if (a->kind == AT_VAR && named_for_line(a->var, a->exp, INT_MAX, c))
            return 0; /* a named scalar: with the consts (B*a*t); the
                       * same place wherever it is written by its name
                       * (forms are shared by a scheme's outputs) */
        return a->var < c->nparams + c->nconsts ? 0 : 3;
    case AT_ABS:
        return 3;
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
    if (a->kind == AT_VAR || a->kind == AT_BAR || a->kind == AT_ABS) {
        if (a->var != b->var)
            return a->var < b->var ? -1 : 1;
        if (a->kind != b->kind)
            return a->kind < b->kind ? -1 : 1;
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
static void term_sort(PTerm *t, const Ctx *c)
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
static void term_absorb(PTerm *dst, PTerm *src)
{
    fmpz_mul(dst->coeff, dst->coeff, src->coeff);
    dst->neg ^= src->neg;
    for (slong i = 0; i < src->n; i++)
        term_push(dst, src->a[i]);
    free(src->a);
    src->a = NULL;
    src->n = 0;
}

/* ---- measuring --------------------------------------------------------- */

static slong sum_leaves(const PSum *s);

static slong term_leaves(const PTerm *t)
{
    slong n = 1;
    for (slong i = 0; i < t->n; i++)
        if (t->a[i].kind == AT_SUM)
            n += sum_leaves(t->a[i].sum) - 1;
    return n;
}

static slong sum_leaves(const PSum *s)
{
    slong n = 0;
    for (slong i = 0; i < s->n; i++)
        n += term_leaves(&s->t[i]);
    return n ? n : 1;
}

/* ---- writing ------------------------------------------------------------ */

static void put_sum(StrBuf *b, const PSum *s, const Ctx *c);

static void put_var(StrBuf *b, slong v, const Ctx *c)
{
    const Ring *r = c->r;
    if (c->latex && r->latex && r->latex[v])
        sb_puts(b, r->latex[v]);
    else if (c->latex)
        latex_name(b, r->names[v]);
    else
        sb_puts(b, r->names[v]);
}

static void put_point(StrBuf *b, const char *p, const Ctx *c)
{
    if (c->latex)
        latex_name(b, p);
    else
        sb_puts(b, p);
}

static void put_exp(StrBuf *b, ulong e, const Ctx *c)
{
    if (e <= 1)
        return;
    sb_puts(b, c->latex ? "^{" : "^");
    sb_ulong(b, e);
    if (c->latex)
        sb_puts(b, "}");
}

static void rhs_scalar(StrBuf *b, const RatFun x, const Ctx *c);
static PSum *form_expanded(const fmpz_mpoly_t p, const Ctx *c);
static PSum *render(const fmpz_mpoly_t p, int depth, const Ctx *c);

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

static void put_frac(StrBuf *b, const char *num, int num_items, const PSum *den,
                     const Ctx *c);

/* a kernel's argument x: its best form (expanded: its terms only), a
 * positive term first (sqrt(a^2 - b^2), not sqrt(-b^2 + a^2)) */
static void put_arg(StrBuf *b, const RatFun x, int expanded, const Ctx *c)
{
    PSum *s = expanded ? form_expanded(x->num, c) : render(x->num, 0, c);
    arg_lead(s);
    if (fmpz_mpoly_is_one(x->den, c->r->ctx)) {
        put_sum(b, s, c);
        sum_free(s, c);
        return;
    }
    /* a quotient: both parts lead with a positive term, as written
     * (sqrt((rho^2 - b^2)/(a^2 - b^2))) */
    PSum *d = expanded ? form_expanded(x->den, c) : render(x->den, 0, c);
    arg_lead(d);
    StrBuf n = {0};
    put_sum(&n, s, c);
    put_frac(b, n.s, (int)s->n, d, c);
    free(n.s);
    sum_free(d, c);
    sum_free(s, c);
}

/* the argument of kernel k in its best form (book.c), or expanded as
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
    StrBuf bk = {0};
    put_arg(&bk, k->arg, 0, &t);
    int book = bk.len < strlen(own); /* ties: as kernel.c named it */
    if (!c->latex) {
        if (book) {
            free(own);
            return sb_take(&bk);
        }
        free(bk.s);
        return own;
    }
    free(own);
    free(bk.s);
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
    static const char *const lx[KF_COUNT] = {
        [KF_SIN] = "\\sin",     [KF_COS] = "\\cos",     [KF_SINH] = "\\sinh",
        [KF_COSH] = "\\cosh",   [KF_LN] = "\\ln",       [KF_ASIN] = "\\arcsin",
        [KF_ACOS] = "\\arccos", [KF_ATAN] = "\\arctan",
    };
    char *a;
    if (k->fn == KF_SQRT) {
        a = kernel_arg(k, "sqrt(", ")", c);
        if (!a)
            return 0;
        sb_puts(b, c->latex ? "\\sqrt{" : "sqrt(");
        sb_puts(b, a);
        sb_puts(b, c->latex ? "}" : ")");
        put_exp(b, e, c);
        free(a);
        return 1;
    }
    if (k->fn >= KF_COUNT || !lx[k->fn])
        return 0;
    char open[16];
    static const char *const names[] = {
#define X(id, name, cfn) name,
        PC_KERNEL_FNS(X)
#undef X
    };
    snprintf(open, sizeof open, "%s(", names[k->fn]);
    a = kernel_arg(k, open, ")", c);
    if (!a)
        return 0;
    if (!c->latex) {
        sb_puts(b, open);
        sb_puts(b, a);
        sb_puts(b, ")");
        put_exp(b, e, c);
        free(a);
        return 1;
    }
    sb_puts(b, lx[k->fn]);
    if (e > 1 && k->fn != KF_ASIN && k->fn != KF_ACOS && k->fn != KF_ATAN)
        put_exp(b, e, c);
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
        put_exp(b, e, c); /* \arcsin^{2} would read as a power of the map */
    free(a);
    return 1;
}

static void put_atom(StrBuf *b, const Atom *a, const Ctx *c)
{
    const char *open = c->latex ? "\\left(" : "(";
    const char *close = c->latex ? "\\right)" : ")";
    switch (a->kind) {
    case AT_VAR: {
        const DerivedName *nm = named_for(a->var, a->exp, c);
        if (nm) {
            /* dist(A, C)^4 = a^2 for a = dist(A, C)^2 */
            if (c->latex)
                latex_name(b, nm->name);
            else
                sb_puts(b, nm->name);
            put_exp(b, a->exp / nm->exp, c);
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
        put_sum(b, a->sum, c);
        sb_puts(b, close);
        break;
    case AT_ABS: {
        char *x = absform_arg_text(kernels_of_var(c->K, a->var), c->latex);
        sb_puts(b, c->latex ? "\\left|" : "abs(");
        sb_puts(b, x);
        sb_puts(b, c->latex ? "\\right|" : ")");
        free(x);
        break;
    }
    case AT_POINT:
        if (a->point2) {
            sb_puts(b, open);
            put_point(b, a->point, c);
            sb_puts(b, " - ");
            put_point(b, a->point2, c);
            sb_puts(b, close);
        } else {
            put_point(b, a->point, c);
        }
        break;
    }
    put_exp(b, a->exp, c);
}

/* the term without its sign */
static void put_term(StrBuf *b, const PTerm *t, const Ctx *c)
{
    int any = 0;
    if (!fmpz_is_one(t->coeff) || t->n == 0) {
        sb_fmpz(b, t->coeff);
        any = 1;
    }
    for (slong i = 0; i < t->n; i++) {
        if (any)
            sb_puts(b, c->latex ? " " : "*");
        put_atom(b, &t->a[i], c);
        any = 1;
    }
}

static void put_sum(StrBuf *b, const PSum *s, const Ctx *c)
{
    if (s->n == 0) {
        sb_puts(b, "0");
        return;
    }
    for (slong i = 0; i < s->n; i++) {
        const PTerm *t = &s->t[i];
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
        put_term(b, t, c);
    }
}

static size_t sum_text_len(const PSum *s, const Ctx *c)
{
    StrBuf b = {0};
    put_sum(&b, s, c);
    size_t n = b.len;
    free(b.s);
    return n;
}

/* ---- the forms of a polynomial ------------------------------------------ */

static PSum *render(const fmpz_mpoly_t p, int depth, const Ctx *c);

/* negates every term of s (and its poly) */
static void sum_neg(PSum *s, const Ctx *c)
{
    for (slong i = 0; i < s->n; i++)
        s->t[i].neg ^= 1;
    fmpz_mpoly_neg(s->poly, s->poly, c->r->ctx);
}

static void sum_finish(PSum *s, const fmpz_mpoly_t p, const Ctx *c)
{
    fmpz_mpoly_set(s->poly, p, c->r->ctx);
    s->has_param = 0;
    for (slong v = 0; v < c->nparams && !s->has_param; v++)
        s->has_param = fmpz_mpoly_degree_si(p, v, c->r->ctx) > 0;
    for (slong i = 0; i < s->n; i++)
        term_sort(&s->t[i], c);
}

/* the total degree of p's term k */
static slong term_degree(const fmpz_mpoly_t p, slong k, const Ctx *c)
{
    const Ring *r = c->r;
    ulong *e = pc_xmalloc(sizeof(ulong) * (size_t)(r->nvars ? r->nvars : 1));
    fmpz_mpoly_get_term_exp_ui(e, p, k, r->ctx);
    slong d = 0;
    for (slong v = 0; v < r->nvars; v++)
        d += (slong)e[v];
    free(e);
    return d;
}

/* expanded, ascending (the reverse of FLINT's degrevlex) */
static PSum *form_expanded(const fmpz_mpoly_t p, const Ctx *c)
{
    const Ring *r = c->r;
    PSum *s = sum_new(c);
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
                PTerm *t = sum_push(s);
                fmpz_mpoly_get_term_coeff_fmpz(t->coeff, p, j, r->ctx);
                t->neg = fmpz_sgn(t->coeff) < 0;
                fmpz_abs(t->coeff, t->coeff);
                fmpz_mpoly_get_term_exp_ui(e, p, j, r->ctx);
                for (slong v = 0; v < r->nvars; v++)
                    if (e[v])
                        term_push(t, (Atom){AT_VAR, v, NULL, NULL, NULL, e[v]});
            }
            kk = lo;
            continue;
        }
        PTerm *t = sum_push(s);
        fmpz_mpoly_get_term_coeff_fmpz(t->coeff, p, k, r->ctx);
        t->neg = fmpz_sgn(t->coeff) < 0;
        fmpz_abs(t->coeff, t->coeff);
        fmpz_mpoly_get_term_exp_ui(e, p, k, r->ctx);
        for (slong v = 0; v < r->nvars; v++)
            if (e[v])
                term_push(t, (Atom){AT_VAR, v, NULL, NULL, NULL, e[v]});
    }
    free(e);
    sum_finish(s, p, c);
    return s;
}

/* is p = s*(1 - x) for a param or const x and a sign s?  returns x or -1 */
static slong bar_var(const fmpz_mpoly_t p, const Ctx *c, int *sign)
{
    const Ring *r = c->r;
    if (fmpz_mpoly_length(p, r->ctx) != 2 ||
        fmpz_mpoly_total_degree_si(p, r->ctx) != 1)
        return -1;
    for (slong v = 0; v < c->nparams + c->nconsts && v < r->nvars; v++) {
        if (fmpz_mpoly_degree_si(p, v, r->ctx) != 1)
            continue;
        fmpz_mpoly_t q;
        fmpz_mpoly_init(q, r->ctx);
        fmpz_mpoly_gen(q, v, r->ctx);
        fmpz_mpoly_neg(q, q, r->ctx);
        fmpz_mpoly_add_si(q, q, 1, r->ctx);
        int s = fmpz_mpoly_equal(p, q, r->ctx) ? 1 : 0;
        if (!s) {
            fmpz_mpoly_neg(q, q, r->ctx);
            s = fmpz_mpoly_equal(p, q, r->ctx) ? -1 : 0;
        }
        fmpz_mpoly_clear(q, r->ctx);
        if (s) {
            *sign = s;
            return v;
        }
    }
    return -1;
}

/* p as one factor raised to e, appended to t: an atom x, 1 - x, or a
 * parenthesised sum with its first term positive (the sign goes to t) */
static void push_factor(PTerm *t, const fmpz_mpoly_t p, ulong e, int depth,
                        const Ctx *c)
{
    const Ring *r = c->r;
    int sign = 1;
    slong v = bar_var(p, c, &sign);
    if (v >= 0) {
        if (sign < 0 && (e & 1))
            t->neg ^= 1;
        term_push(t, (Atom){AT_BAR, v, NULL, NULL, NULL, e});
        return;
    }
    PSum *s = render(p, depth, c);
    if (s->n == 1) {
        /* a monomial (or a constant): its pieces, to the power e */
        PTerm *u = &s->t[0];
        if (u->neg && (e & 1))
            t->neg ^= 1;
        fmpz_t pw;
        fmpz_init(pw);
        fmpz_pow_ui(pw, u->coeff, e);
        fmpz_mul(t->coeff, t->coeff, pw);
        fmpz_clear(pw);
        for (slong i = 0; i < u->n; i++) {
            Atom a = u->a[i];
            a.exp *= e;
            term_push(t, a);
        }
        free(u->a);
        u->a = NULL;
        u->n = 0;
        sum_free(s, c);
        return;
    }
    if (s->t[0].neg) {
        sum_neg(s, c);
        if (e & 1)
            t->neg ^= 1;
    }
    (void)r;
    term_push(t, (Atom){AT_SUM, -1, s, NULL, NULL, e});
}

/* the proofs above, for the unit tests (book.h) */
int book_test_surely_irreducible(const fmpz_mpoly_t p, const Ring *r)
{
    return polyfactor_surely_irreducible(p, r);
}

int book_test_irreducible_mod_small_prime(const fmpz_poly_t u)
{
    return polyfactor_irreducible_mod_small_prime(u);
}

int book_test_quadratic_irreducible(const fmpz_poly_t u)
{
    return polyfactor_quadratic_irreducible(u);
}

/* FLINT's factorisation of p (ring_factor), or what form_factored makes
 * of it, when p is a constant times a monomial times powers of x - 1 (x a
 * param or const) times a polynomial q that polyfactor_surely_irreducible
 * proves irreducible (or 1), without FLINT's factoring (most of the
 * printing time).  FLINT's factoring first takes out the integer content (with the
 * sign of p's leading term), then the powers of the variables in their
 * order (fmpz_mpoly_factor_content), then splits the rest:
 *   - without the powers of x - 1, the rest, q, stays whole, in both of
 *     ring_factor's ways: the same factors in the same order;
 *   - with them, when ring_factor factors fully (ring_factor_affordable):
 *     the same factors, up to their order after the monomials; an order
 *     form_factored does not see, as a power of x - 1 is an atom (\bar{x})
 *     and only q is rendered (the squarefree way might keep a product of
 *     them whole: not taken).
 * 0: no such proof (f untouched). */
static int factor_known(fmpz_mpoly_factor_t f, const fmpz_mpoly_t p,
                        const Ctx *c)
{
    const Ring *r = c->r;
    enum { SQUAREFREE_MAX_TERMS = 4096 }; /* ring_factor's: beyond, it fails */
    slong len = fmpz_mpoly_length(p, r->ctx), nv = r->ctx->minfo->nvars;
    if (len < 2 || len > SQUAREFREE_MAX_TERMS ||
        !fmpz_mpoly_degrees_fit_si(p, r->ctx))
        return 0;
    fmpz_t g;
    fmpz_init(g);
    _fmpz_vec_content(g, p->coeffs, len);
    if (fmpz_sgn(p->coeffs + 0) < 0)
        fmpz_neg(g, g);
    ulong *lo = pc_xmalloc(sizeof(ulong) * (size_t)nv);
    ulong *e = pc_xmalloc(sizeof(ulong) * (size_t)nv);
    for (slong k = 0; k < len; k++) {
        fmpz_mpoly_get_term_exp_ui(e, p, k, r->ctx);
        for (slong v = 0; v < nv; v++)
            lo[v] = k == 0 || e[v] < lo[v] ? e[v] : lo[v];
    }
    fmpz_mpoly_t q;
    fmpz_mpoly_init(q, r->ctx);
    fmpz_t cq;
    fmpz_init(cq);
    for (slong k = 0; k < len; k++) {
        fmpz_mpoly_get_term_exp_ui(e, p, k, r->ctx);
        for (slong v = 0; v < nv; v++)
            e[v] -= lo[v];
        fmpz_divexact(cq, p->coeffs + k, g);
        fmpz_mpoly_push_term_fmpz_ui(q, cq, e, r->ctx);
    }
    /* (the same order: dividing by a monomial keeps degrevlex's) */
    /* powers of x - 1, when FLINT factors fully */
    ulong *bars = pc_xcalloc((size_t)nv, sizeof(ulong));
    int nbars = 0;
    if (ring_factor_affordable(p, r)) {
        fmpz_mpoly_t bar, quo;
        fmpz_mpoly_init(bar, r->ctx);
        fmpz_mpoly_init(quo, r->ctx);
        for (slong v = 0; v < c->nparams + c->nconsts && v < nv; v++) {
            fmpz_mpoly_gen(bar, v, r->ctx);
            fmpz_mpoly_sub_ui(bar, bar, 1, r->ctx);
            while (fmpz_mpoly_degree_si(q, v, r->ctx) > 0 &&
                   polyfactor_vanishes_at_ones(q, r) &&
                   fmpz_mpoly_divides(quo, q, bar, r->ctx)) {
                fmpz_mpoly_swap(q, quo, r->ctx);
                bars[v]++;
            }
            nbars += bars[v] > 0;
        }
        fmpz_mpoly_clear(quo, r->ctx);
        fmpz_mpoly_clear(bar, r->ctx);
    }
    /* q: 1 (only with powers of x - 1: p is not linear), or irreducible */
    int unit = fmpz_mpoly_is_one(q, r->ctx);
    int ok = unit ? nbars > 0 : polyfactor_surely_irreducible(q, r);
    if (ok) {
        slong n = 1 + nbars;
        for (slong v = 0; v < nv; v++)
            n += lo[v] > 0;
        fmpz_mpoly_factor_fit_length(f, n, r->ctx);
        fmpz_swap(f->constant, g);
        f->num = 0;
        for (slong v = 0; v < nv; v++)
            if (lo[v] > 0) {
                fmpz_mpoly_gen(f->poly + f->num, v, r->ctx);
                fmpz_set_ui(f->exp + f->num, lo[v]);
                f->num++;
            }
        for (slong v = 0; v < nv; v++)
            if (bars[v] > 0) {
                fmpz_mpoly_gen(f->poly + f->num, v, r->ctx);
                fmpz_mpoly_sub_ui(f->poly + f->num, f->poly + f->num, 1,
                                  r->ctx);
                fmpz_set_ui(f->exp + f->num, bars[v]);
                f->num++;
            }
        if (!unit) {
            fmpz_mpoly_swap(f->poly + f->num, q, r->ctx);
            fmpz_one(f->exp + f->num);
            f->num++;
        }
    }
    free(bars);
    fmpz_clear(cq);
    fmpz_mpoly_clear(q, r->ctx);
    free(e);
    free(lo);
    fmpz_clear(g);
    return ok;
}

static PSum *form_factored(const fmpz_mpoly_t p, int depth, const Ctx *c)
{
    const Ring *r = c->r;
    if (fmpz_mpoly_total_degree_si(p, r->ctx) <= 1) {
        /* linear: irreducible but for its integer content */
        fmpz_t g;
        fmpz_init(g);
        _fmpz_vec_content(g, p->coeffs, fmpz_mpoly_length(p, r->ctx));
        PSum *s = NULL;
        if (!fmpz_is_one(g)) {
            fmpz_mpoly_t q;
            fmpz_mpoly_init(q, r->ctx);
            fmpz_mpoly_scalar_divexact_fmpz(q, p, g, r->ctx);
            s = sum_new(c);
            PTerm *t = sum_push(s);
            fmpz_set(t->coeff, g);
            push_factor(t, q, 1, depth + 1, c);
            sum_finish(s, p, c);
            fmpz_mpoly_clear(q, r->ctx);
        }
        fmpz_clear(g);
        return s;
    }
    fmpz_mpoly_factor_t f;
    fmpz_mpoly_factor_init(f, r->ctx);
    if (!factor_known(f, p, c) && !polyfactor_compact(f, p, r)) {
        fmpz_mpoly_factor_clear(f, r->ctx);
        return NULL;
    }
    /* trivial: p itself, irreducible and primitive */
    if (f->num == 0 || (f->num == 1 && fmpz_is_pm1(f->constant) &&
                        fmpz_is_one(f->exp))) {
        fmpz_mpoly_factor_clear(f, r->ctx);
        return NULL;
    }
    PSum *s = sum_new(c);
    PTerm *t = sum_push(s);
    t->neg = fmpz_sgn(f->constant) < 0;
    fmpz_abs(t->coeff, f->constant);
    for (slong i = 0; i < f->num; i++)
        push_factor(t, f->poly + i, fmpz_get_ui(f->exp + i), depth + 1, c);
    fmpz_mpoly_factor_clear(f, r->ctx);
    sum_finish(s, p, c);
    return s;
}

/* appends coefficient k (a polynomial free of x) times the atoms of x to
 * s: the coefficient's best form, merged when it is one term */
static void push_collected(PSum *s, const fmpz_mpoly_t coef, Atom *xs,
                           int nx, int depth, const Ctx *c)
{
    PSum *cs = render(coef, depth + 1, c);
    int bare = 1;
    for (int i = 0; i < nx; i++)
        bare &= xs[i].exp == 0;
    if (bare && cs->n > 1) {
        /* x^0: the coefficient's terms join the sum */
        for (slong i = 0; i < cs->n; i++) {
            PTerm *t = sum_push(s);
            term_absorb(t, &cs->t[i]);
        }
        sum_free(cs, c);
        return;
    }
    PTerm *t = sum_push(s);
    if (cs->n == 1) {
        term_absorb(t, &cs->t[0]);
        sum_free(cs, c);
    } else {
        if (cs->t[0].neg) {
            sum_neg(cs, c);
            t->neg ^= 1;
        }
        term_push(t, (Atom){AT_SUM, -1, cs, NULL, NULL, 1});
    }
    for (int i = 0; i < nx; i++)
        if (xs[i].exp)
            term_push(t, xs[i]);
}

/* the coefficients a[0..n] of p in powers of x (caller clears) */
static fmpz_mpoly_struct *coeffs_in(const fmpz_mpoly_t p, slong x, slong n,
                                    const Ctx *c)
{
    fmpz_mpoly_struct *a = pc_xmalloc(sizeof(fmpz_mpoly_struct) *
                                      (size_t)(n + 1));
    for (slong i = 0; i <= n; i++) {
        fmpz_mpoly_init(a + i, c->r->ctx);
        fmpz_mpoly_get_coeff_vars_ui(a + i, p, &x, (ulong *)&i, 1,
                                     c->r->ctx);
    }
    return a;
}

static void coeffs_clear(fmpz_mpoly_struct *a, slong n, const Ctx *c)
{
    for (slong i = 0; i <= n; i++)
        fmpz_mpoly_clear(a + i, c->r->ctx);
    free(a);
}

/* p = sum_k c_k x^k, ascending */
static PSum *form_powers(const fmpz_mpoly_t p, slong x, int depth,
                         const Ctx *c)
{
    slong n = fmpz_mpoly_degree_si(p, x, c->r->ctx);
    fmpz_mpoly_struct *a = coeffs_in(p, x, n, c);
    PSum *s = sum_new(c);
    for (slong k = 0; k <= n; k++) {
        if (fmpz_mpoly_is_zero(a + k, c->r->ctx))
            continue;
        Atom xa = {AT_VAR, x, NULL, NULL, NULL, (ulong)k};
        push_collected(s, a + k, &xa, 1, depth, c);
    }
    coeffs_clear(a, n, c);
    sum_finish(s, p, c);
    return s;
}

/* bk = sum_{i <= k} a[stride*i] C(n - i, k - i): the k-th Bernstein
 * coefficient (without binomials) of the polynomial whose coefficients are
 * a[0], a[stride], ... (tmp and bin: scratch) */
static void bernstein_coeff(fmpz_mpoly_t bk, const fmpz_mpoly_struct *a,
                            slong stride, slong n, slong k, fmpz_mpoly_t tmp,
                            fmpz_t bin, const Ring *r)
{
    fmpz_mpoly_zero(bk, r->ctx);
    for (slong i = 0; i <= k; i++) {
        fmpz_bin_uiui(bin, (ulong)(n - i), (ulong)(k - i));
        fmpz_mpoly_scalar_mul_fmpz(tmp, a + stride * i, bin, r->ctx);
        fmpz_mpoly_add(bk, bk, tmp, r->ctx);
    }
}

/* p = sum_k b_k x^k (1 - x)^(n-k), n = deg_x p: the Bernstein basis of
 * the param x (without binomials), b_k = sum_{i<=k} a_i C(n-i, k-i) */
static PSum *form_bernstein(const fmpz_mpoly_t p, slong x, int depth,
                            const Ctx *c)
{
    const Ring *r = c->r;
    slong n = fmpz_mpoly_degree_si(p, x, r->ctx);
    fmpz_mpoly_struct *a = coeffs_in(p, x, n, c);
    PSum *s = sum_new(c);
    fmpz_mpoly_t bk, tmp;
    fmpz_mpoly_init(bk, r->ctx);
    fmpz_mpoly_init(tmp, r->ctx);
    fmpz_t bin;
    fmpz_init(bin);
    for (slong k = 0; k <= n; k++) {
        bernstein_coeff(bk, a, 1, n, k, tmp, bin, r);
        if (fmpz_mpoly_is_zero(bk, r->ctx))
            continue;
        Atom xs[2] = {{AT_VAR, x, NULL, NULL, NULL, (ulong)k},
                      {AT_BAR, x, NULL, NULL, NULL, (ulong)(n - k)}};
        push_collected(s, bk, xs, 2, depth, c);
    }
    fmpz_clear(bin);
    fmpz_mpoly_clear(tmp, r->ctx);
    fmpz_mpoly_clear(bk, r->ctx);
    coeffs_clear(a, n, c);
    sum_finish(s, p, c);
    return s;
}

/* the cos kernel of the same argument as sin kernel var v (its companion:
 * cos^2 = 1 - sin^2), or -1 */
static slong cos_companion(slong v, const Ctx *c)
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

/* p (even in s = sin(x), free of w = cos(x)) as a polynomial in y = s^2,
 * in the basis y^k (1 - y)^(n-k) with 1 - y = cos(x)^2: the book's
 * a^2*sin(phi)^2 + b^2*cos(phi)^2 for the normal form's b^2 - b^2*sin(phi)^2
 * + a^2*sin(phi)^2 (form_bernstein in y); NULL when p is not such */
static PSum *form_sin2(const fmpz_mpoly_t p, slong s, slong w, int depth,
                       const Ctx *c)
{
    const Ring *r = c->r;
    slong n2 = fmpz_mpoly_degree_si(p, s, r->ctx);
    if (n2 < 2 || (n2 & 1) || fmpz_mpoly_degree_si(p, w, r->ctx) > 0)
        return NULL;
    fmpz_mpoly_struct *a = coeffs_in(p, s, n2, c);
    for (slong i = 1; i <= n2; i += 2)
        if (!fmpz_mpoly_is_zero(a + i, r->ctx)) {
            coeffs_clear(a, n2, c);
            return NULL;
        }
    slong n = n2 / 2;
    PSum *sum = sum_new(c);
    fmpz_mpoly_t bk, tmp;
    fmpz_mpoly_init(bk, r->ctx);
    fmpz_mpoly_init(tmp, r->ctx);
    fmpz_t bin;
    fmpz_init(bin);
    for (slong k = 0; k <= n; k++) {
        bernstein_coeff(bk, a, 2, n, k, tmp, bin, r);
        if (fmpz_mpoly_is_zero(bk, r->ctx))
            continue;
        Atom xs[2] = {{AT_VAR, s, NULL, NULL, NULL, (ulong)(2 * k)},
                      {AT_VAR, w, NULL, NULL, NULL, (ulong)(2 * (n - k))}};
        push_collected(sum, bk, xs, 2, depth, c);
    }
    fmpz_clear(bin);
    fmpz_mpoly_clear(tmp, r->ctx);
    fmpz_mpoly_clear(bk, r->ctx);
    coeffs_clear(a, n2, c);
    sum_finish(sum, p, c);
    return sum;
}

/* the length of s's text form (whatever the style): measured only when a
 * tie between two collected forms needs it */
static size_t text_len(const PSum *s, const Ctx *c)
{
    Ctx text = *c;
    text.latex = 0;
    return sum_text_len(s, &text);
}

/* keeps the better of *best and cand: fewer leaves; then factored before
 * expanded before collected; among collected forms the shorter text, then
 * Bernstein before powers; then the earlier candidate.  Lengths are those
 * of the text form whatever the style, so text and LaTeX agree (*best_len:
 * (size_t)-1 until measured). */
static void keep_better(PSum **best, int *best_rank, size_t *best_len,
                        PSum *cand, int rank, const Ctx *c)
{
    if (!cand)
        return;
    size_t len = (size_t)-1;
    if (*best) {
        slong lb = sum_leaves(*best), lc = sum_leaves(cand);
        int kb = *best_rank < 2 ? *best_rank : 2;
        int kc = rank < 2 ? rank : 2;
        int better = lc < lb || (lc == lb && kc < kb);
        if (lc == lb && kc == kb && kc == 2) {
            if (*best_len == (size_t)-1)
                *best_len = text_len(*best, c);
            len = text_len(cand, c);
            better = len < *best_len ||
                     (len == *best_len && rank < *best_rank);
        }
        if (!better) {
            sum_free(cand, c);
            return;
        }
        sum_free(*best, c);
    }
    *best = cand;
    *best_rank = rank;
    *best_len = len;
}

static PSum *render_new(const fmpz_mpoly_t p, int depth, const Ctx *c);

enum { MEMO_MAX = 1024 };

/* A partial factoring without FLINT's (deep inside a form, where full
 * factoring would cost more than it shows): the integer content, the
 * monomial content, powers of 1 - x of params and consts, and a perfect
 * square.  NULL when none of these is there. */
static PSum *form_factored_cheap(const fmpz_mpoly_t p, int depth,
                                 const Ctx *c)
{
    const Ring *r = c->r;
    slong nv = r->nvars;
    fmpz_mpoly_t q, m, bar, quo;
    fmpz_mpoly_init(q, r->ctx);
    fmpz_mpoly_init(m, r->ctx);
    fmpz_mpoly_init(bar, r->ctx);
    fmpz_mpoly_init(quo, r->ctx);
    PSum *s = sum_new(c);
    PTerm *t = sum_push(s);
    int found = 0;
    /* integer content, with the sign of the first (ascending) term */
    _fmpz_vec_content(t->coeff, p->coeffs, fmpz_mpoly_length(p, r->ctx));
    fmpz_mpoly_scalar_divexact_fmpz(q, p, t->coeff, r->ctx);
    found |= !fmpz_is_one(t->coeff);
    /* the monomial content */
    ulong *lo = pc_xmalloc(sizeof(ulong) * (size_t)(nv ? nv : 1));
    ulong *e = pc_xmalloc(sizeof(ulong) * (size_t)(nv ? nv : 1));
    for (slong k = 0; k < fmpz_mpoly_length(q, r->ctx); k++) {
        fmpz_mpoly_get_term_exp_ui(e, q, k, r->ctx);
        for (slong v = 0; v < nv; v++)
            lo[v] = k == 0 || e[v] < lo[v] ? e[v] : lo[v];
    }
    for (slong v = 0; v < nv; v++)
        if (lo[v]) {
            fmpz_mpoly_gen(m, v, r->ctx);
            fmpz_mpoly_pow_ui(m, m, lo[v], r->ctx);
            fmpz_mpoly_divides(q, q, m, r->ctx);
            term_push(t, (Atom){AT_VAR, v, NULL, NULL, NULL, lo[v]});
            found = 1;
        }
    /* (1 - x)^k */
    for (slong v = 0; v < c->nparams + c->nconsts && v < nv; v++) {
        ulong k = 0;
        fmpz_mpoly_gen(bar, v, r->ctx);
        fmpz_mpoly_neg(bar, bar, r->ctx);
        fmpz_mpoly_add_si(bar, bar, 1, r->ctx);
        while (fmpz_mpoly_degree_si(q, v, r->ctx) > 0 &&
               fmpz_mpoly_length(q, r->ctx) > 1 && polyfactor_vanishes_at_ones(q, r) &&
               fmpz_mpoly_divides(quo, q, bar, r->ctx)) {
            fmpz_mpoly_swap(q, quo, r->ctx);
            k++;
        }
        if (k) {
            term_push(t, (Atom){AT_BAR, v, NULL, NULL, NULL, k});
            found = 1;
        }
    }
    free(lo);
    free(e);
    if (fmpz_mpoly_is_fmpz(q, r->ctx)) {
        /* what is left is a unit: its sign */
        if (fmpz_sgn(q->coeffs) < 0)
            t->neg ^= 1;
    } else if (fmpz_mpoly_length(q, r->ctx) > 1 &&
               fmpz_mpoly_sqrt(m, q, r->ctx)) {
        push_factor(t, m, 2, depth + 1, c);
        found = 1;
    } else if (found) {
        push_factor(t, q, 1, depth + 1, c);
    }
    fmpz_mpoly_clear(q, r->ctx);
    fmpz_mpoly_clear(m, r->ctx);
    fmpz_mpoly_clear(bar, r->ctx);
    fmpz_mpoly_clear(quo, r->ctx);
    if (!found) {
        sum_free(s, c);
        return NULL;
    }
    sum_finish(s, p, c);
    return s;
}

/* p in its best form (see book.h), remembered per output */
static PSum *render_memo(const fmpz_mpoly_t p, int depth, const Ctx *c);

/* the atoms of s (and of its sums) that are vars marked in is_abs become
 * |x| */
static void mark_abs(PSum *s, const unsigned char *is_abs)
{
    for (slong i = 0; i < s->n; i++)
        for (slong j = 0; j < s->t[i].n; j++) {
            Atom *a = &s->t[i].a[j];
            if (a->kind == AT_VAR && is_abs[a->var])
                a->kind = AT_ABS;
            else if (a->kind == AT_SUM)
                mark_abs(a->sum, is_abs);
        }
}

/* p in its best form; a p with x*sign(x) in it is written through |x|
 * (absform.h) */
static PSum *render(const fmpz_mpoly_t p, int depth, const Ctx *c)
{
    if (!c->has_sign || c->is_abs)
        return render_memo(p, depth, c);
    const Ring *r = c->r;
    unsigned char *mask = pc_xcalloc((size_t)(r->nvars ? r->nvars : 1), 1);
    fmpz_mpoly_t q;
    fmpz_mpoly_init(q, r->ctx);
    PSum *s;
    if (absform_rewrite(q, mask, p, c->K, r) > 0) {
        Ctx a = *c;
        a.is_abs = mask;
        a.mode = 1;
        for (slong v = 0; v < r->nvars; v++)
            a.mode = a.mode * 31 + mask[v];
        a.mode |= 1;
        s = render_memo(q, depth, &a);
        mark_abs(s, mask);
    } else {
        s = render_memo(p, depth, c);
    }
    fmpz_mpoly_clear(q, r->ctx);
    free(mask);
    return s;
}

static PSum *render_memo(const fmpz_mpoly_t p, int depth, const Ctx *c)
{
    Memo *m = c->memo;
    slong len = fmpz_mpoly_length(p, c->r->ctx);
    if (len < 2 || !m)
        return render_new(p, depth, c);
    for (slong i = 0; i < m->n; i++)
        if (m->e[i].depth == depth && m->e[i].mode == c->mode &&
            fmpz_mpoly_length(m->e[i].poly, c->r->ctx) == len &&
            fmpz_mpoly_equal(m->e[i].poly, p, c->r->ctx))
            return sum_copy(m->e[i].sum, c);
    PSum *s = render_new(p, depth, c);
    if (m->n < MEMO_MAX) {
        if (m->n == m->alloc) {
            m->alloc = m->alloc ? 2 * m->alloc : 32;
            m->e = pc_xrealloc(m->e, sizeof(MemoEntry) * (size_t)m->alloc);
        }
        MemoEntry *e = &m->e[m->n++];
        fmpz_mpoly_init(e->poly, c->r->ctx);
        fmpz_mpoly_set(e->poly, p, c->r->ctx);
        e->depth = depth;
        e->mode = c->mode;
        e->sum = sum_copy(s, c);
    }
    return s;
}

static PSum *render_new(const fmpz_mpoly_t p, int depth, const Ctx *c)
{
    enum { R_FACTORED, R_EXPANDED, R_BERNSTEIN, R_POWERS };
    const Ring *r = c->r;
    slong len = fmpz_mpoly_length(p, r->ctx);
    PSum *best = form_expanded(p, c);
    if (len == 0 || fmpz_mpoly_is_fmpz(p, r->ctx))
        return best;
    int rank = R_EXPANDED;
    size_t blen = (size_t)-1;
    *c->work += len;
    if (len < 2)
        return best; /* a monomial: expanded is factored */
    if (depth < CHEAP_FACTOR_DEPTH &&
        (depth == 0 ||
         (*c->work < RENDER_WORK && len <= MAX_FACTOR_TERMS_NESTED))) {
        *c->work += FACTOR_WORK + 20 * len;
        keep_better(&best, &rank, &blen, form_factored(p, depth, c),
                    R_FACTORED, c);
    } else if (depth >= CHEAP_FACTOR_DEPTH) {
        *c->work += 4 * len;
        keep_better(&best, &rank, &blen, form_factored_cheap(p, depth, c),
                    R_FACTORED, c);
    }
    if (depth >= MAX_DEPTH || len > MAX_COLLECT_TERMS || len < 2)
        return best;
    for (slong v = 0; v < r->nvars && *c->work < RENDER_WORK; v++) {
        if (fmpz_mpoly_degree_si(p, v, r->ctx) < 1)
            continue;
        *c->work += 2 * len;
        if (is_param(c, v))
            keep_better(&best, &rank, &blen, form_bernstein(p, v, depth, c),
                        R_BERNSTEIN, c);
        slong w = c->K ? cos_companion(v, c) : -1;
        if (w >= 0)
            keep_better(&best, &rank, &blen, form_sin2(p, v, w, depth, c),
                        R_BERNSTEIN, c);
        keep_better(&best, &rank, &blen, form_powers(p, v, depth, c),
                    R_POWERS, c);
    }
    return best;
}

/* ---- roots where the user put them ----------------------------------------
 */

/* The normal form rationalises: b*cos(phi)/sqrt(X) is kept as
 * b*cos(phi)*sqrt(X)/X, and 1/(a - c*cos(phi)) (c a root) as
 * (a + c*cos(phi))/(a^2 - c^2*cos(phi)^2) reduced.  The printer undoes it
 * where that is shorter: for a root kernel s (s^2 = X) and a multiplier
 * Lb = P - Q*s (the conjugate of L = P + Q*s),
 *     N/D = reduce(N*Lb)/(D*Lb),
 * and G = reduce(L*Lb) = P^2 - Q^2*X (free of s) cancels when it divides D
 * and every reduce(N*Lb): the weight becomes M/(D1*Lb), D = G*D1.  The
 * multipliers tried: s itself (P = 0: N*s/X -> N/s), and the conjugates of
 * the numerators' factors of degree 1 in s.  Every candidate is exactly
 * equal (the relations are identities); the shortest text wins. */

/* p modulo the kernels' relations v^q = rel, for polynomial rels; 0 when
 * a relation with a denominator would be needed (p then unusable) */
static int reduce_rel(fmpz_mpoly_t p, const Ctx *c)
{
    const Ring *r = c->r;
    const Kernels *K = c->K;
    if (!K)
        return 1;
    int ok = 1;
    fmpz_mpoly_t res, cj, rp, m;
    fmpz_mpoly_init(res, r->ctx);
    fmpz_mpoly_init(cj, r->ctx);
    fmpz_mpoly_init(rp, r->ctx);
    fmpz_mpoly_init(m, r->ctx);
    /* later kernels first: a relation uses only earlier variables */
    for (slong i = K->n - 1; i >= 0 && ok; i--) {
        const Kernel *k = &K->k[i];
        slong v = k->var, q = k->deg;
        if (q < 2 || fmpz_mpoly_degree_si(p, v, r->ctx) < q)
            continue;
        if (!fmpz_mpoly_is_one(k->rel->den, r->ctx)) {
            ok = 0;
            break;
        }
        slong n = fmpz_mpoly_degree_si(p, v, r->ctx);
        fmpz_mpoly_zero(res, r->ctx);
        for (slong j = 0; j <= n; j++) {
            ulong e = (ulong)j;
            fmpz_mpoly_get_coeff_vars_ui(cj, p, &v, &e, 1, r->ctx);
            if (fmpz_mpoly_is_zero(cj, r->ctx))
                continue;
            /* v^j = v^(j mod q) * rel^(j div q) */
            fmpz_mpoly_pow_ui(rp, k->rel->num, (ulong)(j / q), r->ctx);
            fmpz_mpoly_gen(m, v, r->ctx);
            fmpz_mpoly_pow_ui(m, m, (ulong)(j % q), r->ctx);
            fmpz_mpoly_mul(rp, rp, m, r->ctx);
            fmpz_mpoly_mul(rp, rp, cj, r->ctx);
            fmpz_mpoly_add(res, res, rp, r->ctx);
            if (fmpz_mpoly_length(res, r->ctx) > 4096)
                ok = 0;
        }
        fmpz_mpoly_swap(p, res, r->ctx);
    }
    fmpz_mpoly_clear(m, r->ctx);
    fmpz_mpoly_clear(rp, r->ctx);
    fmpz_mpoly_clear(cj, r->ctx);
    fmpz_mpoly_clear(res, r->ctx);
    return ok;
}

/* res = L with s replaced by -s */
static void conj_root(fmpz_mpoly_t res, const fmpz_mpoly_t L, slong s,
                      const Ctx *c)
{
    const Ring *r = c->r;
    ulong *e = pc_xmalloc(sizeof(ulong) * (size_t)(r->nvars ? r->nvars : 1));
    fmpz_t k;
    fmpz_init(k);
    fmpz_mpoly_zero(res, r->ctx);
    for (slong i = 0; i < fmpz_mpoly_length(L, r->ctx); i++) {
        fmpz_mpoly_get_term_exp_ui(e, L, i, r->ctx);
        fmpz_mpoly_get_term_coeff_fmpz(k, L, i, r->ctx);
        if (e[s] & 1)
            fmpz_neg(k, k);
        fmpz_mpoly_push_term_fmpz_ui(res, k, e, r->ctx);
    }
    fmpz_mpoly_sort_terms(res, r->ctx);
    fmpz_mpoly_combine_like_terms(res, r->ctx);
    fmpz_clear(k);
    free(e);
}

/* One form of n numerators over one denominator (the printers' input) */
typedef struct Cand {
    slong n;
    fmpz_mpoly_struct *num; // n numerators
    fmpz_mpoly_t den;
} Cand;

static void cand_init(Cand *x, slong n, const Ctx *c)
{
    x->n = n;
    x->num = pc_xmalloc(sizeof(fmpz_mpoly_struct) * (size_t)(n ? n : 1));
    for (slong i = 0; i < n; i++)
        fmpz_mpoly_init(x->num + i, c->r->ctx);
    fmpz_mpoly_init(x->den, c->r->ctx);
}

static void cand_clear(Cand *x, const Ctx *c)
{
    for (slong i = 0; i < x->n; i++)
        fmpz_mpoly_clear(x->num + i, c->r->ctx);
    free(x->num);
    fmpz_mpoly_clear(x->den, c->r->ctx);
}

/* N/D with the multiplier lb of root kernel s (above): 1 and *out when G
 * cancels */
static int unroot_with(Cand *out, const fmpz_mpoly_struct *const *N, slong n,
                       const fmpz_mpoly_t D, const fmpz_mpoly_t lb, slong s,
                       const Ctx *c)
{
    const Ring *r = c->r;
    fmpz_mpoly_t L, G, q;
    fmpz_mpoly_init(L, r->ctx);
    fmpz_mpoly_init(G, r->ctx);
    fmpz_mpoly_init(q, r->ctx);
    conj_root(L, lb, s, c);
    fmpz_mpoly_mul(G, L, lb, r->ctx);
    int ok = reduce_rel(G, c) && !fmpz_mpoly_is_fmpz(G, r->ctx) &&
             fmpz_mpoly_degree_si(G, s, r->ctx) == 0;
    if (ok) {
        fmpz_t g;
        fmpz_init(g);
        _fmpz_vec_content(g, G->coeffs, fmpz_mpoly_length(G, r->ctx));
        fmpz_mpoly_scalar_divexact_fmpz(G, G, g, r->ctx);
        fmpz_clear(g);
        cand_init(out, n, c);
        ok = fmpz_mpoly_divides(q, D, G, r->ctx);
        if (ok)
            fmpz_mpoly_mul(out->den, q, lb, r->ctx);
        for (slong i = 0; i < n && ok; i++) {
            fmpz_mpoly_mul(q, N[i], lb, r->ctx);
            ok = reduce_rel(q, c) &&
                 fmpz_mpoly_divides(out->num + i, q, G, r->ctx);
        }
        if (!ok)
            cand_clear(out, c);
    }
    fmpz_mpoly_clear(q, r->ctx);
    fmpz_mpoly_clear(G, r->ctx);
    fmpz_mpoly_clear(L, r->ctx);
    return ok;
}

enum { MAX_UNROOT = 6, MAX_UNROOT_TERMS = 200 };

/* the multipliers P -+ Q*s read off D (unroot_cands), tried; returns the
 * number of candidates put in cs (at most room) */
static slong den_cands(Cand *cs, slong room, const fmpz_mpoly_struct *const *N,
                       slong n, const fmpz_mpoly_t D, const Kernel *k,
                       const Ctx *c)
{
    const Ring *r = c->r;
    slong s = k->var, nc = 0;
    slong nv = r->nvars;
    fmpz_mpoly_t Dp, Q, T, P, lb, m;
    fmpz_mpoly_init(Dp, r->ctx);
    fmpz_mpoly_init(Q, r->ctx);
    fmpz_mpoly_init(T, r->ctx);
    fmpz_mpoly_init(P, r->ctx);
    fmpz_mpoly_init(lb, r->ctx);
    fmpz_mpoly_init(m, r->ctx);
    fmpz_t g;
    fmpz_init(g);
    _fmpz_vec_content(g, D->coeffs, fmpz_mpoly_length(D, r->ctx));
    fmpz_mpoly_scalar_divexact_fmpz(Dp, D, g, r->ctx);
    for (slong q = -1; q < nv && nc < room; q++) {
        if (q == s)
            continue;
        if (q >= 0) {
            int in_d = fmpz_mpoly_degree_si(D, q, r->ctx) > 0;
            slong cw = -1;
            for (slong v = 0; v < nv && cw < 0; v++)
                if (fmpz_mpoly_degree_si(D, v, r->ctx) > 0 &&
                    cos_companion(v, c) == q)
                    cw = q;
            if (!in_d && cw < 0)
                continue;
            fmpz_mpoly_gen(Q, q, r->ctx);
        } else {
            fmpz_mpoly_one(Q, r->ctx);
        }
        for (int sg = 0; sg < 2 && nc < room; sg++) {
            /* T = Q^2*X + D (D = Q^2*X - P^2 ... up to sign) */
            fmpz_mpoly_mul(T, Q, Q, r->ctx);
            fmpz_mpoly_mul(T, T, k->rel->num, r->ctx);
            if (sg)
                fmpz_mpoly_sub(T, T, Dp, r->ctx);
            else
                fmpz_mpoly_add(T, T, Dp, r->ctx);
            if (!reduce_rel(T, c) || fmpz_mpoly_is_zero(T, r->ctx) ||
                fmpz_mpoly_degree_si(T, s, r->ctx) > 0 ||
                !fmpz_mpoly_sqrt(P, T, r->ctx))
                continue;
            /* lb = P - Q*s, then P + Q*s */
            for (int pm = 0; pm < 2 && nc < room; pm++) {
                fmpz_mpoly_gen(m, s, r->ctx);
                fmpz_mpoly_mul(m, m, Q, r->ctx);
                if (pm)
                    fmpz_mpoly_add(lb, P, m, r->ctx);
                else
                    fmpz_mpoly_sub(lb, P, m, r->ctx);
                if (unroot_with(&cs[nc], N, n, D, lb, s, c))
                    nc++;
            }
        }
    }
    fmpz_clear(g);
    fmpz_mpoly_clear(m, r->ctx);
    fmpz_mpoly_clear(lb, r->ctx);
    fmpz_mpoly_clear(P, r->ctx);
    fmpz_mpoly_clear(T, r->ctx);
    fmpz_mpoly_clear(Q, r->ctx);
    fmpz_mpoly_clear(Dp, r->ctx);
    return nc;
}

/* the un-rationalised forms of N/D (at most MAX_UNROOT): returns their
 * number, *out malloc'd (cand_clear each, then free) */
static slong unroot_cands(Cand **out, const fmpz_mpoly_struct *const *N,
                          slong n, const fmpz_mpoly_t D,
                          const fmpz_mpoly_struct *const *H, slong nh,
                          const Ctx *c)
{
    const Ring *r = c->r;
    const Kernels *K = c->K;
    *out = NULL;
    if (!K || fmpz_mpoly_is_fmpz(D, r->ctx) || c->is_abs)
        return 0;
    slong len = fmpz_mpoly_length(D, r->ctx);
    for (slong i = 0; i < n; i++)
        len += fmpz_mpoly_length(N[i], r->ctx);
    if (len > MAX_UNROOT_TERMS)
        return 0;
    Cand *cs = pc_xmalloc(sizeof(Cand) * MAX_UNROOT);
    slong nc = 0;
    fmpz_mpoly_t lb;
    fmpz_mpoly_init(lb, r->ctx);
    for (slong ki = 0; ki < K->n && nc < MAX_UNROOT; ki++) {
        const Kernel *k = &K->k[ki];
        slong s = k->var;
        if (k->fn != KF_SQRT || k->deg != 2)
            continue;
        int used = 0;
        for (slong i = 0; i < n; i++)
            used |= fmpz_mpoly_degree_si(N[i], s, r->ctx) > 0;
        if (!used)
            continue;
        /* s itself */
        fmpz_mpoly_gen(lb, s, r->ctx);
        if (unroot_with(&cs[nc], N, n, D, lb, s, c))
            nc++;
        /* the conjugates of the numerators' factors linear in s (of N,
         * then of the hints: the other weights of the equation) */
        for (slong i = 0; i < n + nh && nc < MAX_UNROOT; i++) {
            const fmpz_mpoly_struct *x = i < n ? N[i] : H[i - n];
            if (fmpz_mpoly_degree_si(x, s, r->ctx) != 1 ||
                fmpz_mpoly_length(x, r->ctx) > MAX_UNROOT_TERMS ||
                !ring_factor_affordable(x, r))
                continue;
            fmpz_mpoly_factor_t f;
            fmpz_mpoly_factor_init(f, r->ctx);
            if (polyfactor_compact(f, x, r))
                for (slong j = 0; j < f->num && nc < MAX_UNROOT; j++) {
                    if (fmpz_mpoly_degree_si(f->poly + j, s, r->ctx) != 1 ||
                        fmpz_mpoly_length(f->poly + j, r->ctx) < 2)
                        continue;
                    conj_root(lb, f->poly + j, s, c);
                    if (unroot_with(&cs[nc], N, n, D, lb, s, c))
                        nc++;
                }
            fmpz_mpoly_factor_clear(f, r->ctx);
        }
        /* from the denominator: D = +-(P^2 - Q^2*X) up to its content,
         * for Q = 1 or a variable of D (or the cos of a sin of D): P the
         * square root of reduce(Q^2*X -+ D); 1/(a - c*cos(phi)) of a
         * focal conic, whose numerators need not show a - c*cos(phi) */
        if (fmpz_mpoly_is_one(k->rel->den, r->ctx) &&
            fmpz_mpoly_length(D, r->ctx) <= MAX_UNROOT_TERMS / 4)
            nc += den_cands(cs + nc, MAX_UNROOT - nc, N, n, D, k, c);
    }
    fmpz_mpoly_clear(lb, r->ctx);
    if (nc == 0) {
        free(cs);
        return 0;
    }
    *out = cs;
    return nc;
}

/* ---- equations ------------------------------------------------------------ */

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
    if (s->n == 0 || !s->t[0].neg)
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
    free(head);
    return 1;
}

static int sum_lead(PSum *s, const Ctx *c)
{
    if (s->n == 0 || !s->t[0].neg || sum_rotate(s))
        return 0;
    sum_neg(s, c);
    return 1;
}

static void push_item(PSum *eq, const fmpz_mpoly_t num, Atom pt,
                      const Ctx *c)
{
    PSum *s = render(num, 0, c);
    PTerm *t = sum_push(eq);
    if (s->n == 1) {
        term_absorb(t, &s->t[0]);
        sum_free(s, c);
    } else {
        if (sum_lead(s, c))
            t->neg = 1;
        term_push(t, (Atom){AT_SUM, -1, s, NULL, NULL, 1});
    }
    term_push(t, pt);
    term_sort(t, c);
}

static void put_frac(StrBuf *b, const char *num, int num_items,
                     const PSum *den, const Ctx *c)
{
    if (c->latex) {
        sb_puts(b, "\\frac{");
        sb_puts(b, num);
        sb_puts(b, "}{");
        put_sum(b, den, c);
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
    put_sum(b, den, c);
    if (pd)
        sb_puts(b, ")");
}

/* the denominator's form with its first term positive; *flip = 1 when
 * that negated it */
static PSum *render_den(const fmpz_mpoly_t den, const Ctx *c, int *flip)
{
    PSum *d = render(den, 0, c);
    *flip = d->t[0].neg;
    if (*flip)
        sum_neg(d, c);
    return d;
}

static int all_negative(const PSum *s)
{
    for (slong i = 0; i < s->n; i++)
        if (!s->t[i].neg)
            return 0;
    return s->n > 0;
}

/* writes items / den: an all-minus numerator as -(...)/den */
static void put_quotient(StrBuf *b, PSum *items, const PSum *den,
                         const Ctx *c)
{
    int minus = all_negative(items);
    if (minus)
        for (slong i = 0; i < items->n; i++)
            items->t[i].neg = 0;
    else if (den)
        sum_rotate(items); /* (a*cos(phi) - c)/d, not (-c + a*cos(phi))/d */
    StrBuf n = {0};
    put_sum(&n, items, c);
    if (minus)
        sb_puts(b, "-");
    if (!den)
        sb_puts(b, n.s);
    else
        put_frac(b, n.s, (int)items->n, den, c);
    free(n.s);
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
    PSum *s = render(num, 0, c);
    if (!den)
        put_sum(b, s, c);
    else
        put_quotient(b, s, den, c);
    sum_free(s, c);
    sum_free(den, c);
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
    slong nc = unroot_cands(&cs, &np, 1, den, H, nh, c);
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
        free(m.s);
    }
    if (best < 0)
        put(b, num, den, arg, c);
    else
        put(b, cs[best].num, cs[best].den, arg, c);
    for (slong i = 0; i < nc; i++)
        cand_clear(&cs[i], c);
    free(cs);
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
    PSum *one = sum_new(c);
    push_item(one, num, pa, c);
    int neg = one->t[0].neg;
    one->t[0].neg = 0;
    sb_puts(b, it->first ? (neg ? "-" : "") : (neg ? " - " : " + "));
    StrBuf n = {0};
    put_term(&n, &one->t[0], c);
    if (den && c->latex) {
        /* (A - C) \frac{n}{d}: the point outside the fraction */
        StrBuf m = {0};
        PSum *s = render(num, 0, c);
        sum_lead(s, c);
        put_sum(&m, s, c);
        sum_free(s, c);
        put_atom(b, &pa, c);
        sb_puts(b, " \\frac{");
        sb_puts(b, m.s);
        sb_puts(b, "}{");
        put_sum(b, den, c);
        sb_puts(b, "}");
        free(m.s);
    } else {
        sb_puts(b, n.s);
        if (den) {
            int pd =
                den->n > 1 || den->t[0].n + !fmpz_is_one(den->t[0].coeff) > 1;
            sb_puts(b, pd ? "/(" : "/");
            put_sum(b, den, c);
            if (pd)
                sb_puts(b, ")");
        }
    }
    free(n.s);
    sum_free(one, c);
    sum_free(den, c);
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
    free(H);
    if (o->kind == KIND_POINT) {
        sb_puts(b, first ? "" : " + ");
        put_point(b, d->points[origin], c);
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
        P->common = render(g, 0, c);
        if (P->common->t[0].neg) { /* keep g's first term positive */
            sum_neg(P->common, c);
            fmpz_mpoly_neg(g, g, r->ctx);
        }
    } else {
        fmpz_mpoly_one(g, r->ctx);
    }
    P->items = sum_new(c);
    char *used = pc_xcalloc((size_t)eq->len + 1, 1);
    for (slong i = 0; i < eq->len; i++) {
        if (used[i])
            continue;
        fmpz_mpoly_divides(q, eq->terms[i].num, g, r->ctx);
        if (flip)
            fmpz_mpoly_neg(q, q, r->ctx);
        Atom pt = {AT_POINT, -1, NULL, d->points[eq->terms[i].point], NULL,
                   1};
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
                PSum *probe = render(q, 0, c);
                if (probe->t[0].neg) {
                    pt.point2 = pt.point;
                    pt.point = d->points[eq->terms[j].point];
                    fmpz_mpoly_neg(q, q, r->ctx);
                }
                sum_free(probe, c);
                break;
            }
        }
        push_item(P->items, q, pt, c);
    }
    free(used);
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
    free(b.s);
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
    slong nc = unroot_cands(&cs, N, n, eq->den, NULL, 0, c);
    free(N);
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
        free(e.terms);
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
        cand_clear(&cs[k], c);
    free(cs);
    return res;
}

static void eq_form_clear(PointEqStruct *tmp, const PointEqStruct *used,
                          const Ctx *c)
{
    if (used != tmp)
        return;
    for (slong i = 0; i < tmp->len; i++)
        fmpz_mpoly_clear(tmp->terms[i].num, c->r->ctx);
    free(tmp->terms);
    fmpz_mpoly_clear(tmp->den, c->r->ctx);
}

static void eq_parts_clear(EqParts *P, const Ctx *c)
{
    sum_free(P->items, c);
    sum_free(P->den, c);
    sum_free(P->common, c);
}

static void put_common(StrBuf *b, const PSum *common, const Ctx *c)
{
    if (!common)
        return;
    if (common->n == 1) {
        put_term(b, &common->t[0], c);
    } else {
        sb_puts(b, c->latex ? "\\left(" : "(");
        put_sum(b, common, c);
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
    put_sum(&n, P->items, c);
    if (P->common) {
        put_common(b, P->common, c);
        if (!P->den) {
            int paren = P->items->n > 1;
            sb_puts(b, paren ? (c->latex ? "\\left(" : "(") : "");
            sb_puts(b, n.s);
            sb_puts(b, paren ? (c->latex ? "\\right)" : ")") : "");
        } else {
            put_frac(b, n.s, (int)P->items->n, P->den, c);
        }
    } else if (!P->den) {
        sb_puts(b, n.s);
    } else {
        put_frac(b, n.s, (int)P->items->n, P->den, c);
    }
    if (minus)
        for (slong i = 0; i < P->items->n; i++)
            P->items->t[i].neg = 1;
    free(n.s);
}

static void ctx_init(Ctx *c, const Derived *d, const BookOptions *opt,
                     long *work, Memo *memo)
{
    *work = 0;
    c->work = work;
    memo->e = NULL;
    memo->n = memo->alloc = 0;
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

char *book_rhs(const Derived *d, const DerivedOutput *o,
               const BookOptions *opt)
{
    Ctx c;
    long work;
    Memo memo;
    ctx_init(&c, d, opt, &work, &memo);
    c.line = o->line;
    StrBuf b = {0};
    rhs_into(&b, d, o, opt, &c);
    memo_clear(&memo, &c);
    return sb_take(&b);
}

/* ---- whole outputs --------------------------------------------------------- */

static void put_lhs(StrBuf *b, const DerivedOutput *o, const Ctx *c)
{
    if (!c->latex) {
        sb_puts(b, o->name);
        return;
    }
    if (o->diff_of) {
        sb_puts(b, "\\frac{\\mathrm{d}");
        put_exp(b, (ulong)o->diff_order, c);
        latex_name(b, o->diff_of);
        sb_puts(b, "}{\\mathrm{d}");
        latex_name(b, o->diff_var);
        put_exp(b, (ulong)o->diff_order, c);
        sb_puts(b, "}");
        return;
    }
    latex_name(b, o->name);
}

/* one line of a multline* (and the line break after it unless last),
 * itself broken where it is wider than the page (latexbreak.h) */
static void put_line(StrBuf *b, const char *line, int last)
{
    if (latex_width(line, strlen(line)) > LATEX_LINE_UNITS) {
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
            put_term(&line, &P->common->t[0], c);
        else
            sb_puts(&line, "1");
        sb_puts(&line, "}{");
        if (P->den)
            put_sum(&line, P->den, c);
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
        put_term(&item, &P->items->t[i], c);
        if (i > 0 && (int)(line.len + item.len + 1) > width) {
            put_line(b, line.s, 0);
            line.len = 0;
            line.s[0] = '\0';
        } else if (i > 0) {
            sb_puts(&line, " ");
        }
        sb_puts(&line, item.s);
        free(item.s);
    }
    sb_puts(&line, "\\Bigr)");
    put_line(b, line.s, 1);
    sb_puts(b, "\\end{multline*}\n");
    free(line.s);
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
    rhs_into(&rb, d, o, opt, &c);
    char *rhs = sb_take(&rb);
    int width = opt->width > 0 ? opt->width : 80;
    if (opt->latex && o->kind != KIND_SCALAR && opt->origin < 0) {
        /* a fraction is as wide as the longer of its two lines */
        PointEqStruct tmp;
        const PointEqStruct *eq = eq_form(&tmp, d, o, &c);
        EqParts P;
        eq_parts(&P, d, o, eq, &c);
        StrBuf n = {0}, dn = {0}, cm = {0};
        put_sum(&n, P.items, &c);
        if (P.den)
            put_sum(&dn, P.den, &c);
        put_common(&cm, P.common, &c);
        size_t wide = lhs.len + 3 + cm.len + (n.len > dn.len ? n.len : dn.len);
        free(n.s);
        free(dn.s);
        free(cm.s);
        if ((int)wide > width && P.items->n > 1) {
            put_multline(&b, &lhs, &P, &c, width);
            eq_parts_clear(&P, &c);
            eq_form_clear(&tmp, eq, &c);
            memo_clear(&memo, &c);
            free(rhs);
            free(lhs.s);
            return sb_take(&b);
        }
        eq_parts_clear(&P, &c);
        eq_form_clear(&tmp, eq, &c);
    }
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
        free(eq.s);
    } else {
        sb_puts(&b, lhs.s);
        sb_puts(&b, " = ");
        sb_puts(&b, rhs);
        sb_puts(&b, o->kind == KIND_VECTOR ? "    (vector)\n" : "\n");
    }
    memo_clear(&memo, &c);
    free(rhs);
    free(lhs.s);
    return sb_take(&b);
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
    memo_clear(m, &c);
    free(m);
}
