#!/bin/sh
# Live acquisition: libsigrok's demo device through `decode --device demo` (SPI on D0/D1
# of its pattern). First a sweep of short runs finds the highest sample rate that decode
# keeps up with (every sample acquired and none dropped in DURATION seconds of samples
# taking no more than 10 % longer than that in wall time); then one long run at that rate
# reports samples per second, CPU use and memory: resident size sampled every few seconds,
# flat when the first and last samples and the peak agree.
#   bench/live_demo.sh [-b BUILD_DIR] [-d SECONDS] [-s SWEEP_SECONDS] [-r "RATES..."]
#   (defaults: build, 600, 5, "50M 20M 10M 5M 2M 1M")
set -eu
duration=600
sweep=5
rates="50M 20M 10M 5M 2M 1M"
usage="[-d SECONDS] [-s SWEEP_SECONDS] [-r RATES]"
bench_option() {
    case $1 in
    d) duration=$2 ;;
    s) sweep=$2 ;;
    r) rates=$2 ;;
    esac
}
. "$(dirname "$0")/common.sh"
bench_parse "d:s:r:" "$@"
bench_need bc pgrep

hz() { echo "$1" | sed 's/k$/000/; s/M$/000000/; s/G$/000000000/'; }

# run RATE SECONDS: decodes, sampling VmRSS every 2 s into $dir/rss; leaves GNU time's
# "wall user sys maxkb" in $dir/time and decode's summary in $dir/out.
run() {
    : >"$dir/rss"
    /usr/bin/time -f "%e %U %S %M" -o "$dir/time" "$decode" --device demo --samplerate "$1" \
        --channels D0,D1 --time "$2" --proto spi --map sclk=D0 --map mosi=D1 >"$dir/out" 2>&1 &
    tpid=$!
    while kill -0 $tpid 2>/dev/null; do
        sleep 2
        pid=$(pgrep -P $tpid decode || true)
        [ -n "$pid" ] && awk '/VmRSS/ {print $2}' /proc/"$pid"/status 2>/dev/null >>"$dir/rss" || true
    done
    wait $tpid || true
}

# kept RATE SECONDS: true when the last run acquired every sample, dropped none, in time.
kept() {
    want=$(echo "$(hz "$1") * $2" | bc)
    got=$(sed -n 's/.*demo: \([0-9]*\) samples at.*/\1/p' "$dir/out")
    read -r wall _ _ _ <"$dir/time"
    [ "${got:-0}" = "$want" ] && ! grep -q "dropped" "$dir/out" &&
        [ "$(echo "$wall <= $2 * 1.1" | bc)" = 1 ]
}

best=
for rate in $rates; do
    run "$rate" "$sweep"
    if kept "$rate" "$sweep"; then
        echo "sweep: $rate kept up over $sweep s"
        best=$rate
        break
    fi
    read -r wall _ _ _ <"$dir/time"
    echo "sweep: $rate fell behind: $(sed -n 's/.*demo: \([0-9]*\) samples at.*/\1/p' "$dir/out") samples in $wall s, $(grep -o 'dropped [0-9]* samples' "$dir/out" || echo "none dropped")"
done
[ -n "$best" ] || { echo "$0: no rate of $rates kept up" >&2; exit 1; }

run "$best" "$duration"
read -r wall user sys kb <"$dir/time"
samples=$(sed -n 's/.*demo: \([0-9]*\) samples at.*/\1/p' "$dir/out")
behind=$(sed -n 's/.*decoding at most \([0-9.]*\) s behind.*/\1/p' "$dir/out")
dropped=$(sed -n 's/.*dropped \([0-9]*\) samples.*/\1/p' "$dir/out")
first=$(head -n 1 "$dir/rss")
last=$(tail -n 1 "$dir/rss")
echo "$samples $wall $user $sys $kb ${first:-0} ${last:-0} ${dropped:-0} ${behind:-?}" | awk -v rate="$best" '{
    printf "demo at %s for %.0f s: %.0f samples, %.2f Msamples/s, dropped %.0f, at most %s s behind\n",
           rate, $2, $1, $1 / $2 / 1e6, $8, $9
    printf "CPU %.1f %% of one core (user %.1f s, sys %.1f s); peak RSS %.1f MB, RSS first %.1f MB, last %.1f MB\n",
           100 * ($3 + $4) / $2, $3, $4, $5 / 1024, $6 / 1024, $7 / 1024
}'
