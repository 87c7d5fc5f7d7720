/*
 * steps_rec.c - the steps recorder: Derived.steps (derive --steps), one
 * step per definition and per solved unknown with its final value and,
 * for the constructions, what they were built from (meet's parameters and
 * S/V-theorem data); and Derived.named, the scalar definitions that are a
 * power of one kernel.
 *
 * The last pass (pipeline.c), after the outputs, on a derivation without
 * errors.
 */
#include "compiler/derive/derive_int.h"

#include <stdlib.h>
#include <string.h>

#include "base/budget.h"
#include "base/mem.h"
#include "compiler/algebra/construct.h"

void derive_step_clear(DerivedStep *st, const Ring *r)
{
    derive_output_clear(&st->value, r);
    for (slong k = 0; k < st->nargs; k++)
        derive_output_clear(&st->args[k], r);
    pc_free(st->args);
    if (st->params)
        ratfun_vec_clear(st->params, st->nparams, r);
    if (st->sv_coord)
        ratfun_vec_clear(st->sv_coord, st->nparams + 1, r);
    ratfun_clear(st->det, r);
    ratfun_clear(st->scalar, r);
    pc_free((char *)st->var);
    pc_free(st->expr);
}

/* the source text of span, owned */
static char *span_text(const Source *src, Span span)
{
    size_t n = span.end > span.start ? (size_t)(span.end - span.start) : 0;
    char *s = pc_xmalloc(n + 1);
    if (n)
        memcpy(s, src->text + span.start, n);
    s[n] = '\0';
    return s;
}

/* a zero value of the step's kind, when it is pending */
static void step_pending(DerivedStep *st, const char *name, Span span,
                         const Source *src, const Ring *r)
{
    Value zero;
    derive_value_init(&zero, r);
    st->pending = 1;
    derive_output_fill(&st->value, name, span, &zero, src, r);
    derive_value_clear(&zero, r);
}

/* st->args[k] = the value of argument node a (named by its text); 0, or
 * -1 when it still holds an unsolved unknown (or failed: reported) */
static int step_arg(Deriver *D, DerivedStep *st, slong k, const Node *a)
{
    Value v;
    int rc = 0;
    derive_value_init(&v, D->r);
    /* (a name as derive knows it: a family member M[2] is "M_2") */
    char *name = a->kind == ND_NAME && a->sym ? pc_xstrdup(a->sym->name)
                                              : span_text(D->src, a->span);
    if (derive_eval(D, &v, a) < 0 || derive_unsolved_in(D, &v))
        rc = -1;
    derive_output_fill(&st->args[k], name, a->span, &v, D->src, D->r);
    pc_free(name);
    derive_value_clear(&v, D->r);
    return rc;
}

/* the operation of a definition's expression */
static StepOp step_op(const Node *e)
{
    if (e->kind != ND_CALL)
        return STEP_EXPR;
    switch ((Builtin)e->builtin) {
    case BI_ALONG:
        return STEP_ALONG;
    case BI_DIVIDE:
        return STEP_DIVIDE;
    case BI_MEET:
        return STEP_MEET;
    case BI_SUBST:
        return STEP_SUBST;
    case BI_DIFF:
        return STEP_DIFF;
    case BI_BEZIER:
        return STEP_BEZIER;
    default:
        return STEP_EXPR;
    }
}

/* the construction of a definition: its args and scalars */
static void step_construction(Deriver *D, DerivedStep *st, const Node *e)
{
    const Ring *r = D->r;
    const Node *a;
    slong k = 0;
    if (e->kind != ND_CALL)
        return;
    switch ((Builtin)e->builtin) {
    case BI_ALONG:
    case BI_DIVIDE:
        st->nargs = 2;
        st->args = pc_xcalloc(2, sizeof(DerivedOutput));
        for (a = e->args; k < 2; a = a->next, k++)
            step_arg(D, st, k, a);
        derive_eval_scalar(D, st->scalar, derive_nth(e, 2));
        break;
    case BI_BEZIER:
        st->nargs = e->nargs - 1;
        st->args = pc_xcalloc((size_t)st->nargs, sizeof(DerivedOutput));
        for (a = e->args->next; a; a = a->next, k++)
            step_arg(D, st, k, a);
        derive_eval_scalar(D, st->scalar, e->args);
        break;
    case BI_SUBST: {
        const Node *x = derive_nth(e, 1);
        st->var = pc_xstrdup(x->sym->name);
        if (x->sym->kind == SYM_POINT || x->sym->kind == SYM_UNKNOWN) {
            st->nargs = 1;
            st->args = pc_xcalloc(1, sizeof(DerivedOutput));
            step_arg(D, st, 0, derive_nth(e, 2));
        } else {
            derive_eval_scalar(D, st->scalar, derive_nth(e, 2));
        }
        break;
    }
    case BI_DIFF:
        st->var = pc_xstrdup(derive_nth(e, 1)->sym->name);
        st->order =
            derive_nth(e, 2) ? strtol(derive_nth(e, 2)->text, NULL, 10) : 1;
        break;
    case BI_MEET: {
        const Node *fa = derive_nth(e, 0), *fb = derive_nth(e, 1);
        int ok = 1;
        st->nfirst = fa->nargs;
        st->nargs = fa->nargs + fb->nargs;
        st->args = pc_xcalloc((size_t)st->nargs, sizeof(DerivedOutput));
        for (a = fa->args; a; a = a->next, k++)
            ok &= step_arg(D, st, k, a) == 0;
        for (a = fb->args; a; a = a->next, k++)
            ok &= step_arg(D, st, k, a) == 0;
        if (!ok || fa->nargs != 2)
            break;
        /* the args' equations (borrowed views) */
        PointEq pa[2], pb[3];
        for (slong j = 0; j < 2; j++)
            pa[j][0] = st->args[j].eq[0];
        for (slong j = 0; j < fb->nargs; j++)
            pb[j][0] = st->args[2 + j].eq[0];
        RatFunStruct *par = ratfun_vec_init(fb->nargs, r);
        if (construct_meet_params(par, st->value.eq, (const PointEq *)pa,
                                  (const PointEq *)pb, fb->nargs, r) == 0) {
            st->nparams = fb->nargs;
            st->params = par;
        } else {
            ratfun_vec_clear(par, fb->nargs, r);
        }
        RatFunStruct *co = ratfun_vec_init(fb->nargs + 1, r);
        slong w = 0;
        if (st->params &&
            construct_meet_sv(co, &w, st->det, (const PointEq *)pa,
                              (const PointEq *)pb, fb->nargs, r) == 0) {
            st->has_sv = 1;
            st->sv_w = 2 + w;
            st->sv_coord = co;
        } else {
            ratfun_vec_clear(co, fb->nargs + 1, r);
        }
        break;
    }
    default:
        break;
    }
}

