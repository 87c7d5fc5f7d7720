/*
 * absform.h - abs(x) as the printers write it.
 *
 * The algebra keeps |x| as x*sign(x) (kernel.h: a KF_SIGN kernel s with
 * s^2 = 1), which is the normal form, not what a reader wrote: the book
 * prints |t - 1|, and the contract's functions have abs but no sign.  A
 * polynomial p (reduced: of degree <= 1 in every sign kernel) is
 *     p = p0 + s*p1,   p0, p1 free of s;
 * when x divides p1, p1 = x^(2m+1)*q with q not divisible by x^2, and
 *     p = p0 + |x|^(2m+1)*q        (|x|^3 = x^2*|x|: the book's |x|^3).
 * absform_rewrite writes that as p0 + s^(2m+1)*q, the variable s now
 * standing for |x| (marked in is_abs): the printers write s as abs(x).
 * A sign(x) with no factor x stays sign(x) (docs/language.md).
 */
#ifndef PC_ABSFORM_H
#define PC_ABSFORM_H

#include "compiler/algebra/kernel.h"

/* res = p with every sign kernel s = sign(x) whose terms all carry the
 * factor x rewritten as above; is_abs[v] (r->nvars entries, set by the
 * caller to 0) becomes 1 for each such s.  Returns the number of kernels
 * rewritten (0: res = p).  K may be NULL.  res must not alias p. */
slong absform_rewrite(fmpz_mpoly_t res, unsigned char *is_abs,
                      const fmpz_mpoly_t p, const Kernels *K, const Ring *r);

/* the same, also for a sign kernel s = sign(N/d) whose argument has a
 * number d > 0 for denominator (the kernels keep sign((2t - 1)/2) apart
 * from sign(2t - 1)): sign(N/d) = sign(N), so x*s with N | x reads as
 * |N| (times x/N), and its var stands for |N| (absform_abs_text) */
slong absform_rewrite_num(fmpz_mpoly_t res, unsigned char *is_abs,
                          const fmpz_mpoly_t p, const Kernels *K,
                          const Ring *r);

/* the text inside |.| of a var rewritten by absform_rewrite_num: the
 * argument x ("t - 1"), or its numerator N ("2*t - 1") when x has a
 * denominator (malloc'd) */
char *absform_abs_text(const Kernel *s, const Ring *r, int latex);

/* 1 when some kernel of K is a sign kernel (nothing to do otherwise) */
int absform_any(const Kernels *K);

/* the argument x of sign kernel s as its name writes it ("t - 1" of
 * "sign(t - 1)"), text or LaTeX (malloc'd) */
char *absform_arg_text(const Kernel *s, int latex);

#endif
