/*
 * strbuf.c - a growing string (strbuf.h) for the printers: append text,
 * integers (%lu needs no locale) and FLINT integers, then take the
 * malloc'd result.
 */
#include "base/strbuf.h"

#include <stdio.h>
#include <string.h>

#include "base/mem.h"

void sb_putn(StrBuf *b, const char *s, size_t n)
{
    if (b->len + n + 1 > b->cap) {
        b->cap = 2 * (b->len + n + 1) + 32;
        b->s = pc_xrealloc(b->s, b->cap);
    }
    memcpy(b->s + b->len, s, n);
    b->len += n;
    b->s[b->len] = '\0';
}

void sb_puts(StrBuf *b, const char *s)
{
    sb_putn(b, s, strlen(s));
}

void sb_ulong(StrBuf *b, ulong u)
{
    char num[32];
    snprintf(num, sizeof num, "%lu", u);
    sb_puts(b, num);
}

void sb_fmpz(StrBuf *b, const fmpz_t c)
{
    char *s = fmpz_get_str(NULL, 10, c);
    sb_puts(b, s);
    flint_free(s);
}

char *sb_take(StrBuf *b)
{
    if (!b->s)
        sb_puts(b, "");
    char *s = b->s;
    b->s = NULL;
    b->len = b->cap = 0;
    return s;
}
