"""The installed module: `cmake --install` into a scratch prefix, then imported from there
with the build tree out of sight. It must find the installed plugins and library."""

import json
import os
import subprocess
import sys

import pytest

from conftest import BIN, CAPTURES, cli_events

BUILD = BIN.parent
CMAKE = os.environ.get("BUSDECODE_CMAKE", "cmake")


def test_the_installed_module_decodes_with_the_installed_plugins(tmp_path):
    prefix = tmp_path / "prefix"
    subprocess.run([CMAKE, "--install", str(BUILD), "--prefix", str(prefix)], check=True,
                   capture_output=True)
    packages = list(prefix.glob("lib/python3*/dist-packages"))
    assert len(packages) == 1
    env = {k: v for k, v in os.environ.items() if k != "BUSDECODE_PLUGIN_PATH"}
    env["PYTHONPATH"] = str(packages[0])
    script = ("import busdecode, json, sys; "
              "print(json.dumps([busdecode.__file__, "
              "list(busdecode.decode(sys.argv[1], proto='tmcl', opts={'baud': 115200}))]))")
    r = subprocess.run([sys.executable, "-c", script, str(CAPTURES / "tmcl_lines_115200.vcd")],
                       env=env, capture_output=True, text=True, cwd=tmp_path, timeout=60)
    assert r.returncode == 0, r.stderr
    where, events = json.loads(r.stdout)
    assert where.startswith(str(packages[0]))
    assert events == cli_events("tmcl_lines_115200.vcd", ["tmcl"], {"baud": 115200})
