/*
 * json.h - the one JSON writer of the tree: strings and numbers, written
 * straight to a FILE.  Used by derive --format json (format_json.c) and by
 * eval --format json (driver/cli/table.c); the objects around them are
 * each caller's own.
 */
#ifndef PC_JSON_H
#define PC_JSON_H

#include <stdio.h>

/* A JSON string literal, quotes included: '"' and '\' escaped, control
 * characters and DEL as \u00XX, every other byte as it is (UTF-8 passes
 * through).  A scheme's name comes from its file name and may hold
 * anything. */
void json_string(FILE *out, const char *s);

/* A number as %.17g (it reads back exactly) in the C locale, never "-0";
 * JSON has no NaN or infinity, so a value that is not finite is null. */
void json_number(FILE *out, double v);

#endif
