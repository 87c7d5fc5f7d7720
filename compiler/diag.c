#include "compiler/diag.h"

#include <stdarg.h>
#include <stdlib.h>

void diag_init(Diag *d, const Source *src, FILE *out)
{
    d->src = src;
    d->out = out;
    d->nerrors = 0;
    d->hold = 0;
    d->msgs = NULL;
    d->nmsgs = d->amsgs = 0;
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

void diag_flush(Diag *d)
{
    if (d->nmsgs > 1)
        qsort(d->msgs, (size_t)d->nmsgs, sizeof *d->msgs, msg_cmp);
    for (int i = 0; i < d->nmsgs; i++) {
        if (d->out)
            fputs(d->msgs[i].text, d->out);
        free(d->msgs[i].text);
    }
    free(d->msgs);
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
    if (!d->out)
        return;
    if (!d->hold) {
        emit(d, span, what, fmt, ap);
        return;
    }
    char *text = NULL;
    size_t len = 0;
    FILE *m = open_memstream(&text, &len);
    FILE *out = d->out;
    d->out = m;
    emit(d, span, what, fmt, ap);
    d->out = out;
    fclose(m);
    if (d->nmsgs == d->amsgs) {
        d->amsgs = d->amsgs ? 2 * d->amsgs : 8;
        d->msgs = realloc(d->msgs, sizeof *d->msgs * (size_t)d->amsgs);
        if (!d->msgs)
            abort();
    }
    DiagMsg *g = &d->msgs[d->nmsgs];
    int is_note = what[0] == 'n';
    g->start = is_note && d->nmsgs ? d->msgs[d->nmsgs - 1].start : span.start;
    g->seq = d->nmsgs;
    g->text = text;
    d->nmsgs++;
}

static void emit(Diag *d, Span span, const char *what, const char *fmt,
                 va_list ap)
{
    const Source *s = d->src;
    if (span.start < 0)
        span.start = 0;
    if ((size_t)span.start > s->len)
        span.start = (int)s->len;
    if (span.end < span.start)
        span.end = span.start;
    int line, col;
    source_locate(s, span.start, &line, &col);
    fprintf(d->out, "%s:%d:%d: %s: ", s->name, line, col, what);
    vfprintf(d->out, fmt, ap);
    fputc('\n', d->out);
    int len;
    const char *text = source_line(s, line, &len);
    /* the line as it is, but a NUL (which would end it early) as a space */
    for (int i = 0; i < len; i++)
        fputc(text[i] ? text[i] : ' ', d->out);
    fputc('\n', d->out);
    /* caret line: keep tabs so the caret lines up under tabbed text */
    for (int i = 0; i < col - 1 && i < len; i++)
        fputc(text[i] == '\t' ? '\t' : ' ', d->out);
    fputc('^', d->out);
    int width = span.end - span.start;
    if (col - 1 + width > len)
        width = len - (col - 1);
    for (int i = 1; i < width; i++)
        fputc('~', d->out);
    fputc('\n', d->out);
}

void diag_error(Diag *d, Span span, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    report(d, span, "error", fmt, ap);
    va_end(ap);
    d->nerrors++;
}

void diag_verror(Diag *d, Span span, const char *fmt, va_list ap)
{
    report(d, span, "error", fmt, ap);
    d->nerrors++;
}

void diag_note(Diag *d, Span span, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    report(d, span, "note", fmt, ap);
    va_end(ap);
}
