/*
 * fuzz_light.c - the light libFuzzer target (`make fuzz`, beside
 * fuzz_derive.c): derive, the text printer and the C emission only
 * (exercise_light in tests/fuzz/exercise.h), with small inputs (-max_len
 * 512) and seeds without the heavy chapter-2 schemes, so that a campaign
 * of 10^6 executions fits in hours on one core.  Each input has a work
 * budget (FUZZ_DERIVE_SECONDS for the derivation, FUZZ_BACKEND_SECONDS for
 * printing and lowering, base/budget.h): an input past it is abandoned
 * with the budget's error, which is a result, not a finding.  Any crash,
 * sanitizer report, leak, or an inconsistent result is a bug.
 */
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>

#include "compiler/derive.h"
#include "tests/fuzz/exercise.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    return fuzz_one_input(data, size, exercise_light);
}
