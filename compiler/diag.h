/*
 * diag.h - the one diagnostics module (house style 22).
 *
 *   FILE:LINE:COL: error: MESSAGE
 *   <the source line>
 *   <caret under the span: ^~~~>
 *
 * Errors are counted; output goes only to the FILE * given (NULL discards),
 * never to stdout unless the caller passes it.
 */
#ifndef PC_DIAG_H
#define PC_DIAG_H

#include <stdarg.h>
#include <stdio.h>

#include "compiler/source.h"

typedef struct Diag {
    const Source *src; // borrowed
    FILE *out;         // borrowed; NULL = count only
    int nerrors;
} Diag;

void diag_init(Diag *d, const Source *src, FILE *out);
#if defined(__GNUC__)
__attribute__((format(printf, 3, 4)))
#endif
void diag_error(Diag *d, Span span, const char *fmt, ...);
/* diag_error with a va_list */
void diag_verror(Diag *d, Span span, const char *fmt, va_list ap);
#if defined(__GNUC__)
__attribute__((format(printf, 3, 4)))
#endif
void diag_note(Diag *d, Span span, const char *fmt, ...);

#endif
