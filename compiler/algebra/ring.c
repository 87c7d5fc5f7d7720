/*
 * ring.c - the polynomial ring of one compilation.
 *
 * A thin wrapper: one FLINT context in degree-reverse-lexicographic order
 * (so "leading coefficient" means the coefficient of the highest total
 * degree term, which is what a reader expects of a denominator's sign) and a
 * copy of the names array.  FLINT cannot build a context with zero
 * variables, so a scheme without scalars gets one hidden variable that no
 * polynomial ever uses.
 */
#include "compiler/algebra/ring.h"

#include <string.h>

void ring_init(Ring *r, slong nvars, const char *const *names)
{
    FLINT_ASSERT(nvars >= 0);
    fmpz_mpoly_ctx_init(r->ctx, nvars > 0 ? nvars : 1, ORD_DEGREVLEX);
    r->nvars = nvars;
    r->names = NULL;
    r->latex = NULL;
    if (nvars > 0) {
        r->names = flint_malloc((size_t)nvars * sizeof(const char *));
        for (slong i = 0; i < nvars; i++)
            r->names[i] = names[i];
    }
}

void ring_clear(Ring *r)
{
    flint_free(r->names);
    flint_free(r->latex);
    r->names = NULL;
    r->latex = NULL;
    r->nvars = 0;
    fmpz_mpoly_ctx_clear(r->ctx);
}

int ring_factor_affordable(const fmpz_mpoly_t p, const Ring *r)
{
    enum { MAX_TERMS = 400, MAX_VARS = 8, MAX_DEG1 = 200, MAX_DEG = 32 };
    slong nv = r->ctx->minfo->nvars;
    if (fmpz_mpoly_length(p, r->ctx) > MAX_TERMS ||
        !fmpz_mpoly_degrees_fit_si(p, r->ctx))
        return 0;
    slong *degs = flint_malloc((size_t)nv * sizeof(slong));
    fmpz_mpoly_degrees_si(degs, p, r->ctx);
    slong used = 0, top = 0;
    for (slong v = 0; v < nv; v++) {
        used += degs[v] > 0;
        top = degs[v] > top ? degs[v] : top;
    }
    flint_free(degs);
    if (used > MAX_VARS)
        return 0;
    if (used <= 1)
        return top <= MAX_DEG1;
    return fmpz_mpoly_total_degree_si(p, r->ctx) <= MAX_DEG;
}

int ring_factor(fmpz_mpoly_factor_t f, const fmpz_mpoly_t p, const Ring *r)
{
    enum { SQUAREFREE_MAX_TERMS = 4096 };
    if (ring_factor_affordable(p, r))
        return ring_factor_compact(f, p, 1, r);
    if (fmpz_mpoly_length(p, r->ctx) <= SQUAREFREE_MAX_TERMS)
        return fmpz_mpoly_factor_squarefree(f, p, r->ctx);
    return 0;
}

/* q (context cq) = p (context cp) with its variable j renamed map[j]
 * (to_big) or variable map[j] renamed j (!to_big); k variables mapped */
static void remap(fmpz_mpoly_t q, const fmpz_mpoly_ctx_t cq,
                  const fmpz_mpoly_t p, const fmpz_mpoly_ctx_t cp,
                  const slong *map, slong k, int to_big)
{
    slong np = cp->minfo->nvars, nq = cq->minfo->nvars;
    ulong *e = flint_calloc((size_t)np, sizeof(ulong));
    ulong *e2 = flint_calloc((size_t)nq, sizeof(ulong));
    fmpz_t c;
    fmpz_init(c);
    fmpz_mpoly_zero(q, cq);
    for (slong i = 0; i < p->length; i++) {
        fmpz_mpoly_get_term_coeff_fmpz(c, p, i, cp);
        fmpz_mpoly_get_term_exp_ui(e, p, i, cp);
        for (slong j = 0; j < k; j++) {
            if (to_big)
                e2[map[j]] = e[j];
            else
                e2[j] = e[map[j]];
        }
        fmpz_mpoly_push_term_fmpz_ui(q, c, e2, cq);
    }
    fmpz_mpoly_sort_terms(q, cq);
    fmpz_mpoly_combine_like_terms(q, cq);
    fmpz_clear(c);
    flint_free(e2);
    flint_free(e);
}

int ring_factor_compact(fmpz_mpoly_factor_t f, const fmpz_mpoly_t p, int full,
                        const Ring *r)
{
    slong nv = r->ctx->minfo->nvars, k = 0;
    slong *degs = flint_malloc((size_t)nv * sizeof(slong));
    slong *map = flint_malloc((size_t)nv * sizeof(slong));
    fmpz_mpoly_degrees_si(degs, p, r->ctx);
    for (slong v = 0; v < nv; v++)
        if (degs[v] > 0)
            map[k++] = v;
    fmpz_mpoly_ctx_t c2;
    fmpz_mpoly_ctx_init(c2, k ? k : 1, r->ctx->minfo->ord);
    fmpz_mpoly_t q;
    fmpz_mpoly_init(q, c2);
    remap(q, c2, p, r->ctx, map, k, 0);
    fmpz_mpoly_factor_t g;
    fmpz_mpoly_factor_init(g, c2);
    int ok = full ? fmpz_mpoly_factor(g, q, c2)
                  : fmpz_mpoly_factor_squarefree(g, q, c2);
    if (ok) {
        fmpz_set(f->constant, g->constant);
        fmpz_set(f->constant_den, g->constant_den);
        f->num = 0;
        fmpz_mpoly_t b;
        fmpz_mpoly_init(b, r->ctx);
        for (slong i = 0; i < g->num; i++) {
            remap(b, r->ctx, g->poly + i, c2, map, k, 1);
            fmpz_mpoly_factor_append_fmpz_swap(f, b, g->exp + i, r->ctx);
        }
        fmpz_mpoly_clear(b, r->ctx);
    }
    fmpz_mpoly_factor_clear(g, c2);
    fmpz_mpoly_clear(q, c2);
    fmpz_mpoly_ctx_clear(c2);
    flint_free(map);
    flint_free(degs);
    return ok;
}

slong ring_var_index(const Ring *r, const char *name)
{
    for (slong i = 0; i < r->nvars; i++)
        if (strcmp(r->names[i], name) == 0)
            return i;
    return -1;
}
