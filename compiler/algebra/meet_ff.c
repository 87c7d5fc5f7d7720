/*
 * meet_ff.c - the meet of two flats, fraction-free (construct_meet's fast
 * path; construct.c holds the exact general one).
 *
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
 *
 * meet_fraction_free runs as steps over one MeetFF state: ff_units,
 * ff_reduce, ff_rows, ff_need, ff_null_vector, ff_divide_multipliers,
 * ff_content, ff_check_rows, ff_form_rows, ff_divide_rows, ff_finish.
 */
#include "compiler/algebra/meet_ff.h"

#include "base/budget.h"
#include "base/check.h"

#include <stdio.h>
#include <stdlib.h>

#include <flint/nmod_vec.h>
#include <flint/ulong_extras.h>

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

/* 1 when the product a*b could exceed the limit of one intermediate, or
 * the derivation's time has run out (budget_late: the caller then reports
 * the time budget, not the size) */
static int too_big(const fmpz_mpoly_t a, const fmpz_mpoly_t b, const Ring *r)
{
    return budget_late() ||
           ratfun_poly_log2_bits_mul(a, b, r) > MEET_MAX_LOG2_BITS;
}

/* The minor of rows sel[0..|mask|-1] and the columns in mask (bits index
 * cols[]), by Laplace expansion along its last row, memoised in minor[]
 * (have[mask] set once computed): only the minors the wanted ones need are
 * formed. */
static const fmpz_mpoly_struct *
get_minor(fmpz_mpoly_struct *minor, char *have, slong mask,
          const fmpz_mpoly_struct **G, slong k, const slong *sel,
          const slong *cols, slong nc, fmpz_mpoly_t t, int *big, const Ring *r)
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
static void mark_row(char *need, const fmpz_mpoly_struct **G, slong i, slong k,
                     const slong *cl, slong nc, slong lo, slong hi)
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
                       const PointEq *cols, const slong *cl, slong nc, slong lo,
                       slong hi, fmpz_mpoly_struct *fac, slong *nfac, int *big,
                       const Ring *r)
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

/* The state of one fraction-free meet, shared by its steps below: the
 * problem (cols, na, k, rows, m), G and its reduced columns, the rows R,
 * the null vector z with the factors divided out of it, and M (acc). */
typedef struct MeetFF {
    const PointEq *cols;
    slong na, k, m;
    const slong *rows;
    const Ring *r;
    const fmpz_mpoly_struct **G; // G[i*k + j], NULL for a zero entry
    fmpz_mpoly_struct *own;      // reduce_side's columns (m*k), or NULL
    slong *row_unit;             // per row: its unit column, or -1
    slong *rl, nr;               // the rows without a unit column
    slong cl[MEET_MAX_COLS], nc; // the columns that are not unit columns
    fmpz_mpoly_struct fac[MEET_MAX_COLS]; // reduce_side's multipliers
    slong nfac, nfac_a;                   // ... of both sides, of side a
    slong sel[MEET_MAX_COLS], rank;       // the rows R
    char need[MEET_MAX_COLS];             // the z that M's rows use
    fmpz_mpoly_struct *minor;             // memoised minors (get_minor), nmask
    char *have;
    slong nmask;
    fmpz_mpoly_struct *z; // the null vector (nc), or NULL
    fmpz_mpoly_struct quo[MEET_MAX_COLS];
    slong nquo;
    fmpz_mpoly_struct rdiv[2]; // divided out of the other side's z
    char rdiv_set[2], used[MEET_MAX_COLS];
    char *from, from_buf[64]; // per row of M: the side it comes from
    fmpz_mpoly_struct *rq;    // the rows of M divided by rdiv
    fmpz_mpoly_t t, u, ub;
    PointEq acc; // M
    int big;     // a product would be too large
} MeetFF;

