/*
 * metric.c - the metric atoms dot, dist and angle, and coord: scalars
 * measured on combinations of base points through the kernels' distance
 * and coordinate variables (kernel.h).
 *
 * Called by eval (expr.c) for the metric builtins.
 */
#include "compiler/derive/derive_int.h"

#include <stdlib.h>

#include "base/check.h"
#include "base/diag.h"

/* ---- metric atoms: dot, dist, angle ------------------------------------- */

/* res = U . V for vectors U, V (weights summing to 0) over the base points:
 * with d_ij = |A_i A_j|,  U . V = -1/2 sum_{i != j} u_i v_j d_ij^2 */
static int metric_dot(Deriver *D, RatFun res, const PointEq U, const PointEq V,
                      const Node *n)
{
    const Ring *r = D->r;
    RatFun acc, d, t;
    ratfun_init(acc, r);
    ratfun_init(d, r);
    ratfun_init(t, r);
    int rc = 0;
    for (slong i = 0; i < U->len && rc == 0; i++)
        for (slong j = 0; j < V->len && rc == 0; j++) {
            slong a = U->terms[i].point, b = V->terms[j].point;
            if (a == b)
                continue;
            rc = kernel_dist(D->K, d, a, b);
            if (rc != 0)
                break;
            ratfun_mul(d, d, d, r);
            fmpz_mpoly_mul(t->num, U->terms[i].num, V->terms[j].num, r->ctx);
            fmpz_mpoly_one(t->den, r->ctx);
            ratfun_canonicalise(t, r);
            ratfun_mul(t, t, d, r);
            ratfun_add(acc, acc, t, r);
        }
    if (rc == 0) {
        fmpz_mpoly_mul(t->num, U->den, V->den, r->ctx);
        fmpz_mpoly_scalar_mul_si(t->num, t->num, -2, r->ctx);
        fmpz_mpoly_one(t->den, r->ctx);
        ratfun_canonicalise(t, r);
        ratfun_div(res, acc, t, r);
        rc = kernel_reduce(D->K, res);
    }
    ratfun_clear(t, r);
    ratfun_clear(d, r);
    ratfun_clear(acc, r);
    return rc ? derive_kernel_error(D, rc, n, NULL) : 0;
}

/* evaluates argument k of n as a combination of base points: 0, or -1
 * reported (an unsolved unknown point has no coordinates) */
static int metric_arg(Deriver *D, PointEq res, const Node *n, int k)
{
    if (derive_eval_point(D, res, derive_nth(n, k)) < 0)
        return -1;
    for (slong i = 0; i < res->len; i++)
        if (res->terms[i].point >= D->ucol0) {
            diag_error(D->diag, derive_nth(n, k)->span,
                       "%s() of an unknown point: solve it before measuring "
                       "it",
                       n->text);
            return -1;
        }
    return 0;
}

/* diff = P - Q must be a vector; 0 or -1 reported */
static int metric_difference(Deriver *D, PointEq diff, const PointEq P,
                             const PointEq Q, const Node *n, const Node *at)
{
    const Ring *r = D->r;
    pteq_sub(diff, P, Q, r);
    RatFun sum;
    ratfun_init(sum, r);
    pteq_weight_sum(sum, diff, r);
    kernel_reduce(D->K, sum);
    int ok = ratfun_is_zero(sum, r);
    if (!ok) {
        const char *what[2];
        for (int k = 0; k < 2; k++) {
            pteq_weight_sum(sum, k ? Q : P, r);
            kernel_reduce(D->K, sum);
            what[k] = ratfun_is_one(sum, r)    ? "a point"
                      : ratfun_is_zero(sum, r) ? "a vector"
                                               : "a combination of points";
        }
        int at_first = at == derive_nth(n, 0);
        diag_error(D->diag, at->span,
                   "%s() measures two points (or two vectors), but this "
                   "argument is %s and the %s %s",
                   n->text, what[at_first ? 0 : 1],
                   at_first ? "vertex" : "first", what[at_first ? 1 : 0]);
    }
    ratfun_clear(sum, r);
    return ok ? 0 : -1;
}

