/*
 * ratfun.h - exact multivariate rational functions over Q.
 *
 * A RatFun is num/den with num, den in Z[x1..xn] (fmpz_mpoly over one Ring),
 * kept CANONICAL on entry and exit of every public function, as FLINT 3's
 * fmpz_mpoly_q documents it:
 *   - gcd(num, den) = 1 (as polynomials over Z, content included),
 *   - den has a positive leading coefficient (in the ring's ordering),
 *   - zero is 0/1.
 * So two RatFuns are equal iff their nums and dens are equal.
 *
 * Conventions (FLINT's): result first, inputs next, ring last; every result
 * may alias any input.  Functions returning int return 0 on success and a
 * negative RATFUN_E* code on a mathematical failure (never abort on user
 * input).
 */
#ifndef PC_RATFUN_H
#define PC_RATFUN_H

#include <flint/fmpq.h>
#include <flint/fmpz_mpoly.h>

#include "compiler/algebra/ring.h"

typedef struct RatFunStruct {
    fmpz_mpoly_t num; // numerator
    fmpz_mpoly_t den; // denominator, lc > 0, coprime to num
} RatFunStruct;
typedef RatFunStruct RatFun[1];

enum {
    RATFUN_OK = 0,
    RATFUN_EDIVZERO = -1,  // division by an identically zero function
    RATFUN_ESYNTAX = -2,   // ratfun_set_str: malformed text
    RATFUN_ENAME = -3,     // ratfun_set_str: unknown variable name
    RATFUN_EPOLE = -4,     // evaluation/substitution where the den vanishes
    RATFUN_EOVERFLOW = -5, // exponent too large (FLINT's limit or set_str's
                           // cap of RATFUN_STR_MAX_EXP)
};

/* ratfun_set_str rejects exponents (x^e, 1e+e) beyond this magnitude with
 * RATFUN_EOVERFLOW, so text cannot make it build gigantic polynomials. */
#define RATFUN_STR_MAX_EXP 4096

void ratfun_init(RatFun x, const Ring *r); // x = 0
void ratfun_clear(RatFun x, const Ring *r);
void ratfun_swap(RatFun x, RatFun y, const Ring *r);
/* len initialised zeros (never NULL, also for len 0), and their release */
RatFunStruct *ratfun_vec_init(slong len, const Ring *r);
void ratfun_vec_clear(RatFunStruct *v, slong len, const Ring *r);
void ratfun_set(RatFun res, const RatFun x, const Ring *r);

void ratfun_zero(RatFun res, const Ring *r);
void ratfun_one(RatFun res, const Ring *r);
void ratfun_set_si(RatFun res, slong c, const Ring *r);
void ratfun_set_fmpq(RatFun res, const fmpq_t c, const Ring *r);
/* res = the variable with index var */
void ratfun_gen(RatFun res, slong var, const Ring *r);

int ratfun_is_zero(const RatFun x, const Ring *r);
int ratfun_is_one(const RatFun x, const Ring *r);
/* constant: no variable occurs (ratfun_get_fmpq returns the value) */
int ratfun_is_constant(const RatFun x, const Ring *r);
int ratfun_get_fmpq(fmpq_t c, const RatFun x, const Ring *r); // 1 if constant
int ratfun_equal(const RatFun x, const RatFun y, const Ring *r);
/* checks the invariant above; for asserts and tests */
int ratfun_is_canonical(const RatFun x, const Ring *r);
/* does variable var occur in x? */
int ratfun_depends_on(const RatFun x, slong var, const Ring *r);
/* size measure (number of terms of num plus den), to pick simple pivots */
slong ratfun_length(const RatFun x, const Ring *r);

void ratfun_neg(RatFun res, const RatFun x, const Ring *r);
void ratfun_add(RatFun res, const RatFun x, const RatFun y, const Ring *r);
void ratfun_sub(RatFun res, const RatFun x, const RatFun y, const Ring *r);
void ratfun_mul(RatFun res, const RatFun x, const RatFun y, const Ring *r);
void ratfun_mul_si(RatFun res, const RatFun x, slong c, const Ring *r);
/* RATFUN_EDIVZERO when y is zero */
int ratfun_div(RatFun res, const RatFun x, const RatFun y, const Ring *r);
int ratfun_inv(RatFun res, const RatFun x, const Ring *r);
/* any integer e; RATFUN_EDIVZERO for 0^e, e < 0 (0^0 = 1);
 * RATFUN_EOVERFLOW if FLINT cannot represent the power (res untouched) */
int ratfun_pow_si(RatFun res, const RatFun x, slong e, const Ring *r);

