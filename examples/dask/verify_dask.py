#!/usr/bin/env python3
"""Verify captures on a Dask cluster: `busdecode.verify` on each worker, one chunk of
captures per task, verdicts gathered back in input order into one VerifyResult that
prints like `decode verify`.

    python3 verify_dask.py --rules RULES --from-list LIST [--opt KEY=VALUE]...
                           [--scheduler tcp://HOST:8786 | --workers N] [--chunk N]

Without --scheduler it starts a LocalCluster of N worker processes on this machine.
Every worker needs the busdecode module and the captures at the same paths. Exit status
as `decode verify`: 0 all pass, 1 a rule failed, 2 a capture could not be read.
"""

import argparse
import sys
from typing import Dict, List, Sequence

import busdecode
from dask.distributed import Client, LocalCluster


def _verify_chunk(captures: Sequence[str], rules: str, opts: Dict[str, str]):
    # One thread per task: Dask already runs a task per worker thread.
    return busdecode.verify(captures, rules=rules, opts=opts, jobs=1).captures


def totals_line(results: Sequence[busdecode.CaptureResult]) -> str:
    """The summary line `decode verify` prints for these verdicts."""
    unreadable = sum(r.error is not None for r in results)
    passed = sum(r.passed for r in results)
    checks = sum(len(r.rules) for r in results)
    failed_checks = sum(len(r.failed) for r in results)
    n = len(results)
    return (f"{n} capture{'' if n == 1 else 's'}: {passed} passed, "
            f"{n - passed - unreadable} failed, {unreadable} unreadable; "
            f"{checks} rule checks, {failed_checks} failed")


def verify_on_cluster(client: Client, captures: Sequence[str], rules: str,
                      opts: Dict[str, str] = None, chunk: int = 8) -> busdecode.VerifyResult:
    """Maps chunks of `captures` over the cluster's workers; verdicts come back in order."""
    chunks = [list(captures[i:i + chunk]) for i in range(0, len(captures), chunk)]
    futures = client.map(_verify_chunk, chunks, rules=str(rules), opts=dict(opts or {}),
                         pure=False)
    results: List[busdecode.CaptureResult] = []
    for part in client.gather(futures):
        results.extend(part)
    return busdecode.VerifyResult(results, totals_line(results))


def main(argv=None) -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--rules", required=True)
    p.add_argument("--from-list", required=True, help="one capture path a line")
    p.add_argument("--opt", action="append", default=[], metavar="KEY=VALUE")
    p.add_argument("--scheduler", help="address of a running Dask scheduler")
    p.add_argument("--workers", type=int, default=2, help="LocalCluster worker processes")
    p.add_argument("--chunk", type=int, default=8, help="captures per task")
    a = p.parse_args(argv)
    with open(a.from_list, encoding="utf-8") as f:
        captures = [line.rstrip("\r\n") for line in f]
    captures = [c for c in captures if c and not c.startswith("#")]
    opts = dict(o.split("=", 1) for o in a.opt)
    try:
        if a.scheduler:
            with Client(a.scheduler) as client:
                result = verify_on_cluster(client, captures, a.rules, opts, a.chunk)
        else:
            with LocalCluster(n_workers=a.workers, threads_per_worker=1, processes=True,
                              dashboard_address=None) as cluster, Client(cluster) as client:
                result = verify_on_cluster(client, captures, a.rules, opts, a.chunk)
    except busdecode.InputError as e:
        print(f"verify_dask: {e}", file=sys.stderr)
        return 2
    print(result.summary)
    if any(c.error is not None for c in result):
        return 2
    return 0 if result.passed else 1


if __name__ == "__main__":
    sys.exit(main())
