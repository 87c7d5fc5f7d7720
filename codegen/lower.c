/*
 * lower.c - exact weights (fmpz_mpoly num/den) -> Plan instructions.
 *
 * The pipeline for one output (formula in lower.h):
 *
 *   factor every numerator and denominator (fmpz_mpoly_factor; a
 *     polynomial too big to factor cheaply stays one factor)
 *   lower every irreducible factor once, in Horner form   -> registers
 *   L = the lcm of the denominators, as {factor register: max exponent}
 *   bad = pole(L),  inv = 1/L
 *   w_i = c_i * prod(num factors) * prod(L / d_i) * inv
 *
 * Factors are identified by their register: the Plan builder hash-conses,
 * so the same polynomial lowered twice is the same register, and t - 1 in
 * the numerator of one weight is t - 1 in the next.  An output with a
 * single weight (a scalar) divides directly instead of multiplying by an
 * inverse.  Constant denominators never reach the Plan: they are folded
 * into the constant c_i (or into the Horner coefficients).
 */
#include "codegen/lower.h"

#include <stdlib.h>
#include <string.h>

#include <flint/fmpq.h>
#include <flint/fmpz_mpoly_factor.h>

enum { FACTOR_MAX_TERMS = 400 }; // bigger polynomials are not factored

typedef struct Lower {
    Plan *p;
    const Ring *r;
    slong nparams, nconsts;
} Lower;

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
    free(F->f);
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
        F->f = realloc(F->f, sizeof *F->f * (size_t)F->alloc);
        if (!F->f)
            abort();
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

/* the product of the factors (not the constant), in register order so that
 * equal products give equal registers */
static int factored_product(Lower *L, Factored *F)
{
    int acc = plan_const(L->p, 1);
    if (F->n > 1)
        qsort(F->f, (size_t)F->n, sizeof *F->f, cmp_factor);
    for (slong i = 0; i < F->n; i++)
        if (F->f[i].exp > 0)
            acc = plan_mul(L->p, acc, plan_pow(L->p, F->f[i].reg, F->f[i].exp));
    return acc;
}

/* x * c for an exact constant c */
static int mul_fmpq(Lower *L, int x, const fmpq_t c)
{
    if (fmpq_is_one(c))
        return x;
    return plan_mul(L->p, x, plan_const(L->p, fmpq_get_d(c)));
}

/* ---- Horner form -------------------------------------------------------- */

/* The main variable of P: a param if P has one (so the coefficients, in the
 * consts, are uniform and computed once per call), the one of highest
 * degree, ties to the first declared. */
static slong main_var(const Lower *L, const slong *degs)
{
    slong best = -1;
    for (slong v = 0; v < L->nparams; v++)
        if (degs[v] > 0 && (best < 0 || degs[v] > degs[best]))
            best = v;
    if (best >= 0)
        return best;
    for (slong v = L->nparams; v < L->nparams + L->nconsts; v++)
        if (degs[v] > 0 && (best < 0 || degs[v] > degs[best]))
            best = v;
    return best;
}

/* P * scale in recursive Horner form:
 *   P = sum_k c_k x^k  ->  ((c_n x^(n-m) + c_m) x^(m-l) + c_l) ... x^low
 * with the gaps of a sparse P as shared powers, coefficients recursively. */
