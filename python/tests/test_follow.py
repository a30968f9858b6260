"""follow(): a capture still being written, and a pipe, each event out as it is decoded."""

import faulthandler
import json
import os
import subprocess
import sys
import threading
import time

import pytest

import busdecode
from conftest import BIN, CAPTURES, cli_events, plain_env

CAPTURE = "uart_rxtx_9600_8n1.vcd"


@pytest.fixture(autouse=True)
def watchdog():
    # A follow that never ends would hang the suite: fail it loudly instead.
    faulthandler.dump_traceback_later(60, exit=True)
    yield
    faulthandler.cancel_dump_traceback_later()


def halves(text):
    """The capture cut at a timestamp line about halfway through."""
    cut = text.index("\n#", len(text) // 2) + 1
    return text[:cut], text[cut:]


def test_follow_a_growing_file(tmp_path):
    expected = cli_events(CAPTURE, ["uart"])
    first, rest = halves((CAPTURES / CAPTURE).read_text())
    live = tmp_path / "live.vcd"
    with open(live, "w") as f:
        f.write(first)
    got = []
    with busdecode.follow(live, proto="uart") as events:
        for ev in events:
            got.append(ev)
            if len(got) == 3:  # decoded from the first half: now the rest arrives
                with open(live, "a") as f:
                    f.write(rest)
            if len(got) == len(expected) - 1:
                break  # the last byte may wait for more input to end
    assert got == expected[: len(got)]
    assert events.facts["file"] == str(live)


def test_follow_a_pipe_ends_when_the_writer_closes():
    expected = cli_events(CAPTURE, ["uart"])
    text = (CAPTURES / CAPTURE).read_bytes()
    r, w = os.pipe()

    def write():
        with os.fdopen(w, "wb") as out:
            for i in range(0, len(text), 4096):
                out.write(text[i:i + 4096])
                out.flush()
                time.sleep(0.002)

    writer = threading.Thread(target=write)
    writer.start()
    with os.fdopen(r, "rb") as stream:
        got = list(busdecode.follow(stream, proto="uart"))
    writer.join()
    assert got == expected


def test_close_from_another_thread_ends_a_waiting_follow(tmp_path):
    first, _ = halves((CAPTURES / CAPTURE).read_text())
    live = tmp_path / "live.vcd"
    live.write_text(first)
    events = busdecode.follow(live, proto="uart")
    threading.Timer(0.5, events.close).start()
    got = list(events)  # waits for more input until closed
    assert 0 < len(got) < len(cli_events(CAPTURE, ["uart"]))



# Follows its standard input, a pipe, given as sys.stdin.
FOLLOW_STDIN = """
import json, sys
import busdecode
try:
    with busdecode.follow(sys.stdin, proto=sys.argv[1]) as events:
        print(json.dumps({"events": list(events), "file": events.facts["file"]}))
except busdecode.Error as e:
    print(json.dumps({"error": str(e)}))
"""


def follow_stdin(data, proto):
    r = subprocess.run([sys.executable, "-c", FOLLOW_STDIN, proto], input=data,
                       capture_output=True, timeout=60)
    assert r.returncode == 0, r.stderr
    return json.loads(r.stdout)


def test_follow_standard_input_names_it_as_the_cli_does():
    garbage = b"garbage\n"
    r = subprocess.run([str(BIN / "decode"), "-", "--proto", "bissc", "--follow"],
                       input=garbage, capture_output=True, timeout=60, env=plain_env())
    assert r.returncode == 2
    error = follow_stdin(garbage, "bissc")["error"]
    assert error.startswith("<stdin>:1: ")
    assert r.stderr.decode() == f"decode: {error}\n"
    got = follow_stdin((CAPTURES / CAPTURE).read_bytes(), "uart")
    assert got["events"] == cli_events(CAPTURE, ["uart"])
    assert got["file"] == "-"  # as follow("-") and decode("-") give it
