/*
 * format.h - printers of derived equations: text (book-like), LaTeX, JSON.
 *
 * text:   M = (A*(1-t)^3 + B*t^2*(1-t) + ...) / (2*t^2 - 2*t + 1)
 *         grouped by base point, numerators factored, a denominator shared
 *         by every weight pulled out.
 * latex:  the same with \frac, \bar{t} for 1 - t and subscripted names.
 * json:   contract section 4: {"scheme":..,"points":..,"params":..,
 *         "consts":..,"outputs":[{"name":..,"kind":..,"terms":{..}}]}
 *         (scalar outputs carry "value" instead of "terms").
 *
 * Past the thread's deadline (base/budget.h: budget_deadline_set) the
 * text and LaTeX printers stop choosing forms and cut their text short (a
 * sum ends "+ ..." after its first term): a caller that set a deadline
 * reads budget_late() after the call and discards the text when it is 1.
 */
#ifndef PC_FORMAT_H
#define PC_FORMAT_H

#include <stdio.h>

#include "compiler/algebra/poly_print.h" /* FormatStyle */
#include "compiler/derive.h"

/* origin: a base point index to write the equations relative to
 * (M = (A - C)*f + (B - C)*g + C), or -1.  JSON ignores it. */
void format_derived(FILE *out, const Derived *d, FormatStyle style,
                    slong origin);

/* The same with the LaTeX line width (0: 80 columns of source; see
 * book.h) */
void format_derived_width(FILE *out, const Derived *d, FormatStyle style,
                          slong origin, int width);

/* --standalone: a LaTeX document around what derive prints (article class,
 * amsmath; compiles with pdflatex) */
void format_latex_begin(FILE *out, const Derived *d);
void format_latex_end(FILE *out);

/* One weight as a reduced, re-readable expression with '*' for every
 * product (the JSON form).  Caller frees with pc_free(). */
char *format_weight(const RatFun w, const Ring *r);
/* the same with abs(x) for every x*sign(x) of K's sign kernels (absform.h):
 * what derive --format json writes (the contract has abs, not sign) */
struct Kernels;
char *format_weight_k(const RatFun w, const Ring *r, const struct Kernels *K);
/* the same for the weights of one Derived d, which share factors: those
 * found in the weights written before with the same memo (book.h's
 * book_memo_new, freed by book_memo_free with d) are divided out first
 * (book_factor); the text is format_weight_k's */
struct Memo;
typedef struct FormatShare {
    const Derived *d;
    struct Memo *memo;
} FormatShare;
char *format_weight_share(const RatFun w, const FormatShare *share);

/* The right-hand side of one output as derive prints it (text or LaTeX;
 * "(A*(1 - t)^3 + ...)/(2*t^2 - 2*t + 1)"), for a point, vector or scalar;
 * origin as above.  Used by derive --steps and plot labels.  Caller frees
 * with pc_free(). */
char *format_output_rhs(const Derived *d, const DerivedOutput *o,
                        FormatStyle st, slong origin);

#endif