/* Makes x canonical from ANY num/den pair (e.g. one built directly on the
 * fields): cancels gcd(num, den), makes lc(den) > 0, zero becomes 0/1.
 * RATFUN_EDIVZERO (x untouched) when den is zero. */
int ratfun_canonicalise(RatFun x, const Ring *r);

/* g = gcd(a, b) over Z (content included, lc(g) > 0; gcd(0, 0) = 0), with
 * the fast paths of the reduction: a constant or a unit operand, equal
 * operands, one shared variable (through fmpz_poly).  g may alias a or b.
 * Returns 1 when FLINT computed it, 0 when it could not (then g = 1). */
int ratfun_poly_gcd(fmpz_mpoly_t g, const fmpz_mpoly_t a, const fmpz_mpoly_t b,
                    const Ring *r);

/* partial derivative d x / d var */
void ratfun_derivative(RatFun res, const RatFun x, slong var, const Ring *r);
/* the k-th partial derivative (k >= 0), reduced once at the end */
void ratfun_derivative_n(RatFun res, const RatFun x, slong var, ulong k,
                         const Ring *r);
/* res = x with variable var replaced by s (s may depend on var itself and on
 * any other variable).  RATFUN_EPOLE when the denominator of x becomes
 * identically zero under the substitution (res is then untouched). */
int ratfun_compose_var(RatFun res, const RatFun x, slong var, const RatFun s,
                       const Ring *r);
/* res = b^e * p(var := a/b) with e = deg_var(p) (*deg = e): the
 * polynomial part of a substitution, for callers that keep one
 * denominator themselves.  Returns 0 if a power overflows FLINT's exponent
 * range. */
int ratfun_poly_compose_homog(fmpz_mpoly_t res, slong *deg,
                              const fmpz_mpoly_t p, slong var,
                              const fmpz_mpoly_t a, const fmpz_mpoly_t b,
                              const Ring *r);
/* Exact value at vals[0..nvars-1]; RATFUN_EPOLE if den vanishes there. */
int ratfun_evaluate_fmpq(fmpq_t res, const RatFun x, const fmpq *vals,
                         const Ring *r);

/* Size guards.  Exact arithmetic has no bound of its own: a three-line
 * scheme (x = 1e1000^1000, y = x^1000) asks GMP for 10^9 digits and dies.
 * These estimate, before an operation and in microseconds, log2 of the
 * bits its result could need at most (terms x coefficient bits, bounded by
 * the term count and by the degrees), for the products that x*y, x/y,
 * x +- y form, for x^e, and for x with variable var replaced by s.  Callers
 * refuse an operation whose estimate exceeds RATFUN_MAX_LOG2_BITS (2^26
 * bits: 8 MB of coefficients for one polynomial, far beyond what a scheme
 * of the monograph needs - its largest results are a few hundred bytes). */
#define RATFUN_MAX_LOG2_BITS 26.0
double ratfun_log2_bits_product(const RatFun x, const RatFun y, const Ring *r);
double ratfun_log2_bits_pow(const RatFun x, slong e, const Ring *r);
/* the same estimate for the product of two polynomials */
double ratfun_poly_log2_bits_mul(const fmpz_mpoly_t a, const fmpz_mpoly_t b,
                                 const Ring *r);
double ratfun_log2_bits_compose(const RatFun x, slong var, const RatFun s,
                                const Ring *r);

/* Parse text with the ring's variable names, integers, decimals (exact:
 * "0.3" is 3/10), + - * / ^ (integer exponent, possibly negative or
 * parenthesised: x^-2, x^(-2)), unary minus, parentheses.  Used by tests and
 * for reading expectations.  Returns RATFUN_OK, RATFUN_ESYNTAX, RATFUN_ENAME,
 * RATFUN_EDIVZERO or RATFUN_EOVERFLOW; res is untouched on failure.  Numbers
 * follow the language's lexer: 12, 0.3, .5, 1e-3, 2.5E+2 (all exact). */
int ratfun_set_str(RatFun res, const char *s, const Ring *r);
/* q = the number literal text ("0.3" is 3/10, "1e-3" 1/1000, exactly), of
 * the lexer's form digits[.digits][e[+-]digits]; -1 (q untouched) when
 * its exponent is beyond +-1000.  The one reader of a scheme's numbers:
 * derive, and expand's knots. */
int ratfun_literal_fmpq(fmpq_t q, const char *text);
/* Text "num" or "(num)/(den)" (parentheses only where needed) with '*' for
 * every product, expanded polynomials as fmpz_mpoly_get_str_pretty writes
 * them.  Re-readable by ratfun_set_str.  Caller frees with flint_free. */
char *ratfun_get_str(const RatFun x, const Ring *r);

#endif
