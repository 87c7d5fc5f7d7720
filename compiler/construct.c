#include "compiler/construct.h"

#include <stdlib.h>

#include <flint/nmod_vec.h>
#include <flint/ulong_extras.h>

#include "compiler/linsolve.h"
#include "base/mem.h"

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
        free(rows);
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
    free(x);
    free(b);
    free(a);
    free(rows);
    return rank;
}


/* ---- meet, fraction-free ----------------------------------------------- */

/*
 * The intersection point of two flats in homogeneous form.  Each defining
 * point (or direction) of a flat is a column: its numerators over the base
 * points (its denominator only scales it, which changes no span).  With
 * G = [a_1 .. a_na | b_1 .. b_nb] (m rows, k = na + nb columns) the flats
 * meet in one point exactly when G has rank k - 1; then its null vector z
 * gives M ~ sum z_i a_i = -sum z_j b_j, and M = that over its weight sum.
 *
 * A column that is a base point X itself (a "unit" column, as in
 * line(A, P)) only fixes its own z from row X, so it is eliminated with
 * its row first; the other z come from k' - 1 independent rows R of what
 * is left, as signed maximal minors, z_j = (-1)^j det(G'_R without column
 * j): polynomial products only, no division and no gcd.  M is then formed
 * row by row from the side whose terms do not cancel (a row X of a unit
 * column on side a takes -sum_b z_j b_j[X]: the a-side sum there is that
 * plus terms that cancel), and one content reduction makes it primitive.
 * For meet(line(A, P), line(B, Q)) in the plane ABC this is three products,
 * M ~ (P_C Q_A, Q_C P_B, Q_C P_C).  Before the minors, the columns of each
 * side are reduced against each other where they share a big common part
 * (reduce_side: points made from one X), and only the z that M's rows use
 * are formed.
 *
 * R is chosen by Gaussian elimination of G' evaluated at a random point
 * modulo a 61-bit prime, which never claims a rank that G' lacks (a minor
 * non-zero mod p is non-zero); rows outside R are then checked exactly.
 * Anything else (two unit columns of one point, no column left, rank too
 * small mod p, a failed check, M zero or at infinity) returns 0 and
 * construct_meet takes the exact general path, which also says what is
 * degenerate.
 */

#define MEET_MAX_COLS 5
/* reduce_side works on entries of at least this many terms */
#define MEET_REDUCE_MIN_TERMS 100
/* the limit of one intermediate product (ratfun.h's estimates) */
#define MEET_MAX_LOG2_BITS 30.0

/* x mod p at vals (mod p); 0 and *ok = 0 when exponents do not fit */
static ulong eval_mod(const fmpz_mpoly_t x, const ulong *vals, nmod_t mod,
                      ulong *exp, int *ok, const Ring *r)
{
    ulong acc = 0;
    slong nv = fmpz_mpoly_ctx_nvars(r->ctx);
    if (x->bits > FLINT_BITS) {
        *ok = 0;
        return 0;
    }
    for (slong i = 0; i < x->length; i++) {
        ulong t = fmpz_fdiv_ui(x->coeffs + i, mod.n);
        fmpz_mpoly_get_term_exp_ui(exp, x, i, r->ctx);
        for (slong v = 0; v < nv && t != 0; v++)
            if (exp[v] != 0)
                t = nmod_mul(t, nmod_pow_ui(vals[v], exp[v], mod), mod);
        acc = nmod_add(acc, t, mod);
    }
    return acc;
}

/* the numerator of point pt in x, or NULL */
static const fmpz_mpoly_struct *num_at(const PointEq x, slong pt)
{
    for (slong i = 0; i < x->len; i++)
        if (x->terms[i].point == pt)
            return x->terms[i].num;
    return NULL;
}

/* 1 when the product a*b could exceed the limit of one intermediate */
static int too_big(const fmpz_mpoly_t a, const fmpz_mpoly_t b, const Ring *r)
{
    return ratfun_poly_log2_bits_mul(a, b, r) > MEET_MAX_LOG2_BITS;
}

/* The minor of rows sel[0..|mask|-1] and the columns in mask (bits index
 * cols[]), by Laplace expansion along its last row, memoised in minor[]
 * (have[mask] set once computed): only the minors the wanted ones need are
 * formed. */
