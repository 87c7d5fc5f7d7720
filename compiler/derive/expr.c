/*
 * expr.c - eval: the exact value of an expression node.  Numbers, names
 * (memoised definitions, solved unknowns), arithmetic with its size guards,
 * powers and roots, and the constructions along, divide, meet, subst, diff
 * and bezier; the functions and metric atoms are in functions.c and
 * metric.c.
 *
 * The heart of the derive pass (pipeline.c): deriver.c and solve_stmt.c
 * evaluate each statement's expressions here.
 */
#include "compiler/derive/derive_int.h"

#include <stdlib.h>
#include <string.h>

#include "base/check.h"
#include "base/mem.h"
#include "base/stack.h"
#include "compiler/algebra/construct.h"

/* every argument of a flat is a point (sum 1) or a direction (sum 0),
 * and each flat has at least one point: 0, or -1 reported */
static int meet_check_flat(Deriver *D, const Node *flat, PointEq *args)
{
    const Ring *r = D->r;
    int st = 0;
    const char *what = flat->nargs == 2 ? "line" : "plane";
    RatFun sum;
    ratfun_init(sum, r);
    int points = 0, k = 0;
    for (const Node *a = flat->args; a && st == 0; a = a->next, k++) {
        pteq_weight_sum(sum, args[k], r);
        if (ratfun_is_one(sum, r)) {
            points++;
        } else if (!ratfun_is_zero(sum, r)) {
            char *txt = derive_show(sum, r);
            diag_error(D->diag, a->span,
                       "an argument of %s() must be a point (weights "
                       "summing to 1) or a direction (summing to 0); "
                       "its weights sum to %s",
                       what, txt);
            flint_free(txt);
            st = -1;
        }
    }
    if (st == 0 && points == 0) {
        diag_error(D->diag, flat->span,
                   "every argument of %s() is a vector; expected at "
                   "least one point",
                   what);
        st = -1;
    }
    ratfun_clear(sum, r);
    return st;
}

/* the error of a meet() that failed with ms (MEET_OK: none); 0, or -1
 * reported */
static int meet_report(Deriver *D, MeetStatus ms, const Node *n, const Node *fa,
                       const Node *fb, LinNormal *nf)
{
    int plane = fb->nargs == 3;
    int st = -1;
    switch (ms) {
    case MEET_OK:
        st = 0;
        break;
    case MEET_DEGENERATE_FIRST:
        diag_error(D->diag, fa->span,
                   "degenerate line: its two points coincide, so it "
                   "defines no line");
        break;
    case MEET_DEGENERATE_SECOND:
        diag_error(D->diag, fb->span,
                   plane ? "degenerate plane: its three points are "
                           "collinear, so they define no plane"
                         : "degenerate line: its two points coincide, "
                           "so it defines no line");
        break;
    case MEET_PARALLEL:
        diag_error(D->diag, n->span,
                   plane ? "the line is parallel to the plane: no "
                           "intersection"
                         : "lines in meet() are parallel: no "
                           "intersection");
        break;
    case MEET_COINCIDENT:
        diag_error(D->diag, n->span,
                   plane ? "the line lies in the plane: no single "
                           "intersection point"
                         : "lines in meet() coincide: no single "
                           "intersection point");
        break;
    case MEET_SKEW:
        diag_error(D->diag, n->span,
                   plane ? "the line and the plane do not lie in one "
                           "3-space: they do not meet"
                         : "lines in meet() are skew (not coplanar): "
                           "they do not meet");
        break;
    case MEET_TOO_BIG: /* or stopped by the time budget (meet_ff.c) */
        if (!derive_out_of_time(D, n))
            diag_error(D->diag, n->span,
                       "expression too large to compute exactly: an "
                       "intermediate product of meet() could need more than "
                       "128 MB of coefficients");
        break;
    case MEET_FAILED:
        derive_kernel_error(D, nf->err, n, NULL);
        break;
    case MEET_NO_POINT: /* checked above */
        PC_UNREACHABLE("a flat of meet() without a point");
    }
    return st;
}

