#!/usr/bin/env bash
# Derivation speed side by side: pointcalc (in-process, bench_derive) and
# Maxima (bench/maxima/bench_core.mac) on the same two core schemes.
# Skips cleanly when maxima is not installed.
set -u
B=${1:-build}
if ! command -v maxima >/dev/null 2>&1; then
    echo "maxima: not installed (apt-get install maxima maxima-share); side-by-side skipped"
    exit 0
fi
pc=$("$B/bench/bench_derive" bench/schemes) || exit 1
mx=$(maxima --very-quiet --batch-string='batchload("bench/maxima/bench_core.mac")$' 2>&1)
if ! echo "$mx" | grep -q '^maxima '; then
    # printf lives in Maxima's share library (Debian: maxima-share)
    echo "maxima: the bench script failed (is maxima-share installed?):"
    echo "$mx" | tail -3
    exit 0
fi
mx=$(echo "$mx" | grep '^maxima ')
echo
echo "side by side (ms per derivation; Maxima: first call (10 ms clock) and mean of repeated calls)"
printf "%-22s %12s %12s %12s %12s %10s\n" scheme "pointcalc" "maxima 1st" "maxima mean" "ratio mean" "ratio 1st"
for s in desargues_arc conic_five_points; do
    p=$(echo "$pc" | awk -v s="${s}_min.pcs" '$1 == s {print $3}')
    m1=$(echo "$mx" | awk -v s="$s" '$2 == s {print $3}')
    mm=$(echo "$mx" | awk -v s="$s" '$2 == s {print $4}')
    if [ -z "$p" ] || [ -z "$m1" ]; then
        echo "$s: missing figures (pointcalc '$p', maxima '$m1')"
        continue
    fi
    awk -v s="$s" -v p="$p" -v m1="$m1" -v mm="$mm" 'BEGIN {
        printf "%-22s %12.4f %12.4f %12.4f %11.1fx %9.1fx\n", s, p, m1, mm, mm / p, m1 / p }'
done
