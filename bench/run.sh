#!/usr/bin/env bash
# The benchmark table of bench/README.md, in one command:
#
#   bench/run.sh [-b BUILD_DIR] [-s SIZE_MB] [-q]
#
# Generates the captures with the project's generators (make_capture: SPI at 10 MHz back
# to back and BiSS-C at 10 MHz, 100 MHz sampling, as VCD, sigrok dense CSV, Saleae CSV and
# a sigrok session) into a
# temporary directory (removed at the end; one large capture at a time, so that each
# stays in the page cache), then times `decode` against `sigrok-cli`, `wc -l` and the
# tokeniser alone on the same cached files (hyperfine, median), then decode and `wc -l`
# again on each VCD dropped from the page cache and read back (as root; `wc -l` is
# fastest then), read as decode reads it (in pieces on both threads) by a thread that
# only counts the edges (decode's floor), and with all of decode's work on one thread (--threads 1: its CPU
# shared over the cores bounds any split of that work), records peak memory
# (/usr/bin/time -v) on 1 GB and 5 GB captures, times the doubling curve, measures the
# --follow latency, times `verify --jobs 1` against all cores (and all cores with
# --threads 1), and prints a table of ratios. -q: a quick run (small files, no 5 GB).
# Needs: a Release/RelWithDebInfo build (default ./build), hyperfine, sigrok-cli, python3.
set -euo pipefail
src="$(cd "$(dirname "$0")/.." && pwd)"
build="$src/build"
size=500
quick=0
while getopts "b:s:q" o; do
    case $o in
        b) build="$(cd "$OPTARG" && pwd)" ;;
        s) size="$OPTARG" ;;
        q) quick=1 ;;
        *) exit 2 ;;
    esac
done
if [ $quick = 1 ]; then size=50; fi
big=$((size * 2))
huge=$((size * 10))
decode="$build/bin/decode"
make="$build/bin/make_capture"
reader="$build/bin/read_capture"
for x in "$decode" "$make" "$reader"; do
    [ -x "$x" ] || { echo "missing $x (build with: cmake --build $build)" >&2; exit 2; }
done
# The peers and tools it times with: missing, the run would stop halfway through.
for t in hyperfine sigrok-cli jq bc wc python3 /usr/bin/time; do
    command -v "$t" >/dev/null || {
        echo "run.sh: $t not found (Debian: apt-get install hyperfine sigrok-cli jq bc time python3)" >&2
        exit 2
    }
done
tmp="$(mktemp -d "${TMPDIR:-/tmp}/busdecode-bench.XXXXXX")"
trap 'rm -rf "$tmp"' EXIT
runs=5

