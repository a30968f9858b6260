"""decode(), read() and decoders() against the CLI on every decoder's captures."""

import gc
import itertools
import math
import random
import sys
import tracemalloc

import pandas as pd
import pytest

import busdecode
from busdecode import _busdecode
from conftest import CAPTURES, cli_events, run_cli, BIN


def test_decode_fields_equal_the_cli_jsonl(case):
    capture, protos, opts = case
    events = list(busdecode.decode(CAPTURES / capture, proto=protos, opts=opts))
    expected = cli_events(capture, protos, opts)
    assert events, "no events: the case proves nothing"
    assert events == expected
    for got, want in zip(events, expected):  # same keys in the same order, same types
        assert list(got) == list(want)
        assert [type(v) for v in got.values()] == [type(v) for v in want.values()]


def test_decode_threads_1_gives_the_same_events():
    path = CAPTURES / "tmc8100_ssi_dialogue.vcd"
    two = list(busdecode.decode(path, proto=["tmc8100", "ssi"]))
    one = list(busdecode.decode(path, proto=["tmc8100", "ssi"], threads=1))
    assert one == two


def test_decode_facts_and_advice_match_the_cli_hints():
    capture = "bissc_errors.vcd"
    it = busdecode.decode(CAPTURES / capture, proto="bissc")
    assert it.facts["format"] == "vcd"
    assert {b["role"] for b in it.facts["bindings"]} == {"ma", "sl"}
    list(it)
    rc, _, err = run_cli([str(BIN / "decode"), str(CAPTURES / capture), "--proto", "bissc",
                          "--format", "jsonl"])
    hints = [f"decode: {CAPTURES / capture}: hint: {a}" for a in it.facts["advice"]]
    assert hints and err.splitlines() == hints
    assert it.facts["edges"] > 0


def test_decode_scoped_map_and_options():
    # The roles bound by name explicitly, and an option scoped to one of two decoders.
    events = list(busdecode.decode(CAPTURES / "tmc8100_ssi_dialogue.vcd", proto=["tmc8100", "ssi"],
                                   opts={"ssi.bits": 25}))
    assert events == cli_events("tmc8100_ssi_dialogue.vcd", ["tmc8100", "ssi"], {"ssi.bits": 25})


def test_decode_stops_early_and_closes():
    it = busdecode.decode(CAPTURES / "bissc_1mhz_26bit.vcd", proto="bissc")
    first = list(itertools.islice(it, 2))
    assert len(first) == 2
    it.close()
    assert list(it) == []
    with busdecode.decode(CAPTURES / "bissc_1mhz_26bit.vcd", proto="bissc") as it2:
        assert next(it2)["type"] == "frame"


def test_decode_memory_stays_bounded_while_iterating():
    # Python-side memory while iterating one event at a time: the queue is bounded, so
    # what is held does not grow with the number of events consumed.
    path = CAPTURES / "tmc8100_ssi_dialogue.vcd"
    tracemalloc.start()
    it = busdecode.decode(path, proto=["tmc8100", "ssi"])
    n = 0
    for _ in it:
        n += 1
    current, _peak = tracemalloc.get_traced_memory()
    tracemalloc.stop()
    assert n > 50 and current < 200_000


def _row_dicts(df):
    rows = []
    for rec in df.to_dict("records"):
        rows.append({k: (None if v is pd.NA or (isinstance(v, float) and math.isnan(v)) else v)
                     for k, v in rec.items()})
    return rows


def test_read_tables_hold_the_cli_events(case):
    capture, protos, opts = case
    frames = busdecode.read(CAPTURES / capture, proto=protos, opts=opts)
    expected = cli_events(capture, protos, opts)
    by_table = {}
    for ev in expected:
        by_table.setdefault(f"{ev['proto']}/{ev['type']}", []).append(ev)
    assert list(frames) == list(by_table)
    for name, df in frames.items():
        assert df["start_ns"].dtype == "int64" and df["end_ns"].dtype == "int64"
        rows = _row_dicts(df)
        want = by_table[name]
        assert len(rows) == len(want)
        for got, ev in zip(rows, want):
            proto, typ = name.split("/")
            full = {"proto": proto, "type": typ, **got}
            # A row holds every column of its table; a field this event lacks is null.
            assert {k: v for k, v in full.items() if k in ev} == ev
            assert all(full[k] is None for k in full if k not in ev)


