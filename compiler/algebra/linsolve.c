/*
 * linsolve.c - Gaussian elimination over the field of rational functions.
 *
 * The augmented matrix [a | b] is copied and brought to row echelon form
 * with full pivoting: at every step the pivot is the structurally simplest
 * (fewest terms, ratfun_length) entry among the remaining rows and unused
 * columns.  Over Q(x1..xk) every non-zero entry is a valid pivot, so the
 * choice is free, and the simplest one keeps the intermediate expressions
 * small: dividing a row by a constant or by a monomial costs next to
 * nothing, while dividing by a long polynomial spreads it over the row.
 * Pivot rows are normalised to a leading 1, so back substitution needs no
 * divisions.  Rows are swapped through an array of row pointers; entries are
 * never struct-copied.
 */
#include "compiler/algebra/linsolve.h"

/* x in the normal form; 0, or -1 with nf->err set */
static int normal(LinNormal *nf, RatFunStruct *x)
{
    if (!nf || nf->err)
        return nf ? -1 : 0;
    nf->err = nf->reduce(nf->ctx, x);
    return nf->err ? -1 : 0;
}

slong linsolve_pivot(RatFunStruct *const *row, slong from, slong m, slong n,
                     const char *used, slong *col, const Ring *r)
{
    slong bi = -1, blen = 0;
    for (slong i = from; i < m; i++)
        for (slong j = 0; j < n; j++) {
            slong len;
            if (used[j] || ratfun_is_zero(row[i] + j, r))
                continue;
            len = ratfun_length(row[i] + j, r);
            if (bi < 0 || len < blen) {
                bi = i;
                *col = j;
                blen = len;
            }
        }
    return bi;
}

LinSolveResult linsolve(RatFunStruct *x, slong *rank, const RatFunStruct *a,
                        const RatFunStruct *b, slong m, slong n, const Ring *r)
{
    return linsolve_nf(x, rank, a, b, m, n, NULL, r);
}

LinSolveResult linsolve_nf(RatFunStruct *x, slong *rank, const RatFunStruct *a,
                           const RatFunStruct *b, slong m, slong n,
                           LinNormal *nf, const Ring *r)
{
    LinSolveResult res = LINSOLVE_UNIQUE;
    slong w = n + 1; /* row width: n coefficients and the right-hand side */
    slong rk = 0;
    RatFunStruct *mat = ratfun_vec_init(m * w, r);
    RatFunStruct **row =
        flint_malloc((size_t)FLINT_MAX(m, 1) * sizeof(RatFunStruct *));
    RatFunStruct *sol = ratfun_vec_init(w, r);
    slong *pivcol = flint_malloc((size_t)FLINT_MAX(m, 1) * sizeof(slong));
    char *used = flint_calloc((size_t)w, 1);
    RatFun piv, t;

    ratfun_init(piv, r);
    ratfun_init(t, r);
    for (slong i = 0; i < m; i++) {
        row[i] = mat + i * w;
        for (slong j = 0; j < n; j++)
            ratfun_set(row[i] + j, a + i * n + j, r);
        ratfun_set(row[i] + n, b + i, r);
        for (slong c = 0; c < w; c++)
            if (normal(nf, row[i] + c) < 0)
                goto failed;
    }

    while (rk < m) {
        slong bj, bi = linsolve_pivot(row, rk, m, n, used, &bj, r);
        if (bi < 0)
            break;
        if (bi != rk) {
            RatFunStruct *tr = row[bi];
            row[bi] = row[rk];
            row[rk] = tr;
        }
        pivcol[rk] = bj;
        used[bj] = 1;

        /* normalise the pivot row: row /= pivot (the pivot itself -> 1) */
        ratfun_set(piv, row[rk] + bj, r);
        if (!ratfun_is_one(piv, r)) {
            for (slong c = 0; c < w; c++)
                if (c != bj && !ratfun_is_zero(row[rk] + c, r)) {
                    ratfun_div(row[rk] + c, row[rk] + c, piv, r); /* piv != 0 */
                    if (normal(nf, row[rk] + c) < 0)
                        goto failed;
                }
            ratfun_one(row[rk] + bj, r);
        }

        /* eliminate below: row_i -= row_i[bj] * row_rk */
        for (slong i = rk + 1; i < m; i++) {
            RatFunStruct *f = row[i] + bj;
            if (ratfun_is_zero(f, r))
                continue;
            for (slong c = 0; c < w; c++) {
                if (c == bj || ratfun_is_zero(row[rk] + c, r))
                    continue;
                ratfun_mul(t, f, row[rk] + c, r);
                ratfun_sub(row[i] + c, row[i] + c, t, r);
                if (normal(nf, row[i] + c) < 0)
                    goto failed;
            }
            ratfun_zero(f, r);
        }
        rk++;
    }

    /* rows rk.. have zero coefficients: consistent iff their rhs vanish */
    for (slong i = rk; i < m; i++)
        if (!ratfun_is_zero(row[i] + n, r)) {
            res = LINSOLVE_INCONSISTENT;
            goto cleanup;
        }

    /* back substitution; free unknowns stay 0 in sol */
    for (slong k = rk - 1; k >= 0; k--) {
        slong pc = pivcol[k];
        ratfun_set(sol + pc, row[k] + n, r);
        for (slong l = k + 1; l < rk; l++) {
            slong qc = pivcol[l];
            if (ratfun_is_zero(row[k] + qc, r) || ratfun_is_zero(sol + qc, r))
                continue;
            ratfun_mul(t, row[k] + qc, sol + qc, r);
            ratfun_sub(sol + pc, sol + pc, t, r);
            if (normal(nf, sol + pc) < 0)
                goto failed;
        }
    }
    for (slong j = 0; j < n; j++)
        ratfun_swap(x + j, sol + j, r);
    res = rk == n ? LINSOLVE_UNIQUE : LINSOLVE_UNDERDETERMINED;
    goto cleanup;

failed:
    res = LINSOLVE_FAILED;
cleanup:
    if (rank != NULL)
        *rank = rk;
    ratfun_vec_clear(sol, w, r);
    ratfun_vec_clear(mat, m * w, r);
    ratfun_clear(t, r);
    ratfun_clear(piv, r);
    flint_free(used);
    flint_free(pivcol);
    flint_free(row);
    return res;
}
