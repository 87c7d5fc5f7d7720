#!/usr/bin/env bash
# What a user sees, side by side (issue 24): pointcalc's derive alone,
# + text, + LaTeX, + JSON (in-process) and the whole `pointcalc derive`
# process (bench_derive's table, PC_BENCH_WHOLE_ONLY), beside SymPy
# (bench/sympy/bench_whole.py: the same derivations printed with str(), the
# median of 3 runs, one run from n = 24) where python3 has sympy.  SymPy
# at n = 48 takes about 30 s and n = 96 minutes: PC_BENCH_SYMPY_MAX=96
# includes them (default 24).  Maxima: bench/run_maxima.sh.
set -u
B=${1:-build}
PY=${PYTHON:-python3}
pc=$(PC_BENCH_WHOLE_ONLY=1 PC_BENCH_BIN=${PC_BENCH_BIN:-$B/pointcalc} \
    "$B/bench/bench_derive" examples) || exit 1
echo "$pc"
if ! $PY -c 'import sympy' 2>/dev/null; then
    echo "sympy: not installed for $PY (apt-get install python3-sympy); side-by-side skipped"
    exit 0
fi
max=${PC_BENCH_SYMPY_MAX:-24}
jobs="desargues_arc conic_five_points double_contact space_cubic"
for n in 4 8 12 24 48 96; do
    [ "$n" -le "$max" ] && jobs="$jobs interp:$n"
done
sy=$($PY bench/sympy/bench_whole.py $jobs) || exit 1
echo
echo "side by side: SymPy (derive + str, ms) against pointcalc's whole process (text)"
printf "%-20s %12s %12s %12s %10s\n" scheme "pointcalc" "SymPy" "[min..max]" "SymPy/pc"
for j in $jobs; do
    label=${j/interp:/interp n=}
    p=$(echo "$pc" | awk -v l="$label" 'substr($0, 1, 20) ~ "^"l" *$" {print $(NF-2)}')
    s=$(echo "$sy" | awk -v j="$j" '$1 == j {printf "%.1f %.1f %.1f", $2*1e3, $3*1e3, $4*1e3}')
    if [ -z "$p" ] || [ -z "$s" ]; then
        echo "$label: missing figures (pointcalc '$p', sympy '$s')"
        continue
    fi
    set -- $s
    awk -v l="$label" -v p="$p" -v s="$1" -v lo="$2" -v hi="$3" 'BEGIN {
        printf "%-20s %12.3f %12.1f %5.0f..%-6.0f %9.0fx\n", l, p, s, lo, hi, s / p }'
done
