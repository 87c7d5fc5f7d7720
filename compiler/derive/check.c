/*
 * check.c - the `check` statements proved (compiler/check.h,
 * docs/language.md "Checks"), after every definition and solve.
 *
 * Each claim is decided exactly on the reduced values: a difference is
 * zero when its reduced form is (weights over the generic simplex, in the
 * kernels' normal form), V is parallel to U when V - lambda*U is zero for
 * the lambda one weight gives, a point lies on a flat when its difference
 * from the flat's first point is such a combination of the flat's
 * directions (Cramer's rule on a non-zero minor of the weights).  Joints
 * compare the jets of the two curves: C^k the derivatives 0..k; G^k the
 * beta-constraints of a reparametrisation u -> t = phi(u), phi' = beta1 >
 * 0 (Faa di Bruno: N^(j) = sum_i M^(i) B_{j,i}(beta1, ..., beta_{j-i+1}),
 * whose i = 1 term is M' beta_j, so N^(j) minus the other terms must be
 * parallel to M'); contact the same without the orientation.  A failed
 * claim is an error at the statement that prints what differs, reduced,
 * in the book's form; every claim's verdict goes to Derived.checks.
 */
#include "compiler/derive/derive_int.h"

#include <stdlib.h>
#include <string.h>

#include "base/budget.h"
#include "base/mem.h"
#include "compiler/check.h"
#include "compiler/derive/knots.h"
#include "compiler/print/format.h"

typedef struct Checker {
    Deriver *D;
    const Derived *d;
    const CheckInfo *c;
    const Stmt *st;
    Value *v; // per op, evaluated on demand
    char *ok; // per op: 1 evaluated, -1 failed
    int error;
} Checker;

/* the value of op i, evaluated once; NULL on an error (reported) */
static Value *op(Checker *K, int i)
{
    if (!K->ok[i]) {
        K->ok[i] = derive_eval(K->D, &K->v[i], K->c->ops[i]) < 0 ||
                           derive_reduce_value(K->D, &K->v[i], K->c->ops[i]) < 0
                       ? -1
                       : 1;
        const Sym *u = K->ok[i] > 0 ? derive_unsolved_in(K->D, &K->v[i]) : NULL;
        if (u) { /* a claim is about the known points */
            diag_error(K->D->diag, K->c->ops[i]->span,
                       "the check depends on the unknown '%s', which no "
                       "solve determines; expected 'solve ... for %s' "
                       "before it",
                       u->name, u->name);
            K->ok[i] = -1;
        }
    }
    if (K->ok[i] < 0)
        K->error = 1;
    return K->ok[i] > 0 ? &K->v[i] : NULL;
}

/* x in the book's form (format_output_rhs); the caller frees it */
static char *show(Checker *K, const Value *x)
{
    DerivedOutput o = {0};
    derive_output_fill(&o, "", K->st->span, x, K->D->src, K->D->r);
    char *s = format_output_rhs(K->d, &o, FMT_TEXT, -1);
    derive_output_clear(&o, K->D->r);
    return s;
}

/* res = x - s*y (s NULL: 1), reduced */
static int sub_mul(Checker *K, Value *res, const Value *x, const RatFun s,
                   const Value *y)
{
    const Ring *r = K->D->r;
    RatFun m;
    ratfun_init(m, r);
    if (s)
        ratfun_neg(m, s, r);
    else
        ratfun_set_si(m, -1, r);
    Value t;
    derive_value_init(&t, r);
    t.is_point = x->is_point;
    if (x->is_point) {
        pteq_addmul(t.p, x->p, y->p, m, r);
    } else {
        ratfun_mul(m, m, y->s, r);
        ratfun_add(t.s, x->s, m, r);
    }
    res->is_point = t.is_point;
    pteq_swap(res->p, t.p, r);
    ratfun_swap(res->s, t.s, r);
    derive_value_clear(&t, r);
    ratfun_clear(m, r);
    return derive_reduce_value(K->D, res, K->st->expr);
}

static int is_zero(const Value *x, const Ring *r)
{
    return x->is_point ? pteq_is_zero(x->p, r) : ratfun_is_zero(x->s, r);
}

