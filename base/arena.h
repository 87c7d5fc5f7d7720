/*
 * arena.h - compilation-lifetime memory (house style 1.2).
 *
 * One Arena per compilation holds the source copy, identifier strings, the
 * AST and the symbols.  Memory is zero-filled, aligned for any type, never
 * NULL, and freed all at once by arena_reset.  Nothing in an arena owns
 * heap memory (FLINT values live on the heap, owned by their results).
 */
#ifndef PC_ARENA_H
#define PC_ARENA_H

#include <stddef.h>

typedef struct ArenaBlock ArenaBlock;

typedef struct Arena {
    ArenaBlock *blocks; // owned, newest first
} Arena;

void arena_init(Arena *a);
/* zeroed, max_align_t-aligned; aborts only when the machine is out of memory */
void *arena_alloc(Arena *a, size_t size);
#define arena_new(a, T) ((T *)arena_alloc((a), sizeof(T)))
char *arena_strndup(Arena *a, const char *s, size_t n);
char *arena_strdup(Arena *a, const char *s);
void arena_reset(Arena *a);

#endif
