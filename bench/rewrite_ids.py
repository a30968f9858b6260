#!/usr/bin/env python3
"""Rewrites a VCD so that every identifier code has two characters ("!" -> "!a").

The VCD reader's tight loop takes one- and two-character identifiers; this makes the
two-character case from a capture written with one-character codes, to time it:

    bench/rewrite_ids.py spi10.vcd spi10_id2.vcd

Handles what the project's writer produces: `$var` lines, then tokens separated by
blanks: timestamps, scalar changes ("0!", "1!") and vector or real changes ("b0101 !").
"""
import sys


def main(src, dst):
    ids = {}
    with open(src) as f, open(dst, "w") as out:
        in_header = True
        for line in f:
            if in_header:
                words = line.split()
                if len(words) >= 5 and words[0] == "$var":
                    code = words[3]
                    ids[code] = code + "a"
                    words[3] = ids[code]
                    line = " ".join(words) + "\n"
                elif "$enddefinitions" in line:
                    in_header = False
                out.write(line)
                continue
            tokens = line.split()
            for i, tok in enumerate(tokens):
                if tok[:1] in "01xzXZ" and tok[1:] in ids:
                    tokens[i] = tok[0] + ids[tok[1:]]
                elif i > 0 and tok in ids and tokens[i - 1][:1] in "bBrR":
                    tokens[i] = ids[tok]  # the code of a vector or real change
            line = " ".join(tokens) + "\n"
            out.write(line)


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit("usage: rewrite_ids.py IN.vcd OUT.vcd")
    main(sys.argv[1], sys.argv[2])