/* x reduced in the kernels' normal form; 1 when it is zero */
static int nf_zero(Checker *K, RatFun x)
{
    if (K->D->K && K->D->K->nrel)
        (void)kernel_reduce(K->D->K, x); /* on failure: an equal form */
    return ratfun_is_zero(x, K->D->r);
}

/* the weight of base point i in x (a scalar: x itself for i = 0) */
static void weight(RatFun w, const Value *x, slong i, const Ring *r)
{
    if (x->is_point)
        pteq_get_weight(w, x->p, i, r);
    else if (i == 0)
        ratfun_set(w, x->s, r);
    else
        ratfun_zero(w, r);
}

static slong ncols(const Checker *K)
{
    return K->d->npoints ? K->d->npoints : 1;
}

/* 1 when v = lambda*u for some lambda (into lambda when not NULL), 0 when
 * not or when u is zero; -1 on an error */
static int parallel(Checker *K, const Value *u, const Value *v, RatFun lambda)
{
    const Ring *r = K->D->r;
    if (is_zero(u, r))
        return 0;
    RatFun a, b, l;
    ratfun_init(a, r);
    ratfun_init(b, r);
    ratfun_init(l, r);
    slong i = u->is_point ? u->p->terms[0].point : 0;
    weight(a, u, i, r);
    weight(b, v, i, r);
    int rc = ratfun_div(l, b, a, r) ? -1 : 0;
    Value res;
    derive_value_init(&res, r);
    if (rc == 0 && sub_mul(K, &res, v, l, u) < 0)
        rc = -1;
    else if (rc == 0)
        rc = is_zero(&res, r);
    if (rc == 1 && lambda)
        ratfun_set(lambda, l, r);
    derive_value_clear(&res, r);
    ratfun_clear(l, r);
    ratfun_clear(b, r);
    ratfun_clear(a, r);
    return rc;
}

/* a failed claim: the message (consumed) at the statement, and kept */
static void fail(Checker *K, DerivedCheck *out, char *msg)
{
    if (K->st->name) /* an instance of `check ... for i in a..b` */
        diag_error(K->D->diag, K->st->span, "check failed (for %s): %s",
                   K->st->name->text, msg);
    else
        diag_error(K->D->diag, K->st->span, "check failed: %s", msg);
    out->pass = 0;
    out->detail = msg;
}

/* the message "<pre>X<mid>Y<post>" of two values (y NULL: no mid, Y) */
static void fail2(Checker *K, DerivedCheck *out, const char *pre,
                  const Value *x, const char *mid, const Value *y,
                  const char *post)
{
    char *a = show(K, x), *b = y ? show(K, y) : NULL;
    fail(K, out,
         pc_xasprintf("%s%s%s%s%s", pre, a, y ? mid : "", y ? b : "", post));
    pc_free(b);
    pc_free(a);
}

/* L = R */
static void claim_equal(Checker *K, DerivedCheck *out)
{
    const Value *l = op(K, 0), *rv = l ? op(K, 1) : NULL;
    Value x;
    derive_value_init(&x, K->D->r);
    if (rv && sub_mul(K, &x, l, NULL, rv) == 0 && !is_zero(&x, K->D->r))
        fail2(K, out, "the two sides differ: left minus right is ", &x, "",
              NULL, ", not 0");
    else if (!rv)
        K->error = 1;
    derive_value_clear(&x, K->D->r);
}

/* u = p - a, the difference of a point from a flat's first point */
static int diff_from(Checker *K, Value *u, const Value *p, const Value *a)
{
    return sub_mul(K, u, p, NULL, a);
}

/* on(P, line(A, B)): P - A parallel to B - A (or zero); at ops
 * first..first+2 (tangent: its jet's point, then the line) */
