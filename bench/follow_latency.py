#!/usr/bin/env python3
"""--follow latency: how long after a frame's last edge lands in the file its event
appears on decode's stdout.

    follow_latency.py DECODE [FRAMES] [INTERVAL_S]

Writes a VCD header, starts `decode FILE --proto spi --follow --format jsonl`, then
every INTERVAL_S appends one SPI word (mode 3, 32 bits) plus cs release and a later
timestamp, flushes, and times the arrival of the word's event line. Prints the median,
the 90th percentile and the maximum in milliseconds.
"""
import os
import select
import subprocess
import sys
import tempfile
import time

decode = sys.argv[1]
frames = int(sys.argv[2]) if len(sys.argv) > 2 else 60
interval = float(sys.argv[3]) if len(sys.argv) > 3 else 0.05

HEADER = ("$timescale 1 ns $end\n$scope module top $end\n"
          "$var wire 1 ! cs $end\n$var wire 1 \" sclk $end\n"
          "$var wire 1 # mosi $end\n$var wire 1 $ miso $end\n"
          "$upscope $end\n$enddefinitions $end\n#0 1! 1\" 0# 0$\n")


def word(t, value):
    """One 32-bit word starting at t (ns); returns (text, end time)."""
    out = [f"#{t} 0!\n"]
    t += 100
    level = 0
    for b in range(32):
        bit = (value >> (31 - b)) & 1
        change = f" {bit}#" if bit != level else ""
        level = bit
        out.append(f"#{t} 0\"{change}\n#{t + 50} 1\"\n")
        t += 100
    out.append(f"#{t + 100} 1!\n")
    if level:
        out.append(f"#{t + 150} 0#\n")
    return "".join(out), t + 1000


with tempfile.TemporaryDirectory(prefix="busdecode-follow-") as d:
    path = os.path.join(d, "live.vcd")
    with open(path, "w") as f:
        f.write(HEADER)
    proc = subprocess.Popen([decode, path, "--proto", "spi", "--follow", "--format", "jsonl"],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, bufsize=0)
    time.sleep(0.3)  # let it open the file and read the header
    lat = []
    buf = b""
    t = 1000
    with open(path, "a") as f:
        for k in range(frames):
            text, t = word(t, 0x12345678 + k)
            f.write(text)
            f.flush()
            sent = time.monotonic()
            got = None
            while got is None and time.monotonic() - sent < 2.0:
                r, _, _ = select.select([proc.stdout], [], [], 0.5)
                if r:
                    chunk = os.read(proc.stdout.fileno(), 65536)
                    if not chunk:
                        break
                    buf += chunk
                    while b"\n" in buf:
                        line, buf = buf.split(b"\n", 1)
                        if b'"transfer"' in line and got is None:
                            got = time.monotonic()
            if got is not None:
                lat.append((got - sent) * 1000)
            time.sleep(interval)
    proc.kill()
    proc.wait()
    if not lat:
        print("follow latency: no events arrived", file=sys.stderr)
        sys.exit(1)
    lat.sort()
    med = lat[len(lat) // 2]
    p90 = lat[int(len(lat) * 0.9)]
    print(f"{med:.1f} {p90:.1f} {lat[-1]:.1f} {len(lat)} {frames}")
