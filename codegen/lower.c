/*
 * lower.c - exact weights (fmpz_mpoly num/den) -> Plan instructions.
 *
 * The pipeline for one output (formula in lower.h):
 *
 *   factor every numerator and denominator (ring_factor: irreducible
 *     where that is cheap, else square-free, else one factor)
 *   lower every factor once, in Horner form                -> registers
 *   L = the lcm of the denominators, as {factor register: max exponent}
 *   inv = 1/L,  bad = sum of pole(factor of L) + 0.5 pole(inv)
 *   w_i = c_i * prod(num factors) * prod(L / d_i) * inv
 *
 * Factors are identified by their register: the Plan builder hash-conses,
 * so the same polynomial lowered twice is the same register, and t - 1 in
 * the numerator of one weight is t - 1 in the next.  A scalar is an output
 * of one weight and takes the same path.  Constant denominators never
 * reach the Plan: they are folded into the constant c_i.
 */
#include "codegen/lower.h"

#include "base/budget.h"
#include "base/mem.h"
#include "base/stack.h"
#include "codegen/collapse.h"
#include "codegen/lower_int.h"
#include "compiler/algebra/kernel.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <flint/fmpq.h>
#include <flint/fmpz_mpoly_factor.h>

enum {
    DEGREE_MAX = 1 << 24, // beyond this degree no plan is made
};

typedef struct Lower {
    Plan *p;
    const Ring *r;
    slong nparams, nconsts;
    LowerError error;    // first unrepresentable coefficient ...
    slong error_exp10;   // ... and its decimal exponent (about)
    const Kernels *K;    // the functions of the ring (kernel.h), or NULL
    int *kreg;           // per kernel: its register, or -1 not yet lowered
    int *kbad;           // per kernel: its flags (poles of its argument's
                         // denominator, domain), or -1: none
    unsigned char *used; // per kernel: the current output uses it
    slong shift_var;     // horner reads this param as shift_reg (the
    int shift_reg;       // shifted form below), or -1: none
    int stop;            // gave up: 1 the deadline (budget_late), 2 the stack
} Lower;

/* 1 when lowering must stop (sets L->stop): each recursive step asks */
static int lower_stopped(Lower *L)
{
    if (!L->stop)
        L->stop = stack_low() ? 2 : budget_late() ? 1 : 0;
    return L->stop != 0;
}

static int kernel_reg(Lower *L, slong var);

typedef struct Factor {
    int reg;   // register of the irreducible factor
    slong exp; // its multiplicity
} Factor;

/* c * prod f[i].reg ^ f[i].exp */
typedef struct Factored {
    fmpq_t c;
    slong n, alloc;
    Factor *f; // owned
} Factored;

static void factored_init(Factored *F)
{
    fmpq_init(F->c);
    fmpq_one(F->c);
    F->n = F->alloc = 0;
    F->f = NULL;
}

static void factored_clear(Factored *F)
{
    fmpq_clear(F->c);
    pc_free(F->f);
}

/* multiplies F by reg^exp, merging equal registers */
static void factored_mul(Factored *F, int reg, slong exp)
{
    for (slong i = 0; i < F->n; i++)
        if (F->f[i].reg == reg) {
            F->f[i].exp += exp;
            return;
        }
    if (F->n == F->alloc) {
        F->alloc = F->alloc ? 2 * F->alloc : 4;
        F->f = pc_xrealloc(F->f, sizeof *F->f * (size_t)F->alloc);
    }
    F->f[F->n].reg = reg;
    F->f[F->n].exp = exp;
    F->n++;
}

static slong factored_exp(const Factored *F, int reg)
{
    for (slong i = 0; i < F->n; i++)
        if (F->f[i].reg == reg)
            return F->f[i].exp;
    return 0;
}

static int cmp_factor(const void *x, const void *y)
{
    const Factor *a = x, *b = y;
    return (a->reg > b->reg) - (a->reg < b->reg);
}

/* the product of the factors (not the constant) that are uniform (1) or
 * vary with the params (0), in register order so that equal products give
 * equal registers.  Weights are built as varying * uniform * constant, so
 * that the uniform part (consts only) is one product computed once per
 * call, not factors multiplied into the per-sample chain. */
static int factored_product(Lower *L, Factored *F, int uniform)
{
    int acc = plan_const(L->p, 1);
    if (F->n > 1)
        qsort(F->f, (size_t)F->n, sizeof *F->f, cmp_factor);
    for (slong i = 0; i < F->n; i++)
        if (F->f[i].exp > 0 && L->p->ins[F->f[i].reg].uniform == uniform)
            acc = plan_mul(L->p, acc, plan_pow(L->p, F->f[i].reg, F->f[i].exp));
    return acc;
}