static int on_line(Checker *K, DerivedCheck *out, const Value *p, int a,
                   const char *what)
{
    const Value *va = op(K, a), *vb = va ? op(K, a + 1) : NULL;
    if (!vb)
        return -1;
    Value u, dir;
    derive_value_init(&u, K->D->r);
    derive_value_init(&dir, K->D->r);
    int rc = -1;
    if (diff_from(K, &u, p, va) == 0 && diff_from(K, &dir, vb, va) == 0) {
        if (is_zero(&dir, K->D->r)) {
            diag_error(K->D->diag, K->c->ops[a + 1]->span,
                       "degenerate line: its two points coincide, so it "
                       "defines no line");
            K->error = 1;
        } else if (is_zero(&u, K->D->r) ||
                   (rc = parallel(K, &dir, &u, NULL)) == 1) {
            rc = 1;
        } else if (rc == 0) {
            char *pre = pc_xasprintf("%s is not on the line: it minus the "
                                     "line's first point is ",
                                     what);
            fail2(K, out, pre, &u, ", not a multiple of its direction ", &dir,
                  "");
            pc_free(pre);
        }
    }
    derive_value_clear(&dir, K->D->r);
    derive_value_clear(&u, K->D->r);
    return rc;
}

/* lambda, mu with u = lambda*d1 + mu*d2 from the first non-zero minor of
 * d1, d2's weights (Cramer); 1 found, 0 the directions are parallel */
static int plane_coords(Checker *K, RatFun lambda, RatFun mu, const Value *u,
                        const Value *d1, const Value *d2)
{
    const Ring *r = K->D->r;
    /* only the points where d1 or d2 has a weight give non-zero minors */
    slong n = 0, *col = pc_xmalloc(sizeof(slong) * (size_t)(ncols(K) + 1));
    for (slong i = 0; i < ncols(K); i++)
        if (pteq_has_point(d1->p, i) || pteq_has_point(d2->p, i))
            col[n++] = i;
    RatFun a1, a2, b1, b2, c1, c2, m, t;
    ratfun_init(a1, r), ratfun_init(a2, r), ratfun_init(b1, r);
    ratfun_init(b2, r), ratfun_init(c1, r), ratfun_init(c2, r);
    ratfun_init(m, r), ratfun_init(t, r);
    int found = 0;
    for (slong ii = 0; ii < n && !found; ii++)
        for (slong jj = ii + 1; jj < n && !found; jj++) {
            slong i = col[ii], j = col[jj];
            weight(a1, d1, i, r), weight(a2, d1, j, r);
            weight(b1, d2, i, r), weight(b2, d2, j, r);
            ratfun_mul(m, a1, b2, r);
            ratfun_mul(t, a2, b1, r);
            ratfun_sub(m, m, t, r);
            if (nf_zero(K, m))
                continue;
            found = 1;
            weight(c1, u, i, r), weight(c2, u, j, r);
            ratfun_mul(lambda, c1, b2, r); /* (c1 b2 - c2 b1)/m */
            ratfun_mul(t, c2, b1, r);
            ratfun_sub(lambda, lambda, t, r);
            (void)ratfun_div(lambda, lambda, m, r);
            ratfun_mul(mu, a1, c2, r); /* (a1 c2 - a2 c1)/m */
            ratfun_mul(t, a2, c1, r);
            ratfun_sub(mu, mu, t, r);
            (void)ratfun_div(mu, mu, m, r);
        }
    ratfun_clear(t, r), ratfun_clear(m, r), ratfun_clear(c2, r);
    ratfun_clear(c1, r), ratfun_clear(b2, r), ratfun_clear(b1, r);
    ratfun_clear(a2, r), ratfun_clear(a1, r);
    pc_free(col);
    return found;
}

