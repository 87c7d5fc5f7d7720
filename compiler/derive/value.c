/*
 * value.c - the Values a derivation computes and what every evaluation
 * checks: numbers read exactly (the one decimal reader), the size guards
 * that refuse a result too large to compute, the time budget, the declared
 * bounds a value rests on, and the kernels' errors and normal form.
 *
 * The ground floor of compiler/derive/: expr.c, metric.c, functions.c and
 * solve_stmt.c build on it.
 */
#include "compiler/derive/derive_int.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "base/budget.h"
#include "base/mem.h"
#include "base/stack.h"

/* the ring variable of a param, a const or an unknown scalar */
slong derive_scalar_var(const Deriver *D, const Sym *s)
{
    return s->kind == SYM_PARAM   ? s->index
           : s->kind == SYM_CONST ? D->info->nparams + s->index
                                  : D->uvar[s->index];
}

/* the point column of a base point or an (unsolved) unknown */
slong derive_point_col(const Deriver *D, const Sym *s)
{
    return s->kind == SYM_UNKNOWN ? D->ucol0 + s->index : s->index;
}

double derive_now_seconds(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* 1 (reported at n, once) when the time budget has run out */
int derive_out_of_time_at(Deriver *D, Span span)
{
    if (D->expired)
        return 1;
    if (D->deadline == 0 || derive_now_seconds() <= D->deadline)
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

int derive_out_of_time(Deriver *D, const Node *n)
{
    return derive_out_of_time_at(D, n->span);
}

void derive_value_init(Value *v, const Ring *r)
{
    v->is_point = 0;
    ratfun_init(v->s, r);
    pteq_init(v->p, r);
}

void derive_value_clear(Value *v, const Ring *r)
{
    pteq_clear(v->p, r);
    ratfun_clear(v->s, r);
}

void derive_value_set(Value *res, const Value *x, const Ring *r)
{
    res->is_point = x->is_point;
    if (x->is_point)
        pteq_set(res->p, x->p, r);
    else
        ratfun_set(res->s, x->s, r);
}

/* ---- size guards (ratfun.h) --------------------------------------------- */

/* the largest estimate over the weights of p times s */
double derive_scalar_bits(const PointEq p, const RatFun s, const Ring *r)
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
double derive_pair_bits(const PointEq p, const PointEq q, const Ring *r)
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
int derive_too_big(Deriver *D, double log2_bits, const Node *n)
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
int derive_eval_point(Deriver *D, PointEq res, const Node *n)
{
    Value v;
    derive_value_init(&v, D->r);
    int st = derive_eval(D, &v, n);
    if (st == 0)
        pteq_swap(res, v.p, D->r);
    derive_value_clear(&v, D->r);
    return st;
}

int derive_eval_scalar(Deriver *D, RatFun res, const Node *n)
{
    Value v;
    derive_value_init(&v, D->r);
    int st = derive_eval(D, &v, n);
    if (st == 0)
        ratfun_swap(res, v.s, D->r);
    derive_value_clear(&v, D->r);
    return st;
}

const Node *derive_nth(const Node *call, int i)
{
    const Node *a = call->args;
    while (a && i-- > 0)
        a = a->next;
    return a;
}

/* ---- assumptions: the declared bounds a value rests on ---------------- */

/* the bounds a value read here rests on are those of what reads it */
void derive_assume_from(Deriver *D, const unsigned char *a)
{
    slong nv = D->info->nparams + D->info->nconsts;
    for (slong v = 0; a && D->K && v < nv; v++)
        D->K->cur[v] |= a[v];
}

/* *dst |= what the kernels' sign proofs assumed since K->cur was cleared */
void derive_assume_into(Deriver *D, unsigned char **dst)
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

void derive_assume_clear(Deriver *D)
{
    if (D->K)
        memset(D->K->cur, 0, (size_t)D->K->first);
}

/* 1 when value v uses ring variable var (directly) */
int derive_value_has_var(const Value *v, slong var, const Ring *r)
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
char *derive_show(const RatFun x, const Ring *r)
{
    return ratfun_get_str(x, r);
}

/* ---- kernels (kernel.h): errors and the normal form ------------------- */

/* the terms of a value: KERNEL_MAX_TERMS bounds what kernels take */
slong derive_value_terms(const Value *v)
{
    if (!v->is_point)
        return v->s->num->length + v->s->den->length;
    slong n = v->p->den->length;
    for (slong i = 0; i < v->p->len; i++)
        n += v->p->terms[i].num->length;
    return n;
}

/* reports a failed kernel operation at n; returns -1 */
int derive_kernel_error(Deriver *D, int rc, const Node *n, const Node *arg)
{
    return derive_kernel_error_at(D, rc, n->span, (arg ? arg : n)->span);
}

/* the message of a failed kernel operation (rc: KERNEL_E*) at `at` (a
 * domain error at `arg`); returns -1 */
int derive_kernel_error_at(Deriver *D, int rc, Span at, Span arg)
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
        if (!D->expired && !derive_out_of_time_at(D, at))
            diag_error(D->diag, at,
                       "the time budget ran out while "
                       "deriving this");
        break;
    case KERNEL_ESTACK:
        diag_error(D->diag, at, "%s", STACK_MESSAGE);
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
int derive_reduce_value(Deriver *D, Value *v, const Node *n)
{
    if (!D->K || D->K->nrel == 0)
        return 0;
    if (v->is_point ? !kernel_uses_pteq(D->K, v->p, 0)
                    : !kernel_uses(D->K, v->s, 0))
        return 0;
    if (derive_value_terms(v) > KERNEL_MAX_TERMS)
        return derive_kernel_error(D, KERNEL_EBIG, n, NULL);
    int rc = v->is_point ? kernel_reduce_pteq(D->K, v->p)
                         : kernel_reduce(D->K, v->s);
    return rc ? derive_kernel_error(D, rc, n, NULL) : 0;
}

/* the kernels' normal form as solve's and linsolve's hook (LinNormal) */
static int normal_form(void *ctx, RatFunStruct *x)
{
    return kernel_reduce((Kernels *)ctx, x);
}

/* the normal form for a system whose entries may hold kernels with
 * identities, or NULL when none can occur */
LinNormal *derive_solve_normal_form(Deriver *D, LinNormal *nf)
{
    if (!D->K || D->K->nrel == 0)
        return NULL;
    nf->reduce = normal_form;
    nf->ctx = D->K;
    nf->err = 0;
    return nf;
}

/* terms, total degree and largest coefficient bits of a value */
void derive_value_size(const Value *v, slong *terms, slong *deg, slong *bits,
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
