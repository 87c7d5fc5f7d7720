#include "compiler/format.h"

#include <ctype.h>
#include <stdlib.h>
#include <string.h>

#include <flint/fmpz_mpoly_factor.h>

#include "compiler/format_json.h"
#include "compiler/mem.h"

/* ---- a growable string ---------------------------------------------- */

typedef struct Buf {
    char *s;
    size_t len, cap;
} Buf;

static void buf_putn(Buf *b, const char *s, size_t n)
{
    if (b->len + n + 1 > b->cap) {
        b->cap = 2 * (b->len + n + 1) + 32;
        b->s = pc_xrealloc(b->s, b->cap);
    }
    memcpy(b->s + b->len, s, n);
    b->len += n;
    b->s[b->len] = '\0';
}

static void buf_puts(Buf *b, const char *s)
{
    buf_putn(b, s, strlen(s));
}

static void buf_fmpz(Buf *b, const fmpz_t c)
{
    char *s = fmpz_get_str(NULL, 10, c);
    buf_puts(b, s);
    flint_free(s);
}

static char *buf_take(Buf *b)
{
    if (!b->s)
        buf_puts(b, "");
    char *s = b->s;
    b->s = NULL;
    b->len = b->cap = 0;
    return s;
}

/* ---- names ----------------------------------------------------------- */

static const char *const greek[] = {
    "alpha", "beta",  "gamma", "delta", "epsilon", "zeta", "eta",
    "theta", "iota",  "kappa", "lambda", "mu",     "nu",   "xi",
    "pi",    "rho",   "sigma", "tau",   "upsilon", "phi",  "chi",
    "psi",   "omega", "Gamma", "Delta", "Theta",   "Lambda", "Xi",
    "Pi",    "Sigma", "Phi",   "Psi",   "Omega",
};

/* LaTeX for a name: greek words get a backslash; a lower-case stem followed
 * by upper-case letters or digits is subscripted (pD -> p_{D}, A1 -> A_{1}) */
static void latex_name(Buf *b, const char *name)
{
    size_t n = strlen(name), stem = 0;
    while (stem < n && isalpha((unsigned char)name[stem]) &&
           (stem == 0 || islower((unsigned char)name[stem])))
        stem++;
    const char *under = strchr(name, '_');
    if (under && under != name) {
        stem = (size_t)(under - name);
    }
    for (size_t g = 0; g < sizeof greek / sizeof greek[0]; g++)
        if (strlen(greek[g]) == stem && strncmp(greek[g], name, stem) == 0) {
            buf_puts(b, "\\");
            break;
        }
    buf_putn(b, name, stem);
    if (stem < n) {
        const char *sub = name + stem + (name[stem] == '_');
        buf_puts(b, "_{");
        buf_puts(b, sub);
        buf_puts(b, "}");
    }
}

/* ---- polynomials ------------------------------------------------------ */

/* Writes p expanded.  text: "2*t^2 - 2*t + 1"; json: "2*t^2-2*t+1";
 * latex: "2 t^{2} - 2 t + 1".  A polynomial with a negative leading
 * coefficient is written in ascending order ("1 - t"). */