/* on(P, plane(A, B, C)): P - A = lambda*(B - A) + mu*(C - A) */
static void claim_on_plane(Checker *K, DerivedCheck *out)
{
    const Ring *r = K->D->r;
    Value *p = op(K, 0), *a = p ? op(K, 1) : NULL, *b = a ? op(K, 2) : NULL,
          *c = b ? op(K, 3) : NULL;
    if (!c)
        return;
    Value u, d1, d2, res;
    RatFun l, m;
    derive_value_init(&u, r), derive_value_init(&d1, r);
    derive_value_init(&d2, r), derive_value_init(&res, r);
    ratfun_init(l, r), ratfun_init(m, r);
    if (diff_from(K, &u, p, a) < 0 || diff_from(K, &d1, b, a) < 0 ||
        diff_from(K, &d2, c, a) < 0) {
        K->error = 1;
    } else if (!plane_coords(K, l, m, &u, &d1, &d2)) {
        diag_error(K->D->diag, K->st->expr->span,
                   "degenerate plane: its three points are collinear");
        K->error = 1;
    } else if (sub_mul(K, &res, &u, l, &d1) < 0 ||
               sub_mul(K, &res, &res, m, &d2) < 0) {
        K->error = 1;
    } else if (!is_zero(&res, r)) {
        char *x = show(K, &u), *y = show(K, &d1), *z = show(K, &d2);
        fail(K, out,
             pc_xasprintf("the point is not on the plane: it minus the "
                          "plane's first point is %s, not a combination of "
                          "its directions %s and %s",
                          x, y, z));
        pc_free(z), pc_free(y), pc_free(x);
    }
    ratfun_clear(m, r), ratfun_clear(l, r);
    derive_value_clear(&res, r), derive_value_clear(&d2, r);
    derive_value_clear(&d1, r), derive_value_clear(&u, r);
}

/* parallel(U, V) */
static void claim_parallel(Checker *K, DerivedCheck *out)
{
    const Value *u = op(K, 0), *v = u ? op(K, 1) : NULL;
    if (!v)
        return;
    if (is_zero(u, K->D->r) || is_zero(v, K->D->r)) {
        fail(K, out,
             pc_xasprintf("the %s vector is zero: it has no direction",
                          is_zero(u, K->D->r) ? "first" : "second"));
        return;
    }
    int rc = parallel(K, u, v, NULL);
    if (rc == 0)
        fail2(K, out, "the vectors are not parallel: ", u, " and ", v, "");
    K->error |= rc < 0;
}

/* the first non-zero derivative of the jet starting at op j0 (orders
 * 1..len-1): its order, 0 when all vanish, -1 on an error */
static int first_nonzero(Checker *K, int j0, int len)
{
    for (int j = 1; j < len; j++) {
        const Value *x = op(K, j0 + j);
        if (!x)
            return -1;
        if (!is_zero(x, K->D->r))
            return j;
    }
    return 0;
}

/* tangent(M at t = v, line(A, B)): M(v) on the line and the first
 * derivative of M that does not vanish at v parallel to B - A (a cusp's
 * tangent is its second derivative's direction) */
static void claim_tangent(Checker *K, DerivedCheck *out)
{
    const CheckInfo *c = K->c;
    const Value *m0 = op(K, c->jet0);
    if (!m0 || on_line(K, out, m0, 0, "the curve's point") != 1)
        return;
    int j = first_nonzero(K, c->jet0, c->jetlen);
    if (j < 0)
        return;
    if (j == 0) {
        fail(K, out,
             pc_xasprintf("the curve's derivatives of orders 1 to %d vanish "
                          "at its point: it has no tangent there",
                          c->jetlen - 1));
        return;
    }
    Value dir;
    derive_value_init(&dir, K->D->r);
    const Value *a = op(K, 0), *b = op(K, 1), *mj = op(K, c->jet0 + j);
    int rc = diff_from(K, &dir, b, a) < 0 ? -1 : parallel(K, &dir, mj, NULL);
    if (rc == 0) {
        char *pre = pc_xasprintf("the curve is not tangent to the line: its "
                                 "derivative of order %d is ",
                                 j);
        fail2(K, out, pre, mj, ", not a multiple of the line's direction ",
              &dir, "");
        pc_free(pre);
    }
    K->error |= rc < 0;
    derive_value_clear(&dir, K->D->r);
}

/* contact(k, M at t = a, line(A, B)): M(a) on the line, and the first
 * derivative of M there that is not along the line (zero counts as along)
 * is of order k + 1: the contact is of order k */