LowerError lower_q_to_double(double *res, const fmpq_t q)
{
    if (fmpq_is_zero(q)) {
        *res = 0;
        return LOWER_OK;
    }
    fmpz_t n, d, quo, rem;
    fmpz_init(n);
    fmpz_init(d);
    fmpz_init(quo);
    fmpz_init(rem);
    /* m = |q| 2^-e rounded, with 2^52 <= |q| 2^-e < 2^53 (or e = -1074,
     * the subnormal grid) */
    slong e = (slong)fmpz_bits(fmpq_numref(q)) -
              (slong)fmpz_bits(fmpq_denref(q)) - 53;
    LowerError st = LOWER_OK;
    if (e > 1100) {
        st = LOWER_OVERFLOW;
        goto done;
    }
    for (;;) {
        if (e < -1074)
            e = -1074;
        fmpz_abs(n, fmpq_numref(q));
        fmpz_set(d, fmpq_denref(q));
        if (e >= 0)
            fmpz_mul_2exp(d, d, (ulong)e);
        else
            fmpz_mul_2exp(n, n, (ulong)-e);
        fmpz_fdiv_qr(quo, rem, n, d);
        if (fmpz_bits(quo) <= 53)
            break;
        e++;
    }
    fmpz_mul_2exp(rem, rem, 1);
    int c = fmpz_cmp(rem, d);
    if (c > 0 || (c == 0 && fmpz_is_odd(quo)))
        fmpz_add_ui(quo, quo, 1);
    double v = ldexp(fmpz_get_d(quo), (int)e); // quo <= 2^53: exact
    if (isinf(v))
        st = LOWER_OVERFLOW;
    else if (v == 0)
        st = LOWER_UNDERFLOW;
    *res = fmpz_sgn(fmpq_numref(q)) < 0 ? -v : v;
done:
    fmpz_clear(rem);
    fmpz_clear(quo);
    fmpz_clear(d);
    fmpz_clear(n);
    return st;
}

/* the register of the constant q; an unrepresentable q is recorded */
static int const_fmpq(Lower *L, const fmpq_t q)
{
    double v = 0;
    LowerError st = lower_q_to_double(&v, q);
    if (st != LOWER_OK) {
        if (L->error == LOWER_OK) {
            L->error = st;
            L->error_exp10 = (slong)fmpz_sizeinbase(fmpq_numref(q), 10) -
                             (slong)fmpz_sizeinbase(fmpq_denref(q), 10);
        }
        v = st == LOWER_OVERFLOW ? 1 : 0; // keeps building; never emitted
    }
    return plan_const(L->p, v);
}

/* x * c for an exact constant c */
static int mul_fmpq(Lower *L, int x, const fmpq_t c)
{
    if (fmpq_is_one(c))
        return x;
    return plan_mul(L->p, x, const_fmpq(L, c));
}

/* ---- Horner form -------------------------------------------------------- */

/* The main variable of P: a param if P has one (so the coefficients, in the
 * consts, are uniform and computed once per call), the one of highest
 * degree, ties to the first declared. */
static slong main_var(Lower *L, const slong *degs)
{
    slong best = -1;
    for (slong v = 0; v < L->nparams; v++)
        if (degs[v] > 0 && (best < 0 || degs[v] > degs[best]))
            best = v;
    if (best >= 0)
        return best;
    /* then the functions of params (sin(t)), whose registers vary too */
    for (slong i = 0; L->K && i < L->K->n; i++) {
        slong v = L->K->k[i].var;
        if (degs[v] <= 0)
            continue;
        int kr = kernel_reg(L, v); /* may grow (move) L->p->ins */
        if (!L->p->ins[kr].uniform && (best < 0 || degs[v] > degs[best]))
            best = v;
    }
    if (best >= 0)
        return best;
    for (slong v = L->nparams; v < L->nparams + L->nconsts; v++)
        if (degs[v] > 0 && (best < 0 || degs[v] > degs[best]))
            best = v;
    for (slong i = 0; best < 0 && L->K && i < L->K->n; i++) {
        slong v = L->K->k[i].var;
        if (degs[v] > 0)
            best = v;
    }
    return best;
}

static int horner(Lower *L, const fmpz_mpoly_t P, const fmpq_t scale);

/* 1 when kernel kn is sign(a*t + b), t a param and a, b numbers: t and
 * the root k = -b/a set */
static int shift_sign(Lower *L, const Kernel *kn, slong *t, fmpq_t k)
{
    const fmpz_mpoly_ctx_struct *ctx = L->r->ctx;
    const fmpz_mpoly_struct *a = kn->arg->num;
    if (kn->fn != KF_SIGN || !fmpz_mpoly_is_fmpz(kn->arg->den, ctx) ||
        fmpz_mpoly_total_degree_si(a, ctx) != 1 || a->length > 2)
        return 0;
    slong v = -1;
    for (slong u = 0; u < L->nparams && v < 0; u++)
        if (fmpz_mpoly_degree_si(a, u, ctx) == 1)
            v = u;
    if (v < 0)
        return 0;
    /* a = c1*t + c0, c1 and c0 numbers */
    fmpz_mpoly_t C;
    fmpz_mpoly_init(C, ctx);
    ulong e0 = 0, e1 = 1;
    fmpz_t c1, c0;
    fmpz_init(c1);
    fmpz_init(c0);
    fmpz_mpoly_get_coeff_vars_ui(C, a, &v, &e1, 1, ctx);
    int ok = fmpz_mpoly_is_fmpz(C, ctx);
    if (ok)
        fmpz_mpoly_get_fmpz(c1, C, ctx);
    fmpz_mpoly_get_coeff_vars_ui(C, a, &v, &e0, 1, ctx);
    ok = ok && fmpz_mpoly_is_fmpz(C, ctx) && !fmpz_is_zero(c1);
    if (ok) {
        fmpz_mpoly_get_fmpz(c0, C, ctx);
        fmpz_neg(c0, c0);
        fmpq_set_fmpz_frac(k, c0, c1);
        *t = v;
    }
    fmpz_clear(c0);
    fmpz_clear(c1);
    fmpz_mpoly_clear(C, ctx);
    return ok;
}

