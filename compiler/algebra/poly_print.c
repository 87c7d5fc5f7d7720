/*
 * poly_print.c - the small printer the algebra needs (poly_print.h): a
 * polynomial or a rational function expanded, as text, JSON or LaTeX, and
 * identifiers as LaTeX (the book's names: subscripts, Greek letters,
 * \mathit words).  The kernels name themselves with it (sin(phi),
 * sqrt(a^2 - b^2)); the printers of compiler/print/ build on it.  It
 * chooses no form: that is the book printer's job (compiler/print/).
 */
#include "compiler/algebra/poly_print.h"

#include <ctype.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/mem.h"

static const char *const greek[] = {
    "alpha", "beta",  "gamma", "delta",  "epsilon", "zeta",   "eta",
    "theta", "iota",  "kappa", "lambda", "mu",      "nu",     "xi",
    "pi",    "rho",   "sigma", "tau",    "upsilon", "phi",    "chi",
    "psi",   "omega", "Gamma", "Delta",  "Theta",   "Lambda", "Xi",
    "Pi",    "Sigma", "Phi",   "Psi",    "Omega",
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

void poly_print_latex_name(StrBuf *b, const char *name)
{
    size_t n = strlen(name);
    const char *under = strchr(name, '_');
    if (under && under != name && under[1]) {
        char *stem = pc_xstrndup(name, (size_t)(under - name));
        StrBuf st = {0};
        poly_print_latex_name(&st, stem);
        pc_free(stem);
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
        pc_free(s);
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
        sub =
            isupper((unsigned char)name[i]) || isdigit((unsigned char)name[i]);
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

/* Writes p expanded.  text: "2*t^2 - 2*t + 1"; json: "2*t^2-2*t+1";
 * latex: "2 t^{2} - 2 t + 1".  A polynomial with a negative leading
 * coefficient is written in ascending order ("1 - t"). */
void poly_print(StrBuf *b, const fmpz_mpoly_t p, const Ring *r, FormatStyle st)
{
    slong len = fmpz_mpoly_length(p, r->ctx);
    if (len == 0) {
        sb_puts(b, "0");
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
                sb_puts(b, "-");
        } else if (st == FMT_JSON) {
            sb_puts(b, neg ? "-" : "+");
        } else {
            sb_puts(b, neg ? " - " : " + ");
        }
        fmpz_abs(c, c);
        int any_var = 0;
        for (slong v = 0; v < r->nvars; v++)
            any_var |= e[v] != 0;
        int first = 1;
        if (!fmpz_is_one(c) || !any_var) {
            sb_fmpz(b, c);
            first = 0;
        }
        for (slong v = 0; v < r->nvars; v++) {
            if (!e[v])
                continue;
            if (!first)
                sb_puts(b, st == FMT_LATEX ? " " : "*");
            first = 0;
            if (st == FMT_LATEX && r->latex && r->latex[v])
                sb_puts(b, r->latex[v]);
            else if (st == FMT_LATEX)
                poly_print_latex_name(b, r->names[v]);
            else
                sb_puts(b, r->names[v]);
            if (e[v] > 1) {
                char num[32];
                snprintf(num, sizeof num, st == FMT_LATEX ? "^{%lu}" : "^%lu",
                         e[v]);
                sb_puts(b, num);
            }
        }
    }
    pc_free(e);
    fmpz_clear(c);
}

char *poly_print_ratfun(const RatFun x, const Ring *r, FormatStyle st)
{
    StrBuf b = {0};
    int frac = !fmpz_mpoly_is_one(x->den, r->ctx);
    int multi = x->num->length > 1;
    if (st == FMT_LATEX && frac) {
        sb_puts(&b, "\\frac{");
        poly_print(&b, x->num, r, st);
        sb_puts(&b, "}{");
        poly_print(&b, x->den, r, st);
        sb_puts(&b, "}");
        return sb_take(&b);
    }
    if (frac && multi)
        sb_puts(&b, "(");
    poly_print(&b, x->num, r, st);
    if (frac && multi)
        sb_puts(&b, ")");
    if (frac) {
        int dmulti = x->den->length > 1 ||
                     (fmpz_mpoly_total_degree_si(x->den, r->ctx) > 0 &&
                      !fmpz_mpoly_is_gen(x->den, -1, r->ctx));
        sb_puts(&b, dmulti ? "/(" : "/");
        poly_print(&b, x->den, r, st);
        if (dmulti)
            sb_puts(&b, ")");
    }
    return sb_take(&b);
}