static void ff_init(MeetFF *s, const PointEq *cols, slong na, slong k,
                    const slong *rows, slong m, const Ring *r)
{
    s->cols = cols;
    s->na = na;
    s->k = k;
    s->rows = rows;
    s->m = m;
    s->r = r;
    s->row_unit = flint_malloc((size_t)FLINT_MAX(m, 1) * sizeof(slong));
    s->rl = flint_malloc((size_t)FLINT_MAX(m, 1) * sizeof(slong));
    s->G =
        flint_calloc((size_t)FLINT_MAX(m * k, 1), sizeof(fmpz_mpoly_struct *));
    s->own = s->minor = s->z = s->rq = NULL;
    s->have = s->from = NULL;
    s->nr = s->nc = s->nfac = s->nfac_a = s->rank = s->nmask = s->nquo = 0;
    s->rdiv_set[0] = s->rdiv_set[1] = 0;
    for (slong c = 0; c < MEET_MAX_COLS; c++)
        s->used[c] = 0;
    s->big = 0;
    fmpz_mpoly_init(s->t, r->ctx);
    fmpz_mpoly_init(s->u, r->ctx);
    fmpz_mpoly_init(s->ub, r->ctx);
    fmpz_mpoly_init(s->rdiv + 0, r->ctx); /* 1 until rdiv_set[] */
    fmpz_mpoly_init(s->rdiv + 1, r->ctx);
    pteq_init(s->acc, r);
}

static void ff_clear(MeetFF *s)
{
    const Ring *r = s->r;
    slong m = s->m, k = s->k;
    if (s->own != NULL) {
        for (slong i = 0; i < m * k; i++)
            fmpz_mpoly_clear(s->own + i, r->ctx);
        flint_free(s->own);
    }
    for (slong f = 0; f < s->nfac; f++)
        fmpz_mpoly_clear(s->fac + f, r->ctx);
    fmpz_mpoly_clear(s->rdiv + 0, r->ctx);
    fmpz_mpoly_clear(s->rdiv + 1, r->ctx);
    if (s->from != s->from_buf)
        flint_free(s->from);
    if (s->rq != NULL) {
        for (slong i = 0; i < m; i++)
            fmpz_mpoly_clear(s->rq + i, r->ctx);
        flint_free(s->rq);
    }
    for (slong c = 0; c < s->nquo; c++)
        fmpz_mpoly_clear(s->quo + c, r->ctx);
    if (s->z != NULL) {
        for (slong c = 0; c < s->nc; c++)
            fmpz_mpoly_clear(s->z + c, r->ctx);
        flint_free(s->z);
    }
    if (s->minor != NULL) {
        for (slong q = 0; q < s->nmask; q++)
            fmpz_mpoly_clear(s->minor + q, r->ctx);
        flint_free(s->minor);
    }
    flint_free(s->have);
    pteq_clear(s->acc, r);
    fmpz_mpoly_clear(s->ub, r->ctx);
    fmpz_mpoly_clear(s->u, r->ctx);
    fmpz_mpoly_clear(s->t, r->ctx);
    flint_free(s->G);
    flint_free(s->rl);
    flint_free(s->row_unit);
}

/* G from the columns; unit columns and their rows leave the system.  0
 * when the fast path cannot go on */
static int ff_units(MeetFF *s)
{
    const Ring *r = s->r;
    slong m = s->m, k = s->k;
    for (slong i = 0; i < m; i++) {
        s->row_unit[i] = -1;
        for (slong j = 0; j < k; j++)
            s->G[i * k + j] = num_at(s->cols[j], s->rows[i]);
    }
    /* unit columns and their rows leave the system */
    for (slong j = 0; j < k; j++) {
        const PointEqStruct *c = s->cols[j];
        if (c->len == 1 && fmpz_mpoly_is_one(c->terms[0].num, r->ctx) &&
            fmpz_mpoly_is_one(c->den, r->ctx)) {
            slong i = 0;
            while (s->rows[i] != c->terms[0].point)
                i++;
            if (s->row_unit[i] >= 0)
                return 0; /* one point on both sides, or twice */
            s->row_unit[i] = j;
        } else {
            s->cl[s->nc++] = j;
        }
    }
    for (slong i = 0; i < m; i++)
        if (s->row_unit[i] < 0)
            s->rl[s->nr++] = i;
    return !(s->nc == 0 || s->nr < s->nc - 1);
}

