/*
 * solve.c - linear systems of point equations (see solve.h).
 */
#include "compiler/algebra/solve.h"

#include <string.h>
#include <time.h>

#include <flint/fmpz_mat.h>

#include "base/check.h"
#include "base/mem.h"

/* The system as a matrix of numerators: row e, column c < nunk the unknown
 * cols[c], column nunk + k the known column known[k]. */
typedef struct System {
    slong neq, nunk, nknown, width;
    slong *known;            // sorted point indices of the known columns
    fmpz_mpoly_struct *a;    // neq * width entries
    fmpz_mpoly_struct **row; // row pointers (rows are swapped, not copied)
    slong *orig;             // orig[i]: the equation now in row i
    char *nonzero;           // after elimination: row i's known part
                             // is not zero (classify)
} System;

static slong find_col(const slong *cols, slong n, slong point)
{
    for (slong j = 0; j < n; j++)
        if (cols[j] == point)
            return j;
    return -1;
}

static void system_init(System *S, const PointEq *eqs, slong neq,
                        const slong *cols, slong nunk, const Ring *r)
{
    slong cap = 0;
    S->neq = neq;
    S->nunk = nunk;
    S->nknown = 0;
    S->known = NULL;
    /* the known columns: every point of an equation that is not unknown,
     * sorted (insertion into a sorted array; schemes have few points) */
    for (slong e = 0; e < neq; e++)
        for (slong i = 0; i < eqs[e]->len; i++) {
            slong p = eqs[e]->terms[i].point, k;
            if (find_col(cols, nunk, p) >= 0)
                continue;
            for (k = 0; k < S->nknown && S->known[k] < p; k++)
                ;
            if (k < S->nknown && S->known[k] == p)
                continue;
            if (S->nknown == cap) {
                cap = cap ? 2 * cap : 16;
                S->known = pc_xrealloc(S->known, sizeof(slong) * (size_t)cap);
            }
            for (slong m = S->nknown; m > k; m--)
                S->known[m] = S->known[m - 1];
            S->known[k] = p;
            S->nknown++;
        }
    S->width = nunk + S->nknown;
    S->a = pc_xmalloc(sizeof(fmpz_mpoly_struct) *
                      (size_t)FLINT_MAX(neq * S->width, 1));
    S->row =
        pc_xmalloc(sizeof(fmpz_mpoly_struct *) * (size_t)FLINT_MAX(neq, 1));
    S->orig = pc_xmalloc(sizeof(slong) * (size_t)FLINT_MAX(neq, 1));
    S->nonzero = pc_xcalloc((size_t)FLINT_MAX(neq, 1), 1);
    for (slong e = 0; e < neq; e++) {
        S->row[e] = S->a + e * S->width;
        S->orig[e] = e;
        for (slong c = 0; c < S->width; c++)
            fmpz_mpoly_init(S->row[e] + c, r->ctx);
        for (slong i = 0; i < eqs[e]->len; i++) {
            slong p = eqs[e]->terms[i].point;
            slong c = find_col(cols, nunk, p);
            if (c < 0) /* a known column: it is in S->known */
                for (c = nunk; S->known[c - nunk] != p; c++)
                    ;
            fmpz_mpoly_set(S->row[e] + c, eqs[e]->terms[i].num, r->ctx);
        }
    }
}

static void system_clear(System *S, const Ring *r)
{
    for (slong i = 0; i < S->neq * S->width; i++)
        fmpz_mpoly_clear(S->a + i, r->ctx);
    pc_free(S->a);
    pc_free(S->row);
    pc_free(S->orig);
    pc_free(S->nonzero);
    pc_free(S->known);
}

