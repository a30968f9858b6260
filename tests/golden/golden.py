#!/usr/bin/python3
"""Every example capture's golden output: the command in captures/README.md's table,
run with --format jsonl, prints exactly captures/<stem>.golden.jsonl.

    tests/golden/golden.py --check BIN_DIR    # the test (ctest -R golden_outputs)
    tests/golden/golden.py --write BIN_DIR    # remakes every golden file after a change

The README's table is the one list: a capture added there gets its golden file from
--write, and --check fails for a row without one.
"""

import argparse
import difflib
import os
import re
import shlex
import subprocess
import sys
from pathlib import Path

SOURCE = Path(__file__).resolve().parents[2]
COMMAND = re.compile(r"`(decode captures/[^`]+)`\s*\|\s*$")


def commands():
    """(golden path, decode arguments) for each row of the README's table."""
    rows = []
    for line in (SOURCE / "captures" / "README.md").read_text().splitlines():
        m = COMMAND.search(line)
        if not m:
            continue
        args = shlex.split(m.group(1))[1:]
        capture = Path(args[0])
        rows.append((SOURCE / "captures" / (capture.stem + ".golden.jsonl"), args))
    return rows


def run(bin_dir, args):
    env = {k: v for k, v in os.environ.items() if k != "LD_PRELOAD"}
    r = subprocess.run([str(Path(bin_dir) / "decode")] + args + ["--format", "jsonl"],
                       cwd=SOURCE, capture_output=True, text=True, timeout=120, env=env)
    if r.returncode != 0:
        sys.exit(f"{' '.join(args)}: exit {r.returncode}: {r.stderr.strip()}")
    return r.stdout


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    mode = ap.add_mutually_exclusive_group(required=True)
    mode.add_argument("--check", metavar="BIN_DIR")
    mode.add_argument("--write", metavar="BIN_DIR")
    a = ap.parse_args()
    rows = commands()
    if len(rows) < 10:
        sys.exit(f"captures/README.md: found only {len(rows)} commands in its table")
    failed = 0
    for golden, args in rows:
        out = run(a.check or a.write, args)
        if a.write:
            golden.write_text(out)
            continue
        if not golden.exists():
            print(f"{golden.name}: missing (make it with tests/golden/golden.py --write)")
            failed += 1
        elif golden.read_text() != out:
            diff = difflib.unified_diff(golden.read_text().splitlines(), out.splitlines(),
                                        golden.name, "decode now", lineterm="", n=1)
            print("\n".join(list(diff)[:40]))
            failed += 1
    print(f"{len(rows) - failed} of {len(rows)} captures print their golden output")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