enum { PIECES_MAX = 16 }; // sign(t - k) kernels of one polynomial

typedef struct Knot {
    slong var; // the sign kernel's variable
    int reg;   // its register
    fmpq_t k;  // its root
} Knot;

static int cmp_knot(const void *x, const void *y)
{
    return fmpq_cmp(((const Knot *)x)->k, ((const Knot *)y)->k);
}

/* P in the signs sign(t - k_1) < ... < sign(t - k_m) of one param t
 * (abs(t - k)^3 = (t - k)^3 sign(t - k)), lowered piece by piece:
 *
 *   P = sum_j chi_j p_j(t - c_j),  chi_j = (s_{j-1} - s_j)/2
 *                                  (s_0 = 1 and s_{m+1} = -1 beyond the ends)
 *
 * p_j is P on the j-th interval (its signs set to +-1, combined exactly),
 * written in powers of t - c_j, c_j the nearest knot.  The knots sorted,
 * chi_j is exactly 1 on its interval and 0 elsewhere (1/2 for the two
 * pieces at a knot: P is linear in each sign, so their mean is P at sign
 * 0), so no two pieces cancel; it is prod_{i < j} (1 + s_i)/2 prod_{i >= j}
 * (1 - s_i)/2 in one subtraction per piece instead of m products (the 1/2
 * goes into p_j's coefficients).  Expanded, (6t^2 - 39t + 64)(t - 2)^3 |t - 2|
 * and its three companions of the C^2 square have coefficients up to 4320
 * cancelling to about 0.01 at t = 3.9; piecewise the square is 1 - (t - 3)^3
 * (...) in powers of t - 3.  The register, or -1 (P has no such signs, others
 * too, or a shift is being lowered). */
static int horner_shifted(Lower *L, const fmpz_mpoly_t P, const fmpq_t scale)
{
    const fmpz_mpoly_ctx_struct *ctx = L->r->ctx;
    if (L->shift_var >= 0 || !L->K)
        return -1;
    Knot kn[PIECES_MAX];
    slong m = 0, t = -1;
    int ok = 1;
    for (slong i = 0; i < L->K->n && ok; i++) {
        const Kernel *ke = &L->K->k[i];
        if (fmpz_mpoly_degree_si(P, ke->var, ctx) <= 0)
            continue;
        slong ti = -1;
        fmpq_t q;
        fmpq_init(q);
        ok = ke->fn == KF_SIGN && m < PIECES_MAX &&
             fmpz_mpoly_degree_si(P, ke->var, ctx) == 1 &&
             shift_sign(L, ke, &ti, q) && (t < 0 || ti == t);
        if (ok) {
            t = ti;
            kn[m].var = ke->var;
            fmpq_init(kn[m].k);
            fmpq_swap(kn[m].k, q);
            m++;
        }
        fmpq_clear(q);
    }
    if (ok && m > 0)
        qsort(kn, (size_t)m, sizeof kn[0], cmp_knot);
    for (slong i = 1; ok && i < m; i++)
        ok = !fmpq_equal(kn[i - 1].k, kn[i].k);
    int reg = -1;
    if (ok && m > 0) {
        for (slong i = 0; i < m; i++)
            kn[i].reg = kernel_reg(L, kn[i].var);
        fmpq_t sc, mc;
        fmpq_init(sc);
        fmpq_init(mc);
        int one = plan_const(L->p, 1);
        fmpz_t sv, d;
        fmpz_init(sv);
        fmpz_init(d);
        fmpz_mpoly_t Pj;
        fmpz_mpoly_init(Pj, ctx);
        int failed = 0;
        RatFun Q, s, c;
        ratfun_init(Q, L->r);
        ratfun_init(s, L->r);
        ratfun_init(c, L->r);
        for (slong j = 0; j <= m; j++) {
            /* interval j: t above knots 0..j-1, below knots j..m-1 */
            fmpz_mpoly_set(Pj, P, ctx);
            for (slong i = 0; i < m; i++) {
                fmpz_set_si(sv, i < j ? 1 : -1);
                fmpz_mpoly_evaluate_one_fmpz(Pj, Pj, kn[i].var, sv, ctx);
            }
            if (fmpz_mpoly_is_zero(Pj, ctx))
                continue;
            const fmpq *cj = kn[j > 0 ? j - 1 : 0].k;
            /* Pj(t) = Q(t - cj): Q = Pj(t + cj) */
            fmpz_mpoly_set(Q->num, Pj, ctx);
            fmpz_mpoly_one(Q->den, ctx);
            ratfun_gen(s, t, L->r);
            ratfun_set_fmpq(c, cj, L->r);
            ratfun_add(s, s, c, L->r);
            if (ratfun_compose_var(Q, Q, t, s, L->r) != 0 ||
                !fmpz_mpoly_is_fmpz(Q->den, ctx)) {
                failed = 1; /* (a polynomial: never) the plain form */
                break;
            }
            fmpz_mpoly_get_fmpz(d, Q->den, ctx);
            fmpq_div_fmpz(sc, scale, d);
            fmpq_div_2exp(sc, sc, 1); // chi_j = (s_{j-1} - s_j)/2
            fmpq_neg(mc, cj);
            L->shift_var = t;
            L->shift_reg =
                plan_add(L->p, plan_input(L->p, (int)t), const_fmpq(L, mc));
            int q = horner(L, Q->num, sc);
            L->shift_var = -1;
            L->shift_reg = -1;
            int chi2 = j == 0   ? plan_sub(L->p, one, kn[0].reg)
                       : j == m ? plan_add(L->p, one, kn[m - 1].reg)
                                : plan_sub(L->p, kn[j - 1].reg, kn[j].reg);
            q = plan_mul(L->p, q, chi2);
            reg = reg < 0 ? q : plan_add(L->p, reg, q);
        }
        if (failed)
            reg = -1;
        else if (reg < 0)
            reg = plan_const(L->p, 0);
        ratfun_clear(c, L->r);
        ratfun_clear(s, L->r);
        ratfun_clear(Q, L->r);
        fmpz_mpoly_clear(Pj, ctx);
        fmpz_clear(d);
        fmpz_clear(sv);
        fmpq_clear(mc);
        fmpq_clear(sc);
    }
    for (slong i = 0; i < m; i++)
        fmpq_clear(kn[i].k);
    return reg;
}