/* x = -(sum_k num[k] * known[k]) / den, canonical; num[k] may be swapped out */
static void set_solution(PointEq x, const System *S, fmpz_mpoly_struct *num,
                         const fmpz_mpoly_t den, const Ring *r)
{
    pteq_zero(x, r);
    for (slong k = 0; k < S->nknown; k++)
        if (!fmpz_mpoly_is_zero(num + k, r->ctx))
            fmpz_mpoly_neg(pteq_append(x, S->known[k], r), num + k, r->ctx);
    fmpz_mpoly_set(x->den, den, r->ctx);
    pteq_canonicalise(x, r);
}

/* The numeric path: every coefficient of an unknown is a number.  Returns 0
 * when it solved the system, -1 when U is singular (the general path then
 * finds out what is wrong). */
static int solve_numeric(PointEq *x, const System *S, const Ring *r)
{
    slong n = S->nunk;
    fmpz_mat_t U, I, Y;
    fmpz_t det;
    int ok;

    fmpz_mat_init(U, n, n);
    fmpz_mat_init(I, n, n);
    fmpz_mat_init(Y, n, n);
    fmpz_init(det);
    for (slong e = 0; e < n; e++) {
        for (slong j = 0; j < n; j++)
            if (!fmpz_mpoly_is_zero(S->row[e] + j, r->ctx))
                fmpz_mpoly_get_fmpz(fmpz_mat_entry(U, e, j), S->row[e] + j,
                                    r->ctx);
        fmpz_one(fmpz_mat_entry(I, e, e));
    }
    /* U * Y = det * I, i.e. U^-1 = Y / det */
    ok = fmpz_mat_solve(Y, det, U, I);
    if (ok) {
        fmpz_mpoly_t den, t;
        fmpz_mpoly_struct *num = pc_xmalloc(sizeof(fmpz_mpoly_struct) *
                                            (size_t)FLINT_MAX(S->nknown, 1));
        fmpz_mpoly_init(den, r->ctx);
        fmpz_mpoly_init(t, r->ctx);
        fmpz_mpoly_set_fmpz(den, det, r->ctx);
        for (slong k = 0; k < S->nknown; k++)
            fmpz_mpoly_init(num + k, r->ctx);
        for (slong j = 0; j < n; j++) {
            /* num[k] = sum_e Y[j][e] * R[e][k] */
            for (slong k = 0; k < S->nknown; k++) {
                fmpz_mpoly_zero(num + k, r->ctx);
                for (slong e = 0; e < n; e++) {
                    const fmpz *y = fmpz_mat_entry(Y, j, e);
                    const fmpz_mpoly_struct *re = S->row[e] + n + k;
                    if (fmpz_is_zero(y) || fmpz_mpoly_is_zero(re, r->ctx))
                        continue;
                    fmpz_mpoly_scalar_mul_fmpz(t, re, y, r->ctx);
                    fmpz_mpoly_add(num + k, num + k, t, r->ctx);
                }
            }
            set_solution(x[j], S, num, den, r);
        }
        for (slong k = 0; k < S->nknown; k++)
            fmpz_mpoly_clear(num + k, r->ctx);
        pc_free(num);
        fmpz_mpoly_clear(t, r->ctx);
        fmpz_mpoly_clear(den, r->ctx);
    }
    fmpz_clear(det);
    fmpz_mat_clear(Y);
    fmpz_mat_clear(I);
    fmpz_mat_clear(U);
    return ok ? 0 : -1;
}

/* 1 when a*b - c*d could pass the size limit */
static int product_too_big(const fmpz_mpoly_t a, const fmpz_mpoly_t b,
                           const fmpz_mpoly_t c, const fmpz_mpoly_t d,
                           const Ring *r)
{
    return ratfun_poly_log2_bits_mul(a, b, r) > RATFUN_MAX_LOG2_BITS ||
           ratfun_poly_log2_bits_mul(c, d, r) > RATFUN_MAX_LOG2_BITS;
}

/* Fraction-free Gauss-Jordan (Bareiss): after the step with pivot p (and
 * the previous pivot q), every row i other than the pivot row becomes
 * (p * row_i - row_i[j] * pivot_row) / q, an exact division. */