static void claim_contact_line(Checker *K, DerivedCheck *out)
{
    const CheckInfo *c = K->c;
    const Value *m0 = op(K, c->jet0);
    if (!m0 || on_line(K, out, m0, 0, "the curve's point") != 1)
        return;
    Value dir;
    derive_value_init(&dir, K->D->r);
    int rc = diff_from(K, &dir, op(K, 1), op(K, 0)) < 0 ? -1 : 1, j = 1;
    const Value *mj = NULL;
    for (; rc == 1 && j < c->jetlen; j++) {
        mj = op(K, c->jet0 + j);
        rc = !mj ? -1 : is_zero(mj, K->D->r) ? 1 : parallel(K, &dir, mj, NULL);
        if (rc != 1)
            break;
    }
    out->found = j - 1;
    if (rc == 1)
        fail(K, out,
             pc_xasprintf("the contact with the line is of order %d or "
                          "more, not %d",
                          j - 1, c->order));
    else if (rc == 0 && j - 1 != c->order) {
        char *pre = pc_xasprintf("the contact with the line is of order %d, "
                                 "not %d: the curve's derivative of order %d "
                                 "is ",
                                 j - 1, c->order, j);
        fail2(K, out, pre, mj, ", not a multiple of the line's direction ",
              &dir, "");
        pc_free(pre);
    }
    K->error |= rc < 0;
    derive_value_clear(&dir, K->D->r);
}

/* "the curves are" at a joint of two, "the curve is" at a knot of one */
static const char *subject(const Checker *K)
{
    return K->c->knot_var >= 0 ? "the curve is" : "the curves are";
}

static const char *place(const Checker *K)
{
    return K->c->knot_var >= 0 ? "knot" : "joint";
}

/* Ck(M at t = a, N at u = b): the derivatives 0..k agree; Ck(M at t = a):
 * the one-sided derivatives (the jump is right minus left, as knots.h) */
static void claim_c(Checker *K, DerivedCheck *out)
{
    const CheckInfo *c = K->c;
    int knot = c->knot_var >= 0;
    Value x;
    derive_value_init(&x, K->D->r);
    out->found = c->order;
    for (int j = 0; j <= c->order; j++) {
        const Value *m = op(K, j), *n = m ? op(K, c->jetlen + j) : NULL;
        if (!n || (knot ? sub_mul(K, &x, n, NULL, m)
                        : sub_mul(K, &x, m, NULL, n)) < 0) {
            K->error = 1;
            break;
        }
        if (is_zero(&x, K->D->r))
            continue;
        out->found = j - 1;
        char *pre =
            !j ? pc_xasprintf("%s not continuous (not C0) at this %s: the %s "
                              "is ",
                              subject(K), place(K),
                              knot ? "right limit minus the left"
                                   : "first point minus the second")
            : knot ? pc_xasprintf("the curve is C%d, not C%d, at this knot: "
                                  "its derivative of order %d jumps by ",
                                  j - 1, c->order, j)
                   : pc_xasprintf("the curves are C%d, not C%d, at this "
                                  "joint: their derivatives of order %d "
                                  "differ by ",
                                  j - 1, c->order, j);
        fail2(K, out, pre, &x, "", NULL,
              !j     ? ""
              : knot ? " (right minus left)"
                     : " (first minus second)");
        pc_free(pre);
        break;
    }
    derive_value_clear(&x, K->D->r);
}

/* the partial Bell polynomials B[n][k], n, k <= j, of beta[1..j-1]:
 * B_{n,k} = sum_{m=1}^{n-k+1} C(n-1, m-1) beta_m B_{n-m,k-1} */
static void bell(RatFunStruct *B, const RatFunStruct *beta, int j,
                 const Ring *r)
{
    int w = j + 1;
    RatFun t;
    ratfun_init(t, r);
    for (int n = 0; n <= j; n++)
        for (int k = 0; k <= n; k++) {
            RatFunStruct *x = B + n * w + k;
            ratfun_set_si(x, n == 0 && k == 0, r);
            for (int m = 1, c = 1; k > 0 && m <= n - k + 1; m++) {
                ratfun_mul(t, beta + m, B + (n - m) * w + (k - 1), r);
                ratfun_mul_si(t, t, c, r);
                ratfun_add(x, x, t, r);
                c = c * (n - m) / m; /* C(n-1, m) from C(n-1, m-1) */
            }
        }
    ratfun_clear(t, r);
}

