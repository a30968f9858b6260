"""Errors raise InputError / UsageError with the line `decode` prints after "decode: "."""

import pytest

import busdecode
from conftest import BIN, CAPTURES, run_cli

GOOD = CAPTURES / "bissc_1mhz_26bit.vcd"


def cli_error(args):
    rc, _, err = run_cli([str(BIN / "decode")] + [str(a) for a in args])
    assert rc == 2
    lines = err.splitlines()
    assert len(lines) == 1 and lines[0].startswith("decode: ")
    return lines[0][len("decode: "):]


@pytest.mark.parametrize("kind, call, cli", [
    (busdecode.InputError, dict(path=CAPTURES / "nothere.vcd", proto="bissc"),
     [CAPTURES / "nothere.vcd", "--proto", "bissc"]),
    (busdecode.UsageError, dict(path=GOOD, proto="nosuch"), [GOOD, "--proto", "nosuch"]),
    (busdecode.UsageError, dict(path=GOOD, proto="bissc", opts={"bits": 999}),
     [GOOD, "--proto", "bissc", "--opt", "bits=999"]),
    (busdecode.UsageError, dict(path=GOOD, proto="bissc", opts={"nokey": 1}),
     [GOOD, "--proto", "bissc", "--opt", "nokey=1"]),
    (busdecode.InputError, dict(path=GOOD, proto="bissc", map={"ma": "NOPE"}),
     [GOOD, "--proto", "bissc", "--map", "ma=NOPE"]),
    (busdecode.UsageError, dict(path=GOOD, proto="bissc", rate=-5),
     [GOOD, "--proto", "bissc", "--rate", "-5"]),
    (busdecode.InputError, dict(path=GOOD, proto=[]), [GOOD]),
    (busdecode.InputError, dict(path=CAPTURES, proto="bissc"), [CAPTURES, "--proto", "bissc"]),
], ids=["missing file", "unknown decoder", "option range", "unknown option", "unbound role",
        "bad rate", "no decoder", "directory"])
def test_error_text_is_the_clis(kind, call, cli):
    with pytest.raises(kind) as raised:
        busdecode.decode(**call)
    assert str(raised.value) == cli_error(cli)
    with pytest.raises(kind) as raised_by_read:
        busdecode.read(**call)
    assert str(raised_by_read.value) == str(raised.value)
    assert isinstance(raised.value, busdecode.Error)


