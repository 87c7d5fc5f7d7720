/*
 * print_latex.c - the report of `analyze --format latex` (analyze.h,
 * docs/analyze.md): the text report's findings with every formula in the
 * book's LaTeX (derive --format latex): names as A_{1}, \varphi
 * (poly_print_latex_name), derivatives as \frac{\mathrm{d}M}{\mathrm{d}t},
 * fractions as \frac, roots as \sqrt{5}.  Each curve is one paragraph;
 * the end points and the implicit equations are displayed (\[ ... \]).
 */
#include "compiler/analyze/analyze.h"

#include <math.h>
#include <string.h>

#include "base/mem.h"
#include "base/numfmt.h"
#include "base/strbuf.h"
#include "compiler/algebra/poly_print.h"

/* a name as LaTeX */
static void tex_name(StrBuf *b, const char *name)
{
    poly_print_latex_name(b, name);
}

/* the weights w over their common denominator: \frac{11 A - 3 B}{11} */
static void tex_combo(StrBuf *b, const fmpq *w, const Derived *d)
{
    fmpz_t L, k;
    fmpz_init_set_ui(L, 1);
    fmpz_init(k);
    for (slong i = 0; i < d->npoints; i++)
        if (!fmpq_is_zero(w + i))
            fmpz_lcm(L, L, fmpq_denref(w + i));
    slong firstpos = -1;
    for (slong i = 0; i < d->npoints && firstpos < 0; i++)
        if (fmpq_sgn(w + i) > 0)
            firstpos = i;
    StrBuf n = {0};
    for (slong j = -1; j < d->npoints; j++) { /* a positive term first */
        slong i = j < 0 ? firstpos : j;
        if (i < 0 || (j >= 0 && i == firstpos) || fmpq_is_zero(w + i))
            continue;
        fmpz_divexact(k, L, fmpq_denref(w + i));
        fmpz_mul(k, k, fmpq_numref(w + i));
        sb_puts(&n, n.len ? (fmpz_sgn(k) < 0 ? " - " : " + ")
                          : (fmpz_sgn(k) < 0 ? "-" : ""));
        fmpz_abs(k, k);
        if (!fmpz_is_one(k)) {
            sb_fmpz(&n, k);
            sb_puts(&n, " ");
        }
        tex_name(&n, d->points[i]);
    }
    if (!n.len)
        sb_puts(&n, "0");
    char *s = sb_take(&n);
    if (fmpz_is_one(L))
        sb_puts(b, s);
    else {
        sb_puts(b, "\\frac{");
        sb_puts(b, s);
        sb_puts(b, "}{");
        sb_fmpz(b, L);
        sb_puts(b, "}");
    }
    pc_free(s);
    fmpz_clear(k);
    fmpz_clear(L);
}

/* numeric weights: 0.5 A + 0.5 B */
static void tex_combo_num(StrBuf *b, const double *w, const Derived *d)
{
    double big = 0;
    for (slong i = 0; i < d->npoints; i++)
        big = fmax(big, fabs(w[i]));
    int any = 0;
    for (slong i = 0; i < d->npoints; i++) {
        if (w[i] == 0 || fabs(w[i]) <= 1e-14 * big)
            continue;
        char num[40];
        pc_snprintf(num, sizeof num, "%.15g", fabs(w[i]));
        sb_puts(b, any ? (w[i] < 0 ? " - " : " + ") : w[i] < 0 ? "-" : "");
        if (strcmp(num, "1") != 0) {
            sb_puts(b, num);
            sb_puts(b, " ");
        }
        tex_name(b, d->points[i]);
        any = 1;
    }
    if (!any)
        sb_puts(b, "0");
}

/* an exact root's text ("(1 - 2*sqrt(5))/3", "-1/2") as LaTeX */
static void tex_exact(StrBuf *b, const char *s)
{
    const char *slash = strrchr(s, '/');
    const char *close = strrchr(s, ')');
    if (slash && close && slash < close) /* the slash is inside: none */
        slash = NULL;
    size_t n = slash ? (size_t)(slash - s) : strlen(s);
    const char *p = s;
    int neg = 0;
    if (slash && s[0] == '(' && s[n - 1] == ')')
        p++, n -= 2;
    else if (slash && s[0] == '-')
        neg = 1, p++, n--;
    StrBuf num = {0};
    for (size_t i = 0; i < n; i++) {
        if (p[i] == '*')
            sb_puts(&num, " ");
        else if (strncmp(p + i, "sqrt(", 5) == 0) {
            size_t e = i + 5;
            while (e < n && p[e] != ')')
                e++;
            sb_puts(&num, "\\sqrt{");
            sb_putn(&num, p + i + 5, e - i - 5);
            sb_puts(&num, "}");
            i = e;
        } else
            sb_putn(&num, p + i, 1);
    }
    char *t = sb_take(&num);
    if (slash) {
        sb_puts(b, neg ? "-\\frac{" : "\\frac{");
        sb_puts(b, t);
        sb_puts(b, "}{");
        sb_puts(b, slash + 1);
        sb_puts(b, "}");
    } else
        sb_puts(b, t);
    pc_free(t);
}

