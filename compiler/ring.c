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
    if (nvars > 0) {
        r->names = flint_malloc((size_t)nvars * sizeof(const char *));
        for (slong i = 0; i < nvars; i++)
            r->names[i] = names[i];
    }
}

void ring_clear(Ring *r)
{
    flint_free(r->names);
    r->names = NULL;
    r->nvars = 0;
    fmpz_mpoly_ctx_clear(r->ctx);
}

slong ring_var_index(const Ring *r, const char *name)
{
    for (slong i = 0; i < r->nvars; i++)
        if (strcmp(r->names[i], name) == 0)
            return i;
    return -1;
}
