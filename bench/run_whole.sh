#!/usr/bin/env bash
# What a user sees, side by side (issue 24): pointcalc's derive alone,
# + text, + LaTeX, + JSON (in-process) and the whole `pointcalc derive`
# process (bench_derive's table, PC_BENCH_WHOLE_ONLY), beside SymPy
# (bench/sympy/bench_whole.py: the same derivations printed with str(), the
# median of 3 runs, one run from n = 24) where python3 has sympy.  SymPy
# at n = 48 takes about 30 s and n = 96 minutes: PC_BENCH_SYMPY_MAX=96
# includes them (default 24).  And Maxima where it is installed
# (bench/maxima/bench_whole.mac: derive + string(), for the Desargues arc,
# the five-point conic and the interpolation curve).
set -u
B=${1:-build}
PY=${PYTHON:-python3}
pc=$(PC_BENCH_WHOLE_ONLY=1 PC_BENCH_BIN=${PC_BENCH_BIN:-$B/pointcalc} \
    "$B/bench/bench_derive" examples) || exit 1
echo "$pc"
max=${PC_BENCH_SYMPY_MAX:-24}
jobs="desargues_arc conic_five_points double_contact space_cubic"
for n in 4 8 12 24 48 96; do
    [ "$n" -le "$max" ] && jobs="$jobs interp:$n"
done
sy=""
if $PY -c 'import sympy' 2>/dev/null; then
    sy=$($PY bench/sympy/bench_whole.py $jobs) || exit 1
else
    echo "sympy: not installed for $PY (apt-get install python3-sympy); its column is empty"
fi
# Maxima (bench/maxima/bench_whole.mac): the Desargues arc, the five-point
# conic and the interpolation curve; n = 48 takes about 12 s
mx=""
if command -v maxima > /dev/null 2>&1; then
    mj=$(for j in $jobs; do
        case $j in desargues_arc | conic_five_points | interp:*) printf '"%s", ' "$j" ;; esac
    done)
    mx=$(maxima --very-quiet --batch-string="jobs: [${mj%, }]\$ batchload(\"bench/maxima/bench_whole.mac\")\$" 2>&1 |
        grep -E '^(desargues_arc|conic_five_points|interp:[0-9]+) ')
    [ -n "$mx" ] || echo "maxima: bench/maxima/bench_whole.mac failed (is maxima-share installed?)"
else
    echo "maxima: not installed (apt-get install maxima maxima-share); its column is empty"
fi
echo
echo "side by side: derive + print (text; ms) - pointcalc's whole process (CPU), SymPy (str) and Maxima (string), medians"
printf "%-20s %12s %12s %13s %10s %12s %10s\n" scheme "pointcalc" "SymPy" "[min..max]" "SymPy/pc" "Maxima" "Maxima/pc"
for j in $jobs; do
    label=${j/interp:/interp n=}
    p=$(echo "$pc" | awk -v l="$label" 'substr($0, 1, 20) ~ "^"l" *$" {print $(NF-2)}')
    s=$(echo "$sy" | awk -v j="$j" '$1 == j {printf "%.1f %.1f %.1f", $2*1e3, $3*1e3, $4*1e3}')
    m=$(echo "$mx" | awk -v j="$j" '$1 == j {printf "%.1f", $2*1e3}')
    if [ -z "$p" ]; then
        echo "$label: no pointcalc figure"
        continue
    fi
    set -- ${s:-- - -}
    awk -v l="$label" -v p="$p" -v s="$1" -v lo="$2" -v hi="$3" -v m="${m:--}" 'BEGIN {
        sr = s == "-" ? "-" : sprintf("%.0fx", s / p)
        mr = m == "-" ? "-" : sprintf("%.0fx", m / p)
        printf "%-20s %12.3f %12s %6s..%-6s %10s %12s %10s\n", l, p, s, lo, hi, sr, m, mr }'
done
