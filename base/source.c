/*
 * source.c - a scheme's text and its line map.
 *
 * A line ends at "\n", "\r\n" or a lone "\r" (files written on any system
 * read the same).  Columns count characters: a valid UTF-8 sequence is one
 * column, and so is every other byte (source_char_len).
 */
#include "base/source.h"

#include <stdlib.h>

#include "base/mem.h"

/* offset just past the line break starting at i, or i when there is none */
static size_t line_break_end(const char *text, size_t len, size_t i)
{
    if (text[i] == '\n')
        return i + 1;
    if (text[i] == '\r')
        return i + 1 < len && text[i + 1] == '\n' ? i + 2 : i + 1;
    return i;
}

void source_init(Source *s, const char *name, const char *text, size_t len)
{
    s->name = name;
    s->text = text;
    s->len = len;
    int n = 1;
    for (size_t i = 0; i < len;) {
        size_t e = line_break_end(text, len, i);
        n += e != i;
        i = e != i ? e : i + 1;
    }
    s->line_starts = pc_xmalloc(sizeof(int) * (size_t)n);
    s->nlines = n;
    int k = 0;
    s->line_starts[k++] = 0;
    for (size_t i = 0; i < len;) {
        size_t e = line_break_end(text, len, i);
        if (e != i)
            s->line_starts[k++] = (int)e;
        i = e != i ? e : i + 1;
    }
}

void source_clear(Source *s)
{
    pc_free(s->line_starts);
    s->line_starts = NULL;
}

int source_char_len(const char *p, size_t n)
{
    const unsigned char *u = (const unsigned char *)p;
    int need;
    if (n == 0)
        return 0;
    if (u[0] < 0x80)
        return 1;
    if (u[0] >= 0xc2 && u[0] <= 0xdf)
        need = 2;
    else if (u[0] >= 0xe0 && u[0] <= 0xef)
        need = 3;
    else if (u[0] >= 0xf0 && u[0] <= 0xf4)
        need = 4;
    else
        return -1;
    if ((size_t)need > n)
        return -1;
    for (int i = 1; i < need; i++)
        if ((u[i] & 0xc0) != 0x80)
            return -1;
    /* no overlong forms, surrogates or code points above U+10FFFF */
    if ((u[0] == 0xe0 && u[1] < 0xa0) || (u[0] == 0xed && u[1] >= 0xa0) ||
        (u[0] == 0xf0 && u[1] < 0x90) || (u[0] == 0xf4 && u[1] >= 0x90))
        return -1;
    return need;
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
    int c = 1;
    for (int i = s->line_starts[lo]; i < offset;) {
        int k = source_char_len(s->text + i, s->len - (size_t)i);
        i += k > 0 ? k : 1;
        c++;
    }
    *col = c;
}

const char *source_line(const Source *s, int line, int *len)
{
    int start = s->line_starts[line - 1];
    int end = start;
    while ((size_t)end < s->len && s->text[end] != '\n' && s->text[end] != '\r')
        end++;
    *len = end - start;
    return s->text + start;
}
