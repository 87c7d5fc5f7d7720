/*
 * format_int.h - private to the format module (format.h), shared by its
 * two files: format.c (the entry points, text and LaTeX through book.h)
 * and format_json.c (derive --format json, contract section 4):
 *
 *   {"scheme": .., "points": [..], "params": [..], "consts": [..],
 *    "outputs": [{"name": .., "kind": .., "terms": {POINT: WEIGHT, ..}}]}
 *
 * A scalar output carries "value" instead of "terms".  format_derived
 * calls format_json for FMT_JSON; format_json writes each weight with
 * format.h's format_weight_k.  One module in two files, so the include
 * goes one way: both include this header, format_json.c also format.h.
 */
#ifndef PC_FORMAT_INT_H
#define PC_FORMAT_INT_H

#include <stdio.h>

#include "base/source.h"
#include "compiler/derive.h"
#include "compiler/print/book.h"

void format_json(FILE *out, const Derived *d);
/* "key": "WEIGHT", w as derive's JSON writes every weight (format_weight_k:
 * abs kept); the outputs' terms and the knots' values and jumps; memo
 * (book.h; NULL: none) shares the factors among the weights */
void format_json_weight(FILE *out, const char *key, const RatFun w,
                        const Derived *d, BookMemo *memo);

#endif