/* P * scale in recursive Horner form:
 *   P = sum_k c_k x^k  ->  ((c_n x^(n-m) + c_m) x^(m-l) + c_l) ... x^low
 * with the gaps of a sparse P as shared powers, coefficients recursively. */
static int horner(Lower *L, const fmpz_mpoly_t P, const fmpq_t scale)
{
    const fmpz_mpoly_ctx_struct *ctx = L->r->ctx;
    if (lower_stopped(L))
        return plan_const(L->p, 0);
    if (fmpz_mpoly_is_fmpz(P, ctx)) {
        fmpz_t c;
        fmpq_t q;
        fmpz_init(c);
        fmpq_init(q);
        fmpz_mpoly_get_fmpz(c, P, ctx);
        fmpq_mul_fmpz(q, scale, c);
        int reg = const_fmpq(L, q);
        fmpq_clear(q);
        fmpz_clear(c);
        return reg;
    }
    int shifted = horner_shifted(L, P, scale);
    if (shifted >= 0)
        return shifted;
    slong nv = ctx->minfo->nvars;
    slong *degs = flint_malloc(sizeof *degs * (size_t)nv);
    fmpz_mpoly_degrees_si(degs, P, ctx);
    slong var = main_var(L, degs);
    slong deg = degs[var];
    flint_free(degs);

    fmpz_mpoly_t C;
    fmpz_mpoly_init(C, ctx);
    int x = var == L->shift_var             ? L->shift_reg
            : var < L->nparams + L->nconsts ? plan_input(L->p, (int)var)
                                            : kernel_reg(L, var);
    int acc = -1;
    slong prev = 0;
    for (slong k = deg; k >= 0; k--) {
        ulong ku = (ulong)k;
        fmpz_mpoly_get_coeff_vars_ui(C, P, &var, &ku, 1, ctx);
        if (fmpz_mpoly_is_zero(C, ctx))
            continue;
        int c = horner(L, C, scale);
        if (acc < 0)
            acc = c;
        else
            acc = plan_add(L->p,
                           plan_mul(L->p, acc, plan_pow(L->p, x, prev - k)), c);
        prev = k;
    }
    fmpz_mpoly_clear(C, ctx);
    return plan_mul(L->p, acc, plan_pow(L->p, x, prev));
}

/* F *= P, factored into Horner-lowered irreducible factors. */
static void factor_poly(Lower *L, Factored *F, const fmpz_mpoly_t P)
{
    const fmpz_mpoly_ctx_struct *ctx = L->r->ctx;
    if (lower_stopped(L))
        return;
    fmpq_t one;
    fmpq_init(one);
    fmpq_one(one);
    if (fmpz_mpoly_is_fmpz(P, ctx)) {
        fmpz_t c;
        fmpz_init(c);
        fmpz_mpoly_get_fmpz(c, P, ctx);
        fmpq_mul_fmpz(F->c, F->c, c);
        fmpz_clear(c);
        fmpq_clear(one);
        return;
    }
    fmpz_mpoly_factor_t f;
    fmpz_mpoly_factor_init(f, ctx);
    if (ring_factor(f, P, L->r)) {
        fmpq_t k;
        fmpq_init(k);
        fmpq_set_fmpz_frac(k, f->constant, f->constant_den);
        fmpq_mul(F->c, F->c, k);
        fmpq_clear(k);
        for (slong i = 0; i < f->num; i++) {
            if (fmpz_mpoly_is_fmpz(f->poly + i, ctx)) { // defensive
                fmpz_t c;
                fmpz_init(c);
                fmpz_mpoly_get_fmpz(c, f->poly + i, ctx);
                fmpz_pow_ui(c, c, fmpz_get_ui(f->exp + i));
                fmpq_mul_fmpz(F->c, F->c, c);
                fmpz_clear(c);
                continue;
            }
            factored_mul(F, horner(L, f->poly + i, one),
                         fmpz_get_si(f->exp + i));
        }
    } else {
        factored_mul(F, horner(L, P, one), 1);
    }
    fmpz_mpoly_factor_clear(f, ctx);
    fmpq_clear(one);
}

