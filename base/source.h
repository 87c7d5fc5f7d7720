/*
 * source.h - a scheme's text and its line map.
 *
 * Locations are byte spans {start, end}; line and column are computed here
 * only when a diagnostic is printed (house style 11).
 */
#ifndef PC_SOURCE_H
#define PC_SOURCE_H

#include <stddef.h>

typedef struct Span {
    int start; // byte offset of the first byte
    int end;   // one past the last byte
} Span;

typedef struct Source {
    const char *name; // file name as the user gave it (borrowed)
    const char *text; // borrowed, len bytes (need not be NUL-terminated)
    size_t len;
    int *line_starts; // owned: offset of each line's first byte
    int nlines;
} Source;

void source_init(Source *s, const char *name, const char *text, size_t len);
void source_clear(Source *s);
/* 1-based line and column of a byte offset; the column counts characters
 * (a valid UTF-8 sequence is one, any other byte is one) */
void source_locate(const Source *s, int offset, int *line, int *col);
/* the text of a 1-based line without its line break ("\n", "\r\n" or
 * "\r": all three end a line) */
const char *source_line(const Source *s, int line, int *len);
/* the length of the valid UTF-8 sequence at p (1 for ASCII), or -1 for a
 * byte that starts none (n bytes are readable at p; 0 when n is 0) */
int source_char_len(const char *p, size_t n);

#endif
