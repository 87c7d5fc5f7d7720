/*
 * solve_num.c - the numeric solve: `solve EQ, ... for a, b near a = 1, b = 0`
 * (docs/language.md, "Numeric solve").
 *
 * The unknowns are scalars and the equations, once derived, are functions
 * of them alone (numbers, pi and the scalar functions of the unknowns: no
 * param, const or coordinate).  Each scalar equation is one residual
 * lhs - rhs; each point (or vector) equation one residual per weight of
 * lhs - rhs on the known points but the last (the weights of lhs - rhs sum
 * to 0, so the last follows from the others).  The Jacobian is exact: the
 * derivative of every residual by every unknown (kernel_derivative, the
 * chain rule through the functions).  Residuals and Jacobian are handed,
 * as the scalar outputs of a view of the derivation, to the numeric back
 * end (DeriveOptions.numeric: codegen/numsolve.c lowers them to a Plan and
 * runs damped Newton for as many residuals as unknowns, Levenberg-Marquardt
 * for more), and the values it finds become exact decimals: the shortest
 * decimal (at most 17 significant digits) that reads back to the double
 * found.  From there on the unknowns are solved, as by an exact solve: the
 * values are substituted into everything derived so far and every later
 * use.
 *
 * Called by derive_solve (solve_stmt.c) for a solve with `near`.
 */
#include "compiler/derive/derive_int.h"

#include <math.h>
#include <string.h>

#include "base/budget.h"
#include "base/mem.h"
#include "base/numfmt.h"

enum {
    NUMSOLVE_MAX_UNKNOWNS = 64,     // runtime/lsq.h's LSQ_MAX_UNKNOWNS
    NUMSOLVE_MAX_RESIDUALS = 10000, // (its Jacobian is m*n exact values)
    NUMSOLVE_MAX_ITER = 200,
};

/* the system being built: n unknowns (their ring variables var, symbols
 * sym, names in the `for` list nm), m residuals (row, each from equation
 * eq_of[i]) and the exact Jacobian jac (m*n) */
typedef struct NumSys {
    slong n, m, cap;
    slong *var;
    Sym **sym;
    Name **nm;
    RatFunStruct *row; // m residuals (owned)
    slong *eq_of;
    RatFunStruct *jac; // m*n (owned), once built
    double *u;         // the starts, then the values
} NumSys;

/* the unknowns: scalars only (an unknown point has no number); 1, or 0
 * reported */
static int num_unknowns(Deriver *D, const Stmt *st, NumSys *S, Sym **syms)
{
    int ok = 1;
    slong j = 0;
    for (Name *nm = st->names; nm; nm = nm->next, j++) {
        S->sym[j] = syms[j];
        S->nm[j] = nm;
        S->var[j] = D->uvar[syms[j]->index];
        if (syms[j]->is_point) {
            diag_error(D->diag, nm->span,
                       "'%s' is an unknown point; a numeric solve ('near') "
                       "finds unknown scalars only (unknown scalar %s)",
                       nm->text, nm->text);
            ok = 0;
        }
    }
    if (ok && S->n > NUMSOLVE_MAX_UNKNOWNS) {
        diag_error(D->diag, st->span,
                   "system too large to solve numerically: %ld unknowns (at "
                   "most %d)",
                   (long)S->n, NUMSOLVE_MAX_UNKNOWNS);
        ok = 0;
    }
    return ok;
}

/* a number written with literals and + - * / ^ */
static int is_number(const Node *n)
{
    switch (n->kind) {
    case ND_NUM:
        return 1;
    case ND_NEG:
        return is_number(n->lhs);
    case ND_ADD:
    case ND_SUB:
    case ND_MUL:
    case ND_DIV:
    case ND_POW:
        return is_number(n->lhs) && is_number(n->rhs);
    default:
        return 0;
    }
}

