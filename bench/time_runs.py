#!/usr/bin/env python3
"""Times commands side by side, interleaved: run 1 of each, run 2 of each, ...

    bench/time_runs.py [-n RUNS] [-w WARMUP] [--json FILE] [--split MS] CMD1 ARGS... [--- CMD2 ARGS...]

WARMUP rounds (default 0) run every command first, untimed. Prints, per command, the
median wall time, the mean CPU time (user + system) and the cores kept busy (CPU /
wall). Interleaving matters on a VM whose speed drifts within minutes: two commands
timed one after the other can differ by the drift alone. Output goes to /dev/null.
--json FILE also writes every run's times there (bench/run.sh reads them):
{"results": [{"command": ..., "times": [s...], "cpu": [s...]}, ...]}.
Each command after the first is also compared with the first round by round: the median
of its wall time over the first's in the same round ("paired"), which the machine's drift
moves less than a ratio of medians. --split MS gives that median separately for the
rounds in which the first command took less than MS milliseconds and for the others: on
the bench VM, the minutes when its two cores share a die and when they do not
(bench/README.md, "Two dies").
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
    usage = ("usage: time_runs.py [-n RUNS] [-w WARMUP] [--json FILE] [--split MS] "
             "CMD ARGS... [--- CMD ...]")
    runs, warmup, json_path, split = 10, 0, None, None
    while len(argv) >= 2 and argv[0] in ("-n", "-w", "--json", "--split"):
        try:
            if argv[0] == "-n":
                runs = int(argv[1])
            elif argv[0] == "-w":
                warmup = int(argv[1])
            elif argv[0] == "--split":
                split = float(argv[1]) / 1e3
            else:
                json_path = argv[1]
        except ValueError:
            kind = "a number" if argv[0] == "--split" else "a whole number"
            print(f"time_runs.py: {argv[0]} {argv[1]}: expected {kind}", file=sys.stderr)
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
    for i in range(1, len(commands)):
        print(f"  {i + 1}. against 1., round by round: {paired(wall[i], wall[0], split)}")
    if json_path:
        with open(json_path, "w") as out:
            json.dump({"results": [{"command": " ".join(cmd), "times": wall[i], "cpu": cpu[i]}
                                   for i, cmd in enumerate(commands)]}, out)


def paired(times, first, split):
    """The median of times[r] / first[r] over the rounds r, as text; with `split` (s),
    over the rounds whose first time is under it and over the others, apart."""
    def median_ratio(rounds):
        if not rounds:
            return "- (no rounds)"
        ratio = statistics.median(times[r] / first[r] for r in rounds)
        return f"x{ratio:.3f} (median of {len(rounds)})"
    every = range(len(first))
    if split is None:
        return median_ratio(list(every))
    under = [r for r in every if first[r] < split]
    over = [r for r in every if first[r] >= split]
    return (f"first under {split * 1e3:g} ms: {median_ratio(under)}; "
            f"at or over: {median_ratio(over)}")


if __name__ == "__main__":
    main(sys.argv[1:])