static int eval_meet(Deriver *D, Value *res, const Node *n)
{
    const Ring *r = D->r;
    const Node *fa = derive_nth(n, 0), *fb = derive_nth(n, 1);
    PointEq pa[2], pb[3];
    int st = 0;
    for (int i = 0; i < 2; i++)
        pteq_init(pa[i], r);
    for (int i = 0; i < 3; i++)
        pteq_init(pb[i], r);
    int i = 0;
    for (const Node *a = fa->args; a; a = a->next)
        if (derive_eval_point(D, pa[i++], a) < 0)
            st = -1;
    i = 0;
    for (const Node *a = fb->args; a; a = a->next)
        if (derive_eval_point(D, pb[i++], a) < 0)
            st = -1;
    for (int f = 0; f < 2 && st == 0; f++)
        st = meet_check_flat(D, f ? fb : fa, f ? pb : pa);
    if (st == 0) {
        /* with functions that obey identities, in their normal form:
         * the fraction-free form is blind to them (flats parallel or
         * coincident only by sin^2 + cos^2 = 1 would meet "generically") */
        LinNormal nfs, *nf = derive_solve_normal_form(D, &nfs);
        int uses = 0;
        for (int k = 0; nf && k < fa->nargs; k++)
            uses |= kernel_uses_pteq(D->K, pa[k], 0);
        for (int k = 0; nf && k < fb->nargs; k++)
            uses |= kernel_uses_pteq(D->K, pb[k], 0);
        MeetStatus ms =
            uses ? construct_meet_general_nf(res->p, pa, fa->nargs, pb,
                                             fb->nargs, nf, r)
                 : construct_meet(res->p, pa, fa->nargs, pb, fb->nargs, r);
        st = meet_report(D, ms, n, fa, fb, nf);
    }
    for (int k = 0; k < 3; k++)
        pteq_clear(pb[k], r);
    for (int k = 0; k < 2; k++)
        pteq_clear(pa[k], r);
    res->is_point = 1;
    return st;
}

/* 1 when v (a point or a scalar) uses a distance to base point `point` */
static int value_measures_point(const Deriver *D, const Value *v, slong point)
{
    if (v->is_point || !D->K)
        return kernel_measures_point(D->K, v->p, point);
    PointEq one; /* the scalar as the weight of a point: its variables */
    pteq_init(one, D->r);
    pteq_set_weight(one, 0, v->s, D->r);
    int m = kernel_measures_point(D->K, one, point);
    pteq_clear(one, D->r);
    return m;
}

/* the coordinates' part of subst(E, A, P): every coord(A, k) in v becomes
 * coord(P, k) (kernel_subst_coords), in place; 0 or -1 reported at n */
static int subst_coords(Deriver *D, Value *v, const Sym *x, const PointEq P,
                        const Node *n)
{
    if (!D->K || x->kind != SYM_POINT)
        return 0;
    int rc = v->is_point
                 ? kernel_subst_coords_pteq(D->K, v->p, v->p, x->index, P)
                 : kernel_subst_coords(D->K, v->s, v->s, x->index, P);
    return rc ? derive_kernel_error(D, rc, n, derive_nth(n, 2)) : 0;
}