static int past(double deadline)
{
    struct timespec ts;
    if (deadline == 0)
        return 0;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec > deadline;
}

/* After an elimination of rank `rank` (used[j]: unknown j has a pivot;
 * S->nonzero[i] for rows rank..: row i, which has no unknown left, says 0 =
 * a non-zero known part): SOLVE_OK, SOLVE_SINGULAR (an unknown without a
 * pivot) or SOLVE_INCONSISTENT (a row 0 = non-zero), with the unknowns left
 * undetermined and the equations that follow from (or contradict) the
 * others marked by their original index. */
static SolveStatus classify(const System *S, slong rank, const char *used,
                            char *undetermined, char *dependent)
{
    slong n = S->nunk;
    SolveStatus st = rank < n ? SOLVE_SINGULAR : SOLVE_OK;
    if (undetermined)
        memset(undetermined, 0, (size_t)n);
    if (dependent)
        memset(dependent, 0, (size_t)S->neq);
    if (rank >= S->neq && rank >= n)
        return st;
    for (slong i = rank; i < S->neq; i++) {
        if (S->nonzero[i] && st != SOLVE_INCONSISTENT) {
            st = SOLVE_INCONSISTENT;
            if (dependent)
                memset(dependent, 0, (size_t)S->neq);
        }
        if (dependent && (S->nonzero[i] || st != SOLVE_INCONSISTENT))
            dependent[S->orig[i]] = 1;
    }
    if (undetermined)
        for (slong j = 0; j < n; j++)
            undetermined[j] = !used[j];
    return st;
}

static SolveStatus solve_general(PointEq *x, System *S, char *undetermined,
                                 char *dependent, double deadline,
                                 const Ring *r)
{
    slong n = S->nunk, w = S->width, rank = 0;
    slong *pivcol = pc_xmalloc(sizeof(slong) * (size_t)FLINT_MAX(S->neq, 1));
    char *used = pc_xcalloc((size_t)FLINT_MAX(n, 1), 1);
    fmpz_mpoly_t prev, p, t, u;
    SolveStatus st = SOLVE_OK;

    fmpz_mpoly_init(prev, r->ctx);
    fmpz_mpoly_init(p, r->ctx);
    fmpz_mpoly_init(t, r->ctx);
    fmpz_mpoly_init(u, r->ctx);
    fmpz_mpoly_one(prev, r->ctx);
    while (rank < S->neq) {
        slong bi = -1, bj = -1, blen = 0;
        for (slong i = rank; i < S->neq; i++)
            for (slong j = 0; j < n; j++) {
                slong len = S->row[i][j].length;
                if (used[j] || len == 0)
                    continue;
                if (bi < 0 || len < blen) {
                    bi = i;
                    bj = j;
                    blen = len;
                }
            }
        if (bi < 0)
            break;
        if (bi != rank) {
            fmpz_mpoly_struct *tr = S->row[bi];
            slong to = S->orig[bi];
            S->row[bi] = S->row[rank];
            S->orig[bi] = S->orig[rank];
            S->row[rank] = tr;
            S->orig[rank] = to;
        }
        used[bj] = 1;
        pivcol[rank] = bj;
        fmpz_mpoly_set(p, S->row[rank] + bj, r->ctx);
        for (slong i = 0; i < S->neq && st == SOLVE_OK; i++) {
            fmpz_mpoly_struct *ri = S->row[i], *rp = S->row[rank];
            if (i == rank)
                continue;
            if (past(deadline)) {
                st = SOLVE_TIME;
                break;
            }
            for (slong c = 0; c < w; c++) {
                if (c == bj)
                    continue;
                if (product_too_big(p, ri + c, ri + bj, rp + c, r)) {
                    st = SOLVE_TOO_BIG;
                    break;
                }
                fmpz_mpoly_mul(t, p, ri + c, r->ctx);
                fmpz_mpoly_mul(u, ri + bj, rp + c, r->ctx);
                fmpz_mpoly_sub(t, t, u, r->ctx);
                if (!fmpz_mpoly_is_one(prev, r->ctx) &&
                    !fmpz_mpoly_divides(t, t, prev, r->ctx)) /* exact */
                    PC_UNREACHABLE("a Bareiss step's division is not exact");
                fmpz_mpoly_swap(ri + c, t, r->ctx);
            }
            fmpz_mpoly_zero(ri + bj, r->ctx);
        }
        if (st != SOLVE_OK)
            goto done;
        fmpz_mpoly_swap(prev, p, r->ctx);
        rank++;
    }

    for (slong i = rank; i < S->neq; i++) {
        S->nonzero[i] = 0;
        for (slong c = n; c < w; c++)
            if (!fmpz_mpoly_is_zero(S->row[i] + c, r->ctx))
                S->nonzero[i] = 1;
    }
    st = classify(S, rank, used, undetermined, dependent);
    if (st != SOLVE_OK)
        goto done;
    /* row i: prev * X_pivcol[i] + sum_k R[i][k] K_k = 0 */
    for (slong i = 0; i < rank; i++)
        set_solution(x[pivcol[i]], S, S->row[i] + n, prev, r);
done:
    fmpz_mpoly_clear(u, r->ctx);
    fmpz_mpoly_clear(t, r->ctx);
    fmpz_mpoly_clear(p, r->ctx);
    fmpz_mpoly_clear(prev, r->ctx);
    pc_free(used);
    pc_free(pivcol);
    return st;
}

