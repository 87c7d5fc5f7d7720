/*
 * solve_stmt.c - the `solve` statement: its equations evaluated, solved
 * for the unknown points (solve.c) or, with unknown scalars among them, as
 * a linear system over the rational functions (linsolve.c), the errors of
 * a singular or inconsistent system, and the solutions substituted into
 * everything derived so far.
 *
 * Called by derive_all (deriver.c) for each ST_SOLVE.
 */
#include "compiler/derive/derive_int.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/budget.h"
#include "base/mem.h"
#include "base/numfmt.h"
#include "compiler/algebra/solve.h"

/* x (a point equation p or a scalar *sp) with var replaced by v, also
 * inside the functions' arguments (sqrt(h) with h solved is sqrt of the
 * solution: with ratfun_compose_var alone it kept h, an unknown no output
 * may depend on, and lowering such an output broke) */
static int compose(Deriver *D, int is_point, PointEq p, RatFunStruct *s,
                   slong var, const RatFun v)
{
    if (D->K)
        return is_point ? kernel_compose_pteq(D->K, p, p, var, v)
                        : kernel_compose(D->K, s, s, var, v);
    return is_point ? pteq_compose_var(p, p, var, v, D->r)
                    : ratfun_compose_var(s, s, var, v, D->r);
}

static Span s_span(const Deriver *D, int i)
{
    return D->info->defs[i]->def->expr->span;
}

/* replaces the unknown scalar var by its solution v in every value derived
 * so far (a value whose denominator vanishes then keeps its form: its
 * definition was generic in var, and the outputs are checked later) */
void derive_substitute_scalar(Deriver *D, slong var, const RatFun v,
                              const Stmt *st)
{
    const Ring *r = D->r;
    for (int i = 0; i < D->info->ndefs; i++) {
        Value *d = &D->defs[i];
        int rc;
        if (D->state[i] != 1)
            continue;
        if (derive_value_has_var(d, var, r)) /* the solve's assumptions too */
            derive_assume_into(D, &D->dassume[i]);
        rc = compose(D, d->is_point, d->p, d->s, var, v);
        if (rc != 0 && rc != KERNEL_EZERO && rc != RATFUN_EPOLE) {
            derive_kernel_error_at(D, rc, s_span(D, i), st->span);
            D->state[i] = -1;
        } else if (rc != 0) {
            const Sym *s = D->info->defs[i];
            char *txt = derive_show(v, r);
            diag_error(D->diag, s->def->expr->span,
                       "vanishing denominator: with the solution %s = %s, a "
                       "denominator of '%s' is identically zero",
                       r->names[var], txt, s->name);
            diag_note(D->diag, st->span, "'%s' is solved here", r->names[var]);
            flint_free(txt);
            D->state[i] = -1;
        } else if (derive_reduce_value(D, d, D->info->defs[i]->def->expr) < 0) {
            D->state[i] = -1;
        }
    }
    for (int k = 0; k < D->info->nunknowns; k++) {
        if (!D->usolved[k])
            continue;
        int rc;
        rc = compose(D, D->info->unknowns[k]->is_point, D->usol[k], D->ssol + k,
                     var, v);
        /* (a failure leaves the solution as it is, valid but not in the
         * normal form: what uses it is reduced and reports) */
        if (rc == 0 && D->K && D->K->nrel)
            (void)(D->info->unknowns[k]->is_point
                       ? kernel_reduce_pteq(D->K, D->usol[k])
                       : kernel_reduce(D->K, D->ssol + k));
    }
}

/* replaces unknown column col by its solution x in every value derived so
 * far: the definitions and the unknowns solved earlier in terms of it */
static int has_any(const PointEq p, const slong *cols, slong n)
{
    for (slong j = 0; j < n; j++)
        if (pteq_has_point(p, cols[j]))
            return 1;
    return 0;
}

/* the unknown points syms[0..n-1], just solved (their columns cols),
 * replaced in every value derived so far, all in one pass */
