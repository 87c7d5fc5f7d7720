/*
 * knots.c - the knots of a composite curve and the smoothness at each
 * (knots.h; docs/composite.md, "Knots and smoothness").
 *
 * After the derivation, on a finished output: find the sign kernels its
 * weights use (also inside other kernels' arguments) whose argument
 * depends on the param, find their zeros exactly, then at each zero
 * compare the one-sided derivatives order by order.  Everything is exact:
 * a one-sided form is the weight with the vanishing sign kernels replaced
 * by +-1 and the others by their values at the knot (knots_scan.c), then
 * differentiated by the chain rule (kernel_derivative) and evaluated at
 * t = t_k.  Called by the printers (format_json.c, knots_print.c).
 */
#include "compiler/derive/knots_int.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/mem.h"

/* a one-sided form with more terms (numerator and denominator) than this
 * is not differentiated further: eight derivatives of a large rational
 * function grow like its denominator's ninth power */
enum { KNOTS_MAX_TERMS = 4000 };

/* The one-sided derivatives of xs[0..nx-1] at a knot, order by order:
 * cur holds the side's derivative of order have - 1 (the side's form
 * before the first), val[j] the values of order j at the knot. */
typedef struct Side {
    RatFunStruct *cur;  // nx
    RatFunStruct **val; // KNOTS_MAX_ORDER + 1 rows of nx, made on demand
    int have;           // orders 0..have-1 are in val
    int failed;         // an order could not be made: 1 not finite or exact, 2
                        // too large (KNOTS_MAX_TERMS)
} Side;

typedef struct Sides {
    Scan *S;
    const RatFunStruct *t0; // the knot
    slong nx;
    Side s[2]; // [0] right, [1] left
} Sides;

static int sides_init(Sides *Q, Scan *S, const RatFunStruct *xs, slong nx,
                      const RatFun t0, const char **why)
{
    memset(Q, 0, sizeof *Q);
    Q->S = S;
    Q->t0 = t0;
    Q->nx = nx;
    for (int k = 0; k < 2; k++) {
        Q->s[k].cur = ratfun_vec_init(nx, S->r);
        Q->s[k].val = pc_xcalloc(KNOTS_MAX_ORDER + 1, sizeof *Q->s[k].val);
    }
    return knots_side_forms(S, t0, xs, nx, Q->s[0].cur, Q->s[1].cur, why);
}

static void sides_clear(Sides *Q)
{
    for (int k = 0; k < 2; k++) {
        ratfun_vec_clear(Q->s[k].cur, Q->nx, Q->S->r);
        for (int j = 0; j <= KNOTS_MAX_ORDER; j++)
            if (Q->s[k].val[j])
                ratfun_vec_clear(Q->s[k].val[j], Q->nx, Q->S->r);
        pc_free(Q->s[k].val);
    }
}

/* the values of order j on side k (0 right, 1 left), or NULL when they
 * are not finite or exact */
static const RatFunStruct *side_value(Sides *Q, int k, int j)
{
    Side *s = &Q->s[k];
    Scan *S = Q->S;
    while (!s->failed && s->have <= j) {
        RatFunStruct *v = ratfun_vec_init(Q->nx, S->r);
        int rc = 0;
        for (slong i = 0; i < Q->nx && rc == 0; i++) {
            if (ratfun_length(s->cur + i, S->r) > KNOTS_MAX_TERMS) {
                rc = 2;
                break;
            }
            if (s->have > 0)
                rc = kernel_derivative(S->K, s->cur + i, s->cur + i, S->t);
            if (rc == 0)
                rc = knots_eval_at(S, v + i, s->cur + i, Q->t0);
        }
        if (rc != 0) {
            ratfun_vec_clear(v, Q->nx, S->r);
            s->failed = rc == 2 ? 2 : 1;
            break;
        }
        s->val[s->have++] = v;
    }
    return s->have > j ? s->val[j] : NULL;
}

/* why side_value failed */
static const char *side_why(const Sides *Q)
{
    return Q->s[0].failed == 2 || Q->s[1].failed == 2
               ? "the one-sided derivatives grow too large to compare"
               : "a one-sided derivative is not finite or exact";
}

static int vec_is_zero(const RatFunStruct *v, slong n, const Ring *r)
{
    for (slong i = 0; i < n; i++)
        if (!ratfun_is_zero(v + i, r))
            return 0;
    return 1;
}

