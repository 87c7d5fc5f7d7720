#!/bin/sh
# The natural-parametrization article, figure 3: clothoids (the linear
# curvature law k = as + b) from T1 = (0, 0) to T2 = (1, 0.25) whose start
# angle phi1 runs from 0 to 50 degrees in steps of 10 with phi2 = 0; one
# command, six curves (a later --from starts the next).  With a directory
# argument, also the picture natural_fig3.svg there (docs/natural.md).
PC=${PC:-build/pointcalc}
set -- ${1:+--plot "$1/natural_fig3.svg"}
args=""
for deg in 0 10 20 30 40 50; do
    args="$args --from 0,0,$(awk "BEGIN { printf \"%.17g\", $deg * atan2(0, -1) / 180 }") --to 1,0.25,0"
done
# shellcheck disable=SC2086
exec "$PC" natural $args "$@"