static int eval_subst(Deriver *D, Value *res, const Node *n)
{
    const Ring *r = D->r;
    const Node *e = derive_nth(n, 0), *x = derive_nth(n, 1),
               *by = derive_nth(n, 2);
    Value ve, vb;
    int st = 0;
    derive_value_init(&ve, r);
    derive_value_init(&vb, r);
    if (derive_eval(D, &ve, e) < 0 || derive_eval(D, &vb, by) < 0) {
        st = -1;
        goto done;
    }
    res->is_point = ve.is_point;
    int xpoint = x->sym->kind == SYM_POINT || x->sym->kind == SYM_UNKNOWN;
    if (xpoint && x->sym->kind == SYM_POINT &&
        value_measures_point(D, &ve, x->sym->index)) {
        diag_error(D->diag, x->span,
                   "subst() cannot replace base point '%s' here: the "
                   "expression measures distances to it (dist, dot, angle); "
                   "replace the point before measuring",
                   x->sym->name);
        st = -1;
        goto done;
    }
    if (xpoint && ve.is_point) {
        RatFun wx;
        ratfun_init(wx, r);
        pteq_get_weight(wx, ve.p, derive_point_col(D, x->sym), r);
        int big = !ratfun_is_zero(wx, r) &&
                  derive_too_big(D, derive_scalar_bits(vb.p, wx, r), n) < 0;
        ratfun_clear(wx, r);
        if (big) {
            st = -1;
            goto done;
        }
    } else if (!xpoint) {
        slong var = derive_scalar_var(D, x->sym);
        double bits = 0;
        if (ve.is_point)
            for (slong i = 0; i < ve.p->len; i++) {
                RatFunStruct w;
                pteq_weight_view(&w, ve.p, i);
                double b = ratfun_log2_bits_compose(&w, var, vb.s, r);
                bits = b > bits ? b : bits;
            }
        else
            bits = ratfun_log2_bits_compose(ve.s, var, vb.s, r);
        if (derive_too_big(D, bits, n) < 0) {
            st = -1;
            goto done;
        }
    }
    if (xpoint) {
        RatFun sum;
        ratfun_init(sum, r);
        pteq_weight_sum(sum, vb.p, r);
        if (!ratfun_is_one(sum, r)) {
            char *s = derive_show(sum, r);
            diag_error(D->diag, by->span,
                       "the replacement of %s '%s' must be a point, but its "
                       "weights sum to %s, not 1",
                       x->sym->kind == SYM_POINT ? "base point" : "unknown",
                       x->sym->name, s);
            flint_free(s);
            st = -1;
        } else if (subst_coords(D, &ve, x->sym, vb.p, n) < 0) {
            st = -1;
        } else if (ve.is_point) {
            pteq_subst_point(res->p, ve.p, derive_point_col(D, x->sym), vb.p,
                             r);
        } else {
            ratfun_set(res->s, ve.s, r);
        }
        ratfun_clear(sum, r);
    } else {
        slong var = derive_scalar_var(D, x->sym);
        int rc;
        if (D->K && (ve.is_point ? kernel_uses_pteq(D->K, ve.p, 1)
                                 : kernel_uses(D->K, ve.s, 1))) {
            /* also inside the functions: sin(t) -> sin(s) */
            if (derive_value_terms(&ve) > KERNEL_MAX_TERMS) {
                st = derive_kernel_error(D, KERNEL_EBIG, n, NULL);
                goto done;
            }
            rc = ve.is_point
                     ? kernel_compose_pteq(D->K, res->p, ve.p, var, vb.s)
                     : kernel_compose(D->K, res->s, ve.s, var, vb.s);
            if (rc != 0 && rc != RATFUN_EPOLE && rc != KERNEL_EZERO) {
                st = derive_kernel_error(D, rc, n, by);
                goto done;
            }
        } else {
            rc = ve.is_point ? pteq_compose_var(res->p, ve.p, var, vb.s, r)
                             : ratfun_compose_var(res->s, ve.s, var, vb.s, r);
        }
        if (rc != 0) {
            char *s = derive_show(vb.s, r);
            diag_error(D->diag, n->span,
                       "vanishing denominator: substituting %s = %s makes a "
                       "denominator of the expression identically zero",
                       x->sym->name, s);
            flint_free(s);
            st = -1;
        }
    }
done:
    derive_value_clear(&vb, r);
    derive_value_clear(&ve, r);
    return st;
}

