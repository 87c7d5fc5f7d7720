/*
 * output.h - the number and string forms of eval's CSV and JSON output.
 *
 * Numbers are %.17g (they read back exactly).  A pole's NaN is written
 * `nan` in CSV (never glibc's `-nan`) and `null` in JSON, which has no NaN;
 * infinities likewise `inf`/`-inf` and `null`.
 */
#ifndef PC_OUTPUT_H
#define PC_OUTPUT_H

#include <stdio.h>

typedef enum OutputFormat { OUTPUT_CSV, OUTPUT_JSON } OutputFormat;

void output_number(FILE *out, double v, OutputFormat f);
/* a JSON string literal, quotes included */
void output_json_string(FILE *out, const char *s);

#endif