/* ---- outputs ------------------------------------------------------------ */

/* Lowers the weights ws[0..n-1] of one output: reg[i] and *bad. */
static void lower_weights(Lower *L, const RatFunStruct *const *ws, slong n,
                          int *reg, int *bad)
{
    Factored *num = pc_xmalloc(sizeof *num * (size_t)(n ? n : 1));
    Factored *den = pc_xmalloc(sizeof *den * (size_t)(n ? n : 1));
    Factored lcm;
    factored_init(&lcm);
    for (slong i = 0; i < n; i++) {
        factored_init(&num[i]);
        factored_init(&den[i]);
        factor_poly(L, &num[i], ws[i]->num);
        factor_poly(L, &den[i], ws[i]->den);
        /* c_i = num constant / den constant; the den keeps only factors */
        fmpq_div(num[i].c, num[i].c, den[i].c);
        for (slong j = 0; j < den[i].n; j++) {
            slong e = factored_exp(&lcm, den[i].f[j].reg);
            if (den[i].f[j].exp > e)
                factored_mul(&lcm, den[i].f[j].reg, den[i].f[j].exp - e);
        }
    }
    /* the pole flag: one check per distinct irreducible factor of the
     * denominators (their product could underflow to 0 where no factor
     * is 0); the flags are shared with every output of the same factors */
    *bad = -1;
    if (lcm.n > 1)
        qsort(lcm.f, (size_t)lcm.n, sizeof *lcm.f, cmp_factor);
    for (slong j = 0; j < lcm.n; j++) {
        int flag = plan_pole(L->p, lcm.f[j].reg);
        *bad = *bad < 0 ? flag : plan_add(L->p, *bad, flag);
    }
    if (lcm.n == 0) { // polynomial weights: nothing can vanish or overflow
        for (slong i = 0; i < n; i++)
            reg[i] = mul_fmpq(L,
                              plan_mul(L->p, factored_product(L, &num[i], 0),
                                       factored_product(L, &num[i], 1)),
                              num[i].c);
    } else {
        int d = plan_mul(L->p, factored_product(L, &lcm, 0),
                         factored_product(L, &lcm, 1));
        int inv = plan_div(L->p, plan_const(L->p, 1), d);
        /* an overflow of L makes inv 0 and every weight finite and wrong:
         * the same check as a pole, on inv, flagged as 0.5 (plan.h) */
        int ovf = plan_mul(L->p, plan_pole(L->p, inv), plan_const(L->p, 0.5));
        *bad = plan_add(L->p, *bad, ovf);
        for (slong i = 0; i < n; i++) {
            /* num_i * L/d_i */
            for (slong j = 0; j < lcm.n; j++) {
                slong e = lcm.f[j].exp - factored_exp(&den[i], lcm.f[j].reg);
                if (e > 0)
                    factored_mul(&num[i], lcm.f[j].reg, e);
            }
            int w = plan_mul(L->p, factored_product(L, &num[i], 0), inv);
            w = plan_mul(L->p, w, factored_product(L, &num[i], 1));
            reg[i] = mul_fmpq(L, w, num[i].c);
        }
    }
    for (slong i = 0; i < n; i++) {
        factored_clear(&num[i]);
        factored_clear(&den[i]);
    }
    factored_clear(&lcm);
    pc_free(num);
    pc_free(den);
}

/* is x exactly an exp() kernel? */
static int is_exp_kernel(const Lower *L, const RatFunStruct *x)
{
    for (slong i = 0; i < L->K->n; i++) {
        const Kernel *k = &L->K->k[i];
        if (k->fn != KF_EXP || !fmpz_mpoly_is_one(x->den, L->r->ctx) ||
            x->num->length != 1 ||
            fmpz_mpoly_total_degree_si(x->num, L->r->ctx) != 1 ||
            fmpz_mpoly_degree_si(x->num, k->var, L->r->ctx) != 1)
            continue;
        fmpz_t c;
        fmpz_init(c);
        fmpz_mpoly_get_term_coeff_fmpz(c, x->num, 0, L->r->ctx);
        int one = fmpz_is_one(c);
        fmpz_clear(c);
        if (one)
            return 1;
    }
    return 0;
}

static int kernel_reg(Lower *L, slong var);

/* the register of the argument of the exp() kernel x */
static int plan_fn_arg(Lower *L, const RatFunStruct *x)
{
    for (slong i = 0; i < L->K->n; i++)
        if (L->K->k[i].fn == KF_EXP &&
            fmpz_mpoly_degree_si(x->num, L->K->k[i].var, L->r->ctx) == 1) {
            kernel_reg(L, L->K->k[i].var); /* marks it used, flags */
            int a, bad = -1;
            const RatFunStruct *w[1] = {L->K->k[i].arg};
            lower_weights(L, w, 1, &a, &bad);
            return a;
        }
    return plan_const(L->p, 0);
}

/* the register of kernel variable var: its argument lowered like a
 * weight, the function applied once (shared by every use); marks it used
 * by the current output */