/* Derived.steps (derive.h): after a successful derivation, one step per
 * definition and per unknown a solve determines, in source order, from the
 * final values; the arguments of the constructions are evaluated again
 * (names are memoised: copies) */
void derive_record_steps(Deriver *D, Derived *d, const Source *src)
{
    const Ring *r = D->r;
    const SemaInfo *info = D->info;
    slong n = 0;
    for (int i = 0; i < info->nsteps; i++) {
        const Stmt *st = info->steps[i];
        if (st->kind != ST_SOLVE)
            n++;
        else
            for (Name *nm = st->names; nm; nm = nm->next)
                n++;
    }
    d->steps = pc_xcalloc((size_t)(n ? n : 1), sizeof(DerivedStep));
    for (int i = 0; i < info->nsteps; i++) {
        const Stmt *st = info->steps[i];
        if (st->kind == ST_SOLVE) {
            for (Name *nm = st->names; nm; nm = nm->next) {
                DerivedStep *ds = &d->steps[d->nsteps++];
                Sym *u = NULL;
                for (int k = 0; k < info->nunknowns && !u; k++)
                    if (strcmp(info->unknowns[k]->name, nm->text) == 0)
                        u = info->unknowns[k];
                ratfun_init(ds->scalar, r);
                ratfun_init(ds->det, r);
                ds->op = STEP_SOLVE;
                ds->expr = span_text(src, st->span);
                Value uv;
                uv.is_point = u->is_point;
                uv.p[0] = D->usol[u->index][0]; /* borrowed */
                uv.s[0] = D->ssol[u->index];
                if (!D->usolved[u->index] || derive_unsolved_in(D, &uv))
                    step_pending(ds, u->name, nm->span, src, r);
                else
                    derive_output_fill(&ds->value, u->name, nm->span, &uv, src,
                                       r);
            }
            continue;
        }
        Sym *s = st->sym;
        DerivedStep *ds = &d->steps[d->nsteps++];
        budget_statement(src, st->expr->span); /* (blamed if out of memory) */
        const Value *v = &D->defs[s->index];
        ratfun_init(ds->scalar, r);
        ratfun_init(ds->det, r);
        ds->op = step_op(st->expr);
        ds->expr = span_text(src, st->expr->span);
        if (D->state[s->index] != 1 || derive_unsolved_in(D, v)) {
            step_pending(ds, s->name, s->span, src, r);
            continue;
        }
        derive_output_fill(&ds->value, s->name, s->span, v, src, r);
        step_construction(D, ds, st->expr);
    }
}

/* Derived.named: the scalar definitions whose value is v^k, v a kernel */
void derive_record_named(Deriver *D, Derived *d, const Source *src)
{
    const Ring *r = D->r;
    const SemaInfo *info = D->info;
    d->named = pc_xcalloc((size_t)info->nsteps + 1, sizeof(DerivedName));
    ulong *e = pc_xmalloc(sizeof(ulong) * (size_t)(r->nvars ? r->nvars : 1));
    for (int i = 0; i < info->nsteps && D->K; i++) {
        const Stmt *st = info->steps[i];
        if (st->kind == ST_SOLVE)
            continue;
        const Sym *s = st->sym;
        const Value *v = &D->defs[s->index];
        if (D->state[s->index] != 1 || v->is_point ||
            !fmpz_mpoly_is_one(v->s->den, r->ctx) ||
            fmpz_mpoly_length(v->s->num, r->ctx) != 1 ||
            !fmpz_is_one(v->s->num->coeffs))
            continue;
        fmpz_mpoly_get_term_exp_ui(e, v->s->num, 0, r->ctx);
        slong var = -1, nv = 0;
        for (slong k = 0; k < r->nvars; k++)
            if (e[k]) {
                var = k;
                nv++;
            }
        if (nv != 1 || !kernels_of_var(D->K, var))
            continue;
        int line, col;
        source_locate(src, s->span.start, &line, &col);
        DerivedName *nm = &d->named[d->nnamed++];
        nm->name = pc_xstrdup(s->name);
        nm->var = var;
        nm->exp = e[var];
        nm->line = line;
    }
    pc_free(e);
}
