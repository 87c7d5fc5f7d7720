/*
 * fuzz_derive.c - libFuzzer target for the whole pipeline (parse, sema,
 * exact derivation, then every back end: tests/fuzz/exercise.h).  `make fuzz`
 * builds it with clang and runs it on the example corpus; any crash, sanitizer
 * report or inconsistent result (a NULL derivation without an error, or an
 * error with a derivation) is a bug.  Each input has a work budget
 * (FUZZ_DERIVE_SECONDS for the derivation, FUZZ_BACKEND_SECONDS for the
 * back ends, base/budget.h): an input past it is abandoned with the
 * budget's error.  fuzz_light.c is the lighter target beside it.
 */
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>

#include "compiler/derive.h"
#include "tests/fuzz/exercise.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    return fuzz_one_input(data, size, exercise_backends);
}