static void put_poly(Buf *b, const fmpz_mpoly_t p, const Ring *r,
                     FormatStyle st)
{
    slong len = fmpz_mpoly_length(p, r->ctx);
    if (len == 0) {
        buf_puts(b, "0");
        return;
    }
    fmpz_t c;
    fmpz_init(c);
    ulong *e = pc_xmalloc(sizeof(ulong) * (size_t)(r->nvars ? r->nvars : 1));
    fmpz_mpoly_get_term_coeff_fmpz(c, p, 0, r->ctx);
    int reverse = fmpz_sgn(c) < 0 && len > 1;
    for (slong k = 0; k < len; k++) {
        slong i = reverse ? len - 1 - k : k;
        fmpz_mpoly_get_term_coeff_fmpz(c, p, i, r->ctx);
        fmpz_mpoly_get_term_exp_ui(e, p, i, r->ctx);
        int neg = fmpz_sgn(c) < 0;
        if (k == 0) {
            if (neg)
                buf_puts(b, "-");
        } else if (st == FMT_JSON) {
            buf_puts(b, neg ? "-" : "+");
        } else {
            buf_puts(b, neg ? " - " : " + ");
        }
        fmpz_abs(c, c);
        int any_var = 0;
        for (slong v = 0; v < r->nvars; v++)
            any_var |= e[v] != 0;
        int first = 1;
        if (!fmpz_is_one(c) || !any_var) {
            buf_fmpz(b, c);
            first = 0;
        }
        for (slong v = 0; v < r->nvars; v++) {
            if (!e[v])
                continue;
            if (!first)
                buf_puts(b, st == FMT_LATEX ? " " : "*");
            first = 0;
            if (st == FMT_LATEX && r->latex && r->latex[v])
                buf_puts(b, r->latex[v]);
            else if (st == FMT_LATEX)
                latex_name(b, r->names[v]);
            else
                buf_puts(b, r->names[v]);
            if (e[v] > 1) {
                char num[32];
                snprintf(num, sizeof num, st == FMT_LATEX ? "^{%lu}" : "^%lu",
                         e[v]);
                buf_puts(b, num);
            }
        }
    }
    free(e);
    fmpz_clear(c);
}

/* is p (up to the sign s) exactly 1 - v for a variable v?  returns v or -1 */
static slong one_minus_var(const fmpz_mpoly_t p, const Ring *r)
{
    if (fmpz_mpoly_length(p, r->ctx) != 2 || fmpz_mpoly_total_degree_si(p, r->ctx) != 1)
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

static int factor_cmp(const void *x, const void *y)
{
    const Factor *a = x, *b = y;
    if (a->len != b->len)
        return a->len < b->len ? -1 : 1;
    return 0;
}

/* Writes |p| as  [c] f1^e1 f2^e2 ... (the sign is NOT written: *negative
 * receives it).  Factors are normalised so their constant term is positive
 * (1 - t rather than t - 1), the book's habit; monomial factors come first.
 * With `positive` (a denominator), a factor of odd power is left as it was
 * when that is what keeps the whole positive: /(t - 1), not /(-(1 - t)).
 * Returns the number of items written (a constant counts as one), so that
 * callers can decide on parentheses. */
static int put_factored_ex(Buf *b, const fmpz_mpoly_t p, const Ring *r,
                           FormatStyle st, int *negative, int bare,
                           int positive)
{
    fmpz_mpoly_factor_t f;
    fmpz_mpoly_factor_init(f, r->ctx);
    if (fmpz_mpoly_is_zero(p, r->ctx) || !ring_factor(f, p, r)) {
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
            put_poly(b, q, r, st);
            fmpz_mpoly_clear(q, r->ctx);
            return 1;
        }
        int paren = !bare && fmpz_mpoly_length(p, r->ctx) > 1;
        if (paren)
            buf_puts(b, st == FMT_LATEX ? "\\left(" : "(");
        put_poly(b, p, r, st);
        if (paren)
            buf_puts(b, st == FMT_LATEX ? "\\right)" : ")");
        return 1;
    }
    int neg = fmpz_sgn(f->constant) < 0;
    Factor *fs = pc_xmalloc(sizeof(Factor) * (size_t)(f->num ? f->num : 1));
    ulong *zero = pc_xcalloc((size_t)(r->nvars ? r->nvars : 1) + 1, sizeof(ulong));
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
    qsort(fs, (size_t)f->num, sizeof(Factor), factor_cmp);
    int items = 0;
    fmpz_abs(c, f->constant);
    if (!fmpz_is_one(c) || f->num == 0) {
        buf_fmpz(b, c);
        items++;
    }
    for (slong i = 0; i < f->num; i++) {
        if (items)
            buf_puts(b, st == FMT_LATEX ? " " : "*");
        items++;
        slong v = st == FMT_LATEX ? one_minus_var(fs[i].poly, r) : -1;
        if (v >= 0 && r->latex && r->latex[v])
            v = -1; /* 1 - sin(t): no bar over a function */
        int atom = fs[i].len == 1 &&
                   fmpz_mpoly_total_degree_si(fs[i].poly, r->ctx) == 1;
        if (v >= 0) {
            buf_puts(b, "\\bar{");
            latex_name(b, r->names[v]);
            buf_puts(b, "}");
        } else if (atom || (bare && f->num == 1 && fs[i].exp == 1 &&
                            fmpz_is_one(c))) {
            put_poly(b, fs[i].poly, r, st);
        } else {
            buf_puts(b, st == FMT_LATEX ? "\\left(" : "(");
            put_poly(b, fs[i].poly, r, st);
            buf_puts(b, st == FMT_LATEX ? "\\right)" : ")");
        }
        if (fs[i].exp > 1) {
            char num[32];
            snprintf(num, sizeof num, st == FMT_LATEX ? "^{%lu}" : "^%lu",
                     fs[i].exp);
            buf_puts(b, num);
        }
    }
    fmpz_clear(c);
    free(zero);
    free(fs);
    fmpz_mpoly_factor_clear(f, r->ctx);
    *negative = neg;
    return items;
}