@pytest.mark.parametrize("fields", [True, False])
def test_count_events_counts_the_cli_events(case, fields):
    # bench/python_read.py's floors: read()'s decoding with the events only counted, with
    # and without their fields; leaving the fields out must not lose or add an event.
    capture, protos, opts = case
    args = busdecode._capture_args(CAPTURES / capture, protos, None, opts, None, 2)
    assert _busdecode.count_events(args, fields) == len(cli_events(capture, protos, opts))


def write_uart_vcd(path, data, baud=1_000_000):
    """`data` sent 8N1 on one line `rx`, an idle bit between bytes, as a VCD."""
    bit = 10**9 // baud
    lines = ["$timescale 1 ns $end", "$scope module t $end", "$var wire 1 ! rx $end",
             "$upscope $end", "$enddefinitions $end", "#0", "1!"]
    t, level = 2 * bit, 1
    for byte in data:
        for b in [0] + [(byte >> i) & 1 for i in range(8)] + [1, 1]:
            if b != level:
                lines += [f"#{t}", f"{b}!"]
                level = b
            t += bit
    lines.append(f"#{t}")
    path.write_text("\n".join(lines) + "\n")


def test_decode_of_many_batches_equals_the_cli_jsonl(tmp_path):
    # Thousands of events come in many batches from the decoding thread, whose storage
    # is filled again once the iterator has taken them: each event must still be its own.
    rng = random.Random(5)
    data = bytes(rng.randrange(256) for _ in range(20000))  # 40 batches
    path = tmp_path / "uart.vcd"
    write_uart_vcd(path, data)
    events = list(busdecode.decode(path, proto="uart", opts={"baud": 1000000}))
    assert [e["value"] for e in events] == list(data)
    assert events == cli_events(path, ["uart"], {"baud": 1000000})


