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
/* 1-based line and column (column counts bytes) of a byte offset */
void source_locate(const Source *s, int offset, int *line, int *col);
/* the text of a 1-based line without its newline */
const char *source_line(const Source *s, int line, int *len);

#endif
