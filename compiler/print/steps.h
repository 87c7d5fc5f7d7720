/*
 * steps.h - the printer of `pointcalc derive --steps`: every step of a
 * derivation (derive.h, Derived.steps) in source order, as the monograph
 * prints a derivation: each construction with its point equation, each
 * meet with the S- or V-theorem determinant, the solved line parameter
 * and the determinant that vanishes for parallel lines, each subst and
 * diff with its result (docs/language.md, "derive --steps").
 */
#ifndef PC_STEPS_H
#define PC_STEPS_H

#include <stdio.h>

#include "compiler/derive.h"
#include "compiler/print/format.h"

/* Prints the steps of d (derived with DeriveOptions.keep_steps) in style
 * st: text and LaTeX list the steps (origin as in format_derived: a base
 * point to write the point equations relative to, or -1); JSON prints
 * derive's JSON object (format_derived) with a "steps" array added. */
void steps_print(FILE *out, const Derived *d, FormatStyle st, slong origin);

#endif
