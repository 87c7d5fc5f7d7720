/*
 * arena.c - compilation-lifetime memory (arena.h): blocks of 64 KiB (or one
 * block the size of a larger request) handed out by bumping an offset,
 * aligned for any type and zero-filled, freed all at once.  The AST, names
 * and symbols of one compilation live here; nothing in it owns heap memory.
 */
#include "base/arena.h"

#include <stdalign.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/mem.h"

enum { BLOCK_SIZE = 64 * 1024 };

struct ArenaBlock {
    ArenaBlock *next;
    size_t used, size;
    alignas(max_align_t) unsigned char data[];
};

void arena_init(Arena *a)
{
    a->blocks = NULL;
}

static ArenaBlock *new_block(size_t size)
{
    ArenaBlock *b = pc_xmalloc(sizeof(ArenaBlock) + size);
    b->next = NULL;
    b->used = 0;
    b->size = size;
    return b;
}

void *arena_alloc(Arena *a, size_t size)
{
    const size_t align = alignof(max_align_t);
    size = (size + align - 1) & ~(align - 1);
    if (size == 0)
        size = align;
    ArenaBlock *b = a->blocks;
    if (!b || b->size - b->used < size) {
        if (size > BLOCK_SIZE / 4) {
            /* big request: own block, kept behind the current one */
            ArenaBlock *big = new_block(size);
            big->used = size;
            if (b) {
                big->next = b->next;
                b->next = big;
            } else {
                a->blocks = big;
            }
            memset(big->data, 0, size);
            return big->data;
        }
        b = new_block(BLOCK_SIZE);
        b->next = a->blocks;
        a->blocks = b;
    }
    void *p = b->data + b->used;
    b->used += size;
    memset(p, 0, size);
    return p;
}

char *arena_strndup(Arena *a, const char *s, size_t n)
{
    char *d = arena_alloc(a, n + 1);
    memcpy(d, s, n);
    d[n] = '\0';
    return d;
}

char *arena_strdup(Arena *a, const char *s)
{
    return arena_strndup(a, s, strlen(s));
}

void arena_reset(Arena *a)
{
    ArenaBlock *b = a->blocks;
    while (b) {
        ArenaBlock *next = b->next;
        pc_free(b);
        b = next;
    }
    a->blocks = NULL;
}
