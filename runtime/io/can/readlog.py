"""`softplc log FILE` for a CAN log `--bus-log` wrote (wire.py): python-can
reads it back (the reader of its ending), and each frame is printed with
its time in engine seconds, its [[can]] bus, Tx or Rx, the COB-ID and the
data, and the words of the protocol whose frame it is (Bus.frame_text of
every registered bus: CANopen, a plain-CAN device).

       0.000000 can0 Tx 000 [2] 01 28                    NMT start: motor (40)
       0.000000 can0 Rx 728 [1] 00                       motor (40) boot-up
"""

from __future__ import annotations

from collections.abc import Iterator
from pathlib import Path

import can
from can.io.player import MESSAGE_READERS

from ...plugin.registry import registry


def read_log(path: Path, config) -> Iterator[str] | None:
    """The frames of path decoded, or None when python-can reads no such file."""
    suffixes = [s.lower() for s in path.suffixes]
    ending = suffixes[-2] if suffixes[-1:] == [".gz"] and len(suffixes) > 1 else (suffixes or [""])[-1]
    if ending not in MESSAGE_READERS or path.name.lower().endswith(".modbus.log"):  # that one is Modbus's
        return None
    return _lines(path, [bus.name for bus in config.can], config)


def _lines(path: Path, buses: list, config) -> Iterator[str]:
    texts = [bus.frame_text(config) for bus in registry().buses if bus.frame_text is not None]
    try:
        for msg in can.LogReader(path):
            bus = _bus(msg.channel, buses)
            data = "" if msg.is_remote_frame else bytes(msg.data).hex(" ").upper()
            cob = f"{msg.arbitration_id:08X}" if msg.is_extended_id else f"{msg.arbitration_id:03X}"
            kind = "R" if msg.is_remote_frame else ""
            words = next((t for text in texts if (t := text(bus, msg))), "")
            way = "Rx" if msg.is_rx else "Tx"
            yield f"{msg.timestamp:11.6f} {bus} {way} {cob} [{msg.dlc}]{kind} {data:<23}  {words}".rstrip()
    except (ValueError, OSError, can.CanError) as exc:
        raise ValueError(f"python-can cannot read it as a {path.suffix} file: {exc}") from None


def _bus(channel, buses: list) -> str:
    """The [[can]] name of a channel number (candump: can0, can1 ...)."""
    number = channel
    if isinstance(channel, str) and channel.removeprefix("can").isdigit():
        number = int(channel.removeprefix("can"))
    if isinstance(number, int) and 0 <= number < len(buses):
        return buses[number]
    return str(channel)


__all__ = ["read_log"]