static void substitute_solved(Deriver *D, const slong *cols, Sym *const *syms,
                              slong n)
{
    const Ring *r = D->r;
    PointEq *sol = pc_xmalloc(sizeof(PointEq) * (size_t)(n ? n : 1));
    for (slong j = 0; j < n; j++)
        sol[j][0] = D->usol[syms[j]->index][0]; /* borrowed, not modified */
    for (int i = 0; i < D->info->ndefs; i++) {
        Value *v = &D->defs[i];
        if (D->state[i] == 1 && v->is_point && has_any(v->p, cols, n)) {
            derive_assume_into(D, &D->dassume[i]); /* the solve's assumptions */
            pteq_subst_points(v->p, v->p, cols, (const PointEq *)sol, n, r);
            if (derive_reduce_value(D, v, D->info->defs[i]->def->expr) < 0)
                D->state[i] = -1;
        }
    }
    for (int k = 0; k < D->info->nunknowns; k++)
        if (D->usolved[k] && D->info->unknowns[k]->is_point &&
            has_any(D->usol[k], cols, n))
            pteq_subst_points(D->usol[k], D->usol[k], cols,
                              (const PointEq *)sol, n, r);
    pc_free(sol);
}

/* the names of the unknowns flagged in `which`, "'B', 'C'" (caller frees) */
static char *unknown_list(Sym **syms, const char *which, slong n)
{
    size_t len = 1;
    for (slong j = 0; j < n; j++)
        if (which[j])
            len += strlen(syms[j]->name) + 4;
    char *out = pc_xmalloc(len), *o = out;
    *o = '\0';
    for (slong j = 0; j < n; j++)
        if (which[j])
            o += sprintf(o, "%s'%s'", o == out ? "" : ", ", syms[j]->name);
    return out;
}

/* The largest total degree of p in the ring variables vars[0..nv-1]; when
 * it is at least `limit`, the first such monomial's text ("k^2", "k*m")
 * goes to buf.  For the linearity check of solve. */
static slong degree_in(const fmpz_mpoly_t p, const slong *vars, slong nv,
                       slong limit, char *buf, size_t cap, const Ring *r)
{
    slong best = 0;
    ulong *e = pc_xmalloc(sizeof(ulong) * (size_t)(r->nvars ? r->nvars : 1));
    if (cap)
        buf[0] = '\0';
    for (slong i = 0; i < p->length; i++) {
        slong d = 0;
        fmpz_mpoly_get_term_exp_ui(e, p, i, r->ctx);
        for (slong k = 0; k < nv; k++)
            d += (slong)e[vars[k]];
        if (d >= limit && best < limit) {
            size_t len = 0;
            for (slong k = 0; k < nv && cap; k++) {
                if (e[vars[k]] == 0)
                    continue;
                len += (size_t)snprintf(buf + len, cap - len, "%s%s",
                                        len ? "*" : "", r->names[vars[k]]);
                if (e[vars[k]] > 1 && len < cap)
                    len += (size_t)snprintf(buf + len, cap - len, "^%lu",
                                            (unsigned long)e[vars[k]]);
                if (len >= cap)
                    len = cap - 1;
            }
        }
        best = d > best ? d : best;
    }
    pc_free(e);
    return best;
}

/* the coefficient of vars[m] (m >= 0) or the part free of all vars (m < 0)
 * in p, which is linear in them */
static void linear_coeff(fmpz_mpoly_t c, const fmpz_mpoly_t p,
                         const slong *vars, slong nv, slong m, const Ring *r)
{
    ulong *ex = pc_xcalloc((size_t)(nv ? nv : 1), sizeof(ulong));
    if (m >= 0)
        ex[m] = 1;
    fmpz_mpoly_get_coeff_vars_ui(c, p, vars, ex, nv, r->ctx);
    pc_free(ex);
}

/* the note on a system that is singular only by the functions' identities
 * (over the polynomials, without them, it has one solution) */
static void note_by_identity(Deriver *D, const Stmt *st)
{
    diag_note(D->diag, st->span,
              "its determinant vanishes by the identities of its functions "
              "(sin^2 + cos^2 = 1, sqrt(x)^2 = x, ...), not as a polynomial");
}