static int horner(Lower *L, const fmpz_mpoly_t P, const fmpq_t scale)
{
    const fmpz_mpoly_ctx_struct *ctx = L->r->ctx;
    if (fmpz_mpoly_is_fmpz(P, ctx)) {
        fmpz_t c;
        fmpq_t q;
        fmpz_init(c);
        fmpq_init(q);
        fmpz_mpoly_get_fmpz(c, P, ctx);
        fmpq_mul_fmpz(q, scale, c);
        int reg = plan_const(L->p, fmpq_get_d(q));
        fmpq_clear(q);
        fmpz_clear(c);
        return reg;
    }
    slong nv = ctx->minfo->nvars;
    slong *degs = flint_malloc(sizeof *degs * (size_t)nv);
    fmpz_mpoly_degrees_si(degs, P, ctx);
    slong var = main_var(L, degs);
    slong deg = degs[var];
    flint_free(degs);

    fmpz_mpoly_t C;
    fmpz_mpoly_init(C, ctx);
    int x = plan_input(L->p, (int)var);
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
    if (fmpz_mpoly_length(P, ctx) <= FACTOR_MAX_TERMS &&
        fmpz_mpoly_factor(f, P, ctx)) {
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
    Factored *num = malloc(sizeof *num * (size_t)(n ? n : 1));
    Factored *den = malloc(sizeof *den * (size_t)(n ? n : 1));
    Factored lcm;
    if (!num || !den)
        abort();
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
    *bad = -1;
    if (lcm.n == 0) {
        for (slong i = 0; i < n; i++)
            reg[i] = mul_fmpq(L, factored_product(L, &num[i]), num[i].c);
    } else if (n == 1) {
        int d = factored_product(L, &den[0]);
        *bad = plan_pole(L->p, d);
        reg[0] = mul_fmpq(L, plan_div(L->p, factored_product(L, &num[0]), d),
                          num[0].c);
    } else {
        int d = factored_product(L, &lcm);
        *bad = plan_pole(L->p, d);
        int inv = plan_div(L->p, plan_const(L->p, 1), d);
        for (slong i = 0; i < n; i++) {
            /* num_i * L/d_i */
            for (slong j = 0; j < lcm.n; j++) {
                slong e = lcm.f[j].exp - factored_exp(&den[i], lcm.f[j].reg);
                if (e > 0)
                    factored_mul(&num[i], lcm.f[j].reg, e);
            }
            int w = plan_mul(L->p, factored_product(L, &num[i]), inv);
            reg[i] = mul_fmpq(L, w, num[i].c);
        }
    }
    for (slong i = 0; i < n; i++) {
        factored_clear(&num[i]);
        factored_clear(&den[i]);
    }
    factored_clear(&lcm);
    free(num);
    free(den);
}

/* does x use a ring variable that is neither a param nor a const? */
static int uses_atoms(const Lower *L, const RatFunStruct *x)
{
    const fmpz_mpoly_ctx_struct *ctx = L->r->ctx;
    slong nv = ctx->minfo->nvars, first = L->nparams + L->nconsts;
    if (first >= nv)
        return 0;
    slong *degs = flint_malloc(sizeof *degs * (size_t)nv);
    int found = 0;
    for (int k = 0; k < 2 && !found; k++) {
        fmpz_mpoly_degrees_si(degs, k ? x->den : x->num, ctx);
        for (slong v = first; v < nv; v++)
            if (degs[v] > 0)
                found = 1;
    }
    flint_free(degs);
    return found && first < L->r->nvars;
}

Plan *lower_derived(const Derived *d, FILE *err)
{
    Lower L;
    L.r = &d->ring;
    L.nparams = d->nparams;
    L.nconsts = d->nconsts;
    L.p = plan_new(d->scheme, (int)d->nparams, (const char *const *)d->params,
                   (int)d->nconsts, (const char *const *)d->consts,
                   (int)d->npoints, (const char *const *)d->points);
    for (slong o = 0; o < d->noutputs; o++) {
        const DerivedOutput *out = &d->outputs[o];
        slong n = out->kind == KIND_SCALAR ? 1 : out->eq->len;
        const RatFunStruct **ws = malloc(sizeof *ws * (size_t)(n ? n : 1));
        int *point = malloc(sizeof *point * (size_t)(n ? n : 1));
        int *reg = malloc(sizeof *reg * (size_t)(n ? n : 1));
        if (!ws || !point || !reg)
            abort();
        for (slong i = 0; i < n; i++) {
            if (out->kind == KIND_SCALAR) {
                ws[i] = out->scalar;
                point[i] = -1;
            } else {
                ws[i] = &out->eq->terms[i].w;
                point[i] = (int)out->eq->terms[i].point;
            }
        }
        int atoms = 0;
        for (slong i = 0; i < n; i++)
            atoms |= uses_atoms(&L, ws[i]);
        if (atoms) {
            if (err)
                fprintf(err,
                        "pointcalc: output %s uses symbolic atoms that "
                        "emit-c and eval cannot evaluate yet\n",
                        out->name);
            free(ws);
            free(point);
            free(reg);
            plan_free(L.p);
            return NULL;
        }
        int bad = -1;
        L.p->line = out->line;
        lower_weights(&L, ws, n, reg, &bad);
        PlanKind kind = out->kind == KIND_SCALAR  ? PLAN_SCALAR
                        : out->kind == KIND_POINT ? PLAN_POINT
                                                  : PLAN_VECTOR;
        plan_add_output(L.p, out->name, kind, out->line, (int)n, point, reg,
                        bad);
        free(ws);
        free(point);
        free(reg);
    }
    plan_prune(L.p);
    return L.p;
}
