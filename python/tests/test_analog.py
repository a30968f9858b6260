"""Scope captures from Python: threshold= and hysteresis= act as --threshold and
--hysteresis do, in decode(), read() and verify()."""

import json

import pytest

import busdecode
from conftest import BIN, run_cli

BAUD = 9600
SAMPLE_S = 2e-6
TEXT = b"Ab\x55"


def uart_volts(data, low=0.1, high=3.2):
    """The line's voltage per sample: idle, then each byte 8N1 LSB first, then idle."""
    bits = [1] * 40
    for byte in data:
        bits += [0] + [(byte >> i) & 1 for i in range(8)] + [1, 1]
    bits += [1] * 40
    per_bit = round(1 / BAUD / SAMPLE_S)
    return [high if b else low for b in bits for _ in range(per_bit)]


@pytest.fixture
def scope_csv(tmp_path):
    """A Keysight InfiniiVision export (x-axis,1 / second,Volt) of one UART line."""
    path = tmp_path / "scope_uart.csv"
    rows = ["x-axis,1", "second,Volt"]
    rows += [f"{i * SAMPLE_S:.9E},{v:+.6E}" for i, v in enumerate(uart_volts(TEXT))]
    path.write_text("\n".join(rows) + "\n")
    return path


def cli_jsonl(path, *extra):
    rc, out, err = run_cli([str(BIN / "decode"), str(path), "--proto", "uart", "--map",
                            "rx=1", "--format", "jsonl", *extra])
    assert rc == 0, err
    return [json.loads(line) for line in out.splitlines()]


def data_bytes(events):
    return [e["value"] for e in events if e.get("type") == "byte"]


def test_default_threshold_decodes_the_bytes(scope_csv):
    events = list(busdecode.decode(scope_csv, proto="uart", map={"rx": "1"}))
    assert data_bytes(events) == list(TEXT)
    assert events == cli_jsonl(scope_csv)


@pytest.mark.parametrize("threshold, cli", [
    (1.0, ["--threshold", "1.0"]),
    ({"1": 2.5}, ["--threshold", "1=2.5"]),
    ("0.8", ["--threshold", "0.8"]),
])
def test_threshold_and_hysteresis_as_the_cli(scope_csv, threshold, cli):
    got = list(busdecode.decode(scope_csv, proto="uart", map={"rx": "1"},
                                threshold=threshold, hysteresis=0.2))
    assert got == cli_jsonl(scope_csv, *cli, "--hysteresis", "0.2")
    assert data_bytes(got) == list(TEXT)


def test_a_threshold_above_the_line_sees_no_byte(scope_csv):
    # 5 V is above the 3.2 V high level: the line never crosses, nothing is decoded.
    events = list(busdecode.decode(scope_csv, proto="uart", map={"rx": "1"}, threshold=5))
    assert data_bytes(events) == []


def test_read_takes_the_threshold(scope_csv):
    tables = busdecode.read(scope_csv, proto="uart", map={"rx": "1"}, threshold=1.6)
    assert list(tables["uart/byte"]["value"]) == list(TEXT)


def test_signal_columns_are_typed_by_their_declaration(tmp_path):
    # A line that stays high measures no edge: its rise and fall columns are all null, and
    # still float64 as for a line with edges.
    path = tmp_path / "scope_two.csv"
    rows = ["x-axis,1,2", "second,Volt,Volt"]
    rows += [f"{i * SAMPLE_S:.9E},{v:+.6E},{3.2:+.6E}" for i, v in enumerate(uart_volts(TEXT))]
    path.write_text("\n".join(rows) + "\n")
    for line, edges in (("1", True), ("2", False)):
        sig = busdecode.read(path, proto="uart", map={"rx": line})["capture/signal"]
        assert str(sig["rise_median_ns"].dtype) == "float64"
        assert str(sig["fall_p99_ns"].dtype) == "float64"
        assert str(sig["rises"].dtype) == "Int64"
        assert sig["rise_median_ns"].isna().all() != edges


def test_verify_takes_the_threshold(scope_csv, tmp_path):
    rules = tmp_path / "rules.toml"
    rules.write_text('[decode]\nproto = "uart"\nmap = { rx = "1" }\n\n'
                     '[uart]\nmax_errors = 0\nmin_frames = 3\n')
    assert busdecode.verify(scope_csv, rules=rules, threshold=1.6).passed


@pytest.mark.parametrize("kwargs, cli, kind", [
    (dict(threshold="volts"), ["--threshold", "volts"], busdecode.UsageError),
    (dict(threshold={"": 1}), ["--threshold", "=1"], busdecode.UsageError),
    (dict(hysteresis=-0.1), ["--hysteresis", "-0.1"], busdecode.UsageError),
    (dict(threshold={"CH9": 1.0}), ["--threshold", "CH9=1.0"], busdecode.InputError),
])
def test_bad_analog_options_raise_the_cli_message(scope_csv, kwargs, cli, kind):
    rc, _, err = run_cli([str(BIN / "decode"), str(scope_csv), "--proto", "uart", "--map",
                          "rx=1", *cli])
    assert rc == 2
    with pytest.raises(kind) as caught:
        list(busdecode.decode(scope_csv, proto="uart", map={"rx": "1"}, **kwargs))
    assert str(caught.value) == err.strip()[len("decode: "):]


def test_threshold_of_the_wrong_type_is_a_usage_error(scope_csv):
    with pytest.raises(busdecode.UsageError, match="threshold"):
        busdecode.decode(scope_csv, proto="uart", map={"rx": "1"}, threshold=[1.0])