/* beta1 > 0 proved: 1, else 0 */
static int positive(Checker *K, const RatFun b)
{
    fmpq_t q;
    fmpq_init(q);
    int pos = ratfun_get_fmpq(q, b, K->D->r) ? fmpq_sgn(q) > 0
              : K->D->K                      ? kernel_sign(K->D->K, b) == 2
                                             : 0;
    fmpq_clear(q);
    return pos;
}

/* S_j = N^(j) - sum_{i=2..j} B_{j,i} M^(i) into s; -1 on an error */
static int beta_rest(Checker *K, Value *s, const RatFunStruct *beta, int j)
{
    const Ring *r = K->D->r;
    RatFunStruct *B = ratfun_vec_init((j + 1) * (j + 1), r);
    bell(B, beta, j, r);
    const Value *n = op(K, K->c->jetlen + j);
    int rc = n ? 0 : -1;
    if (n)
        derive_value_set(s, n, r);
    for (int i = 2; i <= j && rc == 0; i++) {
        const Value *m = op(K, i);
        rc = m ? sub_mul(K, s, s, B + j * (j + 1) + i, m) : -1;
    }
    ratfun_vec_clear(B, (j + 1) * (j + 1), r);
    return rc;
}

/* The geometric order of the joint, up to maxj: the largest j for which
 * N(u) = M(phi(u)) holds to order j (oriented: phi' > 0); -2 on an error.
 * Where it stops, *why says why (malloc'd). */
static int geometric(Checker *K, int oriented, int maxj, char **why)
{
    const Ring *r = K->D->r;
    const Value *m0 = op(K, 0), *n0 = m0 ? op(K, K->c->jetlen) : NULL;
    Value x;
    derive_value_init(&x, r);
    RatFunStruct *beta = ratfun_vec_init(maxj + 1, r);
    int j = 0, found = -2;
    if (!n0 || sub_mul(K, &x, m0, NULL, n0) < 0)
        goto done;
    found = -1;
    if (!is_zero(&x, r)) {
        char *a = show(K, &x);
        *why =
            pc_xasprintf("%s: the %s is %s",
                         K->c->knot_var >= 0 ? "it jumps" : "they do not meet",
                         K->c->knot_var >= 0 ? "left limit minus the right"
                                             : "first point minus the second",
                         a);
        pc_free(a);
        goto done;
    }
    for (found = 0, j = 1; j <= maxj; j++, found++) {
        const Value *m1 = op(K, 1);
        if (!m1 || beta_rest(K, &x, beta, j) < 0) {
            found = -2;
            break;
        }
        if (is_zero(m1, r) || (j == 1 && is_zero(&x, r))) {
            *why = pc_xasprintf(
                "the %s first derivative vanishes at the point, so its "
                "tangent is not decided",
                K->c->knot_var >= 0
                    ? (is_zero(m1, r) ? "left" : "right")
                    : (is_zero(m1, r) ? "first curve's" : "second curve's"));
            break;
        }
        int rc = parallel(K, m1, &x, beta + j);
        if (rc < 0) {
            found = -2;
            break;
        }
        if (rc == 1 && (j > 1 || !oriented || positive(K, beta + 1)))
            continue;
        char *a = show(K, &x), *b = show(K, m1);
        if (rc == 1)
            *why = pc_xasprintf("the second tangent %s is not a positive "
                                "multiple of the first %s",
                                a, b);
        else if (j == 1)
            *why =
                pc_xasprintf("the tangents %s and %s are not parallel", b, a);
        else
            *why = pc_xasprintf(
                "the second curve's derivative of order %d, less its part "
                "through the first curve's derivative%s of order%s 2%s%.0d "
                "(the chain rule), is %s, not parallel to the first tangent %s",
                j, j > 2 ? "s" : "", j > 2 ? "s" : "", j > 2 ? " to " : "",
                j > 2 ? j : 0, a, b);
        pc_free(b);
        pc_free(a);
        break;
    }
done:
    ratfun_vec_clear(beta, maxj + 1, r);
    derive_value_clear(&x, r);
    return found;
}

