#include "compiler/diag.h"

#include <stdarg.h>

void diag_init(Diag *d, const Source *src, FILE *out)
{
    d->src = src;
    d->out = out;
    d->nerrors = 0;
}

static void report(Diag *d, Span span, const char *what, const char *fmt,
                   va_list ap)
{
    if (!d->out)
        return;
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
    fprintf(d->out, "%.*s\n", len, text);
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
