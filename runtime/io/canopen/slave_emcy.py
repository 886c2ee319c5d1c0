"""The emergencies of a simulated CANopen slave (slave.py): an EMCY
produced as CiA 301 says (the error register 1001h, the history 1003h,
the COB-ID 1014h; none while stopped or booting), and what it sent kept for
its records (--final-json) and the traces' events."""

from __future__ import annotations

import struct
import threading
from collections import deque
from collections.abc import Callable
from typing import Any

from .cia301 import COB_ID_INVALID, STATE_BOOTUP, STATE_STOPPED, cob_emcy

ERROR_REGISTER = 0x1001
ERROR_HISTORY = 0x1003
EMCY_COB_ID = 0x1014
# EMCY (CiA 301): 2 bytes error code, error register, 5 manufacturer bytes
EMCY_MANUFACTURER_BYTES = 5
EMCY_RECORDS = 1000  # the EMCYs sent a simulated slave keeps for its records (the newest)


def _record_ns(record: dict) -> int:
    return round(record["t_s"] * 1e9)


class EmcyMixin:
    """send_emcy, records and events_since for SimulatedCanopenSlave."""

    od: Any
    node_id: int
    _state: int
    _lock: threading.RLock
    emcys_sent: deque
    emcy_text: Callable[[int, int, bytes], str] | None

    # provided by SimulatedCanopenSlave
    def _value(self, index: int, subindex: int) -> int:
        raise NotImplementedError

    def _store(self, index: int, subindex: int, value: int) -> None:
        raise NotImplementedError

    def _send(self, can_id: int, data: bytes) -> None:
        raise NotImplementedError

    def _clock_ns(self) -> int:
        raise NotImplementedError

    def send_emcy(self, error_code: int, error_register: int, manufacturer_bytes: bytes = b"") -> None:
        """Produce an emergency (CiA 301): keeps 0x1001 and the 0x1003 history;
        error code 0x0000 is "error reset" and is not added to the history."""
        with self._lock:
            data = bytes(manufacturer_bytes)
            if len(data) > EMCY_MANUFACTURER_BYTES:
                raise ValueError(f"an EMCY carries {EMCY_MANUFACTURER_BYTES} manufacturer bytes, not {len(data)}")
            if ERROR_REGISTER in self.od:
                self._store(ERROR_REGISTER, 0, error_register)
            if error_code:
                self._push_error_history(error_code)
            cob = self._value(EMCY_COB_ID, 0) if EMCY_COB_ID in self.od else cob_emcy(self.node_id)
            # CiA 301: no EMCY in Stopped; bit 31 of 0x1014 switches the EMCY off
            if cob & COB_ID_INVALID or self._state in (STATE_STOPPED, STATE_BOOTUP):
                return
            payload = struct.pack("<HB", error_code, error_register) + data.ljust(EMCY_MANUFACTURER_BYTES, b"\0")
            self._send(cob & 0x7FF, payload)
            record = {
                "t_s": self._clock_ns() / 1e9,
                "code": f"{error_code:04X}h",
                "register": f"{error_register:02X}h",
                "data": payload[3:].hex(" ").upper(),
            }
            if self.emcy_text is not None and error_code:
                record["text"] = self.emcy_text(error_code, error_register, payload[3:])
            self.emcys_sent.append(record)

    def records(self) -> dict:
        """What happened to the simulated device, as JSON data (--final-json):
        the EMCYs it sent, each with its engine time and the device's words."""
        with self._lock:
            return {"emcys": list(self.emcys_sent)} if self.emcys_sent else {}

    def events_since(self, t_ns: int) -> list:
        """The EMCYs sent after t_ns, for the traces: "EMCY 1000h thermal overload (register 01h)"."""
        sent = self.emcys_sent
        if not sent or _record_ns(sent[-1]) <= t_ns:  # every scan of a trace asks: the common answer first
            return []
        with self._lock:
            new = []
            for record in reversed(sent):
                at = _record_ns(record)
                if at <= t_ns:
                    break
                words = record.get("text") or ("error reset" if record["code"] == "0000h" else f"data {record['data']}")
                new.append((at, f"EMCY {record['code']} {words} (register {record['register']})"))
        return new[::-1]

    def _push_error_history(self, error_code: int) -> None:
        """0x1003: newest first, as many entries as the EDS gives; bits 16-23
        additional information, all 0 (manual 001 §4)."""
        obj = self.od.get(ERROR_HISTORY)
        if obj is None:
            return
        subs = sorted(s for s in obj.subindices if s)
        count = min(self._value(ERROR_HISTORY, 0), len(subs))
        history = [error_code & 0xFFFF] + [self._value(ERROR_HISTORY, s) for s in subs[:count]]
        history = history[: len(subs)]
        for sub, value in zip(subs, history):
            self._store(ERROR_HISTORY, sub, value)
        self._store(ERROR_HISTORY, 0, len(history))
