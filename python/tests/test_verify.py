"""verify(): verdicts and failed rules as objects, the same as `decode verify` prints."""

import pytest

import busdecode
from conftest import BIN, CAPTURES, run_cli

RULES = CAPTURES / "rules_bissc.toml"
PASSING = CAPTURES / "bissc_1mhz_26bit.vcd"
FAILING = CAPTURES / "bissc_errors.vcd"


def test_verdicts_match_decode_verify(tmp_path):
    missing = tmp_path / "gone.vcd"
    paths = [PASSING, FAILING, missing]
    result = busdecode.verify(paths, rules=RULES, opts={"bissc.bits": 26}, jobs=2)
    rc, out, _ = run_cli([str(BIN / "decode"), "verify"] + [str(p) for p in paths] +
                         ["--rules", str(RULES), "--opt", "bissc.bits=26", "--jobs", "2"])
    assert rc == 2
    assert result.summary == out.rstrip("\n")
    assert not result.passed and len(result) == 3
    ok, bad, gone = result
    assert ok.passed and ok.failed == [] and ok.error is None
    assert len(ok.rules) == 9 and all(r.passed for r in ok.rules)
    assert ok.events == "bissc 126 frames"
    assert not bad.passed and [r.name for r in bad.failed] == ["bissc.max_faults"]
    fault = bad.failed[0]
    assert fault.offending == 6 and fault.first_ns == 5000 and "short_frame" in fault.message
    assert bad.hints and "bits=26" in bad.hints[0]
    assert not gone.passed and gone.error.endswith("cannot open: No such file or directory")
    assert result.failed == [bad, gone]


def test_a_passing_batch_asserts_clean():
    result = busdecode.verify(PASSING, rules=RULES, opts={"bissc.bits": 26})
    assert result.passed, result.summary
    assert result.summary.startswith("PASS")


def test_bad_rules_raise_input_error(tmp_path):
    rules = tmp_path / "bad.toml"
    rules.write_text("[bissc]\nmax_crc_errors = -1\nno_such_rule = 3\n")
    rc, _, err = run_cli([str(BIN / "decode"), "verify", str(PASSING), "--rules", str(rules)])
    assert rc == 2
    with pytest.raises(busdecode.InputError) as raised:
        busdecode.verify(PASSING, rules=rules)
    assert err.strip() == "decode verify: " + str(raised.value)


def test_bad_option_value_raises_once_as_decode_verify_says_it():
    rc, out, err = run_cli([str(BIN / "decode"), "verify", str(PASSING), str(FAILING), "--rules",
                            str(RULES), "--opt", "bits=999"])
    assert rc == 2 and out == ""
    with pytest.raises(busdecode.InputError) as raised:
        busdecode.verify([PASSING, FAILING], rules=RULES, opts={"bits": 999})
    assert err == "decode verify: " + str(raised.value) + "\n"
    assert "option bits=999" in str(raised.value)


def test_no_capture_is_a_usage_error_as_decode_verify_says_it():
    rc, _, err = run_cli([str(BIN / "decode"), "verify", "--rules", str(RULES)])
    assert rc == 2
    with pytest.raises(busdecode.UsageError) as raised:
        busdecode.verify([], rules=RULES)
    assert str(raised.value) == "no capture given"
    assert err.startswith("decode: " + str(raised.value))
