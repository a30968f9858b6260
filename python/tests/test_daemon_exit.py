"""A program that exits while a daemon thread of its own waits in the module exits
cleanly. Python ends such threads with pthread_exit as it finalizes, and that unwinding
through C++ aborted the process ("terminate called without an active exception")."""

import os
import subprocess
import sys
import textwrap

import pytest

from conftest import CAPTURES

# Each call waits for ever: on a FIFO no one writes, on a capture whose header never
# ends, or on an LCM feed no one publishes.
CALLS = {
    "read": "busdecode.read(FIFO, proto='uart')",
    "decode": "list(busdecode.decode(FIFO, proto='uart'))",
    "verify": "busdecode.verify([FIFO], rules=RULES, proto='uart', jobs=2)",
    "follow": "list(busdecode.follow(HALF, proto='uart'))",
    "subscribe": "list(busdecode.subscribe('memq://'))",
}


@pytest.mark.parametrize("call", CALLS)
def test_exit_with_a_daemon_thread_in_the_module(tmp_path, call):
    fifo = tmp_path / "never.vcd"
    os.mkfifo(fifo)
    half = tmp_path / "half.vcd"
    half.write_text("$timescale 1 ns $end\n$scope module top $end\n")
    rules = tmp_path / "rules.toml"
    rules.write_text("[uart]\nmin_frames = 1\n")
    program = textwrap.dedent(f"""
        import threading, time
        import busdecode
        FIFO, HALF, RULES = {str(fifo)!r}, {str(half)!r}, {str(rules)!r}
        started = threading.Event()
        def work():
            started.set()
            {CALLS[call]}
        class SlowToGo:
            # Python finalizes while this goes: the thread's wait of 100 ms ends meanwhile.
            def __del__(self, sleep=time.sleep):
                sleep(0.3)
        keep = SlowToGo()
        threading.Thread(target=work, daemon=True).start()
        started.wait()
        time.sleep(0.3)
    """)
    r = subprocess.run([sys.executable, "-c", program], capture_output=True, text=True,
                       timeout=60)
    assert (r.returncode, r.stderr) == (0, "")


# Iterators that the program still holds when it ends: the main thread, finalizing, closes
# them and goes on to exit.
HELD = {
    "decode": "busdecode.decode(CAPTURE, proto='uart')",
    "follow": "busdecode.follow(CAPTURE, proto='uart')",  # waiting for more
    "subscribe": "busdecode.subscribe('memq://')",
}


@pytest.mark.parametrize("call", HELD)
def test_exit_holding_an_iterator(call):
    program = textwrap.dedent(f"""
        import busdecode
        CAPTURE = {str(CAPTURES / "uart_rxtx_9600_8n1.vcd")!r}
        held = {HELD[call]}
    """)
    r = subprocess.run([sys.executable, "-c", program], capture_output=True, text=True,
                       timeout=60)
    assert (r.returncode, r.stderr) == (0, "")
