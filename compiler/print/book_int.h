/*
 * book_int.h - private to the book printer (book.h), shared by its files:
 * book_model.c (the model of a printed polynomial), book_write.c (the
 * model as text or LaTeX), book_forms.c (the forms of a polynomial, the
 * choice among them), book_factor.c (the factored forms), book_collect.c
 * (the collected forms), book_unroot.c (un-rationalised alternatives) and
 * book_eq.c (equations and whole outputs).  Nothing outside
 * compiler/print/book_*.c includes it.
 */
#ifndef PC_BOOK_INT_H
#define PC_BOOK_INT_H

#include <flint/fmpz_mpoly.h>

#include "base/strbuf.h"
#include "compiler/algebra/kernel.h"
#include "compiler/algebra/poly_print.h"
#include "compiler/print/book.h"

/* ---- the print model: sums of products of atoms ------------------------ */

typedef enum AtomKind {
    AT_VAR,   // a ring variable: param, const, function
    AT_BAR,   // 1 - x of a param or const
    AT_SUM,   // a parenthesised sum
    AT_POINT, // a point name, or a difference of two (point2)
    AT_ABS,   // |x| of the sign kernel var = sign(x) (absform.h)
    AT_KNOT,  // x of the sign kernel var = sign(x), as its |x| writes it: the
              // (t - 1) of the book's (2t + 1)(t - 1)|t - 1|
} AtomKind;

typedef struct PSum PSum;

typedef struct Atom {
    AtomKind kind;
    slong var;          // AT_VAR, AT_BAR
    PSum *sum;          // AT_SUM (owned)
    const char *point;  // AT_POINT (borrowed)
    const char *point2; // AT_POINT: point - point2, or NULL
    ulong exp;
} Atom;

typedef struct PTerm {
    int neg;
    fmpz_t coeff; // >= 1
    slong n;
    Atom *a;
} PTerm;

struct PSum {
    slong n, alloc; // alloc: the terms t has room for (it grows by doubling)
    PTerm *t;
    fmpz_mpoly_t poly; // what the sum is, up to sign (for the total order)
    int has_param;     // it involves a param
    int keep_order;    // collected by the knots (book_forms.c): never rotated
                       // (a leading minus is taken out whole instead)
};

typedef struct Ctx {
    const Ring *r;
    slong nparams, nconsts; // vars < nparams are params; < nparams+nconsts
                            // consts; the rest functions and extras
    int latex;
    long *work;        // the printing work spent on this output (RENDER_WORK)
    struct Memo *memo; // forms already chosen: this output's, or the
                       // scheme's (BookOptions.memo)
    const Kernels *K;  // the functions (NULL: none)
    int has_sign;      // K has a sign kernel: polynomials are read for |x|
    const unsigned char *is_abs; // rendering a polynomial rewritten by
                                 // absform_rewrite: its vars meaning |x|
    ulong mode; // 0, or a key of is_abs (memo entries differ by it)
    const DerivedName *named; // the scheme's named kernel powers, and the
    slong nnamed;             // line of the definition being printed:
    int line;                 // names defined before it print for them
    int exhaustive; // BookOptions.exhaustive: no form given up by a bound
} Ctx;

/* render() of a polynomial at a depth, kept: the same coefficients and
 * factors come up in every collection */
typedef struct MemoEntry {
    fmpz_mpoly_t poly;
    ulong key; // memo_key of poly: most entries are passed over by it
    int depth;
    ulong mode; // Ctx.mode it was rendered in
    struct PSum *sum;
} MemoEntry;

enum {
    MEMO_MAX = 1024,  // entries remembered (the first ones)
    MEMO_SLOTS = 2048 // the hash table's slots: a power of 2 > MEMO_MAX
};

typedef struct Memo {
    MemoEntry *e;
    slong n, alloc;
    slong *slot; // MEMO_SLOTS: 1 + the index of an entry in e, or 0; by key
                 // (open addressing), allocated with the first entry
    fmpz_mpoly_struct *fac; // irreducible factors (not monomials, positive
    slong nfac, facalloc;   // leading coefficient) of the polynomials
                            // factored fully so far (book_factor.c)
} Memo;                     /* = BookMemo (book.h) */

enum {
    MAX_DEPTH = 2,          // levels of collection (factors and coefficients)
    MAX_COLLECT_TERMS = 60, // larger polynomials: expanded or factored only
    RENDER_WORK = 60000,    // per output, in terms looked at (a factoring
                            // counts FACTOR_WORK + 20 per term): beyond it,
                            // polynomials are written expanded, or factored
                            // at the top level only
    FACTOR_WORK = 200,
    MAX_FACTOR_TERMS_NESTED = 24, // factors and coefficients factored only
                                  // when this short
    CHEAP_FACTOR_DEPTH = 2,       // from this depth on: form_factored_cheap
};

/* One form of n numerators over one denominator (the printers' input) */
typedef struct Cand {
    slong n;
    fmpz_mpoly_struct *num; // n numerators
    fmpz_mpoly_t den;
} Cand;

