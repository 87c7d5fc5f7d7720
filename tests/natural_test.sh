#!/usr/bin/env bash
# `pointcalc natural` (issue 21, docs/natural.md): the command line's
# contract, results against closed forms (a line, circular arcs), the G2/G3
# joints, the article's search against Newton, the picture and the C.
set -u
PC=${1:-build/pointcalc}
CC=${CC:-cc}
pass=0
fail=0
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

check() { # NAME CONDITION-COMMAND...
    local name=$1
    shift
    if "$@"; then pass=$((pass + 1)); else fail=$((fail + 1)); echo "FAIL: $name"; fi
}

# the straight line, text written by hand
"$PC" natural --from 0,0,0 --to 2,0,0 >"$tmp/line" 2>"$tmp/err"
check "line: exit 0" test $? -eq 0
cat >"$tmp/line.want" <<'EOF'
natural curve through 2 points, linear law (G1), Newton
segment 1: (0, 0) at 0 -> (2, 0) at 0
  k(s)   = 0
  phi(s) = 0
  S = 2
EOF
check "line: text" diff <(head -5 "$tmp/line") "$tmp/line.want"
check "line: quiet stderr" test ! -s "$tmp/err"

# a circular arc: chord 1 with angles a and -a is the arc of radius
# 1/(2 sin a), curvature -2 sin a, length 2 a R (the short arc)
for a in 0.3 1.2 2.5; do
    "$PC" natural --from 0,0,$a --to 1,0,-$a --format json >"$tmp/arc.json"
    check "arc $a: k and S in closed form" python3 -c "
import json, math
d = json.load(open('$tmp/arc.json'))
g = d['segments'][0]
a = $a
R = 1 / (2 * math.sin(a))
assert abs(g['k'][0] + 1 / R) < 1e-12, g
assert abs(g['k'][1]) < 1e-12, g
assert abs(g['length'] - 2 * a * R) < 1e-12, g
assert d['error'] < 1e-12
"
done

# a composite through points without inner angles: the chord rule gives
# the inner angles; G2 and G3 keep k (and k') at the joints, G1 does not
for law in linear quadratic cubic; do
    "$PC" natural --from 0,0,0.2 --through 1,0.3 --through 2,0.1 --to 3,-0.2,-0.3 \
        --law $law --format json --samples 4 >"$tmp/c.json"
    check "composite $law: joints" python3 -c "
import json, math
d = json.load(open('$tmp/c.json'))
law = '$law'
assert d['law'] == law and len(d['segments']) == 3 and len(d['joints']) == 2
p = d['points']
assert abs(p[1][2] - math.atan2(0.1 - 0, 2 - 0)) < 1e-15, p
assert abs(p[2][2] - math.atan2(-0.2 - 0.3, 3 - 1)) < 1e-15, p
deg = {'linear': 1, 'quadratic': 2, 'cubic': 3}[law]
for i, g in enumerate(d['segments']):
    assert len(g['k']) == (2 if i == 0 else deg + 1), g
for dphi, dk, ddk in d['joints']:
    assert abs(dphi) < 1e-13
    if law == 'linear': assert abs(dk) > 1e-3
    else: assert abs(dk) < 1e-12
    if law == 'cubic': assert abs(ddk) < 1e-12
# the samples: the first and the last of each segment are its points
for i, rows in enumerate(d['samples']):
    assert len(rows) == 5
    s0, x0, y0 = rows[0][:3]; s1, x1, y1 = rows[-1][:3]
    assert s0 == 0 and abs(s1 - d['segments'][i]['length']) < 1e-15
    assert abs(x0 - p[i][0]) < 1e-14 and abs(y0 - p[i][1]) < 1e-14
    assert abs(x1 - p[i+1][0]) < 1e-12 and abs(y1 - p[i+1][1]) < 1e-12
"
done

# the article's Hooke-Jeeves finds the same clothoid as Newton
"$PC" natural --from 0,0,0.3 --to 1,0.2,-0.4 --format json >"$tmp/n.json"
"$PC" natural --from 0,0,0.3 --to 1,0.2,-0.4 --format json --method hooke-jeeves >"$tmp/h.json"
check "hooke-jeeves: the same clothoid" python3 -c "
import json
n = json.load(open('$tmp/n.json')); h = json.load(open('$tmp/h.json'))
assert h['method'] == 'hooke-jeeves'
a, b = n['segments'][0], h['segments'][0]
assert abs(a['length'] - b['length']) < 1e-9
assert all(abs(x - y) < 1e-8 for x, y in zip(a['k'], b['k']))
assert h['integrals'] > 50 * n['integrals'], (h['integrals'], n['integrals'])
"

# two curves in one command: a later --from starts another
"$PC" natural --from 0,0,0 --to 1,0,0.5 --from 0,0,0 --to 1,0,1 --format json >"$tmp/two.json"
check "two curves: curves[]" python3 -c "
import json
d = json.load(open('$tmp/two.json'))
assert len(d['curves']) == 2 and all(len(c['segments']) == 1 for c in d['curves'])
"

# the picture: an SVG with the curve, the points and the comb
"$PC" natural --from 0,0,0.3 --through 1,0.4 --to 2,0,-0.3 --law cubic \
    --plot "$tmp/n.svg" --comb >/dev/null
check "plot: exit 0" test $? -eq 0
check "plot: SVG" python3 -c "
import xml.etree.ElementTree as E
r = E.parse('$tmp/n.svg').getroot()
ns = '{http://www.w3.org/2000/svg}'
cls = [e.get('class') for e in r.iter()]
assert cls.count('curve') == 1 and cls.count('point') == 3, cls
assert cls.count('tooth') == 2 * 61 and cls.count('comb') == 2
"

