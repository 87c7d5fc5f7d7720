/*
 * slow_lower.h - a scheme that derives in milliseconds and lowers for much
 * longer (40 outputs, factoring 40 weights of degree about 60): the
 * budgets of the work after the derivation are tested on it (test_lower,
 * test_api).
 */
#ifndef PC_TESTS_SLOW_LOWER_H
#define PC_TESTS_SLOW_LOWER_H

#include <stdio.h>
#include <stdlib.h>

/* the scheme's text (malloc'd) */
static inline char *slow_to_lower(void)
{
    char *text = malloc(4096), *p = text;
    p += sprintf(p, "point A, B\nparam t\n");
    for (int i = 1; i <= 40; i++)
        p += sprintf(p, "M%d = along(A, B, (t + %d)^%d + t^3)\n", i, i,
                     60 + i % 7);
    p += sprintf(p, "output M1");
    for (int i = 2; i <= 40; i++)
        p += sprintf(p, ", M%d", i);
    sprintf(p, "\n");
    return text;
}

#endif
