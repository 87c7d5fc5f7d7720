#include "compiler/construct.h"

#include <stdlib.h>

#include "compiler/linsolve.h"

void construct_along(PointEq res, const PointEq p, const PointEq q,
                     const RatFun s, const Ring *r)
{
    PointEq d;
    pteq_init(d, r);
    pteq_sub(d, q, p, r);
    pteq_addmul(res, p, d, s, r);
    pteq_clear(d, r);
}

int construct_divide(PointEq res, const PointEq p, const PointEq q,
                     const RatFun k, const Ring *r)
{
    RatFun den;
    PointEq num;
    int st;
    ratfun_init(den, r);
    pteq_init(num, r);
    ratfun_one(den, r);
    ratfun_add(den, den, k, r);
    pteq_addmul(num, p, q, k, r);
    st = pteq_scalar_div(res, num, den, r);
    pteq_clear(num, r);
    ratfun_clear(den, r);
    return st;
}

void construct_bezier(PointEq res, const RatFun s, const PointEq *pts,
                      slong npts, const Ring *r)
{
    slong n = npts - 1;
    RatFun sb, w, pw;
    PointEq acc;
    ratfun_init(sb, r);
    ratfun_init(w, r);
    ratfun_init(pw, r);
    pteq_init(acc, r);
    ratfun_one(sb, r);
    ratfun_sub(sb, sb, s, r); /* 1 - s */
    fmpz_t c;
    fmpz_init(c);
    for (slong i = 0; i <= n; i++) {
        fmpz_bin_uiui(c, (ulong)n, (ulong)i);
        fmpq_t cq;
        fmpq_init(cq);
        fmpz_set(fmpq_numref(cq), c);
        fmpz_one(fmpq_denref(cq));
        ratfun_set_fmpq(w, cq, r);
        fmpq_clear(cq);
        ratfun_pow_si(pw, s, i, r);
        ratfun_mul(w, w, pw, r);
        ratfun_pow_si(pw, sb, n - i, r);
        ratfun_mul(w, w, pw, r);
        pteq_addmul(acc, acc, pts[i], w, r);
    }
    fmpz_clear(c);
    pteq_swap(res, acc, r);
    pteq_clear(acc, r);
    ratfun_clear(pw, r);
    ratfun_clear(w, r);
    ratfun_clear(sb, r);
}

/* Splits a flat's defining points into its origin (the first proper point)
 * and directions (the others minus the origin, or the improper points
 * themselves).  dirs must hold n - 1 initialised PointEqs.  Returns 0, or -1
 * when the flat has no proper point. */
static int flat_split(PointEq origin, PointEq *dirs, const PointEq *pts,
                      slong n, const Ring *r)
{
    RatFun sum;
    ratfun_init(sum, r);
    slong o = -1;
    for (slong i = 0; i < n && o < 0; i++) {
        pteq_weight_sum(sum, pts[i], r);
        if (!ratfun_is_zero(sum, r))
            o = i;
    }
    if (o < 0) {
        ratfun_clear(sum, r);
        return -1;
    }
    pteq_set(origin, pts[o], r);
    slong k = 0;
    for (slong i = 0; i < n; i++) {
        if (i == o)
            continue;
        pteq_weight_sum(sum, pts[i], r);
        if (ratfun_is_zero(sum, r))
            pteq_set(dirs[k], pts[i], r);
        else
            pteq_sub(dirs[k], pts[i], origin, r);
        k++;
    }
    ratfun_clear(sum, r);
    return 0;
}

/* the sorted union of the base points in the supports of eqs[0..n-1] */
static slong *support_union(slong *nrows, const PointEq *eqs, slong n)
{
    slong cap = 0;
    for (slong i = 0; i < n; i++)
        cap += eqs[i]->len;
    slong *rows = malloc(sizeof(slong) * (size_t)(cap ? cap : 1));
    slong m = 0;
    for (slong i = 0; i < n; i++)
        for (slong j = 0; j < eqs[i]->len; j++) {
            slong pt = eqs[i]->terms[j].point, k = m;
            while (k > 0 && rows[k - 1] > pt)
                k--;
            if (k > 0 && rows[k - 1] == pt)
                continue;
            for (slong q = m; q > k; q--)
                rows[q] = rows[q - 1];
            rows[k] = pt;
            m++;
        }
    *nrows = m;
    return rows;
}

