"""subscribe() against a real `decode --lcm udpm://...` publisher on loopback."""

import json
import struct
import subprocess
import sys
import threading
import time
from pathlib import Path

import pytest

import busdecode
from conftest import BIN, CAPTURES, cli_events, run_cli


def test_the_feed_gives_the_events_decode_gives():
    capture, protos = "tmc8100_ssi_dialogue.vcd", ["tmc8100", "ssi"]
    r = subprocess.run([sys.executable, str(Path(__file__).with_name("lcm_feed.py")),
                        str(BIN / "decode"), str(CAPTURES / capture), "DECODE_SSI_.*"] + protos,
                       capture_output=True, text=True, timeout=120)
    assert r.returncode == 0, r.stderr
    got = json.loads(r.stdout)
    expected = cli_events(capture, protos)
    assert got["all"] == expected
    assert got["some"] == [e for e in expected if e["proto"] == "ssi"]
    assert got["some"]


def test_a_bad_url_raises_the_clis_error():
    with pytest.raises(busdecode.InputError) as raised:
        busdecode.subscribe("nosuch://x")
    assert str(raised.value).startswith("--lcm: cannot open LCM URL 'nosuch://x'")


def test_a_tcpq_url_without_a_server_raises():
    # LCM's tcpq:// stays "good" without a connection, and waiting on it aborted Python.
    with pytest.raises(busdecode.InputError) as raised:
        busdecode.subscribe("tcpq://127.0.0.1:1", timeout=1)
    assert "Unable to connect to server" in str(raised.value)


def test_a_bad_channel_pattern_is_a_usage_error():
    with pytest.raises(busdecode.UsageError):
        busdecode.subscribe("memq://", channels="DECODE_(")


def test_until_end_waits_for_the_runs_last_capture(tmp_path):
    # Each capture of a run ends with "end"; the run itself with "done".
    log = tmp_path / "two.lcm"
    captures = [str(CAPTURES / "bissc_errors.vcd"), str(CAPTURES / "bissc_1mhz_26bit.vcd")]
    args = [str(BIN / "decode")] + captures + ["--proto", "bissc", "--opt", "bits=26"]
    rc, out, err = run_cli(args + ["--format", "jsonl"])
    assert rc == 0, err
    expected = [json.loads(line) for line in out.splitlines()]
    rc, _, err = run_cli(args + ["--lcm", f"file://{log}?mode=w"])
    assert rc == 0, err
    got = list(busdecode.subscribe(f"file://{log}?mode=r", until_end=True, timeout=30))
    assert got == expected
    assert {e["capture"] for e in got} == set(captures)


def without_some_events(log, drop):
    """An LCM log (the file:// provider's format) with the DECODE_EVENTS records whose
    order among them is in `drop` left out, as UDP loses datagrams."""
    data, out, at, k = log.read_bytes(), bytearray(), 0, 0
    while at < len(data):
        sync, _, _, clen, dlen = struct.unpack_from(">IqqII", data, at)
        assert sync == 0xEDA1DA01
        end = at + 28 + clen + dlen
        channel = data[at + 28:at + 28 + clen].decode()
        if channel != "DECODE_EVENTS" or k not in drop:
            out += data[at:end]
        k += channel == "DECODE_EVENTS"
        at = end
    lossy = log.with_name("lossy.lcm")
    lossy.write_bytes(bytes(out))
    return lossy


def test_lost_events_are_counted(tmp_path):
    log = tmp_path / "all.lcm"
    rc, _, err = run_cli([str(BIN / "decode"), str(CAPTURES / "bissc_1mhz_26bit.vcd"), "--proto",
                          "bissc", "--lcm", f"file://{log}?mode=w"])
    assert rc == 0, err
    whole = busdecode.subscribe(f"file://{log}?mode=r", until_end=True, timeout=30)
    n = len(list(whole))
    assert n > 20 and whole.lost == 0
    lossy = without_some_events(log, {3, 4, 10, n - 1})  # the last one too
    sub = busdecode.subscribe(f"file://{lossy}?mode=r", until_end=True, timeout=30)
    assert len(list(sub)) == n - 4
    assert sub.lost == 4


def test_close_and_with_end_the_iteration():
    url = "memq://"
    with busdecode.subscribe(url, timeout=30) as sub:
        pass
    assert list(sub) == []
    sub = busdecode.subscribe(url, timeout=30)
    sub.close()
    sub.close()
    assert list(sub) == []


def test_close_from_another_thread_ends_a_waiting_iteration():
    sub = busdecode.subscribe("memq://")
    got = []
    reader = threading.Thread(target=lambda: got.extend(sub))
    reader.start()
    time.sleep(0.3)  # waiting in next()
    sub.close()
    reader.join(10)
    assert not reader.is_alive()
    assert got == []
