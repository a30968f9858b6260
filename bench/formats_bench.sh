#!/usr/bin/env bash
# Throughput and peak memory of the readers for other tools' files:
#
#   bench/formats_bench.sh [-b BUILD_DIR] [-s SAMPLES_M] [-v VCD_MB]
#
# - DSView .dsl and sigrok .sr: SAMPLES_M million samples (default 1000) of 4 probes (an
#   SPI-like clock every 20 samples, chip select, two data lines), decoded as SPI; goal
#   300 M samples/s.
# - Compressed VCD: a VCD of about VCD_MB MB (default 200) of the same kind, compressed
#   with gzip -1 and zstd -3, `decode f.vcd.zst` against `zstdcat f.vcd.zst | decode -`
#   (and gzip alike); goal: no slower.
# Peak memory from GNU time; goal under 64 MB. Needs python3, hyperfine, zstd, jq.
set -euo pipefail
samples_m=1000
vcd_mb=200
usage="[-s SAMPLES_M] [-v VCD_MB]"
bench_option() {
    case $1 in
    s) samples_m=$2 ;;
    v) vcd_mb=$2 ;;
    esac
}
. "$(dirname "$0")/common.sh"
bench_parse "s:v:" "$@"
bench_need python3 hyperfine zstd zstdcat gzip zcat jq
tmp=$dir
spi=(--proto spi --map sclk=clk --map mosi=mosi --map miso=miso --map cs=cs)

python3 - "$tmp/bench.dsl" "$samples_m" <<'PY'
import sys, zipfile
path, n = sys.argv[1], int(float(sys.argv[2]) * 1e6)
n -= n % 64
block = 1 << 24
blocks = (n + block - 1) // block
def plane(period, phase):  # a square wave of `period` samples, as LSB-first bytes
    bits = [(((k + phase) // (period // 2)) & 1) for k in range(8 * period)]
    pat = bytes(sum(bits[8 * i + b] << b for b in range(8)) for i in range(period))
    return pat * (block // 8 // period + 5120 // period + 2)
pats = {"clk": plane(20, 0), "mosi": plane(40, 5), "miso": plane(80, 15), "cs": plane(5120, 100)}
with zipfile.ZipFile(path, "w", zipfile.ZIP_DEFLATED, compresslevel=1) as z:
    z.writestr("header", "[version]\nversion = 2\n[header]\ndevice mode = 0\n"
               f"total samples = {n}\ntotal probes = 4\ntotal blocks = {blocks}\n"
               "samplerate = 100 MHz\n" + "".join(f"probe{i} = {k}\n" for i, k in enumerate(pats)))
    for i, (k, pat) in enumerate(pats.items()):
        for b in range(blocks):
            size = min(block, n - b * block) // 8
            z.writestr(f"L-{i}/{b}", pat[b * block // 8 % 5120: b * block // 8 % 5120 + size])
PY
python3 - "$tmp/bench.sr" "$samples_m" <<'PY'
import sys, zipfile
path, n = sys.argv[1], int(float(sys.argv[2]) * 1e6)
n -= n % 64
chunk = 4 << 20  # samples (one byte each) per logic-1-N member, as sigrok writes them
def unit(k):  # clk every 20 samples, mosi 40, miso 80, cs 5120: bits 0..3
    return (((k // 10) & 1) | (((k + 5) // 20) & 1) << 1 | (((k + 15) // 40) & 1) << 2
            | (((k + 100) // 2560) & 1) << 3)
period = bytes(unit(k) for k in range(5120))
pattern = period * (chunk // 5120 + 2)
with zipfile.ZipFile(path, "w", zipfile.ZIP_DEFLATED, compresslevel=1) as z:
    z.writestr("version", "2")
    z.writestr("metadata", "[global]\nsigrok version=0.5.2\n[device 1]\ncapturefile=logic-1\n"
               "total probes=4\nsamplerate=100 MHz\ntotal analog=0\nprobe1=clk\nprobe2=mosi\n"
               "probe3=miso\nprobe4=cs\nunitsize=1\n")
    for i, at in enumerate(range(0, n, chunk)):
        off = at % 5120
        z.writestr(f"logic-1-{i + 1}", pattern[off: off + min(chunk, n - at)])
PY
for f in bench.dsl bench.sr; do
    echo "== $f: ${samples_m} M samples, 4 probes, decoded as SPI"
    bench_time "$tmp/time" "$decode" "$tmp/$f" "${spi[@]}"
    read -r wall user sys kb <"$tmp/time"
    echo "$wall $user $sys $kb" | awk -v m="$samples_m" '{
        printf "wall %.2f s (CPU %.2f s), %.0f M samples/s, peak RSS %.1f MB\n",
               $1, $2 + $3, m / $1, $4 / 1024 }'
done

python3 - "$tmp/bench.vcd" "$vcd_mb" <<'PY'
import sys
path, mb = sys.argv[1], float(sys.argv[2])
with open(path, "w") as f:
    f.write("$timescale 10 ns $end\n$scope module spi $end\n$var wire 1 ! clk $end\n"
            "$var wire 1 \" mosi $end\n$var wire 1 # miso $end\n$var wire 1 $ cs $end\n"
            "$upscope $end\n$enddefinitions $end\n#0\n1$\n0!\n0\"\n0#\n")
    t, chunk, written = 0, [], 0
    while written < mb * 1e6:
        for word in range(256):
            t += 10; chunk.append(f"#{t}\n0$\n")
            for bit in range(8):
                t += 10; chunk.append(f"#{t}\n1!\n{(word >> (7 - bit)) & 1}\"\n{(word >> bit) & 1}#\n")
                t += 10; chunk.append(f"#{t}\n0!\n")
            t += 10; chunk.append(f"#{t}\n1$\n")
        s = "".join(chunk); f.write(s); written += len(s); chunk = []
PY
gzip -1 -k "$tmp/bench.vcd"
zstd -q -3 -k "$tmp/bench.vcd"
echo "== compressed VCD: $(du -m "$tmp/bench.vcd" | cut -f1) MB plain"
hyperfine -N -w 1 -r 3 --export-json "$tmp/h.json" \
    "$decode $tmp/bench.vcd.zst ${spi[*]}" \
    "sh -c 'zstdcat $tmp/bench.vcd.zst | $decode - ${spi[*]}'" \
    "$decode $tmp/bench.vcd.gz ${spi[*]}" \
    "sh -c 'zcat $tmp/bench.vcd.gz | $decode - ${spi[*]}'" >/dev/null
jq -r '.results[] | "\(.median * 1000 | floor) ms  \(.command)"' "$tmp/h.json" |
    sed "s|$tmp/||g; s|$decode|decode|g"
for f in bench.vcd.zst bench.vcd.gz; do
    bench_time "$tmp/time" "$decode" "$tmp/$f" "${spi[@]}"
    read -r _ _ _ kb <"$tmp/time"
    echo "$f: peak RSS $((kb / 1024)) MB"
done
