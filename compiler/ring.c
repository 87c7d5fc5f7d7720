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
#include "compiler/ring.h"

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
        return fmpz_mpoly_factor(f, p, r->ctx);
    if (fmpz_mpoly_length(p, r->ctx) <= SQUAREFREE_MAX_TERMS)
        return fmpz_mpoly_factor_squarefree(f, p, r->ctx);
    return 0;
}

slong ring_var_index(const Ring *r, const char *name)
{
    for (slong i = 0; i < r->nvars; i++)
        if (strcmp(r->names[i], name) == 0)
            return i;
    return -1;
}
