"""Where the four Modbus tables live in the process image: OpenPLC's fixed
mapping (docs/guide/surfaces.md "Modbus TCP server" has the table).

    coil n               %QX(n div 8).(n mod 8)   coils 0..65535
    discrete input n     %IX(n div 8).(n mod 8)   discrete inputs 0..65535
    input register n     %IWn                     input registers 0..32767
    holding register n   %QWn     for n <  1024   (%QW0..%QW1023)
                         %MW(n-1024) for n >= 1024 (%MW0..%MW32767)

The image keeps words little-endian at byte 2n (%QW1 = bytes 2-3 in the
IEC model and word 1 in the Schneider model alike, image/memory.py), so a
register is the same 16 bits whichever addressing the profile uses; a coil
is bit n mod 8 of byte n div 8. The ranges shrink with a smaller image.

Reads take the bytes of a snapshot (never the live image); writes are the
paths ``Access`` writes: "%QX0.3", "%QW5", "%MW7".
"""

from __future__ import annotations

import struct

COILS = "coils"
DISCRETE_INPUTS = "discrete inputs"
INPUT_REGISTERS = "input registers"
HOLDING_REGISTERS = "holding registers"

#: holding registers 0..1023 are %QW0..%QW1023, from 1024 on %MW0.. (OpenPLC)
QW_REGISTERS = 1024
#: Modbus addresses are 16 bits
ADDRESSES = 1 << 16


class OutOfRange(LookupError):
    """A request reaching past a table: the message names the table and its range."""


class Mapping:
    """The tables of an image whose %I, %Q and %M areas have area_size bytes each."""

    def __init__(self, area_size: int) -> None:
        words = area_size // 2
        self.bits = min(ADDRESSES, 8 * area_size)
        self.input_registers = min(ADDRESSES, words)
        self.q_registers = min(QW_REGISTERS, words)
        self.m_registers = min(ADDRESSES - QW_REGISTERS, words)

    def ranges(self) -> dict:
        """Each table's valid addresses, as text for messages and the log."""
        return {
            COILS: f"0..{self.bits - 1} (%QX)",
            DISCRETE_INPUTS: f"0..{self.bits - 1} (%IX)",
            INPUT_REGISTERS: f"0..{self.input_registers - 1} (%IW)",
            HOLDING_REGISTERS: f"0..{self.q_registers - 1} (%QW), "
            f"{QW_REGISTERS}..{QW_REGISTERS + self.m_registers - 1} (%MW)",
        }

    # ------------------------------------------------------------ where

    def segments(self, table: str, address: int, count: int) -> list:
        """[(area letter, first bit or word in the area, count)] covering
        address..address+count-1 of table; OutOfRange if any is not mapped."""
        end = address + count
        if count < 1 or address < 0:
            raise OutOfRange(f"{table}: {count} from {address}")
        if table in (COILS, DISCRETE_INPUTS):
            if end > self.bits:
                raise self._outside(table, address, count)
            return [("Q" if table == COILS else "I", address, count)]
        if table == INPUT_REGISTERS:
            if end > self.input_registers:
                raise self._outside(table, address, count)
            return [("I", address, count)]
        out = []
        if address < QW_REGISTERS:
            if min(end, QW_REGISTERS) > self.q_registers:
                raise self._outside(table, address, count)
            out.append(("Q", address, min(end, QW_REGISTERS) - address))
        if end > QW_REGISTERS:
            first = max(address, QW_REGISTERS) - QW_REGISTERS
            if end - QW_REGISTERS > self.m_registers:
                raise self._outside(table, address, count)
            out.append(("M", first, end - QW_REGISTERS - first))
        return out

    def _outside(self, table: str, address: int, count: int) -> OutOfRange:
        what = f"{address}" if count == 1 else f"{address}..{address + count - 1}"
        return OutOfRange(f"{table} {what}: outside {self.ranges()[table]}")

    def paths(self, table: str, address: int, count: int) -> list:
        """The image address of each coil or register, as Access writes it."""
        out = []
        for area, first, n in self.segments(table, address, count):
            if table in (COILS, DISCRETE_INPUTS):
                out += [f"%{area}X{i >> 3}.{i & 7}" for i in range(first, first + n)]
            else:
                out += [f"%{area}W{i}" for i in range(first, first + n)]
        return out

    # ------------------------------------------------------------ reading a snapshot

    def read(self, image: dict, table: str, address: int, count: int) -> list:
        """The values of a snapshot's image bytes: bools for bits, 0..65535 for registers."""
        out: list = []
        for area, first, n in self.segments(table, address, count):
            data = image[area]
            if table in (COILS, DISCRETE_INPUTS):
                low, high = first >> 3, (first + n - 1) >> 3
                chunk = int.from_bytes(data[low : high + 1], "little") >> (first & 7)
                out += [bool(chunk >> i & 1) for i in range(n)]
            else:
                out += struct.unpack_from(f"<{n}H", data, 2 * first)
        return out