/* `solve` with unknown scalars among the unknowns: each point equation
 * holds one scalar equation per known point (its weight on both sides
 * agrees), each scalar equation one; the unknowns are the weights x[j][b]
 * of every unknown point X_j on every known point b, and the scalars.  The
 * numerators must be linear in the unknowns (the coefficient of an unknown
 * point free of the unknown scalars, no product of two unknown scalars).
 * Solved by linsolve over the rational functions of everything else. */
/* the unknowns of a mixed solve: the points X_j (xsym: their index in
 * the `for` list, xcol: their columns) and the scalars (ksym, kvar: their
 * ring variables), and the known points the equations hold */
typedef struct Mixed {
    slong nx, nk, nknown, capk;
    slong *xcol, *kvar, *xsym, *ksym, *known;
} Mixed;

/* linearity, and the known columns (M->known): 1, or 0 reported */
static int mixed_check_linear(Deriver *D, Mixed *M, PointEq *peq, Equation **pe,
                              slong npe, RatFunStruct *seq, Equation **se,
                              slong nse, Sym **syms)
{
    const Ring *r = D->r;
    slong nx = M->nx, nk = M->nk, nknown = M->nknown, capk = M->capk;
    const slong *xcol = M->xcol, *kvar = M->kvar, *xsym = M->xsym;
    slong *known = M->known;
    char prod[128];
    int ok = 1;
    for (slong e = 0; e < npe && ok; e++)
        for (slong i = 0; i < peq[e]->len && ok; i++) {
            slong c = peq[e]->terms[i].point, x;
            const fmpz_mpoly_struct *num = peq[e]->terms[i].num;
            for (x = 0; x < nx && xcol[x] != c; x++)
                ;
            if (x < nx) {
                if (degree_in(num, kvar, nk, 1, prod, sizeof prod, r) > 0) {
                    diag_error(D->diag, pe[e]->span,
                               "the equation is not linear in the unknowns: "
                               "it holds the product %s*%s",
                               prod, syms[xsym[x]]->name);
                    ok = 0;
                }
                continue;
            }
            if (degree_in(num, kvar, nk, 2, prod, sizeof prod, r) > 1) {
                diag_error(D->diag, pe[e]->span,
                           "the equation is not linear in the unknowns: it "
                           "holds the product %s",
                           prod);
                ok = 0;
            }
            slong k;
            for (k = 0; k < nknown && known[k] != c; k++)
                ;
            if (k == nknown) {
                if (nknown == capk) {
                    capk = capk ? 2 * capk : 16;
                    known = pc_xrealloc(known, sizeof(slong) * (size_t)capk);
                }
                known[nknown++] = c;
            }
        }
    for (slong e = 0; e < nse && ok; e++)
        if (degree_in(seq[e].num, kvar, nk, 2, prod, sizeof prod, r) > 1) {
            diag_error(D->diag, se[e]->span,
                       "the equation is not linear in the unknowns: it holds "
                       "the product %s",
                       prod);
            ok = 0;
        }
    M->nknown = nknown;
    M->capk = capk;
    M->known = known;
    return ok;
}

/* the system A x = b: unknown x[j][b] is column j*nknown + b, scalar m
 * is column nx*nknown + m; a row per known point of each point equation,
 * one per scalar equation */
static void mixed_fill(const Mixed *M, RatFunStruct *A, RatFunStruct *b,
                       fmpz_mpoly_t c, PointEq *peq, slong npe,
                       RatFunStruct *seq, slong nse, slong ncol, const Ring *r)
{
    slong nx = M->nx, nk = M->nk, nknown = M->nknown;
    const slong *xcol = M->xcol, *kvar = M->kvar, *known = M->known;
    for (slong e = 0; e < npe; e++)
        for (slong i = 0; i < peq[e]->len; i++) {
            slong col = peq[e]->terms[i].point, xi, bi;
            const fmpz_mpoly_struct *num = peq[e]->terms[i].num;
            for (xi = 0; xi < nx && xcol[xi] != col; xi++)
                ;
            if (xi < nx) { /* u * x[xi][b] in every row b of e */
                for (bi = 0; bi < nknown; bi++)
                    fmpz_mpoly_set(
                        A[(e * nknown + bi) * ncol + xi * nknown + bi].num, num,
                        r->ctx);
                continue;
            }
            for (bi = 0; known[bi] != col; bi++)
                ;
            slong row = e * nknown + bi;
            linear_coeff(c, num, kvar, nk, -1, r);
            fmpz_mpoly_neg(b[row].num, c, r->ctx);
            for (slong m = 0; m < nk; m++) {
                linear_coeff(c, num, kvar, nk, m, r);
                fmpz_mpoly_set(A[row * ncol + nx * nknown + m].num, c, r->ctx);
            }
        }
    for (slong e = 0; e < nse; e++) {
        slong row = npe * nknown + e;
        linear_coeff(c, seq[e].num, kvar, nk, -1, r);
        fmpz_mpoly_neg(b[row].num, c, r->ctx);
        for (slong m = 0; m < nk; m++) {
            linear_coeff(c, seq[e].num, kvar, nk, m, r);
            fmpz_mpoly_set(A[row * ncol + nx * nknown + m].num, c, r->ctx);
        }
    }
}

