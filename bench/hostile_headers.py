#!/usr/bin/env python3
"""Writes the two wide-header captures of the bounded-cost notes (bench/README.md,
"Wide headers"): a VCD declaring N one-bit signals of which a decode maps two, and a CSV
of N columns. Usage: hostile_headers.py vcd N OUT | csv N OUT"""
import sys


def ident(i):
    # VCD identifier codes of printable ASCII '!'..'~', as simulators number them.
    out = ""
    while True:
        out += chr(33 + i % 94)
        i //= 94
        if i == 0:
            return out


def column(i):
    digits = "0123456789abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"
    out = "c"
    while True:
        out += digits[i % 62]
        i //= 62
        if i == 0:
            return out


def vcd(n, path):
    with open(path, "w") as f:
        f.write("$timescale 1 ns $end\n$scope module top $end\n")
        for i in range(n):
            f.write(f"$var wire 1 {ident(i)} s{i} $end\n")
        f.write("$upscope $end\n$enddefinitions $end\n#0\n1! 1\"\n")
        t = 0
        for k in range(2000):  # 1 MBd UART bytes on s0 and s1
            for bit in [0] + [(k >> b) & 1 for b in range(8)] + [1]:
                t += 1000
                f.write(f"#{t}\n{bit}! {bit}\"\n")


def csv(n, path):
    with open(path, "w") as f:
        # Short names (4 bytes a column with its comma), the line under the 1 MiB cap.
        f.write("Time [s]," + ",".join(column(i) for i in range(n)) + "\n")
        row = ",".join("1" for _ in range(n))
        for k in range(3):
            f.write(f"{k * 1e-6:.6f},{row}\n")


if __name__ == "__main__":
    {"vcd": vcd, "csv": csv}[sys.argv[1]](int(sys.argv[2]), sys.argv[3])