/* Gk(M at t = a, N at u = b), contact(k, ...) */
static void claim_geometric(Checker *K, DerivedCheck *out)
{
    const CheckInfo *c = K->c;
    int contact = c->kind == CK_CONTACT;
    char *why = NULL;
    int g = geometric(K, !contact, c->jetlen - 1, &why);
    out->found = g < -1 ? -1 : g;
    if (g == -2) {
        K->error = 1;
    } else if (!contact && g < c->order) {
        fail(K, out,
             g >= 0 ? pc_xasprintf("%s G%d, not G%d, at this %s: %s",
                                   subject(K), g, c->order, place(K), why)
                    : pc_xasprintf("%s not G%d at this %s: %s", subject(K),
                                   c->order, place(K), why));
    } else if (contact && g != c->order) {
        fail(K, out,
             g > c->order
                 ? pc_xasprintf("the contact is of order %d or more, not %d", g,
                                c->order)
             : g >= 0 ? pc_xasprintf("the contact is of order %d, not %d: %s",
                                     g, c->order, why)
                      : pc_xasprintf("no contact: %s", why));
    }
    pc_free(why);
}

/* the one-sided derivative of order j of x (a weight or a scalar) at t0,
 * side -1 the left, +1 the right (knots.h: every sign kernel that
 * vanishes at t0 takes its one-sided value); without kernels the
 * derivative itself.  0, or -1 when it is not exact there */
static int one_sided(Checker *K, RatFun res, const RatFun x, const RatFun t0,
                     int side, int j)
{
    const Ring *r = K->D->r;
    slong var = K->c->knot_var;
    if (K->d->kernels)
        return knots_one_sided(res, K->d, x, var, t0, side, (ulong)j);
    ratfun_derivative_n(res, x, var, (ulong)j, r);
    return ratfun_compose_var(res, res, var, t0, r) ? -1 : 0;
}

/* Ck(M at t = a) of one curve: its left jet into ops 0..len-1, its right
 * jet into ops len..2*len-1 (check.h); 0, or -1 (reported) */
static int knot_jets(Checker *K)
{
    const CheckInfo *c = K->c;
    const Ring *r = K->D->r;
    const Value *m = op(K, 2 * c->jetlen),
                *a = m ? op(K, 2 * c->jetlen + 1) : NULL;
    if (!a)
        return -1;
    RatFun x, y;
    ratfun_init(x, r);
    ratfun_init(y, r);
    int rc = 0;
    for (int i = 0; i < 2 * c->jetlen && rc == 0; i++) {
        Value *v = &K->v[i];
        v->is_point = m->is_point;
        for (slong k = 0; rc == 0 && k < (m->is_point ? m->p->len : 1); k++) {
            slong pt = m->is_point ? m->p->terms[k].point : 0;
            weight(x, m, pt, r);
            rc =
                one_sided(K, y, x, a->s, i < c->jetlen ? -1 : 1, i % c->jetlen);
            if (rc == 0 && m->is_point)
                pteq_set_weight(v->p, pt, y, r);
            else if (rc == 0)
                ratfun_set(v->s, y, r);
        }
        K->ok[i] = 1;
    }
    if (rc < 0)
        diag_error(K->D->diag, c->what[0],
                   "cannot take the one-sided derivatives of this curve at "
                   "its point: they are not finite there, or a knot's "
                   "argument is not analysed (docs/composite.md)");
    ratfun_clear(y, r);
    ratfun_clear(x, r);
    return rc;
}

/* order(M, t) = n: the largest degree in t of the numerators and the
 * denominator of M's reduced equation (a scalar: of its numerator and
 * denominator).  For a rational curve traced once (a proper
 * parametrisation) over a generic simplex, its order: a line meets it in
 * as many points as the degree of the equation in t that the line's
 * equation makes of it. */
