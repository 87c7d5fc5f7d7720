/*
 * check.h - the policy for internal invariants (docs/contributing.md).
 *
 * A user error is reported through diag at the user's text.  An internal
 * invariant that fails (a canonical form broken, an exact division that
 * left a remainder, a FLINT call that failed where it cannot by
 * construction, a case no input reaches) is a bug in pointcalc: it is never
 * turned into a silent wrong result or a message that blames the input.
 * PC_ASSERT checks it in every build (these checks are cheap and guard
 * exactness); pc_internal_error says what broke, where, and aborts.
 */
#ifndef PC_BASE_CHECK_H
#define PC_BASE_CHECK_H

#include <stddef.h>

/* writes s[0..n) to fd with write(2), retrying short writes; allocates
 * nothing and is safe in a signal handler (the budget's and the tests'
 * last words); gives up silently when the fd refuses */
void pc_write_all(int fd, const char *s, size_t n);

/* prints "pointcalc: internal error at FILE:LINE: WHAT (a bug: please
 * report it with the scheme)" to stderr and aborts */
_Noreturn void pc_internal_error(const char *file, int line, const char *what);

#define PC_ASSERT(cond)                                                        \
    ((cond) ? (void)0 : pc_internal_error(__FILE__, __LINE__, #cond))
#define PC_UNREACHABLE(what) pc_internal_error(__FILE__, __LINE__, (what))

#endif
