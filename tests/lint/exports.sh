#!/bin/sh
# tests/lint/exports.sh BUILDDIR - every function or variable the library and
# the command line export is used outside the object that defines it: by
# another object of the archives or main.o, by a test, a bench, an example
# or a fuzzer, or it is the public API (libpointcalc.h).  An export nobody
# uses is either dead or should be static; exits 1 listing them.
cd "$(dirname "$0")/../.." || exit 2
b=${1:-build}
objs="$b/libpointcalc.a $b/libpointcalc-cli.a $b/driver/cli/main.o"
for o in $objs; do
    [ -f "$o" ] || { echo "exports.sh: no $o (build first)"; exit 2; }
done
tmp=$(mktemp -d)
# defined globals (functions, data) per object; undefined references of all
nm -g --defined-only $objs 2>/dev/null | awk '
    /:$/ { obj = substr($0, 1, length($0) - 1); next }
    /^$/ { next }
    NF == 3 && $2 ~ /[TDBR]/ { print $3, obj }' | sort > "$tmp/def"
nm -u $objs 2>/dev/null | awk 'NF == 2 { print $2 }' | sort -u > "$tmp/used"
# identifiers used by tests, benches, examples, fuzzers and the public header
cat tests/unit/*.c tests/unit/*.h tests/fuzz/*.c tests/fuzz/*.h bench/*.c \
    bench/*.h examples/*.c libpointcalc.h 2>/dev/null |
    tr -c 'A-Za-z0-9_' '\n' | sort -u > "$tmp/words"
bad=0
while read -r sym obj; do
    grep -qx "$sym" "$tmp/used" && continue
    grep -qx "$sym" "$tmp/words" && continue
    case $sym in main | yy* | pc_yy*) continue ;; esac # generated scanner
    echo "$obj: '$sym' is exported but used by no other file (make it static or remove it)"
    bad=1
done < "$tmp/def"
rm -rf "$tmp"
exit $bad