/* each side's columns reduced against each other (reduce_side) */
static int ff_reduce(MeetFF *s)
{
    if (reduce_side(&s->own, s->G, s->m, s->k, s->row_unit, s->cols, s->cl,
                    s->nc, 0, s->na, s->fac, &s->nfac, &s->big, s->r) < 0 ||
        s->big)
        return 0;
    s->nfac_a = s->nfac;
    return !(reduce_side(&s->own, s->G, s->m, s->k, s->row_unit, s->cols, s->cl,
                         s->nc, s->na, s->k, s->fac, &s->nfac, &s->big,
                         s->r) < 0 ||
             s->big);
}

/* rows R: independent rows of G' at a random point mod p; 0 unless their
 * rank is nc - 1 */
static int ff_rows(MeetFF *s)
{
    const Ring *r = s->r;
    slong nv = fmpz_mpoly_ctx_nvars(r->ctx), nc = s->nc, k = s->k;
    slong pivot[MEET_MAX_COLS];
    ulong basis[MEET_MAX_COLS][MEET_MAX_COLS], row_mod[MEET_MAX_COLS];
    nmod_t mod;
    flint_rand_t st;
    int ok = 1;
    ulong *vals = flint_malloc((size_t)FLINT_MAX(nv, 1) * sizeof(ulong));
    ulong *exp = flint_malloc((size_t)FLINT_MAX(nv, 1) * sizeof(ulong));
    nmod_init(&mod, UWORD(2305843009213693951)); /* 2^61 - 1 */
    flint_randinit(st);
    for (slong v = 0; v < nv; v++)
        vals[v] = 1 + n_randint(st, mod.n - 1);
    flint_randclear(st);
    for (slong q = 0; q < s->nr && ok; q++) {
        slong i = s->rl[q], c;
        for (slong j = 0; j < nc && ok; j++) {
            const fmpz_mpoly_struct *g = s->G[i * k + s->cl[j]];
            row_mod[j] = g ? eval_mod(g, vals, mod, exp, &ok, r) : 0;
        }
        for (slong b = 0; b < s->rank; b++) { /* reduce by the basis */
            ulong f = row_mod[pivot[b]];
            if (f == 0)
                continue;
            for (slong j = 0; j < nc; j++)
                row_mod[j] =
                    nmod_sub(row_mod[j], nmod_mul(f, basis[b][j], mod), mod);
        }
        for (c = 0; c < nc && row_mod[c] == 0; c++)
            ;
        if (c == nc)
            continue;
        if (s->rank == nc - 1) { /* rank nc: no common point (skew) */
            ok = 0;
            break;
        }
        slong rank = s->rank;
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
        s->sel[s->rank++] = i;
    }
    flint_free(exp);
    flint_free(vals);
    return ok && s->rank == nc - 1;
}

/* Which z M needs: a unit row takes the other side's columns, the rows
 * beyond R all of them, a free row either side; a free row that no
 * side needed so far covers makes every z needed (then the cheaper
 * side per row, as before).  A z nothing needs is not formed: after
 * reduce_side that is often the one minor of two big entries. */
