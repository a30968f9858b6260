#!/bin/sh
# make_examples writes every generated example capture in captures/ again, byte for byte,
# and refuses an unknown decoder id with exit 2.
#   examples_rewritten.sh MAKE_EXAMPLES SOURCE_DIR
set -eu
maker=$1
src=$2
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
"$maker" "$out" > /dev/null
n=0
for f in "$out"/*; do
    cmp "$f" "$src/captures/$(basename "$f")"
    n=$((n + 1))
done
# Six decoders' examples: 17 files when this was written; fewer means a list went missing.
if [ "$n" -lt 17 ]; then
    echo "make_examples wrote only $n captures"
    exit 1
fi
status=0
"$maker" "$out" no_such_decoder 2> "$out/err" || status=$?
if [ "$status" -ne 2 ] || ! grep -q "no decoder 'no_such_decoder'" "$out/err"; then
    echo "an unknown id: exit $status, $(cat "$out/err")"
    exit 1
fi
