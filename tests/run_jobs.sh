#!/bin/sh
# run_jobs.sh JOBS COMMAND... - runs each COMMAND (one shell command line
# per argument) with at most JOBS of them at once, as `make check`, `make
# asan` and `make valgrind` run their suites.  Each command's output is kept
# apart and printed whole, under "== COMMAND (N s)", when it ends; a failed
# one ends with "FAILED (exit N)".  The list of failures comes last, and the
# exit status is 1 when any command failed.  Give the longest commands first:
# they start first, and the short ones fill the other slots around them.
set -u
if [ $# -lt 1 ]; then
    echo "usage: $0 JOBS COMMAND..." >&2
    exit 2
fi
jobs=$1
shift
case $jobs in '' | *[!0-9]* | 0) jobs=1 ;; esac
dir=$(mktemp -d) || exit 1
trap 'rm -rf "$dir"' EXIT
trap 'exit 130' INT TERM
n=0
for c in "$@"; do
    n=$((n + 1))
    printf '%s\n' "$c" > "$dir/cmd.$n"
done
[ $n -gt 0 ] || exit 0
export RUN_JOBS_DIR="$dir"
seq 1 $n | xargs -P "$jobs" -I{} sh -c '
    d=$RUN_JOBS_DIR
    c=$(cat "$d/cmd.$1")
    start=$(date +%s)
    sh -c "$c" > "$d/log.$1" 2>&1
    rc=$?
    took=$(($(date +%s) - start))
    {
        flock 9
        echo "== $c ($took s)"
        cat "$d/log.$1"
        if [ $rc -ne 0 ]; then
            echo "FAILED (exit $rc): $c"
            echo "$c" >> "$d/failed"
        fi
    } 9> "$d/lock"
    exit 0' run_job {}
if [ -s "$dir/failed" ]; then
    echo "== failed:"
    cat "$dir/failed"
    exit 1
fi
echo "== all $n passed"
