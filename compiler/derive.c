/*
 * derive.c - the pipeline front half: parse -> sema_check -> derive.
 *
 * Definitions are reduced in source order, each to an exact Value (a RatFun
 * for scalars, a PointEq for combinations of points), memoised per
 * definition; a name refers to the memoised value.  The weight sum of every
 * combination-valued definition is checked here (contract section 3): it must
 * be identically 1 (a point) or 0 (a vector).
 */
#include "compiler/derive.h"

#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <poll.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "base/arena.h"
#include "base/budget.h"
#include "compiler/construct.h"
#include "base/diag.h"
#include "compiler/expand.h"
#include "compiler/kernel.h"
#include "compiler/linsolve.h"
#include "base/mem.h"
#include "base/numfmt.h"
#include "compiler/sema.h"
#include "compiler/solve.h"
#include "grammar/parse.h"

/* the value of an expression while deriving */
typedef struct Value {
    int is_point; // 1: p holds a combination of base points; 0: s a scalar
    RatFun s;
    PointEq p;
} Value;

typedef struct Deriver {
    Diag *diag;
    const Ring *r;
    SemaInfo *info;
    Value *defs; // one per definition, initialised
    int *state;  // per definition: 0 not yet, 1 done, -1 failed
    const Source *src;
    double deadline;   // CLOCK_MONOTONIC seconds; 0: no time budget
    double max_seconds;
    int expired;       // the time budget ran out (reported once)
    FILE *verbose;     // progress per definition, or NULL
    slong ucol0;       // unknown k is point column ucol0 + k while unknown
    PointEq *usol;     // per unknown point: its solution, once solved
    RatFunStruct *ssol; // per unknown scalar: its solution, once solved
    slong *uvar;       // per unknown scalar: its ring variable (else -1)
    int *usolved;      // per unknown: 1 once its solve succeeded
    Kernels *K;        // functions and pi (kernel.h), or NULL: none used
    unsigned char **dassume; // per definition and per unknown: the ends of
    unsigned char **uassume; // declared bounds its value rests on (K->cur
                             // while it was derived, and its names'), or
                             // NULL: none
} Deriver;

/* the ring variable of a param, a const or an unknown scalar */
static slong scalar_var(const Deriver *D, const Sym *s)
{
    return s->kind == SYM_PARAM   ? s->index
           : s->kind == SYM_CONST ? D->info->nparams + s->index
                                  : D->uvar[s->index];
}

/* the point column of a base point or an (unsolved) unknown */
static slong point_col(const Deriver *D, const Sym *s)
{
    return s->kind == SYM_UNKNOWN ? D->ucol0 + s->index : s->index;
}

static double now_seconds(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* 1 (reported at n, once) when the time budget has run out */
static int out_of_time_at(Deriver *D, Span span)
{
    if (D->expired)
        return 1;
    if (D->deadline == 0 || now_seconds() <= D->deadline)
        return 0;
    char amount[48];
    budget_format_seconds(amount, sizeof amount, D->max_seconds);
    diag_error(D->diag, span,
               "the time budget of %s ran out while deriving this; raise it "
               "with --max-seconds",
               amount);
    D->expired = 1;
    return 1;
}

static int out_of_time(Deriver *D, const Node *n)
{
    return out_of_time_at(D, n->span);
}

static void value_init(Value *v, const Ring *r)
{
    v->is_point = 0;
    ratfun_init(v->s, r);
    pteq_init(v->p, r);
}

static void value_clear(Value *v, const Ring *r)
{
    pteq_clear(v->p, r);
    ratfun_clear(v->s, r);
}

static void value_set(Value *res, const Value *x, const Ring *r)
{
    res->is_point = x->is_point;
    if (x->is_point)
        pteq_set(res->p, x->p, r);
    else
        ratfun_set(res->s, x->s, r);
}

/* "0.3" -> 3/10, "1e-3" -> 1/1000 exactly.  The lexer guarantees the form
 * digits[.digits][e[+-]digits]. */
static int number_to_fmpq(fmpq_t q, const char *text)
{
    size_t n = strlen(text);
    char *digits = pc_xmalloc(n + 2);
    size_t k = 0;
    long frac = 0, exp10 = 0;
    int in_frac = 0;
    const char *c = text;
    for (; *c && *c != 'e' && *c != 'E'; c++) {
        if (*c == '.') {
            in_frac = 1;
            continue;
        }
        digits[k++] = *c;
        frac += in_frac;
    }
    if (k == 0)
        digits[k++] = '0';
    digits[k] = '\0';
    if (*c == 'e' || *c == 'E') {
        exp10 = strtol(c + 1, NULL, 10);
        if (exp10 > 1000 || exp10 < -1000) {
            free(digits);
            return -1;
        }
    }
    fmpz_set_str(fmpq_numref(q), digits, 10);
    fmpz_one(fmpq_denref(q));
    free(digits);
    long e = exp10 - frac;
    fmpz_t p;
    fmpz_init(p);
    fmpz_set_ui(p, 10);
    fmpz_pow_ui(p, p, (ulong)(e < 0 ? -e : e));
    if (e < 0)
        fmpz_set(fmpq_denref(q), p);
    else
        fmpz_mul(fmpq_numref(q), fmpq_numref(q), p);
    fmpz_clear(p);
    fmpq_canonicalise(q);
    return 0;
}

static int eval(Deriver *D, Value *res, const Node *n);

/* ---- size guards (ratfun.h) --------------------------------------------- */

/* the largest estimate over the weights of p times s */
static double scalar_bits(const PointEq p, const RatFun s, const Ring *r)
{
    double m = 0;
    for (slong i = 0; i < p->len; i++) {
        RatFunStruct w;
        pteq_weight_view(&w, p, i);
        double b = ratfun_log2_bits_product(&w, s, r);
        m = b > m ? b : m;
    }
    return m;
}

/* the largest estimate over the weights p and q share a point in */
static double pair_bits(const PointEq p, const PointEq q, const Ring *r)
{
    double m = 0;
    for (slong i = 0, j = 0; i < p->len && j < q->len;) {
        if (p->terms[i].point < q->terms[j].point) {
            i++;
        } else if (p->terms[i].point > q->terms[j].point) {
            j++;
        } else {
            RatFunStruct wp, wq;
            pteq_weight_view(&wp, p, i);
            pteq_weight_view(&wq, q, j);
            double b = ratfun_log2_bits_product(&wp, &wq, r);
            m = b > m ? b : m;
            i++;
            j++;
        }
    }
    return m;
}

/* 0, or -1 after reporting at n that a result could exceed the limit */
static int too_big(Deriver *D, double log2_bits, const Node *n)
{
    if (log2_bits <= RATFUN_MAX_LOG2_BITS)
        return 0;
    double mb = exp2(log2_bits - 23);
    if (mb < 1e6)
        diag_error(D->diag, n->span,
                   "expression too large to compute exactly: its result "
                   "could need about %.0f MB of coefficients (the limit is "
                   "%.0f MB)",
                   mb, exp2(RATFUN_MAX_LOG2_BITS - 23));
    else
        diag_error(D->diag, n->span,
                   "expression too large to compute exactly: its result "
                   "could need about 2^%.0f bytes of coefficients (the "
                   "limit is %.0f MB)",
                   log2_bits - 3, exp2(RATFUN_MAX_LOG2_BITS - 23));
    return -1;
}

/* evaluates a combination-valued argument */
static int eval_point(Deriver *D, PointEq res, const Node *n)
{
    Value v;
    value_init(&v, D->r);
    int st = eval(D, &v, n);
    if (st == 0)
        pteq_swap(res, v.p, D->r);
    value_clear(&v, D->r);
    return st;
}

static int eval_scalar(Deriver *D, RatFun res, const Node *n)
{
    Value v;
    value_init(&v, D->r);
    int st = eval(D, &v, n);
    if (st == 0)
        ratfun_swap(res, v.s, D->r);
    value_clear(&v, D->r);
    return st;
}

static const Node *nth(const Node *call, int i)
{
    const Node *a = call->args;
    while (a && i-- > 0)
        a = a->next;
    return a;
}

/* ---- assumptions: the declared bounds a value rests on ---------------- */

/* the bounds a value read here rests on are those of what reads it */
static void assume_from(Deriver *D, const unsigned char *a)
{
    slong nv = D->info->nparams + D->info->nconsts;
    for (slong v = 0; a && D->K && v < nv; v++)
        D->K->cur[v] |= a[v];
}

/* *dst |= what the kernels' sign proofs assumed since K->cur was cleared */
static void assume_into(Deriver *D, unsigned char **dst)
{
    slong nv = D->info->nparams + D->info->nconsts;
    slong v;
    if (!D->K)
        return;
    for (v = 0; v < nv && !D->K->cur[v]; v++)
        ;
    if (v == nv)
        return;
    if (!*dst)
        *dst = pc_xcalloc((size_t)nv, 1);
    for (v = 0; v < nv; v++)
        (*dst)[v] |= D->K->cur[v];
}

static void assume_clear(Deriver *D)
{
    if (D->K)
        memset(D->K->cur, 0, (size_t)D->K->first);
}

/* 1 when value v uses ring variable var (directly) */
static int value_has_var(const Value *v, slong var, const Ring *r)
{
    if (!v->is_point)
        return fmpz_mpoly_degree_si(v->s->num, var, r->ctx) > 0 ||
               fmpz_mpoly_degree_si(v->s->den, var, r->ctx) > 0;
    if (fmpz_mpoly_degree_si(v->p->den, var, r->ctx) > 0)
        return 1;
    for (slong i = 0; i < v->p->len; i++)
        if (fmpz_mpoly_degree_si(v->p->terms[i].num, var, r->ctx) > 0)
            return 1;
    return 0;
}

/* prints a RatFun into a diagnostic-sized string (caller frees) */
static char *show(const RatFun x, const Ring *r)
{
    return ratfun_get_str(x, r);
}


/* ---- functions (kernel.h) ------------------------------------------------ */

/* values that kernel operations take: beyond this many terms they are
 * refused (they work with per-weight gcds, sized for chapter 2's conics) */
enum { KERNEL_MAX_TERMS = 20000 };

static slong value_terms(const Value *v)
{
    if (!v->is_point)
        return v->s->num->length + v->s->den->length;
    slong n = v->p->den->length;
    for (slong i = 0; i < v->p->len; i++)
        n += v->p->terms[i].num->length;
    return n;
}

/* reports a failed kernel operation at n; returns -1 */
static int kernel_error_at(Deriver *D, int rc, Span at, Span arg);

static int kernel_error(Deriver *D, int rc, const Node *n, const Node *arg)
{
    return kernel_error_at(D, rc, n->span, (arg ? arg : n)->span);
}

/* the message of a failed kernel operation (rc: KERNEL_E*) at `at` (a
 * domain error at `arg`); returns -1 */
static int kernel_error_at(Deriver *D, int rc, Span at, Span arg)
{
    switch (rc) {
    case KERNEL_EFULL:
        diag_error(D->diag, at,
                   "too many distinct functions in one scheme: at most %ld "
                   "different function values (kernels) fit; split the "
                   "scheme",
                   (long)D->K->cap);
        break;
    case KERNEL_EDOMAIN:
        diag_error(D->diag, arg, "%s",
                   D->K->why ? D->K->why : "argument outside the domain");
        break;
    case KERNEL_ETIME:
        if (!D->expired && !out_of_time_at(D, at))
            diag_error(D->diag, at, "the time budget ran out while "
                                         "deriving this");
        break;
    case KERNEL_EBIG:
        diag_error(D->diag, at,
                   "expression too large for the functions' identities: "
                   "a value of over %d terms, or an intermediate result of "
                   "over %d",
                   KERNEL_MAX_TERMS, KERNEL_MAX_WORK_TERMS);
        break;
    case RATFUN_EPOLE:
    case KERNEL_EZERO:
    default:
        diag_error(D->diag, at,
                   "vanishing denominator: a denominator of this expression "
                   "is identically zero by the identities of its functions "
                   "(sin^2 + cos^2 = 1, sqrt(x)^2 = x, ...)");
        break;
    }
    return -1;
}

/* the normal form of a value (kernel.h); -1 reported at n */
static int reduce_value(Deriver *D, Value *v, const Node *n)
{
    if (!D->K || D->K->nrel == 0)
        return 0;
    if (v->is_point ? !kernel_uses_pteq(D->K, v->p, 0)
                    : !kernel_uses(D->K, v->s, 0))
        return 0;
    if (value_terms(v) > KERNEL_MAX_TERMS)
        return kernel_error(D, KERNEL_EBIG, n, NULL);
    int rc = v->is_point ? kernel_reduce_pteq(D->K, v->p)
                         : kernel_reduce(D->K, v->s);
    return rc ? kernel_error(D, rc, n, NULL) : 0;
}

/* the kernels' normal form as solve's and linsolve's hook (LinNormal) */
static int normal_form(void *ctx, RatFunStruct *x)
{
    return kernel_reduce((Kernels *)ctx, x);
}

/* the normal form for a system whose entries may hold kernels with
 * identities, or NULL when none can occur */
static LinNormal *solve_normal_form(Deriver *D, LinNormal *nf)
{
    if (!D->K || D->K->nrel == 0)
        return NULL;
    nf->reduce = normal_form;
    nf->ctx = D->K;
    nf->err = 0;
    return nf;
}

/* the scalar functions are the builtins BI_SQRT .. BI_SIGN (sema.h) */
static int is_function(int b)
{
    return b >= BI_SQRT && b <= BI_SIGN;
}

/* the kernel a function builtin makes directly (tan, tanh and abs are
 * rewritten, kernel.h), or -1 */
static int builtin_kernel(int b)
{
    switch ((Builtin)b) {
    case BI_SQRT: return KF_SQRT;
    case BI_SIN: return KF_SIN;
    case BI_COS: return KF_COS;
    case BI_ASIN: return KF_ASIN;
    case BI_ACOS: return KF_ACOS;
    case BI_ATAN: return KF_ATAN;
    case BI_ATAN2: return KF_ATAN2;
    case BI_SINH: return KF_SINH;
    case BI_COSH: return KF_COSH;
    case BI_EXP: return KF_EXP;
    case BI_LN: return KF_LN;
    case BI_SIGN: return KF_SIGN;
    default: return -1;
    }
}

/* ---- metric atoms: dot, dist, angle ------------------------------------- */

/* res = U . V for vectors U, V (weights summing to 0) over the base points:
 * with d_ij = |A_i A_j|,  U . V = -1/2 sum_{i != j} u_i v_j d_ij^2 */
static int metric_dot(Deriver *D, RatFun res, const PointEq U,
                      const PointEq V, const Node *n)
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
    return rc ? kernel_error(D, rc, n, NULL) : 0;
}

