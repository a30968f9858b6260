"""Shared by the busdecode module's tests: where the captures and the `decode` binary are
(ctest passes BUSDECODE_SOURCE_DIR and BUSDECODE_BIN_DIR), and running the CLI."""

import json
import os
import subprocess
from pathlib import Path

import pytest

SOURCE = Path(os.environ.get("BUSDECODE_SOURCE_DIR", Path(__file__).resolve().parents[2]))
BIN = Path(os.environ.get("BUSDECODE_BIN_DIR", SOURCE / "build" / "bin"))
CAPTURES = SOURCE / "captures"

# Every decoder on the repository's captures: (capture, protos, opts). Two decoders in
# one pass, errors and nulls included.
CASES = [
    ("bissc_1mhz_26bit.vcd", ["bissc"], {}),
    ("bissc_errors.vcd", ["bissc"], {}),
    ("bissc_10mhz_long_cable.csv", ["bissc"], {}),
    ("ssi_posital_lead.csv", ["ssi"], {"bits": 24}),
    ("ssi_ringshift_delay.vcd", ["ssi"], {}),
    ("ssi_tmc8100_gray25.vcd", ["ssi"], {"gray": True}),
    ("spi_mode0_lsb16.vcd", ["spi"], {}),
    ("spi_mode3_32bit_saleae.csv", ["spi"], {"cpol": 1, "cpha": 1}),
    ("tmc8100_ssi_dialogue.vcd", ["tmc8100", "ssi"], {}),
    ("tmc8100_faults.vcd", ["tmc8100", "ssi"], {}),
    ("tmc8100_bootloader.vcd", ["tmc8100"], {}),
    ("tmcl_lines_115200.vcd", ["tmcl"], {"baud": 115200}),
    ("tmcl_rs485_9600.vcd", ["tmcl"], {}),
    ("uart_rxtx_9600_8n1.vcd", ["uart"], {}),
    ("uart_7e1_faults.csv", ["uart"], {}),
    # A $date: every event carries capture_start.
    ("uart_rxtx_overlapped_sigrok-cli.vcd", ["uart"], {"baud": 115200}),
]


def cli_args(capture, protos, opts=None, maps=None):
    args = [str(BIN / "decode"), str(CAPTURES / capture)]
    for p in protos:
        args += ["--proto", p]
    for k, v in (maps or {}).items():
        args += ["--map", f"{k}={v}"]
    for k, v in (opts or {}).items():
        v = ("1" if v else "0") if isinstance(v, bool) else v
        args += ["--opt", f"{k}={v}"]
    return args


def plain_env():
    """The environment for programs other than Python: without the sanitizer runtimes
    that a sanitizer build preloads into the interpreter (its own programs link them)."""
    return {k: v for k, v in os.environ.items() if k != "LD_PRELOAD"}


def run_cli(args):
    """(exit status, stdout, stderr) of `decode ARGS`."""
    r = subprocess.run(args, capture_output=True, text=True, timeout=60, env=plain_env())
    return r.returncode, r.stdout, r.stderr


def cli_events(capture, protos, opts=None, maps=None):
    rc, out, err = run_cli(cli_args(capture, protos, opts, maps) + ["--format", "jsonl"])
    assert rc == 0, err
    return [json.loads(line) for line in out.splitlines()]


@pytest.fixture(params=CASES, ids=[c[0] for c in CASES])
def case(request):
    return request.param
