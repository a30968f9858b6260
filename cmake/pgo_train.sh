#!/bin/bash
# usage: pgo_train.sh BIN PROFILE_DIR WORK_DIR STAMP
# The training run of profile-guided optimisation (cmake/BusdecodePgo.cmake): BIN's
# instrumented `decode` decodes SPI and BiSS-C VCD captures that BIN's `make_capture`
# writes into WORK_DIR, as users and bench/run.sh run it; its counts land in PROFILE_DIR.
# STAMP is written last, so that a failed run trains again at the next build.
set -euo pipefail
bin="$1" profile="$2" work="$3" stamp="$4"
rm -f "$stamp"
# Counts from an earlier build of other code would be merged with these: start afresh.
rm -rf "$profile" "$work"
mkdir -p "$profile" "$work"
trap 'rm -rf "$work"' EXIT

run() { "$bin/decode" "$@" >/dev/null; }
for proto in spi bissc; do
    # The VCD reader has a loop per length of the times, and a loop the training never
    # runs gets no profile: trained on captures with times of 7 digits at most, SPI's
    # `decode` on 8- and 9-digit times was no faster than without the profile
    # (bench/README.md, "Profile-guided optimisation"). So the training has times of
    # every length a long capture at 100 MS/s has: up to 8 digits (40 MB from tick 0),
    # 9 (from 1 s) and 10 (from 10 s).
    "$bin/make_capture" $proto vcd 40 "$work/$proto.vcd" >/dev/null
    "$bin/make_capture" $proto vcd 16 "$work/${proto}_9.vcd" 100000000 >/dev/null
    "$bin/make_capture" $proto vcd 16 "$work/${proto}_10.vcd" 1000000000 >/dev/null
    run "$work/$proto.vcd" --proto $proto
    run "$work/$proto.vcd" --proto $proto --format jsonl
    run "$work/$proto.vcd" --proto $proto --threads 1
    run "$work/${proto}_9.vcd" --proto $proto
    run "$work/${proto}_10.vcd" --proto $proto
    rm -f "$work"/*.vcd
done
# The counts must be named by the objects' paths inside the build folder
# (-fprofile-prefix-path), or the optimised build finds none and silently compiles
# without them: stop here instead (the compiler must see the build folder under the
# path CMake gives it).
expected="analyzer#CMakeFiles#busdecode_core.dir#capture#vcd_reader.cpp.gcda"
if [ ! -f "$profile/$expected" ]; then
    echo "pgo_train.sh: no $expected in $profile: the profiles are named otherwise;" \
        "configure with -DBUSDECODE_PGO=OFF" >&2
    exit 1
fi
touch "$stamp"