static const fmpz_mpoly_struct *
get_minor(fmpz_mpoly_struct *minor, char *have, slong mask,
          const fmpz_mpoly_struct **G, slong k, const slong *sel,
          const slong *cols, slong nc, fmpz_mpoly_t t, int *big,
          const Ring *r)
{
    fmpz_mpoly_struct *res = minor + mask;
    slong lev = 0, q = 0;

    if (have[mask])
        return res;
    have[mask] = 1;
    for (slong c = 0; c < nc; c++)
        lev += (mask >> c) & 1;
    fmpz_mpoly_zero(res, r->ctx);
    if (lev == 0) {
        fmpz_mpoly_one(res, r->ctx);
        return res;
    }
    for (slong c = 0; c < nc; c++) {
        if (!(mask & (WORD(1) << c)))
            continue;
        const fmpz_mpoly_struct *g = G[sel[lev - 1] * k + cols[c]];
        if (g != NULL) {
            const fmpz_mpoly_struct *sub =
                get_minor(minor, have, mask ^ (WORD(1) << c), G, k, sel, cols,
                          nc, t, big, r);
            if (*big)
                return res;
            if (!fmpz_mpoly_is_zero(sub, r->ctx)) {
                if (too_big(g, sub, r)) {
                    *big = 1;
                    return res;
                }
                fmpz_mpoly_mul(t, g, sub, r->ctx);
                if ((lev - 1 + q) & 1)
                    fmpz_mpoly_sub(res, res, t, r->ctx);
                else
                    fmpz_mpoly_add(res, res, t, r->ctx);
            }
        }
        q++;
    }
    return res;
}

/* acc = sign * sum of z[j]*G[i*k + j] over the columns j of cols[0..nc)
 * in [lo, hi) */
static void row_sum(fmpz_mpoly_t acc, const fmpz_mpoly_struct **G, slong i,
                    slong k, const fmpz_mpoly_struct *z, const slong *cols,
                    slong nc, slong lo, slong hi, int sign, fmpz_mpoly_t t,
                    int *big, const Ring *r)
{
    fmpz_mpoly_zero(acc, r->ctx);
    for (slong c = 0; c < nc; c++) {
        slong j = cols[c];
        const fmpz_mpoly_struct *g = G[i * k + j];
        if (j < lo || j >= hi || g == NULL || fmpz_mpoly_is_zero(z + c, r->ctx))
            continue;
        if (too_big(g, z + c, r)) {
            *big = 1;
            return;
        }
        fmpz_mpoly_mul(t, g, z + c, r->ctx);
        if (fmpz_mpoly_is_zero(acc, r->ctx))
            fmpz_mpoly_swap(acc, t, r->ctx); /* the first term: no copy */
        else
            fmpz_mpoly_add(acc, acc, t, r->ctx);
    }
    if (sign < 0)
        fmpz_mpoly_neg(acc, acc, r->ctx);
}

/* the work of row_sum, estimated as the sum of the products' term counts */
static double row_cost(const fmpz_mpoly_struct **G, slong i, slong k,
                       const fmpz_mpoly_struct *z, const slong *cols, slong nc,
                       slong lo, slong hi)
{
    double c = 0;
    for (slong q = 0; q < nc; q++) {
        slong j = cols[q];
        if (j >= lo && j < hi && G[i * k + j] != NULL)
            c += (double)G[i * k + j]->length * (double)z[q].length;
    }
    return c;
}

/* 1 when every column of [lo, hi) with an entry in row i has need[] set */
static int covered(const char *need, const fmpz_mpoly_struct **G, slong i,
                   slong k, const slong *cl, slong nc, slong lo, slong hi)
{
    for (slong c = 0; c < nc; c++)
        if (cl[c] >= lo && cl[c] < hi && G[i * k + cl[c]] != NULL && !need[c])
            return 0;
    return 1;
}

/* need[] set for every column of [lo, hi) with an entry in row i */
static void mark_row(char *need, const fmpz_mpoly_struct **G, slong i,
                     slong k, const slong *cl, slong nc, slong lo, slong hi)
{
    for (slong c = 0; c < nc; c++)
        if (cl[c] >= lo && cl[c] < hi && G[i * k + cl[c]] != NULL)
            need[c] = 1;
}

/* reduce_side's threshold: below it the gcd that finds the multipliers
 * costs more than the products it saves (FLINT's gcd has a large constant
 * cost); construct_meet_set_reduce_min_terms changes it for tests.  The
 * threshold and the statistics are the calling thread's: threads meeting
 * distinct flats share nothing. */