static int kernel_reg(Lower *L, slong var)
{
    slong i = var - L->K->first;
    const Kernel *k = &L->K->k[i];
    L->used[i] = 1;
    if (lower_stopped(L))
        return plan_const(L->p, 0);
    if (L->kreg[i] >= 0) {
        /* lowered for an earlier output: the kernels inside its argument
         * are used by this one too (their flags) */
        for (slong j = 0; j < i; j++) {
            slong v = L->K->k[j].var;
            if (!L->used[j] &&
                (fmpz_mpoly_degree_si(k->arg->num, v, L->r->ctx) > 0 ||
                 fmpz_mpoly_degree_si(k->arg->den, v, L->r->ctx) > 0 ||
                 fmpz_mpoly_degree_si(k->arg2->num, v, L->r->ctx) > 0 ||
                 fmpz_mpoly_degree_si(k->arg2->den, v, L->r->ctx) > 0))
                kernel_reg(L, v);
        }
        return L->kreg[i];
    }
    int reg, bad = -1, abad = -1;
    if (k->fn == KF_PI) {
        reg = plan_const(L->p, 3.14159265358979323846);
    } else if (k->fn == KF_DIST) {
        reg = plan_dist(L->p, (int)k->pa, (int)k->pb);
    } else if (k->fn == KF_COORD) {
        reg = plan_coord(L->p, (int)k->pa, (int)k->pb - 1);
    } else {
        int a, b = -1;
        const RatFunStruct *w[1] = {k->arg};
        lower_weights(L, w, 1, &a, &abad);
        bad = abad;
        if (k->fn == KF_ATAN2) {
            w[0] = k->arg2;
            lower_weights(L, w, 1, &b, &abad);
            if (abad >= 0)
                bad = bad < 0 ? abad : plan_add(L->p, bad, abad);
            reg = plan_atan2(L->p, a, b);
        } else if (k->fn == KF_NATX || k->fn == KF_NATY) {
            reg = lower_natural(L->p, L->K, k, a, &bad);
        } else if (k->fn == KF_ROOT && is_exp_kernel(L, k->arg)) {
            /* exp(m)^(1/q) is computed as exp(m/q): no overflow of exp(m) */
            reg = plan_fn(L->p, PLAN_FN_EXP,
                          plan_mul(L->p, plan_fn_arg(L, k->arg),
                                   plan_const(L->p, 1.0 / (double)k->q)));
        } else {
            int fn = lower_plan_fn(k);
            reg = plan_fn(L->p, fn, a);
            if (plan_fn_has_domain(fn)) {
                int dom = plan_mul(L->p, plan_domain(L->p, fn, a),
                                   plan_const(L->p, PLAN_DOMAIN_FLAG));
                bad = bad < 0 ? dom : plan_add(L->p, bad, dom);
            }
        }
    }
    L->kreg[i] = reg;
    L->kbad[i] = bad;
    return reg;
}

/* a bound's value as a double (a constant: 2*pi by its enclosure) */
static double bound_value(const Lower *L, const RatFunStruct *b)
{
    fmpq_t q, lo, hi;
    int lo_open, hi_open;
    double v = 0;
    fmpq_init(q);
    fmpq_init(lo);
    fmpq_init(hi);
    if (ratfun_get_fmpq(q, b, L->r))
        v = fmpq_get_d(q);
    else if (L->K && kernel_bounds(L->K, b, lo, &lo_open, hi, &hi_open) == 3)
        v = 0.5 * (fmpq_get_d(lo) + fmpq_get_d(hi));
    fmpq_clear(hi);
    fmpq_clear(lo);
    fmpq_clear(q);
    return v;
}

/* what the Plan says of input v's assumed bounds (PlanBound): the ends
 * a (1 lower, 2 upper) that an output assumed, with the others' */
static void plan_bound(Lower *L, const Derived *d, slong v, unsigned char a)
{
    Plan *p = L->p;
    unsigned char f = d->bound_flags[v];
    if (!p->bound)
        p->bound =
            pc_xcalloc((size_t)(p->nparams + p->nconsts), sizeof(PlanBound));
    PlanBound *b = &p->bound[v];
    b->flags |=
        (unsigned char)((a & 1 ? PLAN_BOUND_LO : 0) |
                        (a & 2 ? PLAN_BOUND_HI : 0) |
                        (f & DERIVED_BOUND_LO_OPEN ? PLAN_BOUND_LO_OPEN : 0) |
                        (f & DERIVED_BOUND_HI_OPEN ? PLAN_BOUND_HI_OPEN : 0));
    if (b->text)
        return;
    int has_lo = f & DERIVED_BOUND_LO, has_hi = f & DERIVED_BOUND_HI;
    b->lo = has_lo ? bound_value(L, d->bound + 2 * v) : -INFINITY;
    b->hi = has_hi ? bound_value(L, d->bound + 2 * v + 1) : INFINITY;
    char *lo = has_lo ? ratfun_get_str(d->bound + 2 * v, L->r) : NULL;
    char *hi = has_hi ? ratfun_get_str(d->bound + 2 * v + 1, L->r) : NULL;
    b->text = pc_xasprintf("%c%s, %s%c",
                           (f & DERIVED_BOUND_LO_OPEN) || !lo ? '(' : '[',
                           lo ? lo : "-inf", hi ? hi : "inf",
                           (f & DERIVED_BOUND_HI_OPEN) || !hi ? ')' : ']');
    flint_free(lo);
    flint_free(hi);
}

