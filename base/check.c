/*
 * check.c - the one way an internal invariant fails (check.h): a line on
 * stderr with write(2) (no allocation: the failure may be in the memory
 * path), then abort() so a debugger or a core dump sees the stack; and
 * pc_write_all, the one write loop that such last words (the budget
 * handlers', the fuzz watchdog's) go through.
 */
#include "base/check.h"

#include <stdlib.h>
#include <string.h>
#include <unistd.h>

void pc_write_all(int fd, const char *s, size_t n)
{
    while (n > 0) {
        ssize_t w = write(fd, s, n);
        if (w <= 0)
            return;
        s += w;
        n -= (size_t)w;
    }
}

static void put(const char *s)
{
    pc_write_all(2, s, strlen(s));
}

_Noreturn void pc_internal_error(const char *file, int line, const char *what)
{
    char num[16];
    int k = (int)sizeof num - 1;
    num[k] = '\0';
    unsigned u = line > 0 ? (unsigned)line : 0;
    do
        num[--k] = (char)('0' + u % 10);
    while ((u /= 10) > 0 && k > 0);
    put("pointcalc: internal error at ");
    put(file);
    put(":");
    put(num + k);
    put(": ");
    put(what);
    put(" (a bug: please report it with the scheme)\n");
    abort();
}