/* ---- book_model.c: making, ordering and measuring models ---------------- */

/* a new empty sum, owned by the caller; book_sum_free frees it and the
 * sums nested in it (NULL is allowed); book_sum_copy: a deep copy */
PSum *book_sum_new(const Ctx *c);
void book_sum_free(PSum *s, const Ctx *c);
PSum *book_sum_copy(const PSum *s, const Ctx *c);
PTerm *book_sum_push(PSum *s);                 // appends the term 1
void book_term_push(PTerm *t, Atom a);         // appends an atom (consumed)
void book_term_absorb(PTerm *dst, PTerm *src); // dst *= src; src emptied
void book_term_sort(PTerm *t, const Ctx *c);   // atoms in book.h's order
void book_sum_neg(PSum *s, const Ctx *c);      // negates every term
/* s is a form of p: records p and whether it has a param, sorts the terms */
void book_sum_finish(PSum *s, const fmpz_mpoly_t p, const Ctx *c);
slong book_sum_leaves(const PSum *s); // the size the forms compete on
void book_memo_clear(Memo *m, const Ctx *c);
int book_is_param(const Ctx *c, slong v); // var v is a param
/* the scheme's name to write var^e through, or NULL */
const DerivedName *book_named_for(slong var, ulong e, const Ctx *c);

/* ---- book_write.c: models as text or LaTeX ------------------------------- */

void book_put_point(StrBuf *b, const char *p, const Ctx *c);
void book_put_exp(StrBuf *b, ulong e, const Ctx *c); // ^e, nothing for e <= 1
/* num/den: \frac in LaTeX, parentheses as needed in text */
void book_put_frac(StrBuf *b, const char *num, int num_items, const PSum *den,
                   const Ctx *c);
void book_put_atom(StrBuf *b, const Atom *a, const Ctx *c);
void book_put_term(StrBuf *b, const PTerm *t, const Ctx *c); // without sign
void book_put_sum(StrBuf *b, const PSum *s, const Ctx *c);
size_t book_sum_text_len(const PSum *s, const Ctx *c); // in c's style

/* ---- book_forms.c: the forms of a polynomial ----------------------------- */

/* p expanded, ascending (the reverse of FLINT's degrevlex) */
PSum *book_form_expanded(const fmpz_mpoly_t p, const Ctx *c);
/* p in its best form at depth (0: the top level) */
PSum *book_render(const fmpz_mpoly_t p, int depth, const Ctx *c);
/* a lower bound on the leaves of book_render(p, depth, c), without
 * rendering it: 1 or 2, or the leaves of the form in the memo */
slong book_leaves_lower(const fmpz_mpoly_t p, int depth, const Ctx *c);

/* ---- book_factor.c: the factored forms ----------------------------------- */

/* p factored (FLINT's factoring, or what proves it), NULL when p is
 * irreducible and primitive; its factors are remembered in c->memo and
 * divided out of the polynomials factored after it */
PSum *book_form_factored(const fmpz_mpoly_t p, int depth, const Ctx *c);
/* deep inside a form: the integer and monomial content, powers of 1 - x
 * and a perfect square, without FLINT's factoring; NULL when none is there */
PSum *book_form_factored_cheap(const fmpz_mpoly_t p, int depth, const Ctx *c);

/* ---- book_collect.c: the collected forms --------------------------------- */

/* Each is NULL when it has more leaves than limit (it could not win), or
 * when it does not apply. */
/* p = sum_k c_k x^k, ascending */
PSum *book_form_powers(const fmpz_mpoly_t p, slong x, int depth, slong limit,
                       const Ctx *c);
/* p = sum_k b_k x^k (1 - x)^(n-k), n = deg_x p: the Bernstein basis of
 * the param x (without binomials) */
PSum *book_form_bernstein(const fmpz_mpoly_t p, slong x, int depth, slong limit,
                          const Ctx *c);
/* the cos kernel var of the same argument as sin kernel var v, or -1 */
slong book_cos_companion(slong v, const Ctx *c);
/* p (even in s = sin(x), free of w = cos(x)) as a polynomial in y = s^2,
 * in the basis y^k (1 - y)^(n-k) with 1 - y = cos(x)^2: the book's
 * a^2*sin(phi)^2 + b^2*cos(phi)^2 for the normal form's b^2 - b^2*sin(phi)^2
 * + a^2*sin(phi)^2; NULL when p is not such */
PSum *book_form_sin2(const fmpz_mpoly_t p, slong s, slong w, int depth,
                     slong limit, const Ctx *c);

/* ---- book_unroot.c: roots where the user put them ------------------------ */

void book_cand_clear(Cand *x, const Ctx *c);
/* the un-rationalised forms of N/D (H: hints, the other weights); returns
 * their number, *out malloc'd (book_cand_clear each, then free) */
slong book_unroot_cands(Cand **out, const fmpz_mpoly_struct *const *N, slong n,
                        const fmpz_mpoly_t D, const fmpz_mpoly_struct *const *H,
                        slong nh, const Ctx *c);

#endif
