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
# under valgrind (make valgrind, suites side by side) a multistart fit can
# take minutes: no time budget then (the default is 60 s)
NB=""
[ -n "${PC_VALGRIND:-}" ] && NB="--max-seconds 0"

check() { # NAME CONDITION-COMMAND...
    local name=$1
    shift
    if "$@"; then pass=$((pass + 1)); else fail=$((fail + 1)); echo "FAIL: $name"; fi
}

# the straight line, text written by hand
"$PC" natural $NB --from 0,0,0 --to 2,0,0 >"$tmp/line" 2>"$tmp/err"
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
    "$PC" natural $NB --from 0,0,$a --to 1,0,-$a --format json >"$tmp/arc.json"
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
    "$PC" natural $NB --from 0,0,0.2 --through 1,0.3 --through 2,0.1 --to 3,-0.2,-0.3 \
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
"$PC" natural $NB --from 0,0,0.3 --to 1,0.2,-0.4 --format json >"$tmp/n.json"
"$PC" natural $NB --from 0,0,0.3 --to 1,0.2,-0.4 --format json --method hooke-jeeves >"$tmp/h.json"
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
"$PC" natural $NB --from 0,0,0 --to 1,0,0.5 --from 0,0,0 --to 1,0,1 --format json >"$tmp/two.json"
check "two curves: curves[]" python3 -c "
import json
d = json.load(open('$tmp/two.json'))
assert len(d['curves']) == 2 and all(len(c['segments']) == 1 for c in d['curves'])
"

# the picture: an SVG with the curve, the points and the comb
"$PC" natural $NB --from 0,0,0.3 --through 1,0.4 --to 2,0,-0.3 --law cubic \
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
"$PC" natural $NB --from 0,0,0.3 --through 1,0.4 --to 2,0,-0.3 --law quadratic \
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
    "$PC" natural $NB "$@" >"$tmp/u.out" 2>"$tmp/u.err"
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
"$PC" natural $NB --from 0,0,0 --through 1,1 --through 2,-1 --through 3,1 --to 4,0,0 \
    --law cubic >"$tmp/f.out" 2>"$tmp/f.err"
check "no solution: exit 1" test $? -eq 1
check "no solution: nothing on stdout" test ! -s "$tmp/f.out"
check "no solution: says which" grep -q "^pointcalc: natural: curve 1, segment 2: no cubic segment reaches point 3 from the start values the joint gives" "$tmp/f.err"
# a start curvature against the turning: found by the multistart (a loop)
"$PC" natural $NB --from 0,0,-1.20838 --to 1,0,0.390253 --law cubic --k0 -0.792412 \
    --dk0 -0.520567 --format json >"$tmp/loop.json"
check "against the turning: solved" python3 -c "
import json
d = json.load(open('$tmp/loop.json'))
g = d['segments'][0]
assert g['k'][0] == -0.792412 and g['k'][1] == -0.520567 and d['error'] < 1e-12
"

# ---- natural curves in the scheme language (natx, naty) ----
# Euler's spiral against Fresnel's integrals (mpmath, 30 digits:
# sqrt(pi) C(s/sqrt(pi)), sqrt(pi) S(s/sqrt(pi)))
"$PC" eval examples/natural_clothoid.pcs --param s=1,2,3.5 --at O=0,0 --at E1=1,0 \
    --at E2=0,1 --output M --format json >"$tmp/nc.json" 2>"$tmp/nc.err"
check "clothoid scheme: exit 0" test $? -eq 0
check "clothoid scheme: Fresnel's integrals" python3 -c "
import json
want = {1: (0.97528768820034454498, 0.16371404737570058525),
        2: (1.3351936962943366222, 0.99762371132542129799),
        3.5: (0.82068657502446940966, 0.61224042940072453833)}
d = json.load(open('$tmp/nc.json'))
assert len(d['samples']) == 3
for s in d['samples']:
    x, y = s['values']['M']
    wx, wy = want[s['params']['s']]
    assert abs(x - wx) < 2e-15 and abs(y - wy) < 2e-15, (s, wx, wy)
"
# the fitted segment placed by a user function: it ends at the fit's target
# (1, 0) with the target's angle -0.3, and its apex is where the end
# tangents meet (the lines through the ends at those angles, by hand)
"$PC" eval examples/natural_g1_scheme.pcs --param s=0.5 --at O=0,0 --at E1=1,0 \
    --at E2=0,1 --output P1,T1,Q --format json >"$tmp/ng.json"