static void tex_root(StrBuf *b, const AnRoot *r)
{
    char num[40];
    if (r->exact)
        tex_exact(b, r->exact);
    else {
        pc_snprintf(num, sizeof num, "%.16g", r->value);
        sb_puts(b, num);
    }
    if (r->mult > 1) {
        pc_snprintf(num, sizeof num, "%ld", (long)r->mult);
        sb_puts(b, " \\ (\\text{multiplicity } ");
        sb_puts(b, num);
        sb_puts(b, ")");
    }
}

/* "$t = \frac{1}{2}$, $t = 1$" or "none" */
static void tex_roots(StrBuf *b, const char *what, const AnRoots *r,
                      const char *t)
{
    sb_puts(b, what);
    sb_puts(b, ": ");
    if (!r->n)
        sb_puts(b, "none");
    for (slong i = 0; i < r->n; i++) {
        sb_puts(b, i ? ", $" : "$");
        tex_name(b, t);
        if (r->v[i].mult == AN_RUN_START && i + 1 < r->n) {
            char num[80];
            pc_snprintf(num, sizeof num, " \\in [%.16g, %.16g]$", r->v[i].value,
                        r->v[i + 1].value);
            sb_puts(b, num);
            i++;
            continue;
        }
        sb_puts(b, " = ");
        tex_root(b, r->v + i);
        sb_puts(b, "$");
    }
    sb_puts(b, ".\n");
}

/* \frac{\mathrm{d}^{k}M}{\mathrm{d}t^{k}} */
static void tex_deriv(StrBuf *b, const char *m, const char *t, slong k)
{
    char kk[24];
    pc_snprintf(kk, sizeof kk, "%ld", (long)k);
    sb_puts(b, "\\frac{\\mathrm{d}");
    if (k > 1) {
        sb_puts(b, "^{");
        sb_puts(b, kk);
        sb_puts(b, "}");
    }
    tex_name(b, m);
    sb_puts(b, "}{\\mathrm{d}");
    tex_name(b, t);
    if (k > 1) {
        sb_puts(b, "^{");
        sb_puts(b, kk);
        sb_puts(b, "}");
    }
    sb_puts(b, "}");
}

static void tex_end(StrBuf *b, const AnCurve *c, const AnEnd *e,
                    const Derived *d, const char *t)
{
    sb_puts(b, "\\[ ");
    tex_name(b, t);
    sb_puts(b, e->t[0] == 'o' ? " \\to \\infty" : " = ");
    if (e->t[0] != 'o')
        sb_puts(b, e->t);
    sb_puts(b, "\\colon\\quad ");
    if (e->infinite) {
        if (e->point) {
            sb_puts(b, "\\text{at infinity, in the direction } ");
            tex_combo(b, e->point, d);
        } else
            sb_puts(b, "\\text{no finite point}");
        sb_puts(b, " \\]\n");
        return;
    }
    tex_name(b, c->name);
    sb_puts(b, " = ");
    if (e->num)
        tex_combo_num(b, e->num, d);
    else
        tex_combo(b, e->point, d);
    if (e->tangent || e->num_tan) {
        sb_puts(b, ", \\quad ");
        tex_deriv(b, c->name, e->t[0] == 'o' ? "s" : t, e->first);
        sb_puts(b, " = ");
        if (e->num_tan)
            tex_combo_num(b, e->num_tan, d);
        else
            tex_combo(b, e->tangent, d);
        if (e->tangent && e->parallel >= 0) {
            char num[64];
            pc_snprintf(num, sizeof num,
                        " \\quad (\\text{smoothness order } %ld)",
                        (long)e->parallel);
            sb_puts(b, num);
        }
    }
    sb_puts(b, " \\]\n");
}

