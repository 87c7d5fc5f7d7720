/*
 * numfmt.h - the one way numbers are printed and read: in the C locale,
 * whatever locale the program (or a program using the library) has set
 * with setlocale, so that generated C, JSON, CSV, plan dumps and messages
 * never get a decimal comma, and "0.5" on a command line is always one
 * half.  Everything in the tree that formats or parses a floating-point
 * number goes through these.
 */
#ifndef PC_NUMFMT_H
#define PC_NUMFMT_H

#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>

#if defined(__GNUC__)
#define PC_PRINTF(a, b) __attribute__((format(printf, a, b)))
#else
#define PC_PRINTF(a, b)
#endif

int pc_snprintf(char *buf, size_t cap, const char *fmt, ...) PC_PRINTF(3, 4);
int pc_fprintf(FILE *f, const char *fmt, ...) PC_PRINTF(2, 3);
int pc_vfprintf(FILE *f, const char *fmt, va_list ap) PC_PRINTF(2, 0);
int pc_vsnprintf(char *buf, size_t cap, const char *fmt, va_list ap)
    PC_PRINTF(3, 0);
double pc_strtod(const char *s, char **end);

#endif