static void ff_need(MeetFF *s)
{
    slong nc = s->nc, na = s->na, k = s->k;
    for (slong c = 0; c < nc; c++)
        s->need[c] = s->nr > s->rank;
    for (slong i = 0; i < s->m; i++)
        if (s->row_unit[i] >= 0)
            mark_row(s->need, s->G, i, k, s->cl, nc,
                     s->row_unit[i] < na ? na : 0,
                     s->row_unit[i] < na ? k : na);
    for (slong i = 0; i < s->m; i++)
        if (s->row_unit[i] < 0 &&
            !covered(s->need, s->G, i, k, s->cl, nc, 0, na) &&
            !covered(s->need, s->G, i, k, s->cl, nc, na, k)) {
            for (slong c = 0; c < nc; c++)
                s->need[c] = 1;
            break;
        }
}

/* the null vector of G': z[c] for column cl[c] (0 where not needed); 0
 * when a minor would be too big */
static int ff_null_vector(MeetFF *s)
{
    const Ring *r = s->r;
    slong nc = s->nc;
    s->nmask = WORD(1) << nc;
    s->minor = flint_malloc((size_t)s->nmask * sizeof(fmpz_mpoly_struct));
    s->have = flint_calloc((size_t)s->nmask, 1);
    for (slong q = 0; q < s->nmask; q++)
        fmpz_mpoly_init(s->minor + q, r->ctx);
    s->z = flint_malloc((size_t)nc * sizeof(fmpz_mpoly_struct));
    for (slong c = 0; c < nc; c++) {
        fmpz_mpoly_init(s->z + c, r->ctx);
        fmpz_mpoly_init(s->quo + c, r->ctx);
        s->nquo++;
    }
    for (slong c = 0; c < nc; c++) {
        if (!s->need[c])
            continue;
        const fmpz_mpoly_struct *mc =
            get_minor(s->minor, s->have, (s->nmask - 1) ^ (WORD(1) << c), s->G,
                      s->k, s->sel, s->cl, nc, s->t, &s->big, r);
        if (s->big)
            return 0;
        if (c & 1)
            fmpz_mpoly_neg(s->z + c, mc, r->ctx);
        else
            fmpz_mpoly_set(s->z + c, mc, r->ctx);
    }
    return 1;
}

/* z's own content (z = (N, -N) for two lines through the same ratio
 * N/D) would otherwise multiply M and only be found again, at twice
 * the degree, by the reduction at the end.  Only the z M uses need to
 * be divisible: M is a multiple of the point whatever the scale.
 * reduce_side's multiplier ap of a column of one side divides the
 * other side's z (its minors hold the whole reduced side, whose
 * determinant ap/f the column operations multiplied in): divided out
 * there, and later from the rows formed from the reduced side */
static void ff_divide_multipliers(MeetFF *s)
{
    const Ring *r = s->r;
    slong nc = s->nc;
    fmpz_mpoly_struct *z = s->z;
    for (slong f = 0; f < s->nfac; f++) {
        int sd = f >= s->nfac_a, all = 1;
        slong olo = sd ? 0 : s->na, ohi = sd ? s->na : s->k;
        for (slong c = 0; c < nc && all; c++)
            if (s->cl[c] >= olo && s->cl[c] < ohi &&
                !fmpz_mpoly_is_zero(z + c, r->ctx))
                all = fmpz_mpoly_divides(s->quo + c, z + c, s->fac + f, r->ctx);
        if (!all)
            continue;
        for (slong c = 0; c < nc; c++)
            if (s->cl[c] >= olo && s->cl[c] < ohi &&
                !fmpz_mpoly_is_zero(z + c, r->ctx))
                fmpz_mpoly_swap(z + c, s->quo + c, r->ctx);
        if (s->rdiv_set[sd])
            fmpz_mpoly_mul(s->rdiv + sd, s->rdiv + sd, s->fac + f, r->ctx);
        else
            fmpz_mpoly_set(s->rdiv + sd, s->fac + f, r->ctx);
        s->rdiv_set[sd] = 1;
        s->used[f] = 1;
    }
}