# make_capture BUS FORMAT MB NAME -> prints the decode arguments, sigrok arguments
gen() {
    local out
    out="$("$make" "$1" "$2" "$3" "$tmp/$4")"
    cat "$tmp/$4" >/dev/null  # into the page cache: every tool reads a cached file
    # Written back now, not by kernel threads competing with the timed runs for the two
    # cores (the first tool timed would pay for it).
    sync
    echo "$out"
}
field() { echo "$1" | cut -f"$2"; }
# Percent of FILE in the page cache (fincore, util-linux), or "?" without fincore. This
# VM's page cache holds only about 2.1 GB whatever the free memory, so the script keeps
# one large capture at a time, and the table says whether the file stayed cached.
resident() {
    fincore --bytes --noheadings --output RES,SIZE "$1" 2>/dev/null |
        awk '{ if ($2 > 0) printf "%.0f", 100 * $1 / $2 }' || echo "?"
}
mb() { awk -v b="$(stat -c %s "$1")" 'BEGIN { printf "%.1f", b / 1000000 }'; }
# "WALL CPU" seconds of a command: the median wall time and the mean user+system time
# over N runs (hyperfine, no shell, one warm-up run unless N is 1).
median() {
    local n="$1"
    shift
    local warm=1
    [ "$n" = 1 ] && warm=0  # sigrok-cli: the file is cached already, one run is minutes
    hyperfine -N --style none --warmup "$warm" --runs "$n" --export-json "$tmp/h.json" "$*" >/dev/null 2>&1
    jq -r '.results[0] | "\(.median) \(.user + .system)"' "$tmp/h.json"
}
# The same for decode and wc -l timed around sigrok-cli's run of the same file: N rounds
# before it and N after, median and mean over all 2N. The machine's speed drifts (this
# VM: up to 40 % within minutes); sigrok-cli's one run spans a minute or more, so the
# fast tools are sampled across that same stretch, not in one moment of it. Within each
# stretch the two alternate, a run of decode then one of wc -l (time_runs.py, after one
# untimed round): a ratio of two tools timed in the same seconds, not of two blocks of
# runs a few seconds apart. On this VM what ran just before moves decode's time by up to
# a fifth (bench/README.md, "A faster machine whose two cores come and go"). Without
# sigrok's arguments (""), decode and wc -l alone, N rounds, twice.
around() {
    local n="$1" f="$2" sargs="$3" args="$4"
    local i
    for i in 1 2; do
        # shellcheck disable=SC2086
        python3 "$src/bench/time_runs.py" -n "$n" -w 1 --json "$tmp/side$i.json" \
            "$decode" "$f" $args --- wc -l "$f" >/dev/null
        # shellcheck disable=SC2086
        [ $i = 1 ] && [ -n "$sargs" ] && read -r t_sig c_sig < <(median 1 sigrok-cli -I vcd -i "$f" $sargs)
    done
    # Command K (0: decode, 1: wc -l) over both stretches: "median-wall mean-cpu".
    local q="$jq_median"'[.[].results[$k]] | [(map(.times[]) | median), (map(.cpu[]) | add / length)] | "\(.[0]) \(.[1])"'
    read -r t_dec c_dec < <(jq -rs --argjson k 0 "$q" "$tmp/side1.json" "$tmp/side2.json")
    read -r t_wc c_wc < <(jq -rs --argjson k 1 "$q" "$tmp/side1.json" "$tmp/side2.json")
}
peak_mb() {  # peak resident set of a command, MB
    /usr/bin/time -v "$@" >/dev/null 2>"$tmp/time.txt" || true
    awk '/Maximum resident set size/ {printf "%.1f", $6 / 1024}' "$tmp/time.txt"
}
ratio() { echo "scale=2; $1 / $2" | bc -l; }
# jq: the median of an array of numbers (prefix a filter with it).
jq_median='def median: sort | if length % 2 == 1 then .[length / 2 | floor] else (.[length / 2 - 1] + .[length / 2]) / 2 end; '

fmt_s() { printf '%.3f' "$1"; }
verdict() { if [ "$(echo "$1" | bc -l)" = 1 ]; then echo "yes"; else echo "**no**"; fi; }

rows=()
row() { rows+=("| $(IFS='|'; echo "$*" | sed 's/|/ | /g') |"); }

load_start="$(cut -d' ' -f1-3 /proc/loadavg)"

# sigrok's own session format, the one PulseView saves (make_capture spi sr: deflated
# 4 MiB chunks, as sigrok writes them): decode and sigrok-cli on the same .sr, no VCD
# parsing on sigrok's side. A quarter of SIZE_MB in M samples: about the VCD's duration.
time_sr() {
    local sr="$tmp/spi.sr" info samples t_sr c_sr t_srs c_srs
    samples=$((size / 4))
    echo "generating $sr ..." >&2
    info="$(gen spi sr "$samples" spi.sr)"
    echo "timing $sr ..." >&2
    # shellcheck disable=SC2086
    read -r t_sr c_sr < <(median "$runs" "$decode" "$sr" $(field "$info" 4))
    # shellcheck disable=SC2086
    read -r t_srs c_srs < <(median 1 sigrok-cli -i "$sr" $(field "$info" 5))
    row "spi.sr (sigrok session, $samples M samples at 100 MS/s): decode vs sigrok-cli" \
        "$(mb "$sr") MB" \
        "$(fmt_s "$t_sr") s wall, $(fmt_s "$c_sr") s CPU ($(echo "scale=0; $samples / $t_sr" | bc -l) M samples/s)" \
        "sigrok-cli $(fmt_s "$t_srs") s wall, $(fmt_s "$c_srs") s CPU: **$(ratio "$t_srs" "$t_sr")x** (wall), **$(ratio "$c_srs" "$c_sr")x** (CPU)" \
        "(none)" "-"
    rm -f "$sr"
}

