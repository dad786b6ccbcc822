"""Reading and writing LCM event logs (the files lcm-logger writes).

Each event: sync word 0xEDA1DA01, event number (int64), timestamp in us
(int64), channel length (int32), data length (int32), channel, data; all
big-endian. No LCM installation is needed.
"""
import struct
from typing import Iterator, NamedTuple

SYNC = 0xEDA1DA01
_HEADER = struct.Struct(">IqqII")


class Event(NamedTuple):
    number: int
    timestamp: int
    channel: str
    data: bytes


class LogError(Exception):
    pass


def read_events(path: str) -> Iterator[Event]:
    """Yields the events of a log; raises LogError on a damaged file."""
    with open(path, "rb") as f:
        while True:
            header = f.read(_HEADER.size)
            if not header:
                return
            if len(header) < _HEADER.size:
                raise LogError(f"{path}: truncated event header")
            sync, number, timestamp, channel_len, data_len = _HEADER.unpack(header)
            if sync != SYNC:
                raise LogError(f"{path}: bad sync word 0x{sync:08x}")
            channel = f.read(channel_len)
            data = f.read(data_len)
            if len(channel) < channel_len or len(data) < data_len:
                raise LogError(f"{path}: truncated event {number}")
            yield Event(number, timestamp, channel.decode("utf-8", "replace"), data)


def write_events(path: str, events) -> None:
    with open(path, "wb") as f:
        for e in events:
            channel = e.channel.encode()
            f.write(_HEADER.pack(SYNC, e.number, e.timestamp, len(channel), len(e.data)))
            f.write(channel)
            f.write(e.data)
