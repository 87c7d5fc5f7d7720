#!/bin/sh
# tests/lint/selftest.sh - the layer check can fail: copies of the tree with
# one planted upward include each (runtime/ -> codegen/, the algebra -> the
# printer) must be refused, with the planted line named.
cd "$(dirname "$0")/../.." || exit 2
t=$(mktemp -d) || exit 2
trap 'rm -rf "$t"' EXIT
# plant FILE HEADER WHAT: a fresh copy of the tree with FILE including
# HEADER must fail tests/lint/layers.sh, naming FILE and HEADER
plant() {
    rm -rf "${t:?}"/*
    cp -r base grammar compiler runtime codegen driver "$t"/
    echo "#include \"$2\"" >> "$t/$1"
    if tests/lint/layers.sh "$t" > "$t/out"; then
        echo "FAIL: tests/lint/layers.sh accepted $3"
        exit 1
    fi
    grep -q "$1:.*may not include \"$2\"" "$t/out" || {
        echo "FAIL: tests/lint/layers.sh did not name the planted include:"
        cat "$t/out"; exit 1; }
}
plant runtime/plan.c codegen/lower.h "runtime/ including codegen/"
plant compiler/algebra/kernel.c compiler/print/format.h "the algebra including a printer"
echo "lint self-test: planted upward includes are refused"