/* solves A x = b, reports a singular or inconsistent system, and stores
 * and substitutes the solutions */
static void mixed_solve(Deriver *D, Stmt *st, const Mixed *M, RatFunStruct *A,
                        RatFunStruct *b, RatFunStruct *x, slong nrow,
                        slong ncol, Sym **syms, Name **names, slong nunk)
{
    const Ring *r = D->r;
    slong nx = M->nx, nk = M->nk, nknown = M->nknown;
    const slong *xcol = M->xcol, *kvar = M->kvar, *xsym = M->xsym,
                *ksym = M->ksym, *known = M->known;
    slong rank = 0;
    LinNormal nfs, *nf = derive_solve_normal_form(D, &nfs);
    LinSolveResult lr = linsolve_nf(x, &rank, A, b, nrow, ncol, nf, r);
    for (slong m = 0; lr != LINSOLVE_FAILED && nf && m < ncol; m++)
        if ((nf->err = kernel_reduce(D->K, x + m)))
            lr = LINSOLVE_FAILED;
    int by_identity = 0;
    if (nf && (lr == LINSOLVE_INCONSISTENT || lr == LINSOLVE_UNDERDETERMINED)) {
        /* only by the identities? (the plain system solves) */
        RatFunStruct *y = ratfun_vec_init(ncol, r);
        by_identity = linsolve(y, NULL, A, b, nrow, ncol, r) == LINSOLVE_UNIQUE;
        ratfun_vec_clear(y, ncol, r);
    }
    if (lr == LINSOLVE_FAILED) {
        derive_kernel_error_at(D, nf->err, st->span, st->span);
    } else if (lr == LINSOLVE_INCONSISTENT && rank < ncol) {
        diag_error(D->diag, st->span,
                   "singular system: the determinant of the unknowns' "
                   "coefficients vanishes (rank %ld of %ld scalar "
                   "unknowns), and the equations contradict each other",
                   (long)rank, (long)ncol);
    } else if (lr == LINSOLVE_INCONSISTENT) {
        diag_error(D->diag, st->span,
                   "inconsistent system: the equations contradict each "
                   "other");
    } else if (lr == LINSOLVE_UNDERDETERMINED) {
        diag_error(D->diag, names[0]->span,
                   "singular system: the equations leave the unknowns "
                   "undetermined (rank %ld of %ld scalar unknowns)",
                   (long)rank, (long)ncol);
    }
    if (by_identity)
        note_by_identity(D, st);
    if (lr == LINSOLVE_UNIQUE) {
        /* the scalars first: the points' weights do not hold them */
        for (slong m = 0; m < nk; m++) {
            Sym *u = syms[ksym[m]];
            ratfun_set(D->ssol + u->index, x + nx * nknown + m, r);
        }
        for (slong xi = 0; xi < nx; xi++) {
            Sym *u = syms[xsym[xi]];
            pteq_set_weights(D->usol[u->index], known, x + xi * nknown, nknown,
                             r);
        }
        for (slong j = 0; j < nunk; j++)
            derive_assume_into(D, &D->uassume[syms[j]->index]);
        for (slong m = 0; m < nk; m++) {
            Sym *u = syms[ksym[m]];
            D->usolved[u->index] = 1;
            derive_substitute_scalar(D, kvar[m], D->ssol + u->index, st);
        }
        Sym **xs = pc_xmalloc(sizeof(Sym *) * (size_t)(nx ? nx : 1));
        for (slong xi = 0; xi < nx; xi++) {
            xs[xi] = syms[xsym[xi]];
            D->usolved[xs[xi]->index] = 1;
        }
        substitute_solved(D, xcol, xs, nx);
        pc_free(xs);
    }
}