static _Thread_local slong meet_reduce_min_terms = MEET_REDUCE_MIN_TERMS;
static _Thread_local slong meet_reductions, meet_fast;

void construct_meet_set_reduce_min_terms(slong n)
{
    meet_reduce_min_terms = n < 0 ? MEET_REDUCE_MIN_TERMS : n;
}

void construct_meet_stats(slong *fast, slong *reduced)
{
    *fast = meet_fast;
    *reduced = meet_reductions;
}

/* the most rows column_divide works on (base points in the flats' support) */
#define MEET_MAX_ROWS 64

/* Divides every entry of column j (rows 0..m-1 of G, own storage) by f
 * when f divides them all; the shortest entries first, so that a factor
 * that is not there is usually found out on a short one. */
static void column_divide(fmpz_mpoly_struct *own, const fmpz_mpoly_struct **G,
                          slong m, slong k, slong j, const fmpz_mpoly_t f,
                          const Ring *r)
{
    slong order[MEET_MAX_ROWS], n = 0, q;
    fmpz_mpoly_struct quo[MEET_MAX_ROWS];
    if (fmpz_mpoly_is_fmpz(f, r->ctx) || m > MEET_MAX_ROWS)
        return;
    for (slong i = 0; i < m; i++) {
        if (G[i * k + j] == NULL)
            continue;
        q = n++;
        while (q > 0 &&
               G[order[q - 1] * k + j]->length > G[i * k + j]->length) {
            order[q] = order[q - 1];
            q--;
        }
        order[q] = i;
    }
    for (q = 0; q < n; q++) {
        fmpz_mpoly_init(quo + q, r->ctx);
        if (!fmpz_mpoly_divides(quo + q, G[order[q] * k + j], f, r->ctx))
            break;
    }
    if (q == n)
        for (slong e = 0; e < n; e++)
            fmpz_mpoly_swap(own + order[e] * k + j, quo + e, r->ctx);
    for (slong e = 0; e < q + (q < n); e++)
        fmpz_mpoly_clear(quo + e, r->ctx);
}

/*
 * Column operations inside one side (columns [lo, hi)): they change the
 * null vector but not the spans, so not M.  The defining points of a flat
 * built from one point X = N/d (plane(B, along(X, C, r), along(X, D, s)))
 * share X's numerators N: in a row where both columns are only multiples
 * of N's entry (row A there: (1 - r) N_A and (1 - s) N_A), the gcd of the
 * two entries is that entry and its cofactors are the small multipliers of
 * the combination that eliminates N, (1 - r) b3 - (1 - s) b2 =
 * d ((1 - r) s D - (1 - s) r C): after the known factor d is divided out,
 * a column of small entries.  The minors are then products of a big entry
 * and a small one, and none of them carries d, which otherwise every 2x2
 * minor of such a plane would (formed by products of big entries and
 * divided out again).  Every other non-unit column of the side is reduced
 * against the first where a row's gcd holds most of both entries (the
 * shortest two rows are tried); the side's own unit rows are never read
 * (M's rows there are formed from the other side) and stay NULL.
 * The multiplier ap of a reduced column scales the other side's z, and so
 * M: it is recorded in fac[] (*nfac of them) for M's content reduction.
 * The reduced columns live in *ownp (m*k entries, allocated by the first).
 * Returns 0, or -1 when a column became zero (dependent points: the
 * general path names it); *big when a product would be too large.
 */
