#!/usr/bin/python3
"""busdecode.read() into DataFrames against `decode --format jsonl > /dev/null`.

    bench/python_read.py [-b BUILD_DIR] [-s SIZE_MB] [-n RUNS] [--bus bissc] [--capture FILE]
                         [--opt KEY=VALUE]

Makes a SIZE_MB capture with the project's generator (make_capture BUS vcd; default a
500 MB BiSS-C VCD, as bench/run.sh), reads it once into the page cache, then times, RUNS times
in turn, `decode CAPTURE --proto BUS --format jsonl > /dev/null` and
busdecode.read(CAPTURE, proto=BUS) in a fresh interpreter (so that its peak resident memory
is its own), and read()'s floors: the same decoding with each event counted and dropped (no
columns), and so again with the decoders told to leave out the fields (what the decoding
costs without them). Prints the medians: wall and CPU seconds (user + system, all threads),
events per second, read's speed against the others', the peak memories; read's time split
into decoding into columns (C++, GIL released) and making the DataFrames. Wall times on a
shared machine are noisy: the CPU seconds are the steadier figure.
"""

import argparse
import json
import os
import resource
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

SRC = Path(__file__).resolve().parents[1]


def child(capture, bus, opts, floor):
    """Runs in the fresh interpreter: one read(), timed by stage, or a floor of it."""
    if not floor:
        import pandas as pd  # before the clock starts, as for a user who has it loaded

    import busdecode
    from busdecode import _busdecode

    t0 = time.perf_counter()
    c0 = time.process_time()
    args = busdecode._capture_args(capture, bus, None, opts, None, 2)
    if floor:
        events = _busdecode.count_events(args, fields=floor == "fields")
        return report(t0, c0, events)
    with busdecode._collector_paused():  # as read() does
        columns = _busdecode.read_columns(args)
        t1 = time.perf_counter()
        frames = {}
        for name, cols in columns.items():
            data = {k: busdecode._pandas_array(pd, kind, v, m) for k, kind, v, m in cols}
            frames[name] = pd.DataFrame(data, copy=False)
    t2 = time.perf_counter()
    report(t0, c0, sum(len(f) for f in frames.values()), columns=t1 - t0, frames=t2 - t1)


def report(t0, c0, events, **stages):
    """The child's one line of JSON: wall and CPU seconds since t0 and c0, and its peak."""
    print(json.dumps({"wall": time.perf_counter() - t0, "cpu": time.process_time() - c0, **stages,
                      "events": events,
                      "peak_mb": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024}))


def run_decode(decode, capture, bus, opts):
    t0 = time.perf_counter()
    with open(os.devnull, "w") as null:
        p = subprocess.Popen([str(decode), capture, "--proto", bus, "--format", "jsonl"] +
                             opt_args(opts), stdout=null)
        _, status, usage = os.wait4(p.pid, 0)
    wall = time.perf_counter() - t0
    assert status == 0, "decode failed"
    return {"wall": wall, "cpu": usage.ru_utime + usage.ru_stime, "peak_mb": usage.ru_maxrss / 1024}


def opt_args(opts):
    return [a for k, v in opts.items() for a in ("--opt", f"{k}={v}")]


def run_read(build, capture, bus, opts, floor=None):
    env = dict(os.environ, PYTHONPATH=str(build / "python"))
    out = subprocess.run([sys.executable, __file__, "--child", capture, "--bus", bus] +
                         opt_args(opts) + (["--floor", floor] if floor else []), env=env,
                         check=True, capture_output=True, text=True).stdout
    return json.loads(out)


def count_lines(decode, capture, bus, opts):
    p = subprocess.run(f"'{decode}' '{capture}' --proto {bus} --format jsonl "
                       f"{' '.join(opt_args(opts))} | wc -l", shell=True,
                       check=True, capture_output=True, text=True)
    return int(p.stdout)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("-b", "--build", default=str(SRC / "build"))
    ap.add_argument("-s", "--size", type=int, default=500, help="capture size in MB")
    ap.add_argument("-n", "--runs", type=int, default=3)
    ap.add_argument("--bus", default="bissc", help="make_capture's bus, the decoder run")
    ap.add_argument("--capture", help="an existing capture instead of a generated one")
    ap.add_argument("--opt", action="append", default=[], help="decoder option KEY=VALUE")
    ap.add_argument("--child", help=argparse.SUPPRESS)
    ap.add_argument("--floor", choices=["fields", "bare"], help=argparse.SUPPRESS)
    a = ap.parse_args()
    opts = dict(o.split("=", 1) for o in a.opt)
    if a.child:
        return child(a.child, a.bus, opts, a.floor)
    build = Path(a.build).resolve()
    decode = build / "bin" / "decode"
    with tempfile.TemporaryDirectory(prefix="busdecode-pyread.") as tmp:
        capture = a.capture
        if not capture:
            capture = str(Path(tmp) / f"{a.bus}.vcd")
            made = subprocess.run([str(build / "bin" / "make_capture"), a.bus, "vcd",
                                   str(a.size), capture], check=True, capture_output=True,
                                  text=True).stdout.split("\t")
            # Its fourth field: the decode arguments the capture wants (--opt baud=...).
            words = made[3].split()
            opts.update(dict(w.split("=", 1) for p, w in zip(words, words[1:]) if p == "--opt"))
        with open(capture, "rb") as f:  # into the page cache
            while f.read(1 << 24):
                pass
        events = count_lines(decode, capture, a.bus, opts)
        dec, rd, floor, bare = [], [], [], []
        for _ in range(a.runs):
            dec.append(run_decode(decode, capture, a.bus, opts))
            rd.append(run_read(build, capture, a.bus, opts))
            floor.append(run_read(build, capture, a.bus, opts, floor="fields"))
            bare.append(run_read(build, capture, a.bus, opts, floor="bare"))
        assert all(r["events"] == events for r in rd + floor + bare), "decode and read() differ"
        med = lambda runs, k: statistics.median(r[k] for r in runs)  # noqa: E731
        mb = os.path.getsize(capture) / 1e6
        print(f"capture: {capture if a.capture else a.bus + ' vcd'} {mb:.0f} MB, {events} events, "
              f"{a.runs} runs each, medians")
        for name, runs in (("decode --format jsonl", dec), ("busdecode.read", rd),
                           ("floor: events dropped", floor), ("floor: without fields", bare)):
            print(f"  {name:<22} wall {med(runs, 'wall'):6.2f} s  cpu {med(runs, 'cpu'):6.2f} s  "
                  f"{events / med(runs, 'wall') / 1e6:5.2f} M events/s (wall)  "
                  f"{events / med(runs, 'cpu') / 1e6:5.2f} M events/s (cpu)  "
                  f"peak {med(runs, 'peak_mb'):6.0f} MB")
        print(f"  read: columns {med(rd, 'columns'):.2f} s, DataFrames {med(rd, 'frames'):.3f} s "
              f"({events / med(rd, 'frames') / 1e6:.1f} M events/s)")
        print(f"  read speed / decode speed: wall {med(dec, 'wall') / med(rd, 'wall'):.2f}, "
              f"cpu {med(dec, 'cpu') / med(rd, 'cpu'):.2f}")
        print(f"  read speed / floor speed: wall {med(floor, 'wall') / med(rd, 'wall'):.2f}, "
              f"cpu {med(floor, 'cpu') / med(rd, 'cpu'):.2f}")


if __name__ == "__main__":
    main()
