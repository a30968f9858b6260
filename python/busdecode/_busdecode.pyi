"""Type stubs of the compiled half of busdecode (use the functions of the package)."""

from typing import Any, Dict, Iterator, List, Optional, Sequence, Tuple, Union

Event = Dict[str, Any]

class Error(Exception):
    """Base of busdecode's errors: str(e) is the line `decode` prints."""

class InputError(Error):
    """Bad input: an unreadable capture or rules file, an unbound role."""

class UsageError(Error):
    """A wrong call: unknown decoder, option, role or argument value."""

class CaptureArgs:
    path: Union[str, bytes]  # bytes: the file system's own (os.fsencode)
    protos: List[str]
    maps: List[str]
    opts: List[str]
    rate: Optional[float]
    thresholds: List[str]
    hysteresis: Optional[str]
    threads: int
    def __init__(self) -> None: ...

class Events(Iterator[Event]):
    """Events of one capture as they are decoded."""

    def __iter__(self) -> "Events": ...
    def __next__(self) -> Event: ...
    def close(self) -> None: ...
    def __enter__(self) -> "Events": ...
    def __exit__(self, *args: Any) -> None: ...
    @property
    def facts(self) -> Dict[str, Any]: ...

class Subscription(Iterator[Event]):
    """Events received from a decode --lcm feed."""

    def __iter__(self) -> "Subscription": ...
    def __next__(self) -> Event: ...
    def close(self) -> None:
        """Stops receiving; the iteration then ends."""
    def __enter__(self) -> "Subscription": ...
    def __exit__(self, *args: Any) -> None: ...
    @property
    def lost(self) -> int:
        """Events known to be lost so far (gaps in their numbering, never-came ones)."""

def decoders() -> List[Dict[str, Any]]: ...
def decode_events(args: CaptureArgs, follow: bool, realtime: bool) -> Events: ...
def read_columns(args: CaptureArgs) -> Dict[str, List[Tuple[str, str, Any, Any]]]: ...
def count_events(args: CaptureArgs, fields: bool = True) -> int: ...
def verify_captures(captures: Sequence[Union[str, bytes]], rules: Union[str, bytes], protos: List[str], maps: List[str],
                    opts: List[str], rate: Optional[float], jobs: int,
                    threads: int, thresholds: List[str],
                    hysteresis: Optional[str]) -> Tuple[List[Dict[str, Any]], str]: ...
def subscribe_feed(url: str, channels: List[str], timeout: Optional[float],
                   until_end: bool) -> Subscription: ...
