/*
 * numfmt.c - printing and reading numbers in the C locale (numfmt.h).
 *
 * POSIX.1-2008 per-thread locales: the C locale is made once
 * (pthread_once: any thread may be the first) and put in force around each
 * call with uselocale, then the caller's is restored; nothing process-wide
 * is touched, so this is safe in a library and from several threads.
 */
#include "base/numfmt.h"

#include <locale.h>
#include <pthread.h>
#include <stdlib.h>

static locale_t c_loc = (locale_t)0;
static pthread_once_t c_once = PTHREAD_ONCE_INIT;

static void make_c_locale(void)
{
    c_loc = newlocale(LC_ALL_MASK, "C", (locale_t)0);
}

static locale_t c_locale(void)
{
    pthread_once(&c_once, make_c_locale);
    return c_loc;
}

/* the C locale in force until restore(old) */
static locale_t enter(void)
{
    locale_t c = c_locale();
    return c != (locale_t)0 ? uselocale(c) : (locale_t)0;
}

static void restore(locale_t old)
{
    if (old != (locale_t)0)
        uselocale(old);
}

int pc_vsnprintf(char *buf, size_t cap, const char *fmt, va_list ap)
{
    locale_t old = enter();
    int n = vsnprintf(buf, cap, fmt, ap);
    restore(old);
    return n;
}

int pc_vfprintf(FILE *f, const char *fmt, va_list ap)
{
    locale_t old = enter();
    int n = vfprintf(f, fmt, ap);
    restore(old);
    return n;
}

int pc_snprintf(char *buf, size_t cap, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    int n = pc_vsnprintf(buf, cap, fmt, ap);
    va_end(ap);
    return n;
}

int pc_fprintf(FILE *f, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    int n = pc_vfprintf(f, fmt, ap);
    va_end(ap);
    return n;
}

double pc_strtod(const char *s, char **end)
{
    locale_t old = enter();
    double x = strtod(s, end);
    restore(old);
    return x;
}
