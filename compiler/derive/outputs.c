/*
 * outputs.c - the outputs of a derivation: the check that none still holds
 * an unknown no solve determined, the assumed bounds and the params'
 * ranges, and each output as a DerivedOutput (kind, reduced weights).
 *
 * The pass after derive (pipeline.c); steps_rec.c and derived.c share
 * derive_output_fill and derive_output_clear.  derive_final_deadline is
 * the derivation's last look at the clock.
 */
#include "compiler/derive/derive_int.h"

#include <stdlib.h>
#include <string.h>

#include "base/budget.h"
#include "base/mem.h"

/* 1 when p depends on ring variable var */
static int poly_has_var(const fmpz_mpoly_t p, slong var, const Ring *r)
{
    return fmpz_mpoly_degree_si(p, var, r->ctx) > 0;
}

/* the unknown (point or scalar) that value v of output o still holds, or
 * NULL */
const Sym *derive_unsolved_in(const Deriver *D, const Value *v)
{
    const Ring *r = D->r;
    for (slong i = 0; i < (v->is_point ? v->p->len : 0); i++)
        if (v->p->terms[i].point >= D->ucol0)
            return D->info->unknowns[v->p->terms[i].point - D->ucol0];
    for (int k = 0; k < D->info->nunknowns; k++) {
        slong var = D->uvar[k];
        int dep = 0;
        if (var < 0)
            continue;
        if (v->is_point) {
            dep = poly_has_var(v->p->den, var, r);
            for (slong i = 0; i < v->p->len && !dep; i++)
                dep = poly_has_var(v->p->terms[i].num, var, r);
        } else {
            dep = ratfun_depends_on(v->s, var, r);
        }
        if (dep)
            return D->info->unknowns[k];
    }
    return NULL;
}

/* 0, or -1 after reporting that output o (value v) still holds an unknown
 * that no solve determined */
static int check_no_unknown(Deriver *D, const Sym *o, const Value *v)
{
    const Sym *u = derive_unsolved_in(D, v);
    if (!u)
        return 0;
    diag_error(D->diag, o->span,
               "'%s' depends on the unknown '%s', which no solve "
               "determines; expected 'solve ... for %s' before the output",
               o->name, u->name, u->name);
    diag_note(D->diag, u->span, "'%s' was declared here", u->name);
    return -1;
}

/* o = the value v, as derive prints it and codegen lowers it: kind from
 * the weight sum, each weight reduced on its own (DerivedOutput).  With
 * may_stop, the weights past the derivation's deadline (budget_late) are
 * left unreduced (equal values, copied in linear time): one reduction is
 * a gcd of the whole equation's size, and the caller then reports the
 * derivation out of time. */
static void output_fill(DerivedOutput *o, const char *name, Span span,
                        const Value *v, const Source *src, const Ring *r,
                        int may_stop)
{
    int line, col;
    o->name = pc_xstrdup(name);
    source_locate(src, span.start, &line, &col);
    o->line = line;
    o->span = span;
    pteq_init(o->eq, r);
    ratfun_init(o->scalar, r);
    o->w = NULL;
    o->diff_of = o->diff_var = NULL;
    o->diff_order = 0;
    if (v->is_point) {
        RatFun sum;
        ratfun_init(sum, r);
        pteq_weight_sum(sum, v->p, r);
        o->kind = ratfun_is_one(sum, r) ? KIND_POINT : KIND_VECTOR;
        ratfun_clear(sum, r);
        pteq_set(o->eq, v->p, r);
        o->w = flint_malloc(sizeof(RatFunStruct) *
                            (size_t)FLINT_MAX(o->eq->len, 1));
        for (slong k = 0; k < o->eq->len; k++) {
            ratfun_init(o->w + k, r);
            fmpz_mpoly_set(o->w[k].num, o->eq->terms[k].num, r->ctx);
            fmpz_mpoly_set(o->w[k].den, o->eq->den, r->ctx);
            if (!may_stop || !budget_late())
                ratfun_canonicalise(o->w + k, r);
        }
    } else {
        o->kind = KIND_SCALAR;
        ratfun_set(o->scalar, v->s, r);
    }
}

void derive_output_fill(DerivedOutput *o, const char *name, Span span,
                        const Value *v, const Source *src, const Ring *r)
{
    output_fill(o, name, span, v, src, r, 0);
}

void derive_output_clear(DerivedOutput *o, const Ring *r)
{
    if (o->w != NULL) {
        for (slong k = 0; k < o->eq->len; k++)
            ratfun_clear(o->w + k, r);
        flint_free(o->w);
    }
    pteq_clear(o->eq, r);
    ratfun_clear(o->scalar, r);
    pc_free((char *)o->name);
    pc_free(o->assumed);
    pc_free(o->diff_of);
    pc_free(o->diff_var);
}

/* an output defined as diff(NAME, t[, n]) of a plain name: the printers
 * write it as dNAME/dt^n */
