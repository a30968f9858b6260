"""busdecode: decode logic-analyser captures of encoder and motion-control buses.

The same decoders, plugins and checks as the `decode` command, from Python:

    import busdecode
    for ev in busdecode.decode("capture.vcd", proto="bissc"):
        print(ev["start_ns"], ev["position"], ev["errors"])

    frames = busdecode.read("capture.vcd", proto="bissc")["bissc/frame"]  # a DataFrame

    result = busdecode.verify(["a.vcd", "b.vcd"], rules="rules.toml")
    assert result.passed, result.summary

Events are dicts with exactly the keys and values of `decode --format jsonl`: proto,
type, start_ns, end_ns, the decoder's fields in order, errors. Bad input raises
InputError and a wrong call UsageError, whose text is the line `decode` prints after
"decode: ".
"""

from __future__ import annotations

import contextlib
import gc
import importlib
import os
from dataclasses import dataclass, field
from typing import Any, Dict, Iterable, Iterator, List, Mapping, Optional, Sequence, Union

from . import _busdecode
from ._busdecode import Error, InputError, UsageError

__all__ = [
    "Error",
    "InputError",
    "UsageError",
    "decoders",
    "decode",
    "follow",
    "read",
    "verify",
    "subscribe",
    "RuleResult",
    "CaptureResult",
    "VerifyResult",
]

Protos = Union[str, Sequence[str]]
Assignments = Optional[Mapping[str, Any]]
PathLike = Union[str, bytes, "os.PathLike[str]", "os.PathLike[bytes]"]

_RATE = "expected a positive number of Hz (like 24 MHz, 2.5 Hz or 1e6)"
_THREADS = "expected 1 (read and decode on one thread) or 2 (read ahead on a second)"
_JOBS = "expected a whole number from 0 (all cores) to 256"


def _scalar(value: Any) -> Any:
    """A numpy scalar (np.bool_, np.float32, as pandas hands them out) as the Python one."""
    if hasattr(value, "item") and callable(value.item) and not isinstance(value, str):
        return value.item()
    return value


def _text(value: Any) -> str:
    """An option value as the command line writes it (True -> "1")."""
    value = _scalar(value)
    if isinstance(value, bool):
        return "1" if value else "0"
    return str(value)


def _shown(value: Any) -> str:
    """A wrong argument as a message names it: as typed after the option on the command
    line, quoted only where that would not read as one word on one line."""
    if isinstance(value, str):
        plain = value != "" and value.isprintable() and value.strip() == value
        return value if plain else repr(value)
    return str(value)


def _path(path: PathLike, what: str = "capture") -> bytes:
    """A path as the file system's bytes: a name that is not UTF-8 (a Latin-1 one from
    os.listdir or Path.glob) reaches the same file. A NUL byte is refused: the C++ side
    would open the name cut short at it, another file."""
    name = os.fsencode(path)
    if b"\0" in name:
        raise UsageError(f"{what} {os.fsdecode(name)!r}: contains a NUL byte")
    return name


def _rate(rate: Any) -> Optional[float]:
    """rate= as Hz. What is no number is refused here, in `decode --rate`'s words; the
    C++ side refuses the numbers that are no rate (0, negative, inf)."""
    if rate is None:
        return None
    value = _scalar(rate)
    if not isinstance(value, bool):
        with contextlib.suppress(TypeError, ValueError, OverflowError):
            return float(value)
    raise UsageError(f"--rate {_shown(rate)}: {_RATE}")


def _count(option: str, given: Any, expected: str) -> int:
    """threads= or jobs= as an int: a whole number (2, 2.0, "2", a numpy integer). A bool,
    a fraction or text that is no number is refused, in the words of `decode OPTION`;
    so is an int the C++ side could not take (beyond 32 bits). The C++ side checks the
    range."""
    value = _scalar(given)
    if isinstance(value, str):
        with contextlib.suppress(ValueError):
            value = int(value)
    if isinstance(value, float) and value.is_integer():
        value = int(value)
    if isinstance(value, int) and not isinstance(value, bool) and -2**31 <= value < 2**31:
        return value
    raise UsageError(f"{option} {_shown(given)}: {expected}")


def _assignments(what: str, given: Assignments) -> List[str]:
    if given is None:
        return []
    if not isinstance(given, Mapping):
        raise UsageError(f"{what}: expected a dict of KEY: VALUE, not {type(given).__name__}")
    return [f"{key}={_text(value)}" for key, value in given.items()]


def _protos(proto: Protos) -> List[str]:
    if isinstance(proto, str):
        return [proto]
    if proto is None:
        return []
    return [str(p) for p in proto]


Threshold = Union[None, float, str, Mapping[str, float]]


