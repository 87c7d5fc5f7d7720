/*
 * kernel.h - transcendental and algebraic atoms as ring variables.
 *
 * A kernel is a variable of the compilation's ring that stands for f(arg):
 * sin(phi), sqrt(a^2 - b^2), exp(t), pi.  Its argument is kept canonical
 * (a reduced RatFun over the variables before it), so equal kernels are one
 * variable whatever the spelling: sin(2*t) and sin(t + t) are the same
 * kernel, sin(-t) is -sin(t).  The ring reserves the kernel slots when it is
 * built (kernels_slots estimates how many a scheme can need); a scheme that
 * asks for more gets a located error, never a crash.
 *
 * Identities are applied by a normal form: some kernels carry a relation
 * v^q = rel (rel a RatFun of earlier variables):
 *
 *   cos(a)^2  = 1 - sin(a)^2     (cos is created with sin, right after it)
 *   cosh(a)^2 = 1 + sinh(a)^2
 *   sqrt(a)^2 = a,   root(a, q)^q = a,   sign(a)^2 = 1
 *
 * kernel_reduce rewrites every power v^k (k >= q) with the relation and
 * rationalises denominators that are linear in a quadratic kernel (multiply
 * by the conjugate).  With squares pulled out of square roots
 * (sqrt(x^2*y) = abs(x)*sqrt(y), abs(x) = x*sign(x)), the relations form a
 * triangular set of irreducible polynomials (and squares modulo the
 * relations come out too: sqrt((1 + cos(t))^2) = abs(1 + cos(t)), whose
 * argument reduces to 2 + 2*cos(t) - sin(t)^2), so a reduced numerator is zero
 * exactly when the value is zero: weight sums and degenerate geometry are
 * decided exactly where these identities decide them.  Identities beyond
 * them (sin(2a) = 2 sin(a) cos(a), sqrt(x)*sqrt(y) = sqrt(x*y)) are not
 * applied: such a value is kept as written.
 *
 * Rewrites applied when a kernel is made: tan = sin/cos, tanh = sinh/cosh,
 * abs(x) = x*sign(x), exp(a + b) = exp(a)*exp(b), exp(k*a) = exp(a)^k,
 * exp(ln(x)) = x, ln(exp(x)) = x, odd and even symmetry (sin(-a) =
 * -sin(a), cos(-a) = cos(a), acos(-a) = pi - acos(a) ...), and exact values
 * at numbers (sin(0) = 0, cos(pi) = -1, sin(pi/6) = 1/2, sqrt(8) =
 * 2*sqrt(2), asin(1) = pi/2 ...).
 */
#ifndef PC_KERNEL_H
#define PC_KERNEL_H

#include "base/functions.h"
#include "compiler/algebra/pteq.h"
#include "compiler/algebra/ratfun.h"
#include "compiler/algebra/ring.h"

/* the functions a kernel can stand for: the rows of base/functions.def
 * with kernel = 1 (pi, sqrt, the real q-th root of x^(p/q), sin, ...), then
 * the metric atoms */
