#!/usr/bin/env python3
"""Times commands side by side, interleaved: run 1 of each, run 2 of each, ...

    bench/time_runs.py [-n RUNS] [-w WARMUP] [--json FILE] CMD1 ARGS... [--- CMD2 ARGS...]

WARMUP rounds (default 0) run every command first, untimed. Prints, per command, the
median wall time, the mean CPU time (user + system) and the cores kept busy (CPU /
wall). Interleaving matters on a VM whose speed drifts within minutes: two commands
timed one after the other can differ by the drift alone. Output goes to /dev/null.
--json FILE also writes every run's times there (bench/run.sh reads them):
{"results": [{"command": ..., "times": [s...], "cpu": [s...]}, ...]}.
Examples (bench/README.md):

    bench/time_runs.py -n 15 wc -l F.vcd --- build/bin/decode F.vcd --proto spi
    bench/time_runs.py -n 15 old/bin/decode F.vcd --proto spi --- build/bin/decode F.vcd --proto spi
    bench/time_runs.py -n 5 build/bin/decode verify a.vcd b.vcd c.vcd d.vcd --rules r.toml --jobs 2
"""
import json
import resource
import statistics
import subprocess
import sys
import time


def main(argv):
    usage = "usage: time_runs.py [-n RUNS] [-w WARMUP] [--json FILE] CMD ARGS... [--- CMD ...]"
    runs, warmup, json_path = 10, 0, None
    while len(argv) >= 2 and argv[0] in ("-n", "-w", "--json"):
        try:
            if argv[0] == "-n":
                runs = int(argv[1])
            elif argv[0] == "-w":
                warmup = int(argv[1])
            else:
                json_path = argv[1]
        except ValueError:
            print(f"time_runs.py: {argv[0]} {argv[1]}: expected a whole number", file=sys.stderr)
            sys.exit(2)
        argv = argv[2:]
    commands, current = [], []
    for word in argv:
        if word == "---":
            commands.append(current)
            current = []
        else:
            current.append(word)
    commands.append(current)
    if runs < 1 or warmup < 0 or any(not c for c in commands):
        print(usage, file=sys.stderr)
        sys.exit(2)
    for _ in range(warmup):
        for cmd in commands:
            subprocess.run(cmd, stdout=subprocess.DEVNULL, check=True)
    wall = [[] for _ in commands]
    cpu = [[] for _ in commands]
    for _ in range(runs):
        for i, cmd in enumerate(commands):
            before = resource.getrusage(resource.RUSAGE_CHILDREN)
            start = time.perf_counter()
            subprocess.run(cmd, stdout=subprocess.DEVNULL, check=True)
            wall[i].append(time.perf_counter() - start)
            after = resource.getrusage(resource.RUSAGE_CHILDREN)
            cpu[i].append(after.ru_utime - before.ru_utime + after.ru_stime - before.ru_stime)
    for i, cmd in enumerate(commands):
        w, c = statistics.median(wall[i]), statistics.mean(cpu[i])
        print(f"{w * 1e3:9.1f} ms wall (median of {runs}, {min(wall[i]) * 1e3:.1f}-"
              f"{max(wall[i]) * 1e3:.1f})  {c * 1e3:9.1f} ms CPU  {c / w:5.2f} cores  "
              f"{' '.join(cmd)}")
    if json_path:
        with open(json_path, "w") as out:
            json.dump({"results": [{"command": " ".join(cmd), "times": wall[i], "cpu": cpu[i]}
                                   for i, cmd in enumerate(commands)]}, out)


if __name__ == "__main__":
    main(sys.argv[1:])
