/*
 * output.c - numbers and strings for eval's CSV and JSON writers.
 */
#include "runtime/output.h"

#include <math.h>

#include "compiler/numfmt.h"

void output_number(FILE *out, double v, OutputFormat f)
{
    if (isnan(v))
        fputs(f == OUTPUT_JSON ? "null" : "nan", out);
    else if (isinf(v))
        fputs(f == OUTPUT_JSON ? "null" : v > 0 ? "inf" : "-inf", out);
    else
        pc_fprintf(out, "%.17g", v == 0 ? 0.0 : v); // never "-0"
}

void output_json_string(FILE *out, const char *s)
{
    fputc('"', out);
    for (; *s; s++) {
        unsigned char c = (unsigned char)*s;
        if (c == '"' || c == '\\')
            fprintf(out, "\\%c", c);
        else if (c < 0x20)
            fprintf(out, "\\u%04x", c);
        else
            fputc(c, out);
    }
    fputc('"', out);
}