def test_one_iterator_is_read_by_one_thread_at_a_time(tmp_path):
    # As a generator: a second thread reading the same iterator while the first waits for
    # events gets ValueError, never a crash, and no event is lost or given twice.
    import threading
    data = bytes(range(256)) * 200
    path = tmp_path / "uart.vcd"
    write_uart_vcd(path, data)
    it = busdecode.decode(path, proto="uart", opts={"baud": 1000000})
    got, refused = [[], []], []

    def read(i):
        while True:
            try:
                got[i].append(next(it)["value"])
            except StopIteration:
                return
            except ValueError as e:
                refused.append(str(e))

    threads = [threading.Thread(target=read, args=(i,)) for i in range(2)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert sorted(got[0] + got[1]) == sorted(data)
    assert all(r == "decode(): already being read on another thread" for r in refused)


def test_close_from_another_thread_ends_the_iteration(tmp_path):
    # A watchdog or GUI thread stops a long decode while the main thread iterates.
    import threading
    path = tmp_path / "uart.vcd"
    write_uart_vcd(path, bytes(range(256)) * 100)
    for delay in (0, 0.001, 0.005, 0.02):
        it = busdecode.decode(path, proto="uart", opts={"baud": 1000000})
        timer = threading.Timer(delay, it.close)
        timer.start()
        values = [e["value"] for e in it]
        timer.join()
        assert values == list(bytes(range(256)) * 100)[:len(values)]
        with pytest.raises(StopIteration):
            next(it)


def test_read_column_types():
    frames = busdecode.read(CAPTURES / "bissc_1mhz_26bit.vcd", proto="bissc")
    df = frames["bissc/frame"]
    assert str(df["position"].dtype) == "Int64"
    assert str(df["crc_ok"].dtype) == "boolean"
    assert df["clock_hz"].dtype == "float64"
    assert df["errors"].map(type).eq(list).all()
    reg = frames["bissc/register"]
    assert reg["echo"].isna().any() and str(reg["echo"].dtype) == "Int64"
    # Each row's error list is its own.
    errs = busdecode.read(CAPTURES / "bissc_errors.vcd", proto="bissc")["bissc/frame"]["errors"]
    faulty = [e for e in errs if e]
    assert faulty
    faulty[0].append("mine")
    assert sum("mine" in e for e in errs) == 1


@pytest.mark.parametrize("enabled", [True, False])
def test_read_leaves_the_garbage_collector_as_it_was(enabled):
    # read() holds the collector off while it makes its objects, and then gives it back,
    # also when it fails.
    was = gc.isenabled()
    try:
        gc.enable() if enabled else gc.disable()
        assert busdecode.read(CAPTURES / "uart_rxtx_9600_8n1.vcd", proto="uart")
        assert gc.isenabled() == enabled
        with pytest.raises(busdecode.InputError):
            busdecode.read(CAPTURES / "no_such_capture.vcd", proto="uart")
        assert gc.isenabled() == enabled
    finally:
        gc.enable() if was else gc.disable()


def test_read_keeps_no_reference_to_none():
    # The object columns are filled in C++: a null row must hold one reference to None,
    # given back with the DataFrame (Python 3.11: None has a reference count). A row's
    # reference kept or dropped would move the count by a null row each, three reads.
    def read_once():
        # tmc8100/reply's text is a text column with None in it; bissc_errors.vcd read
        # as 26-bit frames has columns with no value at all (position...).
        frames = dict(
            busdecode.read(CAPTURES / "tmc8100_faults.vcd", proto=["tmc8100", "ssi"]),
            **busdecode.read(CAPTURES / "bissc_errors.vcd", proto="bissc"))
        return sum(df[k].isna().sum() for df in frames.values() for k in df
                   if df[k].dtype == object)

    nulls = read_once()
    assert nulls > 0  # rows whose object is None
    gc.collect()
    before = sys.getrefcount(None)
    for _ in range(3):
        read_once()
    gc.collect()
    assert abs(sys.getrefcount(None) - before) < nulls


def test_decoders_list_what_decode_list_shows():
    listed = busdecode.decoders()
    rc, out, _ = run_cli([str(BIN / "decode"), "--list"])
    assert rc == 0
    ids = [d["id"] for d in listed]
    assert ids == ["bissc", "spi", "ssi", "tmc8100", "tmcl", "uart"]
    for d in listed:
        assert f"{d['id']}  {d['name']}" in out
        for o in d["options"]:
            assert f"    {o['key']:<14} {o['kind']:<7} default {o['default'] or '-':<8}" in out
        for r in d["roles"]:
            assert f"    {r['name']:<10} {'required' if r['required'] else 'optional':<9}" in out
    bissc = listed[0]
    assert {"ma", "sl"} <= {r["name"] for r in bissc["roles"]}
    assert "frame" in {e["type"] for e in bissc["events"]}


def test_help_is_useful():
    doc = busdecode.decode.__doc__
    for word in ("proto", "map", "opts", "rate", "jsonl", "InputError", "constant"):
        assert word in doc


def _declared(proto, type_):
    """The declaration of one event type, as busdecode.decoders() gives it."""
    decoder = next(d for d in busdecode.decoders() if d["id"] == proto)
    return next(e for e in decoder["events"] if e["type"] == type_)


def test_read_types_columns_by_the_declarations():
    # bissc_errors.vcd read as 26-bit frames: no frame is complete, so no event has a
    # position or a CRC; the columns are still those of a capture that has them.
    full = busdecode.read(CAPTURES / "bissc_1mhz_26bit.vcd", proto="bissc")["bissc/frame"]
    short = busdecode.read(CAPTURES / "bissc_errors.vcd", proto="bissc")["bissc/frame"]
    assert short["position"].isna().all() and short["crc_ok"].isna().all()
    assert list(short.columns) == list(full.columns)
    assert dict(short.dtypes) == dict(full.dtypes)
    # A declared field no event gave (parity_ok: no parity on this encoder) is a column
    # of its kind, all null, after the fields the events gave.
    ssi = busdecode.read(CAPTURES / "ssi_posital_lead.csv", proto="ssi",
                         opts={"bits": 24})["ssi/frame"]
    assert str(ssi["parity_ok"].dtype) == "boolean" and ssi["parity_ok"].isna().all()
    declared = _declared("ssi", "frame")
    named = [f for f in declared["fields"] if not f.startswith("<")]
    assert sorted(ssi.columns) == sorted(["start_ns", "end_ns", "errors"] + named)


def test_decoders_declare_each_fields_kind_as_decode_list_shows_it():
    rc, out, _ = run_cli([str(BIN / "decode"), "--list"])
    assert rc == 0
    dtype_of = {"int": "Int64", "bool": "boolean", "number": "float64"}
    for d in busdecode.decoders():
        for e in d["events"]:
            assert list(e["kinds"]) == e["fields"]
            shown = ", ".join(f if k == "any" else f"{f}:{k}" for f, k in e["kinds"].items())
            assert f"    {e['type']:<14} {e['help']} ({shown})" in out
            assert set(e["kinds"].values()) <= {"int", "number", "bool", "text", "list", "any"}
    bissc = _declared("bissc", "frame")["kinds"]
    assert (bissc["position"], bissc["crc_ok"], bissc["clock_hz"]) == ("int", "bool", "number")
    frame = busdecode.read(CAPTURES / "bissc_1mhz_26bit.vcd", proto="bissc")["bissc/frame"]
    for field, kind in bissc.items():
        if kind in dtype_of:
            assert str(frame[field].dtype) == dtype_of[kind], field
