/*
 * plan.h - the Plan: a flat, register-based numeric program that computes
 * the weights of a scheme's reduced point equations.  It is the one IR that
 * both back ends read: codegen/ prints it as C (emit_c.c, emit_weights.c),
 * runtime/eval.c interprets it.  runtime/ is FLINT-free; codegen/lower.c is the
 * only bridge that turns exact polynomials into a Plan.
 *
 *   register i  =  the value of instruction i  (SSA: each written once)
 *
 * Instructions are appended in dependency order, so the list is already a
 * schedule.  The builder hash-conses: asking twice for the same
 * (op, a, b) returns the same register, and operations on constants are
 * folded.  A register is *uniform* when it depends on no param (only on
 * numeric constants and the scheme's consts): back ends compute uniform
 * registers once per call, the others once per sample.
 *
 * An output M = sum_k w_k * P_k lists its weight slots (point index,
 * register) and a `bad` register: the sum of POLE flags over the factors
 * of its denominators (an integer >= 1 where one evaluates to 0) plus 0.5
 * where 1/L is 0 (the product L overflowed, and the weights would be
 * silently wrong).  Where bad != 0 the back ends write NaN
 * coordinates and report the sample as a pole (bad >= 1) or an overflow
 * (bad = 0.5) (docs/codegen.md).  A scalar output has one slot, point -1.
 */
#ifndef PC_PLAN_H
#define PC_PLAN_H

#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include "base/functions.h"
#include "base/kind.h"

/* X(name, number of register operands, C operator or NULL): one comment of
 * semantics per opcode, d = the instruction's own register. */
#define PLAN_OPS(X)                                                            \
    X(CONST, 0, NULL) /* d = consts[a]   (a literal from the constant pool) */ \
    X(INPUT, 0, NULL) /* d = input a: param a, or const a - nparams        */  \
    X(NEG, 1, "-")    /* d = -r[a]                                          */ \
    X(ADD, 2, "+")    /* d = r[a] + r[b]                                    */ \
    X(SUB, 2, "-")    /* d = r[a] - r[b]                                    */ \
    X(MUL, 2, "*")    /* d = r[a] * r[b]                                    */ \
    X(DIV, 2, "/")    /* d = r[a] / r[b]   (b is checked by a POLE first)   */ \
    X(POWI, 1, NULL)  /* d = pow(r[a], b), integer b > PLAN_POW_CHAIN       */ \
    X(POLE, 1, NULL)  /* d = (r[a] == 0) ? 1 : 0   (pole check of a den)    */ \
    X(FN, 1, NULL)    /* d = f(r[a]), f = b: a PlanFn (sqrt, sin, ...)      */ \
    X(ATAN2, 2, NULL) /* d = atan2(r[a], r[b])                              */ \
    X(DOMAIN, 1, NULL) /* d = (r[a] outside the domain of PlanFn b) ? 1 : 0 */ \
    X(DIST, 0, NULL)   /* d = |P_a - P_b|: base points a < b (uniform)     */  \
    X(COORD, 0, NULL) /* d = P_a[b]: coordinate b >= 0 of point a (uniform) */ \
    X(NATX, 1, NULL)  /* d = natx(r[a], consts[b .. b+3]): natural.h     */    \
    X(NATY, 1, NULL)  /* d = naty(r[a], consts[b .. b+3])                 */   \
    X(ISNAN, 1, NULL) /* d = (r[a] is NaN) ? 1 : 0  (natx out of reach)  */

/* x^e for 2 <= e <= PLAN_POW_CHAIN is a shared multiplication chain (error
 * below e/2 ulp, vectorisable); higher powers call pow() (about 1 ulp). */
enum { PLAN_POW_CHAIN = 32 };

/* The functions of FN: b = the PlanFn | (q << 8) for the real q-th root.
 * Their values and domains are defined once, here, for the runtime, the
 * folding of constants and (as C text) emit_c.c. */