/* The flags of the declared bounds an output's value rests on (Derived
 * bound_flags: DERIVED_BOUND_ASSUMED): for each such param or const that
 * the weights depend on, x - lo < 0 (<= 0 for an open end) and hi - x < 0
 * (<= 0) are domain flags, so a value outside the declared interval is
 * status 4, never a value the derivation did not promise (abs(t) = t on
 * [0, 1] is wrong at t = -1/2).  The comparisons are the Plan's DOMAIN
 * tests of sqrt (x < 0) and ln (x <= 0). */
static int bound_flags(Lower *L, const Derived *d, const DerivedOutput *o,
                       int bad)
{
    for (slong v = 0; o->assumed && v < d->nparams + d->nconsts; v++) {
        unsigned char a = o->assumed[v];
        if (!a)
            continue;
        int x = plan_input(L->p, (int)v);
        plan_bound(L, d, v, a);
        for (int upper = 0; upper < 2; upper++) {
            if (!(a & (upper ? 2 : 1)))
                continue;
            const RatFunStruct *w[1] = {d->bound + 2 * v + upper};
            int e, ebad = -1;
            lower_weights(L, w, 1, &e, &ebad);
            int diff = upper ? plan_sub(L->p, e, x) : plan_sub(L->p, x, e);
            int open = d->bound_flags[v] &
                       (upper ? DERIVED_BOUND_HI_OPEN : DERIVED_BOUND_LO_OPEN);
            int dom = plan_mul(
                L->p, plan_domain(L->p, open ? PLAN_FN_LN : PLAN_FN_SQRT, diff),
                plan_const(L->p, PLAN_DOMAIN_FLAG));
            bad = bad < 0 ? dom : plan_add(L->p, bad, dom);
        }
    }
    return bad;
}

/* the highest degree of x's numerator or denominator in any variable, or
 * -1 when it does not even fit a slong */
static slong max_degree(const Lower *L, const RatFunStruct *x)
{
    const fmpz_mpoly_ctx_struct *ctx = L->r->ctx;
    slong nv = ctx->minfo->nvars, best = 0;
    if (nv == 0)
        return 0;
    slong *degs = flint_malloc(sizeof *degs * (size_t)nv);
    for (int k = 0; k < 2; k++) {
        const fmpz_mpoly_struct *P = k ? x->den : x->num;
        if (!fmpz_mpoly_degrees_fit_si(P, ctx)) {
            best = -1;
            break;
        }
        fmpz_mpoly_degrees_si(degs, P, ctx);
        for (slong v = 0; v < nv; v++)
            if (degs[v] > best)
                best = degs[v];
    }
    flint_free(degs);
    return best;
}

/* does x use a ring variable that is neither a param nor a const? */
/* 1 when x has a positive degree in a variable v with bad[v] set */
static int has_marked(const Lower *L, const RatFunStruct *x,
                      const unsigned char *bad, slong *degs)
{
    const fmpz_mpoly_ctx_struct *ctx = L->r->ctx;
    slong all = ctx->minfo->nvars;
    for (int k = 0; k < 2; k++) {
        fmpz_mpoly_degrees_si(degs, k ? x->den : x->num, ctx);
        for (slong v = 0; v < all; v++)
            if (bad[v] && degs[v] > 0)
                return 1;
    }
    return 0;
}

/* 1 when x depends on an unknown scalar no solve determined (a ring
 * variable after the consts and before the kernels), directly or inside a
 * function's argument (sqrt(h)): such a value has no number */
static int uses_atoms(const Lower *L, const RatFunStruct *x)
{
    const fmpz_mpoly_ctx_struct *ctx = L->r->ctx;
    slong all = ctx->minfo->nvars;
    slong first = L->nparams + L->nconsts, nv = L->K ? L->K->first : all;
    if (first >= nv)
        return 0;
    unsigned char *bad = pc_xcalloc((size_t)all, 1);
    slong *degs = flint_malloc(sizeof *degs * (size_t)all);
    for (slong v = first; v < nv; v++)
        bad[v] = 1;
    /* a kernel's arguments use only kernels made before it */
    for (slong i = 0; L->K && i < L->K->n; i++) {
        const Kernel *k = &L->K->k[i];
        if (k->fn == KF_PI || k->fn == KF_DIST || k->fn == KF_COORD)
            continue;
        bad[k->var] = has_marked(L, k->arg, bad, degs) ||
                      (k->fn == KF_ATAN2 && has_marked(L, k->arg2, bad, degs));
    }
    int found = has_marked(L, x, bad, degs);
    flint_free(degs);
    pc_free(bad);
    return found;
}

