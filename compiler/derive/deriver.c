/*
 * deriver.c - the derive pass proper: the Deriver's setup and teardown,
 * the declared bounds of params and consts, and every definition and
 * `solve` in source order (derive_def here, derive_solve in solve_stmt.c).
 *
 * Runs after ringplan.c, before outputs.c (pipeline.c).
 */
#include "compiler/derive/derive_int.h"

#include <stdlib.h>
#include <string.h>

#include "base/budget.h"
#include "base/mem.h"
#include "base/numfmt.h"

/* the difference x (a combination or a scalar) as text, each weight by
 * derive_show: "A*(w) + B*(w)"; the caller frees it */
static char *show_difference(Deriver *D, const Value *x)
{
    const Ring *r = D->r;
    if (!x->is_point)
        return derive_show(x->s, r);
    char *text = NULL;
    size_t len = 0;
    FILE *m = pc_xopen_memstream(&text, &len);
    RatFun w;
    ratfun_init(w, r);
    for (slong i = 0; i < x->p->len; i++) {
        pteq_get_weight(w, x->p, x->p->terms[i].point, r);
        char *ws = derive_show(w, r);
        fprintf(m, "%s%s*(%s)", i ? " + " : "",
                D->info->points[x->p->terms[i].point]->name, ws);
        flint_free(ws);
    }
    ratfun_clear(w, r);
    pc_xclose_memstream(m);
    return text;
}

/* the joints of the join() calls of a definition: where segment g ends,
 * segment h must begin (Dolya 2.1: R_{k-1}(tau^1) = R_k(tau^0)) */
static int check_joints(Deriver *D, Sym *s)
{
    const Ring *r = D->r;
    int st = 0;
    for (const Equation *e = s->def->joints; e && st == 0; e = e->next) {
        Value a, b;
        derive_value_init(&a, r);
        derive_value_init(&b, r);
        if (derive_eval(D, &a, e->lhs) < 0 || derive_eval(D, &b, e->rhs) < 0) {
            st = -1;
        } else {
            if (a.is_point)
                pteq_sub(a.p, a.p, b.p, r);
            else
                ratfun_sub(a.s, a.s, b.s, r);
            if (derive_reduce_value(D, &a, e->lhs) < 0)
                st = -1;
            else if (a.is_point ? !pteq_is_zero(a.p, r)
                                : !ratfun_is_zero(a.s, r)) {
                const char *sp = strchr(e->what, ' ');
                char *txt = show_difference(D, &a);
                diag_error(D->diag, e->span,
                           "the segments %.*s and %s do not meet at this "
                           "knot: the end of %.*s minus the start of %s is "
                           "%s, expected 0",
                           (int)(sp - e->what), e->what, sp + 1,
                           (int)(sp - e->what), e->what, sp + 1, txt);
                pc_free(txt);
                st = -1;
            }
        }
        derive_value_clear(&a, r);
        derive_value_clear(&b, r);
    }
    return st;
}

/* derives definition i and checks its weight sum */
static void derive_def(Deriver *D, Sym *s)
{
    const Ring *r = D->r;
    Value *v = &D->defs[s->index];
    double t0 = D->verbose ? derive_now_seconds() : 0;
    budget_statement(D->src, s->def->expr->span);
    derive_assume_clear(D);
    if (s->bad || D->expired || derive_eval(D, v, s->def->expr) < 0) {
        D->state[s->index] = -1;
        return;
    }
    if (s->def->joints && check_joints(D, s) < 0) {
        D->state[s->index] = -1;
        return;
    }
    D->state[s->index] = 1;
    derive_assume_into(D, &D->dassume[s->index]);
    if (D->verbose) {
        slong terms, deg, bits;
        int line, col;
        derive_value_size(v, &terms, &deg, &bits, r);
        source_locate(D->src, s->def->expr->span.start, &line, &col);
        pc_fprintf(D->verbose,
                   "%s:%d: %s: %.3f ms, %s, %ld terms, degree %ld, %ld-bit "
                   "coefficients\n",
                   D->src->name, line, s->name,
                   1e3 * (derive_now_seconds() - t0),
                   v->is_point ? "combination of points" : "scalar",
                   (long)terms, (long)deg, (long)bits);
        fflush(D->verbose);
    }
    if (!v->is_point)
        return;
    RatFun sum;
    ratfun_init(sum, r);
    pteq_weight_sum(sum, v->p, r);
    if (D->K) /* (on failure sum keeps an equal, unreduced form) */
        (void)kernel_reduce(D->K, sum);
    if (!ratfun_is_zero(sum, r) && !ratfun_is_one(sum, r)) {
        char *txt = derive_show(sum, r);
        if (!ratfun_is_constant(sum, r) && kernel_uses(D->K, sum, 1))
            diag_error(D->diag, s->def->expr->span,
                       "the weights of %s could not be proved to sum to 0 "
                       "(a vector) or 1 (a point): their sum is %s, and the "
                       "identities pointcalc applies (sin^2 + cos^2 = 1, "
                       "cosh^2 - sinh^2 = 1, sqrt(x)^2 = x) do not reduce it "
                       "to a number; write the point as C + (vector), with "
                       "the weights of the vector summing to 0 term by term",
                       s->name, txt);
        else
            diag_error(D->diag, s->def->expr->span,
                       "weights of %s sum to %s, not 0 (a vector) or 1 (a "
                       "point)",
                       s->name, txt);
        flint_free(txt);
        D->state[s->index] = -1;
    }
    ratfun_clear(sum, r);
}

