"""A Dask LocalCluster of two worker processes verifies 200 captures with
busdecode.verify (examples/dask/verify_dask.py): the verdicts equal `decode verify
--jobs 1` on the same list, line for line, summary included."""

import os
import subprocess
import sys
from pathlib import Path

import pytest

distributed = pytest.importorskip("dask.distributed",
                                  reason="python3-distributed is not installed")

SOURCE = Path(os.environ.get("BUSDECODE_SOURCE_DIR", Path(__file__).resolve().parents[2]))
BIN = Path(os.environ.get("BUSDECODE_BIN_DIR", SOURCE / "build" / "bin"))
RULES = SOURCE / "captures" / "rules_bissc.toml"
sys.path.insert(0, str(SOURCE / "examples" / "dask"))

import verify_dask  # noqa: E402


@pytest.fixture(scope="module")
def captures(tmp_path_factory):
    d = tmp_path_factory.mktemp("captures")
    subprocess.run(["bash", str(SOURCE / "tests/cluster/make_captures.sh"), str(SOURCE), str(d),
                    "200"], check=True)
    return d / "list.txt"


def test_local_cluster_verdicts_equal_decode_verify(captures):
    single = subprocess.run([str(BIN / "decode"), "verify", "--from-list", str(captures),
                             "--rules", str(RULES), "--opt", "bissc.bits=26", "--jobs", "1"],
                            capture_output=True, text=True)
    assert single.returncode == 2, single.stderr  # one listed capture is absent
    paths = [line.strip() for line in captures.read_text().splitlines()]
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  dashboard_address=None) as cluster, \
            distributed.Client(cluster) as client:
        result = verify_dask.verify_on_cluster(client, paths, RULES, {"bissc.bits": "26"})
        workers = {w for w in client.run(os.getpid).values()}
    assert len(workers) == 2 and os.getpid() not in workers
    assert [c.capture for c in result] == paths
    assert result.summary + "\n" == single.stdout
    errors = [c.capture for c in result if c.error is not None]
    assert errors == [p for p in paths if "absent" in p]


def test_the_command_exits_as_decode_verify(captures, capsys):
    status = verify_dask.main(["--rules", str(RULES), "--from-list", str(captures), "--opt",
                               "bissc.bits=26", "--workers", "2", "--chunk", "25"])
    assert status == 2
    assert capsys.readouterr().out.splitlines()[-1].startswith("200 captures: ")