/* one start `a = VALUE` into S->u (have[j] set); 1, or 0 reported */
static int num_start(Deriver *D, NumSys *S, const Equation *b, char *have)
{
    const char *name = b->lhs->text;
    slong j;
    for (j = 0; j < S->n && strcmp(S->sym[j]->name, name) != 0; j++)
        ;
    if (j == S->n) {
        diag_error(D->diag, b->lhs->span,
                   "'%s' is not an unknown of this solve; expected one of "
                   "the unknowns after 'for'",
                   name);
        return 0;
    }
    if (have[j]) {
        diag_error(D->diag, b->lhs->span, "'%s' has two starts", name);
        return 0;
    }
    Value v;
    fmpq_t q;
    int ok = 0;
    derive_value_init(&v, D->r);
    fmpq_init(q);
    if (!is_number(b->rhs))
        diag_error(D->diag, b->rhs->span,
                   "expected a number as the start of '%s' (numbers with + "
                   "- * / ^)",
                   name);
    else if (derive_eval(D, &v, b->rhs) == 0) {
        ok = ratfun_get_fmpq(q, v.s, D->r);
        S->u[j] = ok ? fmpq_get_d(q) : 0;
        if (ok && !isfinite(S->u[j])) {
            diag_error(D->diag, b->rhs->span,
                       "the start of '%s' is beyond the range of a double",
                       name);
            ok = 0;
        }
    }
    have[j] = (char)ok;
    fmpq_clear(q);
    derive_value_clear(&v, D->r);
    return ok;
}

/* every unknown's start; 1, or 0 reported */
static int num_starts(Deriver *D, const Stmt *st, NumSys *S)
{
    char *have = pc_xcalloc((size_t)S->n, 1);
    int ok = 1;
    for (const Equation *b = st->start; b; b = b->next)
        if (!num_start(D, S, b, have))
            ok = 0;
    for (slong j = 0; ok && j < S->n; j++)
        if (!have[j]) {
            diag_error(D->diag, S->nm[j]->span,
                       "no start for '%s'; expected 'near %s = VALUE' (a "
                       "numeric solve starts every unknown)",
                       S->sym[j]->name, S->sym[j]->name);
            ok = 0;
        }
    pc_free(have);
    return ok;
}

/* mark[v] for every ring variable: 1 when x may not be evaluated with
 * the unknowns given (a param, a const, another unknown, a distance or a
 * coordinate, or a function of one), 2 when it is an unknown of S or a
 * function of one (and of nothing marked 1), 0 a number (pi) */
static unsigned char *num_marks(const Deriver *D, const NumSys *S)
{
    const Ring *r = D->r;
    slong nv = r->ctx->minfo->nvars, first = D->K ? D->K->first : r->nvars;
    unsigned char *mark = pc_xcalloc((size_t)(nv ? nv : 1), 1);
    slong *deg = flint_malloc(sizeof *deg * (size_t)(nv ? nv : 1));
    for (slong v = 0; v < first; v++)
        mark[v] = 1;
    for (slong j = 0; j < S->n; j++)
        mark[S->var[j]] = 2;
    for (slong i = 0; D->K && i < D->K->n; i++) {
        const Kernel *k = &D->K->k[i];
        unsigned char m = 0;
        if (k->fn == KF_DIST || k->fn == KF_COORD)
            m = 1;
        for (int a = 0; a < 2 && m != 1 && k->fn != KF_PI; a++) {
            const RatFunStruct *x = a ? k->arg2 : k->arg;
            if (a && k->fn != KF_ATAN2)
                break;
            for (int part = 0; part < 2; part++) {
                fmpz_mpoly_degrees_si(deg, part ? x->den : x->num, r->ctx);
                for (slong v = 0; v < nv; v++)
                    if (deg[v] > 0 && mark[v] > m)
                        m = mark[v];
            }
        }
        mark[k->var] = m;
    }
    flint_free(deg);
    return mark;
}

/* 1 when x uses a variable marked 1 (that one in *which), else 2 when it
 * uses one marked 2, else 0 */
static int num_uses(const RatFun x, const unsigned char *mark, slong *which,
                    const Ring *r)
{
    slong nv = r->ctx->minfo->nvars;
    slong *deg = flint_malloc(sizeof *deg * (size_t)(nv ? nv : 1));
    int best = 0;
    for (int part = 0; part < 2; part++) {
        fmpz_mpoly_degrees_si(deg, part ? x->den : x->num, r->ctx);
        for (slong v = 0; v < nv; v++)
            if (deg[v] > 0 && mark[v] && best != 1) {
                best = mark[v];
                *which = v;
            }
    }
    flint_free(deg);
    return best;
}

