/*
 * sample.h - parameter values for eval (contract section 4):
 *
 *   SPEC = VALUE | VALUE,VALUE,... | LO:HI:COUNT   (COUNT samples, both ends)
 *
 * Several parameters form a grid whose last parameter varies fastest.
 * Ranges are not materialised: value k is computed on demand, so a grid of
 * 10^8 rows costs no memory.
 */
#ifndef PC_SAMPLE_H
#define PC_SAMPLE_H

#include <stddef.h>

typedef struct Spec {
    size_t n;  // number of values
    double *v; // owned: the list, or NULL for a range
    double lo, hi;
} Spec;

/* Parses SPEC.  Returns 0, or -1 with a message (no trailing newline) in
 * msg[0..msglen-1]. */
int sample_parse(Spec *s, const char *text, char *msg, size_t msglen);
void sample_clear(Spec *s);
/* value k < s->n (a range's ends are exact: lo and hi themselves) */
double sample_value(const Spec *s, size_t k);

/* Strict number: the whole text, finite.  Returns 0 or -1. */
int sample_number(const char *text, double *v);
/* Comma-separated strict numbers; *v is malloc'ed.  Returns the count
 * (>= 1) or -1. */
long sample_numbers(const char *text, double **v);

#endif