static int put_factored(Buf *b, const fmpz_mpoly_t p, const Ring *r,
                        FormatStyle st, int *negative)
{
    return put_factored_ex(b, p, r, st, negative, 0, 0);
}

/* writes a denominator after the fraction bar (text/json): "/2", "/t",
 * "/(2*t^2 - 2*t + 1)", "/(t*(1-t))" */
static void put_den(Buf *b, const fmpz_mpoly_t den, const Ring *r,
                    FormatStyle st)
{
    Buf d = {0};
    int neg;
    int items = put_factored_ex(&d, den, r, st, &neg, 0, 1);
    char *ds = buf_take(&d);
    int wrap = items > 1 || neg; /* "/(...)^2" and "/t^2" need no more */
    buf_puts(b, "/");
    if (wrap)
        buf_puts(b, "(");
    if (neg)
        buf_puts(b, "-");
    buf_puts(b, ds);
    if (wrap)
        buf_puts(b, ")");
    free(ds);
}

static int is_den_one(const RatFun w, const Ring *r)
{
    return fmpz_mpoly_is_one(w->den, r->ctx);
}

char *format_weight(const RatFun w, const Ring *r)
{
    Buf b = {0};
    Buf n = {0};
    int neg;
    put_factored(&n, w->num, r, FMT_JSON, &neg);
    if (neg)
        buf_puts(&b, "-");
    buf_puts(&b, n.s);
    free(n.s);
    if (!is_den_one(w, r))
        put_den(&b, w->den, r, FMT_JSON);
    return buf_take(&b);
}

/* ---- equations ---------------------------------------------------------- */

/* one "point times numerator" item of a sum, with its sign as an operator:
 * first: "A*t^2", "-3*B*(1-t)";  later: " + A*t^2", " - 3*B*(1-t)".
 * pre/post wrap the point name (used for "(A - C)"). */
