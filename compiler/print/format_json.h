/*
 * format_json.h - derive --format json (contract section 4):
 *
 *   {"scheme": .., "points": [..], "params": [..], "consts": [..],
 *    "outputs": [{"name": .., "kind": .., "terms": {POINT: WEIGHT, ..}}]}
 *
 * A scalar output carries "value" instead of "terms".  format_derived
 * calls it for FMT_JSON.
 */
#ifndef PC_FORMAT_JSON_H
#define PC_FORMAT_JSON_H

#include <stdio.h>

#include "compiler/derive.h"

void format_json(FILE *out, const Derived *d);

#endif