typedef enum PlanFn {
/* the rows of base/functions.def with plan = 1; PLAN_FN_ROOT is the
 * real q-th root (odd q: also of negative numbers) */
#define PC_FUNCTION(ID, name, ar, lang, k, p, c, latex, dom)                   \
    PC_WHEN(p)(PLAN_FN_##ID, )
#include "base/functions.def"
#undef PC_FUNCTION
    PLAN_NFNS
} PlanFn;

/* each PlanFn's domain (functions.def), and the C library function
 * generated code calls for it (NULL: written inline) */
static const PcDomain plan_fn_domain[PLAN_NFNS] = {
#define PC_FUNCTION(ID, name, ar, lang, k, p, c, latex, dom)                   \
    PC_WHEN(p)([PLAN_FN_##ID] = dom, )
#include "base/functions.def"
#undef PC_FUNCTION
};

/* A DOMAIN flag counts this much in an output's bad register (plan.h's
 * pole flags count 1 each, an overflow 0.5): bad >= PLAN_DOMAIN_FLAG is a
 * sample where a function's argument is outside its domain. */
#define PLAN_DOMAIN_FLAG 1048576.0

static inline double plan_fn_eval(int b, double x)
{
    int q = b >> 8;
    switch ((PlanFn)(b & 255)) {
    case PLAN_FN_SQRT:
        return sqrt(x);
    case PLAN_FN_ROOT:
        if (q == 3)
            return cbrt(x);
        if (q % 2 && x < 0)
            return -pow(-x, 1.0 / q);
        return pow(x, 1.0 / q);
    case PLAN_FN_SIN:
        return sin(x);
    case PLAN_FN_COS:
        return cos(x);
    case PLAN_FN_SINH:
        return sinh(x);
    case PLAN_FN_COSH:
        return cosh(x);
    case PLAN_FN_EXP:
        return exp(x);
    case PLAN_FN_LN:
        return log(x);
    case PLAN_FN_ASIN:
        return asin(x);
    case PLAN_FN_ACOS:
        return acos(x);
    case PLAN_FN_ATAN:
        return atan(x);
    case PLAN_FN_SIGN:
        return (double)((x > 0) - (x < 0));
    default:
        return NAN;
    }
}

/* the domain of PlanFn b: its row's, and for the real q-th root x >= 0
 * when q is even */
static inline PcDomain plan_fn_domain_of(int b)
{
    int f = b & 255;
    if (f == PLAN_FN_ROOT)
        return (b >> 8) % 2 == 0 ? PC_DOM_NONNEG : PC_DOM_ALL;
    return f < PLAN_NFNS ? plan_fn_domain[f] : PC_DOM_ALL;
}

/* 1 when PlanFn b has a restricted domain (needs a DOMAIN check) */
static inline int plan_fn_has_domain(int b)
{
    return plan_fn_domain_of(b) != PC_DOM_ALL;
}

/* 1.0 where x is outside the domain of PlanFn b (NaN is not: it shows as
 * a non-finite value) */
static inline double plan_domain_eval(int b, double x)
{
    switch (plan_fn_domain_of(b)) {
    case PC_DOM_NONNEG:
        return (double)(x < 0.0);
    case PC_DOM_POS:
        return (double)(x <= 0.0);
    case PC_DOM_UNIT:
        return (double)(fabs(x) > 1.0);
    default:
        return 0.0;
    }
}

typedef enum PlanOp {
#define PLAN_ENUM(name, nargs, cop) PLAN_##name,
    PLAN_OPS(PLAN_ENUM)
#undef PLAN_ENUM
        PLAN_NOPS
} PlanOp;

typedef struct PlanIns {
    uint8_t op;      // PlanOp
    uint8_t uniform; // 1: depends on no param (computed once per call)
    int32_t a, b;    // operands: registers, or pool/input index, exponent
    int32_t line;    // scheme line of the output that first needed it
} PlanIns;

/* an output's kind is base/kind.h's: a scalar is one value (slot 0 with
 * point -1), a point's weights sum to 1, a vector's to 0 */

typedef struct PlanOutput {
    char *name; // owned
    Kind kind;
    int line;   // definition line in the scheme
    int nterms; // weight slots
    int *point; // owned: base point index of slot k (-1 for a scalar)
    int *reg;   // owned: register holding weight k
    int bad;    // register of pole flags + 0.5 overflow flag, or -1 (no den)
} PlanOutput;

/* A declared bound of a param or const that the derivation assumed (a
 * result simplified on it: abs(t) = t for t in [0, 1]); the outputs that
 * rest on it flag a value outside as status 4 (their bad register does),
 * and this says which input it was, for messages. */
enum {
    PLAN_BOUND_LO = 1,      // lo is assumed: the input is >= lo
    PLAN_BOUND_HI = 2,      // hi is assumed: the input is <= hi
    PLAN_BOUND_LO_OPEN = 4, // ... > lo
    PLAN_BOUND_HI_OPEN = 8, // ... < hi
};
typedef struct PlanBound {
    double lo, hi;
    unsigned char flags; // PLAN_BOUND_*; 0: nothing assumed
    char *text;          // owned: the declared interval as written by
                         // the derivation ("[0, 1]", "(0, 2*pi]"), or NULL
} PlanBound;

/* The collapsed form of each output, for emit-c --kernel collapsed
 * (codegen/collapse.h, docs/codegen.md "The collapsed kernel"): computed
 * exactly while lowering (lower_collapse) and kept here as plain data, so
 * that the C writer reads only the Plan. */
typedef struct CollapseOutput {
    char *name;    // the plan output's name (owned)
    int ok;        // 1: collapsed (the fields below); 0: why says why
    char *why;     // owned; also set when ok ("monomial basis ...")
    int param;     // the param t (index)
    int deg;       // n: the largest degree of the n_k and d in t
    int nterms;    // K
    int *point;    // K base point indices (owned)
    double *a;     // (deg + 1) * K, a[j * K + k] (owned)
    double *b;     // deg + 1 (owned)
    double mid;    // m
    double scale;  // 2^-e
    double lo, hi; // the doubles in [a, b]: the smallest and the largest
    double kappa, kappa_d, bound;
} CollapseOutput;

typedef struct Collapse {
    int n; // = the plan's outputs, in its order
    CollapseOutput *o;
} Collapse;

/* frees a Collapse (NULL: nothing) */
void collapse_free(Collapse *c);

typedef struct Plan {
    char *name; // scheme name (owned): prefix of generated C names
    int nparams, nconsts, npoints;
    char **params, **consts, **points; // owned names, declaration order
    int nins, ains;
    PlanIns *ins; // the program
    int nk, ak;
    double *k; // constant pool
    int noutputs;
    PlanOutput *outputs;
    PlanBound *bound;   // nparams + nconsts entries (params, then consts), or
                        // NULL: no bound assumed
    Collapse *collapse; // the outputs' collapsed forms, in their order
                        // (lower_collapse; emit-c --kernel collapsed), or
                        // NULL
    /* builder state */
    int32_t *hash; // open addressing table of instruction indices, or NULL
    int hcap;
    int line; // line stamped on new instructions
} Plan;

/* Plan with the given names (copied); no instructions, no outputs. */
Plan *plan_new(const char *name, int nparams, const char *const *params,
               int nconsts, const char *const *consts, int npoints,
               const char *const *points);
void plan_free(Plan *p);

/* 1 when value x of input i (params, then consts) lies outside the bounds
 * p assumed of it (PlanBound) */
int plan_out_of_bounds(const Plan *p, int i, double x);

/* What the bad register says of a sample. */
typedef enum PlanStatus {
    PLAN_STATUS_OK = 0,
    PLAN_STATUS_POLE = 1,     // a denominator factor is 0
    PLAN_STATUS_OVERFLOW = 2, // a denominator is not finite
    PLAN_STATUS_DOMAIN = 4,   // a function's argument is outside its
                              // domain (sqrt of a negative number ...);
                              // 3 is the _checked functions' "not finite"
} PlanStatus;

static inline PlanStatus plan_status(double bad)
{
    return bad >= PLAN_DOMAIN_FLAG ? PLAN_STATUS_DOMAIN
           : bad >= 1              ? PLAN_STATUS_POLE
           : bad != 0              ? PLAN_STATUS_OVERFLOW
                                   : PLAN_STATUS_OK;
}

/* Builder.  Each returns a register; equal requests give equal registers,
 * constant operands are folded, trivial identities (x*1, x+0, --x) are
 * simplified. */
int plan_const(Plan *p, double v);
int plan_input(Plan *p, int index); // params then consts
int plan_neg(Plan *p, int a);
int plan_add(Plan *p, int a, int b);
int plan_sub(Plan *p, int a, int b);
int plan_mul(Plan *p, int a, int b);
int plan_div(Plan *p, int a, int b);
int plan_pow(Plan *p, int a, long e); // e >= 0; shares the powers it builds
int plan_pole(Plan *p, int den);
int plan_fn(Plan *p, int fn, int a); // f(a), fn a PlanFn | q << 8
int plan_atan2(Plan *p, int y, int x);
int plan_domain(Plan *p, int fn, int a); // the domain flag of f(a)
int plan_dist(Plan *p, int a, int b);    // |P_a - P_b|, base points a < b
int plan_coord(Plan *p, int a, int c);   // P_a[c], 0-based coordinate c
/* natx(u) (y = 0) or naty(u) (y = 1) of the curvature law k[0 .. 3]
 * (runtime/natural.h): the law goes to the constant pool */
int plan_natural(Plan *p, int y, int u, const double *k);
/* 1 where register a is NaN, else 0: the domain flag of a natx or naty
 * (natural.h: NaN beyond NAT_MAX_TURNING radians of turning) */
int plan_isnan(Plan *p, int a);
/* the value of NATX (y = 0) or NATY at u for law k (natural.h) */
double plan_natural_eval(int y, const double *k, double u);

/* P[c] when the points have dim > c coordinates, else NaN (never read
 * beyond the point: eval and the C API refuse such a dim first) */
static inline double plan_coord_eval(const double *P, int c, int dim)
{
    return c < dim ? P[c] : NAN;
}
/* the number of coordinates output o needs (the largest c + 1 of the
 * coordinates it reads: coord(P, k)), 0 when it reads none; *point (if
 * not NULL) = a base point whose coordinate c it reads, or -1 */
int plan_output_min_dim(const Plan *p, int o, int *point);

/* |P - Q| in dim coordinates (the metric atoms: the same sum everywhere) */
static inline double plan_dist_eval(const double *P, const double *Q, int dim)
{
    double s = 0;
    for (int c = 0; c < dim; c++)
        s += (P[c] - Q[c]) * (P[c] - Q[c]);
    return sqrt(s);
}
/* Appends an output; consumes nothing (arrays are copied). */
void plan_add_output(Plan *p, const char *name, Kind kind, int line, int nterms,
                     const int *point, const int *reg, int bad);

/* Splits a weight register w into  w = sign * root  (negations peeled), so
 * that a back end can negate the points' coordinates once per call instead
 * of the weight every sample.  Only the sign: it is exact, whereas moving
 * a constant or const factor k onto the coordinates could overflow where
 * w itself does not (k = 1e300, B = 1e10).  Returns root; *sign is +-1. */
int plan_peel(const Plan *p, int w, int *sign);

/* Removes instructions no output needs and renumbers (keeps the order). */
void plan_prune(Plan *p);
/* Keeps only outputs sel[0..n-1] (distinct indices), in that order, and
 * prunes what the others alone needed (emit-c --output). */
void plan_keep_outputs(Plan *p, const int *sel, int n);

/* live[i] = 1 for every instruction output `o` needs (all outputs: o < 0). */
void plan_live(const Plan *p, int o, unsigned char *live);
/* Marks the operands of every marked instruction, transitively. */
void plan_live_close(const Plan *p, unsigned char *live);

/* Deterministic text dump: one instruction per line, then the outputs. */
void plan_dump(FILE *out, const Plan *p);

/* Name of an opcode ("mul"); its number of register operands. */
const char *plan_op_name(PlanOp op);
int plan_op_nargs(PlanOp op);

/* Index of the output called name, or -1. */
int plan_find_output(const Plan *p, const char *name);

#endif
