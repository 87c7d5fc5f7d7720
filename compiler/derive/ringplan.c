/*
 * ringplan.c - plan the ring of a scheme: a fresh Derived with the names
 * of its points, params, consts and unknown scalars, and ring variables
 * for them plus kernel slots (functions, pi, distances, coordinates), as
 * many as the scheme's calls need at least.
 *
 * The pass between sema and derive (pipeline.c); it runs again with more
 * slots when a derivation runs out of them.
 */
#include "compiler/derive/derive_int.h"

#include "compiler/check.h"

#include <stdlib.h>
#include <string.h>

#include "base/mem.h"

/* counts what may need kernels: function calls and powers that are not
 * integer literals, subst() and diff(), pi */
static void count_kernel_uses(const Node *n, slong *calls, slong *ops,
                              slong *pis, slong *metric)
{
    if (!n)
        return;
    if (n->kind == ND_CALL) {
        if (n->builtin == BI_DOT || n->builtin == BI_DIST ||
            n->builtin == BI_ANGLE)
            ++*metric;
        if (n->builtin == BI_PI)
            ++*pis;
        else if (derive_is_function(n->builtin))
            ++*calls;
        else if (n->builtin == BI_NATX || n->builtin == BI_NATY)
            *calls += 3; /* its derivative: cos and sin of the phase */
        else if (n->builtin == BI_SUBST || n->builtin == BI_DIFF)
            ++*ops;
        for (const Node *a = n->args; a; a = a->next)
            count_kernel_uses(a, calls, ops, pis, metric);
    }
    /* a power that is not a whole number may be a root: t^(1/2), and
     * t^0.5 (a decimal exponent) */
    if (n->kind == ND_POW &&
        (n->rhs->kind != ND_NUM || strpbrk(n->rhs->text, ".eE")))
        ++*calls;
    count_kernel_uses(n->lhs, calls, ops, pis, metric);
    count_kernel_uses(n->rhs, calls, ops, pis, metric);
}

/* the distinct k of the coord(P, k) in n, added to ks[0 .. *nks - 1] */
static void count_coord_indices(const Node *n, long **ks, slong *nks)
{
    if (!n)
        return;
    if (n->kind == ND_CALL && n->builtin == BI_COORD && n->nargs == 2 &&
        derive_nth(n, 1)->kind == ND_NUM) {
        long k = strtol(derive_nth(n, 1)->text, NULL, 10);
        slong i = 0;
        while (i < *nks && (*ks)[i] != k)
            i++;
        if (i == *nks) {
            *ks = pc_xrealloc(*ks, sizeof(long) * (size_t)(*nks + 1));
            (*ks)[(*nks)++] = k;
        }
    }
    if (n->kind == ND_CALL)
        for (const Node *a = n->args; a; a = a->next)
            count_coord_indices(a, ks, nks);
    count_coord_indices(n->lhs, ks, nks);
    count_coord_indices(n->rhs, ks, nks);
}

static char **copy_names(Sym **syms, int n)
{
    char **names = pc_xcalloc((size_t)(n ? n : 1), sizeof(char *));
    for (int i = 0; i < n; i++)
        names[i] = pc_xstrdup(syms[i]->name);
    return names;
}

/* the file's base name without directory and extension */
static char *base_name(const char *filename)
{
    const char *b = strrchr(filename, '/');
    b = b ? b + 1 : filename;
    char *s = pc_xstrdup(b);
    char *dot = strrchr(s, '.');
    if (dot && dot != s)
        *dot = '\0';
    return s;
}

/* the kernel slots the scheme's calls need at least (functions, pi,
 * distances, coordinates), counted over every definition, solve and
 * declared bound */
