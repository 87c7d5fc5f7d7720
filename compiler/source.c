#include "compiler/source.h"

#include <stdio.h>
#include <stdlib.h>

void source_init(Source *s, const char *name, const char *text, size_t len)
{
    s->name = name;
    s->text = text;
    s->len = len;
    int n = 1;
    for (size_t i = 0; i < len; i++)
        if (text[i] == '\n')
            n++;
    s->line_starts = malloc(sizeof(int) * (size_t)n);
    if (!s->line_starts) {
        fputs("pointcalc: out of memory\n", stderr);
        abort();
    }
    s->nlines = n;
    int k = 0;
    s->line_starts[k++] = 0;
    for (size_t i = 0; i < len; i++)
        if (text[i] == '\n')
            s->line_starts[k++] = (int)i + 1;
}

void source_clear(Source *s)
{
    free(s->line_starts);
    s->line_starts = NULL;
}

void source_locate(const Source *s, int offset, int *line, int *col)
{
    /* binary search for the last line start <= offset */
    int lo = 0, hi = s->nlines - 1;
    while (lo < hi) {
        int mid = (lo + hi + 1) / 2;
        if (s->line_starts[mid] <= offset)
            lo = mid;
        else
            hi = mid - 1;
    }
    *line = lo + 1;
    *col = offset - s->line_starts[lo] + 1;
}

const char *source_line(const Source *s, int line, int *len)
{
    int start = s->line_starts[line - 1];
    int end = start;
    while ((size_t)end < s->len && s->text[end] != '\n')
        end++;
    if (end > start && s->text[end - 1] == '\r')
        end--;
    *len = end - start;
    return s->text + start;
}