static int reduce_side(fmpz_mpoly_struct **ownp, const fmpz_mpoly_struct **G,
                       slong m, slong k, const slong *row_unit,
                       const PointEq *cols, const slong *cl, slong nc,
                       slong lo, slong hi, fmpz_mpoly_struct *fac,
                       slong *nfac, int *big, const Ring *r)
{
    slong sc[MEET_MAX_COLS], ns = 0;
    int st = 0;
    fmpz_mpoly_t g, ap, aj, t;

    for (slong c = 0; c < nc; c++)
        if (cl[c] >= lo && cl[c] < hi)
            sc[ns++] = cl[c];
    if (ns < 2)
        return 0;
    fmpz_mpoly_init(g, r->ctx);
    fmpz_mpoly_init(ap, r->ctx);
    fmpz_mpoly_init(aj, r->ctx);
    fmpz_mpoly_init(t, r->ctx);
    slong p = sc[0];
    for (slong q = 1; q < ns && st == 0 && !*big; q++) {
        slong j = sc[q], tried[2] = {-1, -1}, piv = -1;
        for (slong attempt = 0; attempt < 2 && piv < 0; attempt++) {
            slong best = -1;
            double bl = 0;
            for (slong i = 0; i < m; i++) {
                const fmpz_mpoly_struct *x = G[i * k + p], *y = G[i * k + j];
                if ((row_unit[i] >= lo && row_unit[i] < hi) || x == NULL ||
                    y == NULL || i == tried[0])
                    continue;
                double l = (double)x->length + (double)y->length;
                if (best < 0 || l < bl) {
                    best = i;
                    bl = l;
                }
            }
            if (best < 0)
                break;
            tried[attempt] = best;
            const fmpz_mpoly_struct *x = G[best * k + p], *y = G[best * k + j];
            if (x->length < meet_reduce_min_terms ||
                y->length < meet_reduce_min_terms)
                break; /* nothing big to eliminate */
            if (!fmpz_mpoly_gcd_cofactors(g, ap, aj, x, y, r->ctx))
                break;
            if (g->length >= 2 * FLINT_MAX(ap->length, aj->length) ||
                meet_reduce_min_terms == 0)
                piv = best;
        }
        if (piv < 0)
            continue;
        /* column j := ap*c_j - aj*c_p, in own storage */
        int zero = 1;
        if (*ownp == NULL) {
            *ownp = flint_malloc((size_t)(m * k) * sizeof(fmpz_mpoly_struct));
            for (slong i = 0; i < m * k; i++)
                fmpz_mpoly_init(*ownp + i, r->ctx);
        }
        fmpz_mpoly_struct *own = *ownp;
        for (slong i = 0; i < m && !*big; i++) {
            const fmpz_mpoly_struct *x = G[i * k + p], *y = G[i * k + j];
            fmpz_mpoly_struct *dst = own + i * k + j;
            if (row_unit[i] >= lo && row_unit[i] < hi) {
                G[i * k + j] = NULL;
                continue;
            }
            if (i == piv) {
                G[i * k + j] = NULL; /* exactly zero */
                continue;
            }
            if ((y != NULL && too_big(ap, y, r)) ||
                (x != NULL && too_big(aj, x, r))) {
                *big = 1;
                break;
            }
            if (y != NULL)
                fmpz_mpoly_mul(t, ap, y, r->ctx);
            else
                fmpz_mpoly_zero(t, r->ctx);
            if (x != NULL) {
                fmpz_mpoly_mul(dst, aj, x, r->ctx);
                fmpz_mpoly_sub(dst, t, dst, r->ctx);
            } else {
                fmpz_mpoly_swap(dst, t, r->ctx);
            }
            if (fmpz_mpoly_is_zero(dst, r->ctx)) {
                G[i * k + j] = NULL;
            } else {
                G[i * k + j] = dst;
                zero = 0;
            }
        }
        if (*big)
            break;
        if (zero) {
            st = -1;
            break;
        }
        if (!fmpz_mpoly_is_fmpz(ap, r->ctx)) {
            fmpz_mpoly_init(fac + *nfac, r->ctx);
            fmpz_mpoly_set(fac + (*nfac)++, ap, r->ctx);
        }
        meet_reductions++;
        /* the known factors first: the columns' denominators */
        column_divide(own, G, m, k, j, cols[p]->den, r);
        if (!fmpz_mpoly_equal(cols[p]->den, cols[j]->den, r->ctx))
            column_divide(own, G, m, k, j, cols[j]->den, r);
    }
    fmpz_mpoly_clear(t, r->ctx);
    fmpz_mpoly_clear(aj, r->ctx);
    fmpz_mpoly_clear(ap, r->ctx);
    fmpz_mpoly_clear(g, r->ctx);
    return st;
}