/* one end of a declared bound of ring variable var (a param or a const):
 * the exact value into d->bound, its flags, and what it tells the kernels'
 * sign proofs (kernels_set_range: an exact number, or rational bounds of
 * a constant expression; for a param's end in terms of consts, only its
 * sign).  upper: the upper end.  Returns -1 on an error (reported). */
static int declare_end(Deriver *D, Derived *d, slong var, const Node *end,
                       int open, int upper, int is_const)
{
    const Ring *r = D->r;
    RatFun *vb = (RatFun *)(d->bound + 2 * var + upper);
    if (derive_eval_scalar(D, *vb, end) < 0)
        return -1;
    fmpq_t q, lo, hi;
    fmpq_init(q);
    fmpq_init(lo);
    fmpq_init(hi);
    int lo_open = 0, hi_open = 0, found = 0, rc = 0;
    if (ratfun_get_fmpq(q, *vb, r)) {
        fmpq_set(lo, q);
        fmpq_set(hi, q);
        found = 3;
    } else if (D->K) {
        found = kernel_bounds(D->K, *vb, lo, &lo_open, hi, &hi_open);
    }
    int constant = found || ratfun_get_fmpq(q, *vb, r);
    if (D->keep_abs && !is_const) /* --keep-abs: a param's range decides */
        found = 0, constant = 1;  /* no sign */
    if (!constant && is_const) {
        diag_error(D->diag, end->span,
                   "expected a number as the bound of a const (like 0, 1/2 "
                   "or pi): a bound cannot depend on a param or a const");
        rc = -1;
    } else if (D->K && found) {
        /* var >= value >= lo (strict when either is), or var <= value <=
         * hi */
        if (!upper && (found & 1))
            kernels_set_range(D->K, var, lo, open || lo_open, NULL, 0);
        if (upper && (found & 2))
            kernels_set_range(D->K, var, NULL, 0, hi, open || hi_open);
    } else if (D->K && !constant) {
        /* a param's end in terms of consts: its sign, where it is known */
        int sg = kernel_sign(D->K, *vb);
        if (!upper && sg > 0)
            kernels_set_sign(D->K, var,
                             sg == 2 || open ? KSIGN_POS : KSIGN_NONNEG);
        if (upper && sg < 0) {
            fmpq_zero(q);
            kernels_set_range(D->K, var, NULL, 0, q, sg == -2 || open);
        }
    }
    if (rc == 0)
        d->bound_flags[var] |=
            (unsigned char)(upper ? DERIVED_BOUND_HI |
                                        (open ? DERIVED_BOUND_HI_OPEN : 0)
                                  : DERIVED_BOUND_LO |
                                        (open ? DERIVED_BOUND_LO_OPEN : 0));
    fmpq_clear(hi);
    fmpq_clear(lo);
    fmpq_clear(q);
    return rc;
}

/* The declared bounds of the params (`param t in [0, 1]`) and consts
 * (`const e in (0, 1)`, `const a > 0`, `const k <= 1`): into d->bound and
 * the kernels' sign proofs, which may then simplify abs(t), sqrt(a^2),
 * sign(e^2 - 1) on them; a result that rests on them holds only there,
 * and the numeric side checks it (DERIVED_BOUND_ASSUMED).  An empty
 * interval is an error. */
