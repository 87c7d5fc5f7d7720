/*
 * kind.h - the one kind of a value, from sema to the runtime: a scalar, a
 * point (weights summing to 1) or a vector (weights summing to 0).  The
 * Derived outputs and the Plan's outputs both carry it.
 */
#ifndef PC_BASE_KIND_H
#define PC_BASE_KIND_H

typedef enum Kind {
    KIND_SCALAR, // a rational function of params and consts: one value
    KIND_POINT,  // a point equation whose weights sum to 1
    KIND_VECTOR, // a point equation whose weights sum to 0
} Kind;

/* "scalar", "point", "vector": as messages, JSON and the steps write it */
const char *kind_name(Kind k);

#endif
