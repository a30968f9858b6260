"""follow(): a capture still being written, and a pipe, each event out as it is decoded."""

import faulthandler
import os
import threading
import time

import pytest

import busdecode
from conftest import CAPTURES, cli_events

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