# 1. VCD: decode vs sigrok-cli vs wc -l, one capture at a time (see resident())
for bus in spi bissc; do
    f="$tmp/$bus.vcd"
    echo "generating $f ..." >&2
    info="$(gen "$bus" vcd "$size" "$bus.vcd")"
    args="$(field "$info" 4)"
    sargs="$(field "$info" 5)"
    [ $bus = spi ] && spi_args="$args"
    echo "timing $bus.vcd ..." >&2
    cached_before="$(resident "$f")"
    around "$runs" "$f" "$sargs" "$args"
    cached_after="$(resident "$f")"
    size_mb="$(mb "$f")"
    r_sig="$(ratio "$t_sig" "$t_dec")"
    r_wc="$(ratio "$t_wc" "$t_dec")"
    rc_sig="$(ratio "$c_sig" "$c_dec")"
    rc_wc="$(ratio "$c_wc" "$c_dec")"
    row "$bus.vcd: decode vs sigrok-cli" "$size_mb MB ($cached_before % cached before, $cached_after % after)" \
        "$(fmt_s "$t_dec") s wall, $(fmt_s "$c_dec") s CPU ($(ratio "$size_mb" "$t_dec") MB/s)" \
        "sigrok-cli $(fmt_s "$t_sig") s wall, $(fmt_s "$c_sig") s CPU: **${r_sig}x** (wall), **${rc_sig}x** (CPU)" \
        ">= 100x" "$(verdict "$r_sig >= 100") (wall), $(verdict "$rc_sig >= 100") (CPU)"
    row "$bus.vcd: decode vs wc -l" "$size_mb MB" "as above" \
        "wc -l $(fmt_s "$t_wc") s wall, $(fmt_s "$c_wc") s CPU: decode at **$r_wc** (wall) of its speed; by CPU $rc_wc (decode's work on two cores against wc's on one)" \
        ">= 0.25" "$(verdict "$r_wc >= 0.25") (wall)"
    # The tokeniser alone (every signal read, nothing decoded or printed): what decode
    # could reach with a decoder that cost nothing.
    read -r t_rd c_rd < <(median "$runs" "$reader" "$f")
    row "$bus.vcd: reading alone (read_capture) vs wc -l" "$size_mb MB" \
        "$(fmt_s "$t_rd") s wall, $(fmt_s "$c_rd") s CPU" \
        "wc -l as above: reading alone at **$(ratio "$t_wc" "$t_rd")** (wall) of its speed" \
        "(a bound on the row above)" "-"
    # The same file dropped from the page cache and read back by cat: wc -l reads it
    # about twice as fast as the pages its writer left (the kernel's copy out of the
    # cache is faster; large folios are the likely reason), while decode barely changes
    # (bench/README.md, "Edges in 8 bytes"). The strictest reading of the wc -l target.
    # Needs root (drop_caches).
    if sync && { echo 1 >/proc/sys/vm/drop_caches; } 2>/dev/null; then
        cat "$f" >/dev/null
        around "$runs" "$f" "" "$args"
        r_wc="$(ratio "$t_wc" "$t_dec")"
        row "$bus.vcd read back (cache dropped, then cat): decode vs wc -l" \
            "$size_mb MB ($(resident "$f") % cached after)" \
            "$(fmt_s "$t_dec") s wall, $(fmt_s "$c_dec") s CPU" \
            "wc -l $(fmt_s "$t_wc") s wall, $(fmt_s "$c_wc") s CPU: decode at **$r_wc** (wall) of its speed" \
            ">= 0.25" "$(verdict "$r_wc >= 0.25") (wall)"
        # Reading as decode reads (in pieces on both threads), every edge handed to a
        # thread that only counts them: decode's floor with a decoder that cost nothing
        # (bench/README.md, "A decoder that costs nothing", "A VCD file in pieces").
        read -r t_pf c_pf < <(median "$runs" "$reader" --prefetch "$f")
        row "$bus.vcd read back: reading on two threads, handing over (read_capture --prefetch) vs wc -l" \
            "$size_mb MB" "$(fmt_s "$t_pf") s wall, $(fmt_s "$c_pf") s CPU" \
            "wc -l as above: at **$(ratio "$t_wc" "$t_pf")** (wall) of its speed" \
            "(decode's floor, a bound on the row above)" "-"
        # All of decode's work on one thread (--threads 1): its CPU time shared out
        # perfectly over every core is the least wall time any arrangement of this work
        # could take, by stages (as decode does) or by pieces of the file (bench/README.md,
        # "All the work on one thread").
        # shellcheck disable=SC2086
        read -r t_one c_one < <(median "$runs" "$decode" "$f" $args --threads 1)
        t_share="$(echo "scale=6; $c_one / $(nproc)" | bc -l)"
        row "$bus.vcd read back: decode --threads 1 (all the work on one thread) vs wc -l" \
            "$size_mb MB" "$(fmt_s "$t_one") s wall, $(fmt_s "$c_one") s CPU" \
            "its CPU shared over $(nproc) cores, $(fmt_s "$t_share") s: at **$(ratio "$t_wc" "$t_share")** of wc -l's speed" \
            "(a bound on decode's row above)" "-"
        # Two of those at once: are the two cores really two at this moment? On a VM
        # they may be two threads of one host core, or share it with a neighbour, for
        # minutes at a time; then decode's two threads take about twice the CPU time
        # for the same work, and its rows above say more about the host than the code
        # (bench/README.md, "A faster machine whose two cores come and go").
        hyperfine -N --style none --warmup 1 --runs "$runs" --export-json "$tmp/pair.json" \
            "sh -c '$decode $f $args --threads 1 >/dev/null & $decode $f $args --threads 1 >/dev/null; wait'" \
            >/dev/null 2>&1
        t_pair="$(jq -r '.results[0].median' "$tmp/pair.json")"
        row "$bus.vcd read back: two decode --threads 1 at once vs one (are the cores two?)" \
            "$size_mb MB" "$(fmt_s "$t_pair") s wall for both" \
            "one alone as above: **$(ratio "$t_pair" "$t_one")x** its time (1: two cores; 2: one core shared)" \
            "(how to read the rows above)" "-"
    else
        row "$bus.vcd read back (cache dropped, then cat): decode vs wc -l" "$size_mb MB" \
            "(not measured: dropping the page cache needs root)" "-" ">= 0.25" "-"
    fi
    # BiSS-C's pieces are decoded ahead, their events held until spliced in
    # (core/piece_speculation.h): its peak too. Its row goes with the other peaks.
    # shellcheck disable=SC2086
    if [ $bus = bissc ]; then mem_bissc="$(peak_mb "$decode" "$f" $args)" && bissc_mb="$size_mb"; fi
    rm -f "$f"
    if [ $bus = spi ]; then time_sr; fi