static int eval_call(Deriver *D, Value *res, const Node *n)
{
    const Ring *r = D->r;
    int st = 0;
    if (derive_is_function(n->builtin)) /* pi among them */
        return derive_eval_function(D, res, n);
    if (n->builtin == BI_DOT || n->builtin == BI_DIST || n->builtin == BI_ANGLE)
        return derive_eval_metric(D, res, n);
    if (n->builtin == BI_COORD)
        return derive_eval_coord(D, res, n);
    if (n->builtin == BI_NATX || n->builtin == BI_NATY)
        return derive_eval_natural(D, res, n);
    switch ((Builtin)n->builtin) {
    case BI_ALONG:
    case BI_DIVIDE: {
        PointEq p, q;
        RatFun s;
        pteq_init(p, r);
        pteq_init(q, r);
        ratfun_init(s, r);
        if (derive_eval_point(D, p, derive_nth(n, 0)) < 0 ||
            derive_eval_point(D, q, derive_nth(n, 1)) < 0 ||
            derive_eval_scalar(D, s, derive_nth(n, 2)) < 0 ||
            derive_too_big(D, derive_scalar_bits(p, s, r), n) < 0 ||
            derive_too_big(D, derive_scalar_bits(q, s, r), n) < 0) {
            st = -1;
        } else if (n->builtin == BI_ALONG) {
            construct_along(res->p, p, q, s, r);
        } else if (construct_divide(res->p, p, q, s, r) != 0) {
            diag_error(D->diag, derive_nth(n, 2)->span,
                       "the simple ratio of divide() is identically -1: the "
                       "dividing point would be at infinity");
            st = -1;
        }
        ratfun_clear(s, r);
        pteq_clear(q, r);
        pteq_clear(p, r);
        res->is_point = 1;
        return st;
    }
    case BI_MEET:
        return eval_meet(D, res, n);
    case BI_SUBST:
        return eval_subst(D, res, n);
    case BI_DIFF: {
        const Node *x = derive_nth(n, 1), *order = derive_nth(n, 2);
        long k = order ? strtol(order->text, NULL, 10) : 1;
        slong var = derive_scalar_var(D, x->sym);
        if (derive_eval(D, res, derive_nth(n, 0)) < 0)
            return -1;
        /* the k-th derivative of n/d is N/d^(k+1): about the size of
         * x^(k+1) at most */
        double bits = 0;
        if (res->is_point)
            for (slong j = 0; j < res->p->len; j++) {
                RatFunStruct w;
                pteq_weight_view(&w, res->p, j);
                double b = ratfun_log2_bits_pow(&w, k + 1, r);
                bits = b > bits ? b : bits;
            }
        else
            bits = ratfun_log2_bits_pow(res->s, k + 1, r);
        if (derive_too_big(D, bits, n) < 0)
            return -1;
        if (D->K && (res->is_point ? kernel_uses_pteq(D->K, res->p, 1)
                                   : kernel_uses(D->K, res->s, 1))) {
            /* the chain rule through the functions, one order at a time */
            if (derive_value_terms(res) > KERNEL_MAX_TERMS)
                return derive_kernel_error(D, KERNEL_EBIG, n, NULL);
            for (long j = 0; j < k; j++) {
                int rc = res->is_point
                             ? kernel_derivative_pteq(D->K, res->p, res->p, var)
                             : kernel_derivative(D->K, res->s, res->s, var);
                if (rc != 0)
                    return derive_kernel_error(D, rc, n, NULL);
                if (derive_value_terms(res) > KERNEL_MAX_TERMS)
                    return derive_kernel_error(D, KERNEL_EBIG, n, NULL);
                if (derive_out_of_time(D, n))
                    return -1;
            }
            return 0;
        }
        if (res->is_point)
            pteq_derivative_n(res->p, res->p, var, (ulong)k, r);
        else
            ratfun_derivative_n(res->s, res->s, var, (ulong)k, r);
        return 0;
    }
    case BI_BEZIER: {
        slong npts = n->nargs - 1;
        RatFun s;
        PointEq *pts = pc_xmalloc(sizeof(PointEq) * (size_t)npts);
        ratfun_init(s, r);
        for (slong i = 0; i < npts; i++)
            pteq_init(pts[i], r);
        if (derive_eval_scalar(D, s, derive_nth(n, 0)) < 0)
            st = -1;
        for (slong i = 0; i < npts; i++)
            if (derive_eval_point(D, pts[i], derive_nth(n, (int)i + 1)) < 0)
                st = -1;
        if (st == 0)
            construct_bezier(res->p, s, (const PointEq *)pts, npts, r);
        for (slong i = 0; i < npts; i++)
            pteq_clear(pts[i], r);
        pc_free(pts);
        ratfun_clear(s, r);
        res->is_point = 1;
        return st;
    }
    default:
        /* sema reports unimplemented builtins and stray line()/plane() */
        PC_UNREACHABLE("a call sema should have refused");
    }
}