static void derive_solve_mixed(Deriver *D, Stmt *st, PointEq *peq,
                               Equation **pe, slong npe, RatFunStruct *seq,
                               Equation **se, slong nse, Sym **syms,
                               Name **names, slong nunk)
{
    const Ring *r = D->r;
    Mixed M = {0};
    M.xcol = pc_xmalloc(sizeof(slong) * (size_t)nunk);
    M.kvar = pc_xmalloc(sizeof(slong) * (size_t)nunk);
    M.xsym = pc_xmalloc(sizeof(slong) * (size_t)nunk);
    M.ksym = pc_xmalloc(sizeof(slong) * (size_t)nunk);
    M.known = NULL;
    int ok;
    for (slong j = 0; j < nunk; j++) {
        if (syms[j]->is_point) {
            M.xsym[M.nx] = j;
            M.xcol[M.nx++] = D->ucol0 + syms[j]->index;
        } else {
            M.ksym[M.nk] = j;
            M.kvar[M.nk++] = D->uvar[syms[j]->index];
        }
    }
    ok = mixed_check_linear(D, &M, peq, pe, npe, seq, se, nse, syms);
    /* the system: unknown x[j][b] is column j*nknown + b, scalar m is
     * column nx*nknown + m */
    slong ncol = M.nx * M.nknown + M.nk, nrow = npe * M.nknown + nse;
    RatFunStruct *A = NULL, *b = NULL, *x = NULL;
    fmpz_mpoly_t c;
    fmpz_mpoly_init(c, r->ctx);
    if (ok && (ncol > SOLVE_MAX_UNKNOWNS || nrow > 4 * SOLVE_MAX_UNKNOWNS)) {
        diag_error(D->diag, st->span,
                   "system too large to solve: %ld scalar unknowns in %ld "
                   "equations (at most %d unknowns)",
                   (long)ncol, (long)nrow, SOLVE_MAX_UNKNOWNS);
        ok = 0;
    }
    if (ok && ncol > 0) {
        A = ratfun_vec_init(nrow * ncol, r);
        b = ratfun_vec_init(nrow, r);
        x = ratfun_vec_init(ncol, r);
        mixed_fill(&M, A, b, c, peq, npe, seq, nse, ncol, r);
        mixed_solve(D, st, &M, A, b, x, nrow, ncol, syms, names, nunk);
        ratfun_vec_clear(A, nrow * ncol, r);
        ratfun_vec_clear(b, nrow, r);
        ratfun_vec_clear(x, ncol, r);
    }
    fmpz_mpoly_clear(c, r->ctx);
    pc_free(M.known);
    pc_free(M.ksym);
    pc_free(M.xsym);
    pc_free(M.kvar);
    pc_free(M.xcol);
}

/* a solve statement's system: neq equations (eqn), each a combination
 * that vanishes (eqs) or, scalar_eq[e], a scalar one (seqs); nunk unknowns
 * (syms, named by names, in columns cols) and their solutions x; what
 * solve.c found of a singular system (undetermined, dependent) */
typedef struct SolveSys {
    slong neq, nunk;
    PointEq *eqs;
    RatFunStruct *seqs;
    char *scalar_eq;
    Equation **eqn;
    PointEq *x;
    Sym **syms;
    slong *cols;
    Name **names;
    char *undetermined, *dependent;
} SolveSys;

/* equation q as a combination that vanishes (lhs - rhs) into eq, or, an
 * equation of scalars, into seq (*scalar_eq = 1); sl, sr scratch: 1, or 0
 * reported */