static int meet_fraction_free(PointEq res, const PointEq *cols, slong na,
                              slong k, const slong *rows, slong m,
                              const Ring *r)
{
    int ok = 1, found = 0, big = 0;
    slong nv = fmpz_mpoly_ctx_nvars(r->ctx), rank = 0, nc = 0, nr = 0;
    slong sel[MEET_MAX_COLS], cl[MEET_MAX_COLS], pivot[MEET_MAX_COLS];
    ulong basis[MEET_MAX_COLS][MEET_MAX_COLS], row_mod[MEET_MAX_COLS];
    nmod_t mod;
    flint_rand_t st;
    ulong *vals = flint_malloc((size_t)FLINT_MAX(nv, 1) * sizeof(ulong));
    ulong *exp = flint_malloc((size_t)FLINT_MAX(nv, 1) * sizeof(ulong));
    slong *row_unit = flint_malloc((size_t)FLINT_MAX(m, 1) * sizeof(slong));
    slong *rl = flint_malloc((size_t)FLINT_MAX(m, 1) * sizeof(slong));
    const fmpz_mpoly_struct **G =
        flint_calloc((size_t)FLINT_MAX(m * k, 1), sizeof(fmpz_mpoly_struct *));
    fmpz_mpoly_struct *minor = NULL, *z = NULL, *own = NULL;
    fmpz_mpoly_struct quo[MEET_MAX_COLS];
    char from_buf[64];
    slong nquo = 0;
    char *have = NULL, need[MEET_MAX_COLS];
    fmpz_mpoly_struct fac[MEET_MAX_COLS], rdiv[2], *rq = NULL;
    slong nfac = 0, nfac_a = 0;
    char used[MEET_MAX_COLS] = {0}, *from = NULL, rdiv_set[2] = {0, 0};
    slong nmask = 0;
    fmpz_mpoly_t t, u, ub;
    PointEq acc;

    fmpz_mpoly_init(t, r->ctx);
    fmpz_mpoly_init(u, r->ctx);
    fmpz_mpoly_init(ub, r->ctx);
    fmpz_mpoly_init(rdiv + 0, r->ctx); /* 1 until rdiv_set[] */
    fmpz_mpoly_init(rdiv + 1, r->ctx);
    pteq_init(acc, r);
    if (k > MEET_MAX_COLS)
        goto done;
    for (slong i = 0; i < m; i++) {
        row_unit[i] = -1;
        for (slong j = 0; j < k; j++)
            G[i * k + j] = num_at(cols[j], rows[i]);
    }
    /* unit columns and their rows leave the system */
    for (slong j = 0; j < k; j++) {
        const PointEqStruct *c = cols[j];
        if (c->len == 1 && fmpz_mpoly_is_one(c->terms[0].num, r->ctx) &&
            fmpz_mpoly_is_one(c->den, r->ctx)) {
            slong i = 0;
            while (rows[i] != c->terms[0].point)
                i++;
            if (row_unit[i] >= 0)
                goto done; /* one point on both sides, or twice */
            row_unit[i] = j;
        } else {
            cl[nc++] = j;
        }
    }
    for (slong i = 0; i < m; i++)
        if (row_unit[i] < 0)
            rl[nr++] = i;
    if (nc == 0 || nr < nc - 1)
        goto done;

    /* each side's columns reduced against each other (reduce_side) */
    if (reduce_side(&own, G, m, k, row_unit, cols, cl, nc, 0, na, fac, &nfac,
                    &big, r) < 0 ||
        big || (nfac_a = nfac, 0) ||
        reduce_side(&own, G, m, k, row_unit, cols, cl, nc, na, k, fac, &nfac,
                    &big, r) < 0 ||
        big)
        goto done;

    /* rows R: independent rows of G' at a random point mod p */
    nmod_init(&mod, UWORD(2305843009213693951)); /* 2^61 - 1 */
    flint_randinit(st);
    for (slong v = 0; v < nv; v++)
        vals[v] = 1 + n_randint(st, mod.n - 1);
    flint_randclear(st);
    for (slong q = 0; q < nr && ok; q++) {
        slong i = rl[q], c;
        for (slong j = 0; j < nc && ok; j++) {
            const fmpz_mpoly_struct *g = G[i * k + cl[j]];
            row_mod[j] = g ? eval_mod(g, vals, mod, exp, &ok, r) : 0;
        }
        for (slong b = 0; b < rank; b++) { /* reduce by the basis */
            ulong f = row_mod[pivot[b]];
            if (f == 0)
                continue;
            for (slong j = 0; j < nc; j++)
                row_mod[j] = nmod_sub(row_mod[j],
                                      nmod_mul(f, basis[b][j], mod), mod);
        }
        for (c = 0; c < nc && row_mod[c] == 0; c++)
            ;
        if (c == nc)
            continue;
        if (rank == nc - 1) { /* rank nc: no common point (skew) */
            ok = 0;
            break;
        }
        ulong inv = nmod_inv(row_mod[c], mod);
        for (slong j = 0; j < nc; j++)
            basis[rank][j] = nmod_mul(row_mod[j], inv, mod);
        for (slong b = 0; b < rank; b++) { /* keep the basis reduced */
            ulong f = basis[b][c];
            if (f == 0)
                continue;
            for (slong j = 0; j < nc; j++)
                basis[b][j] = nmod_sub(basis[b][j],
                                       nmod_mul(f, basis[rank][j], mod), mod);
        }
        pivot[rank] = c;
        sel[rank++] = i;
    }
    if (!ok || rank != nc - 1)
        goto done;

    /* Which z M needs: a unit row takes the other side's columns, the rows
     * beyond R all of them, a free row either side; a free row that no
     * side needed so far covers makes every z needed (then the cheaper
     * side per row, as before).  A z nothing needs is not formed: after
     * reduce_side that is often the one minor of two big entries. */
    for (slong c = 0; c < nc; c++)
        need[c] = nr > rank;
    for (slong i = 0; i < m; i++)
        if (row_unit[i] >= 0)
            mark_row(need, G, i, k, cl, nc, row_unit[i] < na ? na : 0,
                     row_unit[i] < na ? k : na);
    for (slong i = 0; i < m; i++)
        if (row_unit[i] < 0 && !covered(need, G, i, k, cl, nc, 0, na) &&
            !covered(need, G, i, k, cl, nc, na, k)) {
            for (slong c = 0; c < nc; c++)
                need[c] = 1;
            break;
        }

    /* the null vector of G': z[c] for column cl[c] (0 where not needed) */
    nmask = WORD(1) << nc;
    minor = flint_malloc((size_t)nmask * sizeof(fmpz_mpoly_struct));
    have = flint_calloc((size_t)nmask, 1);
    for (slong s = 0; s < nmask; s++)
        fmpz_mpoly_init(minor + s, r->ctx);
    z = flint_malloc((size_t)nc * sizeof(fmpz_mpoly_struct));
    for (slong c = 0; c < nc; c++) {
        fmpz_mpoly_init(z + c, r->ctx);
        fmpz_mpoly_init(quo + c, r->ctx);
        nquo++;
    }
    for (slong c = 0; c < nc; c++) {
        if (!need[c])
            continue;
        const fmpz_mpoly_struct *mc =
            get_minor(minor, have, (nmask - 1) ^ (WORD(1) << c), G, k, sel,
                      cl, nc, t, &big, r);
        if (big)
            goto done;
        if (c & 1)
            fmpz_mpoly_neg(z + c, mc, r->ctx);
        else
            fmpz_mpoly_set(z + c, mc, r->ctx);
    }

    /* z's own content (z = (N, -N) for two lines through the same ratio
     * N/D) would otherwise multiply M and only be found again, at twice
     * the degree, by the reduction at the end.  Only the z M uses need to
     * be divisible: M is a multiple of the point whatever the scale. */
    /* reduce_side's multiplier ap of a column of one side divides the
     * other side's z (its minors hold the whole reduced side, whose
     * determinant ap/f the column operations multiplied in): divided out
     * there, and later from the rows formed from the reduced side */
    for (slong f = 0; f < nfac; f++) {
        int sd = f >= nfac_a, all = 1;
        slong olo = sd ? 0 : na, ohi = sd ? na : k;
        for (slong c = 0; c < nc && all; c++)
            if (cl[c] >= olo && cl[c] < ohi && !fmpz_mpoly_is_zero(z + c, r->ctx))
                all = fmpz_mpoly_divides(quo + c, z + c, fac + f, r->ctx);
        if (!all)
            continue;
        for (slong c = 0; c < nc; c++)
            if (cl[c] >= olo && cl[c] < ohi && !fmpz_mpoly_is_zero(z + c, r->ctx))
                fmpz_mpoly_swap(z + c, quo + c, r->ctx);
        if (rdiv_set[sd])
            fmpz_mpoly_mul(rdiv + sd, rdiv + sd, fac + f, r->ctx);
        else
            fmpz_mpoly_set(rdiv + sd, fac + f, r->ctx);
        rdiv_set[sd] = 1;
        used[f] = 1;
    }

    if (nc >= 2) {
        /* the likely content first: the denominators of the columns (in a
         * plane through points made from one X that reduce_side could not
         * simplify, every minor carries X's denominator); dividing by a
         * known factor is far cheaper than finding it with a gcd of the z */
        for (slong c = 0; c < nc; c++) {
            const fmpz_mpoly_struct *den = cols[cl[c]]->den;
            int again = !fmpz_mpoly_is_fmpz(den, r->ctx);
            for (slong e = 0; e < c && again; e++)
                again = !fmpz_mpoly_equal(den, cols[cl[e]]->den, r->ctx);
            if (again) {
                for (slong j = 0; j < nc && again; j++)
                    again = fmpz_mpoly_is_zero(z + j, r->ctx) ||
                            fmpz_mpoly_divides(quo + j, z + j, den, r->ctx);
                if (again)
                    for (slong j = 0; j < nc; j++)
                        if (!fmpz_mpoly_is_zero(z + j, r->ctx))
                            fmpz_mpoly_swap(z + j, quo + j, r->ctx);
            }
        }
        fmpz_mpoly_zero(u, r->ctx);
        for (slong c = 0; c < nc && !fmpz_mpoly_is_one(u, r->ctx); c++)
            ratfun_poly_gcd(u, u, z + c, r);
        if (!fmpz_mpoly_is_zero(u, r->ctx) && !fmpz_mpoly_is_one(u, r->ctx))
            for (slong c = 0; c < nc; c++) {
                int ok_div = fmpz_mpoly_divides(z + c, z + c, u, r->ctx);
                (void)ok_div;
                FLINT_ASSERT(ok_div);
            }
    }

    /* the other rows of G' must vanish too (else rank nc: fall back) */
    for (slong q = 0, b = 0; q < nr; q++) {
        if (b < rank && sel[b] == rl[q]) {
            b++;
            continue;
        }
        /* z_a was divided by rdiv[1], z_b by rdiv[0] */
        row_sum(u, G, rl[q], k, z, cl, nc, 0, na, 1, t, &big, r);
        if (!big)
            row_sum(ub, G, rl[q], k, z, cl, nc, na, k, 1, t, &big, r);
        if (!big && ((rdiv_set[1] && too_big(u, rdiv + 1, r)) ||
                     (rdiv_set[0] && too_big(ub, rdiv + 0, r))))
            big = 1;
        if (big)
            goto done;
        if (rdiv_set[1])
            fmpz_mpoly_mul(u, u, rdiv + 1, r->ctx);
        if (rdiv_set[0])
            fmpz_mpoly_mul(ub, ub, rdiv + 0, r->ctx);
        fmpz_mpoly_add(u, u, ub, r->ctx);
        if (!fmpz_mpoly_is_zero(u, r->ctx))
            goto done;
    }

    /* M row by row (rows are sorted base points), each from one side:
     * from[i] = 0 for sum z_a a, 1 for -sum z_b b */
    from = m <= 64 ? from_buf : flint_malloc((size_t)m);
    for (slong i = 0; i < m; i++) {
        fmpz_mpoly_struct *num = pteq_append(acc, rows[i], r);
        slong un = row_unit[i];
        if (un >= 0)
            from[i] = un < na;
        else
            from[i] = !(!covered(need, G, i, k, cl, nc, na, k) ||
                        (covered(need, G, i, k, cl, nc, 0, na) &&
                         row_cost(G, i, k, z, cl, nc, 0, na) <=
                             row_cost(G, i, k, z, cl, nc, na, k)));
        if (from[i])
            row_sum(num, G, i, k, z, cl, nc, na, k, -1, t, &big, r);
        else
            row_sum(num, G, i, k, z, cl, nc, 0, na, 1, t, &big, r);
        if (big)
            goto done;
    }
    /* the rows from a side whose multipliers were divided out of the other
     * side's z: divided too (exact unless a unit row's z keeps the factor:
     * then the other rows are multiplied back) */
    for (int sd = 0; sd < 2; sd++) {
        slong i;
        if (!rdiv_set[sd])
            continue;
        if (rq == NULL) {
            rq = flint_malloc((size_t)m * sizeof(fmpz_mpoly_struct));
            for (i = 0; i < m; i++)
                fmpz_mpoly_init(rq + i, r->ctx);
        }
        for (i = 0; i < m; i++)
            if (from[i] == sd &&
                !fmpz_mpoly_divides(rq + i, acc->terms[i].num, rdiv + sd,
                                    r->ctx))
                break;
        for (slong e = 0; e < m && !big; e++) {
            if (i == m && from[e] == sd) {
                fmpz_mpoly_swap(rq + e, acc->terms[e].num, r->ctx);
            } else if (i < m && from[e] != sd) {
                if (too_big(acc->terms[e].num, rdiv + sd, r))
                    big = 1;
                else
                    fmpz_mpoly_mul(acc->terms[e].num, acc->terms[e].num,
                                   rdiv + sd, r->ctx);
            }
        }
        if (big)
            goto done;
    }
    fmpz_mpoly_zero(acc->den, r->ctx);
    for (slong i = 0; i < m; i++)
        fmpz_mpoly_add(acc->den, acc->den, acc->terms[i].num, r->ctx);
    if (fmpz_mpoly_is_zero(acc->den, r->ctx)) {
        pteq_zero(acc, r);
        goto done; /* at infinity, or zero: the general path tells */
    }
    for (slong f = 0; f < nfac; f++)
        if (!used[f])
            pteq_divide_known(acc, fac + f, r);
    pteq_canonicalise(acc, r);
    pteq_swap(res, acc, r);
    found = 1;
    meet_fast++;

done:
    if (own != NULL) {
        for (slong i = 0; i < m * k; i++)
            fmpz_mpoly_clear(own + i, r->ctx);
        flint_free(own);
    }
    for (slong f = 0; f < nfac; f++)
        fmpz_mpoly_clear(fac + f, r->ctx);
    fmpz_mpoly_clear(rdiv + 0, r->ctx);
    fmpz_mpoly_clear(rdiv + 1, r->ctx);
    if (from != from_buf)
        flint_free(from);
    if (rq != NULL) {
        for (slong i = 0; i < m; i++)
            fmpz_mpoly_clear(rq + i, r->ctx);
        flint_free(rq);
    }
    for (slong c = 0; c < nquo; c++)
        fmpz_mpoly_clear(quo + c, r->ctx);
    if (z != NULL) {
        for (slong c = 0; c < nc; c++)
            fmpz_mpoly_clear(z + c, r->ctx);
        flint_free(z);
    }
    if (minor != NULL) {
        for (slong s = 0; s < nmask; s++)
            fmpz_mpoly_clear(minor + s, r->ctx);
        flint_free(minor);
    }
    flint_free(have);
    pteq_clear(acc, r);
    fmpz_mpoly_clear(ub, r->ctx);
    fmpz_mpoly_clear(u, r->ctx);
    fmpz_mpoly_clear(t, r->ctx);
    flint_free(G);
    flint_free(rl);
    flint_free(row_unit);
    flint_free(exp);
    flint_free(vals);
    return big ? -1 : found;
}

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
        free(rows);
        if (done != 0)
            return done > 0 ? MEET_OK : MEET_TOO_BIG;
    }
    return construct_meet_general(res, a, na, b, nb, r);
}

MeetStatus construct_meet_general(PointEq res, const PointEq *a, slong na,
                                  const PointEq *b, slong nb, const Ring *r)
{
    return construct_meet_general_nf(res, a, na, b, nb, NULL, r);
}

MeetStatus construct_meet_general_nf(PointEq res, const PointEq *a, slong na,
                                     const PointEq *b, slong nb,
                                     LinNormal *nf, const Ring *r)
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
    free(rows);
    for (slong j = 0; j <= n; j++)
        pteq_clear(all[j], r);
    free(all);
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
         affine_coords(params + 1, m, origin, (const PointEq *)dirs, nb - 1,
                       r);
    for (slong j = 0; j < MEET_MAX_COLS; j++)
        pteq_clear(dirs[j], r);
    pteq_clear(origin, r);
    return ok ? 0 : -1;
}

/* pts[0..n-1] as proper points: a direction d becomes origin + d */
static int flat_points(PointEq *res, const PointEq *pts, slong n,
                       const Ring *r)
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
        if (!affine_coords(x, pts[2 + cand], pts[0], (const PointEq *)dirs,
                           nb, r))
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
