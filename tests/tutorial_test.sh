#!/usr/bin/env bash
# docs/tutorial.md is a test: every "$ command" line inside a ```sh block is
# run from the repository root with the tested pointcalc first on the PATH,
# and its output must equal the lines that follow it up to the next command
# or the end of the block; every code block preceded by
# "<!-- file: PATH -->" must equal that file.
set -u
PC=${1:-build/pointcalc}
DOC=${2:-docs/tutorial.md}
pass=0
fail=0
bindir=$(mktemp -d)
trap 'rm -rf "$bindir"' EXIT
ln -s "$(cd "$(dirname "$PC")" && pwd)/$(basename "$PC")" "$bindir/pointcalc"
mkdir -p build/tutorial

ok() { pass=$((pass + 1)); }
bad() { fail=$((fail + 1)); echo "FAIL: $1"; }

# runs one command and compares its output with the expected text
run_cmd() { # CMD EXPECTED
    local got
    got=$(PATH="$bindir:$PATH" bash -c "$1" 2>&1)
    local rc=$?
    if [ $rc -ne 0 ]; then
        bad "tutorial: '$1' exited $rc: $got"
    elif [ "$got" != "$2" ]; then
        bad "tutorial: '$1' printed
$got
expected
$2"
    else
        ok
    fi
}

in_block=0 kind="" cmd="" expect="" file="" body=""
while IFS= read -r line || [ -n "$line" ]; do
    if [ $in_block -eq 0 ]; then
        case "$line" in
        "<!-- file: "*" -->") file=${line#<!-- file: }; file=${file% -->} ;;
        '```'*)
            in_block=1 kind=${line#\`\`\`} cmd="" expect="" body="" ;;
        *) [ -n "$line" ] && file="" ;;
        esac
        continue
    fi
    if [ "$line" = '```' ]; then
        if [ "$kind" = sh ] && [ -n "$cmd" ]; then run_cmd "$cmd" "$expect"; fi
        if [ -n "$file" ]; then
            if [ "$body" = "$(cat "$file")" ]; then ok; else bad "tutorial: the block differs from $file"; fi
        fi
        in_block=0 file=""
        continue
    fi
    body=${body:+$body$'\n'}$line
    if [ "$kind" = sh ]; then
        case "$line" in
        '$ '*)
            if [ -n "$cmd" ]; then run_cmd "$cmd" "$expect"; fi
            cmd=${line#\$ } expect="" ;;
        *) expect=${expect:+$expect$'\n'}$line ;;
        esac
    fi
done <"$DOC"
echo "tutorial: $pass passed, $fail failed"
test "$fail" -eq 0 -a "$pass" -ge 10