check "fitted segment in a scheme: end point, end angle, apex" python3 -c "
import json, math
v = json.load(open('$tmp/ng.json'))['samples'][0]['values']
x, y = v['P1']; tx, ty = v['T1']; qx, qy = v['Q']
assert abs(x - 1) < 1e-12 and abs(y) < 1e-12, (x, y)
assert abs(math.hypot(tx, ty) - 1) < 1e-15
assert abs(math.atan2(ty, tx) + 0.3) < 1e-12
# apex: q = t0 (cos .5, sin .5) = (1, 0) + t1 (cos -.3, sin -.3)
a, b = math.tan(0.5), math.tan(-0.3)
X = -b / (a - b)
assert abs(qx - X) < 1e-12 and abs(qy - a * X) < 1e-12, (qx, qy)
"
# the generated C of the scheme compiles with -pedantic -Werror and gives
# eval's digits (tests/unit/test_emit_c compares every example with the
# exact weights too)
"$PC" emit-c examples/natural_clothoid.pcs -o "$tmp/nc.c"
cat >"$tmp/nc_main.c" <<'EOF'
#include <stdio.h>
void natural_clothoid_M(double s, const double *O, const double *E1,
                        const double *E2, int dim, double *out);
int main(void)
{
    const double O[2] = {0, 0}, E1[2] = {1, 0}, E2[2] = {0, 1};
    double m[2];
    natural_clothoid_M(3.5, O, E1, E2, 2, m);
    printf("%.17g,%.17g\n", m[0], m[1]);
    return 0;
}
EOF
check "natx in C: compiles with -pedantic -Werror" $CC -std=c99 -Wall -Wextra -pedantic -Werror \
    -O2 -o "$tmp/nc" "$tmp/nc.c" "$tmp/nc_main.c" -lm
check "natx in C: eval's digits" test "$("$tmp/nc")" = "$("$PC" eval examples/natural_clothoid.pcs \
    --param s=3.5 --at O=0,0 --at E1=1,0 --at E2=0,1 --output M | tail -1 | cut -d, -f2-)"
# a phase beyond reach is a domain error per sample, not a silent NaN
printf 'point O, E1, E2\nparam s\nM = O + natx(s, 0, 1)*(E1 - O) + naty(s, 0, 1)*(E2 - O)\n' >"$tmp/big.pcs"
"$PC" eval "$tmp/big.pcs" --param s=100,1000 --at O=0,0 --at E1=1,0 --at E2=0,1 >"$tmp/big.out" 2>"$tmp/big.err"
check "natx beyond reach: exit 1" test $? -eq 1
check "natx beyond reach: status 4 said" grep -q "M at s=1000 is undefined: a function's argument is outside its domain (.*natx or naty of a phase turning more than 32768 radians)" "$tmp/big.err"
check "natx beyond reach: s=100 evaluated" grep -q "^100,0.876347106693" "$tmp/big.out"

# a fitted composite written as a scheme (--scheme): the committed example
# is what the command writes, and the scheme evaluates to the fit's own
# samples (the Chebyshev table) in the middle of each segment and at the ends
"$PC" natural $NB --from 0,0,0.8 --through 3,1,-0.2 --to 6,0,-0.6 --law quadratic \
    --scheme "$tmp/g2.pcs" --name natural_g2_scheme --samples 4 --format json >"$tmp/g2.json"
check "--scheme: the example is current" cmp "$tmp/g2.pcs" examples/natural_g2_scheme.pcs
python3 -c "
import json
d = json.load(open('$tmp/g2.json'))
a, pts = 0.0, []
for seg, rows in zip(d['segments'], d['samples']):
    for r in rows[1:-1]:
        pts.append((a + r[0], r[1], r[2]))
    a += seg['length']
pts.append((a, rows[-1][1], rows[-1][2]))
print(','.join('%.17g' % p[0] for p in pts))
open('$tmp/g2.want', 'w').write(repr(pts))
" >"$tmp/g2.s"
"$PC" eval examples/natural_g2_scheme.pcs --param s="$(cat "$tmp/g2.s")" --at O=0,0 --at E1=1,0 \
    --at E2=0,1 --format json >"$tmp/g2.eval"