static int eval_pow(Deriver *D, Value *res, const Node *n)
{
    const Ring *r = D->r;
    RatFun e;
    fmpq_t q;
    int st = -1;
    ratfun_init(e, r);
    fmpq_init(q);
    if (derive_eval(D, res, n->lhs) < 0 || derive_eval_scalar(D, e, n->rhs) < 0)
        goto done;
    if (!ratfun_get_fmpq(q, e, r)) {
        diag_error(D->diag, n->rhs->span,
                   "expected a constant exponent; a power depending on "
                   "parameters or constants is transcendental");
        goto done;
    }
    if (!fmpz_is_one(fmpq_denref(q))) {
        /* x^(p/q): a root (kernel.h) */
        if (!fmpz_fits_si(fmpq_numref(q)) || !fmpz_fits_si(fmpq_denref(q)) ||
            labs(fmpz_get_si(fmpq_numref(q))) > 1000 ||
            fmpz_get_si(fmpq_denref(q)) > 1000) {
            diag_error(D->diag, n->rhs->span,
                       "exponent too large; expected p/q with |p| and q at "
                       "most 1000");
            goto done;
        }
        if (!D->K) /* the ring plan counted this power */
            PC_UNREACHABLE("no kernel slots for a root");
        if (res->s->num->length + res->s->den->length > KERNEL_MAX_TERMS) {
            derive_kernel_error(D, KERNEL_EBIG, n, NULL);
            goto done;
        }
        slong pn = fmpz_get_si(fmpq_numref(q)),
              qd = fmpz_get_si(fmpq_denref(q));
        int rc = kernel_pow_q(D->K, res->s, res->s, pn, qd);
        /* refused by the size guard (res unchanged): the root's power is
         * about x^(p/q), its bits those of x^|p| over q */
        if (rc == KERNEL_EBIG &&
            derive_too_big(
                D, ratfun_log2_bits_pow(res->s, labs(pn), r) - log2((double)qd),
                n) < 0)
            goto done;
        if (rc != 0) {
            derive_kernel_error(D, rc, n, n->lhs);
            goto done;
        }
        st = 0;
        goto done;
    }
    if (!fmpz_fits_si(fmpq_numref(q)) ||
        labs(fmpz_get_si(fmpq_numref(q))) > 1000) {
        diag_error(D->diag, n->rhs->span,
                   "exponent too large; expected an integer from -1000 "
                   "to 1000");
        goto done;
    }
    if (derive_too_big(
            D, ratfun_log2_bits_pow(res->s, fmpz_get_si(fmpq_numref(q)), r),
            n) < 0)
        goto done;
    if (ratfun_pow_si(res->s, res->s, fmpz_get_si(fmpq_numref(q)), r) != 0) {
        diag_error(D->diag, n->span,
                   "division by zero: a negative power of an expression "
                   "that is identically zero");
        goto done;
    }
    st = 0;
done:
    fmpq_clear(q);
    ratfun_clear(e, r);
    return st;
}

static int eval_node(Deriver *D, Value *res, const Node *n);

/* res receives the exact value of n; 0 or -1 (reported) */
int derive_eval(Deriver *D, Value *res, const Node *n)
{
    if (stack_low()) { /* a level takes 1-2 KiB: stop before the end */
        diag_error(D->diag, n->span, STACK_MESSAGE);
        return -1;
    }
    if (n->call_site) /* a user function's expansion: errors note the call */
        diag_push_context(D->diag, n->call_site->span, n->call_site->text);
    int st = eval_node(D, res, n);
    if (n->call_site)
        diag_pop_context(D->diag);
    if (st == 0 && n->kind != ND_NUM && n->kind != ND_NAME && n->kind != ND_NEG)
        st = derive_reduce_value(D, res, n);
    return st;
}

/* a name: a base point, a param or const (its ring variable), a
 * definition (its memoised value) or an unknown (its solution, once
 * solved) */