/* a variable's name in a message: its name, or the function's text */
static const char *var_name(const Deriver *D, slong v)
{
    if (D->K && v >= D->K->first && v < D->K->first + D->K->n)
        return D->K->k[v - D->K->first].name;
    return D->r->names[v];
}

static void num_push(NumSys *S, const RatFun x, slong e, const Ring *r)
{
    if (S->m == S->cap) {
        slong cap = S->cap ? 2 * S->cap : 8;
        RatFunStruct *row = ratfun_vec_init(cap, r);
        for (slong i = 0; i < S->m; i++)
            ratfun_swap(row + i, S->row + i, r);
        ratfun_vec_clear(S->row, S->cap, r);
        S->row = row;
        S->eq_of = pc_xrealloc(S->eq_of, sizeof(slong) * (size_t)cap);
        S->cap = cap;
    }
    ratfun_set(S->row + S->m, x, r);
    S->eq_of[S->m++] = e;
}

/* equation e's residuals into S: checked to depend on the unknowns, and
 * on nothing else; 1, or 0 reported */
static int num_equation(Deriver *D, NumSys *S, const RatFunStruct *w, slong nw,
                        const Equation *q, slong e, const unsigned char *mark)
{
    const Ring *r = D->r;
    int dep = 0;
    for (slong i = 0; i < nw; i++) {
        slong v = -1;
        int u = num_uses(w + i, mark, &v, r);
        if (u == 1) {
            diag_error(D->diag, q->span,
                       "this equation depends on %s, not only on the "
                       "unknowns: a numeric solve needs equations in its "
                       "unknowns and numbers alone",
                       var_name(D, v));
            return 0;
        }
        dep |= u == 2;
    }
    if (!dep) {
        diag_error(D->diag, q->span,
                   "this equation does not depend on the unknowns of the "
                   "solve");
        return 0;
    }
    for (slong i = 0; i < nw; i++)
        num_push(S, w + i, e, r);
    return 1;
}

/* the residuals of every equation; 1, or 0 reported */
static int num_residuals(Deriver *D, NumSys *S, PointEq *eqs,
                         RatFunStruct *seqs, const char *scalar_eq,
                         Equation **eqn, slong neq)
{
    const Ring *r = D->r;
    unsigned char *mark = num_marks(D, S);
    int ok = 1;
    for (slong e = 0; e < neq; e++) {
        if (scalar_eq[e]) {
            ok &= num_equation(D, S, seqs + e, 1, eqn[e], e, mark);
            continue;
        }
        /* the weights of lhs - rhs sum to 0: all but the last */
        slong nw = eqs[e]->len;
        RatFunStruct *w = ratfun_vec_init(nw, r);
        pteq_get_weights(w, eqs[e], r);
        ok &= num_equation(D, S, w, nw > 1 ? nw - 1 : nw, eqn[e], e, mark);
        ratfun_vec_clear(w, nw, r);
    }
    pc_free(mark);
    if (ok && S->m < S->n)
        diag_error(D->diag, eqn[0] ? eqn[0]->span : (Span){0, 0},
                   "%ld scalar equation%s for %ld unknowns: the system is "
                   "underdetermined (a numeric solve needs at least one "
                   "equation per unknown)",
                   (long)S->m, S->m == 1 ? "" : "s", (long)S->n);
    if (ok && S->m > NUMSOLVE_MAX_RESIDUALS)
        diag_error(D->diag, eqn[0]->span,
                   "system too large to solve numerically: %ld scalar "
                   "equations (at most %d)",
                   (long)S->m, NUMSOLVE_MAX_RESIDUALS);
    return ok && S->m >= S->n && S->m <= NUMSOLVE_MAX_RESIDUALS;
}

/* the exact Jacobian dr_i/du_j; 1, or 0 reported */
static int num_jacobian(Deriver *D, NumSys *S, Equation **eqn)
{
    const Ring *r = D->r;
    S->jac = ratfun_vec_init(S->m * S->n, r);
    for (slong i = 0; i < S->m; i++)
        for (slong j = 0; j < S->n; j++) {
            RatFunStruct *d = S->jac + i * S->n + j;
            if (!D->K) {
                ratfun_derivative(d, S->row + i, S->var[j], r);
                continue;
            }
            int rc = kernel_derivative(D->K, d, S->row + i, S->var[j]);
            if (rc != 0) {
                derive_kernel_error_at(D, rc, eqn[S->eq_of[i]]->span,
                                       eqn[S->eq_of[i]]->span);
                return 0;
            }
        }
    return 1;
}

