#!/bin/sh
# api_example_test.sh EXAMPLE [RUNNER...] - runs examples/api_example.c's
# binary (under RUNNER, e.g. valgrind, when given) and checks the two lines
# its comments promise: the curve's point at t = 0.5 and no poles.
set -u
ex=$1
shift
out=$(mktemp) || exit 1
trap 'rm -f "$out"' EXIT
"$@" "$ex" > "$out" || { echo "FAIL: api_example exited $?"; exit 1; }
if grep -qx 'M(0.50) = (0.25, 0.25, 0.25)' "$out" && grep -qx 'poles: 0' "$out"; then
    echo "api_example: ok"
else
    echo "FAIL: api_example printed:"
    cat "$out"
    exit 1
fi
