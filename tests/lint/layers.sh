#!/bin/sh
# tests/lint/layers.sh [ROOT] - folders are layers: an #include of a project header
# may only go down or sideways (docs/architecture.md, docs/contributing.md).
#   base              -> base
#   grammar           -> base grammar
#   compiler/algebra  -> base compiler/algebra (the exact algebra knows no
#                        scheme, no derivation and no printer)
#   compiler          -> base grammar compiler (and its algebra)
#   runtime           -> base runtime
#   codegen           -> base grammar compiler runtime codegen
#   driver            -> everything (and libpointcalc.h)
# ROOT (default: the repository) is the tree to check.
# Prints every include that runs up a layer and exits 1 if there is one.
cd "${1:-$(dirname "$0")/../..}" || exit 2
allowed() {
    case $1 in
    base) echo "base" ;;
    grammar) echo "base grammar" ;;
    compiler/algebra) echo "base compiler/algebra" ;;
    compiler) echo "base grammar compiler compiler/algebra" ;;
    runtime) echo "base runtime" ;;
    codegen) echo "base grammar compiler compiler/algebra runtime codegen" ;;
    driver) echo "base grammar compiler compiler/algebra runtime codegen driver libpointcalc.h" ;;
    esac
}
bad=0
for layer in base grammar compiler/algebra compiler runtime codegen driver; do
    ok=$(allowed $layer)
    # compiler/'s own files are those not in compiler/algebra/
    for f in $(find $layer -name '*.[chly]' | grep -v "^compiler/algebra/" | sort) \
             $([ $layer = compiler/algebra ] && find $layer -name '*.[chly]' | sort); do
        # "dir/file.h" -> dir; "file.h" (generated or local) -> file.h
        grep -n '^[[:space:]]*#[[:space:]]*include[[:space:]]*"' "$f" |
        while IFS= read -r line; do
            inc=${line#*\"}; inc=${inc%%\"*}
            case $inc in
            compiler/algebra/*) top=compiler/algebra ;;
            */*) top=${inc%%/*} ;;
            parser.h | lexer.h) top=grammar ;; # generated into $(B)/grammar
            *) top=$inc ;;
            esac
            case " $ok " in
            *" $top "*) ;;
            *) echo "$f:${line%%:*}: error: $layer/ may not include \"$inc\" (it may include: $ok)" ;;
            esac
        done
    done
done > /tmp/pc_layers.$$
if [ -s /tmp/pc_layers.$$ ]; then
    cat /tmp/pc_layers.$$; bad=1
fi
rm -f /tmp/pc_layers.$$
exit $bad