# the C: compiled, it gives the samples' points
"$PC" natural --from 0,0,0.3 --through 1,0.4 --to 2,0,-0.3 --law quadratic \
    --emit-c "$tmp/nc.c" --name curve --format json --samples 8 >"$tmp/nc.json"
check "emit-c: exit 0" test $? -eq 0
cat >"$tmp/main.c" <<'EOF'
#include <stdio.h>
#include <stdlib.h>
void curve(double s, double p[2]);
void curve_batch(const double *s, double *p, long n);
void curve_angle_curvature(double s, double a[2]);
int main(int argc, char **argv)
{
    for (int i = 1; i < argc; i++) {
        double p[2], q[2], a[2], s = strtod(argv[i], NULL);
        curve(s, p);
        curve_batch(&s, q, 1);
        curve_angle_curvature(s, a);
        printf("%.17g %.17g %d %.17g %.17g\n", p[0], p[1],
               p[0] == q[0] && p[1] == q[1], a[0], a[1]);
    }
    return 0;
}
EOF
check "emit-c: compiles with -Wall -Werror" \
    $CC -std=c99 -Wall -Wextra -Werror -O2 -o "$tmp/nc" "$tmp/main.c" "$tmp/nc.c" -lm
check "emit-c: the points of the samples" python3 -c "
import json, subprocess
d = json.load(open('$tmp/nc.json'))
start, args, want = 0.0, [], []
for g, rows in zip(d['segments'], d['samples']):
    for r in rows[:-1] if g is not d['segments'][-1] else rows:
        args.append(repr(start + r[0])); want.append((r[1], r[2], r[3], r[4]))
    start += g['length']
out = subprocess.run(['$tmp/nc'] + args, capture_output=True, text=True).stdout.split('\n')
assert len(out) == len(want) + 1
for line, (x, y, phi, k) in zip(out, want):
    px, py, same, pphi, pk = line.split()
    assert same == '1'
    assert abs(float(px) - x) < 1e-13 and abs(float(py) - y) < 1e-13, (line, x, y)
    assert abs(float(pphi) - phi) < 1e-13 and abs(float(pk) - k) < 1e-12, (line, phi, k)
"

# usage errors: exit 2, the message, nothing on stdout
usage() { # NAME EXPECTED-MESSAGE ARGS...
    local name=$1 want=$2
    shift 2
    "$PC" natural "$@" >"$tmp/u.out" 2>"$tmp/u.err"
    local rc=$?
    check "$name: exit 2" test $rc -eq 2
    check "$name: nothing on stdout" test ! -s "$tmp/u.out"
    check "$name: message" grep -qF "pointcalc: $want" "$tmp/u.err"
}
usage "no curve" "no curve: give --from X,Y,PHI and --to X,Y,PHI"
usage "no --to" "the last curve has no --to" --from 0,0,0 --through 1,1
usage "bad point" "bad value '0,0' for --from (expected X,Y,PHI)" --from 0,0 --to 1,0,0
usage "bad through" "bad value '1,x' for --through (expected X,Y or X,Y,PHI)" \
    --from 0,0,0 --through 1,x --to 1,0,0
usage "through first" "--through before --from" --through 1,1 --to 1,0,0
usage "coincident" "points 1 and 2 of curve 1 coincide: a segment needs two distinct points" \
    --from 1,1,0 --to 1,1,1
usage "k0 linear" "--k0 and --dk0 fix the start of a quadratic or cubic law" \
    --from 0,0,0 --to 1,0,0 --k0 1
usage "dk0 quadratic" "--dk0 needs --law cubic" --from 0,0,0 --to 1,0,0 --law quadratic --dk0 1
usage "hj cubic" "--method hooke-jeeves is the article's search for the linear law only" \
    --from 0,0,0 --to 1,0,0 --law cubic --method hooke-jeeves
usage "bad law" "unknown law 'spline'; expected linear, quadratic or cubic" \
    --from 0,0,0 --to 1,0,0 --law spline
usage "scale" "point 1 of curve 1: coordinates up to 1e100 and points at least 1e-100 apart" \
    --from 0,0,0.3 --to 1e-300,0,0.5
usage "huge" "point 2 of curve 1: coordinates up to 1e100" --from 0,0,0 --to 1e300,0,0
usage "a FILE" "natural takes no FILE, found 'x.pcs'" x.pcs
usage "emit two" "--emit-c writes one curve; this command line has 2" \
    --from 0,0,0 --to 1,0,0 --from 0,0,0 --to 2,0,0 --emit-c "$tmp/x.c"

# a fit that fails: exit 1, the segment named, nothing on stdout (a
# zigzag: the cubic law from the G3 joint at (1, 1) cannot reach (2, -1))
"$PC" natural --from 0,0,0 --through 1,1 --through 2,-1 --through 3,1 --to 4,0,0 \
    --law cubic >"$tmp/f.out" 2>"$tmp/f.err"
check "no solution: exit 1" test $? -eq 1
check "no solution: nothing on stdout" test ! -s "$tmp/f.out"
check "no solution: says which" grep -q "^pointcalc: natural: curve 1, segment 2: no cubic segment reaches point 3 from the start values the joint gives" "$tmp/f.err"
# a start curvature against the turning: found by the multistart (a loop)
"$PC" natural --from 0,0,-1.20838 --to 1,0,0.390253 --law cubic --k0 -0.792412 \
    --dk0 -0.520567 --format json >"$tmp/loop.json"
check "against the turning: solved" python3 -c "
import json
d = json.load(open('$tmp/loop.json'))
g = d['segments'][0]
assert g['k'][0] == -0.792412 and g['k'][1] == -0.520567 and d['error'] < 1e-12
"

echo "natural_test: $pass passed, $fail failed"
test $fail -eq 0
