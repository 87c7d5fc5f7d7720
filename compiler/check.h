/*
 * check.h - `check` statements: claims about a scheme's values, proved
 * exactly after the derivation (docs/language.md, "Checks").
 *
 *   check L = R [at t = v, ...]              equality of points, vectors
 *                                            or scalars
 *   check on(P, line(A, B)) | on(P, plane(A, B, C))    incidence
 *   check parallel(U, V)                     parallel (collinear) vectors
 *   check tangent(M at t = v, line(A, B))    tangency of a curve to a line
 *   check contact(k, M at t = a, N at u = b) contact of order exactly k
 *   check contact(k, M at t = a, line(A, B))  the same with a line: M(a) on
 *                                            it, M' .. M^(k) along it, and
 *                                            M^(k+1) not
 *   check Ck(M at t = a, N at u = b)         C^k at a joint (k = 0..8)
 *   check Gk(M at t = a, N at u = b)         G^k at a joint
 *   check order(M, t) = n                    the degree of M in t (its
 *                                            reduced equation's numerators
 *                                            and denominator): the order of
 *                                            a properly parametrised curve
 *   check Ck(M at t = a), Gk(M at t = a)     the same at a knot of one
 *                                            composite curve (abs, sign):
 *                                            its left side against its right
 *
 * `check CLAIM [at ...] for i in a..b` is one claim per i (expand.c;
 * sum's index semantics), each failure naming its i; `Ck`, `Gk` may
 * take an int (or such an index) k.
 *
 * `at t = v` after a claim substitutes into every value of it (after the
 * derivatives it takes); `M at t = v` among the arguments names the curve
 * M and its point t = v (it is subst(M, t, v) anywhere else).
 *
 * check_resolve (sema, compiler/check_sema.c) turns a statement into a
 * CheckInfo: plain expressions, each typed by sema like any other, that
 * compiler/derive/check.c evaluates and compares.  The jets of a curve at
 * its point are the expressions subst(diff(M, t, j), t, v), j = 0.., so
 * derive's diff and subst (functions, kernels, the chain rule) do the
 * work; a jet's later orders are evaluated only when a comparison needs
 * them.
 */
#ifndef PC_CHECK_H
#define PC_CHECK_H

#include "base/arena.h"
#include "base/diag.h"
#include "grammar/ast.h"

/* the highest derivative a check compares (C8, G8, contact(7, ...), the
 * tangent of a curve whose first 7 derivatives vanish) */
enum { CHECK_MAX_ORDER = 8 };

/* X-macro: kind, its name in JSON */
#define PC_CHECK_KINDS(X)                                                      \
    X(CK_EQUAL, "equal")          /* ops L, R */                               \
    X(CK_ON_LINE, "on_line")      /* ops P, A, B */                            \
    X(CK_ON_PLANE, "on_plane")    /* ops P, A, B, C */                         \
    X(CK_PARALLEL, "parallel")    /* ops U, V */                               \
    X(CK_TANGENT, "tangent")      /* ops A, B, then M's jet 0..order */        \
    X(CK_CONTACT, "contact")      /* ops M's jet 0..order+1, N's jet */        \
    X(CK_CONTACT_LINE, "contact") /* ops A, B, M's jet 0..order+1 */           \
    X(CK_C, "C")                  /* ops M's jet 0..order, N's jet 0..order */ \
    X(CK_G, "G")                  /* the same */                               \
    X(CK_ORDER, "order")          /* ops M; order n, knot_var t */

typedef enum CheckKind {
#define X(k, s) k,
    PC_CHECK_KINDS(X)
#undef X
} CheckKind;

struct CheckInfo {
    CheckKind kind;
    int order;  // CK_C, CK_G, CK_CONTACT: k; CK_TANGENT: the jet's last
                // order (CHECK_MAX_ORDER)
    Node **ops; // nops expressions (above), typed by sema; arena
    int nops;
    int jet0;     // the first op of the first jet (CK_TANGENT: 2, else 0)
    int jetlen;   // the length of each jet
    Span what[2]; // the curves' arguments (`M at t = 1`), for messages
    int knot_var; // order(M, t): t's ring variable.
                  // Ck(M at t = a) of one curve: the param's ring
                  // variable; the jets (left, then right) are the one-sided
                  // derivatives at a, ops 2*jetlen and 2*jetlen + 1 are M and
                  // a, the jets' ops NULL; else -1
};

/* the kind's name (JSON "kind": "equal", "C", ...) */
const char *check_kind_name(CheckKind k);

struct SemaInfo;
/* Resolves check statement st into st->check and appends it to
 * I->checks: type(ctx, n) types an expression as sema does (1 a
 * combination of points, 0 a scalar, -1 an error it reported).  Returns
 * 0, or -1 after reporting an error (st->bad is then set, and st is not
 * appended). */
int check_resolve(struct SemaInfo *I, Stmt *st, Arena *a, Diag *d,
                  int (*type)(void *, Node *), void *ctx);

#endif