/* Gauss-Jordan over the rational functions with every entry in the normal
 * form nf (the kernels' identities): a pivot is non-zero, a row is
 * consistent and an unknown is determined exactly when the identities say
 * so, which the fraction-free path over the polynomial ring cannot see
 * (1 - cos(t)^2 - sin(t)^2 is a non-zero polynomial).  Each pivot row is
 * normalised to 1, so row i ends as X_pivcol[i] + sum_k R[i][k] K_k = 0. */
static SolveStatus solve_normal(PointEq *x, System *S, char *undetermined,
                                char *dependent, double deadline, LinNormal *nf,
                                const Ring *r)
{
    slong n = S->nunk, w = S->width, rank = 0, m = S->neq;
    slong *pivcol = pc_xmalloc(sizeof(slong) * (size_t)FLINT_MAX(m, 1));
    char *used = pc_xcalloc((size_t)FLINT_MAX(n, 1), 1);
    RatFunStruct *a = ratfun_vec_init(FLINT_MAX(m * w, 1), r);
    RatFunStruct **row =
        pc_xmalloc(sizeof(RatFunStruct *) * (size_t)FLINT_MAX(m, 1));
    SolveStatus st = SOLVE_OK;
    RatFun piv, t;

    ratfun_init(piv, r);
    ratfun_init(t, r);
    for (slong i = 0; i < m; i++) {
        row[i] = a + i * w;
        for (slong c = 0; c < w && st == SOLVE_OK; c++) {
            fmpz_mpoly_set(row[i][c].num, S->row[i] + c, r->ctx);
            if ((nf->err = nf->reduce(nf->ctx, row[i] + c)))
                st = SOLVE_FAILED;
        }
    }
    while (st == SOLVE_OK && rank < m) {
        slong bj, bi = linsolve_pivot(row, rank, m, n, used, &bj, r);
        if (bi < 0)
            break;
        if (bi != rank) {
            RatFunStruct *tr = row[bi];
            slong to = S->orig[bi];
            row[bi] = row[rank];
            S->orig[bi] = S->orig[rank];
            row[rank] = tr;
            S->orig[rank] = to;
        }
        used[bj] = 1;
        pivcol[rank] = bj;
        ratfun_swap(piv, row[rank] + bj, r);
        ratfun_one(row[rank] + bj, r);
        for (slong c = 0; c < w && st == SOLVE_OK; c++)
            if (c != bj && !ratfun_is_zero(row[rank] + c, r)) {
                ratfun_div(row[rank] + c, row[rank] + c, piv, r);
                if ((nf->err = nf->reduce(nf->ctx, row[rank] + c)))
                    st = SOLVE_FAILED;
            }
        for (slong i = 0; i < m && st == SOLVE_OK; i++) {
            RatFunStruct *f = row[i] + bj;
            if (i == rank || ratfun_is_zero(f, r))
                continue;
            if (past(deadline)) {
                st = SOLVE_TIME;
                break;
            }
            for (slong c = 0; c < w && st == SOLVE_OK; c++) {
                if (c == bj || ratfun_is_zero(row[rank] + c, r))
                    continue;
                ratfun_mul(t, f, row[rank] + c, r);
                ratfun_sub(row[i] + c, row[i] + c, t, r);
                if ((nf->err = nf->reduce(nf->ctx, row[i] + c)))
                    st = SOLVE_FAILED;
            }
            ratfun_zero(f, r);
        }
        rank++;
    }
    if (st != SOLVE_OK)
        goto done;
    for (slong i = rank; i < m; i++) {
        S->nonzero[i] = 0;
        for (slong c = n; c < w; c++)
            if (!ratfun_is_zero(row[i] + c, r))
                S->nonzero[i] = 1;
    }
    st = classify(S, rank, used, undetermined, dependent);
    if (st != SOLVE_OK)
        goto done;
    for (slong i = 0; i < rank; i++) {
        RatFunStruct *wts = row[i] + n;
        for (slong k = 0; k < S->nknown; k++)
            ratfun_neg(wts + k, wts + k, r);
        pteq_set_weights(x[pivcol[i]], S->known, wts, S->nknown, r);
    }
done:
    ratfun_clear(t, r);
    ratfun_clear(piv, r);
    ratfun_vec_clear(a, FLINT_MAX(m * w, 1), r);
    pc_free(row);
    pc_free(used);
    pc_free(pivcol);
    return st;
}

