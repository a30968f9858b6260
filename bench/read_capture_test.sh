#!/usr/bin/env bash
# read_capture --prefetch (decode's read-ahead thread) hands over exactly what the plain
# reader reads: the same edge count as read_capture and as the edges --edges prints, and a
# checksum of every edge's fields equal to one worked out here from --edges' lines.
#
#   read_capture_test.sh READ_CAPTURE SOURCE_DIR
set -euo pipefail
rc="$1"
src="$2"
checked=0
for f in "$src"/captures/*.vcd "$src"/captures/*.csv; do
    plain="$("$rc" "$f" 2>/dev/null)" || continue  # a CSV that needs --rate: not this test's
    ahead="$("$rc" --prefetch "$f")"
    n="${plain% edges}"
    want_sum=0
    lines=0
    while read -r t l v; do
        want_sum=$((want_sum + (t ^ l ^ v)))
        lines=$((lines + 1))
    done < <("$rc" --edges "$f" | sed '1d;$d')
    want="$n edges (checksum $want_sum)"
    if [ "$ahead" != "$want" ] || [ "$lines" != "$n" ]; then
        echo "FAIL $f: --prefetch '$ahead', expected '$want' ($lines edges printed)" >&2
        exit 1
    fi
    checked=$((checked + 1))
done
if [ "$checked" -lt 10 ]; then
    echo "FAIL: only $checked captures read" >&2
    exit 1
fi
echo "ok: $checked captures"