static void tex_passes(StrBuf *b, const AnCurve *c, const Derived *d,
                       const char *t)
{
    sb_puts(b, "Passes through: ");
    if (!c->npass)
        sb_puts(b, "no base point");
    for (slong i = 0; i < c->npass; i++) {
        sb_puts(b, i ? "; $" : "$");
        tex_name(b, d->points[c->pass[i].point]);
        sb_puts(b, "$ at");
        const AnRoots *r = &c->pass[i].t;
        for (slong k = 0; k < r->n; k++) {
            sb_puts(b, k ? ", $" : " $");
            tex_name(b, t);
            if (r->v[k].mult == AN_RUN_START && k + 1 < r->n) {
                char num[80];
                pc_snprintf(num, sizeof num, " \\in [%.16g, %.16g]$",
                            r->v[k].value, r->v[k + 1].value);
                sb_puts(b, num);
                k++;
                continue;
            }
            sb_puts(b, " = ");
            tex_root(b, r->v + k);
            sb_puts(b, "$");
        }
    }
    sb_puts(b, ".\n");
}

/* the heading: what the curve is */
static void tex_head(StrBuf *b, const AnCurve *c, const Derived *d,
                     const char *t)
{
    char num[160];
    sb_puts(b, "\\paragraph{$");
    tex_name(b, c->name);
    sb_puts(b, "$} ");
    sb_puts(b, c->kind == KIND_POINT ? "A point" : "A vector");
    sb_puts(b, " curve in $");
    tex_name(b, t);
    if (c->bounded && c->nends == 2) {
        sb_puts(b, " \\in [");
        sb_puts(b, c->ends[0].t);
        sb_puts(b, ", ");
        sb_puts(b, c->ends[1].t);
        sb_puts(b, "]");
    }
    sb_puts(b, "$, ");
    if (c->numeric) {
        sb_puts(b, c->nature);
        sb_puts(b, " (it has ");
        sb_puts(b, c->functions);
        sb_puts(b, "), found numerically");
    } else {
        pc_snprintf(num, sizeof num, "degree %ld", (long)c->degree);
        sb_puts(b, num);
        if (c->kind == KIND_POINT) {
            pc_snprintf(num, sizeof num, ", order %ld, %s", (long)c->order,
                        c->index == 1 ? "proper" : "traced more than once");
            sb_puts(b, num);
        }
    }
    if (c->kind == KIND_POINT && (!c->numeric || c->num_done))
        sb_puts(b, c->dim <= 1   ? ", a straight line"
                   : c->dim == 2 ? ", a plane curve"
                                 : ", a space curve");
    sb_puts(b, ".\n");
    (void)d;
}

static void tex_curve(StrBuf *b, const AnCurve *c, const Derived *d)
{
    if (c->skip) {
        sb_puts(b, "\\paragraph{$");
        tex_name(b, c->name);
        sb_puts(b, "$} Not analysed: ");
        sb_puts(b, c->skip);
        sb_puts(b, ".\n\n");
        return;
    }
    const char *t = d->ring.names[c->param];
    tex_head(b, c, d, t);
    if (c->numeric && !c->num_done) {
        sb_puts(b, "Not evaluated.\n\n");
        return;
    }
    for (slong i = 0; i < c->nends; i++)
        tex_end(b, c, c->ends + i, d, t);
    if (c->kind == KIND_POINT)
        tex_passes(b, c, d, t);
    tex_roots(b, "Poles", &c->poles, t);
    if (c->kind == KIND_POINT)
        tex_roots(b, "Stop points", &c->stops, t);
    if (c->has_infl)
        tex_roots(b, "Inflections", &c->infl, t);
    if (c->implicit_tex) {
        sb_puts(b, "Implicit, in barycentric coordinates:\n\\[ ");
        sb_puts(b, c->implicit_tex);
        sb_puts(b, " = 0 \\]\n");
    }
    if (c->implicit_xy_tex) {
        sb_puts(b, "Implicit, in Cartesian coordinates ($x$, $y$):\n\\[ ");
        sb_puts(b, c->implicit_xy_tex);
        sb_puts(b, " = 0 \\]\n");
    }
    sb_puts(b, "\n");
}

void analyze_print_latex(FILE *out, const Analysis *a)
{
    StrBuf b = {0};
    for (slong k = 0; k < a->d->nconsts; k++) {
        if (a->cgiven[k] || !a->cused[k])
            continue;
        char *s = fmpq_get_str(NULL, 10, a->cvalue + k);
        sb_puts(&b, "% const ");
        sb_puts(&b, a->d->consts[k]);
        sb_puts(&b, " without --set, at its generic value ");
        sb_puts(&b, s);
        sb_puts(&b, "\n");
        flint_free(s);
    }
    for (slong i = 0; i < a->ncurves; i++)
        tex_curve(&b, a->curves + i, a->d);
    char *s = sb_take(&b);
    fputs(s, out);
    pc_free(s);
}