/* the content of z (nc >= 2) divided out */
static void ff_content(MeetFF *s)
{
    const Ring *r = s->r;
    slong nc = s->nc;
    fmpz_mpoly_struct *z = s->z;
    /* the likely content first: the denominators of the columns (in a
     * plane through points made from one X that reduce_side could not
     * simplify, every minor carries X's denominator); dividing by a
     * known factor is far cheaper than finding it with a gcd of the z */
    for (slong c = 0; c < nc; c++) {
        const fmpz_mpoly_struct *den = s->cols[s->cl[c]]->den;
        int again = !fmpz_mpoly_is_fmpz(den, r->ctx);
        for (slong e = 0; e < c && again; e++)
            again = !fmpz_mpoly_equal(den, s->cols[s->cl[e]]->den, r->ctx);
        if (again) {
            for (slong j = 0; j < nc && again; j++)
                again = fmpz_mpoly_is_zero(z + j, r->ctx) ||
                        fmpz_mpoly_divides(s->quo + j, z + j, den, r->ctx);
            if (again)
                for (slong j = 0; j < nc; j++)
                    if (!fmpz_mpoly_is_zero(z + j, r->ctx))
                        fmpz_mpoly_swap(z + j, s->quo + j, r->ctx);
        }
    }
    fmpz_mpoly_zero(s->u, r->ctx);
    for (slong c = 0; c < nc && !fmpz_mpoly_is_one(s->u, r->ctx); c++)
        ratfun_poly_gcd(s->u, s->u, z + c, r);
    if (!fmpz_mpoly_is_zero(s->u, r->ctx) && !fmpz_mpoly_is_one(s->u, r->ctx))
        for (slong c = 0; c < nc; c++)
            if (!fmpz_mpoly_divides(z + c, z + c, s->u, r->ctx))
                /* u is the gcd of the z: exact by construction */
                PC_UNREACHABLE("a meet's null vector is no multiple of its "
                               "gcd");
}

/* the other rows of G' must vanish too (else rank nc: fall back) */
static int ff_check_rows(MeetFF *s)
{
    const Ring *r = s->r;
    slong na = s->na, k = s->k;
    for (slong q = 0, b = 0; q < s->nr; q++) {
        if (b < s->rank && s->sel[b] == s->rl[q]) {
            b++;
            continue;
        }
        /* z_a was divided by rdiv[1], z_b by rdiv[0] */
        row_sum(s->u, s->G, s->rl[q], k, s->z, s->cl, s->nc, 0, na, 1, s->t,
                &s->big, r);
        if (!s->big)
            row_sum(s->ub, s->G, s->rl[q], k, s->z, s->cl, s->nc, na, k, 1,
                    s->t, &s->big, r);
        if (!s->big && ((s->rdiv_set[1] && too_big(s->u, s->rdiv + 1, r)) ||
                        (s->rdiv_set[0] && too_big(s->ub, s->rdiv + 0, r))))
            s->big = 1;
        if (s->big)
            return 0;
        if (s->rdiv_set[1])
            fmpz_mpoly_mul(s->u, s->u, s->rdiv + 1, r->ctx);
        if (s->rdiv_set[0])
            fmpz_mpoly_mul(s->ub, s->ub, s->rdiv + 0, r->ctx);
        fmpz_mpoly_add(s->u, s->u, s->ub, r->ctx);
        if (!fmpz_mpoly_is_zero(s->u, r->ctx))
            return 0;
    }
    return 1;
}

/* M row by row (rows are sorted base points), each from one side:
 * from[i] = 0 for sum z_a a, 1 for -sum z_b b */