static void put_term(Buf *b, const char *point, const fmpz_mpoly_t num,
                     const fmpz_mpoly_t den, const Ring *r, FormatStyle st,
                     int first)
{
    Buf n = {0};
    int neg;
    put_factored(&n, num, r, st, &neg);
    char *ns = buf_take(&n);
    if (first)
        buf_puts(b, neg ? "-" : "");
    else
        buf_puts(b, neg ? " - " : " + ");
    int unit = strcmp(ns, "1") == 0;
    int has_den = den && !fmpz_mpoly_is_one(den, r->ctx);
    if (st == FMT_LATEX && has_den) {
        buf_puts(b, point);
        buf_puts(b, " \\frac{");
        buf_puts(b, ns);
        buf_puts(b, "}{");
        int dneg;
        Buf d = {0};
        put_factored_ex(&d, den, r, st, &dneg, 1, 1);
        if (dneg)
            buf_puts(b, "-");
        buf_puts(b, d.s);
        free(d.s);
        buf_puts(b, "}");
        free(ns);
        return;
    }
    /* a leading integer coefficient goes before the point: 3*B*t */
    size_t lead = 0;
    while (isdigit((unsigned char)ns[lead]))
        lead++;
    if (lead > 0 && (ns[lead] == '*' || ns[lead] == ' ')) {
        buf_putn(b, ns, lead);
        buf_puts(b, st == FMT_LATEX ? " " : "*");
        buf_puts(b, point);
        buf_puts(b, st == FMT_LATEX ? " " : "*");
        buf_puts(b, ns + lead + 1);
    } else if (unit) {
        buf_puts(b, point);
    } else if (lead > 0 && ns[lead] == '\0') {
        buf_puts(b, ns);
        buf_puts(b, st == FMT_LATEX ? " " : "*");
        buf_puts(b, point);
    } else {
        buf_puts(b, point);
        buf_puts(b, st == FMT_LATEX ? " " : "*");
        buf_puts(b, ns);
    }
    if (has_den)
        put_den(b, den, r, st);
    free(ns);
}

static void point_label(Buf *b, const Derived *d, slong pt, slong origin,
                        FormatStyle st)
{
    if (origin >= 0)
        buf_puts(b, st == FMT_LATEX ? "\\left(" : "(");
    if (st == FMT_LATEX)
        latex_name(b, d->points[pt]);
    else
        buf_puts(b, d->points[pt]);
    if (origin >= 0) {
        buf_puts(b, " - ");
        if (st == FMT_LATEX)
            latex_name(b, d->points[origin]);
        else
            buf_puts(b, d->points[origin]);
        buf_puts(b, st == FMT_LATEX ? "\\right)" : ")");
    }
}

/* the right-hand side of a point equation (text or latex) */
static void put_equation(Buf *b, const Derived *d, const DerivedOutput *o,
                         FormatStyle st, slong origin)
{
    const Ring *r = &d->ring;
    const PointEq *eq = &o->eq;
    if ((*eq)->len == 0) {
        buf_puts(b, "0");
        return;
    }
    /* a denominator shared by every weight is pulled out */
    int shared = origin < 0;
    for (slong i = 1; i < (*eq)->len && shared; i++)
        shared = fmpz_mpoly_equal(o->w[i].den,
                                  o->w[0].den, r->ctx);
    if (shared && fmpz_mpoly_is_one(o->w[0].den, r->ctx))
        shared = 0;
    if (shared) {
        Buf n = {0};
        for (slong i = 0; i < (*eq)->len; i++) {
            Buf pl = {0};
            point_label(&pl, d, (*eq)->terms[i].point, -1, st);
            put_term(&n, pl.s, o->w[i].num, NULL, r, st, i == 0);
            free(pl.s);
        }
        if (st == FMT_LATEX) {
            buf_puts(b, "\\frac{");
            buf_puts(b, n.s);
            buf_puts(b, "}{");
            int dneg;
            Buf dd = {0};
            put_factored_ex(&dd, o->w[0].den, r, st, &dneg, 1, 1);
            if (dneg)
                buf_puts(b, "-");
            buf_puts(b, dd.s);
            free(dd.s);
            buf_puts(b, "}");
        } else {
            buf_puts(b, (*eq)->len > 1 ? "(" : "");
            buf_puts(b, n.s);
            buf_puts(b, (*eq)->len > 1 ? ")" : "");
            put_den(b, o->w[0].den, r, st);
        }
        free(n.s);
        return;
    }
    int first = 1;
    for (slong i = 0; i < (*eq)->len; i++) {
        slong pt = (*eq)->terms[i].point;
        if (pt == origin)
            continue;
        Buf pl = {0};
        point_label(&pl, d, pt, origin, st);
        put_term(b, pl.s, o->w[i].num, o->w[i].den, r, st,
                 first);
        free(pl.s);
        first = 0;
    }
    if (origin >= 0 && o->kind == KIND_POINT) {
        buf_puts(b, first ? "" : " + ");
        if (st == FMT_LATEX)
            latex_name(b, d->points[origin]);
        else
            buf_puts(b, d->points[origin]);
    } else if (first) {
        buf_puts(b, "0");
    }
}

