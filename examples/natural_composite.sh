#!/bin/sh
# The natural-parametrization article, figures 5-8: a composite curve of
# clothoid segments (G1 joints) through five points; the angles at the ends
# are given, the inner ones come from the chord rule (the direction from the
# previous to the next point, figures 6-7).  With a directory argument, also
# the picture natural_composite.svg there.
PC=${PC:-build/pointcalc}
exec "$PC" natural --from 0,0,0.6 --through 2,1.2 --through 4,0.8 \
    --through 6,1.6 --to 8,0.4,-0.5 ${1:+--plot "$1/natural_composite.svg" --comb}
