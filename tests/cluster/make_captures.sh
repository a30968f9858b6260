#!/bin/bash
# make_captures.sh SOURCE_DIR DIR COUNT: COUNT captures in DIR (copies of a passing and a
# failing BiSS-C capture, every seventh one failing, one listed but absent) and
# DIR/list.txt naming them in order; the truth the cluster runs are compared against
# comes from `decode verify --jobs 1` on the same list.
set -eu
src=$1 dir=$2 count=$3
mkdir -p "$dir"
: >"$dir/list.txt"
for i in $(seq -w 1 "$count"); do
    if [ "$i" = "$(printf '%0*d' ${#count} 100)" ]; then
        echo "$dir/absent-$i.vcd" >>"$dir/list.txt"  # an unreadable capture: an ERROR verdict
        continue
    fi
    if [ $((10#$i % 7)) -eq 0 ]; then from=bissc_errors.vcd; else from=bissc_1mhz_26bit.vcd; fi
    cp "$src/captures/$from" "$dir/cap-$i.vcd"
    echo "$dir/cap-$i.vcd" >>"$dir/list.txt"
done