static int solve_equation(Deriver *D, const Equation *q, PointEq eq,
                          RatFunStruct *seq, char *scalar_eq, RatFun sl,
                          RatFun sr)
{
    const Ring *r = D->r;
    PointEq rhs;
    Value lv, rv;
    int ok = 1;
    pteq_init(rhs, r);
    derive_value_init(&lv, r);
    derive_value_init(&rv, r);
    if (derive_eval(D, &lv, q->lhs) < 0 || derive_eval(D, &rv, q->rhs) < 0) {
        ok = 0;
    } else if (!lv.is_point) { /* sema: a scalar unknown is solved */
        *scalar_eq = 1;
        ratfun_sub(seq, lv.s, rv.s, r);
    } else {
        pteq_swap(eq, lv.p, r);
        pteq_swap(rhs, rv.p, r);
        pteq_weight_sum(sl, eq, r);
        pteq_weight_sum(sr, rhs, r);
        int lk = ratfun_is_one(sl, r) ? 1 : ratfun_is_zero(sl, r) ? 0 : -1;
        int rk = ratfun_is_one(sr, r) ? 1 : ratfun_is_zero(sr, r) ? 0 : -1;
        const Node *bad = lk < 0 ? q->lhs : rk < 0 ? q->rhs : NULL;
        if (bad) {
            char *txt = derive_show(lk < 0 ? sl : sr, r);
            diag_error(D->diag, bad->span,
                       "weights of this side sum to %s, not 0 (a vector) "
                       "or 1 (a point)",
                       txt);
            flint_free(txt);
            ok = 0;
        } else if (lk != rk) {
            diag_error(D->diag, q->span,
                       "cannot equate a %s and a %s: the left side's "
                       "weights sum to %d, the right side's to %d",
                       lk ? "point" : "vector", rk ? "point" : "vector", lk,
                       rk);
            ok = 0;
        } else {
            pteq_sub(eq, eq, rhs, r);
        }
    }
    derive_value_clear(&rv, r);
    derive_value_clear(&lv, r);
    pteq_clear(rhs, r);
    return ok;
}

/* a solve with unknown scalars: its point and scalar equations apart
 * (borrowed), solved by derive_solve_mixed */
static void solve_split_mixed(Deriver *D, Stmt *st, const SolveSys *S)
{
    slong neq = S->neq, nunk = S->nunk, e;
    PointEq *eqs = S->eqs;
    RatFunStruct *seqs = S->seqs;
    const char *scalar_eq = S->scalar_eq;
    Equation **eqn = S->eqn;
    Sym **syms = S->syms;
    Name **names = S->names;
    PointEq *pe = pc_xmalloc(sizeof(PointEq) * (size_t)neq);
    Equation **pq = pc_xmalloc(sizeof(Equation *) * (size_t)neq);
    Equation **sq = pc_xmalloc(sizeof(Equation *) * (size_t)neq);
    RatFunStruct *se = pc_xmalloc(sizeof(RatFunStruct) * (size_t)neq);
    slong npe = 0, nse = 0;
    for (e = 0; e < neq; e++) {
        if (scalar_eq[e]) {
            se[nse] = seqs[e]; /* borrowed */
            sq[nse++] = eqn[e];
        } else {
            pe[npe][0] = eqs[e][0]; /* borrowed */
            pq[npe++] = eqn[e];
        }
    }
    derive_solve_mixed(D, st, pe, pq, npe, se, sq, nse, syms, names, nunk);
    pc_free(se);
    pc_free(sq);
    pc_free(pq);
    pc_free(pe);
}