/* output out's error: lowering gave up, or a coefficient is no double */
static void lower_error(const Lower *L, const Derived *d,
                        const DerivedOutput *out, FILE *err)
{
    char secs[48];
    budget_format_seconds(secs, sizeof secs, budget_deadline_seconds());
    if (L->stop)
        derived_error(d, err, out->span,
                      L->stop == 2 ? "%s"
                                   : "the time budget of %s ran out while "
                                     "lowering this to numbers; raise it "
                                     "with --max-seconds",
                      L->stop == 2 ? STACK_MESSAGE : secs);
    else if (L->error != LOWER_OK)
        derived_error(d, err, out->span,
                      L->error == LOWER_OVERFLOW
                          ? "%s cannot be evaluated in double precision: "
                            "scaled to integer coefficients, its equation "
                            "has a coefficient of about 10^%ld, beyond the "
                            "largest double"
                          : "%s cannot be evaluated in double precision: a "
                            "coefficient of its equation (about 10^%ld) is "
                            "below the smallest double and would be 0",
                      out->name, (long)L->error_exp10);
}

Plan *lower_derived(const Derived *d, FILE *err)
{
    Lower L;
    L.r = &d->ring;
    L.nparams = d->nparams;
    L.nconsts = d->nconsts;
    L.error = LOWER_OK;
    L.error_exp10 = 0;
    L.K = d->kernels;
    slong nk = L.K ? L.K->n : 0;
    L.shift_var = -1;
    L.shift_reg = -1;
    L.stop = 0;
    L.kreg = pc_xmalloc(sizeof(int) * (size_t)(nk ? nk : 1));
    L.kbad = pc_xmalloc(sizeof(int) * (size_t)(nk ? nk : 1));
    L.used = pc_xcalloc((size_t)(nk ? nk : 1), 1);
    for (slong i = 0; i < nk; i++)
        L.kreg[i] = L.kbad[i] = -1;
    L.p = plan_new(d->scheme, (int)d->nparams, (const char *const *)d->params,
                   (int)d->nconsts, (const char *const *)d->consts,
                   (int)d->npoints, (const char *const *)d->points);
    for (slong o = 0; o < d->noutputs; o++) {
        const DerivedOutput *out = &d->outputs[o];
        derived_mark(d, o); /* blamed if a budget runs out */
        slong n = out->kind == KIND_SCALAR ? 1 : out->eq->len;
        const RatFunStruct **ws = pc_xmalloc(sizeof *ws * (size_t)(n ? n : 1));
        int *point = pc_xmalloc(sizeof *point * (size_t)(n ? n : 1));
        int *reg = pc_xmalloc(sizeof *reg * (size_t)(n ? n : 1));
        for (slong i = 0; i < n; i++) {
            if (out->kind == KIND_SCALAR) {
                ws[i] = out->scalar;
                point[i] = -1;
            } else {
                ws[i] = &out->w[i];
                point[i] = (int)out->eq->terms[i].point;
            }
        }
        int atoms = 0;
        slong degree = 0;
        for (slong i = 0; i < n; i++) {
            slong dg = max_degree(&L, ws[i]);
            atoms |= uses_atoms(&L, ws[i]);
            degree = dg < 0 || degree < 0 ? -1 : dg > degree ? dg : degree;
        }
        int bad = -1;
        if (atoms)
            derived_error(d, err, out->span,
                          "%s depends on an unknown scalar that no solve "
                          "determined: emit-c and eval cannot give it a "
                          "value",
                          out->name);
        else if (degree < 0 || degree > DEGREE_MAX)
            derived_error(d, err, out->span,
                          "%s cannot be evaluated numerically: its equation "
                          "has degree %s%ld, beyond the limit of %d",
                          out->name, degree < 0 ? "over " : "",
                          degree < 0 ? (long)WORD_MAX : (long)degree,
                          (int)DEGREE_MAX);
        else {
            L.p->line = out->line;
            memset(L.used, 0, (size_t)(nk ? nk : 1));
            lower_weights(&L, ws, n, reg, &bad);
            /* the flags of the functions it uses (poles of their
             * arguments, domains); lowering a kernel's flags may use
             * further kernels, so this runs to a fixed point */
            unsigned char *added = pc_xcalloc((size_t)(nk ? nk : 1), 1);
            for (int again = 1; again;) {
                again = 0;
                for (slong i = 0; i < nk; i++)
                    if (L.used[i] && !added[i]) {
                        added[i] = 1;
                        again = 1;
                        if (L.kbad[i] >= 0)
                            bad = bad < 0 ? L.kbad[i]
                                          : plan_add(L.p, bad, L.kbad[i]);
                    }
            }
            pc_free(added);
            bad = bound_flags(&L, d, out, bad);
            lower_error(&L, d, out, err);
        }
        if (atoms || degree < 0 || degree > DEGREE_MAX || L.error != LOWER_OK ||
            L.stop) {
            pc_free(ws);
            pc_free(point);
            pc_free(reg);
            plan_free(L.p);
            pc_free(L.kreg);
            pc_free(L.kbad);
            pc_free(L.used);
            return NULL;
        }
        Kind kind = out->kind == KIND_SCALAR  ? KIND_SCALAR
                    : out->kind == KIND_POINT ? KIND_POINT
                                              : KIND_VECTOR;
        plan_add_output(L.p, out->name, kind, out->line, (int)n, point, reg,
                        bad);
        pc_free(ws);
        pc_free(point);
        pc_free(reg);
    }
    pc_free(L.kreg);
    pc_free(L.kbad);
    pc_free(L.used);
    plan_prune(L.p);
    return L.p;
}

Collapse *lower_collapse(Plan *p, const Derived *d)
{
    collapse_free(p->collapse);
    p->collapse = collapse_new(d, p);
    return p->collapse;
}