static void declare_bounds(Deriver *D, Derived *d)
{
    const SemaInfo *info = D->info;
    slong nv = d->nparams + d->nconsts;
    d->bound = ratfun_vec_init(2 * nv, D->r);
    d->bound_flags = pc_xcalloc((size_t)(nv ? nv : 1), 1);
    /* the consts first: a param's range may be in terms of them */
    for (slong i = 0; i < nv; i++) {
        slong v = (i + d->nparams) % (nv ? nv : 1);
        int is_const = v >= d->nparams;
        const Sym *s =
            is_const ? info->consts[v - d->nparams] : info->params[v];
        const Stmt *st = s->decl;
        /* (a bound with an error of its own was reported by sema: its
         * names may be unresolved) */
        if (!st || st->bad)
            continue;
        int ok = 1;
        if (st->lo)
            ok &= declare_end(D, d, v, st->lo, st->lo_open, 0, is_const) == 0;
        if (st->hi)
            ok &= declare_end(D, d, v, st->hi, st->hi_open, 1, is_const) == 0;
        fmpq_t a, b;
        fmpq_init(a);
        fmpq_init(b);
        if (ok && st->lo && st->hi &&
            ratfun_get_fmpq(a, d->bound + 2 * v, D->r) &&
            ratfun_get_fmpq(b, d->bound + 2 * v + 1, D->r)) {
            int c = fmpq_cmp(a, b);
            if (c > 0 || (c == 0 && (st->lo_open || st->hi_open)))
                diag_error(D->diag, st->hi->span,
                           "empty interval for '%s': expected an upper end "
                           "%s the lower one",
                           s->name,
                           st->lo_open || st->hi_open ? "greater than"
                                                      : "at least");
        }
        fmpq_clear(b);
        fmpq_clear(a);
    }
}

/* D for a derivation of info into d (its ring planned): nothing derived
 * yet, the time budget counted from `start` */
void deriver_init(Deriver *D, Derived *d, SemaInfo *info, Diag *diag,
                  const Source *src, double start, const DeriveOptions *opt)
{
    const Ring *r = &d->ring;
    *D = (Deriver){
        .diag = diag, .r = r, .info = info, .src = src, .K = d->kernels};
    if (D->K)
        D->K->deadline = opt->max_seconds > 0 ? start + opt->max_seconds : 0;
    D->max_seconds = opt->max_seconds;
    D->keep_abs = opt->keep_abs;
    D->deadline = opt->max_seconds > 0 ? start + opt->max_seconds : 0;
    D->verbose = opt->verbose;
    D->numeric = opt->numeric;
    D->d = d;
    D->defs =
        pc_xmalloc(sizeof(Value) * (size_t)(info->ndefs ? info->ndefs : 1));
    D->state = pc_xcalloc((size_t)(info->ndefs ? info->ndefs : 1), sizeof(int));
    for (int i = 0; i < info->ndefs; i++)
        derive_value_init(&D->defs[i], r);
    D->ucol0 = info->npoints;
    D->usol = pc_xmalloc(sizeof(PointEq) *
                         (size_t)(info->nunknowns ? info->nunknowns : 1));
    D->usolved = pc_xcalloc((size_t)(info->nunknowns ? info->nunknowns : 1),
                            sizeof(int));
    D->dassume = pc_xcalloc((size_t)(info->ndefs ? info->ndefs : 1),
                            sizeof(unsigned char *));
    D->uassume = pc_xcalloc((size_t)(info->nunknowns ? info->nunknowns : 1),
                            sizeof(unsigned char *));
    D->ssol = ratfun_vec_init(info->nunknowns, r);
    D->uvar = pc_xmalloc(sizeof(slong) *
                         (size_t)(info->nunknowns ? info->nunknowns : 1));
    for (int k = 0, m = 0; k < info->nunknowns; k++) {
        pteq_init(D->usol[k], r);
        D->uvar[k] =
            info->unknowns[k]->is_point ? -1 : d->nparams + d->nconsts + m++;
    }
}

/* the declared bounds, then every definition and solve in source order */
void derive_all(Deriver *D, Derived *d)
{
    const SemaInfo *info = D->info;
    declare_bounds(D, d);
    for (int i = 0; i < info->nsteps; i++) {
        if (info->steps[i]->kind == ST_SOLVE)
            derive_solve(D, info->steps[i]);
        else
            derive_def(D, info->steps[i]->sym);
    }
}

void deriver_clear(Deriver *D)
{
    const Ring *r = D->r;
    const SemaInfo *info = D->info;
    for (int i = 0; i < info->ndefs; i++)
        derive_value_clear(&D->defs[i], r);
    for (int k = 0; k < info->nunknowns; k++)
        pteq_clear(D->usol[k], r);
    pc_free(D->usol);
    ratfun_vec_clear(D->ssol, info->nunknowns, r);
    pc_free(D->uvar);
    pc_free(D->usolved);
    for (int i = 0; i < info->ndefs; i++)
        pc_free(D->dassume[i]);
    for (int i = 0; i < info->nunknowns; i++)
        pc_free(D->uassume[i]);
    pc_free(D->dassume);
    pc_free(D->uassume);
    pc_free(D->defs);
    pc_free(D->state);
}
