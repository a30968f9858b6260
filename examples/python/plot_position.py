#!/usr/bin/python3
"""Plots an encoder's position and line delay over time from a capture, to a PNG.

    examples/python/plot_position.py captures/bissc_1mhz_26bit.vcd -o position.png
    examples/python/plot_position.py enc.vcd --proto ssi --opt bits=25 -o ssi.png

Frames with errors are marked in red on both plots. Needs the busdecode module (built
into build/python: PYTHONPATH=build/python) and matplotlib.
"""

import argparse
import sys

import matplotlib

matplotlib.use("Agg")  # files only, no display needed
import matplotlib.pyplot as plt  # noqa: E402

import busdecode  # noqa: E402


def parse_args(argv):
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("capture")
    p.add_argument("--proto", default="bissc", help="decoder (default bissc)")
    p.add_argument("--opt", action="append", default=[], metavar="KEY=VALUE")
    p.add_argument("--map", action="append", default=[], metavar="ROLE=SIGNAL")
    p.add_argument("-o", "--output", default="position.png")
    return p.parse_args(argv)


def pairs(items):
    return dict(item.split("=", 1) for item in items)


def plot(frames, title, output):
    t_ms = frames["start_ns"] / 1e6
    faulty = frames["errors"].map(bool)
    fig, (pos, delay) = plt.subplots(2, 1, sharex=True, figsize=(10, 6))
    pos.plot(t_ms, frames["position"].astype("float64"), ".-", lw=0.8, ms=3, label="position")
    pos.plot(t_ms[faulty], frames["position"][faulty].astype("float64"), "rx", label="frame with errors")
    pos.set_ylabel("position (counts)")
    pos.legend(loc="upper right")
    pos.set_title(title)
    if "line_delay_ns" in frames:
        ld = frames["line_delay_ns"].astype("float64")
        delay.plot(t_ms, ld, ".-", lw=0.8, ms=3, color="tab:green", label="line delay")
        delay.plot(t_ms[faulty], ld[faulty], "rx")
        delay.set_ylabel("line delay (ns)")
        delay.set_ylim(0, max(1.0, float(ld.max(skipna=True) or 0)) * 1.25)
    else:
        delay.text(0.5, 0.5, "no line delay in these frames", ha="center", transform=delay.transAxes)
    delay.set_xlabel("time (ms)")
    for ax in (pos, delay):
        ax.grid(True, alpha=0.3)
    fig.tight_layout()
    fig.savefig(output, dpi=100)


def main(argv=None):
    args = parse_args(argv)
    try:
        tables = busdecode.read(args.capture, proto=args.proto, opts=pairs(args.opt),
                                map=pairs(args.map))
    except busdecode.Error as e:
        sys.exit(f"plot_position: {e}")
    frames = tables.get(f"{args.proto}/frame")
    if frames is None or frames.empty:
        sys.exit(f"plot_position: {args.capture}: no {args.proto} frames")
    n_bad = int(frames["errors"].map(bool).sum())
    plot(frames, f"{args.capture}: {len(frames)} {args.proto} frames, {n_bad} with errors",
         args.output)
    print(f"{args.output}: {len(frames)} frames, {n_bad} with errors")


if __name__ == "__main__":
    main()