/* rank of the directions as columns over the base points */
static slong dirs_rank(const PointEq *dirs, slong n, const Ring *r)
{
    slong m, rank = 0;
    slong *rows = support_union(&m, dirs, n);
    if (m == 0) {
        free(rows);
        return 0;
    }
    RatFunStruct *a = malloc(sizeof(RatFunStruct) * (size_t)(m * n));
    RatFunStruct *b = malloc(sizeof(RatFunStruct) * (size_t)m);
    RatFunStruct *x = malloc(sizeof(RatFunStruct) * (size_t)n);
    for (slong i = 0; i < m; i++) {
        ratfun_init(b + i, r);
        for (slong j = 0; j < n; j++) {
            ratfun_init(a + i * n + j, r);
            pteq_get_weight(a + i * n + j, dirs[j], rows[i], r);
        }
    }
    for (slong j = 0; j < n; j++)
        ratfun_init(x + j, r);
    linsolve(x, &rank, a, b, m, n, r);
    for (slong j = 0; j < n; j++)
        ratfun_clear(x + j, r);
    for (slong i = 0; i < m; i++) {
        ratfun_clear(b + i, r);
        for (slong j = 0; j < n; j++)
            ratfun_clear(a + i * n + j, r);
    }
    free(x);
    free(b);
    free(a);
    free(rows);
    return rank;
}

MeetStatus construct_meet(PointEq res, const PointEq *a, slong na,
                          const PointEq *b, slong nb, const Ring *r)
{
    /* unknowns: lambda_1..lambda_{na-1}, mu_1..mu_{nb-1};
     * sum lambda_i d_i - sum mu_j e_j = ob - oa  over every base point */
    slong n = na - 1 + nb - 1, m = 0;
    MeetStatus st = MEET_OK;
    PointEq oa, ob, rhs;
    PointEq *cols = malloc(sizeof(PointEq) * (size_t)(n + 1));
    pteq_init(oa, r);
    pteq_init(ob, r);
    pteq_init(rhs, r);
    for (slong j = 0; j <= n; j++)
        pteq_init(cols[j], r);
    RatFunStruct *A = NULL, *B = NULL, *X = NULL;
    slong *rows = NULL;

    if (flat_split(oa, cols, a, na, r) < 0 ||
        flat_split(ob, cols + (na - 1), b, nb, r) < 0) {
        st = MEET_NO_POINT;
        goto cleanup;
    }
    for (slong j = na - 1; j < n; j++)
        pteq_neg(cols[j], cols[j], r);
    pteq_sub(rhs, ob, oa, r);
    pteq_set(cols[n], rhs, r); /* for the row union only */
    rows = support_union(&m, (const PointEq *)cols, n + 1);

    A = malloc(sizeof(RatFunStruct) * (size_t)(m * n + 1));
    B = malloc(sizeof(RatFunStruct) * (size_t)(m + 1));
    X = malloc(sizeof(RatFunStruct) * (size_t)n);
    for (slong i = 0; i < m; i++) {
        ratfun_init(B + i, r);
        pteq_get_weight(B + i, rhs, rows[i], r);
        for (slong j = 0; j < n; j++) {
            ratfun_init(A + i * n + j, r);
            pteq_get_weight(A + i * n + j, cols[j], rows[i], r);
        }
    }
    for (slong j = 0; j < n; j++)
        ratfun_init(X + j, r);

    slong rank = 0;
    LinSolveResult ls = linsolve(X, &rank, A, B, m, n, r);
    if (ls == LINSOLVE_UNIQUE) {
        /* M = oa + sum lambda_i d_i */
        for (slong j = 0; j < na - 1; j++)
            pteq_addmul(oa, oa, cols[j], X + j, r);
        pteq_swap(res, oa, r);
    } else if (dirs_rank((const PointEq *)cols, na - 1, r) < na - 1) {
        st = MEET_DEGENERATE_FIRST;
    } else if (dirs_rank((const PointEq *)cols + (na - 1), nb - 1, r) <
               nb - 1) {
        st = MEET_DEGENERATE_SECOND;
    } else if (rank < n) {
        st = ls == LINSOLVE_INCONSISTENT ? MEET_PARALLEL : MEET_COINCIDENT;
    } else {
        st = MEET_SKEW;
    }

    for (slong j = 0; j < n; j++)
        ratfun_clear(X + j, r);
    for (slong i = 0; i < m; i++) {
        ratfun_clear(B + i, r);
        for (slong j = 0; j < n; j++)
            ratfun_clear(A + i * n + j, r);
    }
cleanup:
    free(X);
    free(B);
    free(A);
    free(rows);
    for (slong j = 0; j <= n; j++)
        pteq_clear(cols[j], r);
    free(cols);
    pteq_clear(rhs, r);
    pteq_clear(ob, r);
    pteq_clear(oa, r);
    return st;
}