done

# 2. CSV throughput: sigrok's dense CSV (the target), then Saleae Logic 2's export (a row
# per change, decimal seconds: no target in the issue, but the other CSV users bring), of
# the same SPI traffic. time_spi FORMAT NAME: generates $tmp/NAME and sets f, t_run,
# c_run (median wall, mean CPU) and size_mb.
time_spi() {
    f="$tmp/$2"
    echo "generating $f ..." >&2
    gen spi "$1" "$size" "$2" >/dev/null
    echo "timing $2 ..." >&2
    # shellcheck disable=SC2086
    read -r t_run c_run < <(median $runs "$decode" "$f" $spi_args)
    size_mb="$(mb "$f")"
}
time_spi csv spi.csv
csv_rate="$(ratio "$size_mb" "$t_run")"
csv_crate="$(ratio "$size_mb" "$c_run")"
row "spi.csv (sigrok dense, 100 MS/s): decode" "$size_mb MB" "$(fmt_s "$t_run") s wall, $(fmt_s "$c_run") s CPU" \
    "**$csv_rate MB/s** (wall), **$csv_crate MB/s** (per CPU second)" \
    ">= 200 MB/s" "$(verdict "$csv_rate >= 200") (wall), $(verdict "$csv_crate >= 200") (CPU)"
