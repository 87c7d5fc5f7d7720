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

#include "base/source.h"

/* a held message (diag_hold) */
typedef struct DiagMsg {
    int start, seq; // sort key: its position, then the order of reports
    int note;       // a note (follows its error), not an error
    char *text;     // owned, complete with source line and caret
} DiagMsg;

/* the most errors a file reports (compilers stop after 20-100): the rest
 * are counted, and one note says how many were not shown */
#define DIAG_MAX_ERRORS 50
/* the most messages held for sorting (diag_hold) */
#define DIAG_MAX_HELD 2000

/* the most nested calls of user functions whose notes follow an error */
#define DIAG_MAX_CONTEXT 8

typedef struct Diag {
    const Source *src; // borrowed
    FILE *out;         // borrowed; NULL = count only
    int nerrors;
    int shown;     // errors written (not held) so far
    int reported;  // errors reported while held (shown or not)
    int muted;     // the last error was not shown: neither are its notes
    int hold;      // 1: messages wait in msgs until diag_flush
    DiagMsg *msgs; // owned
    int nmsgs, amsgs;
    // the calls of user functions being expanded or checked, outermost
    // first: every error is followed by a note at each, innermost first
    Span ctx_span[DIAG_MAX_CONTEXT];
    const char *ctx_name[DIAG_MAX_CONTEXT];
    int nctx; // may exceed DIAG_MAX_CONTEXT: the deeper ones get no note
} Diag;

void diag_init(Diag *d, const Source *src, FILE *out);
/* From now on messages are held and diag_flush writes them in source order
 * (errors of several passes - sema, then derive - read top to bottom; a
 * note stays after its error). */
void diag_hold(Diag *d);
/* Drops the held messages after the first nmsgs and sets the error count
 * back to nerrors (a derivation that is done again). */
void diag_rollback(Diag *d, int nmsgs, int nerrors);
/* Writes the held messages in order and releases them. */
void diag_flush(Diag *d);
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
/* From now until the matching pop, every error is followed by the note
 * "in the call of NAME() here" at span (name borrowed) */
void diag_push_context(Diag *d, Span span, const char *name);
void diag_pop_context(Diag *d);

/* The parts of a message, written through a sink: what diag_error prints,
 * and what a handler that may not allocate (the budgets' signal handler,
 * the out-of-memory handler) prints with write(2).  Both are
 * async-signal-safe when put is.  Control bytes, DEL and invalid UTF-8 in
 * the file name and the source line are shown escaped (\x1b), and so are
 * the C1 controls U+0080-U+009F and the bidi controls U+202A-U+202E,
 * U+2066-U+2069 (\u009b, \u202e), so printing a diagnostic can never
 * drive the terminal or reorder the text it shows; the caret counts
 * characters and lines up under the escapes. */
typedef struct DiagSink {
    void (*put)(void *ctx, const char *s, size_t n);
    void *ctx;
} DiagSink;
/* "NAME:LINE:COL: WHAT: ", or "NAME: WHAT: " for DIAG_WHOLE_FILE */
/* a span that stands for the whole file (no line, no excerpt) */
#define DIAG_WHOLE_FILE ((Span){-1, -2})
#define DIAG_IS_WHOLE_FILE(sp) ((sp).start == -1 && (sp).end == -2)
void diag_put_location(DiagSink *k, const Source *s, Span span,
                       const char *what);
/* the source line of span, then its caret line, each ending in '\n'; a
 * line longer than DIAG_EXCERPT_WIDTH bytes is shown around the span,
 * cut ends marked "..." */
#define DIAG_EXCERPT_WIDTH 160
#define DIAG_EXCERPT_BEFORE 60
void diag_put_excerpt(DiagSink *k, const Source *s, Span span);
/* s (a file name) on out, escaped as in diagnostics */
void diag_fput_escaped(FILE *out, const char *s);

#endif
