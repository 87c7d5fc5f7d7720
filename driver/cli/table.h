/*
 * table.h - eval's output: CSV (contract section 4) or JSON (docs/eval.md),
 * written row by row as the samples are computed.
 *
 * CSV: a header "t,k,M.1,M.2,..." - the given params, then the swept
 * consts (each in declaration order), then every selected output's
 * coordinates (a scalar output as one column "NAME") - and one line per
 * sample, numbers as %.17g; NaN is "nan" (never "-nan"), infinities
 * "inf" and "-inf".
 *
 * JSON: one object; the user's names appear only as keys of the objects
 * "params", "consts" and "values" and in lists, so no name can collide
 * with a key of the format:
 *
 *   {"scheme": "S", "params": ["t"], "consts": ["k"],
 *    "outputs": [{"name": "M", "kind": "point", "dim": 2}],
 *    "samples": [
 *     {"params": {"t": 0}, "consts": {"k": 1}, "values": {"M": [0, 1]}},
 *     {"params": {"t": 1}, "consts": {"k": 1}, "values": {"M": [null, null]},
 *      "poles": ["M"]}, ...]}
 *
 * A sample lists the outputs that are not finite there under "poles",
 * "nonfinite" and "domain" (each only when not empty); their values are
 * null.
 */
#ifndef PC_TABLE_H
#define PC_TABLE_H

#include <stddef.h>
#include <stdio.h>

#include "driver/cli/args.h"
#include "runtime/plan.h"

typedef enum TableFormat { TABLE_CSV, TABLE_JSON } TableFormat;

/* eval's status of a sample beyond PlanStatus: a value that is not finite
 * although its denominator is (the terms of a numerator overflowed) */
enum { TABLE_STATUS_TERMS = PLAN_STATUS_OVERFLOW + 1 };

/* one sample */
typedef struct TableRow {
    const double *params;        // per param of the plan
    const double *consts;        // per const of the plan
    const double *const *values; // per selected output: its coordinates
    const unsigned char *status; // per selected output: PlanStatus or
                                 // TABLE_STATUS_TERMS
} TableRow;

/* the number of columns of output o of the plan: dim, or 1 (a scalar) */
int table_columns(const Plan *p, int o, int dim);

void table_head(FILE *out, TableFormat f, const Plan *p, const EvalSetup *s);
/* sample number `index` (from 0) */
void table_row(FILE *out, TableFormat f, const Plan *p, const EvalSetup *s,
               const TableRow *r, size_t index);
void table_tail(FILE *out, TableFormat f, size_t rows);

/* a number of a CSV line ("nan", "inf", "-inf" when not finite) or of
 * JSON (json_number) */
void table_number(FILE *out, double v, TableFormat f);

#endif
