#!/usr/bin/env bash
# Runs the libFuzzer targets one after another, each for SECONDS (default 600), on one
# core each (-workers/-jobs are left at 1: the build machine is shared).
#
#   fuzz/run.sh [-b BUILD_DIR] [-t SECONDS | -r RUNS] [TARGET...]   (default: every fuzz_* built)
#
# -r stops each target after RUNS executions instead of after SECONDS. DECODER_MAX_LEN
# (default 4096) caps the decoder targets' inputs: shorter edge streams run faster.
# FUZZ_FLAGS adds libFuzzer options to every run (e.g. -entropic=0, see README.md).
#
# Corpora live in BUILD_DIR/corpus/<target> (seeded from the generators via
# fuzz_make_seeds, from captures/ and tests/data/real/, and from fuzz/seeds/), crashes
# in BUILD_DIR/artifacts/<target>/, logs in BUILD_DIR/logs/. Prints the executions of
# each run. Keep every crashing input as tests/robustness/regressions/<target>/NAME.
set -euo pipefail
src="$(cd "$(dirname "$0")/.." && pwd)"
build="$src/build-fuzz"
secs=600
runs_limit=""
while getopts "b:t:r:" o; do
    case $o in
        b) build="$(cd "$OPTARG" && pwd)" ;;
        t) secs="$OPTARG" ;;
        r) runs_limit="$OPTARG" ;;
        *) exit 2 ;;
    esac
done
shift $((OPTIND - 1))
real="$src/tests/data/real"  # the real captures the tests use

targets=("$@")
if [ ${#targets[@]} -eq 0 ]; then
    for f in "$build"/bin/fuzz_*; do
        n="$(basename "$f")"
        [ "$n" = fuzz_make_seeds ] || targets+=("${n#fuzz_}")
    done
fi

# Seeds (small files only: libFuzzer keeps the first -max_len bytes anyway). Short
# inputs keep the executions per second up; the readers' paths need no long files.
seeds="$build/seeds"
if [ ! -d "$seeds" ]; then
    "$build/bin/fuzz_make_seeds" "$seeds" >/dev/null
fi
copy_small() {  # DEST FIND-ARGS...
    local dest="$1"
    shift
    mkdir -p "$dest"
    find "$@" -type f -size -256k -exec cp -n {} "$dest/" \; 2>/dev/null || true
}
seed_corpus() {  # TARGET
    local t="$1" c="$build/corpus/$1"
    mkdir -p "$c"
    [ -d "$seeds/$t" ] && cp -n "$seeds/$t"/* "$c/" 2>/dev/null || true
    [ -d "$src/fuzz/seeds/$t" ] && cp -n "$src/fuzz/seeds/$t"/* "$c/" 2>/dev/null || true
    [ -d "$src/tests/robustness/regressions/$t" ] && cp -n "$src/tests/robustness/regressions/$t"/* "$c/" 2>/dev/null || true
    case "$t" in
        vcd) copy_small "$c" "$src/captures" "$real" -name '*.vcd' ;;
        vcd_pieces) for f in "$seeds/vcd"/*; do  # pieces of 7 bytes, search 64 KiB
            [ -f "$f" ] && { printf '\x07\x80'; cat "$f"; } > "$c/$(basename "$f")"
        done ;;
        csv_sigrok) copy_small "$c" "$src/captures" "$real/biss-renishaw/sigrok-csv" -name '*.csv' ;;
        csv_saleae) copy_small "$c" "$real/sigrok-dumps" -name '*.csv' ;;
        sr) copy_small "$c" "$real" -name '*.sr' -size -64k ;;
        dsl) copy_small "$c" "$src/tests/data/real/formats/dsview" -size -16k ;;
    esac
}
options_for() {  # TARGET -> libFuzzer options
    case "$1" in
        vcd | vcd_pieces) echo "-dict=$src/fuzz/dict/vcd.dict -max_len=4096" ;;
        csv_*) echo "-dict=$src/fuzz/dict/csv.dict -max_len=4096" ;;
        sr) echo "-dict=$src/fuzz/dict/sr.dict -max_len=8192" ;;
        dsl) echo "-max_len=16384" ;;
        compressed | sample_rows | saleae_bin) echo "-max_len=4096" ;;
        rules) echo "-dict=$src/fuzz/dict/rules.dict -max_len=2048" ;;
        cli_args) echo "-dict=$src/fuzz/dict/cli_args.dict -max_len=512" ;;
        *) echo "-max_len=${DECODER_MAX_LEN:-4096}" ;;
    esac
}

mkdir -p "$build/logs"
printf '%-16s %12s %10s %8s  %s\n' target executions exec/s seconds result
for t in "${targets[@]}"; do
    seed_corpus "$t"
    mkdir -p "$build/artifacts/$t"
    log="$build/logs/$t.log"
    # shellcheck disable=SC2046
    set +e
    limit="-max_total_time=$secs"
    [ -n "$runs_limit" ] && limit="-runs=$runs_limit"
    start=$(date +%s)
    "$build/bin/fuzz_$t" "$build/corpus/$t" $(options_for "$t") "$limit" ${FUZZ_FLAGS:-} \
        -timeout=10 -rss_limit_mb=2048 -malloc_limit_mb=1024 -print_final_stats=1 \
        -artifact_prefix="$build/artifacts/$t/" >"$log" 2>&1
    rc=$?
    set -e
    runs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$log" | grep -o '[0-9]*$' | tail -1)
    rate=$(grep -o 'stat::average_exec_per_sec: *[0-9]*' "$log" | grep -o '[0-9]*$' | tail -1)
    res=ok
    [ $rc -ne 0 ] && res="FINDING (see $log, $build/artifacts/$t/)"
    printf '%-16s %12s %10s %8s  %s\n' "$t" "${runs:-?}" "${rate:-?}" "$(($(date +%s) - start))" "$res"
done
