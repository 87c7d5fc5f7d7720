#!/bin/sh
# The natural-parametrization article, figure 4, the mirror case of figure
# 3: phi1 = 0 and the end angle phi2 from 0 to -50 degrees in steps of -10,
# T1 = (0, 0), T2 = (1, 0.25).  With a directory argument, also the picture
# natural_fig4.svg there.
PC=${PC:-build/pointcalc}
set -- ${1:+--plot "$1/natural_fig4.svg"}
args=""
for deg in 0 10 20 30 40 50; do
    args="$args --from 0,0,0 --to 1,0.25,$(awk "BEGIN { printf \"%.17g\", -$deg * atan2(0, -1) / 180 }")"
done
# shellcheck disable=SC2086
exec "$PC" natural $args "$@"
