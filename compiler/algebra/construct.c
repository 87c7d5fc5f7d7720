/*
 * construct.c - the point constructions (construct.h): along, divide,
 * Bezier, and the meet of two flats.
 *
 * A point is a PointEq, a combination of base points over one
 * denominator.  along and divide are one linear combination; a meet is
 * first tried fraction-free (meet_ff.c) and otherwise solved exactly as a
 * linear system, which also names what is degenerate.  derive.c calls
 * these for every construction of a scheme.
 */
#include "compiler/algebra/construct.h"

#include <stdlib.h>

#include "base/budget.h"
#include "base/mem.h"
#include "compiler/algebra/linsolve.h"
#include "compiler/algebra/meet_ff.h"

/* P*(1 - s) + Q*s: one combination over one denominator */
void construct_along(PointEq res, const PointEq p, const PointEq q,
                     const RatFun s, const Ring *r)
{
    RatFun sb;
    ratfun_init(sb, r);
    ratfun_one(sb, r);
    ratfun_sub(sb, sb, s, r);
    pteq_lincomb(res, p, sb, q, s, r);
    ratfun_clear(sb, r);
}

/* P/(1 + k) + Q*k/(1 + k) */
int construct_divide(PointEq res, const PointEq p, const PointEq q,
                     const RatFun k, const Ring *r)
{
    RatFun den, wp, wq;
    int st = RATFUN_OK;
    ratfun_init(den, r);
    ratfun_init(wp, r);
    ratfun_init(wq, r);
    ratfun_one(den, r);
    ratfun_add(den, den, k, r);
    if (ratfun_inv(wp, den, r) != RATFUN_OK) {
        st = RATFUN_EDIVZERO;
    } else {
        ratfun_mul(wq, wp, k, r);
        pteq_lincomb(res, p, wp, q, wq, r);
    }
    ratfun_clear(wq, r);
    ratfun_clear(wp, r);
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
    slong *rows = pc_xmalloc(sizeof(slong) * (size_t)(cap ? cap : 1));
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
static slong dirs_rank(const PointEq *dirs, slong n, LinNormal *nf,
                       const Ring *r)
{
    slong m, rank = 0;
    slong *rows = support_union(&m, dirs, n);
    if (m == 0) {
        pc_free(rows);
        return 0;
    }
    RatFunStruct *a = pc_xmalloc(sizeof(RatFunStruct) * (size_t)(m * n));
    RatFunStruct *b = pc_xmalloc(sizeof(RatFunStruct) * (size_t)m);
    RatFunStruct *x = pc_xmalloc(sizeof(RatFunStruct) * (size_t)n);
    for (slong i = 0; i < m; i++) {
        ratfun_init(b + i, r);
        for (slong j = 0; j < n; j++) {
            ratfun_init(a + i * n + j, r);
            pteq_get_weight(a + i * n + j, dirs[j], rows[i], r);
        }
    }
    for (slong j = 0; j < n; j++)
        ratfun_init(x + j, r);
    linsolve_nf(x, &rank, a, b, m, n, nf, r);
    for (slong j = 0; j < n; j++)
        ratfun_clear(x + j, r);
    for (slong i = 0; i < m; i++) {
        ratfun_clear(b + i, r);
        for (slong j = 0; j < n; j++)
            ratfun_clear(a + i * n + j, r);
    }
    pc_free(x);
    pc_free(b);
    pc_free(a);
    pc_free(rows);
    return rank;
}

/* ---- meet ---------------------------------------------------------------- */

MeetStatus construct_meet(PointEq res, const PointEq *a, slong na,
                          const PointEq *b, slong nb, const Ring *r)
{
    if (na + nb <= MEET_MAX_COLS) { /* shallow copies, read only */
        PointEqStruct gen[MEET_MAX_COLS];
        slong m;
        for (slong j = 0; j < na; j++)
            gen[j] = *a[j];
        for (slong j = 0; j < nb; j++)
            gen[na + j] = *b[j];
        slong *rows = support_union(&m, (const PointEq *)gen, na + nb);
        int done = meet_fraction_free(res, (const PointEq *)gen, na, na + nb,
                                      rows, m, r);
        pc_free(rows);
        /* a meet that ended past the derivation's deadline is stopped by
         * it too: one product can take seconds, and the budget would
         * otherwise depend on where the clock was read (budget.h) */
        if (done != 0)
            return done > 0 && !budget_late() ? MEET_OK : MEET_TOO_BIG;
    }
    return construct_meet_general(res, a, na, b, nb, r);
}

MeetStatus construct_meet_general(PointEq res, const PointEq *a, slong na,
                                  const PointEq *b, slong nb, const Ring *r)
{
    return construct_meet_general_nf(res, a, na, b, nb, NULL, r);
}

MeetStatus construct_meet_general_nf(PointEq res, const PointEq *a, slong na,
                                     const PointEq *b, slong nb, LinNormal *nf,
                                     const Ring *r)
{
    /* unknowns: lambda_1..lambda_{na-1}, mu_1..mu_{nb-1};
     * sum lambda_i d_i - sum mu_j e_j = ob - oa  over every base point */
    slong n = na - 1 + nb - 1, m = 0;
    MeetStatus st = MEET_OK;
    PointEq oa, ob, rhs;
    PointEq *cols = pc_xmalloc(sizeof(PointEq) * (size_t)(n + 1));
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

    A = pc_xmalloc(sizeof(RatFunStruct) * (size_t)(m * n + 1));
    B = pc_xmalloc(sizeof(RatFunStruct) * (size_t)(m + 1));
    X = pc_xmalloc(sizeof(RatFunStruct) * (size_t)n);
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
    LinSolveResult ls = linsolve_nf(X, &rank, A, B, m, n, nf, r);
    if (ls == LINSOLVE_FAILED) {
        st = MEET_FAILED;
    } else if (ls == LINSOLVE_UNIQUE) {
        /* M = oa + sum lambda_i d_i */
        for (slong j = 0; j < na - 1; j++)
            pteq_addmul(oa, oa, cols[j], X + j, r);
        pteq_swap(res, oa, r);
    } else if (dirs_rank((const PointEq *)cols, na - 1, nf, r) < na - 1) {
        st = MEET_DEGENERATE_FIRST;
    } else if (dirs_rank((const PointEq *)cols + (na - 1), nb - 1, nf, r) <
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
    pc_free(X);
    pc_free(B);
    pc_free(A);
    pc_free(rows);
    for (slong j = 0; j <= n; j++)
        pteq_clear(cols[j], r);
    pc_free(cols);
    pteq_clear(rhs, r);
    pteq_clear(ob, r);
    pteq_clear(oa, r);
    return st;
}

/* ---- a meet's parameters, for derive --steps ---------------------------- */

/* x[0..n-1] with target = origin + sum x_j dirs_j over every base point:
 * 1 when that solution exists and is unique (x holds n initialised
 * entries), else 0 */
static int affine_coords(RatFunStruct *x, const PointEq target,
                         const PointEq origin, const PointEq *dirs, slong n,
                         const Ring *r)
{
    slong m;
    PointEq *all = pc_xmalloc(sizeof(PointEq) * (size_t)(n + 1));
    for (slong j = 0; j <= n; j++)
        pteq_init(all[j], r);
    for (slong j = 0; j < n; j++)
        pteq_set(all[j], dirs[j], r);
    pteq_sub(all[n], target, origin, r); /* the right-hand side */
    slong *rows = support_union(&m, (const PointEq *)all, n + 1);
    RatFunStruct *a = ratfun_vec_init(m * n, r);
    RatFunStruct *b = ratfun_vec_init(m, r);
    for (slong i = 0; i < m; i++) {
        pteq_get_weight(b + i, all[n], rows[i], r);
        for (slong j = 0; j < n; j++)
            pteq_get_weight(a + i * n + j, all[j], rows[i], r);
    }
    int ok = linsolve(x, NULL, a, b, m, n, r) == LINSOLVE_UNIQUE;
    ratfun_vec_clear(b, m, r);
    ratfun_vec_clear(a, m * n, r);
    pc_free(rows);
    for (slong j = 0; j <= n; j++)
        pteq_clear(all[j], r);
    pc_free(all);
    return ok;
}

int construct_meet_params(RatFunStruct *params, const PointEq m,
                          const PointEq *a, const PointEq *b, slong nb,
                          const Ring *r)
{
    PointEq origin, dirs[MEET_MAX_COLS];
    int ok = nb >= 2 && nb <= MEET_MAX_COLS;
    pteq_init(origin, r);
    for (slong j = 0; j < MEET_MAX_COLS; j++)
        pteq_init(dirs[j], r);
    ok = ok && flat_split(origin, dirs, a, 2, r) == 0 &&
         affine_coords(params, m, origin, (const PointEq *)dirs, 1, r);
    ok = ok && flat_split(origin, dirs, b, nb, r) == 0 &&
         affine_coords(params + 1, m, origin, (const PointEq *)dirs, nb - 1, r);
    for (slong j = 0; j < MEET_MAX_COLS; j++)
        pteq_clear(dirs[j], r);
    pteq_clear(origin, r);
    return ok ? 0 : -1;
}

/* pts[0..n-1] as proper points: a direction d becomes origin + d */
static int flat_points(PointEq *res, const PointEq *pts, slong n, const Ring *r)
{
    PointEq origin;
    RatFun sum;
    int st = 0;
    pteq_init(origin, r);
    ratfun_init(sum, r);
    for (slong i = 0; i < n; i++) {
        pteq_weight_sum(sum, pts[i], r);
        if (!ratfun_is_zero(sum, r)) {
            pteq_set(origin, pts[i], r);
            break;
        }
    }
    if (pteq_is_zero(origin, r))
        st = -1;
    for (slong i = 0; i < n && st == 0; i++) {
        pteq_weight_sum(sum, pts[i], r);
        if (ratfun_is_zero(sum, r))
            pteq_add(res[i], origin, pts[i], r);
        else
            pteq_set(res[i], pts[i], r);
    }
    ratfun_clear(sum, r);
    pteq_clear(origin, r);
    return st;
}

/* The S- or V-theorem form of a meet (derive.h, DerivedStep): W = b[*w]
 * written in the simplex a0, a1 and the other points of b,
 * W = a0*coord[0] + a1*coord[1] + sum coord[2+j]*V_j; det = coord[0] +
 * coord[1].  The last point of b that works is W.  0, or -1 when none
 * does (every point of b on line a0 a1, or the flats degenerate). */
int construct_meet_sv(RatFunStruct *coord, slong *w, RatFun det,
                      const PointEq *a, const PointEq *b, slong nb,
                      const Ring *r)
{
    PointEq pts[2 + MEET_MAX_COLS], dirs[MEET_MAX_COLS];
    int found = 0;
    if (nb < 2 || nb > MEET_MAX_COLS)
        return -1;
    for (slong j = 0; j < 2 + nb; j++)
        pteq_init(pts[j], r);
    for (slong j = 0; j < nb; j++)
        pteq_init(dirs[j], r);
    RatFunStruct *x = ratfun_vec_init(nb, r);
    if (flat_points(pts, a, 2, r) < 0 || flat_points(pts + 2, b, nb, r) < 0)
        goto done;
    for (slong cand = nb - 1; cand >= 0 && !found; cand--) {
        /* unknowns: x[0] for a1 - a0, x[1..] for the V_j - a0 */
        pteq_sub(dirs[0], pts[1], pts[0], r);
        for (slong j = 0, k = 1; j < nb; j++)
            if (j != cand)
                pteq_sub(dirs[k++], pts[2 + j], pts[0], r);
        if (!affine_coords(x, pts[2 + cand], pts[0], (const PointEq *)dirs, nb,
                           r))
            continue;
        /* a = 1 - x[0] - sum x[1..], b = x[0] */
        ratfun_one(coord, r);
        for (slong j = 0; j < nb; j++)
            ratfun_sub(coord, coord, x + j, r);
        for (slong j = 0; j < nb; j++)
            ratfun_set(coord + 1 + j, x + j, r);
        ratfun_add(det, coord, coord + 1, r);
        *w = cand;
        found = 1;
    }
done:
    ratfun_vec_clear(x, nb, r);
    for (slong j = 0; j < nb; j++)
        pteq_clear(dirs[j], r);
    for (slong j = 0; j < 2 + nb; j++)
        pteq_clear(pts[j], r);
    return found ? 0 : -1;
}