/* "a = 1.5, b = -2" (caller frees) */
static char *num_point_text(const NumSys *S)
{
    size_t cap = 64, len = 0;
    char *out = pc_xmalloc(cap);
    out[0] = '\0';
    for (slong j = 0; j < S->n; j++) {
        char buf[48];
        pc_snprintf(buf, sizeof buf, "%.9g", S->u[j]);
        size_t need = len + strlen(S->sym[j]->name) + strlen(buf) + 8;
        if (need > cap) {
            cap = 2 * need;
            out = pc_xrealloc(out, cap);
        }
        len += (size_t)sprintf(out + len, "%s%s = %s", j ? ", " : "",
                               S->sym[j]->name, buf);
    }
    return out;
}

/* the view of the derivation the back end lowers: the residuals, then the
 * Jacobian, as scalar outputs over the ring's variables before the
 * kernels (the ring and kernels borrowed, read only) */
static void num_view(const Deriver *D, const NumSys *S, Equation **eqn,
                     Derived *view, DerivedOutput *outs)
{
    const Derived *d = D->d;
    const Ring *r = D->r;
    slong m = S->m, n = S->n;
    memset(view, 0, sizeof *view);
    view->scheme = (char *)"numeric_solve";
    view->filename = d->filename;
    view->text = d->text;
    view->len = d->len;
    view->src = *D->src;
    view->nparams = D->K ? D->K->first : r->nvars;
    view->params = (char **)r->names;
    view->ring = *r; /* a shallow copy: read only, never cleared */
    view->kernels = D->K;
    view->noutputs = m + m * n;
    view->outputs = outs;
    for (slong o = 0; o < m + m * n; o++) {
        slong i = o < m ? o : (o - m) / n;
        const Equation *q = eqn[S->eq_of[i]];
        memset(&outs[o], 0, sizeof outs[o]);
        outs[o].name = o < m ? "residual" : "jacobian";
        outs[o].kind = KIND_SCALAR;
        outs[o].scalar[0] = o < m ? S->row[o] : S->jac[o - m]; /* borrowed */
        outs[o].span = q->span;
        int col;
        source_locate(D->src, q->span.start, &outs[o].line, &col);
    }
}

/* the report of a solve that found no values */
static void num_failed(Deriver *D, const Stmt *st, const NumSys *S,
                       const NumericSystem *ns)
{
    char *at = num_point_text(S);
    switch (ns->status) {
    case NUMERIC_NOCONV:
        diag_error(D->diag, st->span,
                   "the numeric solve did not converge (%s, %d iteration%s): "
                   "it reached max |residual| %.3g at %s; try another start "
                   "after 'near'",
                   ns->method, ns->iterations, ns->iterations == 1 ? "" : "s",
                   ns->max_resid, at);
        break;
    case NUMERIC_SINGULAR:
        diag_error(D->diag, st->span,
                   "the Jacobian of the equations is singular (rank %d of "
                   "%d) at %s, after %d iteration%s: the equations do not "
                   "determine the unknowns there; try another start after "
                   "'near'",
                   ns->rank, ns->n, at, ns->iterations,
                   ns->iterations == 1 ? "" : "s");
        break;
    case NUMERIC_EVAL:
        diag_error(D->diag, st->span,
                   "the equations cannot be evaluated at the start %s (a "
                   "denominator vanishes or a function's argument is "
                   "outside its domain); try another start after 'near'",
                   at);
        break;
    default:
        diag_error(D->diag, st->span,
                   "the equations of this solve cannot be evaluated in "
                   "double precision (a coefficient beyond the range of a "
                   "double)");
        break;
    }
    pc_free(at);
}

