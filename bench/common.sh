# Sourced by the bench scripts (POSIX sh): their options, the tools they need, a temporary
# folder removed on exit. A script sets `usage` (its options after -b) and defines
# `bench_option LETTER VALUE` for its own options, then calls
#   bench_parse "LETTERS" "$@"     (getopts letters besides b:, e.g. "s:d:")
#   bench_need python3 hyperfine   (each tool on PATH, GNU time always)
# and finds: $src (the checkout), $build, $decode, $dir (the temporary folder).
src=$(cd "$(dirname "$0")/.." && pwd)
build=$src/build

bench_fail() {
    echo "$0: $*" >&2
    exit 2
}

bench_parse() {
    letters=$1
    shift
    OPTIND=1
    while getopts "b:$letters" opt; do
        case $opt in
        b) build=$(cd "$OPTARG" && pwd) || bench_fail "no folder $OPTARG" ;;
        \?) echo "usage: $0 [-b BUILD_DIR] ${usage:-}" >&2; exit 2 ;;
        *) bench_option "$opt" "$OPTARG" ;;
        esac
    done
    decode=$build/bin/decode
    [ -x "$decode" ] || bench_fail "no $decode (build first)"
    dir=$(mktemp -d)
    trap 'rm -rf "$dir"' EXIT
}

bench_need() {
    [ -x /usr/bin/time ] || bench_fail "needs GNU time (apt-get install time)"
    for tool in "$@"; do
        command -v "$tool" >/dev/null || bench_fail "needs $tool"
    done
}

# bench_time OUT COMMAND...: runs COMMAND (its output dropped), leaving GNU time's
# "wall user sys max_kb" in OUT.
bench_time() {
    out=$1
    shift
    /usr/bin/time -f "%e %U %S %M" -o "$out" "$@" >/dev/null 2>&1
}