/* evaluates argument k of n as a combination of base points: 0, or -1
 * reported (an unsolved unknown point has no coordinates) */
static int metric_arg(Deriver *D, PointEq res, const Node *n, int k)
{
    if (eval_point(D, res, nth(n, k)) < 0)
        return -1;
    for (slong i = 0; i < res->len; i++)
        if (res->terms[i].point >= D->ucol0) {
            diag_error(D->diag, nth(n, k)->span,
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
        int at_first = at == nth(n, 0);
        diag_error(D->diag, at->span,
                   "%s() measures two points (or two vectors), but this "
                   "argument is %s and the %s %s",
                   n->text, what[at_first ? 0 : 1],
                   at_first ? "vertex" : "first", what[at_first ? 1 : 0]);
    }
    ratfun_clear(sum, r);
    return ok ? 0 : -1;
}

static int eval_metric(Deriver *D, Value *res, const Node *n)
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
            diag_error(D->diag, nth(n, bad)->span,
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
            metric_difference(D, U, P, Q, n, nth(n, 1)) < 0 ||
            metric_dot(D, uu, U, U, n) < 0)
            break;
        rc = kernel_apply(D->K, res->s, KF_SQRT, uu, NULL);
        st = rc ? kernel_error(D, rc, n, NULL) : 0;
        break;
    case BI_ANGLE:
        if (metric_arg(D, P, n, 0) < 0 || metric_arg(D, Q, n, 1) < 0 ||
            metric_arg(D, R, n, 2) < 0 ||
            metric_difference(D, U, P, Q, n, nth(n, 0)) < 0 ||
            metric_difference(D, V, R, Q, n, nth(n, 2)) < 0)
            break;
        if (pteq_is_zero(U, r) || pteq_is_zero(V, r)) {
            diag_error(D->diag, nth(n, pteq_is_zero(U, r) ? 0 : 2)->span,
                       "angle() of coincident points: this point is the "
                       "vertex %s itself, so the angle is undefined",
                       "(the second argument)");
            break;
        }
        if (metric_dot(D, res->s, U, V, n) < 0 || metric_dot(D, uu, U, U, n) < 0 ||
            metric_dot(D, vv, V, V, n) < 0)
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
        st = rc ? kernel_error(D, rc, n, NULL) : 0;
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

/* a scalar function applied: sqrt(x), sin(x), ..., pi */
static int eval_function(Deriver *D, Value *res, const Node *n)
{
    const Ring *r = D->r;
    Kernels *K = D->K;
    res->is_point = 0;
    if (n->builtin == BI_PI) {
        int rc = kernel_apply(K, res->s, KF_PI, NULL, NULL);
        return rc ? kernel_error(D, rc, n, NULL) : 0;
    }
    RatFun x, y;
    ratfun_init(x, r);
    ratfun_init(y, r);
    int rc = 0, st = 0;
    if (eval_scalar(D, x, nth(n, 0)) < 0 ||
        (n->builtin == BI_ATAN2 && eval_scalar(D, y, nth(n, 1)) < 0)) {
        st = -1;
        goto done;
    }
    if (x->num->length + x->den->length + y->num->length + y->den->length >
        KERNEL_MAX_TERMS) {
        st = kernel_error(D, KERNEL_EBIG, n, NULL);
        goto done;
    }
    switch ((Builtin)n->builtin) {
    case BI_ABS:
        rc = kernel_abs(K, res->s, x);
        break;
    case BI_TAN:
    case BI_TANH: { /* sin/cos, sinh/cosh */
        int hyp = n->builtin == BI_TANH;
        rc = kernel_apply(K, y, hyp ? KF_SINH : KF_SIN, x, NULL);
        if (rc == 0)
            rc = kernel_apply(K, x, hyp ? KF_COSH : KF_COS, x, NULL);
        if (rc == 0 && ratfun_div(res->s, y, x, r) != 0) {
            diag_error(D->diag, nth(n, 0)->span,
                       "tan() of this argument is infinite: its cosine is "
                       "identically zero");
            st = -1;
        }
        if (rc == 0 && st == 0)
            rc = kernel_reduce(K, res->s);
        break;
    }
    default:
        rc = kernel_apply(K, res->s, (KernelFn)builtin_kernel(n->builtin), x,
                          n->builtin == BI_ATAN2 ? y : NULL);
        break;
    }
    if (rc != 0)
        st = kernel_error(D, rc, n, nth(n, 0));
done:
    ratfun_clear(y, r);
    ratfun_clear(x, r);
    return st;
}

/* counts what may need kernels: function calls and powers that are not
 * integer literals, subst() and diff(), pi */
static void count_kernel_uses(const Node *n, slong *calls, slong *ops,
                              slong *pis, slong *metric)
{
    if (!n)
        return;
    if (n->kind == ND_CALL) {
        if (n->builtin == BI_DOT || n->builtin == BI_DIST ||
            n->builtin == BI_ANGLE)
            ++*metric;
        if (n->builtin == BI_PI)
            ++*pis;
        else if (is_function(n->builtin))
            ++*calls;
        else if (n->builtin == BI_SUBST || n->builtin == BI_DIFF)
            ++*ops;
        for (const Node *a = n->args; a; a = a->next)
            count_kernel_uses(a, calls, ops, pis, metric);
    }
    /* a power that is not a whole number may be a root: t^(1/2), and
     * t^0.5 (a decimal exponent) */
    if (n->kind == ND_POW &&
        (n->rhs->kind != ND_NUM || strpbrk(n->rhs->text, ".eE")))
        ++*calls;
    count_kernel_uses(n->lhs, calls, ops, pis, metric);
    count_kernel_uses(n->rhs, calls, ops, pis, metric);
}

static int eval_meet(Deriver *D, Value *res, const Node *n)
{
    const Ring *r = D->r;
    const Node *fa = nth(n, 0), *fb = nth(n, 1);
    PointEq pa[2], pb[3];
    int st = 0;
    for (int i = 0; i < 2; i++)
        pteq_init(pa[i], r);
    for (int i = 0; i < 3; i++)
        pteq_init(pb[i], r);
    int i = 0;
    for (const Node *a = fa->args; a; a = a->next)
        if (eval_point(D, pa[i++], a) < 0)
            st = -1;
    i = 0;
    for (const Node *a = fb->args; a; a = a->next)
        if (eval_point(D, pb[i++], a) < 0)
            st = -1;
    /* every argument of a flat is a point (sum 1) or a direction (sum 0),
     * and each flat has at least one point */
    for (int f = 0; f < 2 && st == 0; f++) {
        const Node *flat = f ? fb : fa;
        PointEq *args = f ? pb : pa;
        const char *what = flat->nargs == 2 ? "line" : "plane";
        RatFun sum;
        ratfun_init(sum, r);
        int points = 0, k = 0;
        for (const Node *a = flat->args; a && st == 0; a = a->next, k++) {
            pteq_weight_sum(sum, args[k], r);
            if (ratfun_is_one(sum, r)) {
                points++;
            } else if (!ratfun_is_zero(sum, r)) {
                char *txt = show(sum, r);
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
    }
    if (st == 0) {
        /* with functions that obey identities, in their normal form:
         * the fraction-free form is blind to them (flats parallel or
         * coincident only by sin^2 + cos^2 = 1 would meet "generically") */
        LinNormal nfs, *nf = solve_normal_form(D, &nfs);
        int uses = 0;
        for (int k = 0; nf && k < fa->nargs; k++)
            uses |= kernel_uses_pteq(D->K, pa[k], 0);
        for (int k = 0; nf && k < fb->nargs; k++)
            uses |= kernel_uses_pteq(D->K, pb[k], 0);
        MeetStatus ms =
            uses ? construct_meet_general_nf(res->p, pa, fa->nargs, pb,
                                             fb->nargs, nf, r)
                 : construct_meet(res->p, pa, fa->nargs, pb, fb->nargs, r);
        int plane = fb->nargs == 3;
        st = -1;
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
        case MEET_TOO_BIG:
            diag_error(D->diag, n->span,
                       "expression too large to compute exactly: an "
                       "intermediate product of meet() could need more than "
                       "128 MB of coefficients");
            break;
        case MEET_FAILED:
            kernel_error(D, nf->err, n, NULL);
            break;
        case MEET_NO_POINT: /* checked above */
            diag_error(D->diag, n->span,
                       "internal error: a flat of meet() without a point");
            break;
        }
    }
    for (int k = 0; k < 3; k++)
        pteq_clear(pb[k], r);
    for (int k = 0; k < 2; k++)
        pteq_clear(pa[k], r);
    res->is_point = 1;
    return st;
}

/* 1 when v (a point or a scalar) uses a distance to base point `point` */
static int value_measures_point(const Deriver *D, const Value *v,
                                slong point)
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
    return rc ? kernel_error(D, rc, n, nth(n, 2)) : 0;
}

static int eval_subst(Deriver *D, Value *res, const Node *n)
{
    const Ring *r = D->r;
    const Node *e = nth(n, 0), *x = nth(n, 1), *by = nth(n, 2);
    Value ve, vb;
    int st = 0;
    value_init(&ve, r);
    value_init(&vb, r);
    if (eval(D, &ve, e) < 0 || eval(D, &vb, by) < 0) {
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
        pteq_get_weight(wx, ve.p, point_col(D, x->sym), r);
        int big = !ratfun_is_zero(wx, r) &&
                  too_big(D, scalar_bits(vb.p, wx, r), n) < 0;
        ratfun_clear(wx, r);
        if (big) {
            st = -1;
            goto done;
        }
    } else if (!xpoint) {
        slong var = scalar_var(D, x->sym);
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
        if (too_big(D, bits, n) < 0) {
            st = -1;
            goto done;
        }
    }
    if (xpoint) {
        RatFun sum;
        ratfun_init(sum, r);
        pteq_weight_sum(sum, vb.p, r);
        if (!ratfun_is_one(sum, r)) {
            char *s = show(sum, r);
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
            pteq_subst_point(res->p, ve.p, point_col(D, x->sym), vb.p, r);
        } else {
            ratfun_set(res->s, ve.s, r);
        }
        ratfun_clear(sum, r);
    } else {
        slong var = scalar_var(D, x->sym);
        int rc;
        if (D->K && (ve.is_point ? kernel_uses_pteq(D->K, ve.p, 1)
                                 : kernel_uses(D->K, ve.s, 1))) {
            /* also inside the functions: sin(t) -> sin(s) */
            if (value_terms(&ve) > KERNEL_MAX_TERMS) {
                st = kernel_error(D, KERNEL_EBIG, n, NULL);
                goto done;
            }
            rc = ve.is_point
                     ? kernel_compose_pteq(D->K, res->p, ve.p, var, vb.s)
                     : kernel_compose(D->K, res->s, ve.s, var, vb.s);
            if (rc != 0 && rc != RATFUN_EPOLE && rc != KERNEL_EZERO) {
                st = kernel_error(D, rc, n, by);
                goto done;
            }
        } else {
            rc = ve.is_point ? pteq_compose_var(res->p, ve.p, var, vb.s, r)
                             : ratfun_compose_var(res->s, ve.s, var, vb.s, r);
        }
        if (rc != 0) {
            char *s = show(vb.s, r);
            diag_error(D->diag, n->span,
                       "vanishing denominator: substituting %s = %s makes a "
                       "denominator of the expression identically zero",
                       x->sym->name, s);
            flint_free(s);
            st = -1;
        }
    }
done:
    value_clear(&vb, r);
    value_clear(&ve, r);
    return st;
}

/* coord(P, k) = sum_i w_i coord(A_i, k): linear in P, one kernel per base
 * point and k (kernel.h); P a point or a vector of base points */
static int eval_coord(Deriver *D, Value *res, const Node *n)
{
    const Ring *r = D->r;
    PointEq P;
    pteq_init(P, r);
    RatFun sum;
    ratfun_init(sum, r);
    res->is_point = 0;
    int st = eval_point(D, P, nth(n, 0));
    for (slong i = 0; st == 0 && i < P->len; i++)
        if (P->terms[i].point >= D->ucol0) {
            diag_error(D->diag, nth(n, 0)->span,
                       "coord() of an unknown point: solve it before taking "
                       "its coordinates");
            st = -1;
        }
    if (st == 0) {
        pteq_weight_sum(sum, P, r);
        kernel_reduce(D->K, sum);
        if (!ratfun_is_zero(sum, r) && !ratfun_is_one(sum, r)) {
            char *txt = show(sum, r);
            diag_error(D->diag, nth(n, 0)->span,
                       "coord() takes a point (weights summing to 1) or a "
                       "vector (summing to 0), but the weights of this "
                       "argument sum to %s",
                       txt);
            flint_free(txt);
            st = -1;
        }
    }
    if (st == 0 && !D->K) { /* derive_source counts every coord() */
        diag_error(D->diag, n->span,
                   "internal error: no variable reserved for coord()");
        st = -1;
    } else if (st == 0) {
        int rc = kernel_coord_pteq(D->K, res->s, P,
                                   strtol(nth(n, 1)->text, NULL, 10));
        st = rc ? kernel_error(D, rc, n, NULL) : 0;
    }
    ratfun_clear(sum, r);
    pteq_clear(P, r);
    return st;
}

/* the distinct k of the coord(P, k) in n, added to ks[0 .. *nks - 1] */
static void count_coord_indices(const Node *n, long **ks, slong *nks)
{
    if (!n)
        return;
    if (n->kind == ND_CALL && n->builtin == BI_COORD && n->nargs == 2 &&
        nth(n, 1)->kind == ND_NUM) {
        long k = strtol(nth(n, 1)->text, NULL, 10);
        slong i = 0;
        while (i < *nks && (*ks)[i] != k)
            i++;
        if (i == *nks) {
            *ks = pc_xrealloc(*ks, sizeof(long) * (size_t)(*nks + 1));
            (*ks)[(*nks)++] = k;
        }
    }
    if (n->kind == ND_CALL)
        for (const Node *a = n->args; a; a = a->next)
            count_coord_indices(a, ks, nks);
    count_coord_indices(n->lhs, ks, nks);
    count_coord_indices(n->rhs, ks, nks);
}

static int eval_call(Deriver *D, Value *res, const Node *n)
{
    const Ring *r = D->r;
    int st = 0;
    if (is_function(n->builtin) || n->builtin == BI_PI)
        return eval_function(D, res, n);
    if (n->builtin == BI_DOT || n->builtin == BI_DIST ||
        n->builtin == BI_ANGLE)
        return eval_metric(D, res, n);
    if (n->builtin == BI_COORD)
        return eval_coord(D, res, n);
    switch ((Builtin)n->builtin) {
    case BI_ALONG:
    case BI_DIVIDE: {
        PointEq p, q;
        RatFun s;
        pteq_init(p, r);
        pteq_init(q, r);
        ratfun_init(s, r);
        if (eval_point(D, p, nth(n, 0)) < 0 ||
            eval_point(D, q, nth(n, 1)) < 0 ||
            eval_scalar(D, s, nth(n, 2)) < 0 ||
            too_big(D, scalar_bits(p, s, r), n) < 0 ||
            too_big(D, scalar_bits(q, s, r), n) < 0) {
            st = -1;
        } else if (n->builtin == BI_ALONG) {
            construct_along(res->p, p, q, s, r);
        } else if (construct_divide(res->p, p, q, s, r) != 0) {
            diag_error(D->diag, nth(n, 2)->span,
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
        const Node *x = nth(n, 1), *order = nth(n, 2);
        long k = order ? strtol(order->text, NULL, 10) : 1;
        slong var = scalar_var(D, x->sym);
        if (eval(D, res, nth(n, 0)) < 0)
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
        if (too_big(D, bits, n) < 0)
            return -1;
        if (D->K && (res->is_point ? kernel_uses_pteq(D->K, res->p, 1)
                                   : kernel_uses(D->K, res->s, 1))) {
            /* the chain rule through the functions, one order at a time */
            if (value_terms(res) > KERNEL_MAX_TERMS)
                return kernel_error(D, KERNEL_EBIG, n, NULL);
            for (long j = 0; j < k; j++) {
                int rc = res->is_point
                             ? kernel_derivative_pteq(D->K, res->p, res->p, var)
                             : kernel_derivative(D->K, res->s, res->s, var);
                if (rc != 0)
                    return kernel_error(D, rc, n, NULL);
                if (value_terms(res) > KERNEL_MAX_TERMS)
                    return kernel_error(D, KERNEL_EBIG, n, NULL);
                if (out_of_time(D, n))
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
        if (eval_scalar(D, s, nth(n, 0)) < 0)
            st = -1;
        for (slong i = 0; i < npts; i++)
            if (eval_point(D, pts[i], nth(n, (int)i + 1)) < 0)
                st = -1;
        if (st == 0)
            construct_bezier(res->p, s, (const PointEq *)pts, npts, r);
        for (slong i = 0; i < npts; i++)
            pteq_clear(pts[i], r);
        free(pts);
        ratfun_clear(s, r);
        res->is_point = 1;
        return st;
    }
    default:
        /* sema reports unimplemented builtins and stray line()/plane() */
        diag_error(D->diag, n->span, "internal error: unexpected %s()",
                   n->text);
        return -1;
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
    if (eval(D, res, n->lhs) < 0 || eval_scalar(D, e, n->rhs) < 0)
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
        if (!D->K) { /* cannot happen: sema counted this power */
            diag_error(D->diag, n->span, "internal error: no kernel slots");
            goto done;
        }
        if (res->s->num->length + res->s->den->length > KERNEL_MAX_TERMS) {
            kernel_error(D, KERNEL_EBIG, n, NULL);
            goto done;
        }
        int rc = kernel_pow_q(D->K, res->s, res->s,
                              fmpz_get_si(fmpq_numref(q)),
                              fmpz_get_si(fmpq_denref(q)));
        if (rc != 0) {
            kernel_error(D, rc, n, n->lhs);
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
    if (too_big(D, ratfun_log2_bits_pow(res->s, fmpz_get_si(fmpq_numref(q)), r),
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

/* res receives the exact value of n; 0 or -1 (reported) */
static int eval_node(Deriver *D, Value *res, const Node *n);

static int eval(Deriver *D, Value *res, const Node *n)
{
    int st = eval_node(D, res, n);
    if (st == 0 && n->kind != ND_NUM && n->kind != ND_NAME &&
        n->kind != ND_NEG)
        st = reduce_value(D, res, n);
    return st;
}

static int eval_node(Deriver *D, Value *res, const Node *n)
{
    const Ring *r = D->r;
    if (out_of_time(D, n))
        return -1;
    switch (n->kind) {
    case ND_NUM: {
        fmpq_t q;
        fmpq_init(q);
        int st = number_to_fmpq(q, n->text);
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
    case ND_NAME: {
        Sym *s = n->sym;
        switch (s->kind) {
        case SYM_POINT:
            res->is_point = 1;
            pteq_set_point(res->p, s->index, r);
            return 0;
        case SYM_PARAM:
        case SYM_CONST:
            res->is_point = 0;
            ratfun_gen(res->s, scalar_var(D, s), r);
            return 0;
        case SYM_DEF:
            if (D->state[s->index] != 1)
                return -1; /* its own error was reported */
            value_set(res, &D->defs[s->index], r);
            assume_from(D, D->dassume[s->index]);
            return 0;
        case SYM_UNKNOWN:
            if (D->usolved[s->index])
                assume_from(D, D->uassume[s->index]);
            res->is_point = s->is_point;
            if (!s->is_point && D->usolved[s->index])
                ratfun_set(res->s, D->ssol + s->index, r);
            else if (!s->is_point)
                ratfun_gen(res->s, scalar_var(D, s), r);
            else if (D->usolved[s->index])
                pteq_set(res->p, D->usol[s->index], r);
            else
                pteq_set_point(res->p, D->ucol0 + s->index, r);
            return 0;
        }
        return -1;
    }
    case ND_NEG:
        if (eval(D, res, n->lhs) < 0)
            return -1;
        if (res->is_point)
            pteq_neg(res->p, res->p, r);
        else
            ratfun_neg(res->s, res->s, r);
        return 0;
    case ND_ADD:
    case ND_SUB:
    case ND_MUL:
    case ND_DIV: {
        Value b;
        int st = 0;
        value_init(&b, r);
        if (eval(D, res, n->lhs) < 0 || eval(D, &b, n->rhs) < 0) {
            value_clear(&b, r);
            return -1;
        }
        double bits = !res->is_point && !b.is_point
                          ? ratfun_log2_bits_product(res->s, b.s, r)
                      : res->is_point && b.is_point ? pair_bits(res->p, b.p, r)
                      : res->is_point ? scalar_bits(res->p, b.s, r)
                                      : scalar_bits(b.p, res->s, r);
        if (too_big(D, bits, n) < 0) {
            value_clear(&b, r);
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
        value_clear(&b, r);
        return st;
    }
    case ND_POW:
        res->is_point = 0;
        return eval_pow(D, res, n);
    case ND_CALL:
        return eval_call(D, res, n);
    case ND_INDEX: /* expand.c replaced every one */
        return -1;
    }
    return -1;
}

/* terms, total degree and largest coefficient bits of a value */
static void value_size(const Value *v, slong *terms, slong *deg, slong *bits,
                       const Ring *r)
{
    const fmpz_mpoly_struct *p[2];
    slong n = 0;
    *terms = *deg = *bits = 0;
    for (slong i = -1; i < (v->is_point ? v->p->len : 1); i++) {
        if (v->is_point) {
            p[0] = i < 0 ? v->p->den : v->p->terms[i].num;
            n = 1;
        } else {
            if (i >= 0)
                break;
            p[0] = v->s->num;
            p[1] = v->s->den;
            n = 2;
        }
        for (slong k = 0; k < n; k++) {
            *terms += p[k]->length;
            slong dg = fmpz_mpoly_total_degree_si(p[k], r->ctx);
            slong bt = FLINT_ABS(fmpz_mpoly_max_bits(p[k]));
            *deg = FLINT_MAX(*deg, dg);
            *bits = FLINT_MAX(*bits, bt);
        }
    }
}

/* derives definition i and checks its weight sum */
static void derive_def(Deriver *D, Sym *s)
{
    const Ring *r = D->r;
    Value *v = &D->defs[s->index];
    double t0 = D->verbose ? now_seconds() : 0;
    budget_statement(D->src, s->def->expr->span);
    assume_clear(D);
    if (s->bad || D->expired || eval(D, v, s->def->expr) < 0) {
        D->state[s->index] = -1;
        return;
    }
    D->state[s->index] = 1;
    assume_into(D, &D->dassume[s->index]);
    if (D->verbose) {
        slong terms, deg, bits;
        int line, col;
        value_size(v, &terms, &deg, &bits, r);
        source_locate(D->src, s->def->expr->span.start, &line, &col);
        pc_fprintf(D->verbose,
                "%s:%d: %s: %.3f ms, %s, %ld terms, degree %ld, %ld-bit "
                "coefficients\n",
                D->src->name, line, s->name, 1e3 * (now_seconds() - t0),
                v->is_point ? "combination of points" : "scalar",
                (long)terms, (long)deg, (long)bits);
        fflush(D->verbose);
    }
    if (!v->is_point)
        return;
    RatFun sum;
    ratfun_init(sum, r);
    pteq_weight_sum(sum, v->p, r);
    if (D->K) /* (on failure sum keeps an equal, unreduced form) */
        (void)kernel_reduce(D->K, sum);
    if (!ratfun_is_zero(sum, r) && !ratfun_is_one(sum, r)) {
        char *txt = show(sum, r);
        if (!ratfun_is_constant(sum, r) && kernel_uses(D->K, sum, 1))
            diag_error(D->diag, s->def->expr->span,
                       "the weights of %s could not be proved to sum to 0 "
                       "(a vector) or 1 (a point): their sum is %s, and the "
                       "identities pointcalc applies (sin^2 + cos^2 = 1, "
                       "cosh^2 - sinh^2 = 1, sqrt(x)^2 = x) do not reduce it "
                       "to a number; write the point as C + (vector), with "
                       "the weights of the vector summing to 0 term by term",
                       s->name, txt);
        else
        diag_error(D->diag, s->def->expr->span,
                   "weights of %s sum to %s, not 0 (a vector) or 1 (a "
                   "point)",
                   s->name, txt);
        flint_free(txt);
        D->state[s->index] = -1;
    }
    ratfun_clear(sum, r);
}

/* replaces the unknown scalar var by its solution v in every value derived
 * so far (a value whose denominator vanishes then keeps its form: its
 * definition was generic in var, and the outputs are checked later) */
static void substitute_solved_scalar(Deriver *D, slong var, const RatFun v,
                                     const Stmt *st)
{
    const Ring *r = D->r;
    for (int i = 0; i < D->info->ndefs; i++) {
        Value *d = &D->defs[i];
        int rc;
        if (D->state[i] != 1)
            continue;
        if (value_has_var(d, var, r)) /* the solve's assumptions too */
            assume_into(D, &D->dassume[i]);
        if (d->is_point)
            rc = pteq_compose_var(d->p, d->p, var, v, r);
        else
            rc = ratfun_compose_var(d->s, d->s, var, v, r);
        if (rc != 0) {
            const Sym *s = D->info->defs[i];
            char *txt = show(v, r);
            diag_error(D->diag, s->def->expr->span,
                       "vanishing denominator: with the solution %s = %s, a "
                       "denominator of '%s' is identically zero",
                       r->names[var], txt, s->name);
            diag_note(D->diag, st->span, "'%s' is solved here",
                      r->names[var]);
            flint_free(txt);
            D->state[i] = -1;
        } else if (reduce_value(D, d, D->info->defs[i]->def->expr) < 0) {
            D->state[i] = -1;
        }
    }
    for (int k = 0; k < D->info->nunknowns; k++) {
        if (!D->usolved[k])
            continue;
        int rc;
        if (D->info->unknowns[k]->is_point)
            rc = pteq_compose_var(D->usol[k], D->usol[k], var, v, r);
        else
            rc = ratfun_compose_var(D->ssol + k, D->ssol + k, var, v, r);
        /* (a failure leaves the solution as it is, valid but not in the
         * normal form: what uses it is reduced and reports) */
        if (rc == 0 && D->K && D->K->nrel)
            (void)(D->info->unknowns[k]->is_point
                       ? kernel_reduce_pteq(D->K, D->usol[k])
                       : kernel_reduce(D->K, D->ssol + k));
    }
}

/* replaces unknown column col by its solution x in every value derived so
 * far: the definitions and the unknowns solved earlier in terms of it */
static int has_any(const PointEq p, const slong *cols, slong n)
{
    for (slong j = 0; j < n; j++)
        if (pteq_has_point(p, cols[j]))
            return 1;
    return 0;
}

/* the unknown points syms[0..n-1], just solved (their columns cols),
 * replaced in every value derived so far, all in one pass */
static void substitute_solved(Deriver *D, const slong *cols, Sym *const *syms,
                              slong n)
{
    const Ring *r = D->r;
    PointEq *sol = pc_xmalloc(sizeof(PointEq) * (size_t)(n ? n : 1));
    for (slong j = 0; j < n; j++)
        sol[j][0] = D->usol[syms[j]->index][0]; /* borrowed, not modified */
    for (int i = 0; i < D->info->ndefs; i++) {
        Value *v = &D->defs[i];
        if (D->state[i] == 1 && v->is_point && has_any(v->p, cols, n)) {
            assume_into(D, &D->dassume[i]); /* the solve's assumptions */
            pteq_subst_points(v->p, v->p, cols, (const PointEq *)sol, n, r);
            if (reduce_value(D, v, D->info->defs[i]->def->expr) < 0)
                D->state[i] = -1;
        }
    }
    for (int k = 0; k < D->info->nunknowns; k++)
        if (D->usolved[k] && D->info->unknowns[k]->is_point &&
            has_any(D->usol[k], cols, n))
            pteq_subst_points(D->usol[k], D->usol[k], cols,
                              (const PointEq *)sol, n, r);
    free(sol);
}

/* the names of the unknowns flagged in `which`, "'B', 'C'" (caller frees) */
static char *unknown_list(Sym **syms, const char *which, slong n)
{
    size_t len = 1;
    for (slong j = 0; j < n; j++)
        if (which[j])
            len += strlen(syms[j]->name) + 4;
    char *out = pc_xmalloc(len), *o = out;
    *o = '\0';
    for (slong j = 0; j < n; j++)
        if (which[j])
            o += sprintf(o, "%s'%s'", o == out ? "" : ", ", syms[j]->name);
    return out;
}

/* The largest total degree of p in the ring variables vars[0..nv-1]; when
 * it is at least `limit`, the first such monomial's text ("k^2", "k*m")
 * goes to buf.  For the linearity check of solve. */
static slong degree_in(const fmpz_mpoly_t p, const slong *vars, slong nv,
                       slong limit, char *buf, size_t cap, const Ring *r)
{
    slong best = 0;
    ulong *e = pc_xmalloc(sizeof(ulong) * (size_t)(r->nvars ? r->nvars : 1));
    if (cap)
        buf[0] = '\0';
    for (slong i = 0; i < p->length; i++) {
        slong d = 0;
        fmpz_mpoly_get_term_exp_ui(e, p, i, r->ctx);
        for (slong k = 0; k < nv; k++)
            d += (slong)e[vars[k]];
        if (d >= limit && best < limit) {
            size_t len = 0;
            for (slong k = 0; k < nv && cap; k++) {
                if (e[vars[k]] == 0)
                    continue;
                len += (size_t)snprintf(buf + len, cap - len, "%s%s",
                                        len ? "*" : "", r->names[vars[k]]);
                if (e[vars[k]] > 1 && len < cap)
                    len += (size_t)snprintf(buf + len, cap - len, "^%lu",
                                            (unsigned long)e[vars[k]]);
                if (len >= cap)
                    len = cap - 1;
            }
        }
        best = d > best ? d : best;
    }
    free(e);
    return best;
}

/* the coefficient of vars[m] (m >= 0) or the part free of all vars (m < 0)
 * in p, which is linear in them */
static void linear_coeff(fmpz_mpoly_t c, const fmpz_mpoly_t p,
                         const slong *vars, slong nv, slong m, const Ring *r)
{
    ulong *ex = pc_xcalloc((size_t)(nv ? nv : 1), sizeof(ulong));
    if (m >= 0)
        ex[m] = 1;
    fmpz_mpoly_get_coeff_vars_ui(c, p, vars, ex, nv, r->ctx);
    free(ex);
}

/* the note on a system that is singular only by the functions' identities
 * (over the polynomials, without them, it has one solution) */
static void note_by_identity(Deriver *D, const Stmt *st)
{
    diag_note(D->diag, st->span,
              "its determinant vanishes by the identities of its functions "
              "(sin^2 + cos^2 = 1, sqrt(x)^2 = x, ...), not as a polynomial");
}

/* `solve` with unknown scalars among the unknowns: each point equation
 * holds one scalar equation per known point (its weight on both sides
 * agrees), each scalar equation one; the unknowns are the weights x[j][b]
 * of every unknown point X_j on every known point b, and the scalars.  The
 * numerators must be linear in the unknowns (the coefficient of an unknown
 * point free of the unknown scalars, no product of two unknown scalars).
 * Solved by linsolve over the rational functions of everything else. */
static void derive_solve_mixed(Deriver *D, Stmt *st, PointEq *peq,
                               Equation **pe, slong npe, RatFunStruct *seq,
                               Equation **se, slong nse, Sym **syms,
                               Name **names, slong nunk)
{
    const Ring *r = D->r;
    slong nx = 0, nk = 0, nknown = 0, capk = 0;
    slong *xcol = pc_xmalloc(sizeof(slong) * (size_t)nunk);
    slong *kvar = pc_xmalloc(sizeof(slong) * (size_t)nunk);
    slong *xsym = pc_xmalloc(sizeof(slong) * (size_t)nunk);
    slong *ksym = pc_xmalloc(sizeof(slong) * (size_t)nunk);
    slong *known = NULL;
    char prod[128];
    int ok = 1;
    for (slong j = 0; j < nunk; j++) {
        if (syms[j]->is_point) {
            xsym[nx] = j;
            xcol[nx++] = D->ucol0 + syms[j]->index;
        } else {
            ksym[nk] = j;
            kvar[nk++] = D->uvar[syms[j]->index];
        }
    }
    /* linearity, and the known columns */
    for (slong e = 0; e < npe && ok; e++)
        for (slong i = 0; i < peq[e]->len && ok; i++) {
            slong c = peq[e]->terms[i].point, x;
            const fmpz_mpoly_struct *num = peq[e]->terms[i].num;
            for (x = 0; x < nx && xcol[x] != c; x++)
                ;
            if (x < nx) {
                if (degree_in(num, kvar, nk, 1, prod, sizeof prod, r) > 0) {
                    diag_error(D->diag, pe[e]->span,
                               "the equation is not linear in the unknowns: "
                               "it holds the product %s*%s",
                               prod, syms[xsym[x]]->name);
                    ok = 0;
                }
                continue;
            }
            if (degree_in(num, kvar, nk, 2, prod, sizeof prod, r) > 1) {
                diag_error(D->diag, pe[e]->span,
                           "the equation is not linear in the unknowns: it "
                           "holds the product %s",
                           prod);
                ok = 0;
            }
            slong k;
            for (k = 0; k < nknown && known[k] != c; k++)
                ;
            if (k == nknown) {
                if (nknown == capk) {
                    capk = capk ? 2 * capk : 16;
                    known = pc_xrealloc(known, sizeof(slong) * (size_t)capk);
                }
                known[nknown++] = c;
            }
        }
    for (slong e = 0; e < nse && ok; e++)
        if (degree_in(seq[e].num, kvar, nk, 2, prod, sizeof prod, r) > 1) {
            diag_error(D->diag, se[e]->span,
                       "the equation is not linear in the unknowns: it holds "
                       "the product %s",
                       prod);
            ok = 0;
        }
    /* the system: unknown x[j][b] is column j*nknown + b, scalar m is
     * column nx*nknown + m */
    slong ncol = nx * nknown + nk, nrow = npe * nknown + nse;
    RatFunStruct *A = NULL, *b = NULL, *x = NULL;
    fmpz_mpoly_t c;
    fmpz_mpoly_init(c, r->ctx);
    if (ok && (ncol > SOLVE_MAX_UNKNOWNS || nrow > 4 * SOLVE_MAX_UNKNOWNS)) {
        diag_error(D->diag, st->span,
                   "system too large to solve: %ld scalar unknowns in %ld "
                   "equations (at most %d unknowns)",
                   (long)ncol, (long)nrow, SOLVE_MAX_UNKNOWNS);
        ok = 0;
    }
    if (ok && ncol > 0) {
        A = ratfun_vec_init(nrow * ncol, r);
        b = ratfun_vec_init(nrow, r);
        x = ratfun_vec_init(ncol, r);
        for (slong e = 0; e < npe; e++)
            for (slong i = 0; i < peq[e]->len; i++) {
                slong col = peq[e]->terms[i].point, xi, bi;
                const fmpz_mpoly_struct *num = peq[e]->terms[i].num;
                for (xi = 0; xi < nx && xcol[xi] != col; xi++)
                    ;
                if (xi < nx) { /* u * x[xi][b] in every row b of e */
                    for (bi = 0; bi < nknown; bi++)
                        fmpz_mpoly_set(A[(e * nknown + bi) * ncol + xi * nknown + bi].num,
                                       num, r->ctx);
                    continue;
                }
                for (bi = 0; known[bi] != col; bi++)
                    ;
                slong row = e * nknown + bi;
                linear_coeff(c, num, kvar, nk, -1, r);
                fmpz_mpoly_neg(b[row].num, c, r->ctx);
                for (slong m = 0; m < nk; m++) {
                    linear_coeff(c, num, kvar, nk, m, r);
                    fmpz_mpoly_set(A[row * ncol + nx * nknown + m].num, c,
                                   r->ctx);
                }
            }
        for (slong e = 0; e < nse; e++) {
            slong row = npe * nknown + e;
            linear_coeff(c, seq[e].num, kvar, nk, -1, r);
            fmpz_mpoly_neg(b[row].num, c, r->ctx);
            for (slong m = 0; m < nk; m++) {
                linear_coeff(c, seq[e].num, kvar, nk, m, r);
                fmpz_mpoly_set(A[row * ncol + nx * nknown + m].num, c, r->ctx);
            }
        }
        slong rank = 0;
        LinNormal nfs, *nf = solve_normal_form(D, &nfs);
        LinSolveResult lr = linsolve_nf(x, &rank, A, b, nrow, ncol, nf, r);
        for (slong m = 0; lr != LINSOLVE_FAILED && nf && m < ncol; m++)
            if ((nf->err = kernel_reduce(D->K, x + m)))
                lr = LINSOLVE_FAILED;
        int by_identity = 0;
        if (nf && (lr == LINSOLVE_INCONSISTENT ||
                   lr == LINSOLVE_UNDERDETERMINED)) {
            /* only by the identities? (the plain system solves) */
            RatFunStruct *y = ratfun_vec_init(ncol, r);
            by_identity = linsolve(y, NULL, A, b, nrow, ncol, r) ==
                          LINSOLVE_UNIQUE;
            ratfun_vec_clear(y, ncol, r);
        }
        if (lr == LINSOLVE_FAILED) {
            kernel_error_at(D, nf->err, st->span, st->span);
        } else if (lr == LINSOLVE_INCONSISTENT && rank < ncol) {
            diag_error(D->diag, st->span,
                       "singular system: the determinant of the unknowns' "
                       "coefficients vanishes (rank %ld of %ld scalar "
                       "unknowns), and the equations contradict each other",
                       (long)rank, (long)ncol);
        } else if (lr == LINSOLVE_INCONSISTENT) {
            diag_error(D->diag, st->span,
                       "inconsistent system: the equations contradict each "
                       "other");
        } else if (lr == LINSOLVE_UNDERDETERMINED) {
            diag_error(D->diag, names[0]->span,
                       "singular system: the equations leave the unknowns "
                       "undetermined (rank %ld of %ld scalar unknowns)",
                       (long)rank, (long)ncol);
        }
        if (by_identity)
            note_by_identity(D, st);
        if (lr == LINSOLVE_UNIQUE) {
            /* the scalars first: the points' weights do not hold them */
            for (slong m = 0; m < nk; m++) {
                Sym *u = syms[ksym[m]];
                ratfun_set(D->ssol + u->index, x + nx * nknown + m, r);
            }
            for (slong xi = 0; xi < nx; xi++) {
                Sym *u = syms[xsym[xi]];
                pteq_set_weights(D->usol[u->index], known,
                                 x + xi * nknown, nknown, r);
            }
            for (slong j = 0; j < nunk; j++)
                assume_into(D, &D->uassume[syms[j]->index]);
            for (slong m = 0; m < nk; m++) {
                Sym *u = syms[ksym[m]];
                D->usolved[u->index] = 1;
                substitute_solved_scalar(D, kvar[m], D->ssol + u->index, st);
            }
            Sym **xs = pc_xmalloc(sizeof(Sym *) * (size_t)(nx ? nx : 1));
            for (slong xi = 0; xi < nx; xi++) {
                xs[xi] = syms[xsym[xi]];
                D->usolved[xs[xi]->index] = 1;
            }
            substitute_solved(D, xcol, xs, nx);
            free(xs);
        }
        ratfun_vec_clear(A, nrow * ncol, r);
        ratfun_vec_clear(b, nrow, r);
        ratfun_vec_clear(x, ncol, r);
    }
    fmpz_mpoly_clear(c, r->ctx);
    free(known);
    free(ksym);
    free(xsym);
    free(kvar);
    free(xcol);
}

/* one end of a declared bound of ring variable var (a param or a const):
 * the exact value into d->bound, its flags, and what it tells the kernels'
 * sign proofs (kernels_set_range: an exact number, or rational bounds of
 * a constant expression; for a param's end in terms of consts, only its
 * sign).  upper: the upper end.  Returns -1 on an error (reported). */
static int declare_end(Deriver *D, Derived *d, slong var, const Node *end,
                       int open, int upper, int is_const)
{
    const Ring *r = D->r;
    RatFun *vb = (RatFun *)(d->bound + 2 * var + upper);
    if (eval_scalar(D, *vb, end) < 0)
        return -1;
    fmpq_t q, lo, hi;
    fmpq_init(q);
    fmpq_init(lo);
    fmpq_init(hi);
    int lo_open = 0, hi_open = 0, found = 0, rc = 0;
    if (ratfun_get_fmpq(q, *vb, r)) {
        fmpq_set(lo, q);
        fmpq_set(hi, q);
        found = 3;
    } else if (D->K) {
        found = kernel_bounds(D->K, *vb, lo, &lo_open, hi, &hi_open);
    }
    int constant = found || ratfun_get_fmpq(q, *vb, r);
    if (!constant && is_const) {
        diag_error(D->diag, end->span,
                   "expected a number as the bound of a const (like 0, 1/2 "
                   "or pi): a bound cannot depend on a param or a const");
        rc = -1;
    } else if (D->K && found) {
        /* var >= value >= lo (strict when either is), or var <= value <=
         * hi */
        if (!upper && (found & 1))
            kernels_set_range(D->K, var, lo, open || lo_open, NULL, 0);
        if (upper && (found & 2))
            kernels_set_range(D->K, var, NULL, 0, hi, open || hi_open);
    } else if (D->K && !constant) {
        /* a param's end in terms of consts: its sign, where it is known */
        int sg = kernel_sign(D->K, *vb);
        if (!upper && sg > 0)
            kernels_set_sign(D->K, var,
                             sg == 2 || open ? KSIGN_POS : KSIGN_NONNEG);
        if (upper && sg < 0) {
            fmpq_zero(q);
            kernels_set_range(D->K, var, NULL, 0, q, sg == -2 || open);
        }
    }
    if (rc == 0)
        d->bound_flags[var] |=
            (unsigned char)(upper ? DERIVED_BOUND_HI |
                                        (open ? DERIVED_BOUND_HI_OPEN : 0)
                                  : DERIVED_BOUND_LO |
                                        (open ? DERIVED_BOUND_LO_OPEN : 0));
    fmpq_clear(hi);
    fmpq_clear(lo);
    fmpq_clear(q);
    return rc;
}

/* The declared bounds of the params (`param t in [0, 1]`) and consts
 * (`const e in (0, 1)`, `const a > 0`, `const k <= 1`): into d->bound and
 * the kernels' sign proofs, which may then simplify abs(t), sqrt(a^2),
 * sign(e^2 - 1) on them; a result that rests on them holds only there,
 * and the numeric side checks it (DERIVED_BOUND_ASSUMED).  An empty
 * interval is an error. */
static void declare_bounds(Deriver *D, Derived *d)
{
    const SemaInfo *info = D->info;
    slong nv = d->nparams + d->nconsts;
    d->bound = ratfun_vec_init(2 * nv, D->r);
    d->bound_flags = pc_xcalloc((size_t)(nv ? nv : 1), 1);
    /* the consts first: a param's range may be in terms of them */
    for (slong i = 0; i < nv; i++) {
        slong v = (i + d->nparams) % (nv ? nv : 1);
        int is_const = v >= d->nparams;
        const Sym *s = is_const ? info->consts[v - d->nparams] : info->params[v];
        const Stmt *st = s->decl;
        /* (a bound with an error of its own was reported by sema: its
         * names may be unresolved) */
        if (!st || st->bad)
            continue;
        int ok = 1;
        if (st->lo)
            ok &= declare_end(D, d, v, st->lo, st->lo_open, 0, is_const) == 0;
        if (st->hi)
            ok &= declare_end(D, d, v, st->hi, st->hi_open, 1, is_const) == 0;
        fmpq_t a, b;
        fmpq_init(a);
        fmpq_init(b);
        if (ok && st->lo && st->hi &&
            ratfun_get_fmpq(a, d->bound + 2 * v, D->r) &&
            ratfun_get_fmpq(b, d->bound + 2 * v + 1, D->r)) {
            int c = fmpq_cmp(a, b);
            if (c > 0 || (c == 0 && (st->lo_open || st->hi_open)))
                diag_error(D->diag, st->hi->span,
                           "empty interval for '%s': expected an upper end "
                           "%s the lower one",
                           s->name, st->lo_open || st->hi_open
                                        ? "greater than"
                                        : "at least");
        }
        fmpq_clear(b);
        fmpq_clear(a);
    }
}

/* `solve EQ, ... for X, ...`: the equations as combinations that vanish,
 * solved for the unknown columns (solve.c); the solutions replace the
 * unknowns in everything derived so far and in every later use */
static void derive_solve(Deriver *D, Stmt *st)
{
    const Ring *r = D->r;
    slong neq = 0, nunk = 0;
    if (st->bad || D->expired)
        return;
    budget_statement(D->src, st->span);
    assume_clear(D);
    for (Equation *e = st->eqs; e; e = e->next)
        neq++;
    for (Name *nm = st->names; nm; nm = nm->next)
        nunk++;
    PointEq *eqs = pc_xmalloc(sizeof(PointEq) * (size_t)neq);
    PointEq *x = pc_xmalloc(sizeof(PointEq) * (size_t)nunk);
    Sym **syms = pc_xmalloc(sizeof(Sym *) * (size_t)nunk);
    slong *cols = pc_xmalloc(sizeof(slong) * (size_t)nunk);
    char *undetermined = pc_xcalloc((size_t)nunk, 1);
    char *dependent = pc_xcalloc((size_t)neq, 1);
    Equation **eqn = pc_xmalloc(sizeof(Equation *) * (size_t)neq);
    Name **names = pc_xmalloc(sizeof(Name *) * (size_t)nunk);
    RatFun sl, sr;
    int ok = 1;
    double t0 = D->verbose ? now_seconds() : 0;

    ratfun_init(sl, r);
    ratfun_init(sr, r);
    slong j = 0;
    for (Name *nm = st->names; nm; nm = nm->next, j++) {
        names[j] = nm;
        pteq_init(x[j], r);
        /* sema checked: an unknown, solved here only */
        syms[j] = NULL;
        for (int k = 0; k < D->info->nunknowns && !syms[j]; k++)
            if (strcmp(D->info->unknowns[k]->name, nm->text) == 0)
                syms[j] = D->info->unknowns[k];
        cols[j] = D->ucol0 + syms[j]->index;
    }
    slong nsc = 0;
    for (j = 0; j < nunk; j++)
        nsc += !syms[j]->is_point;
    RatFunStruct *seqs = ratfun_vec_init(neq, r);
    char *scalar_eq = pc_xcalloc((size_t)neq, 1);
    slong e = 0;
    for (Equation *q = st->eqs; q; q = q->next, e++) {
        PointEq rhs;
        Value lv, rv;
        eqn[e] = q;
        pteq_init(eqs[e], r);
        pteq_init(rhs, r);
        value_init(&lv, r);
        value_init(&rv, r);
        if (eval(D, &lv, q->lhs) < 0 || eval(D, &rv, q->rhs) < 0) {
            ok = 0;
        } else if (!lv.is_point) { /* sema: a scalar unknown is solved */
            scalar_eq[e] = 1;
            ratfun_sub(seqs + e, lv.s, rv.s, r);
        } else {
            pteq_swap(eqs[e], lv.p, r);
            pteq_swap(rhs, rv.p, r);
            pteq_weight_sum(sl, eqs[e], r);
            pteq_weight_sum(sr, rhs, r);
            int lk = ratfun_is_one(sl, r) ? 1 : ratfun_is_zero(sl, r) ? 0 : -1;
            int rk = ratfun_is_one(sr, r) ? 1 : ratfun_is_zero(sr, r) ? 0 : -1;
            const Node *bad = lk < 0 ? q->lhs : rk < 0 ? q->rhs : NULL;
            if (bad) {
                char *txt = show(lk < 0 ? sl : sr, r);
                diag_error(D->diag, bad->span,
                           "weights of this side sum to %s, not 0 (a vector) "
                           "or 1 (a point)",
                           txt);
                flint_free(txt);
                ok = 0;
            } else if (lk != rk) {
                diag_error(D->diag, q->span,
                           "cannot equate a %s and a %s: the left side's "
                           "weights sum to %d, the right side's to %d",
                           lk ? "point" : "vector", rk ? "point" : "vector",
                           lk, rk);
                ok = 0;
            } else {
                pteq_sub(eqs[e], eqs[e], rhs, r);
            }
        }
        value_clear(&rv, r);
        value_clear(&lv, r);
        pteq_clear(rhs, r);
    }
    if (ok && nsc > 0) {
        PointEq *pe = pc_xmalloc(sizeof(PointEq) * (size_t)neq);
        Equation **pq = pc_xmalloc(sizeof(Equation *) * (size_t)neq);
        Equation **sq = pc_xmalloc(sizeof(Equation *) * (size_t)neq);
        RatFunStruct *se = pc_xmalloc(sizeof(RatFunStruct) * (size_t)neq);
        slong npe = 0, nse = 0;
        for (e = 0; e < neq; e++) {
            if (scalar_eq[e]) {
                se[nse] = seqs[e]; /* borrowed */
                sq[nse++] = eqn[e];
            } else {
                pe[npe][0] = eqs[e][0]; /* borrowed */
                pq[npe++] = eqn[e];
            }
        }
        derive_solve_mixed(D, st, pe, pq, npe, se, sq, nse, syms, names, nunk);
        free(se);
        free(sq);
        free(pq);
        free(pe);
    } else if (ok) {
        /* with functions that obey identities, the system is solved in
         * their normal form (pivots, rank, consistency modulo them) */
        LinNormal nfs, *nf = solve_normal_form(D, &nfs);
        int by_identity = 0;
        for (e = 0; nf && e < neq; e++)
            if (kernel_uses_pteq(D->K, eqs[e], 0))
                break;
        if (nf && e == neq)
            nf = NULL;
        SolveStatus ss =
            nunk > SOLVE_MAX_UNKNOWNS
                ? SOLVE_TOO_BIG
                : solve_points_nf(x, (const PointEq *)eqs, neq, cols, nunk,
                                  undetermined, dependent, D->deadline, nf, r);
        for (j = 0; ss == SOLVE_OK && nf && j < nunk; j++)
            if ((nf->err = kernel_reduce_pteq(D->K, x[j])))
                ss = SOLVE_FAILED;
        if (nf && (ss == SOLVE_SINGULAR || ss == SOLVE_INCONSISTENT)) {
            /* singular or inconsistent only by the identities? (the
             * system over the polynomials, the identities unknown to it) */
            PointEq *y = pc_xmalloc(sizeof(PointEq) * (size_t)nunk);
            for (j = 0; j < nunk; j++)
                pteq_init(y[j], r);
            by_identity = solve_points_ex(y, (const PointEq *)eqs, neq, cols,
                                          nunk, NULL, NULL, D->deadline,
                                          r) == SOLVE_OK;
            for (j = 0; j < nunk; j++)
                pteq_clear(y[j], r);
            free(y);
        }
        if (ss == SOLVE_FAILED)
            kernel_error_at(D, nf->err, st->span, st->span);
        if (ss == SOLVE_TIME)
            out_of_time_at(D, st->span);
        if (ss == SOLVE_OK) {
            for (j = 0; j < nunk; j++) {
                pteq_swap(D->usol[syms[j]->index], x[j], r);
                D->usolved[syms[j]->index] = 1;
                assume_into(D, &D->uassume[syms[j]->index]);
            }
            substitute_solved(D, cols, syms, nunk);
        } else if (ss == SOLVE_SINGULAR) {
            char *list = unknown_list(syms, undetermined, nunk);
            for (j = 0; j < nunk && !undetermined[j]; j++)
                ;
            diag_error(D->diag, names[j < nunk ? j : 0]->span,
                       "singular system: the equations leave %s undetermined",
                       list);
            if (by_identity)
                note_by_identity(D, st);
            for (e = 0; e < neq; e++)
                if (dependent[e])
                    diag_note(D->diag, eqn[e]->span,
                              "this equation follows from the others");
            free(list);
        } else if (ss == SOLVE_INCONSISTENT) {
            for (e = 0; e < neq && !dependent[e]; e++)
                ;
            for (j = 0; j < nunk && !undetermined[j]; j++)
                ;
            if (j < nunk) /* the coefficients' determinant vanishes */
                diag_error(D->diag, eqn[e < neq ? e : 0]->span,
                           "singular system: the determinant of the unknowns' "
                           "coefficients vanishes, and this equation "
                           "contradicts the others");
            else
                diag_error(D->diag, eqn[e < neq ? e : 0]->span,
                           "inconsistent system: this equation contradicts "
                           "the others");
            if (by_identity)
                note_by_identity(D, st);
        } else if (ss == SOLVE_TOO_BIG && nunk > SOLVE_MAX_UNKNOWNS) {
            diag_error(D->diag, st->span,
                       "system too large to solve: %ld unknowns (at most %d)",
                       (long)nunk, SOLVE_MAX_UNKNOWNS);
        } else if (ss == SOLVE_TOO_BIG) {
            diag_error(D->diag, st->span,
                       "expression too large to compute exactly: an "
                       "intermediate product of this solve could need more "
                       "than %.0f MB of coefficients",
                       exp2(RATFUN_MAX_LOG2_BITS - 23));
        }
    }
    if (D->verbose) {
        int line, col;
        source_locate(D->src, st->span.start, &line, &col);
        pc_fprintf(D->verbose, "%s:%d: solve for %ld unknown%s: %.3f ms\n",
                   D->src->name, line, (long)nunk, nunk == 1 ? "" : "s",
                   1e3 * (now_seconds() - t0));
        fflush(D->verbose);
    }
    ratfun_clear(sr, r);
    ratfun_clear(sl, r);
    for (e = 0; e < neq; e++)
        pteq_clear(eqs[e], r);
    ratfun_vec_clear(seqs, neq, r);
    free(scalar_eq);
    for (j = 0; j < nunk; j++)
        pteq_clear(x[j], r);
    free(names);
    free(eqn);
    free(dependent);
    free(undetermined);
    free(cols);
    free(syms);
    free(x);
    free(eqs);
}

/* 1 when p depends on ring variable var */
static int poly_has_var(const fmpz_mpoly_t p, slong var, const Ring *r)
{
    return fmpz_mpoly_degree_si(p, var, r->ctx) > 0;
}

/* the unknown (point or scalar) that value v of output o still holds, or
 * NULL */
static const Sym *unsolved_in(const Deriver *D, const Value *v)
{
    const Ring *r = D->r;
    for (slong i = 0; i < (v->is_point ? v->p->len : 0); i++)
        if (v->p->terms[i].point >= D->ucol0)
            return D->info->unknowns[v->p->terms[i].point - D->ucol0];
    for (int k = 0; k < D->info->nunknowns; k++) {
        slong var = D->uvar[k];
        int dep = 0;
        if (var < 0)
            continue;
        if (v->is_point) {
            dep = poly_has_var(v->p->den, var, r);
            for (slong i = 0; i < v->p->len && !dep; i++)
                dep = poly_has_var(v->p->terms[i].num, var, r);
        } else {
            dep = ratfun_depends_on(v->s, var, r);
        }
        if (dep)
            return D->info->unknowns[k];
    }
    return NULL;
}

/* 0, or -1 after reporting that output o (value v) still holds an unknown
 * that no solve determined */
static int check_no_unknown(Deriver *D, const Sym *o, const Value *v)
{
    const Sym *u = unsolved_in(D, v);
    if (!u)
        return 0;
    diag_error(D->diag, o->span,
               "'%s' depends on the unknown '%s', which no solve "
               "determines; expected 'solve ... for %s' before the output",
               o->name, u->name, u->name);
    diag_note(D->diag, u->span, "'%s' was declared here", u->name);
    return -1;
}

/* ---- outputs and steps -------------------------------------------------- */

/* o = the value v, as derive prints it and codegen lowers it: kind from
 * the weight sum, each weight reduced on its own (DerivedOutput) */
static void output_fill(DerivedOutput *o, const char *name, Span span,
                        const Value *v, const Source *src, const Ring *r)
{
    int line, col;
    o->name = pc_xstrdup(name);
    source_locate(src, span.start, &line, &col);
    o->line = line;
    o->span = span;
    pteq_init(o->eq, r);
    ratfun_init(o->scalar, r);
    o->w = NULL;
    o->diff_of = o->diff_var = NULL;
    o->diff_order = 0;
    if (v->is_point) {
        RatFun sum;
        ratfun_init(sum, r);
        pteq_weight_sum(sum, v->p, r);
        o->kind = ratfun_is_one(sum, r) ? KIND_POINT : KIND_VECTOR;
        ratfun_clear(sum, r);
        pteq_set(o->eq, v->p, r);
        o->w = flint_malloc(sizeof(RatFunStruct) *
                            (size_t)FLINT_MAX(o->eq->len, 1));
        for (slong k = 0; k < o->eq->len; k++)
            ratfun_init(o->w + k, r);
        pteq_get_weights(o->w, o->eq, r);
    } else {
        o->kind = KIND_SCALAR;
        ratfun_set(o->scalar, v->s, r);
    }
}

static void output_clear(DerivedOutput *o, const Ring *r)
{
    if (o->w != NULL) {
        for (slong k = 0; k < o->eq->len; k++)
            ratfun_clear(o->w + k, r);
        flint_free(o->w);
    }
    pteq_clear(o->eq, r);
    ratfun_clear(o->scalar, r);
    free((char *)o->name);
    free(o->assumed);
    free(o->diff_of);
    free(o->diff_var);
}

static void step_clear(DerivedStep *st, const Ring *r)
{
    output_clear(&st->value, r);
    for (slong k = 0; k < st->nargs; k++)
        output_clear(&st->args[k], r);
    free(st->args);
    if (st->params)
        ratfun_vec_clear(st->params, st->nparams, r);
    if (st->sv_coord)
        ratfun_vec_clear(st->sv_coord, st->nparams + 1, r);
    ratfun_clear(st->det, r);
    ratfun_clear(st->scalar, r);
    free((char *)st->var);
    free(st->expr);
}

/* the source text of span, owned */
static char *span_text(const Source *src, Span span)
{
    size_t n = span.end > span.start ? (size_t)(span.end - span.start) : 0;
    char *s = pc_xmalloc(n + 1);
    if (n)
        memcpy(s, src->text + span.start, n);
    s[n] = '\0';
    return s;
}

/* a zero value of the step's kind, when it is pending */
static void step_pending(DerivedStep *st, const char *name, Span span,
                         const Source *src, const Ring *r)
{
    Value zero;
    value_init(&zero, r);
    st->pending = 1;
    output_fill(&st->value, name, span, &zero, src, r);
    value_clear(&zero, r);
}

/* st->args[k] = the value of argument node a (named by its text); 0, or
 * -1 when it still holds an unsolved unknown (or failed: reported) */
static int step_arg(Deriver *D, DerivedStep *st, slong k, const Node *a)
{
    Value v;
    int rc = 0;
    value_init(&v, D->r);
    /* (a name as derive knows it: a family member M[2] is "M_2") */
    char *name = a->kind == ND_NAME && a->sym ? pc_xstrdup(a->sym->name)
                                              : span_text(D->src, a->span);
    if (eval(D, &v, a) < 0 || unsolved_in(D, &v))
        rc = -1;
    output_fill(&st->args[k], name, a->span, &v, D->src, D->r);
    free(name);
    value_clear(&v, D->r);
    return rc;
}

/* the operation of a definition's expression */
static StepOp step_op(const Node *e)
{
    if (e->kind != ND_CALL)
        return STEP_EXPR;
    switch ((Builtin)e->builtin) {
    case BI_ALONG: return STEP_ALONG;
    case BI_DIVIDE: return STEP_DIVIDE;
    case BI_MEET: return STEP_MEET;
    case BI_SUBST: return STEP_SUBST;
    case BI_DIFF: return STEP_DIFF;
    case BI_BEZIER: return STEP_BEZIER;
    default: return STEP_EXPR;
    }
}

/* the construction of a definition: its args and scalars */
static void step_construction(Deriver *D, DerivedStep *st, const Node *e)
{
    const Ring *r = D->r;
    const Node *a;
    slong k = 0;
    if (e->kind != ND_CALL)
        return;
    switch ((Builtin)e->builtin) {
    case BI_ALONG:
    case BI_DIVIDE:
        st->nargs = 2;
        st->args = pc_xcalloc(2, sizeof(DerivedOutput));
        for (a = e->args; k < 2; a = a->next, k++)
            step_arg(D, st, k, a);
        eval_scalar(D, st->scalar, nth(e, 2));
        break;
    case BI_BEZIER:
        st->nargs = e->nargs - 1;
        st->args = pc_xcalloc((size_t)st->nargs, sizeof(DerivedOutput));
        for (a = e->args->next; a; a = a->next, k++)
            step_arg(D, st, k, a);
        eval_scalar(D, st->scalar, e->args);
        break;
    case BI_SUBST: {
        const Node *x = nth(e, 1);
        st->var = pc_xstrdup(x->sym->name);
        if (x->sym->kind == SYM_POINT || x->sym->kind == SYM_UNKNOWN) {
            st->nargs = 1;
            st->args = pc_xcalloc(1, sizeof(DerivedOutput));
            step_arg(D, st, 0, nth(e, 2));
        } else {
            eval_scalar(D, st->scalar, nth(e, 2));
        }
        break;
    }
    case BI_DIFF:
        st->var = pc_xstrdup(nth(e, 1)->sym->name);
        st->order = nth(e, 2) ? strtol(nth(e, 2)->text, NULL, 10) : 1;
        break;
    case BI_MEET: {
        const Node *fa = nth(e, 0), *fb = nth(e, 1);
        int ok = 1;
        st->nfirst = fa->nargs;
        st->nargs = fa->nargs + fb->nargs;
        st->args = pc_xcalloc((size_t)st->nargs, sizeof(DerivedOutput));
        for (a = fa->args; a; a = a->next, k++)
            ok &= step_arg(D, st, k, a) == 0;
        for (a = fb->args; a; a = a->next, k++)
            ok &= step_arg(D, st, k, a) == 0;
        if (!ok || fa->nargs != 2)
            break;
        /* the args' equations (borrowed views) */
        PointEq pa[2], pb[3];
        for (slong j = 0; j < 2; j++)
            pa[j][0] = st->args[j].eq[0];
        for (slong j = 0; j < fb->nargs; j++)
            pb[j][0] = st->args[2 + j].eq[0];
        RatFunStruct *par = ratfun_vec_init(fb->nargs, r);
        if (construct_meet_params(par, st->value.eq, (const PointEq *)pa,
                                  (const PointEq *)pb, fb->nargs, r) == 0) {
            st->nparams = fb->nargs;
            st->params = par;
        } else {
            ratfun_vec_clear(par, fb->nargs, r);
        }
        RatFunStruct *co = ratfun_vec_init(fb->nargs + 1, r);
        slong w = 0;
        if (st->params &&
            construct_meet_sv(co, &w, st->det, (const PointEq *)pa,
                              (const PointEq *)pb, fb->nargs, r) == 0) {
            st->has_sv = 1;
            st->sv_w = 2 + w;
            st->sv_coord = co;
        } else {
            ratfun_vec_clear(co, fb->nargs + 1, r);
        }
        break;
    }
    default:
        break;
    }
}

/* Derived.steps (derive.h): after a successful derivation, one step per
 * definition and per unknown a solve determines, in source order, from the
 * final values; the arguments of the constructions are evaluated again
 * (names are memoised: copies) */
static void record_steps(Deriver *D, Derived *d, const Source *src)
{
    const Ring *r = D->r;
    const SemaInfo *info = D->info;
    slong n = 0;
    for (int i = 0; i < info->nsteps; i++) {
        const Stmt *st = info->steps[i];
        if (st->kind != ST_SOLVE)
            n++;
        else
            for (Name *nm = st->names; nm; nm = nm->next)
                n++;
    }
    d->steps = pc_xcalloc((size_t)(n ? n : 1), sizeof(DerivedStep));
    for (int i = 0; i < info->nsteps; i++) {
        const Stmt *st = info->steps[i];
        if (st->kind == ST_SOLVE) {
            for (Name *nm = st->names; nm; nm = nm->next) {
                DerivedStep *ds = &d->steps[d->nsteps++];
                Sym *u = NULL;
                for (int k = 0; k < info->nunknowns && !u; k++)
                    if (strcmp(info->unknowns[k]->name, nm->text) == 0)
                        u = info->unknowns[k];
                ratfun_init(ds->scalar, r);
                ratfun_init(ds->det, r);
                ds->op = STEP_SOLVE;
                ds->expr = span_text(src, st->span);
                Value uv;
                uv.is_point = u->is_point;
                uv.p[0] = D->usol[u->index][0]; /* borrowed */
                uv.s[0] = D->ssol[u->index];
                if (!D->usolved[u->index] || unsolved_in(D, &uv))
                    step_pending(ds, u->name, nm->span, src, r);
                else
                    output_fill(&ds->value, u->name, nm->span, &uv, src, r);
            }
            continue;
        }
        Sym *s = st->sym;
        DerivedStep *ds = &d->steps[d->nsteps++];
        budget_statement(src, st->expr->span); /* (blamed if out of memory) */
        const Value *v = &D->defs[s->index];
        ratfun_init(ds->scalar, r);
        ratfun_init(ds->det, r);
        ds->op = step_op(st->expr);
        ds->expr = span_text(src, st->expr->span);
        if (D->state[s->index] != 1 || unsolved_in(D, v)) {
            step_pending(ds, s->name, s->span, src, r);
            continue;
        }
        output_fill(&ds->value, s->name, s->span, v, src, r);
        step_construction(D, ds, st->expr);
    }
}

/* Derived.named: the scalar definitions whose value is v^k, v a kernel */
static void record_named(Deriver *D, Derived *d, const Source *src)
{
    const Ring *r = D->r;
    const SemaInfo *info = D->info;
    d->named = pc_xcalloc((size_t)info->nsteps + 1, sizeof(DerivedName));
    ulong *e = pc_xmalloc(sizeof(ulong) * (size_t)(r->nvars ? r->nvars : 1));
    for (int i = 0; i < info->nsteps && D->K; i++) {
        const Stmt *st = info->steps[i];
        if (st->kind == ST_SOLVE)
            continue;
        const Sym *s = st->sym;
        const Value *v = &D->defs[s->index];
        if (D->state[s->index] != 1 || v->is_point ||
            !fmpz_mpoly_is_one(v->s->den, r->ctx) ||
            fmpz_mpoly_length(v->s->num, r->ctx) != 1 ||
            !fmpz_is_one(v->s->num->coeffs))
            continue;
        fmpz_mpoly_get_term_exp_ui(e, v->s->num, 0, r->ctx);
        slong var = -1, nv = 0;
        for (slong k = 0; k < r->nvars; k++)
            if (e[k]) {
                var = k;
                nv++;
            }
        if (nv != 1 || !kernels_of_var(D->K, var))
            continue;
        int line, col;
        source_locate(src, s->span.start, &line, &col);
        DerivedName *nm = &d->named[d->nnamed++];
        nm->name = pc_xstrdup(s->name);
        nm->var = var;
        nm->exp = e[var];
        nm->line = line;
    }
    free(e);
}

static char **copy_names(Sym **syms, int n)
{
    char **names = pc_xcalloc((size_t)(n ? n : 1), sizeof(char *));
    for (int i = 0; i < n; i++)
        names[i] = pc_xstrdup(syms[i]->name);
    return names;
}

/* the file's base name without directory and extension */
static char *base_name(const char *filename)
{
    const char *b = strrchr(filename, '/');
    b = b ? b + 1 : filename;
    char *s = pc_xstrdup(b);
    char *dot = strrchr(s, '.');
    if (dot && dot != s)
        *dot = '\0';
    return s;
}

Derived *derive_source(const char *filename, const char *text, size_t len,
                       FILE *err, int *nerrors)
{
    DeriveOptions opt = {.max_seconds = BUDGET_DEFAULT_SECONDS};
    return derive_source_ex(filename, text, len, err, nerrors, &opt);
}

/* an output defined as diff(NAME, t[, n]) of a plain name: the printers
 * write it as dNAME/dt^n */
static void output_diff_of(DerivedOutput *o, const Sym *s)
{
    const Node *e = s->kind == SYM_DEF && s->def ? s->def->expr : NULL;
    if (!e || e->kind != ND_CALL || e->builtin != BI_DIFF)
        return;
    const Node *x = e->args, *t = x ? x->next : NULL;
    const Node *n = t ? t->next : NULL;
    if (!x || x->kind != ND_NAME || !t || t->kind != ND_NAME)
        return;
    long order = 1;
    if (n) {
        if (n->kind != ND_NUM)
            return;
        char *end;
        order = strtol(n->text, &end, 10);
        if (*end || order < 1 || order > 99)
            return;
    }
    o->diff_of = pc_xstrdup(x->text);
    o->diff_var = pc_xstrdup(t->text);
    o->diff_order = (int)order;
}

Derived *derive_source_ex(const char *filename, const char *text, size_t len,
                          FILE *err, int *nerrors, const DeriveOptions *opt)
{
    double start = now_seconds();
    Arena arena;
    if (opt->bad_define)
        *opt->bad_define = 0;
    Source src;
    Diag diag;
    Derived *d = NULL;
    arena_init(&arena);
    source_init(&src, filename, text, len);
    diag_init(&diag, &src, err);
    diag_hold(&diag);

    Scheme *scheme = parse_scheme(&src, &arena, &diag);
    SemaInfo *info = NULL;
    if (diag.nerrors == 0) {
        int nd = opt->defines ? opt->ndefines : 0;
        char *used = pc_xcalloc((size_t)(nd ? nd : 1), 1);
        expand_scheme(scheme, &arena, &diag, opt->defines, nd, used);
        for (int k = 0; k < nd; k++)
            if (!used[k]) { /* a usage error, like --origin of no point */
                const char *eq = strchr(opt->defines[k], '=');
                int nlen = eq ? (int)(eq - opt->defines[k]) : 0;
                if (err)
                    fprintf(err,
                            "pointcalc: -D %s: %s declares no 'int %.*s'\n",
                            opt->defines[k], filename, nlen,
                            opt->defines[k]);
                if (opt->bad_define)
                    *opt->bad_define = 1;
                diag.nerrors++;
            }
        free(used);
    }
    if (diag.nerrors == 0)
        info = sema_check(scheme, &arena, &diag);
    if (!info)
        goto done;

    /* Kernel slots (functions, pi, distances) are reserved when the ring is
     * built; every unused slot costs in every monomial, so the first try
     * reserves what the scheme's calls need at least, and a derivation
     * that runs out is done again with twice as many (its messages
     * dropped). */
    slong nslots_try = 0;
    int diag_msgs0 = diag.nmsgs, diag_errors0 = diag.nerrors;
retry:
    d = pc_xcalloc(1, sizeof(Derived));
    d->filename = pc_xstrdup(filename);
    d->text = pc_xmalloc(len ? len : 1);
    if (len)
        memcpy(d->text, text, len);
    d->len = len;
    d->scheme = info->scheme_name ? pc_xstrdup(info->scheme_name)
                                  : base_name(filename);
    d->npoints = info->npoints;
    d->points = copy_names(info->points, info->npoints);
    d->nparams = info->nparams;
    d->params = copy_names(info->params, info->nparams);
    d->nconsts = info->nconsts;
    d->consts = copy_names(info->consts, info->nconsts);
    {
        /* unknown scalars are ring variables after the consts */
        for (int k = 0; k < info->nunknowns; k++)
            d->nextra += !info->unknowns[k]->is_point;
        d->extra = pc_xcalloc((size_t)(d->nextra ? d->nextra : 1),
                              sizeof(char *));
        for (int k = 0, m = 0; k < info->nunknowns; k++)
            if (!info->unknowns[k]->is_point)
                d->extra[m++] = pc_xstrdup(info->unknowns[k]->name);
        /* kernel slots (functions, pi) after the extra variables */
        slong calls = 0, ops = 0, pis = 0, metric = 0;
        long *coord_ks = NULL; /* the distinct k of coord(P, k) */
        slong ncoord_ks = 0;
        for (int i = 0; i < info->nsteps; i++) {
            const Stmt *st = info->steps[i];
            if (st->kind == ST_DEF)
                count_kernel_uses(st->expr, &calls, &ops, &pis, &metric);
            for (const Equation *e = st->kind == ST_SOLVE ? st->eqs : NULL;
                 e; e = e->next) {
                count_kernel_uses(e->lhs, &calls, &ops, &pis, &metric);
                count_kernel_uses(e->rhs, &calls, &ops, &pis, &metric);
            }
            if (st->kind == ST_DEF)
                count_coord_indices(st->expr, &coord_ks, &ncoord_ks);
            for (const Equation *e = st->kind == ST_SOLVE ? st->eqs : NULL;
                 e; e = e->next) {
                count_coord_indices(e->lhs, &coord_ks, &ncoord_ks);
                count_coord_indices(e->rhs, &coord_ks, &ncoord_ks);
            }
        }
        /* the params' ranges and the consts' bounds are derived too
         * (Derived.range, Derived.bound) */
        for (int i = 0; i < info->nparams + info->nconsts; i++) {
            const Stmt *st = i < info->nparams
                                 ? info->params[i]->decl
                                 : info->consts[i - info->nparams]->decl;
            if (st && st->lo && !st->bad)
                count_kernel_uses(st->lo, &calls, &ops, &pis, &metric);
            if (st && st->hi && !st->bad)
                count_kernel_uses(st->hi, &calls, &ops, &pis, &metric);
            if (st && st->lo && !st->bad)
                count_coord_indices(st->lo, &coord_ks, &ncoord_ks);
            if (st && st->hi && !st->bad)
                count_coord_indices(st->hi, &coord_ks, &ncoord_ks);
        }
        slong nslots = kernels_slots(calls + 3 * metric, ops, pis);
        if (metric)
            nslots += kernels_metric_slots(metric, d->npoints);
        nslots += kernels_coord_slots(ncoord_ks, d->npoints);
        free(coord_ks);
        if (nslots_try > 0)
            nslots = nslots_try;
        nslots_try = nslots;
        slong nv = d->nparams + d->nconsts + d->nextra + nslots;
        const char **vars = pc_xmalloc(sizeof(char *) * (size_t)(nv ? nv : 1));
        for (slong i = nv - nslots; i < nv; i++)
            vars[i] = "?"; /* named when a kernel takes the slot */
        for (slong i = 0; i < d->nparams; i++)
            vars[i] = d->params[i];
        for (slong i = 0; i < d->nconsts; i++)
            vars[d->nparams + i] = d->consts[i];
        for (slong i = 0; i < d->nextra; i++)
            vars[d->nparams + d->nconsts + i] = d->extra[i];
        ring_init(&d->ring, nv, vars);
        free(vars);
        if (nslots > 0) {
            d->kernels = pc_xcalloc(1, sizeof(Kernels));
            kernels_init(d->kernels, &d->ring, nv - nslots, nslots);
            d->kernels->points = (const char *const *)d->points;
            d->kernels->npoints = d->npoints;
        }
    }
    const Ring *r = &d->ring;

    Deriver D = {.diag = &diag, .r = r, .info = info, .src = &src,
                 .K = d->kernels};
    if (D.K)
        D.K->deadline = opt->max_seconds > 0 ? start + opt->max_seconds : 0;
    D.max_seconds = opt->max_seconds;
    D.deadline = opt->max_seconds > 0 ? start + opt->max_seconds : 0;
    D.verbose = opt->verbose;
    D.defs = pc_xmalloc(sizeof(Value) * (size_t)(info->ndefs ? info->ndefs : 1));
    D.state = pc_xcalloc((size_t)(info->ndefs ? info->ndefs : 1), sizeof(int));
    for (int i = 0; i < info->ndefs; i++)
        value_init(&D.defs[i], r);
    D.ucol0 = info->npoints;
    D.usol = pc_xmalloc(sizeof(PointEq) * (size_t)(info->nunknowns ? info->nunknowns : 1));
    D.usolved = pc_xcalloc((size_t)(info->nunknowns ? info->nunknowns : 1), sizeof(int));
    D.dassume = pc_xcalloc((size_t)(info->ndefs ? info->ndefs : 1),
                           sizeof(unsigned char *));
    D.uassume = pc_xcalloc((size_t)(info->nunknowns ? info->nunknowns : 1),
                           sizeof(unsigned char *));
    D.ssol = ratfun_vec_init(info->nunknowns, r);
    D.uvar = pc_xmalloc(sizeof(slong) * (size_t)(info->nunknowns ? info->nunknowns : 1));
    for (int k = 0, m = 0; k < info->nunknowns; k++) {
        pteq_init(D.usol[k], r);
        D.uvar[k] = info->unknowns[k]->is_point
                        ? -1
                        : d->nparams + d->nconsts + m++;
    }
    declare_bounds(&D, d);
    for (int i = 0; i < info->nsteps; i++) {
        if (info->steps[i]->kind == ST_SOLVE)
            derive_solve(&D, info->steps[i]);
        else
            derive_def(&D, info->steps[i]->sym);
    }
    /* an output may not keep an unknown that no solve determined */
    for (int i = 0; i < info->noutputs && diag.nerrors == 0; i++) {
        Sym *s = info->outputs[i];
        Value uv;
        if (s->kind == SYM_DEF) {
            check_no_unknown(&D, s, &D.defs[s->index]);
        } else {
            uv.is_point = s->is_point;
            uv.p[0] = D.usol[s->index][0]; /* borrowed */
            uv.s[0] = D.ssol[s->index];
            check_no_unknown(&D, s, &uv);
        }
    }

    for (slong v = 0; D.K && v < d->nparams + d->nconsts; v++)
        d->bound_flags[v] |=
            (unsigned char)((kernels_assumed(D.K, v) & 1
                                 ? DERIVED_BOUND_LO_ASSUMED
                                 : 0) |
                            (kernels_assumed(D.K, v) & 2
                                 ? DERIVED_BOUND_HI_ASSUMED
                                 : 0));

    /* the declared ranges, exact (a range that does not reduce is left
     * out: sema has reported what is wrong with it) */
    d->range = ratfun_vec_init(2 * info->nparams, r);
    d->has_range = pc_xcalloc((size_t)info->nparams + 1, 1);
    for (int i = 0; i < info->nparams && diag.nerrors == 0; i++) {
        const Stmt *st = info->params[i]->decl;
        if (st && st->lo && !st->bad &&
            eval_scalar(&D, d->range + 2 * i, st->lo) == 0 &&
            eval_scalar(&D, d->range + 2 * i + 1, st->hi) == 0)
            d->has_range[i] = 1;
    }

    if (diag.nerrors == 0) {
        d->noutputs = info->noutputs;
        d->outputs = pc_xcalloc((size_t)(info->noutputs ? info->noutputs : 1),
                            sizeof(DerivedOutput));
        for (int i = 0; i < info->noutputs; i++) {
            Sym *s = info->outputs[i];
            DerivedOutput *o = &d->outputs[i];
            Value uv, *v = &D.defs[s->index];
            if (s->kind == SYM_UNKNOWN) { /* solved */
                uv.is_point = s->is_point;
                uv.p[0] = D.usol[s->index][0]; /* borrowed */
                uv.s[0] = D.ssol[s->index];
                v = &uv;
            }
            output_fill(o, s->name, s->span, v, &src, r);
            const unsigned char *as = s->kind == SYM_UNKNOWN
                                          ? D.uassume[s->index]
                                          : D.dassume[s->index];
            if (as) {
                size_t nv = (size_t)(d->nparams + d->nconsts);
                o->assumed = pc_xmalloc(nv ? nv : 1);
                memcpy(o->assumed, as, nv);
            }
            output_diff_of(o, s);
        }
        if (opt->keep_steps)
            record_steps(&D, d, &src);
        record_named(&D, d, &src);
    }
    for (int i = 0; i < info->ndefs; i++)
        value_clear(&D.defs[i], r);
    for (int k = 0; k < info->nunknowns; k++)
        pteq_clear(D.usol[k], r);
    free(D.usol);
    ratfun_vec_clear(D.ssol, info->nunknowns, r);
    free(D.uvar);
    free(D.usolved);
    for (int i = 0; i < info->ndefs; i++)
        free(D.dassume[i]);
    for (int i = 0; i < info->nunknowns; i++)
        free(D.uassume[i]);
    free(D.dassume);
    free(D.uassume);
    free(D.defs);
    free(D.state);
    if (diag.nerrors) {
        int again = d->kernels && d->kernels->full &&
                    nslots_try < KERNELS_MAX_SLOTS;
        derived_free(d);
        d = NULL;
        if (again) {
            diag_rollback(&diag, diag_msgs0, diag_errors0);
            nslots_try = FLINT_MIN(2 * nslots_try, KERNELS_MAX_SLOTS);
            goto retry;
        }
    }
done:
    budget_statement(NULL, (Span){0, 0});
    diag_flush(&diag);
    if (nerrors)
        *nerrors = diag.nerrors;
    source_clear(&src);
    arena_reset(&arena);
    return d;
}

static Derived *file_error(const char *filename, FILE *err, int *nerrors,
                           const char *fmt, const char *what)
{
    if (err) {
        diag_fput_escaped(err, filename);
        fputs(": error: ", err);
        fprintf(err, fmt, what);
        fputc('\n', err);
    }
    if (nerrors)
        *nerrors = 1;
    return NULL;
}

/* At most DERIVE_MAX_SOURCE bytes are read, whatever the file is (a
 * regular file is refused by its size before reading; a device or a pipe
 * after the limit + 1 bytes), so /dev/zero ends at once and in bounded
 * memory. */
Derived *derive_file(const char *filename, FILE *err, int *nerrors)
{
    DeriveOptions opt = {.max_seconds = BUDGET_DEFAULT_SECONDS};
    return derive_file_ex(filename, err, nerrors, &opt);
}

Derived *derive_file_ex(const char *filename, FILE *err, int *nerrors,
                        const DeriveOptions *opt)
{
    char limit[32];
    struct stat sb;
    snprintf(limit, sizeof limit, "%d MiB", DERIVE_MAX_SOURCE >> 20);
    /* O_NONBLOCK: opening a FIFO no one writes to does not wait; reading
     * anything but a regular file then waits (poll) within the time
     * budget, so a silent FIFO ends with a message, not the budget's
     * signal */
    int fd = open(filename, O_RDONLY | O_NONBLOCK | O_NOCTTY);
    if (fd < 0)
        return file_error(filename, err, nerrors, "cannot open the file: %s",
                          strerror(errno));
    if (fstat(fd, &sb) == 0 && S_ISDIR(sb.st_mode)) {
        close(fd);
        return file_error(filename, err, nerrors, "cannot read the file: %s",
                          "it is a directory");
    }
    int regular = fstat(fd, &sb) == 0 && S_ISREG(sb.st_mode);
    if (regular && sb.st_size > (off_t)DERIVE_MAX_SOURCE) {
        close(fd);
        return file_error(filename, err, nerrors,
                          "cannot read the file: it is larger than %s, the "
                          "limit of a scheme",
                          limit);
    }
    if (regular)
        fcntl(fd, F_SETFL, fcntl(fd, F_GETFL) & ~O_NONBLOCK);
    double budget = opt ? opt->max_seconds : 0;
    double deadline = budget > 0 ? now_seconds() + budget : 0;
    size_t cap = 4096, len = 0;
    char *buf = pc_xmalloc(cap);
    int e = 0, timeout = 0;
    for (;;) {
        if (!regular) {
            int ms = -1;
            if (deadline > 0) {
                double left = deadline - now_seconds();
                ms = left <= 0    ? 0
                     : left > 1e6 ? 1000000000
                                  : (int)(left * 1e3) + 1;
            }
            struct pollfd pfd = {.fd = fd, .events = POLLIN};
            int r = poll(&pfd, 1, ms);
            if (r < 0 && errno == EINTR)
                continue;
            if (r < 0) {
                e = errno;
                break;
            }
            if (r == 0) {
                timeout = 1;
                break;
            }
        }
        ssize_t got = read(fd, buf + len, cap - len);
        if (got < 0 && (errno == EINTR || errno == EAGAIN))
            continue;
        if (got < 0) {
            e = errno;
            break;
        }
        if (got == 0)
            break;
        len += (size_t)got;
        if (len > (size_t)DERIVE_MAX_SOURCE)
            break;
        if (len == cap) {
            cap = cap * 2 > (size_t)DERIVE_MAX_SOURCE + 1
                      ? (size_t)DERIVE_MAX_SOURCE + 1
                      : cap * 2;
            buf = pc_xrealloc(buf, cap);
        }
    }
    close(fd);
    if (len > (size_t)DERIVE_MAX_SOURCE) {
        free(buf);
        return file_error(filename, err, nerrors,
                          "cannot read the file: it is larger than %s, the "
                          "limit of a scheme",
                          limit);
    }
    if (timeout) {
        char secs[32];
        budget_format_seconds(secs, sizeof secs, budget);
        free(buf);
        return file_error(filename, err, nerrors,
                          "cannot read the file: it did not end within the "
                          "time budget of %s (a FIFO that no one writes "
                          "to?); raise it with --max-seconds",
                          secs);
    }
    if (e) {
        free(buf);
        return file_error(filename, err, nerrors, "cannot read the file: %s",
                          strerror(e));
    }
    Derived *d = derive_source_ex(filename, buf, len, err, nerrors, opt);
    free(buf);
    return d;
}

void derived_free(Derived *d)
{
    if (!d)
        return;
    for (slong i = 0; i < d->noutputs; i++)
        output_clear(&d->outputs[i], &d->ring);
    free(d->outputs);
    for (slong i = 0; i < d->nsteps; i++)
        step_clear(&d->steps[i], &d->ring);
    free(d->steps);
    for (slong i = 0; i < d->nnamed; i++)
        free(d->named[i].name);
    free(d->named);
    if (d->kernels) {
        kernels_clear(d->kernels);
        free(d->kernels);
    }
    if (d->range)
        ratfun_vec_clear(d->range, 2 * d->nparams, &d->ring);
    free(d->has_range);
    if (d->bound)
        ratfun_vec_clear(d->bound, 2 * (d->nparams + d->nconsts), &d->ring);
    free(d->bound_flags);
    ring_clear(&d->ring);
    for (slong i = 0; i < d->npoints; i++)
        free(d->points[i]);
    for (slong i = 0; i < d->nparams; i++)
        free(d->params[i]);
    for (slong i = 0; i < d->nconsts; i++)
        free(d->consts[i]);
    for (slong i = 0; i < d->nextra; i++)
        free(d->extra[i]);
    free(d->extra);
    free(d->points);
    free(d->params);
    free(d->consts);
    free(d->scheme);
    free(d->filename);
    free(d->text);
    free(d);
}

void derived_error(const Derived *d, FILE *err, Span span, const char *fmt,
                   ...)
{
    Source src;
    Diag diag;
    va_list ap;
    source_init(&src, d->filename, d->text, d->len);
    diag_init(&diag, &src, err);
    va_start(ap, fmt);
    diag_verror(&diag, span, fmt, ap);
    va_end(ap);
    source_clear(&src);
}

static slong find(char *const *names, slong n, const char *name)
{
    for (slong i = 0; i < n; i++)
        if (strcmp(names[i], name) == 0)
            return i;
    return -1;
}

slong derived_find_output(const Derived *d, const char *name)
{
    for (slong i = 0; i < d->noutputs; i++)
        if (strcmp(d->outputs[i].name, name) == 0)
            return i;
    return -1;
}

slong derived_find_point(const Derived *d, const char *name)
{
    return find(d->points, d->npoints, name);
}

slong derived_find_param(const Derived *d, const char *name)
{
    return find(d->params, d->nparams, name);
}

slong derived_find_const(const Derived *d, const char *name)
{
    return find(d->consts, d->nconsts, name);
}
