#!/bin/bash
# budget_overshoot.sh [POINTCALC] - how far past its budget each phase of
# the command line stops (issue 23): for each phase a reproducer that
# spends its budget there, run under a --max-seconds and a --max-memory
# budget; prints the exit status, the phase the message names, the wall
# clock (with start-up) and the peak RSS (GNU time).  Then, when it is
# built (make bench), bench_overshoot's table of the library's phases.
# Run it on an idle core (taskset) for numbers that mean something.
PC=${1:-build/pointcalc}
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
# the reproducers
python3 - "$T" <<'PY'
import random, sys
T = sys.argv[1]
def w(name, text):
    open(f"{T}/{name}", "w").write(text)
random.seed(2)
w("garbage.pcs", "".join(random.choice("@!$%&?~") for _ in range(100000)) + "\n")
# lexing and parsing: 12 MB of one long sum
w("longsum.pcs", "param t\nx = " + " + ".join(["t"] * 3000000) + "\n")
w("manydefs.pcs", "param t\n" + "".join(f"x{i} = t + {i}\n" for i in range(400000)))
w("sum3m.pcs", "param t\nx = sum(t for i in 1..3000000)\n")
s = "param u, v\nconst k, h\npoint A, B, C\nX0 = (A + 2*B + 4*C)/7\n"
for i in range(1, 6):
    s += f"X{i} = meet(line(A, along(X{i-1}, B, u + k)), line(B, along(X{i-1}, C, v + h)))\n"
w("chain.pcs", s)
s = "param t\nc0 = t\n" + "".join(f"c{i} = sin(c{i-1}) + cos({i}*c{i-1})\n" for i in range(1, 31))
w("tower.pcs", s)
w("diff30.pcs", "param t, u\nconst k\nx = diff(1/((t+u+1)^3+k*t+1), t, 30)\n")
s = "param t, u\n" + "".join(f"s{i} = (t^9 + u^7 + t^2*u^3 + t*u + {i})*(t^7*u^4 + u^9 + t^3*u + t + {2*i+1})\n" for i in range(1, 601))
s += "output " + ", ".join(f"s{i}" for i in range(1, 601)) + "\n"
w("slowprint.pcs", s)
s = "point A, B\nparam t\n" + "".join(f"M{i} = along(A, B, (t + {i})^{i % 7 + 40} + t^3)\n" for i in range(1, 301))
s += "output " + ", ".join(f"M{i}" for i in range(1, 301)) + "\n"
w("slowlower.pcs", s)
s = "point A, B, C\nparam t in [0, 1]\n" + "".join(f"M{i} = along(along(A, B, t^{11 + i % 3} + {i}*t - 1), C, (t^{9 + i % 2} + 3*t + {i})/(t^2 + {i}))\n" for i in range(1, 61))
s += "output " + ", ".join(f"M{i}" for i in range(1, 61)) + "\n"
w("slowanalyze.pcs", s)
PY
run() { # LABEL CMD...: one row
    local label=$1
    shift
    /usr/bin/time -o "$T/time" -f '%e %M' "$@" >"$T/out" 2>"$T/err"
    local rc=$? out
    out=$(wc -c <"$T/out")
    read -r secs kib < <(tail -1 "$T/time")
    local why
    why=$(grep -o 'ran out while [a-z ]*' "$T/err" | head -1)
    [ -n "$why" ] || why=$(grep -o 'error: .*' "$T/err" | head -1 | cut -c1-50)
    printf '| %s | %s | exit %s, stdout %s B | %s s | %s MiB | %s |\n' \
        "$label" "$(echo "$*" | sed "s|$T/||g; s|$PC|pointcalc|")" "$rc" \
        "$out" "$secs" "$((kib / 1024))" "${why:-ok}"
}
echo "| phase | command | result | wall | peak RSS | message |"
echo "|---|---|---|---|---|---|"
run "lexing, time" "$PC" derive "$T/longsum.pcs" --max-seconds 1
run "lexing, memory" "$PC" derive "$T/longsum.pcs" --max-memory 64M
run "checking, time" "$PC" derive "$T/manydefs.pcs" --max-seconds 1
run "checking, memory" "$PC" derive "$T/manydefs.pcs" --max-memory 64M
run "garbage line" "$PC" derive "$T/garbage.pcs" --max-memory 64M
run "expanding, time" "$PC" derive "$T/sum3m.pcs" --max-seconds 1
run "expanding, memory" "$PC" derive "$T/sum3m.pcs" --max-memory 64M
run "deriving, time" "$PC" derive "$T/chain.pcs" --max-seconds 1
run "deriving, memory" "$PC" derive "$T/chain.pcs" --max-memory 64M
run "tower, memory" "$PC" derive "$T/tower.pcs" --max-memory 64M --max-seconds 60
run "tower, emit-c, memory" "$PC" emit-c "$T/tower.pcs" --max-memory 64M --max-seconds 60
run "printing, time" "$PC" derive "$T/slowprint.pcs" --max-seconds 1
run "printing, memory" "$PC" derive "$T/diff30.pcs" --max-memory 32M
run "diff30, memory" "$PC" derive "$T/diff30.pcs" --max-memory 64M
run "diff30, emit-c, memory" "$PC" emit-c "$T/diff30.pcs" --max-memory 64M
run "lowering, time" "$PC" emit-c "$T/slowlower.pcs" --max-seconds 1
run "lowering, memory" "$PC" emit-c "$T/slowlower.pcs" --max-memory 16M
run "writing C, time" "$PC" emit-c "$T/diff30.pcs" --max-seconds 1.5
run "writing C, memory" "$PC" emit-c "$T/diff30.pcs" --max-memory 24M
run "analysing, time" "$PC" analyze "$T/slowanalyze.pcs" --max-seconds 1
# the library's phases (no timer: the clock read between steps)
LIB=$(dirname "$PC")/bench/bench_overshoot
if [ -x "$LIB" ]; then
    echo
    "$LIB"
fi
