#!/bin/sh
# plot_test.sh - `pointcalc plot` end to end: the SVG's structure, its curve
# against eval, poles cut, 3D views, the usage errors, the figures of
# docs/figures/ up to date, and - where rsvg-convert is installed - that the
# SVG renders with pixels on the curve.
#   tests/plot_test.sh build/pointcalc
set -u
PC=${1:-build/pointcalc}
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
fail=0
ok() { echo "ok: $1"; }
bad() { echo "FAIL: $1"; fail=1; }

PY=
for p in python3 /usr/bin/python3; do
    if command -v "$p" >/dev/null 2>&1 && "$p" -c 'import xml.dom.minidom' 2>/dev/null; then
        PY=$p
        break
    fi
done

# well-formed XML (python's parser, else a rough check of the outline)
wellformed() {
    if [ -n "$PY" ]; then
        "$PY" -c 'import sys, xml.dom.minidom; xml.dom.minidom.parse(sys.argv[1])' "$1"
    else
        head -c 100 "$1" | grep -q '^<?xml' && tail -n 1 "$1" | grep -qx '</svg>'
    fi
}

DES="--at A=0,0 --at B=4,0 --at C=1,3 --at D=5,3"

# ---- the Desargues arc: structure ----------------------------------------
"$PC" plot examples/desargues_arc.pcs $DES --output M -o "$T/d.svg" >"$T/out" 2>"$T/err"
rc=$?
if [ $rc -eq 0 ] && [ ! -s "$T/out" ] && [ ! -s "$T/err" ] && wellformed "$T/d.svg"; then
    ok "desargues: exit 0, nothing on stdout/stderr, well-formed"
else
    bad "desargues: rc=$rc $(cat "$T/err")"
fi
for want in '<svg xmlns="http://www.w3.org/2000/svg"' 'id="curve-M"' '>A</text>' '>D</text>' '<title>'; do
    grep -qF "$want" "$T/d.svg" || bad "desargues: no $want"
done
size=$(wc -c <"$T/d.svg")
[ "$size" -lt 8000 ] && ok "desargues: small ($size bytes)" || bad "desargues: $size bytes"

# stdout when -o is absent: the same document
"$PC" plot examples/desargues_arc.pcs $DES --output M >"$T/d2.svg" 2>"$T/err"
cmp -s "$T/d.svg" "$T/d2.svg" && ok "stdout = -o file" || bad "stdout differs from -o"

# ---- the path against eval --------------------------------------------------
# every vertex of the curve lies on the polyline of a dense eval (to far
# below a pixel), and the path runs from A to D
"$PC" eval examples/desargues_arc.pcs $DES --output M --param t=0:1:20001 >"$T/eval.csv"
if [ -n "$PY" ]; then
    if "$PY" - "$T/d.svg" "$T/eval.csv" <<'EOF'
