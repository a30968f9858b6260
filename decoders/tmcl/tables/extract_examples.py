#!/usr/bin/env python3
"""Extracts the worked examples of the TMCM-1690 TMCL manual ("Binary Form of ..." and the
"Reply (...)" tables after them) into a tab-separated test vector file:

    title <TAB> 9 command bytes (hex) <TAB> 9 reply bytes (hex, or -)

    extract_examples.py MANUAL.txt > tests/tmcl/manual_examples.tsv"""
import re
import sys


def read_bytes(lines, i):
    out = []
    while i < len(lines) and len(out) < 9:
        m = re.search(r"\t([0-9A-F]{2}) _h\s*$", lines[i])
        if m:
            out.append(m.group(1))
        elif out and not lines[i].strip():
            break
        i += 1
    return out, i


def main(path):
    lines = open(path, encoding="utf-8").read().splitlines()
    i = 0
    while i < len(lines):
        m = re.match(r"^Binary Form of (.+?)\s*$", lines[i])
        if not m:
            i += 1
            continue
        title = m.group(1)
        cmd, i = read_bytes(lines, i + 1)
        reply = []
        j = i
        while j < len(lines) and j < i + 4 and not lines[j].startswith("Reply ("):
            j += 1
        if j < len(lines) and lines[j].startswith("Reply ("):
            reply, i = read_bytes(lines, j + 1)
        if len(cmd) == 9:
            print(f"{title}\t{' '.join(cmd)}\t{' '.join(reply) if len(reply) == 9 else '-'}")


main(sys.argv[1])