# shellcheck disable=SC2086
mem_csv="$(peak_mb "$decode" "$f" $spi_args)"  # its row goes with the other peaks below
csv_mb="$size_mb"
rm -f "$f"
time_spi saleae spi_saleae.csv
row "spi_saleae.csv (Saleae Logic 2, a row per change): decode" "$size_mb MB" \
    "$(fmt_s "$t_run") s wall, $(fmt_s "$c_run") s CPU" \
    "**$(ratio "$size_mb" "$t_run") MB/s** (wall), **$(ratio "$size_mb" "$c_run") MB/s** (per CPU second)" \
    "(none)" "-"
rm -f "$f"

# 3. Linear time: the doubling curve (SPI VCD). All four files at once (1.9 GB at the
# default size, within this VM's page cache of about 2.7 GB), timed in rounds, one run of
# each per round (time_runs.py): each doubling compares runs of the same minutes. Timed
# one file after another, a step that fell in slow minutes (two dies, bench/README.md)
# read x2.5-2.9 where side by side it is x1.9. Median CPU time per file.
curve=""
prev=""
sizes=("$((size / 4))" "$((size / 2))" "$size" "$big")
cmds=()
for s in "${sizes[@]}"; do
    gen spi vcd "$s" "curve_$s.vcd" >/dev/null
    [ ${#cmds[@]} -gt 0 ] && cmds+=("---")
    # shellcheck disable=SC2206
    cmds+=("$decode" "$tmp/curve_$s.vcd" $spi_args)
done
echo "timing the doubling curve ..." >&2
python3 "$src/bench/time_runs.py" -n "$runs" -w 1 --json "$tmp/curve.json" "${cmds[@]}" >/dev/null
k=0
for s in "${sizes[@]}"; do
    c="$(jq -r --argjson k "$k" "$jq_median"'.results[$k].cpu | median' "$tmp/curve.json")"
    if [ -n "$prev" ]; then curve+=" -> ${s} MB $(fmt_s "$c") s (x$(ratio "$c" "$prev"))"; else curve="${s} MB $(fmt_s "$c") s"; fi
    prev="$c"
    k=$((k + 1))
done
big_file="$tmp/curve_$big.vcd"
# shellcheck disable=SC2086
mem_big="$(peak_mb "$decode" "$big_file" $spi_args)"
for s in "${sizes[@]}"; do [ "$s" != "$big" ] && rm -f "$tmp/curve_$s.vcd"; done
row "doubling curve (SPI VCD, median CPU seconds, the four side by side)" "" "$curve" "each doubling ~x2" "linear" "see curve"

# 4. Peak memory: 1 GB and 5 GB
row "peak memory, $(mb "$big_file") MB VCD" "" "**$mem_big MB**" "" "< 64 MB" "$(verdict "$mem_big < 64")"
rm -f "$big_file"
if [ $quick = 0 ]; then
    echo "generating the ${huge} MB capture ..." >&2
    gen spi vcd "$huge" huge.vcd >/dev/null
    mem_huge="$(peak_mb "$decode" "$tmp/huge.vcd" $spi_args)"
    row "peak memory, $(mb "$tmp/huge.vcd") MB VCD" "" "**$mem_huge MB**" "" "< 64 MB" "$(verdict "$mem_huge < 64")"
    rm -f "$tmp/huge.vcd"
fi
row "peak memory, $csv_mb MB dense CSV" "" "**$mem_csv MB**" "" "< 64 MB" "$(verdict "$mem_csv < 64")"
row "peak memory, $bissc_mb MB BiSS-C VCD (its pieces decoded ahead)" "" "**$mem_bissc MB**" "" "< 64 MB" "$(verdict "$mem_bissc < 64")"

# 5. --follow latency
echo "measuring --follow latency ..." >&2
read -r lat_med lat_p90 lat_max got sent < <(python3 "$src/bench/follow_latency.py" "$decode" 60 0.05)
row "--follow latency (last edge written -> event on stdout)" "$got/$sent frames" \
    "median $lat_med ms, p90 $lat_p90 ms, max $lat_max ms" "" "< 50 ms" "$(verdict "$lat_max < 50")"

# 6. verify --jobs: files checked in parallel (4 BiSS-C captures of SIZE/4 MB each)
echo "timing verify --jobs ..." >&2
vfiles=()
for i in 1 2 3 4; do
    gen bissc vcd $((size / 4)) "verify_$i.vcd" >/dev/null
    vfiles+=("$tmp/verify_$i.vcd")
done
printf '[bissc]\nmax_crc_errors = 0\nmin_frames = 1\nmax_faults = 0\n\n[decode]\nproto = ["bissc"]\n' >"$tmp/rules.toml"
read -r t_j1 c_j1 < <(median "$runs" "$decode" verify "${vfiles[@]}" --rules "$tmp/rules.toml" --jobs 1)
read -r t_jn c_jn < <(median "$runs" "$decode" verify "${vfiles[@]}" --rules "$tmp/rules.toml" --jobs "$(nproc)")
r_jobs="$(ratio "$t_j1" "$t_jn")"
# One job already runs its reader on a second thread, so the speed-up of --jobs N is
# bounded by how idle the cores were with --jobs 1; the target is that --jobs N keeps
# every core busy (CPU seconds per wall second >= 0.85 x cores).
busy_1="$(ratio "$c_j1" "$t_j1")"
busy_n="$(ratio "$c_jn" "$t_jn")"
row "verify, 4 x $(mb "${vfiles[0]}") MB BiSS-C VCD: --jobs 1 vs --jobs $(nproc)" "" \
    "--jobs $(nproc): $(fmt_s "$t_jn") s wall, $(fmt_s "$c_jn") s CPU: **$busy_n cores busy**" \
    "--jobs 1: $(fmt_s "$t_j1") s wall, $(fmt_s "$c_j1") s CPU ($busy_1 cores busy): --jobs $(nproc) **${r_jobs}x** faster" \
    "uses every core" "$(verdict "$busy_n >= 0.85 * $(nproc)")"
# Each capture read and decoded on one thread (--threads 1), N at a time: no hand-over
# between threads, for a batch with at least as many captures as cores.
read -r t_j1t c_j1t < <(median "$runs" "$decode" verify "${vfiles[@]}" --rules "$tmp/rules.toml" --jobs "$(nproc)" --threads 1)
row "verify, 4 x $(mb "${vfiles[0]}") MB BiSS-C VCD: --jobs $(nproc) --threads 1 vs --jobs $(nproc)" "" \
    "--threads 1: $(fmt_s "$t_j1t") s wall, $(fmt_s "$c_j1t") s CPU ($(ratio "$c_j1t" "$t_j1t") cores busy)" \
    "--jobs $(nproc) as above: --threads 1 **$(ratio "$t_jn" "$t_j1t")x** faster" "(none)" "-"
rm -f "${vfiles[@]}"

echo
echo "Machine: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //'), $(nproc) cores, $(free -g | awk '/Mem:/ {print $2}') GB RAM; load average at the start: $load_start, at the end: $(cut -d' ' -f1-3 /proc/loadavg)"
echo "Wall times are medians: decode and wc -l of $((2 * runs)) runs each, alternating, $runs before and $runs after sigrok-cli's 1 run of the same file (other rows: $runs runs); CPU = user + system, mean. On a loaded machine wall times mostly measure waiting for a core: compare CPU times then."
echo "decode: $decode ($(grep -m1 CMAKE_BUILD_TYPE "$build/CMakeCache.txt" | cut -d= -f2)); $(sigrok-cli --version | head -1); $(wc --version | head -1)"
echo
echo "| measurement | file | busdecode | compared with | target | met |"
echo "|---|---|---|---|---|---|"
printf '%s\n' "${rows[@]}"