/* res = a - b, reduced; 0 or an error */
static int vec_sub(Kernels *K, RatFunStruct *res, const RatFunStruct *a,
                   const RatFunStruct *b, slong n)
{
    int rc = 0;
    for (slong i = 0; i < n && rc == 0; i++) {
        ratfun_sub(res + i, a + i, b + i, K->r);
        rc = kernel_reduce(K, res + i);
    }
    return rc;
}

/* 1 when u = lambda*v for one lambda (v != 0), *lambda set; 0 when not */
static int proportional(Kernels *K, RatFun lambda, const RatFunStruct *u,
                        const RatFunStruct *v, slong n)
{
    const Ring *r = K->r;
    slong i0 = -1;
    for (slong i = 0; i < n && i0 < 0; i++)
        if (!ratfun_is_zero(v + i, r))
            i0 = i;
    if (i0 < 0 || ratfun_div(lambda, u + i0, v + i0, r) != 0 ||
        kernel_reduce(K, lambda) != 0)
        return 0;
    RatFun w;
    ratfun_init(w, r);
    int ok = 1;
    for (slong i = 0; i < n && ok; i++) {
        ratfun_mul(w, lambda, v + i, r);
        ratfun_sub(w, w, u + i, r);
        ok = kernel_reduce(K, w) == 0 && ratfun_is_zero(w, r);
    }
    ratfun_clear(w, r);
    return ok;
}

/* The geometric order at a continuous knot (knots.h): the oriented
 * tangents, then the curvature condition where the curve is regular. */
static void geometric_order(Knot *k, Sides *Q)
{
    Scan *S = Q->S;
    const Ring *r = S->r;
    slong nx = Q->nx;
    int first[2] = {0, 0};
    for (int s = 0; s < 2; s++)
        for (int j = 1; j <= KNOTS_MAX_ORDER && !first[s]; j++) {
            const RatFunStruct *v = side_value(Q, s, j);
            if (!v) {
                k->geometric = -2;
                k->gwhy = side_why(Q);
                return;
            }
            if (!vec_is_zero(v, nx, r))
                first[s] = j;
        }
    k->geometric = 0;
    if (!first[0] || !first[1]) {
        k->gwhy = "the curve stands still on one side: no tangent there";
        return;
    }
    int p = first[0], q = first[1];
    RatFunStruct *tin = ratfun_vec_init(nx, r);
    RatFun lambda, mu;
    ratfun_init(lambda, r);
    ratfun_init(mu, r);
    /* the curve arrives along (-1)^(q+1) L_q and leaves along R_p */
    const RatFunStruct *lq = side_value(Q, 1, q);
    for (slong i = 0; i < nx; i++)
        if (q % 2)
            ratfun_set(tin + i, lq + i, r);
        else
            ratfun_neg(tin + i, lq + i, r);
    if (proportional(S->K, lambda, side_value(Q, 0, p), tin, nx)) {
        int sg = kernel_sign(S->K, lambda);
        if (sg == 2) {
            k->geometric = 1;
        } else if (sg != -2) {
            k->geometric = -2;
            k->gwhy = "the tangents are parallel, but their orientation "
                      "could not be compared";
        } else
            k->gwhy = "the curve turns back: its tangents are opposite";
    }
    if (k->geometric == 1 && (p > 1 || q > 1))
        k->gwhy = "G^2 is tested only where the first derivatives do not "
                  "vanish";
    else if (k->geometric == 1) {
        /* R_2 - lambda^2 L_2 parallel to L_1 */
        const RatFunStruct *r2 = side_value(Q, 0, 2);
        const RatFunStruct *l2 = side_value(Q, 1, 2);
        const RatFunStruct *l1 = side_value(Q, 1, 1);
        int ok = r2 && l2;
        for (slong i = 0; i < nx && ok; i++) {
            ratfun_mul(mu, lambda, lambda, r);
            ratfun_mul(mu, mu, l2 + i, r);
            ratfun_sub(tin + i, r2 + i, mu, r);
            ok = kernel_reduce(S->K, tin + i) == 0;
        }
        if (ok &&
            (vec_is_zero(tin, nx, r) || proportional(S->K, mu, tin, l1, nx))) {
            k->geometric = k->continuity > 2 ? k->continuity : 2;
            k->g_more = k->c_more;
        } else if (!ok)
            k->gwhy = side_why(Q);
    }
    ratfun_clear(mu, r);
    ratfun_clear(lambda, r);
    ratfun_vec_clear(tin, nx, r);
}

