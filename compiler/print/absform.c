/*
 * absform.c - abs(x) for the printers: sign kernels times their argument
 * read back as |x| (absform.h).
 */
#include "compiler/print/absform.h"

#include <string.h>

#include "base/mem.h"
#include "base/strbuf.h"
#include "compiler/algebra/poly_print.h"

int absform_any(const Kernels *K)
{
    if (!K)
        return 0;
    for (slong i = 0; i < K->n; i++)
        if (K->k[i].fn == KF_SIGN)
            return 1;
    return 0;
}

/* p = p0 + v*p1 with x | p1: res = p0 + v^(2m+1)*q; 0 when x does not
 * divide p1 (res untouched) */
static int rewrite_one(fmpz_mpoly_t res, const fmpz_mpoly_t p, slong v,
                       const fmpz_mpoly_t x, const Ring *r)
{
    if (fmpz_mpoly_degree_si(p, v, r->ctx) != 1 ||
        fmpz_mpoly_total_degree_si(x, r->ctx) < 1)
        return 0;
    fmpz_mpoly_t p0, p1, q, x2, m;
    fmpz_mpoly_init(p0, r->ctx);
    fmpz_mpoly_init(p1, r->ctx);
    fmpz_mpoly_init(q, r->ctx);
    fmpz_mpoly_init(x2, r->ctx);
    fmpz_mpoly_init(m, r->ctx);
    ulong zero = 0, one = 1;
    fmpz_mpoly_get_coeff_vars_ui(p0, p, &v, &zero, 1, r->ctx);
    fmpz_mpoly_get_coeff_vars_ui(p1, p, &v, &one, 1, r->ctx);
    int ok = fmpz_mpoly_divides(q, p1, x, r->ctx);
    if (ok) {
        ulong e = 1;
        fmpz_mpoly_mul(x2, x, x, r->ctx);
        while (fmpz_mpoly_divides(m, q, x2, r->ctx)) {
            fmpz_mpoly_swap(q, m, r->ctx);
            e += 2;
        }
        fmpz_mpoly_gen(m, v, r->ctx);
        fmpz_mpoly_pow_ui(m, m, e, r->ctx);
        fmpz_mpoly_mul(q, q, m, r->ctx);
        fmpz_mpoly_add(res, p0, q, r->ctx);
    }
    fmpz_mpoly_clear(m, r->ctx);
    fmpz_mpoly_clear(x2, r->ctx);
    fmpz_mpoly_clear(q, r->ctx);
    fmpz_mpoly_clear(p1, r->ctx);
    fmpz_mpoly_clear(p0, r->ctx);
    return ok;
}

static slong rewrite_all(fmpz_mpoly_t res, unsigned char *is_abs,
                         const fmpz_mpoly_t p, const Kernels *K, const Ring *r,
                         int const_den)
{
    slong n = 0;
    fmpz_mpoly_set(res, p, r->ctx);
    if (!K)
        return 0;
    fmpz_mpoly_t t;
    fmpz_mpoly_init(t, r->ctx);
    for (slong i = 0; i < K->n; i++) {
        const Kernel *k = &K->k[i];
        if (k->fn != KF_SIGN ||
            !(const_den ? fmpz_mpoly_is_fmpz(k->arg->den, r->ctx)
                        : fmpz_mpoly_is_one(k->arg->den, r->ctx)))
            continue;
        if (rewrite_one(t, res, k->var, k->arg->num, r)) {
            fmpz_mpoly_swap(res, t, r->ctx);
            is_abs[k->var] = 1;
            n++;
        }
    }
    fmpz_mpoly_clear(t, r->ctx);
    return n;
}

slong absform_rewrite(fmpz_mpoly_t res, unsigned char *is_abs,
                      const fmpz_mpoly_t p, const Kernels *K, const Ring *r)
{
    return rewrite_all(res, is_abs, p, K, r, 0);
}

slong absform_rewrite_num(fmpz_mpoly_t res, unsigned char *is_abs,
                          const fmpz_mpoly_t p, const Kernels *K, const Ring *r)
{
    return rewrite_all(res, is_abs, p, K, r, 1);
}

char *absform_abs_text(const Kernel *s, const Ring *r, int latex)
{
    if (fmpz_mpoly_is_one(s->arg->den, r->ctx))
        return absform_arg_text(s, latex);
    StrBuf b = {0};
    poly_print(&b, s->arg->num, r, latex ? FMT_LATEX : FMT_TEXT);
    return sb_take(&b);
}

char *absform_arg_text(const Kernel *s, int latex)
{
    const char *name = latex ? s->latex : s->name;
    const char *open = latex ? "\\operatorname{sign}\\left(" : "sign(";
    const char *close = latex ? "\\right)" : ")";
    size_t n = strlen(name), lo = strlen(open), lc = strlen(close);
    if (n >= lo + lc && strncmp(name, open, lo) == 0 &&
        strcmp(name + n - lc, close) == 0)
        return pc_xstrndup(name + lo, n - lo - lc);
    return pc_xstrdup(name);
}
