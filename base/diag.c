/*
 * diag.c - the one printer of user errors (diag.h): FILE:LINE:COL: error:
 * message, the source line (a window of it when the line is long, control
 * and bidirectional characters escaped) and a caret span; messages held
 * and written in source order (diag_hold/diag_flush), at most
 * DIAG_MAX_ERRORS a file.  The budget handlers write through a sink with
 * write(2) only (diag_put_location, diag_put_excerpt): nothing here
 * allocates on that path.
 */
#include "base/diag.h"

#include <limits.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

#include "base/mem.h"
#include "base/numfmt.h"

static void put_file(void *ctx, const char *s, size_t n);
static void put_escaped(DiagSink *k, const char *s, size_t n);

void diag_init(Diag *d, const Source *src, FILE *out)
{
    d->src = src;
    d->out = out;
    d->nerrors = 0;
    d->shown = 0;
    d->reported = 0;
    d->muted = 0;
    d->hold = 0;
    d->msgs = NULL;
    d->nmsgs = d->amsgs = 0;
    d->nctx = 0;
}

void diag_hold(Diag *d)
{
    d->hold = 1;
}

static int msg_cmp(const void *x, const void *y)
{
    const DiagMsg *a = x, *b = y;
    if (a->start != b->start)
        return a->start < b->start ? -1 : 1;
    return (a->seq > b->seq) - (a->seq < b->seq);
}

void diag_rollback(Diag *d, int nmsgs, int nerrors)
{
    for (int i = nmsgs; i < d->nmsgs; i++)
        pc_free(d->msgs[i].text);
    if (nmsgs < d->nmsgs)
        d->nmsgs = nmsgs;
    d->reported -= d->nerrors - nerrors; /* (errors since count both) */
    if (d->reported < 0)
        d->reported = 0;
    d->nerrors = nerrors;
}

/* "NAME: note: N more errors are not shown" once the cap is passed
 * (unshown INT_MAX: "further errors", while they still come) */
static void note_unshown(Diag *d, int unshown)
{
    if (!d->out || unshown <= 0)
        return;
    DiagSink k = {put_file, d->out};
    put_escaped(&k, d->src->name, strlen(d->src->name));
    if (unshown == INT_MAX) /* streaming: the count is not known yet */
        pc_fprintf(d->out,
                   ": note: further errors are not shown (at most %d are); "
                   "fix the first ones and run again\n",
                   DIAG_MAX_ERRORS);
    else
        pc_fprintf(d->out,
                   ": note: %d more error%s not shown (at most %d are); fix "
                   "the first ones and run again\n",
                   unshown, unshown == 1 ? " is" : "s are", DIAG_MAX_ERRORS);
}

void diag_flush(Diag *d)
{
    if (d->nmsgs > 1)
        qsort(d->msgs, (size_t)d->nmsgs, sizeof *d->msgs, msg_cmp);
    int errors = 0, mute = 0;
    for (int i = 0; i < d->nmsgs; i++) {
        if (!d->msgs[i].note) /* an error: shown while under the cap */
            mute = ++errors > DIAG_MAX_ERRORS;
        if (d->out && !mute)
            fputs(d->msgs[i].text, d->out);
        pc_free(d->msgs[i].text);
    }
    note_unshown(d, d->reported -
                        (errors < DIAG_MAX_ERRORS ? errors : DIAG_MAX_ERRORS));
    d->reported = 0;
    pc_free(d->msgs);
    d->msgs = NULL;
    d->nmsgs = d->amsgs = 0;
    d->hold = 0;
}

static void emit(Diag *d, Span span, const char *what, const char *fmt,
                 va_list ap);

/* writes the message, or holds it (a note is held right after its error) */
static void report(Diag *d, Span span, const char *what, const char *fmt,
                   va_list ap)
{
    int is_note = what[0] == 'n';
    if (!d->out)
        return;
    d->reported += !is_note;
    if (!d->hold) {
        if (!is_note) {
            d->muted = d->shown >= DIAG_MAX_ERRORS;
            if (d->shown++ == DIAG_MAX_ERRORS)
                note_unshown(d, INT_MAX); /* the first one not shown */
        }
        if (!d->muted)
            emit(d, span, what, fmt, ap);
        return;
    }
    if (d->nmsgs >= DIAG_MAX_HELD)
        return; /* counted, never shown: the cap is far below */
    char *text = NULL;
    size_t len = 0;
    FILE *m = pc_xopen_memstream(&text, &len);
    FILE *out = d->out;
    d->out = m;
    emit(d, span, what, fmt, ap);
    d->out = out;
    pc_xclose_memstream(m);
    if (d->nmsgs == d->amsgs) {
        d->amsgs = d->amsgs ? 2 * d->amsgs : 8;
        d->msgs = pc_xrealloc(d->msgs, sizeof *d->msgs * (size_t)d->amsgs);
    }
    DiagMsg *g = &d->msgs[d->nmsgs];
    g->note = is_note;
    g->start = is_note && d->nmsgs ? d->msgs[d->nmsgs - 1].start : span.start;
    g->seq = d->nmsgs;
    g->text = text;
    d->nmsgs++;
}