int derive_eval_metric(Deriver *D, Value *res, const Node *n)
{
    const Ring *r = D->r;
    PointEq P, Q, R, U, V;
    pteq_init(P, r);
    pteq_init(Q, r);
    pteq_init(R, r);
    pteq_init(U, r);
    pteq_init(V, r);
    RatFun uu, vv;
    ratfun_init(uu, r);
    ratfun_init(vv, r);
    res->is_point = 0;
    int st = -1, rc;
    switch ((Builtin)n->builtin) {
    case BI_DOT: {
        if (metric_arg(D, U, n, 0) < 0 || metric_arg(D, V, n, 1) < 0)
            break;
        RatFun sum;
        ratfun_init(sum, r);
        int bad = -1;
        for (int k = 0; k < 2 && bad < 0; k++) {
            pteq_weight_sum(sum, k ? V : U, r);
            kernel_reduce(D->K, sum);
            if (!ratfun_is_zero(sum, r))
                bad = k;
        }
        ratfun_clear(sum, r);
        if (bad >= 0) {
            diag_error(D->diag, derive_nth(n, bad)->span,
                       "dot() takes vectors (weights summing to 0), but this "
                       "is a point; use a difference of points, e.g. dot(P - "
                       "Q, R - Q)");
            break;
        }
        st = metric_dot(D, res->s, U, V, n);
        break;
    }
    case BI_DIST:
        if (metric_arg(D, P, n, 0) < 0 || metric_arg(D, Q, n, 1) < 0 ||
            metric_difference(D, U, P, Q, n, derive_nth(n, 1)) < 0 ||
            metric_dot(D, uu, U, U, n) < 0)
            break;
        rc = kernel_apply(D->K, res->s, KF_SQRT, uu, NULL);
        st = rc ? derive_kernel_error(D, rc, n, NULL) : 0;
        break;
    case BI_ANGLE:
        if (metric_arg(D, P, n, 0) < 0 || metric_arg(D, Q, n, 1) < 0 ||
            metric_arg(D, R, n, 2) < 0 ||
            metric_difference(D, U, P, Q, n, derive_nth(n, 0)) < 0 ||
            metric_difference(D, V, R, Q, n, derive_nth(n, 2)) < 0)
            break;
        if (pteq_is_zero(U, r) || pteq_is_zero(V, r)) {
            diag_error(D->diag, derive_nth(n, pteq_is_zero(U, r) ? 0 : 2)->span,
                       "angle() of coincident points: this point is the "
                       "vertex %s itself, so the angle is undefined",
                       "(the second argument)");
            break;
        }
        if (metric_dot(D, res->s, U, V, n) < 0 ||
            metric_dot(D, uu, U, U, n) < 0 || metric_dot(D, vv, V, V, n) < 0)
            break;
        /* acos(U.V / (|U| |V|)) */
        rc = kernel_apply(D->K, uu, KF_SQRT, uu, NULL);
        if (rc == 0)
            rc = kernel_apply(D->K, vv, KF_SQRT, vv, NULL);
        if (rc == 0) {
            ratfun_mul(uu, uu, vv, r);
            if (ratfun_div(res->s, res->s, uu, r) != 0)
                rc = KERNEL_EZERO;
        }
        if (rc == 0)
            rc = kernel_reduce(D->K, res->s);
        if (rc == 0)
            rc = kernel_apply(D->K, res->s, KF_ACOS, res->s, NULL);
        st = rc ? derive_kernel_error(D, rc, n, NULL) : 0;
        break;
    default:
        break;
    }
    ratfun_clear(vv, r);
    ratfun_clear(uu, r);
    pteq_clear(V, r);
    pteq_clear(U, r);
    pteq_clear(R, r);
    pteq_clear(Q, r);
    pteq_clear(P, r);
    return st;
}

/* coord(P, k) = sum_i w_i coord(A_i, k): linear in P, one kernel per base
 * point and k (kernel.h); P a point or a vector of base points */
int derive_eval_coord(Deriver *D, Value *res, const Node *n)
{
    const Ring *r = D->r;
    PointEq P;
    pteq_init(P, r);
    RatFun sum;
    ratfun_init(sum, r);
    res->is_point = 0;
    int st = derive_eval_point(D, P, derive_nth(n, 0));
    for (slong i = 0; st == 0 && i < P->len; i++)
        if (P->terms[i].point >= D->ucol0) {
            diag_error(D->diag, derive_nth(n, 0)->span,
                       "coord() of an unknown point: solve it before taking "
                       "its coordinates");
            st = -1;
        }
    if (st == 0) {
        pteq_weight_sum(sum, P, r);
        kernel_reduce(D->K, sum);
        if (!ratfun_is_zero(sum, r) && !ratfun_is_one(sum, r)) {
            char *txt = derive_show(sum, r);
            diag_error(D->diag, derive_nth(n, 0)->span,
                       "coord() takes a point (weights summing to 1) or a "
                       "vector (summing to 0), but the weights of this "
                       "argument sum to %s",
                       txt);
            flint_free(txt);
            st = -1;
        }
    }
    if (st == 0 && !D->K) /* the ring plan counts every coord() */
        PC_UNREACHABLE("no variable reserved for coord()");
    if (st == 0) {
        int rc = kernel_coord_pteq(D->K, res->s, P,
                                   strtol(derive_nth(n, 1)->text, NULL, 10));
        st = rc ? derive_kernel_error(D, rc, n, NULL) : 0;
    }
    ratfun_clear(sum, r);
    pteq_clear(P, r);
    return st;
}