static void claim_order(Checker *K, DerivedCheck *out)
{
    const Ring *r = K->D->r;
    const Value *m = op(K, 0);
    if (!m)
        return;
    if (K->D->K && (m->is_point ? kernel_uses_pteq(K->D->K, m->p, 1)
                                : kernel_uses(K->D->K, m->s, 1))) {
        diag_error(K->D->diag, K->c->what[0],
                   "order() needs a rational curve: this one holds "
                   "functions (sin, sqrt, abs, ...)");
        K->error = 1;
        return;
    }
    slong v = K->c->knot_var, deg;
    if (m->is_point) {
        deg = fmpz_mpoly_degree_si(m->p->den, v, r->ctx);
        for (slong i = 0; i < m->p->len; i++)
            deg = FLINT_MAX(
                deg, fmpz_mpoly_degree_si(m->p->terms[i].num, v, r->ctx));
    } else {
        deg = FLINT_MAX(fmpz_mpoly_degree_si(m->s->num, v, r->ctx),
                        fmpz_mpoly_degree_si(m->s->den, v, r->ctx));
    }
    deg = FLINT_MAX(deg, 0);
    out->found = (int)deg;
    if (deg != K->c->order) {
        char *pre =
            pc_xasprintf("the curve is of order %ld in %s, not %d: ", (long)deg,
                         r->names[v], K->c->order);
        fail2(K, out, pre, m, "", NULL, "");
        pc_free(pre);
    }
}

/* one check statement: its verdict into out */
static void run_check(Checker *K, DerivedCheck *out)
{
    switch (K->c->kind) {
    case CK_EQUAL:
        claim_equal(K, out);
        break;
    case CK_ON_LINE: {
        const Value *p = op(K, 0);
        if (p)
            (void)on_line(K, out, p, 1, "the point");
        break;
    }
    case CK_ON_PLANE:
        claim_on_plane(K, out);
        break;
    case CK_PARALLEL:
        claim_parallel(K, out);
        break;
    case CK_TANGENT:
        claim_tangent(K, out);
        break;
    case CK_C:
        claim_c(K, out);
        break;
    case CK_G:
    case CK_CONTACT:
        claim_geometric(K, out);
        break;
    case CK_ORDER:
        claim_order(K, out);
        break;
    case CK_CONTACT_LINE:
        claim_contact_line(K, out);
        break;
    }
}

void derive_checks(Deriver *D, Derived *d)
{
    const SemaInfo *info = D->info;
    const Ring *r = D->r;
    d->checks = pc_xcalloc((size_t)(info->nchecks ? info->nchecks : 1),
                           sizeof(DerivedCheck));
    for (int i = 0; i < info->nchecks && !D->expired; i++) {
        const Stmt *st = info->checks[i];
        Checker K = {.D = D, .d = d, .c = st->check, .st = st};
        K.v = pc_xmalloc(sizeof(Value) * (size_t)(K.c->nops ? K.c->nops : 1));
        K.ok = pc_xcalloc((size_t)(K.c->nops ? K.c->nops : 1), 1);
        for (int j = 0; j < K.c->nops; j++)
            derive_value_init(&K.v[j], r);
        DerivedCheck *out = &d->checks[d->nchecks];
        int col;
        source_locate(D->src, st->span.start, &out->line, &col);
        out->kind = check_kind_name(K.c->kind);
        out->order = K.c->kind >= CK_CONTACT ? K.c->order : 0;
        out->found = -1;
        out->pass = 1;
        int errors0 = D->diag->nerrors;
        budget_statement(D->src, st->span); /* for the budget's handlers */
        derive_assume_clear(D);
        if (K.c->knot_var < 0 || K.c->kind == CK_ORDER || knot_jets(&K) == 0)
            run_check(&K, out);
        else
            K.error = 1;
        if (K.error || (out->pass && D->diag->nerrors != errors0))
            out->pass = -1; /* an error, not a verdict */
        d->nchecks++;
        for (int j = 0; j < K.c->nops; j++)
            derive_value_clear(&K.v[j], r);
        pc_free(K.ok);
        pc_free(K.v);
    }
}
