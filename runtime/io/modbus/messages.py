"""What a Modbus connection's parts pass each other: its settings, one
request (Transaction) and how it ended (Outcome). Plain data, below the
link (link.py), the reply checks (replies.py) and the in-memory wire
(wire.py), which all read them."""

from __future__ import annotations

from dataclasses import dataclass, field


@dataclass(frozen=True)
class LinkSettings:
    name: str  # the [[modbus]] name, for messages
    transport: str  # "tcp" | "rtu"
    host: str = "127.0.0.1"
    port: int = 502
    device: str = ""  # serial port
    baud: int = 19200
    parity: str = "N"
    stop_bits: int = 1
    data_bits: int = 8
    frame_gap_s: float | None = None  # None: 3.5 characters (see frame_gap)
    timeout_s: float = 0.1
    retries: int = 1  # requests sent again after a timeout
    reconnect_s: float = 1.0
    reconnect_max_s: float = 10.0


def frame_gap(baud: int, parity: str, stop_bits: int, data_bits: int = 8) -> float:
    """The RTU idle time between frames: 3.5 characters, 1.75 ms above
    19200 bit/s (Modbus over serial line V1.02, 2.5.1.1)."""
    if baud > 19200:
        return 0.00175
    char_bits = 1 + data_bits + (0 if parity == "N" else 1) + stop_bits
    return 3.5 * char_bits / baud


@dataclass
class Transaction:
    """One request. For writes, values holds the registers (ints) or coils
    (bools); for FC 23, offset/count are the read and write_offset/values the
    write."""

    unit: int
    function: int
    offset: int = 0
    count: int = 0
    values: tuple = ()
    write_offset: int = 0


@dataclass
class Outcome:
    error: int = 0
    values: list = field(default_factory=list)
    response_s: float = 0.0  # request sent -> answer: real time, or the modelled time in memory
    message: str = ""
    late_s: float = 0.0  # in memory (virtual time): no answer; the outcome counts this much later