/* the error of a solve of points that failed with ss */
static void report_solve(Deriver *D, Stmt *st, SolveStatus ss, int by_identity,
                         const SolveSys *S)
{
    slong neq = S->neq, nunk = S->nunk, e, j;
    Sym **syms = S->syms;
    Name **names = S->names;
    Equation **eqn = S->eqn;
    const char *undetermined = S->undetermined, *dependent = S->dependent;
    if (ss == SOLVE_SINGULAR) {
        char *list = unknown_list(syms, undetermined, nunk);
        for (j = 0; j < nunk && !undetermined[j]; j++)
            ;
        diag_error(D->diag, names[j < nunk ? j : 0]->span,
                   "singular system: the equations leave %s undetermined",
                   list);
        if (by_identity)
            note_by_identity(D, st);
        for (e = 0; e < neq; e++)
            if (dependent[e])
                diag_note(D->diag, eqn[e]->span,
                          "this equation follows from the others");
        pc_free(list);
    } else if (ss == SOLVE_INCONSISTENT) {
        for (e = 0; e < neq && !dependent[e]; e++)
            ;
        for (j = 0; j < nunk && !undetermined[j]; j++)
            ;
        if (j < nunk) /* the coefficients' determinant vanishes */
            diag_error(D->diag, eqn[e < neq ? e : 0]->span,
                       "singular system: the determinant of the unknowns' "
                       "coefficients vanishes, and this equation "
                       "contradicts the others");
        else
            diag_error(D->diag, eqn[e < neq ? e : 0]->span,
                       "inconsistent system: this equation contradicts "
                       "the others");
        if (by_identity)
            note_by_identity(D, st);
    } else if (ss == SOLVE_TOO_BIG && nunk > SOLVE_MAX_UNKNOWNS) {
        diag_error(D->diag, st->span,
                   "system too large to solve: %ld unknowns (at most %d)",
                   (long)nunk, SOLVE_MAX_UNKNOWNS);
    } else if (ss == SOLVE_TOO_BIG) {
        diag_error(D->diag, st->span,
                   "expression too large to compute exactly: an "
                   "intermediate product of this solve could need more "
                   "than %.0f MB of coefficients",
                   exp2(RATFUN_MAX_LOG2_BITS - 23));
    }
}

/* a solve of unknown points only: solve.c, in the kernels' normal form
 * where the equations hold functions with identities */
static void solve_points_stmt(Deriver *D, Stmt *st, const SolveSys *S)
{
    const Ring *r = D->r;
    slong neq = S->neq, nunk = S->nunk, e, j;
    PointEq *eqs = S->eqs, *x = S->x;
    Sym **syms = S->syms;
    const slong *cols = S->cols;
    char *undetermined = S->undetermined, *dependent = S->dependent;
    /* with functions that obey identities, the system is solved in
     * their normal form (pivots, rank, consistency modulo them) */
    LinNormal nfs, *nf = derive_solve_normal_form(D, &nfs);
    int by_identity = 0;
    for (e = 0; nf && e < neq; e++)
        if (kernel_uses_pteq(D->K, eqs[e], 0))
            break;
    if (nf && e == neq)
        nf = NULL;
    SolveStatus ss =
        nunk > SOLVE_MAX_UNKNOWNS
            ? SOLVE_TOO_BIG
            : solve_points_nf(x, (const PointEq *)eqs, neq, cols, nunk,
                              undetermined, dependent, D->deadline, nf, r);
    for (j = 0; ss == SOLVE_OK && nf && j < nunk; j++)
        if ((nf->err = kernel_reduce_pteq(D->K, x[j])))
            ss = SOLVE_FAILED;
    if (nf && (ss == SOLVE_SINGULAR || ss == SOLVE_INCONSISTENT)) {
        /* singular or inconsistent only by the identities? (the
         * system over the polynomials, the identities unknown to it) */
        PointEq *y = pc_xmalloc(sizeof(PointEq) * (size_t)nunk);
        for (j = 0; j < nunk; j++)
            pteq_init(y[j], r);
        by_identity = solve_points_ex(y, (const PointEq *)eqs, neq, cols, nunk,
                                      NULL, NULL, D->deadline, r) == SOLVE_OK;
        for (j = 0; j < nunk; j++)
            pteq_clear(y[j], r);
        pc_free(y);
    }
    if (ss == SOLVE_FAILED)
        derive_kernel_error_at(D, nf->err, st->span, st->span);
    if (ss == SOLVE_TIME)
        derive_out_of_time_at(D, st->span);
    if (ss == SOLVE_OK) {
        for (j = 0; j < nunk; j++) {
            pteq_swap(D->usol[syms[j]->index], x[j], r);
            D->usolved[syms[j]->index] = 1;
            derive_assume_into(D, &D->uassume[syms[j]->index]);
        }
        substitute_solved(D, cols, syms, nunk);
    } else {
        report_solve(D, st, ss, by_identity, S);
    }
}

