"""An example of verifying captures inside pytest: one test per capture, each failing
with the rules it broke, as `decode verify` would print them.

    PYTHONPATH=build/python python3 -m pytest examples/python/test_verify_captures.py

Point CAPTURES and RULES at your own recordings and limits.
"""

import subprocess
import sys
from pathlib import Path

import pytest

import busdecode

REPO = Path(__file__).resolve().parents[2]
RULES = REPO / "captures" / "rules_ssi.toml"
CAPTURES = [REPO / "captures" / "ssi_tmc8100_gray25.vcd"]


@pytest.mark.parametrize("capture", CAPTURES, ids=lambda p: p.name)
def test_capture_meets_the_rules(capture):
    result = busdecode.verify(capture, rules=RULES, opts={"gray": True})
    assert result.passed, result.summary


def test_a_broken_capture_says_which_rules_it_broke():
    # The same check on a capture with a repeat mismatch and a short frame: it fails,
    # and says so rule by rule.
    result = busdecode.verify(REPO / "captures" / "ssi_ringshift_delay.vcd", rules=RULES)
    assert not result.passed
    broken = {r.rule: r for r in result[0].failed}
    assert set(broken) == {"max_repeat_mismatches", "max_faults"}
    assert broken["max_repeat_mismatches"].offending == 1


def test_the_plot_example_writes_a_png(tmp_path):
    out = tmp_path / "position.png"
    subprocess.run([sys.executable, str(Path(__file__).with_name("plot_position.py")),
                    str(REPO / "captures" / "bissc_1mhz_26bit.vcd"), "-o", str(out)], check=True)
    assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
