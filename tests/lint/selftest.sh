#!/bin/sh
# tests/lint/selftest.sh - the layer check can fail: copies of the tree with
# one planted upward include each (runtime/ -> codegen/, the algebra -> the
# printer) must be refused.
cd "$(dirname "$0")/../.." || exit 2
t=$(mktemp -d) || exit 2
trap 'rm -rf "$t"' EXIT
cp -r base grammar compiler runtime codegen driver "$t"/
echo '#include "codegen/lower.h"' >> "$t/runtime/plan.c"
if tests/lint/layers.sh "$t" > "$t/out"; then
    echo "FAIL: tests/lint/layers.sh accepted runtime/ including codegen/"
    exit 1
fi
grep -q 'runtime/plan.c:.*may not include "codegen/lower.h"' "$t/out" || {
    echo "FAIL: tests/lint/layers.sh did not name the planted include:"
    cat "$t/out"; exit 1; }
# the algebra below the printers: compiler/algebra/ -> compiler/print/
rm -rf "$t"/*
cp -r base grammar compiler runtime codegen driver "$t"/
echo '#include "compiler/print/format.h"' >> "$t/compiler/algebra/kernel.c"
if tests/lint/layers.sh "$t" > "$t/out"; then
    echo "FAIL: tests/lint/layers.sh accepted the algebra including a printer"
    exit 1
fi
grep -q 'compiler/algebra/kernel.c:.*may not include "compiler/print/format.h"' "$t/out" || {
    echo "FAIL: tests/lint/layers.sh did not name the planted include:"
    cat "$t/out"; exit 1; }
echo "lint self-test: planted upward includes are refused"
