/*
 * sample.c - SPEC parsing and grid enumeration for eval (see sample.h).
 *
 * Numbers are read with strtod and must be the whole field and finite, so
 * "0.5x", "", "1,,2", "nan" and "1e999" are all malformed.
 */
#include "runtime/sample.h"

#include <errno.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/mem.h"
#include "base/numfmt.h"

int sample_number(const char *text, double *v)
{
    char *end;
    if (!*text || strchr(" \t\n", *text))
        return -1;
    errno = 0;
    double x = pc_strtod(text, &end);
    /* ERANGE on underflow too: a subnormal result (1e-310) is a double, a
     * result flushed to 0 (1e-400) is not what was written */
    if (*end != '\0' || !isfinite(x) || (errno == ERANGE && x == 0))
        return -1;
    *v = x;
    return 0;
}

long sample_numbers(const char *text, double **v)
{
    size_t len = strlen(text);
    long n = 1;
    for (size_t i = 0; i < len; i++)
        n += text[i] == ',';
    char *buf = pc_xmalloc(len + 1);
    double *out = pc_xmalloc(sizeof *out * (size_t)n);
    memcpy(buf, text, len + 1);
    long k = 0;
    char *field = buf;
    for (;;) {
        char *comma = strchr(field, ',');
        if (comma)
            *comma = '\0';
        if (sample_number(field, &out[k]) != 0) {
            pc_free(buf);
            pc_free(out);
            return -1;
        }
        k++;
        if (!comma)
            break;
        field = comma + 1;
    }
    pc_free(buf);
    *v = out;
    return k;
}

int sample_parse(Spec *s, const char *text, char *msg, size_t msglen)
{
    memset(s, 0, sizeof *s);
    const char *c1 = strchr(text, ':');
    if (!c1) {
        long n = sample_numbers(text, &s->v);
        if (n < 0) {
            snprintf(msg, msglen,
                     "malformed value list '%s': expected a number, a list "
                     "0,0.25,1 or lo:hi:count",
                     text);
            return -1;
        }
        s->n = (size_t)n;
        return 0;
    }
    const char *c2 = strchr(c1 + 1, ':');
    char lo[128], hi[128];
    if (!c2 || strchr(c2 + 1, ':') || (size_t)(c1 - text) >= sizeof lo ||
        (size_t)(c2 - c1 - 1) >= sizeof hi) {
        snprintf(msg, msglen, "malformed range '%s': expected lo:hi:count",
                 text);
        return -1;
    }
    memcpy(lo, text, (size_t)(c1 - text));
    lo[c1 - text] = '\0';
    memcpy(hi, c1 + 1, (size_t)(c2 - c1 - 1));
    hi[c2 - c1 - 1] = '\0';
    const char *cnt = c2 + 1;
    char *end;
    errno = 0;
    unsigned long long n = strtoull(cnt, &end, 10);
    if (sample_number(lo, &s->lo) || sample_number(hi, &s->hi)) {
        snprintf(msg, msglen, "malformed range '%s': lo and hi must be numbers",
                 text);
        return -1;
    }
    if (!*cnt || *end || *cnt < '0' || *cnt > '9' || n == 0) {
        snprintf(msg, msglen,
                 "malformed range '%s': count must be a positive integer",
                 text);
        return -1;
    }
    if (errno || n > (unsigned long long)SIZE_MAX / 2) {
        snprintf(msg, msglen, "range '%s': count %s is too large", text, cnt);
        return -1;
    }
    if (n == 1 && s->lo != s->hi) {
        snprintf(msg, msglen,
                 "range '%s' has count 1 but lo != hi: both ends are "
                 "included, so count must be at least 2",
                 text);
        return -1;
    }
    s->n = (size_t)n;
    return 0;
}

void sample_clear(Spec *s)
{
    pc_free(s->v);
    s->v = NULL;
}

double sample_value(const Spec *s, size_t k)
{
    if (s->v)
        return s->v[k];
    if (k == 0)
        return s->lo;
    if (k == s->n - 1)
        return s->hi;
    double f = (double)k / (double)(s->n - 1);
    if (isfinite(s->hi - s->lo))
        return s->lo + (s->hi - s->lo) * f;
    return s->lo * (1 - f) + s->hi * f; // -1e308:1e308: hi - lo overflows
}
