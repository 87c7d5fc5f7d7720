/*
 * roots.h - the real roots of a univariate integer polynomial, exactly
 * where that is possible: rational roots as fractions, the roots of
 * irreducible quadratic factors in square-root form, and the roots of
 * every other irreducible factor isolated (Sturm sequences, bisection at
 * exact rational points) to an interval of width at most 2^-60 max(1, |x|)
 * (below 1e-15 relative).  What `analyze` reports as poles, stop points,
 * inflections and passages (analyze.h).
 */
#ifndef PC_ROOTS_H
#define PC_ROOTS_H

#include <flint/fmpq.h>
#include <flint/fmpz_poly.h>

/* AnRoot.mult of a number found numerically where it holds on a whole
 * interval: this root starts it, the next one (AN_RUN_END) ends it */
enum { AN_RUN_START = -1, AN_RUN_END = -2 };

typedef struct AnRoot {
    char *exact;  // owned: "1/2", "(1 - sqrt(5))/2"; NULL: isolated only
    double value; // the root (nearest double of the isolating interval)
    slong mult;   // its multiplicity in the polynomial
} AnRoot;

typedef struct AnRoots {
    slong n, alloc;
    AnRoot *v; // owned, sorted by value
} AnRoots;

void roots_init(AnRoots *r);
void roots_clear(AnRoots *r);

/* Appends to res the distinct real roots of p (non-zero) in [lo, hi] (lo
 * or hi NULL: unbounded on that side), except the roots of the
 * irreducible factors of p that divide excl (excl NULL: none), then sorts
 * res by value. */
void roots_real(AnRoots *res, const fmpz_poly_t p, const fmpq *lo,
                const fmpq *hi, const fmpz_poly_t excl);

/* Appends the root x (a number, not exact; mult 1 or AN_RUN_*) to r,
 * kept sorted. */
void roots_push_value(AnRoots *r, double x, slong mult);

#endif