def _thresholds(threshold: Threshold) -> List[str]:
    """threshold= as --threshold options: one for every line, or one per named signal."""
    if threshold is None:
        return []
    if isinstance(threshold, Mapping):
        return [f"{name}={_text(volts)}" for name, volts in threshold.items()]
    threshold = _scalar(threshold)
    if isinstance(threshold, (int, float, str)) and not isinstance(threshold, bool):
        return [_text(threshold)]
    raise UsageError("threshold: expected volts (1.5) or a dict of SIGNAL: volts, "
                     f"not {type(threshold).__name__}")


def _hysteresis(hysteresis: Optional[float]) -> Optional[str]:
    return None if hysteresis is None else _text(hysteresis)


def _capture_args(path: PathLike, proto: Protos, map: Assignments, opts: Assignments,
                  rate: Optional[float], threads: int, threshold: Threshold = None,
                  hysteresis: Optional[float] = None) -> "_busdecode.CaptureArgs":
    args = _busdecode.CaptureArgs()
    args.path = _path(path)
    args.protos = _protos(proto)
    args.maps = _assignments("map", map)
    args.opts = _assignments("opts", opts)
    args.rate = _rate(rate)
    args.threads = _count("--threads", threads, _THREADS)
    args.thresholds = _thresholds(threshold)
    args.hysteresis = _hysteresis(hysteresis)
    return args


def decoders() -> List[Dict[str, Any]]:
    """Every decoder there is, as `decode --list` shows them.

    Each is a dict: id, name, description, roles (name, required, aliases, help),
    options (key, kind, default, choices, min, max, auto, help), events (type, help,
    fields, kinds: each field's kind of value, "int", "number", "bool", "text", "list"
    or "any") and need_one_of (optional roles of which one must be bound). A field
    "<status_bits>" stands for the fields that option names. Every decoder also takes
    the option glitch_ns (ignore pulses shorter than this, in ns).
    """
    return _busdecode.decoders()


def decode(path: PathLike, proto: Protos, map: Assignments = None, opts: Assignments = None,
           rate: Optional[float] = None, threads: int = 2, realtime: bool = False,
           threshold: Threshold = None,
           hysteresis: Optional[float] = None) -> "_busdecode.Events":
    """Decodes a capture; returns an iterator of events, each a dict.

    path: a VCD, CSV or sigrok .sr capture ("-" reads standard input).
    proto: the decoder id ("bissc", "ssi", "spi", "tmc8100", "tmcl", "uart"), or a list
        of them to decode several buses in one pass (see decoders()).
    map: roles bound to capture signals, {"clk": "MA", "data": "SL"}; with several
        decoders a key may be scoped, {"ssi.clk": "D0"}. Unbound roles are bound by
        signal name.
    opts: decoder options, {"bits": 26, "crc": "auto"}, scoped the same way
        ({"ssi.gray": True}).
    rate: sample rate in Hz for a CSV without a time column.
    threads: 2 reads ahead on a second thread, 1 reads and decodes on one.
    realtime: hands events out no faster than the capture's own time runs.
    threshold: for analog lines (scope captures), the switching level in volts for
        every line (1.5) or per signal ({"CH1": 1.5, "CH2": 0.8}), as --threshold;
        None: found from the data (midway between the line's two main levels).
    hysteresis: the Schmitt trigger's band in volts (--hysteresis); None: a tenth of
        the line's swing.

    The dicts have exactly the keys and values of `decode --format jsonl` (ints for
    integers, None for nulls, a list of error strings). The capture is decoded on a
    thread of its own into a small bounded queue while you iterate, so memory stays
    constant however long the capture. The iterator's `facts` property describes the
    capture (file, format, bindings; edges and the decoders' advice once it ended);
    close() (or leaving a `with` block) stops decoding early.

    Raises UsageError (unknown decoder, option or role; bad value) or InputError (the
    capture cannot be read, a role cannot be bound) at once; an input error found
    further into the capture is raised by the iteration, after the events before it.

    >>> for ev in busdecode.decode("enc.vcd", proto="bissc", opts={"bits": 26}):
    ...     if ev["errors"]:
    ...         print(ev["start_ns"], ev["errors"])
    """
    return _busdecode.decode_events(
        _capture_args(path, proto, map, opts, rate, threads, threshold, hysteresis), False,
        bool(realtime))


