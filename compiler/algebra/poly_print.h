/*
 * poly_print.h - polynomials and rational functions written expanded, and
 * identifiers as LaTeX: the printing the algebra itself needs (kernel
 * names), below the book printer (compiler/print/).
 */
#ifndef PC_POLY_PRINT_H
#define PC_POLY_PRINT_H

#include "base/strbuf.h"
#include "compiler/algebra/ratfun.h"

typedef enum FormatStyle {
    FMT_TEXT,  // book-like plain text
    FMT_LATEX, // LaTeX math
    FMT_JSON,  // machine-readable, contract section 4
} FormatStyle;

/* p expanded.  text: "2*t^2 - 2*t + 1"; json: "2*t^2-2*t+1"; latex:
 * "2 t^{2} - 2 t + 1".  A polynomial with a negative leading coefficient
 * is written in ascending order ("1 - t"). */
void poly_print(StrBuf *b, const fmpz_mpoly_t p, const Ring *r, FormatStyle st);

/* x expanded (numerator and denominator as sums of terms, no factoring: as
 * cheap as printing gets), in style st (malloc'd; caller frees) */
char *poly_print_ratfun(const RatFun x, const Ring *r, FormatStyle st);

/* an identifier as LaTeX, the book's way: A1 -> A_{1}, phi -> \varphi,
 * alpha2 -> \alpha_{2}, M_k -> M_{k}, words -> \mathit{...} */
void poly_print_latex_name(StrBuf *b, const char *name);

#endif