static void output_diff_of(DerivedOutput *o, const Sym *s)
{
    const Node *e = s->kind == SYM_DEF && s->def ? s->def->expr : NULL;
    if (!e || e->kind != ND_CALL || e->builtin != BI_DIFF)
        return;
    const Node *x = e->args, *t = x ? x->next : NULL;
    const Node *n = t ? t->next : NULL;
    if (!x || x->kind != ND_NAME || !t || t->kind != ND_NAME)
        return;
    long order = 1;
    if (n) {
        if (n->kind != ND_NUM)
            return;
        char *end;
        order = strtol(n->text, &end, 10);
        if (*end || order < 1 || order > 99)
            return;
    }
    o->diff_of = pc_xstrdup(x->text);
    o->diff_var = pc_xstrdup(t->text);
    o->diff_order = (int)order;
}

/* an output may not keep an unknown that no solve determined */
static void check_outputs_solved(Deriver *D)
{
    const SemaInfo *info = D->info;
    for (int i = 0; i < info->noutputs && D->diag->nerrors == 0; i++) {
        Sym *s = info->outputs[i];
        Value uv;
        if (s->kind == SYM_DEF) {
            check_no_unknown(D, s, &D->defs[s->index]);
        } else {
            uv.is_point = s->is_point;
            uv.p[0] = D->usol[s->index][0]; /* borrowed */
            uv.s[0] = D->ssol[s->index];
            check_no_unknown(D, s, &uv);
        }
    }
}

/* d->outputs: each output's value as a DerivedOutput, with the bounds it
 * rests on and its diff() form */
static void fill_outputs(Deriver *D, Derived *d)
{
    const Ring *r = D->r;
    const SemaInfo *info = D->info;
    d->noutputs = info->noutputs;
    d->outputs = pc_xcalloc((size_t)(info->noutputs ? info->noutputs : 1),
                            sizeof(DerivedOutput));
    for (int i = 0; i < info->noutputs; i++) {
        Sym *s = info->outputs[i];
        DerivedOutput *o = &d->outputs[i];
        Value uv, *v = &D->defs[s->index];
        if (s->kind == SYM_UNKNOWN) { /* solved */
            uv.is_point = s->is_point;
            uv.p[0] = D->usol[s->index][0]; /* borrowed */
            uv.s[0] = D->ssol[s->index];
            v = &uv;
        }
        /* marked: a budget that runs out here is reported at it */
        budget_statement(D->src, s->span);
        output_fill(o, s->name, s->span, v, D->src, r, 1);
        derive_out_of_time_at(D, s->span);
        const unsigned char *as = s->kind == SYM_UNKNOWN ? D->uassume[s->index]
                                                         : D->dassume[s->index];
        if (as) {
            size_t nv = (size_t)(d->nparams + d->nconsts);
            o->assumed = pc_xmalloc(nv ? nv : 1);
            memcpy(o->assumed, as, nv);
        }
        output_diff_of(o, s);
    }
}

/* The outputs of a derivation into d: checked, and (without errors) filled
 * in; the bounds the kernels assumed and the params' exact ranges */
void derive_collect_outputs(Deriver *D, Derived *d)
{
    const Ring *r = D->r;
    const SemaInfo *info = D->info;
    check_outputs_solved(D);

    for (slong v = 0; D->K && v < d->nparams + d->nconsts; v++)
        d->bound_flags[v] |= (unsigned char)((kernels_assumed(D->K, v) & 1
                                                  ? DERIVED_BOUND_LO_ASSUMED
                                                  : 0) |
                                             (kernels_assumed(D->K, v) & 2
                                                  ? DERIVED_BOUND_HI_ASSUMED
                                                  : 0));

    /* the declared ranges, exact (a range that does not reduce is left
     * out: sema has reported what is wrong with it) */
    d->range = ratfun_vec_init(2 * info->nparams, r);
    d->has_range = pc_xcalloc((size_t)info->nparams + 1, 1);
    for (int i = 0; i < info->nparams && D->diag->nerrors == 0; i++) {
        const Stmt *st = info->params[i]->decl;
        if (st && st->lo && !st->bad &&
            derive_eval_scalar(D, d->range + 2 * i, st->lo) == 0 &&
            derive_eval_scalar(D, d->range + 2 * i + 1, st->hi) == 0)
            d->has_range[i] = 1;
    }

    if (D->diag->nerrors == 0)
        fill_outputs(D, d);
}

/* The derivation's last look at the clock: one FLINT call (a product in
 * along, subst, diff or solve, a weight's reduction) is not interrupted,
 * so a derivation can end past its deadline without having read the clock
 * there.  Such a derivation fails like one stopped inside, with the
 * located time-budget message at the statement it marked last (the one
 * that ran long, or the last one).  Failed checks do not keep such a
 * result (their details may have been printed past the deadline, cut
 * short: budget.h). */
void derive_final_deadline(Deriver *D)
{
    if (D->expired || D->deadline == 0 || derive_now_seconds() <= D->deadline)
        return;
    const Source *src;
    Span span;
    budget_where(&src, &span);
    derive_out_of_time_at(D, src == D->src ? span : BUDGET_WHOLE_FILE);
}
