/*
 * emit_c_int.h - private to the emit-c files (emit_c.c, emit_c_names.c,
 * emit_weights.c, emit_fast.c): the names of the generated C, the
 * per-output context, and the helpers they share.
 */
#ifndef PC_EMIT_C_INT_H
#define PC_EMIT_C_INT_H

#include "codegen/cwrite.h"
#include "codegen/emit_c.h"

enum { BLOCK = CWRITE_BLOCK }; // samples per block in the generated batch code

typedef enum Variant { ONE, ONE_CHECKED, BATCH, BATCH_CHECKED } Variant;
enum { NVARIANTS = 4 };

typedef struct Names {
    unsigned want; // EMIT_C_* bits: the variants that are public
    char *prefix;  // owned
    char **fn;     // owned: function name of output i, variant v at 4*i + v
    char **in;     // C names of params then consts (owned)
    char **pt;     // C names of points (owned)
    int nfn, nin, npt;
} Names;

void emit_names_init(Names *N, const Plan *p, const char *prefix);
void emit_names_clear(Names *N);
/* the definition's or prototype's first line(s) of variant v of output
 * oi; restr: see emit_signature_ex in emit_c_names.c */
void emit_signature_ex(FILE *out, const Plan *p, const Names *N, int oi,
                       Variant v, int restr);
void emit_signature(FILE *out, const Plan *p, const Names *N, int oi,
                    Variant v);

typedef struct Ctx {
    FILE *out;
    const Plan *p;
    const Names *N;
    int oi; // the output's index
    const PlanOutput *o;
    unsigned char *live; // registers this output needs
    int batch;           // inputs are x0.. (loop copies) instead of names
    const char **role;   // per register: what it is, or NULL
} Ctx;

/* ---- natx, naty (emit_natural.c) ---- */

/* the static helper pcnat_PREFIX, when p needs it */
void emit_natural_helper(FILE *out, const Plan *p, const char *prefix);
/* the call computing instruction x (NATX or NATY) */
void emit_natural_call(const Ctx *C, const PlanIns *x);

/* ---- the weights code (emit_weights.c) ---- */

/* register r as an operand: a literal, an input or rN */
void emit_operand(const Ctx *C, int r);
/* every needed computing instruction whose uniformity is `uniform` (or
 * all of them when uniform < 0) */
void emit_instructions(const Ctx *C, int uniform, const char *indent);
/* int NAME_M_checked(...) */
void emit_one(const Ctx *C);
/* size_t NAME_M_batch_checked(...) */
void emit_batch(Ctx *C);

/* A weight slot of the batch code: w = sign * root (plan_peel); the block
 * loop computes root, the points' coordinates are negated once per call
 * (the locals kK_C, qK) where the sign is -1. */
typedef struct Slot {
    int root, sign;
} Slot;

static inline int scaled(const Slot *s)
{
    return s->sign != 1;
}

/* does the output check a function's domain (status 4)? */
static inline int uses_domain(const Ctx *C)
{
    for (int r = 0; r < C->p->nins; r++)
        if (C->live[r] && C->p->ins[r].op == PLAN_DOMAIN)
            return 1;
    return 0;
}

static inline int param_used(const Ctx *C, int i)
{
    for (int r = 0; r < C->p->nins; r++)
        if (C->live[r] && C->p->ins[r].op == PLAN_INPUT && C->p->ins[r].a == i)
            return 1;
    return 0;
}

/* ---- the fast _batch and the forwarding functions (emit_fast.c) ---- */

/* void NAME_M_batch(...) for dim 2 and 3; 0 when it did not apply */
int emit_batch_fast(Ctx *C);
/* the call of the _checked variant with the arguments of the variant v
 * (ONE or BATCH) being defined */
void emit_forward(const Ctx *C, Variant v);

#endif
