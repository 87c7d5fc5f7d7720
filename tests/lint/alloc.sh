#!/bin/sh
# alloc.sh - the one allocator (base/mem.h): the tree's code frees with
# pc_free what pc_xmalloc & co. made, so that --max-memory's count stays
# exact (issue 23 item 3).  A bare free() or malloc() in base, grammar,
# compiler, codegen, runtime or driver is refused, except in base/mem.c
# (the allocator itself) and on a line that says whose block it is
# ("libc's block").
cd "$(dirname "$0")/../.." || exit 2
bad=$(grep -nE '(^|[^A-Za-z0-9_>.])(free|malloc|calloc|realloc|strdup|strndup)\(' \
    $(find base grammar compiler codegen runtime driver -name '*.[ch]' ! -path base/mem.c) |
    grep -v "libc's block" |
    grep -vE '^[^:]+:[0-9]+:\s*(/?\*|//)' |
    grep -vE '^[^:]+:[0-9]+:.*/\*.*(free|malloc)\(.*\*/' )
if [ -n "$bad" ]; then
    echo "alloc: a bare allocator call; use pc_xmalloc & co. and pc_free (base/mem.h):"
    echo "$bad"
    exit 1
fi
echo "alloc: every allocation through base/mem.h"