SolveStatus solve_points(PointEq *x, const PointEq *eqs, slong neq,
                         const slong *cols, slong nunk, char *undetermined,
                         char *dependent, const Ring *r)
{
    return solve_points_ex(x, eqs, neq, cols, nunk, undetermined, dependent, 0,
                           r);
}

SolveStatus solve_points_ex(PointEq *x, const PointEq *eqs, slong neq,
                            const slong *cols, slong nunk, char *undetermined,
                            char *dependent, double deadline, const Ring *r)
{
    return solve_points_nf(x, eqs, neq, cols, nunk, undetermined, dependent,
                           deadline, NULL, r);
}

SolveStatus solve_points_nf(PointEq *x, const PointEq *eqs, slong neq,
                            const slong *cols, slong nunk, char *undetermined,
                            char *dependent, double deadline, LinNormal *nf,
                            const Ring *r)
{
    System S;
    SolveStatus st;
    int numeric = neq == nunk;

    system_init(&S, eqs, neq, cols, nunk, r);
    for (slong e = 0; e < neq && numeric; e++)
        for (slong j = 0; j < nunk && numeric; j++)
            numeric = fmpz_mpoly_is_fmpz(S.row[e] + j, r->ctx);
    if (nf) {
        st = solve_normal(x, &S, undetermined, dependent, deadline, nf, r);
    } else if (numeric && nunk > 0 && solve_numeric(x, &S, r) == 0) {
        st = SOLVE_OK;
        if (undetermined)
            memset(undetermined, 0, (size_t)nunk);
        if (dependent)
            memset(dependent, 0, (size_t)neq);
    } else {
        st = solve_general(x, &S, undetermined, dependent, deadline, r);
    }
    system_clear(&S, r);
    return st;
}
