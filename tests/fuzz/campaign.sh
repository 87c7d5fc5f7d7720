#!/bin/sh
# campaign.sh - the fuzz campaign of `make fuzz` (run after `make
# fuzz-build`): prepares each target's seeds, replays the findings of
# earlier campaigns (tests/fuzz/regressions/), then runs the targets named
# (default: all three) side by side on one core at nice 19, and prints what
# each ran: executions, the rate, coverage (cov, ft) and its findings.
#   FUZZ_RUNS     executions per target (default 10^6)
#   FUZZ_SECONDS  wall-clock bound per target (default 120)
#   FUZZ_TIMEOUT  seconds for one input before it is a finding (default 10)
#   FUZZ_CPU      the core to run on (default the last one)
#   FUZZ_NOREPLAY set: skip the replay
# Crashes, leaks and timeouts land in build-fuzz/artifacts/TARGET-*; the
# logs in build-fuzz/log/TARGET.log.  Exit 1 when a target found something.
set -u
B=build-fuzz
RUNS=${FUZZ_RUNS:-1000000}
SECONDS_MAX=${FUZZ_SECONDS:-120}
TIMEOUT=${FUZZ_TIMEOUT:-10}
CPU=${FUZZ_CPU:-$(($(nproc) - 1))}
[ $# -gt 0 ] || set -- fuzz_light fuzz_derive fuzz_eval_args
ON_CORE="taskset -c $CPU nice -n 19"
mkdir -p $B/corpus $B/corpus_light $B/corpus_eval $B/artifacts $B/log

# seeds: one per file, named by its folder (tests/schemes and tests/errors
# share names); the light target's leave out the chapter-2 schemes
# (dolya_2_*: splines, composites) and the slowest ones
for d in examples tests/schemes tests/errors; do
    for f in $d/*.pcs; do
        n="$(echo $d | tr / _)_$(basename "$f")"
        cp "$f" "$B/corpus/$n"
        case "$(basename "$f")" in
        dolya_2_* | steps_* | interpolation_* | conic_five_points.pcs | \
            double_contact.pcs | limits*.pcs) ;;
        *) cp "$f" "$B/corpus_light/$n" ;;
        esac
    done
done
cp tests/fuzz/eval_seeds/* $B/corpus_eval/

failed=0
common="-rss_limit_mb=3072 -dict=tests/fuzz/pointcalc.dict -print_final_stats=1"
if [ -z "${FUZZ_NOREPLAY:-}" ]; then
    for t in "$@"; do
        case $t in
        fuzz_derive | fuzz_light)
            echo "== replay tests/fuzz/regressions/ on $t"
            $ON_CORE $B/$t -timeout=60 -rss_limit_mb=4096 \
                tests/fuzz/regressions/*.pcs > $B/log/$t-replay.log 2>&1 ||
                { echo "$t: the replay failed ($B/log/$t-replay.log)"; failed=1; }
            grep '^Executed' $B/log/$t-replay.log
            ;;
        esac
    done
fi

for t in "$@"; do
    case $t in
    fuzz_derive) args="-max_len=4096 $B/corpus" ;;
    fuzz_light) args="-max_len=512 $B/corpus_light" ;;
    fuzz_eval_args) args="-max_len=512 $B/corpus_eval" ;;
    *) echo "campaign.sh: no target $t" >&2; exit 2 ;;
    esac
    echo "== $t: up to $RUNS executions or $SECONDS_MAX s (log $B/log/$t.log)"
    # shellcheck disable=SC2086
    $ON_CORE $B/$t -runs=$RUNS -max_total_time=$SECONDS_MAX -timeout=$TIMEOUT \
        $common -artifact_prefix=$B/artifacts/$t- $args \
        > $B/log/$t.log 2>&1 &
done
wait

found=$failed
for t in "$@"; do
    log=$B/log/$t.log
    runs=$(sed -n 's/^stat::number_of_executed_units: *//p' $log | tail -1)
    rate=$(sed -n 's/^stat::average_exec_per_sec: *//p' $log | tail -1)
    cov=$(grep -o 'cov: [0-9]* ft: [0-9]*' $log | tail -1)
    echo "$t: ${runs:-?} executions, ${rate:-?} exec/s, ${cov:-no coverage line}"
    # a crash, a leak, a timeout or an out-of-memory is a finding; a
    # slow unit (written as slow-unit-*) is only reported
    if grep -q '^==[0-9]*== ERROR: \|^SUMMARY: ' $log; then
        grep '^==[0-9]*== ERROR: \|^SUMMARY: \|Test unit written' $log
        found=1
    fi
    grep '^Slowest unit' $log | tail -1 | sed "s/^/$t: /"
done
ls $B/artifacts/ 2>/dev/null | sed 's/^/artifact: /'
exit $found
