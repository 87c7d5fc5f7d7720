#!/bin/sh
# make-figures.sh - the figures of docs/plot.md (`make figures`; checked by
# tests/plot_test.sh).
#   docs/figures/make-figures.sh [POINTCALC [DIR]]
set -e
PC=${1:-build/pointcalc}
DIR=${2:-docs/figures}
mkdir -p "$DIR"

# Monograph 3.7, the Desargues contour arc: the construction at t = 0.3
"$PC" plot examples/desargues_arc.pcs \
    --at A=0,0 --at B=4,0 --at C=1,3 --at D=5,3 \
    --output M --at-param t=0.3 --aux P,Q,K,N,J,T,S \
    --tangents 0,1 --size 720 -o "$DIR/desargues_arc.svg"

# Monograph 2.1.6, a conic arc by the engineering discriminant k = 0.7 (an
# ellipse): the points of figure 2.21 at u = 0.3
"$PC" plot examples/conic_engineering_discriminant.pcs \
    --at A=0,0 --at B=6,0 --at C=2,4 --set k=0.7 \
    --output M --at-param u=0.3 --aux T1,K,T,P,Q,N \
    --size 720 -o "$DIR/conic_engineering_discriminant.svg"

# The natural-parametrization article (docs/natural.md): figures 3 and 4
# (clothoid families), a composite G1 curve (figures 5-8) and the G2 / G3
# two-segment curves of sections 3-4 with their curvature combs
for f in natural_fig3 natural_fig4 natural_composite natural_g2 natural_g3; do
    PC="$PC" sh "examples/$f.sh" "$DIR" >/dev/null
done

# Monograph 5.2: Runge's function and the 6-node optimal curve (docs/fit.md)
"$PC" fit --target '1/(1 + 25*x^2)' --on -1,1 --nodes 6 \
    --plot "$DIR/fit_runge6.svg" >/dev/null