/* continuity, jump and geometric order at knot k */
static void analyse_knot(Knot *k, Scan *S, const RatFunStruct *xs, slong nx)
{
    const Ring *r = S->r;
    k->continuity = -1;
    k->jump_order = -1;
    k->geometric = -1;
    Sides Q;
    if (sides_init(&Q, S, xs, nx, k->t, &k->why) != 0) {
        sides_clear(&Q);
        return;
    }
    RatFunStruct *jump = ratfun_vec_init(nx, r);
    int j;
    for (j = 0; j <= KNOTS_MAX_ORDER; j++) {
        const RatFunStruct *R = side_value(&Q, 0, j);
        const RatFunStruct *L = side_value(&Q, 1, j);
        if (!R || !L || vec_sub(S->K, jump, R, L, nx) != 0) {
            k->why = side_why(&Q);
            break;
        }
        if (!vec_is_zero(jump, nx, r))
            break;
    }
    if (j <= KNOTS_MAX_ORDER && k->why) { /* known up to order j - 1 */
        k->continuity = j - 1;
        k->jump_order = j;
        ratfun_vec_clear(jump, nx, r);
    } else {
        k->analysed = 1;
        if (j > KNOTS_MAX_ORDER) {
            k->continuity = KNOTS_MAX_ORDER;
            k->c_more = 1;
            ratfun_vec_clear(jump, nx, r);
        } else {
            k->continuity = j - 1;
            k->jump_order = j;
            k->jump = jump;
            k->njump = nx;
        }
        if (k->continuity >= 0)
            geometric_order(k, &Q);
    }
    sides_clear(&Q);
}

/* ---- the output's knots ------------------------------------------------- */

/* the weights of output o: its terms' (or its scalar value) */
static const RatFunStruct *output_values(const Derived *d, slong o, slong *n)
{
    const DerivedOutput *out = &d->outputs[o];
    if (out->kind == KIND_SCALAR) {
        *n = 1;
        return out->scalar;
    }
    *n = out->eq->len;
    return out->w;
}

int knots_present(const Derived *d, slong o)
{
    const Kernels *K = d->kernels;
    if (!K || o < 0 || o >= d->noutputs)
        return 0;
    slong nx;
    const RatFunStruct *xs = output_values(d, o, &nx);
    unsigned char *used = pc_xcalloc((size_t)K->n + 1, 1);
    unsigned char *dep = pc_xcalloc((size_t)K->n + 1, 1);
    knots_fill_used(K, used, xs, nx);
    int any = 0;
    for (slong p = 0; p < d->nparams && !any; p++) {
        knots_fill_dep(K, dep, p);
        for (slong i = 0; i < K->n && !any; i++)
            any = used[i] && dep[i] && K->k[i].fn == KF_SIGN;
    }
    pc_free(dep);
    pc_free(used);
    return any;
}

/* an approximate value of a knot free of params and consts, or NAN */
static double approx(const Kernels *K, const RatFun x)
{
    fmpq_t q, lo, hi;
    fmpq_init(q);
    fmpq_init(lo);
    fmpq_init(hi);
    double v = NAN;
    int lo_open, hi_open;
    if (ratfun_get_fmpq(q, x, K->r))
        v = fmpq_get_d(q);
    else if (kernel_bounds(K, x, lo, &lo_open, hi, &hi_open) == 3)
        v = (fmpq_get_d(lo) + fmpq_get_d(hi)) / 2;
    fmpq_clear(hi);
    fmpq_clear(lo);
    fmpq_clear(q);
    return v;
}

/* 1 when knot x lies outside param t's declared range (numbers only) */
static int out_of_range(const Derived *d, slong t, const RatFun x)
{
    if (!d->has_range || !d->has_range[t])
        return 0;
    fmpq_t q, b;
    fmpq_init(q);
    fmpq_init(b);
    int out = 0;
    if (ratfun_get_fmpq(q, x, &d->ring)) {
        if (ratfun_get_fmpq(b, d->range + 2 * t, &d->ring) &&
            fmpq_cmp(q, b) < 0)
            out = 1;
        if (ratfun_get_fmpq(b, d->range + 2 * t + 1, &d->ring) &&
            fmpq_cmp(q, b) > 0)
            out = 1;
    }
    fmpq_clear(b);
    fmpq_clear(q);
    return out;
}