/* `solve EQ, ... for X, ...`: the equations as combinations that vanish,
 * solved for the unknown columns (solve.c); the solutions replace the
 * unknowns in everything derived so far and in every later use */
void derive_solve(Deriver *D, Stmt *st)
{
    const Ring *r = D->r;
    slong neq = 0, nunk = 0;
    if (st->bad || D->expired)
        return;
    budget_statement(D->src, st->span);
    derive_assume_clear(D);
    for (Equation *e = st->eqs; e; e = e->next)
        neq++;
    for (Name *nm = st->names; nm; nm = nm->next)
        nunk++;
    PointEq *eqs = pc_xmalloc(sizeof(PointEq) * (size_t)neq);
    PointEq *x = pc_xmalloc(sizeof(PointEq) * (size_t)nunk);
    Sym **syms = pc_xmalloc(sizeof(Sym *) * (size_t)nunk);
    slong *cols = pc_xmalloc(sizeof(slong) * (size_t)nunk);
    char *undetermined = pc_xcalloc((size_t)nunk, 1);
    char *dependent = pc_xcalloc((size_t)neq, 1);
    Equation **eqn = pc_xmalloc(sizeof(Equation *) * (size_t)neq);
    Name **names = pc_xmalloc(sizeof(Name *) * (size_t)nunk);
    RatFun sl, sr;
    int ok = 1;
    double t0 = D->verbose ? derive_now_seconds() : 0;

    ratfun_init(sl, r);
    ratfun_init(sr, r);
    slong j = 0;
    for (Name *nm = st->names; nm; nm = nm->next, j++) {
        names[j] = nm;
        pteq_init(x[j], r);
        /* sema checked: an unknown, solved here only */
        syms[j] = NULL;
        for (int k = 0; k < D->info->nunknowns && !syms[j]; k++)
            if (strcmp(D->info->unknowns[k]->name, nm->text) == 0)
                syms[j] = D->info->unknowns[k];
        cols[j] = D->ucol0 + syms[j]->index;
    }
    slong nsc = 0;
    for (j = 0; j < nunk; j++)
        nsc += !syms[j]->is_point;
    RatFunStruct *seqs = ratfun_vec_init(neq, r);
    char *scalar_eq = pc_xcalloc((size_t)neq, 1);
    SolveSys S = {.neq = neq,
                  .nunk = nunk,
                  .eqs = eqs,
                  .seqs = seqs,
                  .scalar_eq = scalar_eq,
                  .eqn = eqn,
                  .x = x,
                  .syms = syms,
                  .cols = cols,
                  .names = names,
                  .undetermined = undetermined,
                  .dependent = dependent};
    slong e = 0;
    for (Equation *q = st->eqs; q; q = q->next, e++) {
        eqn[e] = q;
        pteq_init(eqs[e], r);
        ok &= solve_equation(D, q, eqs[e], seqs + e, scalar_eq + e, sl, sr);
    }
    if (ok && st->start)
        derive_solve_numeric(D, st, eqs, seqs, scalar_eq, eqn, neq, syms, nunk);
    else if (ok && nsc > 0)
        solve_split_mixed(D, st, &S);
    else if (ok)
        solve_points_stmt(D, st, &S);
    if (D->verbose) {
        int line, col;
        source_locate(D->src, st->span.start, &line, &col);
        pc_fprintf(D->verbose, "%s:%d: solve for %ld unknown%s: %.3f ms\n",
                   D->src->name, line, (long)nunk, nunk == 1 ? "" : "s",
                   1e3 * (derive_now_seconds() - t0));
        fflush(D->verbose);
    }
    ratfun_clear(sr, r);
    ratfun_clear(sl, r);
    for (e = 0; e < neq; e++)
        pteq_clear(eqs[e], r);
    ratfun_vec_clear(seqs, neq, r);
    pc_free(scalar_eq);
    for (j = 0; j < nunk; j++)
        pteq_clear(x[j], r);
    pc_free(names);
    pc_free(eqn);
    pc_free(dependent);
    pc_free(undetermined);
    pc_free(cols);
    pc_free(syms);
    pc_free(x);
    pc_free(eqs);
}