static void put_scalar(Buf *b, const RatFun x, const Ring *r, FormatStyle st)
{
    int neg;
    Buf n = {0};
    put_factored(&n, x->num, r, st, &neg);
    if (st == FMT_LATEX && !fmpz_mpoly_is_one(x->den, r->ctx)) {
        Buf dd = {0};
        int dneg;
        put_factored_ex(&dd, x->den, r, st, &dneg, 1, 1);
        buf_puts(b, neg != dneg ? "-\\frac{" : "\\frac{");
        buf_puts(b, n.s);
        buf_puts(b, "}{");
        buf_puts(b, dd.s);
        buf_puts(b, "}");
        free(dd.s);
    } else {
        if (neg)
            buf_puts(b, "-");
        buf_puts(b, n.s);
        if (!fmpz_mpoly_is_one(x->den, r->ctx))
            put_den(b, x->den, r, st);
    }
    free(n.s);
}

char *format_output_rhs(const Derived *d, const DerivedOutput *o,
                        FormatStyle st, slong origin)
{
    Buf b = {0};
    if (o->kind == KIND_SCALAR)
        put_scalar(&b, o->scalar, &d->ring, st);
    else
        put_equation(&b, d, o, st, origin);
    return buf_take(&b);
}

char *format_scalar_expanded(const RatFun x, const Ring *r, FormatStyle st)
{
    Buf b = {0};
    int frac = !fmpz_mpoly_is_one(x->den, r->ctx);
    int multi = x->num->length > 1;
    if (st == FMT_LATEX && frac) {
        buf_puts(&b, "\\frac{");
        put_poly(&b, x->num, r, st);
        buf_puts(&b, "}{");
        put_poly(&b, x->den, r, st);
        buf_puts(&b, "}");
        return buf_take(&b);
    }
    if (frac && multi)
        buf_puts(&b, "(");
    put_poly(&b, x->num, r, st);
    if (frac && multi)
        buf_puts(&b, ")");
    if (frac) {
        int dmulti = x->den->length > 1 ||
                     (fmpz_mpoly_total_degree_si(x->den, r->ctx) > 0 &&
                      !fmpz_mpoly_is_gen(x->den, -1, r->ctx));
        buf_puts(&b, dmulti ? "/(" : "/");
        put_poly(&b, x->den, r, st);
        if (dmulti)
            buf_puts(&b, ")");
    }
    return buf_take(&b);
}

void format_derived(FILE *out, const Derived *d, FormatStyle st, slong origin)
{
    const Ring *r = &d->ring;
    if (st == FMT_JSON) {
        format_json(out, d);
        return;
    }
    for (slong i = 0; i < d->noutputs; i++) {
        const DerivedOutput *o = &d->outputs[i];
        Buf b = {0};
        if (st == FMT_LATEX)
            latex_name(&b, o->name);
        else
            buf_puts(&b, o->name);
        buf_puts(&b, " = ");
        if (o->kind == KIND_SCALAR)
            put_scalar(&b, o->scalar, r, st);
        else
            put_equation(&b, d, o, st, origin);
        if (st == FMT_LATEX)
            fprintf(out, "\\[ %s \\]\n", b.s);
        else
            fprintf(out, "%s%s\n", b.s,
                    o->kind == KIND_VECTOR ? "    (vector)" : "");
        free(b.s);
    }
}
