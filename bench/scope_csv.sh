#!/bin/sh
# Scope CSV throughput and memory: writes a Rigol-style analog CSV of SIZE MB (two noisy
# channels, 100 MS/s, time base from Start/Increment) and decodes it with every line
# through the Schmitt trigger. Targets: at least 150 MB per CPU second; peak memory under
# 64 MB on a 1 GB file.
#   bench/scope_csv.sh [-b BUILD_DIR] [-s SIZE_MB]     (defaults: build, 1000)
set -eu
size=1000
usage="[-s SIZE_MB]"
bench_option() { size=$2; }
. "$(dirname "$0")/common.sh"
bench_parse "s:" "$@"
bench_need awk
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
    bench_time "$dir/time" "$decode" "$csv" --proto uart --map rx=CH1 --map tx=CH2 \
        --opt baud=1000000 --threads $threads --format jsonl
    read -r _ user sys kb <"$dir/time"
    echo "$bytes $user $sys $kb $threads" | awk '{
        cpu = $2 + $3
        printf "scope CSV %.0f MB, --threads %d: %.2f CPU s, %.0f MB per CPU second, peak %.1f MB\n",
               $1 / 1e6, $5, cpu, $1 / 1e6 / cpu, $4 / 1024
    }'
done