static slong plan_kernel_slots(const SemaInfo *info, slong npoints)
{
    slong calls = 0, ops = 0, pis = 0, metric = 0;
    long *coord_ks = NULL; /* the distinct k of coord(P, k) */
    slong ncoord_ks = 0;
    for (int i = 0; i < info->nsteps; i++) {
        const Stmt *st = info->steps[i];
        if (st->kind == ST_DEF)
            count_kernel_uses(st->expr, &calls, &ops, &pis, &metric);
        for (const Equation *e = st->kind == ST_DEF ? st->joints : NULL; e;
             e = e->next) {
            count_kernel_uses(e->lhs, &calls, &ops, &pis, &metric);
            count_kernel_uses(e->rhs, &calls, &ops, &pis, &metric);
        }
        for (const Equation *e = st->kind == ST_SOLVE ? st->eqs : NULL; e;
             e = e->next) {
            count_kernel_uses(e->lhs, &calls, &ops, &pis, &metric);
            count_kernel_uses(e->rhs, &calls, &ops, &pis, &metric);
        }
        if (st->kind == ST_DEF)
            count_coord_indices(st->expr, &coord_ks, &ncoord_ks);
        for (const Equation *e = st->kind == ST_SOLVE ? st->eqs : NULL; e;
             e = e->next) {
            count_coord_indices(e->lhs, &coord_ks, &ncoord_ks);
            count_coord_indices(e->rhs, &coord_ks, &ncoord_ks);
        }
    }
    /* the checks' values are derived too (compiler/check.h): the claim as
     * written, once (its jets repeat the curve in every derivative: a
     * jet counts as one more subst and diff, and a derivation that needs
     * more slots is done again with twice as many) */
    for (int i = 0; i < info->nchecks; i++) {
        const Stmt *st = info->checks[i];
        const Node *parts[2] = {st->expr, st->rhs};
        for (int k = 0; k < 2; k++) {
            count_kernel_uses(parts[k], &calls, &ops, &pis, &metric);
            count_coord_indices(parts[k], &coord_ks, &ncoord_ks);
        }
        for (const Equation *e = st->eqs; e; e = e->next) {
            count_kernel_uses(e->rhs, &calls, &ops, &pis, &metric);
            count_coord_indices(e->rhs, &coord_ks, &ncoord_ks);
        }
        ops += st->check->jetlen ? 2 : 0;
    }
    /* the params' ranges and the consts' bounds are derived too
     * (Derived.range, Derived.bound) */
    for (int i = 0; i < info->nparams + info->nconsts; i++) {
        const Stmt *st = i < info->nparams
                             ? info->params[i]->decl
                             : info->consts[i - info->nparams]->decl;
        if (st && st->lo && !st->bad)
            count_kernel_uses(st->lo, &calls, &ops, &pis, &metric);
        if (st && st->hi && !st->bad)
            count_kernel_uses(st->hi, &calls, &ops, &pis, &metric);
        if (st && st->lo && !st->bad)
            count_coord_indices(st->lo, &coord_ks, &ncoord_ks);
        if (st && st->hi && !st->bad)
            count_coord_indices(st->hi, &coord_ks, &ncoord_ks);
    }
    slong nslots = kernels_slots(calls + 3 * metric, ops, pis);
    if (metric)
        nslots += kernels_metric_slots(metric, npoints);
    nslots += kernels_coord_slots(ncoord_ks, npoints);
    pc_free(coord_ks);
    return nslots;
}

Derived *derive_plan_ring(const SemaInfo *info, const char *filename,
                          const char *text, size_t len, slong *nslots_try)
{
    Derived *d = pc_xcalloc(1, sizeof(Derived));
    d->filename = pc_xstrdup(filename);
    d->text = pc_xmalloc(len ? len : 1);
    if (len)
        memcpy(d->text, text, len);
    d->len = len;
    source_init(&d->src, d->filename, d->text, len);
    d->scheme =
        info->scheme_name ? pc_xstrdup(info->scheme_name) : base_name(filename);
    d->npoints = info->npoints;
    d->points = copy_names(info->points, info->npoints);
    d->nparams = info->nparams;
    d->params = copy_names(info->params, info->nparams);
    d->nconsts = info->nconsts;
    d->consts = copy_names(info->consts, info->nconsts);
    /* unknown scalars are ring variables after the consts */
    for (int k = 0; k < info->nunknowns; k++)
        d->nextra += !info->unknowns[k]->is_point;
    d->extra = pc_xcalloc((size_t)(d->nextra ? d->nextra : 1), sizeof(char *));
    for (int k = 0, m = 0; k < info->nunknowns; k++)
        if (!info->unknowns[k]->is_point)
            d->extra[m++] = pc_xstrdup(info->unknowns[k]->name);
    /* kernel slots (functions, pi) after the extra variables */
    slong nslots = plan_kernel_slots(info, d->npoints);
    if (*nslots_try > 0)
        nslots = *nslots_try;
    *nslots_try = nslots;
    slong nv = d->nparams + d->nconsts + d->nextra + nslots;
    const char **vars = pc_xmalloc(sizeof(char *) * (size_t)(nv ? nv : 1));
    for (slong i = nv - nslots; i < nv; i++)
        vars[i] = "?"; /* named when a kernel takes the slot */
    for (slong i = 0; i < d->nparams; i++)
        vars[i] = d->params[i];
    for (slong i = 0; i < d->nconsts; i++)
        vars[d->nparams + i] = d->consts[i];
    for (slong i = 0; i < d->nextra; i++)
        vars[d->nparams + d->nconsts + i] = d->extra[i];
    ring_init(&d->ring, nv, vars);
    pc_free(vars);
    if (nslots > 0) {
        d->kernels = pc_xcalloc(1, sizeof(Kernels));
        kernels_init(d->kernels, &d->ring, nv - nslots, nslots);
        d->kernels->points = (const char *const *)d->points;
        d->kernels->npoints = d->npoints;
    }
    return d;
}
