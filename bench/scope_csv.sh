#!/bin/sh
# Scope CSV throughput and memory: writes a Rigol-style analog CSV of SIZE MB (two noisy
# channels, 100 MS/s, time base from Start/Increment) and decodes it with every line
# through the Schmitt trigger. Targets: at least 150 MB per CPU second; peak memory under
# 64 MB on a 1 GB file.
#   bench/scope_csv.sh [-b BUILD_DIR] [-s SIZE_MB]     (defaults: build, 1000)
set -eu
build=build
size=1000
while getopts b:s: opt; do
    case $opt in
    b) build=$OPTARG ;;
    s) size=$OPTARG ;;
    *) echo "usage: $0 [-b BUILD_DIR] [-s SIZE_MB]" >&2; exit 2 ;;
    esac
done
decode=$build/bin/decode
[ -x "$decode" ] || { echo "$0: no $decode (build first)" >&2; exit 2; }
command -v /usr/bin/time >/dev/null || { echo "$0: needs GNU time (apt-get install time)" >&2; exit 2; }
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
csv=$dir/scope.csv
# About 31 bytes a row.
rows=$((size * 1000000 / 31))
awk -v rows="$rows" 'BEGIN {
    srand(1)
    print "X,CH1,CH2,Start,Increment,"
    print "Sequence,Volt,Volt,0.000000e+00,1.000000e-08"
    for (i = 0; i < rows; i++)
        printf "%d,%.4e,%.4e,\n", i, (int(i / 87) % 2) * 3.3 + (rand() - 0.5) * 0.4,
               (int(i / 50) % 2) * 3.3 + (rand() - 0.5) * 0.4
}' >"$csv"
bytes=$(stat -c %s "$csv")
for threads in 1 2; do
    /usr/bin/time -f "%U %S %M" -o "$dir/time" "$decode" "$csv" --proto uart --map rx=CH1 --map tx=CH2 \
        --opt baud=1000000 --threads $threads --format jsonl >/dev/null 2>&1
    read -r user sys kb <"$dir/time"
    echo "$bytes $user $sys $kb $threads" | awk '{
        cpu = $2 + $3
        printf "scope CSV %.0f MB, --threads %d: %.2f CPU s, %.0f MB per CPU second, peak %.1f MB\n",
               $1 / 1e6, $5, cpu, $1 / 1e6 / cpu, $4 / 1024
    }'
done