/* ---- the location and the excerpt, through a sink ---------------------- */

/* 1 for a code point that drives a terminal or reorders text although it
 * is valid UTF-8: the C1 controls (U+0080-U+009F, e.g. U+009B, the CSI)
 * and the bidi embeddings, overrides and isolates (U+202A-U+202E,
 * U+2066-U+2069: "Trojan source") */
static int hidden_char(unsigned long u)
{
    return (u >= 0x80 && u <= 0x9f) || (u >= 0x202a && u <= 0x202e) ||
           (u >= 0x2066 && u <= 0x2069);
}

/* the code point of the valid k-byte UTF-8 sequence at p */
static unsigned long code_point(const char *p, int k)
{
    const unsigned char *u = (const unsigned char *)p;
    unsigned long c = k == 1 ? u[0] : u[0] & (0x7fu >> k);
    for (int i = 1; i < k; i++)
        c = c << 6 | (u[i] & 0x3fu);
    return c;
}

/* The display form of the byte(s) at p, written to out (up to
 * CELL_MAX bytes; returns how many): a valid UTF-8 character or a tab as
 * themselves (one column), a C1 control or a bidi control as \uNNNN (six
 * columns), a control byte, DEL or a byte of no valid sequence as \xNN
 * (four columns) - so that printing a line can never drive the terminal
 * or reorder what it shows.  *bytes receives how many bytes it covers,
 * *cols how many columns it takes. */
enum { CELL_MAX = 6 };
static int cell(char *out, const char *p, size_t n, int *bytes, int *cols)
{
    static const char hex[] = "0123456789abcdef";
    unsigned char c = (unsigned char)p[0];
    int k = source_char_len(p, n);
    unsigned long u = k > 1 ? code_point(p, k) : c;
    if (k > 1 && hidden_char(u)) {
        out[0] = '\\';
        out[1] = 'u';
        for (int i = 0; i < 4; i++)
            out[2 + i] = hex[(u >> (12 - 4 * i)) & 15];
        *bytes = k;
        *cols = 6;
        return 6;
    }
    if (k > 1 || (k == 1 && ((c >= 0x20 && c < 0x7f) || c == '\t'))) {
        for (int i = 0; i < k; i++)
            out[i] = p[i];
        *bytes = k;
        *cols = 1;
        return k;
    }
    out[0] = '\\';
    out[1] = 'x';
    out[2] = hex[c >> 4];
    out[3] = hex[c & 15];
    *bytes = 1;
    *cols = 4;
    return 4;
}

static void put_str(DiagSink *k, const char *s)
{
    size_t n = 0;
    while (s[n])
        n++;
    k->put(k->ctx, s, n);
}

static void put_int(DiagSink *k, long v)
{
    char b[24];
    int i = (int)sizeof b;
    unsigned long u = v < 0 ? 0UL - (unsigned long)v : (unsigned long)v;
    do {
        b[--i] = (char)('0' + u % 10);
        u /= 10;
    } while (u);
    if (v < 0)
        b[--i] = '-';
    k->put(k->ctx, b + i, sizeof b - (size_t)i);
}

/* text escaped cell by cell */
static void put_escaped(DiagSink *k, const char *s, size_t n)
{
    char c[CELL_MAX];
    for (size_t i = 0; i < n;) {
        int used, cols, w = cell(c, s + i, n - i, &used, &cols);
        k->put(k->ctx, c, (size_t)w);
        i += (size_t)used;
    }
}

static Span clamp(const Source *s, Span span)
{
    if (span.start < 0)
        span.start = 0;
    if ((size_t)span.start > s->len)
        span.start = (int)s->len;
    if (span.end < span.start)
        span.end = span.start;
    return span;
}

void diag_put_location(DiagSink *k, const Source *s, Span span,
                       const char *what)
{
    int line, col;
    const char *name = s->name;
    size_t n = 0;
    while (name[n])
        n++;
    if (DIAG_IS_WHOLE_FILE(span)) { /* "NAME: WHAT: " */
        put_escaped(k, name, n);
        put_str(k, ": ");
        put_str(k, what);
        put_str(k, ": ");
        return;
    }
    span = clamp(s, span);
    source_locate(s, span.start, &line, &col);
    put_escaped(k, name, n);
    put_str(k, ":");
    put_int(k, line);
    put_str(k, ":");
    put_int(k, col);
    put_str(k, ": ");
    put_str(k, what);
    put_str(k, ": ");
}