static int ff_form_rows(MeetFF *s)
{
    const Ring *r = s->r;
    slong m = s->m, na = s->na, k = s->k, nc = s->nc;
    const slong *cl = s->cl;
    s->from = m <= 64 ? s->from_buf : flint_malloc((size_t)m);
    for (slong i = 0; i < m; i++) {
        fmpz_mpoly_struct *num = pteq_append(s->acc, s->rows[i], r);
        slong un = s->row_unit[i];
        if (un >= 0)
            s->from[i] = un < na;
        else
            s->from[i] = !(!covered(s->need, s->G, i, k, cl, nc, na, k) ||
                           (covered(s->need, s->G, i, k, cl, nc, 0, na) &&
                            row_cost(s->G, i, k, s->z, cl, nc, 0, na) <=
                                row_cost(s->G, i, k, s->z, cl, nc, na, k)));
        if (s->from[i])
            row_sum(num, s->G, i, k, s->z, cl, nc, na, k, -1, s->t, &s->big, r);
        else
            row_sum(num, s->G, i, k, s->z, cl, nc, 0, na, 1, s->t, &s->big, r);
        if (s->big)
            return 0;
    }
    return 1;
}

/* the rows from a side whose multipliers were divided out of the other
 * side's z: divided too (exact unless a unit row's z keeps the factor:
 * then the other rows are multiplied back) */
static int ff_divide_rows(MeetFF *s)
{
    const Ring *r = s->r;
    slong m = s->m;
    PointEqStruct *acc = s->acc;
    for (int sd = 0; sd < 2; sd++) {
        slong i;
        if (!s->rdiv_set[sd])
            continue;
        if (s->rq == NULL) {
            s->rq = flint_malloc((size_t)m * sizeof(fmpz_mpoly_struct));
            for (i = 0; i < m; i++)
                fmpz_mpoly_init(s->rq + i, r->ctx);
        }
        for (i = 0; i < m; i++)
            if (s->from[i] == sd &&
                !fmpz_mpoly_divides(s->rq + i, acc->terms[i].num, s->rdiv + sd,
                                    r->ctx))
                break;
        for (slong e = 0; e < m && !s->big; e++) {
            if (i == m && s->from[e] == sd) {
                fmpz_mpoly_swap(s->rq + e, acc->terms[e].num, r->ctx);
            } else if (i < m && s->from[e] != sd) {
                if (too_big(acc->terms[e].num, s->rdiv + sd, r))
                    s->big = 1;
                else
                    fmpz_mpoly_mul(acc->terms[e].num, acc->terms[e].num,
                                   s->rdiv + sd, r->ctx);
            }
        }
        if (s->big)
            return 0;
    }
    return 1;
}

/* M over its weight sum, the known factors divided out: 1 (res = M), or
 * 0 when M is at infinity or zero (the general path tells) */
static int ff_finish(MeetFF *s, PointEq res)
{
    const Ring *r = s->r;
    PointEqStruct *acc = s->acc;
    fmpz_mpoly_zero(acc->den, r->ctx);
    for (slong i = 0; i < s->m; i++)
        fmpz_mpoly_add(acc->den, acc->den, acc->terms[i].num, r->ctx);
    if (fmpz_mpoly_is_zero(acc->den, r->ctx)) {
        pteq_zero(acc, r);
        return 0; /* at infinity, or zero: the general path tells */
    }
    for (slong f = 0; f < s->nfac; f++)
        if (!s->used[f])
            pteq_divide_known(acc, s->fac + f, r);
    pteq_canonicalise(acc, r);
    pteq_swap(res, acc, r);
    meet_fast++;
    return 1;
}

int meet_fraction_free(PointEq res, const PointEq *cols, slong na, slong k,
                       const slong *rows, slong m, const Ring *r)
{
    MeetFF s;
    int found = 0;
    ff_init(&s, cols, na, k, rows, m, r);
    if (k <= MEET_MAX_COLS && ff_units(&s) && ff_reduce(&s) && ff_rows(&s)) {
        ff_need(&s);
        if (ff_null_vector(&s)) {
            ff_divide_multipliers(&s);
            if (s.nc >= 2)
                ff_content(&s);
            if (ff_check_rows(&s) && ff_form_rows(&s) && ff_divide_rows(&s))
                found = ff_finish(&s, res);
        }
    }
    int big = s.big;
    ff_clear(&s);
    return big ? -1 : found;
}
