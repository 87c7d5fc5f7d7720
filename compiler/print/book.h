/*
 * book.h - derived equations printed as the monograph prints them (text and
 * LaTeX).  The JSON form (format.c) is separate: it is for programs.
 * Implemented by compiler/print/book_*.c, which share book_int.h.
 *
 * Every polynomial (a weight's numerator, a denominator, a scalar) is
 * written in the form with the fewest additive terms among
 *   - expanded, in ascending order ("1 - 2*t + 2*t^2");
 *   - factored ("t^2*(1 - t)", "2*(C - A)");
 *   - collected in the Bernstein basis of a param t, powers of t and
 *     t̄ = 1 - t ("(1 - t)^2 + t^2" for 2*t^2 - 2*t + 1);
 *   - collected by the powers of one variable ("kq*(1 - 2*v)^2 + 2*v*(1 - v)"),
 * applied recursively to the coefficients and factors (two levels deep), ties
 * broken by the shorter text and then by that order.  1 - x of a param or a
 * const is one atom: "(1 - u)" in text, \bar{u} in LaTeX.
 *
 * One equation, one set of rules (docs/language.md, "How derive prints"):
 *   - a point or vector equation is written over its one denominator:
 *     M = (A*n1 + B*n2 + ...)/d, points in declaration order; a factor
 *     common to every numerator is written once in front;
 *   - the sign is chosen so that the denominator's first term is positive;
 *     a numerator whose every item is negative is written -(...)/d;
 *   - inside a product: the integer, a difference of points ((A - C)*...),
 *     consts, the point, params (t before 1 - t), functions, then
 *     parenthesised sums (those free of params first), sums ordered by
 *     degree, length and then FLINT's monomial order: a total order;
 *   - in a vector, two points with opposite weights are one difference:
 *     2*(C - A).
 *
 * LaTeX: names with a one-letter stem and a suffix of capitals or digits
 * are subscripted (A1 -> A_{1}, fP -> f_{P}), Greek words get their letter,
 * other names of several letters are set upright-italic as one word
 * (kq -> \mathit{kq}); an output defined as diff(M, t[, n]) is written
 * \frac{\mathrm{d}M}{\mathrm{d}t} (\mathrm{d}^{n}M over \mathrm{d}t^{n}).
 * An equation longer than the width (default 80 columns of LaTeX source)
 * is set in a multline* environment broken between its terms.
 */
#ifndef PC_BOOK_H
#define PC_BOOK_H

#include <flint/fmpz_mpoly_factor.h>
#include <flint/fmpz_poly.h>

#include "compiler/derive.h"

/* the forms chosen so far, to share among the outputs of one Derived (they
 * share denominators): book_memo_new, pass in BookOptions, then
 * book_memo_free with that Derived */
typedef struct Memo BookMemo;
BookMemo *book_memo_new(void);
void book_memo_free(BookMemo *m, const Derived *d);

typedef struct BookOptions {
    int latex;      // 0 text, 1 LaTeX
    int width;      // LaTeX: break equations longer than this (0: 80)
    slong origin;   // a base point to write relative to, or -1
    BookMemo *memo; // NULL: each call chooses afresh
    int exhaustive; // tests only: every collected form built whole, none
                    // given up by a bound (the same forms are chosen)
} BookOptions;

/* one output's right-hand side (malloc'd) */
char *book_rhs(const Derived *d, const DerivedOutput *o,
               const BookOptions *opt);
/* the whole line(s) of one output: "M = ...", or in LaTeX the display
 * (\[ ... \] or a multline* environment), with a final newline */
char *book_output(const Derived *d, const DerivedOutput *o,
                  const BookOptions *opt);
/* LaTeX of a name (the rule above) appended to a malloc'd string */
char *book_latex_name(const char *name);

/* f = p's factoring as ring_factor (algebra/ring.h) makes it, up to the
 * order of the factors: where FLINT would factor fully, the factors
 * remembered in m (NULL: none) from the polynomials factored before are
 * divided out first and the irreducible factors found are remembered in
 * turn; derive's JSON and --steps share them this way (format.c).  0 when
 * ring_factor fails. */
int book_factor(fmpz_mpoly_factor_t f, const fmpz_mpoly_t p, const Derived *d,
                BookMemo *m);

/* for tests/unit/test_book.c only: the printer's cheap proofs of
 * irreducibility (compiler/algebra/polyfactor.h; 1: proved; 0: no proof), which
 * let it skip FLINT's factoring.
 * surely_irreducible: p (of r) irreducible and primitive;
 * irreducible_mod_small_prime: u (degree >= 1) irreducible over Q;
 * quadratic_irreducible: u of degree 2 irreducible over Q (an answer both
 * ways: its discriminant is not a square). */
int book_test_surely_irreducible(const fmpz_mpoly_t p, const Ring *r);
int book_test_irreducible_mod_small_prime(const fmpz_poly_t u);
int book_test_quadratic_irreducible(const fmpz_poly_t u);
/* for tests/unit/test_book_fast.c only: the leaves of p's form at depth
 * (p of d's ring) and the printer's lower bound on them, before (lower[0])
 * and after (lower[1], remembered then) the form is chosen */
slong book_test_leaves(const Derived *d, const fmpz_mpoly_t p, int depth,
                       slong *lower);

#endif