def follow(path_or_stream: Union[PathLike, Any], proto: Protos, map: Assignments = None,
           opts: Assignments = None, rate: Optional[float] = None, threads: int = 2,
           threshold: Threshold = None,
           hysteresis: Optional[float] = None) -> "_busdecode.Events":
    """Follows a live capture (`decode --follow`): an iterator of event dicts.

    path_or_stream: a file that is still being written (the iterator waits for more of
    it, and ends only when closed), "-" for standard input, or an open pipe or file
    object (anything with fileno(); the iterator ends when the writer closes it;
    sys.stdin is "-").
    Each event comes out as soon as it is decoded. Otherwise as decode(); stop with
    close(), a `with` block, or Ctrl-C. The call itself returns once the capture's
    header has arrived (the decoders are bound to its signals then): start the writer
    first, or on another thread.
    """
    args = _capture_args(_followed(path_or_stream), proto, map, opts, rate, threads,
                         threshold, hysteresis)
    return _busdecode.decode_events(args, True, False)


def _followed(path_or_stream: Union[PathLike, Any]) -> PathLike:
    """What follow() opens: a path as it is, an open stream through its descriptor.
    Standard input is "-", so that messages name it <stdin> as `decode -` does; another
    descriptor is /dev/fd/N, also in messages (the C++ side takes no separate name)."""
    if not hasattr(path_or_stream, "fileno"):
        return path_or_stream
    fd = path_or_stream.fileno()
    return "-" if fd == 0 else f"/dev/fd/{fd}"


def _pandas_array(pd: Any, kind: str, values: Any, mask: Any) -> Any:
    if kind in ("Int64", "UInt64"):
        return pd.arrays.IntegerArray(values, mask, copy=False)
    if kind == "boolean":
        return pd.arrays.BooleanArray(values, mask, copy=False)
    return values  # float64, int64 and object columns come as numpy arrays already


def read(path: PathLike, proto: Protos, map: Assignments = None, opts: Assignments = None,
         rate: Optional[float] = None, threads: int = 2, threshold: Threshold = None,
         hysteresis: Optional[float] = None) -> Dict[str, Any]:
    """Decodes a whole capture into pandas DataFrames, one per "proto/type".

    Arguments as decode(). Returns {"bissc/frame": DataFrame, "bissc/register": ...}
    in the order the kinds first occur. Each DataFrame has one row per event and the
    columns start_ns, end_ns (int64), the decoder's fields in their jsonl order, and
    errors (a list of strings per row). Integer fields are nullable integers (Int64;
    UInt64 beyond int64), flags nullable booleans, other numbers float64 (NaN for
    null), text and lists objects. The columns are built in C++ as flat buffers while
    decoding, not as a Python object per field. A field an event lacks is null in its
    row. Every field the decoder declares (decoders(), "kinds") is a column of its
    declared type, also when no event of the capture had a value for it (after the
    fields the events gave): a table's columns and types do not depend on which fields
    a capture's events happened to fill.

    Without pandas, returns {"proto/type": [event dict, ...]} instead.
    """
    args = _capture_args(path, proto, map, opts, rate, threads, threshold, hysteresis)
    try:
        # Imported by name: mypy then types pandas as Any, so the module type-checks alike
        # whichever pandas type packages a machine has installed.
        pd = importlib.import_module("pandas")
    except ImportError:
        tables: Dict[str, List[Dict[str, Any]]] = {}
        for ev in _busdecode.decode_events(args, False, False):
            tables.setdefault(f"{ev['proto']}/{ev['type']}", []).append(ev)
        return tables
    frames = {}
    with _collector_paused():
        for name, columns in _busdecode.read_columns(args).items():
            data = {k: _pandas_array(pd, kind, values, mask) for k, kind, values, mask in columns}
            frames[name] = pd.DataFrame(data, copy=False)
    return frames


@contextlib.contextmanager
def _collector_paused() -> Iterator[None]:
    """Holds off Python's cyclic garbage collector while read() makes its objects.

    A capture's columns hold a fresh list per row (errors) and no cycles; collections
    while they are made would walk them again and again (half of read()'s time for a
    UART capture's million rows). Afterwards the collector is as it was.
    """
    was_enabled = gc.isenabled()
    gc.disable()
    try:
        yield
    finally:
        if was_enabled:
            gc.enable()


@dataclass(frozen=True)
class RuleResult:
    """One rule checked on one capture."""

    name: str  # "bissc.max_crc_errors": the rules table and the rule
    proto: str
    rule: str
    passed: bool
    message: str  # what was seen, and where the first offence was
    # when it failed: the first offending event, or for a count limit above 0 the event
    # that passed the limit; None when it passed
    first_ns: Optional[float]
    offending: int  # how many events broke the rule


@dataclass(frozen=True)
class CaptureResult:
    """The verdict on one capture: passed, the rules it failed, or why it is unreadable."""

    capture: str
    passed: bool
    error: Optional[str]  # the input error that made it unreadable, else None
    rules: List[RuleResult]
    events: str  # "bissc 1000 frames"
    seconds: float
    hints: List[str]
    summary: str  # the line `decode verify` prints: "PASS cap.vcd  (...)"

    @property
    def failed(self) -> List[RuleResult]:
        """The rules this capture broke."""
        return [r for r in self.rules if not r.passed]