typedef enum KernelFn {
#define PC_FUNCTION(ID, name, ar, lang, k, p, c, latex, dom)                   \
    PC_WHEN(k)(KF_##ID, )
#include "base/functions.def"
#undef PC_FUNCTION
    KF_DIST,  // |P_a P_b| of two base points: the metric
    KF_COORD, // coordinate pb (1-based) of base point pa
    KF_NATX,  // natx(u, k0, k1, k2, k3): int_0^u cos(psi), the law q
    KF_NATY,  // naty(...): int_0^u sin(psi) (kernel_natural.c)
    KF_COUNT
} KernelFn;

/* a kernel function's name as the language writes it ("dist", "coord" for
 * the metric atoms) */
extern const char *const kernel_fn_names[KF_COUNT];
/* its LaTeX operator (\sin, \ln, ...), or NULL: written its own way */
extern const char *const kernel_fn_latex[KF_COUNT];

typedef struct Kernel {
    KernelFn fn;
    slong var;    // its ring variable
    slong q;      // KF_ROOT: the index of the root (>= 3); KF_NATX, KF_NATY:
                  // the curvature law's index (kernels_law); else 0
    slong pa, pb; // KF_DIST: the base points, pa < pb; KF_COORD: the base
                  // point and the coordinate's number k >= 1
    RatFun arg;   // the canonical argument (KF_ATAN2: y); 0 for pi
    RatFun arg2;  // KF_ATAN2: x
    slong deg;    // the relation var^deg = rel, or 0: none
    RatFun rel;
    char *name;  // text, as printed ("sin(phi)")
    char *latex; // LaTeX
} Kernel;

/* a declared interval of a param or const: [lo, hi], each end present or
 * not, open or closed (kernels_set_range) */
typedef struct KRange {
    fmpq_t lo, hi;
    unsigned char has_lo, has_hi, lo_open, hi_open;
} KRange;

typedef struct Kernels {
    Ring *r;
    slong first; // the first kernel variable
    slong cap;   // kernel slots in the ring
    slong n;     // kernels made: variables first .. first+n-1
    Kernel *k;
    int nrel;        // kernels with a relation
    int full;        // a kernel was refused: no slot left (KERNEL_EFULL)
    double deadline; // CLOCK_MONOTONIC seconds (the derivation's time
                     // budget), 0: none; KERNEL_ETIME past it
    const char *const *points; // base point names (for dist names)
    slong npoints;
    fmpq *laws;          // KF_NATX/KF_NATY: the curvature laws, KERNEL_LAW_LEN
    slong nlaws;         // coefficients each (k0 .. k3), distinct
    KRange *range;       // per ring variable before the kernels: the
                         // declared interval (kernels_set_range)
    unsigned char *used; // per such variable: the ends of its declared
                         // interval a sign proof rested on (kernels_assumed)
    unsigned char *cur;  // the same, since the caller last cleared it (the
                         // assumptions of one definition: derive.c)
    /* an error message of the last failed call (static storage) */
    const char *why;
} Kernels;

/* Errors of the calls below (0 is success). */
enum {
    KERNEL_EFULL = -10,   // no kernel slot left
    KERNEL_EDOMAIN = -11, // a number outside the function's domain: why
    KERNEL_EZERO = -12,   // a denominator vanishes by the identities
    KERNEL_EBIG = -13,    // a power or an argument beyond the size limits
    KERNEL_ETIME = -14,   // the time budget ran out inside an operation
    KERNEL_ESTACK = -15,  // the thread's stack ran low (base/stack.h) in
                          // a recursion over nested functions
};

/* intermediate polynomials of the normal form and of substitution stop
 * here (KERNEL_EBIG) */
#define KERNEL_MAX_WORK_TERMS 200000

/* The number of kernel slots a scheme may need, from its count of
 * function calls and rational powers (calls), of subst() and diff() uses
 * (ops) and of uses of pi: 0 when it has none. */
slong kernels_slots(slong calls, slong ops, slong pis);
/* the most slots a derivation retries with (derive.c doubles them) */
#define KERNELS_MAX_SLOTS 1024
/* ... and for the metric atoms (dot, dist, angle): the distances of the
 * npoints base points */
slong kernels_metric_slots(slong metric, slong npoints);

/* K manages the ring variables first .. first+cap-1 of r (r's names of
 * those variables are set as kernels are made). */
void kernels_init(Kernels *K, Ring *r, slong first, slong cap);
void kernels_clear(Kernels *K);

/* What is known of a value's sign (kernel_sign.c): the declared intervals
 * of params and consts (`param t in [0, 1]`, `const e in (0, 1)`, `const a
 * > 0`) and the ranges of the kernels (sin in [-1, 1], exp > 0, ...). */
enum { KSIGN_UNKNOWN = 0, KSIGN_NONNEG = 1, KSIGN_POS = 2 };
/* var >= 0 (KSIGN_NONNEG) or > 0 (KSIGN_POS), intersected with what is
 * declared already */
void kernels_set_sign(Kernels *K, slong var, int sign);
/* var in the interval lo..hi (an end NULL: unbounded; *_open: excluded),
 * intersected with what is declared already */
void kernels_set_range(Kernels *K, slong var, const fmpq_t lo, int lo_open,
                       const fmpq_t hi, int hi_open);
/* which ends of var's declared interval a sign that kernel_sign proved
 * rested on (1: the lower, 2: the upper, 3: both): the derivation assumed
 * them (the numeric side checks them) */
int kernels_assumed(const Kernels *K, slong var);
/* +1 when x >= 0 is proved (+2: x > 0), -1 / -2 for x <= 0 / x < 0, 0 when
 * unknown, by interval arithmetic over the declared and intrinsic
 * intervals, and factor by factor where that fails.  abs(), sign() and
 * the squares pulled out of sqrt() use it: sqrt(a^2) = a for `const a >
 * 0`, sign(a)*a otherwise.  A proved sign records the declared intervals
 * it used (kernels_assumed). */
int kernel_sign(const Kernels *K, const RatFun x);
/* the same for a polynomial */
int kernel_sign_poly(const Kernels *K, const fmpz_mpoly_t p);
/* Rational bounds lo <= x <= hi (strict where *_open) of a constant x:
 * a value with no variable but kernels (2*pi, sqrt(2)/2), by the kernels'
 * intervals.  Returns 1 | 2 for the bounds found (lo, hi), 0 for none (x
 * depends on a param or const, or has a kernel in its denominator). */
int kernel_bounds(const Kernels *K, const RatFun x, fmpq_t lo, int *lo_open,
                  fmpq_t hi, int *hi_open);

/* the kernel of ring variable var, or NULL (a param, a const ...) */
const Kernel *kernels_of_var(const Kernels *K, slong var);

/* res = a kernel made again from new arguments: x (and y for KF_ATAN2)
 * reduced, then f applied to them, the real q-th root for KF_ROOT; what
 * every substitution does to a kernel whose argument it changes
 * (kernel_compose, subst of coordinates, the knots' one-sided forms).  x
 * and y are changed. */
int kernel_remake(Kernels *K, RatFun res, KernelFn f, slong q, RatFun x,
                  RatFun y);
/* res = f(x) (res = atan2(x, y) for KF_ATAN2; y NULL otherwise), reduced.
 * KF_PI ignores x. */
int kernel_apply(Kernels *K, RatFun res, KernelFn f, const RatFun x,
                 const RatFun y);
/* res = |P_a P_b|, the distance of base points a and b (named by
 * K->points); a variable that is > 0 (0 when a == b) */
int kernel_dist(Kernels *K, RatFun res, slong a, slong b);

/* Coordinates (coord(P, k), docs/language.md "Coordinates"): the k-th
 * Cartesian coordinate of base point a is a variable with no relation and
 * no known sign, whose derivative by every param is 0; coord is linear,
 * so a combination's coordinate is the combination of its points'. */
/* res = coord(P, k) = sum_i w_i coord(A_i, k) for a combination P of base
 * points (no unknown columns) */
int kernel_coord_pteq(Kernels *K, RatFun res, const PointEq P, slong k);
/* x with every coord(A_point, k) it uses (also inside functions'
 * arguments) replaced by coord(P, k), all at once: the coordinates'
 * part of subst(x, A, P); res = x when x uses none */
int kernel_subst_coords(Kernels *K, RatFun res, const RatFun x, slong point,
                        const PointEq P);
int kernel_subst_coords_pteq(Kernels *K, PointEq res, const PointEq x,
                             slong point, const PointEq P);
/* the kernel slots the coordinates of npoints base points need, for
 * nindices distinct k */
slong kernels_coord_slots(slong nindices, slong npoints);

/* res = x^(p/q), q > 1, gcd(p, q) = 1, |p| and q at most 1000 */
int kernel_pow_q(Kernels *K, RatFun res, const RatFun x, slong p, slong q);
/* res = |x| = x*sign(x) */
int kernel_abs(Kernels *K, RatFun res, const RatFun x);

/* Normal form modulo the relations (in place); KERNEL_EZERO when the
 * denominator reduces to zero. */
int kernel_reduce(Kernels *K, RatFun x);
int kernel_reduce_pteq(Kernels *K, PointEq x);
/* 1 when x uses a kernel variable with a relation (reduction can change
 * it), or any kernel at all (any = 1) */
int kernel_uses(const Kernels *K, const RatFun x, int any);
int kernel_uses_pteq(const Kernels *K, const PointEq x, int any);

/* 1 when x uses a distance to base point `point` (directly or inside a
 * function's argument) */
int kernel_measures_point(const Kernels *K, const PointEq x, slong point);

/* the total derivative d x / d var (the chain rule through kernels) */
int kernel_derivative(Kernels *K, RatFun res, const RatFun x, slong var);
int kernel_derivative_pteq(Kernels *K, PointEq res, const PointEq x, slong var);
/* x with var replaced by s, also inside kernels (sin(t) -> sin(s));
 * KERNEL_EZERO / RATFUN_EPOLE when a denominator vanishes */
int kernel_compose(Kernels *K, RatFun res, const RatFun x, slong var,
                   const RatFun s);
int kernel_compose_pteq(Kernels *K, PointEq res, const PointEq x, slong var,
                        const RatFun s);

/* Natural curves (docs/language.md, "Natural curves"): the point at arc
 * length u of the curve that starts at the origin with angle 0 and whose
 * curvature is k(s) = k0 + k1 s + k2 s^2 + k3 s^3, so that its tangent
 * angle is psi(s) = k0 s + k1 s^2/2 + k2 s^3/3 + k3 s^4/4:
 *
 *   natx(u, k) = int_0^u cos(psi(s)) ds,   naty(u, k) = int_0^u sin(psi(s)) ds
 *
 * The law's coefficients are numbers (a law is interned once per scheme:
 * the kernel's q); u is any expression.  d/dt natx(u, k) = cos(psi(u)) u'
 * and naty's with sin: exact.  A law of degree 0 folds: natx(u, k0) =
 * sin(k0 u)/k0, naty(u, k0) = (1 - cos(k0 u))/k0 (u and 0 for k0 = 0);
 * natx(0, k) = naty(0, k) = 0. */
enum { KERNEL_LAW_LEN = 4 };
/* res = natx(u, k) (f = KF_NATX) or naty(u, k) (KF_NATY), k[0 .. 3] */
int kernel_natural(Kernels *K, RatFun res, KernelFn f, const fmpq *k,
                   const RatFun u);
/* the law of kernel q's index: KERNEL_LAW_LEN coefficients */
const fmpq *kernels_law(const Kernels *K, slong q);

#endif
