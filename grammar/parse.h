/*
 * parse.h - source text -> AST.  The only module that sees yyscan_t.
 */
#ifndef PC_PARSE_H
#define PC_PARSE_H

#include "base/arena.h"
#include "base/diag.h"
#include "grammar/ast.h"

/* Parses src (diagnostics to diag).  Returns the Scheme (arena) even when
 * errors were reported, so later passes may still look at the good lines;
 * callers stop when diag->nerrors grew. */
Scheme *parse_scheme(const Source *src, Arena *arena, Diag *diag);

#endif
