/*
 * pipeline.h - one compilation's shared state, as the passes of
 * derive_source_ex (pipeline.c) hand it on:
 *
 *   parse -> expand -> sema -> plan the ring -> derive -> outputs -> steps
 *
 * The public entry points stay in derive.h (derive_source_ex and friends);
 * this header is for the pipeline and the passes it calls.
 */
#ifndef PC_PIPELINE_H
#define PC_PIPELINE_H

#include <stdio.h>

#include "base/arena.h"
#include "base/diag.h"
#include "base/source.h"
#include "compiler/derive.h"
#include "compiler/sema.h"
#include "grammar/ast.h"

typedef struct Compilation {
    const char *filename; // as given
    const char *text;     // the scheme text (len bytes), not owned
    size_t len;
    FILE *err;                // diagnostics, or NULL: discarded
    const DeriveOptions *opt; // not NULL
    double start;             // CLOCK_MONOTONIC seconds at the start: the
                              // time budget counts from here
    Arena arena;              // the AST, symbols and names of this compilation
    Source src;               // filename + text, for diagnostics
    Diag diag;                // held until the end (diag_hold), then flushed
    Scheme *scheme;           // parse
    SemaInfo *info;           // sema, or NULL: an error before or in sema
    Derived *d;               // the result of the current try, or NULL
    slong nslots_try;         // kernel slots of the current try
    int diag_msgs0, diag_errors0; // the diagnostics before the first try
} Compilation;

#endif
