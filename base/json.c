/*
 * json.c - JSON strings and numbers (see json.h).
 */
#include "base/json.h"

#include <math.h>

#include "base/numfmt.h"

void json_string(FILE *out, const char *s)
{
    fputc('"', out);
    for (; *s; s++) {
        unsigned char c = (unsigned char)*s;
        if (c == '"' || c == '\\')
            fprintf(out, "\\%c", c);
        else if (c < 0x20 || c == 0x7f)
            fprintf(out, "\\u%04x", c);
        else
            fputc(c, out);
    }
    fputc('"', out);
}

void json_number(FILE *out, double v)
{
    if (!isfinite(v))
        fputs("null", out);
    else
        pc_fprintf(out, "%.17g", v == 0 ? 0.0 : v); // never "-0"
}
