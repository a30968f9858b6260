"""The package's type hints: mypy --strict finds nothing in it, and they take every path
the functions take (str, bytes, and os.PathLike of either)."""

import subprocess
import sys
from pathlib import Path

import pytest

import busdecode
from conftest import plain_env

USE = '''
import os
import pathlib

import busdecode


def check(raw: bytes, entry: "os.DirEntry[bytes]", path: pathlib.Path) -> None:
    busdecode.decode(raw, proto="bissc")
    busdecode.read(entry, proto="bissc")
    busdecode.follow(path, proto="bissc")
    busdecode.verify([raw, raw], rules=entry)
    busdecode.verify(entry, rules=path)
'''


def test_mypy_strict_passes_the_package_and_paths_of_every_kind(tmp_path):
    pytest.importorskip("mypy")
    (tmp_path / "use.py").write_text(USE)
    env = dict(plain_env(), MYPYPATH=str(Path(busdecode.__file__).parents[1]))
    r = subprocess.run([sys.executable, "-m", "mypy", "--strict", "--cache-dir", "/dev/null",
                        "use.py"], cwd=tmp_path, env=env, capture_output=True, text=True,
                       timeout=120)
    assert r.returncode == 0, r.stdout + r.stderr