/* the first byte of the character that holds byte i of text (UTF-8: not
 * a continuation byte 10xxxxxx) */
static int char_start(const char *text, int i)
{
    while (i > 0 && ((unsigned char)text[i] & 0xc0) == 0x80)
        i--;
    return i;
}

void diag_put_excerpt(DiagSink *k, const Source *s, Span span)
{
    int line, col, len;
    char c[CELL_MAX];
    span = clamp(s, span);
    source_locate(s, span.start, &line, &col);
    const char *text = source_line(s, line, &len);
    int from = (int)(s->text + span.start - text); /* byte offset in line */
    int to = (int)(s->text + span.end - text);
    /* a long line is shown around the span: DIAG_EXCERPT_BEFORE bytes
     * before it, DIAG_EXCERPT_WIDTH in all, "..." where it is cut */
    int cut_left = 0, cut_right = 0;
    if (len > DIAG_EXCERPT_WIDTH) {
        int ws = from > DIAG_EXCERPT_BEFORE ? from - DIAG_EXCERPT_BEFORE : 0;
        ws = char_start(text, ws);
        int we = ws + DIAG_EXCERPT_WIDTH < len ? ws + DIAG_EXCERPT_WIDTH : len;
        if (we < len)
            we = char_start(text, we);
        cut_left = ws > 0;
        cut_right = we < len;
        text += ws;
        len = we - ws;
        from -= ws;
        to -= ws;
    }
    if (cut_left)
        put_str(k, "...");
    put_escaped(k, text, (size_t)len);
    if (cut_right)
        put_str(k, "...");
    put_str(k, "\n");
    if (cut_left)
        put_str(k, "   ");
    /* the caret under the first cell of the span, '~' under the rest;
     * tabs kept so that it lines up under tabbed text */
    int i = 0, marks = 0;
    for (; i < from && i < len;) {
        int used, cols, w = cell(c, text + i, (size_t)(len - i), &used, &cols);
        if (c[0] == '\t' && w == 1)
            k->put(k->ctx, "\t", 1);
        else
            for (int j = 0; j < cols; j++)
                k->put(k->ctx, " ", 1);
        i += used;
    }
    k->put(k->ctx, "^", 1);
    for (; i < to && i < len;) {
        int used, width;
        cell(c, text + i, (size_t)(len - i), &used, &width);
        for (int j = marks == 0 ? 1 : 0; j < width; j++)
            k->put(k->ctx, "~", 1);
        marks++;
        i += used;
    }
    put_str(k, "\n");
}

static void put_file(void *ctx, const char *s, size_t n)
{
    fwrite(s, 1, n, (FILE *)ctx);
}

void diag_fput_escaped(FILE *out, const char *s)
{
    DiagSink k = {put_file, out};
    put_escaped(&k, s, strlen(s));
}

static void emit(Diag *d, Span span, const char *what, const char *fmt,
                 va_list ap)
{
    DiagSink k = {put_file, d->out};
    diag_put_location(&k, d->src, span, what);
    pc_vfprintf(d->out, fmt, ap);
    fputc('\n', d->out);
    diag_put_excerpt(&k, d->src, span);
}

static void context_notes(Diag *d)
{
    int n = d->nctx < DIAG_MAX_CONTEXT ? d->nctx : DIAG_MAX_CONTEXT;
    for (int i = n - 1; i >= 0; i--)
        diag_note(d, d->ctx_span[i], "in the call of %s() here",
                  d->ctx_name[i]);
}

void diag_error(Diag *d, Span span, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    report(d, span, "error", fmt, ap);
    va_end(ap);
    d->nerrors++;
    context_notes(d);
}

void diag_verror(Diag *d, Span span, const char *fmt, va_list ap)
{
    report(d, span, "error", fmt, ap);
    d->nerrors++;
    context_notes(d);
}

void diag_push_context(Diag *d, Span span, const char *name)
{
    if (d->nctx < DIAG_MAX_CONTEXT) {
        d->ctx_span[d->nctx] = span;
        d->ctx_name[d->nctx] = name;
    }
    d->nctx++;
}

void diag_pop_context(Diag *d)
{
    if (d->nctx > 0)
        d->nctx--;
}

void diag_note(Diag *d, Span span, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    report(d, span, "note", fmt, ap);
    va_end(ap);
}
