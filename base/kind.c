/*
 * kind.c - the kinds' names (kind.h).
 */
#include "base/kind.h"

const char *kind_name(Kind k)
{
    return k == KIND_POINT ? "point" : k == KIND_VECTOR ? "vector" : "scalar";
}