static int eval_name(Deriver *D, Value *res, const Node *n)
{
    const Ring *r = D->r;
    Sym *s = n->sym;
    switch (s->kind) {
    case SYM_POINT:
        res->is_point = 1;
        pteq_set_point(res->p, s->index, r);
        return 0;
    case SYM_PARAM:
    case SYM_CONST:
        res->is_point = 0;
        ratfun_gen(res->s, derive_scalar_var(D, s), r);
        return 0;
    case SYM_DEF:
        if (D->state[s->index] != 1)
            return -1; /* its own error was reported */
        derive_value_set(res, &D->defs[s->index], r);
        derive_assume_from(D, D->dassume[s->index]);
        return 0;
    case SYM_UNKNOWN:
        if (D->usolved[s->index])
            derive_assume_from(D, D->uassume[s->index]);
        res->is_point = s->is_point;
        if (!s->is_point && D->usolved[s->index])
            ratfun_set(res->s, D->ssol + s->index, r);
        else if (!s->is_point)
            ratfun_gen(res->s, derive_scalar_var(D, s), r);
        else if (D->usolved[s->index])
            pteq_set(res->p, D->usol[s->index], r);
        else
            pteq_set_point(res->p, D->ucol0 + s->index, r);
        return 0;
    }
    return -1;
}

/* a + b, a - b, a*b, a/b, within the size guards */
static int eval_arith(Deriver *D, Value *res, const Node *n)
{
    const Ring *r = D->r;
    Value b;
    int st = 0;
    derive_value_init(&b, r);
    if (derive_eval(D, res, n->lhs) < 0 || derive_eval(D, &b, n->rhs) < 0) {
        derive_value_clear(&b, r);
        return -1;
    }
    double bits =
        !res->is_point && !b.is_point ? ratfun_log2_bits_product(res->s, b.s, r)
        : res->is_point && b.is_point ? derive_pair_bits(res->p, b.p, r)
        : res->is_point               ? derive_scalar_bits(res->p, b.s, r)
                                      : derive_scalar_bits(b.p, res->s, r);
    if (derive_too_big(D, bits, n) < 0) {
        derive_value_clear(&b, r);
        return -1;
    }
    if (n->kind == ND_ADD) {
        if (res->is_point)
            pteq_add(res->p, res->p, b.p, r);
        else
            ratfun_add(res->s, res->s, b.s, r);
    } else if (n->kind == ND_SUB) {
        if (res->is_point)
            pteq_sub(res->p, res->p, b.p, r);
        else
            ratfun_sub(res->s, res->s, b.s, r);
    } else if (n->kind == ND_MUL) {
        if (res->is_point)
            pteq_scalar_mul(res->p, res->p, b.s, r);
        else if (b.is_point) {
            pteq_scalar_mul(res->p, b.p, res->s, r);
            res->is_point = 1;
        } else
            ratfun_mul(res->s, res->s, b.s, r);
    } else {
        int rc = res->is_point ? pteq_scalar_div(res->p, res->p, b.s, r)
                               : ratfun_div(res->s, res->s, b.s, r);
        if (rc != 0) {
            diag_error(D->diag, n->rhs->span,
                       "division by zero: the divisor is identically "
                       "zero");
            st = -1;
        }
    }
    derive_value_clear(&b, r);
    return st;
}

static int eval_node(Deriver *D, Value *res, const Node *n)
{
    const Ring *r = D->r;
    if (derive_out_of_time(D, n))
        return -1;
    switch (n->kind) {
    case ND_NUM: {
        fmpq_t q;
        fmpq_init(q);
        int st = ratfun_literal_fmpq(q, n->text);
        if (st == 0)
            ratfun_set_fmpq(res->s, q, r);
        else
            diag_error(D->diag, n->span,
                       "number out of range: expected an exponent within "
                       "+-1000");
        fmpq_clear(q);
        res->is_point = 0;
        return st;
    }
    case ND_NAME:
        return eval_name(D, res, n);
    case ND_NEG:
        if (derive_eval(D, res, n->lhs) < 0)
            return -1;
        if (res->is_point)
            pteq_neg(res->p, res->p, r);
        else
            ratfun_neg(res->s, res->s, r);
        return 0;
    case ND_ADD:
    case ND_SUB:
    case ND_MUL:
    case ND_DIV:
        return eval_arith(D, res, n);
    case ND_POW:
        res->is_point = 0;
        return eval_pow(D, res, n);
    case ND_CALL:
        return eval_call(D, res, n);
    case ND_INDEX: /* expand.c replaced every one */
    case ND_COMPR:
        return -1;
    }
    return -1;
}