static int knot_cmp(const void *a, const void *b)
{
    const Knot *x = a, *y = b;
    if (isnan(x->approx) || isnan(y->approx))
        return isnan(x->approx) - isnan(y->approx);
    return (x->approx > y->approx) - (x->approx < y->approx);
}

/* the argument of a sign kernel, as text: "t^2 - 2" of "sign(t^2 - 2)" */
static char *sign_arg_text(const Kernel *k)
{
    const char *s = k->name;
    size_t n = strlen(s);
    if (n > 6 && strncmp(s, "sign(", 5) == 0 && s[n - 1] == ')')
        return pc_xstrndup(s + 5, n - 6);
    return pc_xstrdup(s);
}

void knots_analyse(KnotList *res, const Derived *d, slong o)
{
    memset(res, 0, sizeof *res);
    res->param = -1;
    if (!knots_present(d, o))
        return;
    const Kernels *K = d->kernels;
    const Ring *r = &d->ring;
    slong nx;
    const RatFunStruct *xs = output_values(d, o, &nx);
    /* the one param the output depends on */
    unsigned char *dep = pc_xcalloc((size_t)K->n + 1, 1);
    slong t = -1, nused = 0;
    for (slong p = 0; p < d->nparams; p++) {
        knots_fill_dep(K, dep, p);
        int u = 0;
        for (slong i = 0; i < nx && !u; i++)
            u = knots_uses(K, dep, xs + i, p);
        if (u) {
            t = p;
            nused++;
        }
    }
    pc_free(dep);
    if (nused != 1) {
        res->note = "the output depends on several params: its knots are "
                    "not analysed";
        return;
    }
    res->param = t;
    Scan S;
    knots_scan_init(&S, d, xs, nx, t);
    /* the distinct zeros, in the declared range */
    res->k = pc_xcalloc((size_t)S.nz + 1, sizeof *res->k);
    for (slong j = 0; j < S.nz; j++) {
        int seen = 0;
        for (slong i = 0; i < res->n && !seen; i++)
            seen = ratfun_equal(res->k[i].t, S.z[j].root, r);
        if (seen || out_of_range(d, t, S.z[j].root))
            continue;
        Knot *k = &res->k[res->n++];
        ratfun_init(k->t, r);
        ratfun_set(k->t, S.z[j].root, r);
        k->approx = approx(K, k->t);
    }
    qsort(res->k, (size_t)res->n, sizeof *res->k, knot_cmp);
    for (slong i = 0; i < res->n; i++)
        analyse_knot(&res->k[i], &S, xs, nx);
    res->nskip = S.nother;
    res->skip = pc_xcalloc((size_t)S.nother + 1, sizeof *res->skip);
    for (slong i = 0; i < S.nother; i++)
        res->skip[i] = sign_arg_text(&K->k[S.other[i]]);
    knots_scan_clear(&S);
}

void knots_clear(KnotList *res, const Derived *d)
{
    for (slong i = 0; i < res->n; i++) {
        ratfun_clear(res->k[i].t, &d->ring);
        if (res->k[i].jump)
            ratfun_vec_clear(res->k[i].jump, res->k[i].njump, &d->ring);
    }
    pc_free(res->k);
    for (slong i = 0; i < res->nskip; i++)
        pc_free(res->skip[i]);
    pc_free(res->skip);
    memset(res, 0, sizeof *res);
}

int knots_one_sided(RatFun res, const Derived *d, const RatFun x, slong var,
                    const RatFun t0, int side, ulong j)
{
    if (!d->kernels)
        return -1;
    Scan S;
    knots_scan_init(&S, d, x, 1, var);
    const char *why = NULL;
    RatFun v, w;
    ratfun_init(v, &d->ring);
    ratfun_init(w, &d->ring);
    int rc = side > 0 ? knots_side_forms(&S, t0, x, 1, v, w, &why)
                      : knots_side_forms(&S, t0, x, 1, w, v, &why);
    for (ulong i = 0; i < j && rc == 0; i++)
        rc = kernel_derivative(S.K, v, v, var);
    if (rc == 0)
        rc = knots_eval_at(&S, res, v, t0);
    ratfun_clear(w, &d->ring);
    ratfun_clear(v, &d->ring);
    knots_scan_clear(&S);
    return rc == 0 ? 0 : -1;
}