check "--scheme: eval gives the fit's points" python3 -c "
import json
want = eval(open('$tmp/g2.want').read())
got = json.load(open('$tmp/g2.eval'))['samples']
assert len(got) == len(want) == 7
for (s, x, y), g in zip(want, got):
    gx, gy = g['values']['M']
    assert abs(gx - x) < 1e-12 and abs(gy - y) < 1e-12, (s, x, y, gx, gy)
"
"$PC" natural $NB --from 0,0,0 --to 1,1,0 --scheme "$tmp/x.pcs" --name 9x >"$tmp/o" 2>"$tmp/e"
check "--scheme: a bad --name is a usage error" test $? -eq 2 -a ! -s "$tmp/o" -a ! -e "$tmp/x.pcs"

# analyze reads the same curves numerically from their exact derivatives:
# the arc length is the param's range and the curvature is the law's
# (|k| at the ends, its zeros the inflections), an independent check of
# the kernel's derivatives and of the --scheme placement
"$PC" analyze examples/natural_clothoid.pcs --output M --at O=0,0 --at E1=1,0 --at E2=0,1 \
    --format json >"$tmp/an1.json"
check "analyze of the clothoid: k(s) = s, arc length 3.5" python3 -c "
import json
o = json.load(open('$tmp/an1.json'))['outputs'][0]
assert o['degree'] == 'transcendental'
a, b = o['curvature_ends']
assert abs(a) < 1e-9 and abs(b - 3.5) < 1e-9, (a, b)
assert abs(o['arc_length'] - 3.5) < 1e-12
"
"$PC" analyze examples/natural_g2_scheme.pcs --output M --at O=0,0 --at E1=1,0 --at E2=0,1 \
    --format json >"$tmp/an2.json"
"$PC" natural $NB --from 0,0,0.8 --through 3,1,-0.2 --to 6,0,-0.6 --law quadratic --format json >"$tmp/fit2.json"
check "analyze of the --scheme curve: the fit's laws, lengths and inflections" python3 -c "
import json, math
o = json.load(open('$tmp/an2.json'))['outputs'][0]
f = json.load(open('$tmp/fit2.json'))
segs = f['segments']
total = sum(g['length'] for g in segs)
assert abs(o['arc_length'] - total) < 1e-12, (o['arc_length'], total)
k = lambda g, s: sum(c * s ** j for j, c in enumerate(g['k']))
a, b = o['curvature_ends']
assert abs(a - abs(k(segs[0], 0))) < 1e-9 and abs(b - abs(k(segs[-1], segs[-1]['length']))) < 1e-9
# the zeros of each segment's law inside it, by bisection on the law
zeros, off = [], 0.0
for g in segs:
    n = 2000
    for i in range(n):
        s0, s1 = g['length'] * i / n, g['length'] * (i + 1) / n
        if k(g, s0) * k(g, s1) < 0:
            for _ in range(80):
                m = (s0 + s1) / 2
                if k(g, s0) * k(g, m) <= 0: s1 = m
                else: s0 = m
            zeros.append(off + s0)
    off += g['length']
got = o['inflections']
assert len(got) == len(zeros), (got, zeros)
assert all(abs(x - y) < 1e-9 for x, y in zip(got, zeros)), (got, zeros)
"

# what people read, written by hand: a law's trailing zero dropped, the
# circle folded (naty(2s, -1/2) = (1 - cos(-s))/(-1/2)), the LaTeX operator
printf 'point O, E1, E2\nparam s\nx = natx(s, 1, 2, 0)\ny = naty(2*s, -1/2)\noutput x, y\n' >"$tmp/gold.pcs"
cat >"$tmp/gold.want" <<'EOF'
x = natx(s, 1, 2)
y = -2*(1 - cos(s))
\[ x = \operatorname{natx}\left(s, 1, 2\right) \]
\[ y = -2 \left(1 - \cos s\right) \]
EOF
{ "$PC" derive "$tmp/gold.pcs"; "$PC" derive "$tmp/gold.pcs" --format latex; } >"$tmp/gold.out"
check "natx printed: text and LaTeX goldens" diff "$tmp/gold.want" "$tmp/gold.out"

echo "natural_test: $pass passed, $fail failed"
test $fail -eq 0
