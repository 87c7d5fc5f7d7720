/*
 * strbuf.h - a growable string for the printers (book.c, format.c).
 * Allocation follows the one out-of-memory policy (mem.h).  A zeroed
 * StrBuf is empty; sb_take hands the string over (never NULL) and leaves
 * the buffer empty.
 */
#ifndef PC_STRBUF_H
#define PC_STRBUF_H

#include <stddef.h>

#include <flint/fmpz.h>

typedef struct StrBuf {
    char *s; // NUL-terminated once anything was put
    size_t len, cap;
} StrBuf;

void sb_putn(StrBuf *b, const char *s, size_t n);
void sb_puts(StrBuf *b, const char *s);
void sb_ulong(StrBuf *b, ulong u);
void sb_fmpz(StrBuf *b, const fmpz_t c);
char *sb_take(StrBuf *b);

#endif