@dataclass(frozen=True)
class VerifyResult:
    """Every capture's verdict; passed only if all passed (none unreadable)."""

    captures: List[CaptureResult]
    totals: str  # "3 captures: 2 passed, 1 failed, 0 unreadable; ..."
    passed: bool = field(init=False)

    def __post_init__(self) -> None:
        object.__setattr__(self, "passed", all(c.passed for c in self.captures))

    @property
    def summary(self) -> str:
        """What `decode verify` prints: a line per capture, then the totals."""
        return "\n".join([c.summary for c in self.captures] + [self.totals])

    @property
    def failed(self) -> List[CaptureResult]:
        """The captures that failed or could not be read."""
        return [c for c in self.captures if not c.passed]

    def __iter__(self) -> Iterator[CaptureResult]:
        return iter(self.captures)

    def __len__(self) -> int:
        return len(self.captures)

    def __getitem__(self, i: int) -> CaptureResult:
        return self.captures[i]


def verify(paths: Union[PathLike, Iterable[PathLike]], rules: PathLike, proto: Protos = (),
           map: Assignments = None, opts: Assignments = None, rate: Optional[float] = None,
           jobs: int = 0, threads: int = 2, threshold: Threshold = None,
           hysteresis: Optional[float] = None) -> VerifyResult:
    """Checks captures against a rules file, as `decode verify` does.

    paths: one capture or several; rules: the TOML rules file (see the README, "Rules
    for verify"); proto, map, opts, rate: on top of the rules' [decode] table, as on the
    command line; threshold, hysteresis: for analog lines, as in decode(); jobs:
    captures checked at once (0: one per core).

    Returns a VerifyResult: .passed, .summary (the lines `decode verify` prints),
    .captures (a CaptureResult each, with .failed rules), so that in pytest

        result = busdecode.verify(captures, rules="rules.toml")
        assert result.passed, result.summary

    An unreadable capture is a failed CaptureResult with its .error, and so is one its
    decoder could not be set up for (no decoder chosen, options that do not fit together):
    `decode verify` exits 2 for both. A bad rules file, or an unknown decoder, option or
    option value (they may come from the rules) raises InputError; a bad jobs, rate or
    threads argument UsageError.
    """
    if isinstance(paths, (str, bytes, os.PathLike)):
        paths = [paths]
    captures = [_path(p) for p in paths]
    if not captures:
        raise UsageError("no capture given")
    verdicts, totals = _busdecode.verify_captures(
        captures, _path(rules, "rules"), _protos(proto), _assignments("map", map),
        _assignments("opts", opts), _rate(rate), _count("--jobs", jobs, _JOBS),
        _count("--threads", threads, _THREADS), _thresholds(threshold),
        _hysteresis(hysteresis))
    results = []
    for v in verdicts:
        v["rules"] = [RuleResult(**r) for r in v["rules"]]
        results.append(CaptureResult(**v))
    return VerifyResult(results, totals)


def subscribe(url: Optional[str] = None, channels: Union[None, str, Sequence[str]] = None,
              timeout: Optional[float] = None,
              until_end: bool = False) -> "_busdecode.Subscription":
    """The live feed of a `decode --lcm` run: an iterator of event dicts.

    url: the LCM URL the decoder publishes on (None: LCM's default,
        udpm://239.255.76.67:7667?ttl=0).
    channels: the event channels wanted, names or regular expressions
        ("DECODE_BISSC_FRAME", "DECODE_SSI_.*"); None: every event.
    timeout: end the iteration after this many seconds without a message (None: never).
    until_end: end it when the publisher says its run ended, after its last capture
    (DECODE_STATUS "done"; each capture's "end" does not end it).

    Every event arrives as its annotation message (DECODE_EVENTS), decoded with the
    project's own LCM type; the dicts equal decode()'s for the same events. UDP
    multicast needs a route: on a machine without a network,
    `ip link set lo multicast on; ip route add 224.0.0.0/4 dev lo`. UDP also drops
    datagrams when a subscriber falls behind: the iterator's .lost counts the events
    known to be missing (gaps in their numbering, and those the publisher's status
    counted that never came), so a check can assert sub.lost == 0. Stop with close(), a
    `with` block, or Ctrl-C.
    """
    if isinstance(channels, str):
        channels = [channels]
    if timeout is not None and not float(timeout) >= 0:
        raise UsageError(f"timeout: expected seconds, 0 or more, not {timeout}")
    return _busdecode.subscribe_feed(url or "", list(channels or []), timeout, bool(until_end))