import re, sys, math
svg = open(sys.argv[1]).read()
d = re.search(r'id="curve-M"[^>]* d="([^"]*)"', svg).group(1)
nums = [float(x) for x in re.findall(r'-?[0-9.]+(?:e[-+]?[0-9]+)?', d)]
pts = list(zip(nums[0::2], nums[1::2]))
rows = [list(map(float, l.split(','))) for l in open(sys.argv[2]).read().split('\n')[1:] if l]
ev = [(r[1], r[2]) for r in rows]
def dseg(p, a, b):
    dx, dy = b[0] - a[0], b[1] - a[1]
    l2 = dx * dx + dy * dy
    s = 0 if l2 == 0 else max(0, min(1, ((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / l2))
    return math.hypot(p[0] - a[0] - s * dx, p[1] - a[1] - s * dy)
worst = 0
j = 0
for p in pts:
    # the eval samples near p (the path runs forward in t)
    best = min(dseg(p, ev[i], ev[i + 1]) for i in range(max(0, j - 50), len(ev) - 1))
    worst = max(worst, best)
    j = min(range(len(ev)), key=lambda i: math.hypot(ev[i][0] - p[0], ev[i][1] - p[1]))
assert len(pts) > 10, len(pts)
assert worst < 1e-4, worst
assert abs(pts[0][0]) < 1e-9 and abs(pts[0][1]) < 1e-9, pts[0]
assert abs(pts[-1][0] - 5) < 1e-9 and abs(pts[-1][1] - 3) < 1e-9, pts[-1]
assert d.count('M') == 1
EOF
    then ok "path on eval's curve, A to D, one subpath"; else bad "path against eval"; fi
else
    echo "skip: path against eval (no python3)"
fi

# ---- the construction ---------------------------------------------------------
"$PC" plot examples/desargues_arc.pcs $DES --output M --at-param t=0.3 \
    --aux P,Q,K,N,J,T,S --tangents 0,0.3,1 --comb -o "$T/c.svg" 2>"$T/err"
rc=$?
[ $rc -eq 0 ] && wellformed "$T/c.svg" && ok "construction: well-formed" || bad "construction: rc=$rc $(cat "$T/err")"
for n in P Q K N J T S M; do
    grep -qF ">$n</text>" "$T/c.svg" || bad "construction: no label $n"
done
grep -qF '>R</text>' "$T/c.svg" && bad "construction: R drawn although --aux leaves it out"
for cls in lines tangents comb; do
    grep -qF "class=\"$cls\"" "$T/c.svg" || bad "construction: no $cls"
done

# ---- a pole is cut --------------------------------------------------------------
printf 'point A, B, C\nparam t in [-1, 1]\nM = (B - A)*t + A + (C - A)*(1/(3*t - 1))\n' >"$T/pole.pcs"
"$PC" plot "$T/pole.pcs" --at A=0,0 --at B=1,0 --at C=0,1 --window -1.5,-10,1.5,10 -o "$T/p.svg" 2>"$T/err"
rc=$?
moves=$(sed -n 's/.*id="curve-M"[^>]* d="\([^"]*\)".*/\1/p' "$T/p.svg" | tr -cd 'M' | wc -c)
[ $rc -eq 0 ] && [ "$moves" -eq 2 ] && ok "pole: two subpaths" || bad "pole: rc=$rc, $moves subpaths"

# ---- 3D views -------------------------------------------------------------------
for v in xy xz yz iso 30,20; do
    "$PC" plot examples/desargues_arc.pcs --at A=0,0,0 --at B=1,0,0 --at C=0,1,0 \
        --at D=0,0,1 --output M --view "$v" -o "$T/v.svg" 2>"$T/err" && wellformed "$T/v.svg" \
        || bad "3D view $v: $(cat "$T/err")"
done
ok "3D views"

# ---- usage errors: exit 2, a message, nothing written ------------------------------
usage() { # expected-message-part args...
    want=$1
    shift
    rm -f "$T/u.svg"
    "$PC" plot "$@" -o "$T/u.svg" >"$T/out" 2>"$T/err"
    rc=$?
    if [ $rc -eq 2 ] && [ ! -s "$T/out" ] && [ ! -e "$T/u.svg" ] && grep -qF -- "$want" "$T/err"; then
        ok "usage: $want"
    else
        bad "usage '$want': rc=$rc, stderr: $(head -n 1 "$T/err")"
    fi
}
usage "--output 'X' is not an output of the scheme" examples/desargues_arc.pcs $DES --output X
usage "--output 'dM' is a vector" examples/desargues_arc.pcs $DES --output dM
usage "missing --at D=x,y,...: output M depends on base point D" \
    examples/desargues_arc.pcs --at A=0,0 --at B=4,0 --at C=1,3 --output M
usage "--at-param t=abc: malformed number" examples/desargues_arc.pcs $DES --at-param t=abc
usage "--at-param s: expected the swept param t" examples/desargues_arc.pcs $DES --at-param s=0.3
usage "--at-param expects PARAM=VALUE" examples/desargues_arc.pcs $DES --at-param 0.3
usage "--aux 'Z' is not a point definition" examples/desargues_arc.pcs $DES --at-param t=0.3 --aux Z
usage "--view 'top'" examples/desargues_arc.pcs $DES --view top
usage "--param t=1:0: the range must have LO < HI" examples/desargues_arc.pcs $DES --param t=1:0
usage "--window" examples/desargues_arc.pcs $DES --window 1,2,3
usage "--max-samples" examples/desargues_arc.pcs $DES --max-samples 0
usage "unknown or incomplete option '--bogus'" examples/desargues_arc.pcs $DES --bogus
usage "plot needs a scheme FILE" $DES
printf 'point A, B\nparam t\nM = along(A, B, t)\n' >"$T/norange.pcs"
usage "missing --param t=LO:HI: the scheme declares no range for t" "$T/norange.pcs" --at A=0,0 --at B=1,1
usage "params du, dv, t have no value" examples/contour_arc_general.pcs \
    --at A1=0,0 --at A2=4,0 --at A3=1,3 --param u=0.3 --param v=0.5
usage "--param u=0.3:0.5: only one param is swept (t is already a range)" \
    examples/contour_arc_general.pcs --at A1=0,0 --at A2=4,0 --at A3=1,3 \
    --param t=0:1 --param u=0.3:0.5 --param v=0.5 --param du=0 --param dv=0
usage "missing --set k=VALUE" examples/conic_engineering_discriminant.pcs --at A=0,0 --at B=6,0 --at C=2,4

# a scheme error: exit 1, nothing written
printf 'point A\nM = along(A, Z, t)\n' >"$T/bad.pcs"
"$PC" plot "$T/bad.pcs" --at A=0 -o "$T/u.svg" >"$T/out" 2>"$T/err"
rc=$?
[ $rc -eq 1 ] && [ ! -e "$T/u.svg" ] && grep -q 'error:' "$T/err" && ok "scheme error: exit 1" || bad "scheme error: rc=$rc"

# ---- the figures of docs/figures/ are up to date ------------------------------------
if sh docs/figures/make-figures.sh "$PC" "$T/fig" >"$T/err" 2>&1; then
    for f in docs/figures/*.svg; do
        n=$(basename "$f")
        if wellformed "$f" && cmp -s "$f" "$T/fig/$n"; then
            ok "figure $n up to date"
        else
            bad "figure $n differs from what docs/figures/make-figures.sh makes (make figures)"
        fi
    done
else
    bad "docs/figures/make-figures.sh: $(cat "$T/err")"
fi

# ---- rendering: pixels on the curve --------------------------------------------------
if command -v rsvg-convert >/dev/null 2>&1 && [ -n "$PY" ]; then
    if rsvg-convert "$T/d.svg" -o "$T/d.png" && "$PY" - "$T/d.svg" "$T/d.png" <<'EOF'
import re, sys, zlib, struct
svg = open(sys.argv[1]).read()
png = open(sys.argv[2], 'rb').read()
assert png[:8] == b'\x89PNG\r\n\x1a\n'
pos, idat = 8, b''
while pos < len(png):
    n, kind = struct.unpack('>I4s', png[pos:pos + 8])
    data = png[pos + 8:pos + 8 + n]
    if kind == b'IHDR':
        w, h, depth, ctype = struct.unpack('>IIBB', data[:10])
    elif kind == b'IDAT':
        idat += data
    pos += 12 + n
assert depth == 8 and ctype in (2, 6), (depth, ctype)
bpp = 4 if ctype == 6 else 3
raw = zlib.decompress(idat)
stride = w * bpp
rows, prev, i = [], bytearray(stride), 0
for y in range(h):
    f = raw[i]; line = bytearray(raw[i + 1:i + 1 + stride]); i += 1 + stride
    for x in range(stride):
        a = line[x - bpp] if x >= bpp else 0
        b = prev[x]; c = prev[x - bpp] if x >= bpp else 0
        if f == 1: line[x] = (line[x] + a) & 255
        elif f == 2: line[x] = (line[x] + b) & 255
        elif f == 3: line[x] = (line[x] + (a + b) // 2) & 255
        elif f == 4:
            p = a + b - c; pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
            line[x] = (line[x] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
    rows.append(line); prev = line
def px(x, y):
    r = rows[y]; return tuple(r[x * bpp:x * bpp + 3])
m = re.search(r'transform="matrix\(([^ ]+) 0 0 ([^ ]+) ([^ ]+) ([^ )]+)\)"', svg)
s, ms, tx, ty = map(float, m.groups())
d = re.search(r'id="curve-M"[^>]* d="([^"]*)"', svg).group(1)
nums = [float(x) for x in re.findall(r'-?[0-9.]+(?:e[-+]?[0-9]+)?', d)]
pts = list(zip(nums[0::2], nums[1::2]))
def reddish(c): return c[0] > 150 and c[1] < 120 and c[2] < 120
hits = 0
for (x, y) in pts:
    X, Y = int(round(tx + s * x)), int(round(ty + ms * y))
    near = [px(X + dx, Y + dy) for dx in (-1, 0, 1) for dy in (-1, 0, 1)
            if 0 <= X + dx < w and 0 <= Y + dy < h]
    hits += any(reddish(c) for c in near)
assert hits >= 0.9 * len(pts), (hits, len(pts))
# and the background is white away from the curve: the bottom-right corner
assert px(w - 3, h - 3) == (255, 255, 255), px(w - 3, h - 3)
EOF
    then ok "rendered with rsvg-convert: the curve's pixels are drawn"; else bad "render check"; fi
else
    echo "skip: render check (rsvg-convert or python3 not installed; apt-get install librsvg2-bin)"
fi

# ---- fit --plot (issue 20): f, the curve and its nodes --------------------
if "$PC" fit --target '1/(1 + 25*x^2)' --on -1,1 --nodes 6 --format json \
    --plot "$T/fit.svg" >"$T/fit.json" 2>"$T/err" && wellformed "$T/fit.svg" &&
    [ -n "$PY" ] && "$PY" - "$T/fit.svg" "$T/fit.json" <<'EOF'
import json, re, sys, xml.dom.minidom as X
doc = X.parse(sys.argv[1]); fit = json.load(open(sys.argv[2]))
lines = {l.getAttribute('class'): l.getAttribute('points') for l in doc.getElementsByTagName('polyline')}
circ = [(float(c.getAttribute('cx')), float(c.getAttribute('cy'))) for c in doc.getElementsByTagName('circle')]
assert sorted(lines) == ['curve', 'target'], lines.keys()
pts = lambda s: [tuple(map(float, p.split(','))) for p in s.split()]
tg, cv = pts(lines['target']), pts(lines['curve'])
assert len(tg) == 601 and len(cv) == 401 and len(circ) == 6
# pixels per unit and the origin from the target's ends (x = -1 and 1, f = 1/26)
k = (tg[-1][0] - tg[0][0]) / 2
x0, y0 = tg[0][0] + k, tg[0][1] + k / 26
# every node at its abscissa and on f; the curve from the first node to the last
for (cx, cy), xn in zip(circ, fit['nodes']):
    assert abs(cx - (x0 + k * xn)) < 0.02, (cx, xn)
    assert abs(cy - (y0 - k / (1 + 25 * xn * xn))) < 0.02, (cy, xn)
assert max(abs(cv[0][0] - circ[0][0]), abs(cv[-1][1] - circ[-1][1])) < 0.02
# the curve lies within its max error (JSON) of f: 0.02 of a unit is > 5 px
for (px, py) in cv:
    x = (px - x0) / k
    assert abs((y0 - py) / k - 1 / (1 + 25 * x * x)) < fit['max_error'] + 0.02, (px, py)
EOF
then ok "fit --plot: f, the curve and the nodes where the JSON says"; else bad "fit --plot: $(cat "$T/err")"; fi
printf 'point A, B, C\nparam t in [0, 1]\nX = A*(1-t)*(1-2*t) + 4*B*t*(1-t) + C*t*(2*t-1)\nparam x\nf = x^2\ng = 1 - x^2\nfit X to f on [0, 1]\nfit X to g on [-1, 1]\n' >"$T/two.pcs"
if "$PC" fit "$T/two.pcs" --plot "$T/two.svg" >/dev/null 2>"$T/err" &&
    wellformed "$T/two.svg" && wellformed "$T/two-2.svg"; then
    ok "fit --plot: a scheme's second fit goes to FILE-2.svg"
else
    bad "fit --plot, two fits: $(cat "$T/err")"
fi
"$PC" fit --target 'x^2' --on 0,1 --nodes 3 --plot "$T/no/such/dir.svg" >"$T/out" 2>"$T/err"
rc=$?
[ $rc -eq 1 ] && [ ! -s "$T/out" ] && grep -q 'dir.svg' "$T/err" && ok "fit --plot: an unwritable picture is exit 1, nothing on stdout" || bad "fit --plot unwritable: rc=$rc"

[ $fail -eq 0 ] && echo "plot_test: all ok" || echo "plot_test: FAILED"
exit $fail
