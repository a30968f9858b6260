#!/usr/bin/env bash
# bench/run.sh's decode rows for two builds side by side: is a change slower?
#
#   bench/compare_builds.sh -o OLD_BUILD [-b NEW_BUILD] [-s SIZE_MB] [-n RUNS]
#
# Generates run.sh's captures once (with the new build's make_capture: SPI and BiSS-C VCD,
# the SPI sigrok session, dense and Saleae CSV, four BiSS-C VCDs for verify), then times
# the old and the new `decode` on each in alternating rounds (time_runs.py: run 1 of old,
# run 1 of new, run 2 of old, ...), at the default threads and with --threads 1, and
# records each one's peak memory. A row is "within" when the new build's median paired
# ratio (new over old in the same round) is at most 1.10. Exit 1 when a row is not.
# Needs: two Release/RelWithDebInfo builds with BUSDECODE_BENCH on in the new one,
# python3, jq, /usr/bin/time.
set -euo pipefail
old=""
size=200
runs=9
usage="-o OLD_BUILD [-s SIZE_MB] [-n RUNS]"
bench_option() {
    case $1 in
        o) old="$(cd "$2" && pwd)" ;;
        s) size="$2" ;;
        n) runs="$2" ;;
    esac
}
. "$(dirname "$0")/common.sh"
bench_parse "o:s:n:" "$@"
new="$build"
[ -n "$old" ] || bench_fail "usage: compare_builds.sh [-b NEW_BUILD] $usage"
for x in "$old/bin/decode" "$new/bin/make_capture"; do
    [ -x "$x" ] || bench_fail "missing $x"
done
bench_need jq python3
tmp="$dir"

rows=()
worst=0
# gen BUS FORMAT MB NAME: writes $tmp/NAME, prints decode's arguments for it.
gen() {
    "$new/bin/make_capture" "$1" "$2" "$3" "$tmp/$4" | cut -f4
    sync
}
peak_mb() {
    bench_time "$tmp/time.txt" "$@" || true
    awk '{printf "%.1f", $4 / 1024}' "$tmp/time.txt"
}
# compare LABEL ARGS...: one row, decode ARGS with the old and the new build.
compare() {
    local label="$1"
    shift
    echo "timing $label ..." >&2
    python3 "$src/bench/time_runs.py" -n "$runs" -w 1 --json "$tmp/t.json" \
        "$old/bin/decode" "$@" --- "$new/bin/decode" "$@" >"$tmp/t.txt"
    local ratio before after cpu_old cpu_new
    ratio="$(sed -n 's/.*round by round: x\([0-9.]*\).*/\1/p' "$tmp/t.txt")"
    read -r before cpu_old < <(jq -r '.results[0] | "\(.times | sort | .[length / 2 | floor]) \(.cpu | add / length)"' "$tmp/t.json")
    read -r after cpu_new < <(jq -r '.results[1] | "\(.times | sort | .[length / 2 | floor]) \(.cpu | add / length)"' "$tmp/t.json")
    local mem_old mem_new
    mem_old="$(peak_mb "$old/bin/decode" "$@")"
    mem_new="$(peak_mb "$new/bin/decode" "$@")"
    local ok="yes"
    if awk -v r="$ratio" 'BEGIN { exit !(r > 1.10) }'; then ok="**no**"; worst=1; fi
    rows+=("$(printf '| %s | %.3f s, %.3f s CPU | %.3f s, %.3f s CPU | x%s | %s / %s MB | %s |' \
        "$label" "$before" "$cpu_old" "$after" "$cpu_new" "$ratio" "$mem_old" "$mem_new" "$ok")")
}

for bus in spi bissc; do
    # shellcheck disable=SC2207
    args=($(gen "$bus" vcd "$size" "$bus.vcd"))
    compare "$bus.vcd ($size MB)" "$tmp/$bus.vcd" "${args[@]}"
    compare "$bus.vcd ($size MB), --threads 1" "$tmp/$bus.vcd" "${args[@]}" --threads 1
    [ "$bus" = spi ] && spi_args=("${args[@]}")
    rm -f "$tmp/$bus.vcd"
done
# shellcheck disable=SC2207
args=($(gen spi sr $((size / 4)) spi.sr))
compare "spi.sr ($((size / 4)) M samples)" "$tmp/spi.sr" "${args[@]}"
rm -f "$tmp/spi.sr"
for fmt in csv saleae; do
    gen spi "$fmt" "$size" "spi_$fmt.csv" >/dev/null
    compare "spi $fmt CSV ($size MB)" "$tmp/spi_$fmt.csv" "${spi_args[@]}"
    rm -f "$tmp/spi_$fmt.csv"
done
vfiles=()
for i in 1 2 3 4; do
    gen bissc vcd $((size / 4)) "verify_$i.vcd" >/dev/null
    vfiles+=("$tmp/verify_$i.vcd")
done
printf '[bissc]\nmax_crc_errors = 0\nmin_frames = 1\n\n[decode]\nproto = ["bissc"]\n' >"$tmp/rules.toml"
compare "verify, 4 x $((size / 4)) MB BiSS-C VCD, --jobs $(nproc)" verify "${vfiles[@]}" \
    --rules "$tmp/rules.toml" --jobs "$(nproc)"

echo
echo "Machine: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //'), $(nproc) cores; load average at the end: $(cut -d' ' -f1-3 /proc/loadavg)"
echo "before: $old/bin/decode; after: $new/bin/decode; $runs alternating rounds after one untimed; wall = median, CPU = mean (user + system)"
echo
echo "| capture | before | after | after/before (median of the rounds' ratios) | peak before / after | within 10 % |"
echo "|---|---|---|---|---|---|"
printf '%s\n' "${rows[@]}"
exit "$worst"