/* x = the shortest decimal that reads back to the double v */
static void num_decimal(RatFun x, double v, const Ring *r)
{
    char buf[64];
    double a = fabs(v);
    for (int digits = 1; digits <= 17; digits++) {
        pc_snprintf(buf, sizeof buf, "%.*e", digits - 1, a);
        if (pc_strtod(buf, NULL) == a)
            break;
    }
    fmpq_t q;
    fmpq_init(q);
    if (ratfun_literal_fmpq(q, buf) != 0) /* (a double's exponent fits) */
        fmpq_zero(q);
    if (v < 0)
        fmpq_neg(q, q);
    ratfun_set_fmpq(x, q, r);
    fmpq_clear(q);
}

/* the values found: the unknowns solved, substituted everywhere */
static void num_bind(Deriver *D, const Stmt *st, const NumSys *S)
{
    const Ring *r = D->r;
    for (slong j = 0; j < S->n; j++) {
        int k = S->sym[j]->index;
        num_decimal(D->ssol + k, S->u[j], r);
        D->usolved[k] = 1;
        derive_assume_into(D, &D->uassume[k]);
    }
    for (slong j = 0; j < S->n; j++)
        derive_substitute_scalar(D, S->var[j], D->ssol + S->sym[j]->index, st);
}

/* the back end on S: 1 when it found the values (S->u), or 0 reported */
static int num_run(Deriver *D, const Stmt *st, NumSys *S, Equation **eqn)
{
    if (!D->numeric) {
        diag_error(D->diag, st->span,
                   "a numeric solve needs a numeric back end, and this "
                   "program gave none (DeriveOptions.numeric)");
        return 0;
    }
    slong nout = S->m + S->m * S->n;
    DerivedOutput *outs = pc_xmalloc(sizeof *outs * (size_t)nout);
    int *input = pc_xmalloc(sizeof(int) * (size_t)S->n);
    Derived view;
    num_view(D, S, eqn, &view, outs);
    for (slong j = 0; j < S->n; j++)
        input[j] = (int)S->var[j];
    NumericSystem ns = {.view = &view,
                        .n = (int)S->n,
                        .m = (int)S->m,
                        .input = input,
                        .u = S->u,
                        .max_iter = NUMSOLVE_MAX_ITER};
    int rc = D->numeric(&ns);
    budget_statement(D->src, st->span); /* lowering marked the view */
    if (rc != 0 || ns.status != NUMERIC_OK)
        num_failed(D, st, S, &ns);
    if (D->verbose && ns.status == NUMERIC_OK) {
        int line, col;
        source_locate(D->src, st->span.start, &line, &col);
        pc_fprintf(D->verbose,
                   "%s:%d: numeric solve (%s): %d iterations, max |residual| "
                   "%.3g, rms %.3g\n",
                   D->src->name, line, ns.method, ns.iterations, ns.max_resid,
                   ns.rms_resid);
    }
    pc_free(input);
    pc_free(outs);
    return rc == 0 && ns.status == NUMERIC_OK;
}

void derive_solve_numeric(Deriver *D, Stmt *st, PointEq *eqs,
                          RatFunStruct *seqs, const char *scalar_eq,
                          Equation **eqn, slong neq, Sym **syms, slong nunk)
{
    const Ring *r = D->r;
    NumSys S = {.n = nunk};
    S.var = pc_xmalloc(sizeof(slong) * (size_t)(nunk ? nunk : 1));
    S.sym = pc_xmalloc(sizeof(Sym *) * (size_t)(nunk ? nunk : 1));
    S.nm = pc_xmalloc(sizeof(Name *) * (size_t)(nunk ? nunk : 1));
    S.u = pc_xcalloc((size_t)(nunk ? nunk : 1), sizeof(double));
    int ok = num_unknowns(D, st, &S, syms);
    ok = ok && num_starts(D, st, &S);
    ok = ok && num_residuals(D, &S, eqs, seqs, scalar_eq, eqn, neq);
    ok = ok && num_jacobian(D, &S, eqn);
    if (ok && num_run(D, st, &S, eqn))
        num_bind(D, st, &S);
    if (S.jac)
        ratfun_vec_clear(S.jac, S.m * S.n, r);
    if (S.row)
        ratfun_vec_clear(S.row, S.cap, r);
    pc_free(S.eq_of);
    pc_free(S.u);
    pc_free(S.nm);
    pc_free(S.sym);
    pc_free(S.var);
}
