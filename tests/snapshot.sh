#!/bin/sh
# tests/snapshot.sh PCBIN OUTDIR - every public output of every example and
# test scheme (text, LaTeX, JSON, --steps, --origin, emit-c and its header,
# eval as CSV and JSON, plot, and the errors), one file per scheme and
# output, with stderr and exit status.  For refactorings that must not
# change behaviour: snapshot before and after, then `diff -r` (issue 17).
set -u
bin=$1 out=$2
mkdir -p "$out"
run() { # name args...: stdout, stderr and status into $out/name
    n=$1; shift
    "$bin" "$@" >"$out/$n.out" 2>"$out/$n.err"
    echo "rc=$?" >>"$out/$n.err"
}
for f in examples/*.pcs tests/schemes/*.pcs tests/errors/*.pcs; do
    b=$(echo "$f" | tr '/' '_')
    run "$b.text" derive "$f"
    run "$b.latex" derive "$f" --format latex
    run "$b.json" derive "$f" --format json
    run "$b.steps" derive "$f" --steps
    run "$b.c" emit-c "$f" --header "$out/$b.h"
    # the names of the base points, params and consts, from the JSON
    args=$(python3 - "$out/$b.json.out" <<'PY'
import json, sys
try:
    d = json.load(open(sys.argv[1]))
except Exception:
    sys.exit(0)
a = []
for i, p in enumerate(d.get("points", [])):
    a += ["--at", "%s=%d,%d" % (p, i, i * i - 1)]
for i, c in enumerate(d.get("consts", [])):
    a += ["--set", "%s=%g" % (c, 0.25 + i)]
ev = []
pl = []
for i, p in enumerate(d.get("params", [])):
    ev += ["--param", p + "=-1,0,0.5,1,3"]
    pl += ["--param", p + ("=0:1:9" if i == 0 else "=0.5")]
print(" ".join(a + ev) + "|" + " ".join(a + pl))
PY
)
    [ -n "$args" ] || continue
    pargs=${args#*|} args=${args%%|*}
    run "$b.origin" derive "$f" --origin "$(python3 -c "import json,sys; print(json.load(open(sys.argv[1]))['points'][0])" "$out/$b.json.out" 2>/dev/null)"
    # shellcheck disable=SC2086
    run "$b.csv" eval "$f" $args
    # shellcheck disable=SC2086
    run "$b.evaljson" eval "$f" $args --format json
    # shellcheck disable=SC2086
    run "$b.svg" plot "$f" $pargs
done
