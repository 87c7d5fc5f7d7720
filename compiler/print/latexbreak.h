/*
 * latexbreak.h - LaTeX math broken into lines that fit the page.
 *
 * TeX does not break display math, so an equation, a weight or a scalar
 * wider than the text runs off the page.  latex_break splits the math the
 * printers write into lines of at most a given width, estimated as set
 * (latex_width: about one unit per letter, digit or symbol of the text
 * size, scripts at 0.7, a fraction as wide as its wider part): between the
 * top-level terms first (before a +, - or =), between factors when a term
 * alone is too wide, and inside a part that is still too wide, which is
 * rewritten into a breakable equivalent:
 *   \left( X \right)   ->  \Bigl( X \Bigr)   (the pieces may then part)
 *   \frac{N}{D}        ->  \frac{1}{D} \Bigl( N \Bigr), or
 *                          \Bigl( N \Bigr) \Big/ \Bigl( D \Bigr)
 *   \sqrt{X}           ->  \Bigl( X \Bigr)^{1/2}
 *   \texttt{a b c}     ->  \texttt{a }\texttt{b }\texttt{c}
 * so that every line is itself balanced (no \left without its \right), as
 * a line of multline* or align* must be.
 */
#ifndef PC_LATEXBREAK_H
#define PC_LATEXBREAK_H

#include <stddef.h>

/* article, 10 pt: \textwidth is 345 pt, a unit 5 to 6 pt (measured); the
 * default leaves room for multline's indentation */
#define LATEX_LINE_UNITS 56.0

/* the estimated width of math s[0..n) as set, in units */
double latex_width(const char *s, size_t n);

/* s in lines of at most width units where it can be broken (a part that
 * cannot, a long name, stays whole); returns the number of lines, *lines
 * a malloc'd array of malloc'd strings (latex_lines_free) */
size_t latex_break(char ***lines, const char *s, double width);
void latex_lines_free(char **lines, size_t n);

#endif
