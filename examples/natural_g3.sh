#!/bin/sh
# The natural-parametrization article, section 4 and figure 11: the same
# points as natural_g2.sh, the second segment with the cubic law k = as^3 +
# bs^2 + cs + d, d the end curvature and c the end curvature's derivative of
# the first (G3: k and k' continuous at T2).  With a directory argument,
# also the picture natural_g3.svg there.
PC=${PC:-build/pointcalc}
exec "$PC" natural --from 0,0,0.8 --through 3,1,-0.2 --to 6,0,-0.6 \
    --law cubic ${1:+--plot "$1/natural_g3.svg" --comb}
