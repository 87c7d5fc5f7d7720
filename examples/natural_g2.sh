#!/bin/sh
# The natural-parametrization article, section 3 and figures 9-10: a curve
# of two segments, T1T2 with the linear law and T2T3 with the quadratic law
# k = as^2 + bs + c whose c is the first segment's end curvature (G2: the
# curvature is continuous at T2, its derivative jumps - figure 10's curve
# 3); every point has its angle.  --samples prints phi, k and k' along the
# arc (the graphs of figure 10).  With a directory argument, also the
# picture natural_g2.svg there.
PC=${PC:-build/pointcalc}
exec "$PC" natural --from 0,0,0.8 --through 3,1,-0.2 --to 6,0,-0.6 \
    --law quadratic ${1:+--plot "$1/natural_g2.svg" --comb}