def test_an_error_deep_in_the_capture_is_raised_by_the_iteration(tmp_path):
    text = GOOD.read_text()
    cut = tmp_path / "cut.vcd"
    cut.write_text(text[: len(text) * 2 // 3].rsplit("\n#", 1)[0] + "\n#zz\n")
    rc, out, err = run_cli([str(BIN / "decode"), str(cut), "--proto", "bissc", "--format", "jsonl"])
    assert rc == 2
    got = []
    with pytest.raises(busdecode.InputError) as raised:
        for ev in busdecode.decode(cut, proto="bissc"):
            got.append(ev)
    assert len(got) == out.count("\n")
    assert "decode: " + str(raised.value) == err.strip()


def test_bad_arguments_are_usage_errors():
    with pytest.raises(busdecode.UsageError):
        busdecode.decode(GOOD, proto="bissc", threads=3)
    with pytest.raises(busdecode.UsageError):
        busdecode.decode(GOOD, proto="bissc", opts=["bits=26"])
    with pytest.raises(busdecode.UsageError):
        busdecode.verify(GOOD, rules=CAPTURES / "rules_bissc.toml", jobs=-1)
    with pytest.raises(busdecode.UsageError, match=r"^--threads 3: expected 1"):
        busdecode.verify(GOOD, rules=CAPTURES / "rules_bissc.toml", threads=3)
    with pytest.raises(busdecode.UsageError, match=r"^--rate inf: expected a positive number"):
        busdecode.decode(GOOD, proto="bissc", rate=float("inf"))
    with pytest.raises(busdecode.UsageError, match=r"^timeout: expected seconds"):
        busdecode.subscribe("memq://", timeout=float("nan"))


def test_numpy_scalars_are_values_as_the_python_ones():
    # pandas hands out numpy scalars: np.bool_(True) is gray=1, np.float32 a threshold.
    np = pytest.importorskip("numpy")
    capture = CAPTURES / "ssi_tmc8100_gray25.vcd"
    want = list(busdecode.decode(capture, proto="ssi", opts={"gray": True, "bits": 25}))
    got = list(busdecode.decode(capture, proto="ssi",
                                opts={"gray": np.bool_(True), "bits": np.int64(25)}))
    assert got == want
    assert list(busdecode.decode(GOOD, proto="bissc", threshold=np.float32(1.5))) == \
        list(busdecode.decode(GOOD, proto="bissc", threshold=1.5))


def test_a_file_name_that_is_not_utf8(tmp_path):
    # os.listdir and Path.glob give such a name as a str with surrogates.
    name = tmp_path / "caf\udce9.vcd"
    name.write_bytes(GOOD.read_bytes())
    it = busdecode.decode(name, proto="bissc")
    assert len(list(it)) == len(list(busdecode.decode(GOOD, proto="bissc")))
    assert it.facts["file"] == str(name)
    assert busdecode.verify([name], rules=CAPTURES / "rules_bissc.toml").captures[0].capture \
        == str(name)
    missing = tmp_path / "caf\udce9-gone.vcd"
    with pytest.raises(busdecode.InputError) as raised:
        busdecode.decode(missing, proto="bissc")
    assert "caf\ufffd-gone.vcd: cannot open" in str(raised.value)


RULES = CAPTURES / "rules_bissc.toml"


@pytest.mark.parametrize("call, named", [
    (lambda: busdecode.decode(str(GOOD) + "\0junk", proto="bissc"),
     f"capture {str(GOOD) + chr(0) + 'junk'!r}"),
    (lambda: busdecode.decode("nope\0.vcd", proto="bissc"), r"capture 'nope\x00.vcd'"),
    (lambda: busdecode.read(b"nope\0.vcd", proto="bissc"), r"capture 'nope\x00.vcd'"),
    (lambda: busdecode.follow("nope\0.vcd", proto="bissc"), r"capture 'nope\x00.vcd'"),
    (lambda: busdecode.verify("a\0b", rules=RULES), r"capture 'a\x00b'"),
    (lambda: busdecode.verify([GOOD, "a\0b"], rules=RULES), r"capture 'a\x00b'"),
    (lambda: busdecode.verify(GOOD, rules=str(RULES) + "\0x"),
     f"rules {str(RULES) + chr(0) + 'x'!r}"),
], ids=["decode of a capture", "decode", "read", "follow", "verify", "verify of several",
        "verify rules"])
def test_a_path_with_a_nul_byte_is_refused_before_it_is_opened(call, named):
    # The C++ side would open the name cut short at the NUL: another file.
    with pytest.raises(busdecode.UsageError) as raised:
        call()
    assert str(raised.value) == named + ": contains a NUL byte"


@pytest.mark.parametrize("call, cli", [
    (dict(rate="abc"), ["--rate", "abc"]),
    (dict(rate=[1]), ["--rate", "[1]"]),
    (dict(rate=True), ["--rate", "True"]),
    (dict(threads="x"), ["--threads", "x"]),
    (dict(threads=2.7), ["--threads", "2.7"]),
    (dict(threads=True), ["--threads", "True"]),
    (dict(threads=2**40), ["--threads", str(2**40)]),
], ids=["rate text", "rate list", "rate bool", "threads text", "threads fraction",
        "threads bool", "threads beyond int"])
def test_a_thread_count_or_rate_that_is_no_number_is_refused_as_the_cli_does(call, cli):
    want = cli_error([GOOD, "--proto", "bissc"] + cli)
    for run in (busdecode.decode, busdecode.read, busdecode.follow):
        with pytest.raises(busdecode.UsageError) as raised:
            run(GOOD, proto="bissc", **call)
        assert str(raised.value) == want
    with pytest.raises(busdecode.UsageError) as raised:
        busdecode.verify(GOOD, rules=RULES, **call)
    assert str(raised.value) == want


@pytest.mark.parametrize("jobs", ["x", 1.5, True, None, 2**40])
def test_a_job_count_that_is_no_whole_number_is_a_usage_error_naming_it(jobs):
    with pytest.raises(busdecode.UsageError) as raised:
        busdecode.verify(GOOD, rules=RULES, jobs=jobs)
    # `decode verify --jobs` words it so, without the value.
    assert str(raised.value) == f"--jobs {jobs}: expected a whole number from 0 (all cores) to 256"


def test_whole_numbers_of_any_type_are_counts():
    np = pytest.importorskip("numpy")
    want = list(busdecode.decode(GOOD, proto="bissc"))
    for threads in (1, 2.0, "2", np.int64(1)):
        assert list(busdecode.decode(GOOD, proto="bissc", threads=threads)) == want
    for jobs in (1.0, "2", np.int32(1)):
        assert busdecode.verify(GOOD, rules=RULES, jobs=jobs, opts={"bits": 26}).passed
