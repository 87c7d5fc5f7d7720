/*
 * functions.h - what every stage needs to expand base/functions.def: the
 * domains, and PC_WHEN/PC_PICK, which keep or drop a row's text by one of
 * its 0/1 columns at preprocessing time (so KF_TAN, which does not exist,
 * is never compiled).
 */
#ifndef PC_BASE_FUNCTIONS_H
#define PC_BASE_FUNCTIONS_H

typedef enum PcDomain {
    PC_DOM_ALL,    // every real number
    PC_DOM_NONNEG, // x >= 0
    PC_DOM_POS,    // x > 0
    PC_DOM_UNIT,   // |x| <= 1
} PcDomain;

#define PC_WHEN(c) PC_WHEN_##c
#define PC_WHEN_1(...) __VA_ARGS__
#define PC_WHEN_0(...)
#define PC_PICK(c) PC_PICK_##c
#define PC_PICK_1(yes, no) yes
#define PC_PICK_0(yes, no) no

#endif
