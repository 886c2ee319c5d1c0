"""MODBUS_SAFE_WRITE: a device's safe state on Modbus, declared by the block
that drives the device (a vendor block of fblocks/vendor/), applied by the
master while the PLC holds its outputs safe.

    MODBUS_SAFE_WRITE(CONNECTION, UNIT, OFFSET, COUNT, VALUES)

On Modbus a program drives a device through requests (MODBUS_REQUEST), not
through %Q, so [outputs] safe cannot reach it: the block says once (DA1_DRIVE
after it has identified the drive) which holding registers of its unit take
which values when outputs are safe (the Eaton control word 0: stop). From
the moment the engine hands the drivers its safe-output image (a task fault,
the stop: ProcessImage.held_safe) until the outputs are live again, the
master

  * writes those registers once (function 16 per block of registers; a
    write that fails is sent again a second later), and, at the stop, before
    it closes the connection;
  * puts those values in place of what any request of the program would
    write to them (functions 6, 16 and 23), as the engine puts the safe
    values in place of the program's %Q: a block in a task still running
    reads its device, and cannot start it again.

The call returns TRUE when the values are taken; FALSE for an unknown
connection, a unit beyond 1..247 or a block beyond the 65536 registers or
more than 123 of them (what function 16 carries).
"""

from __future__ import annotations

import dataclasses
import threading
from collections.abc import Callable

from ...st.native import ANY_INT, STRING, WORDS, NativeFunction, Param
from .functions import WRITE_LIMIT
from .link import Transaction

SERVICE = "modbus.safe"
RETRY_NS = 1_000_000_000  # a safe write that failed is sent again after this long
UNIT_MAX = 247
_REGISTER_WRITES = (6, 16, 23)


class SafeWrites:
    """The safe register values by connection and unit, and which of them
    are still to be written while outputs are held safe. The scan thread
    calls everything (request() while the program runs, the rest from the
    driver's write_outputs and _submit) but done(), which the connection's
    worker calls when a safe write ends."""

    def __init__(self, known: Callable[[str], bool]) -> None:
        self._known = known  # is there a connection of this name
        self.values: dict[tuple[str, int], dict[int, int]] = {}  # (connection, unit) -> {offset: value}
        self._due: dict[tuple[str, int], int] = {}  # (connection, unit) -> engine time it is due, while held
        self._lock = threading.Lock()  # _due, between the scan thread and the workers

    # ------------------------------------------------------------ the program's call

    def request(self, name: str, connection, unit, offset, count, values, *signed) -> bool:
        connection, unit, offset, count = str(connection), int(unit), int(offset), int(count)
        if (
            not self._known(connection)
            or not 1 <= unit <= UNIT_MAX
            or not 1 <= count <= min(WRITE_LIMIT[16], len(values))
            or not 0 <= offset <= 0x10000 - count
        ):
            return False
        table = self.values.setdefault((connection, unit), {})
        new = {offset + i: int(values[i]) & 0xFFFF for i in range(count)}
        if any(table.get(k) != v for k, v in new.items()):
            table.update(new)
            with self._lock:
                self._due.setdefault((connection, unit), 0)  # sent at the next write while held
        return True

    # ------------------------------------------------------------ while held safe

    def hold(self) -> None:
        """The outputs became safe: every unit's safe values are due."""
        with self._lock:
            self._due = dict.fromkeys(self.values, 0)

    def due(self, now_ns: int) -> list[tuple[str, Transaction, tuple[str, int]]]:
        """(connection, transaction, key) of the safe writes due at now_ns;
        each is due again RETRY_NS later unless done() says it succeeded."""
        out = []
        with self._lock:
            keys = [key for key, when in self._due.items() if when <= now_ns]
            for key in keys:
                self._due[key] = now_ns + RETRY_NS
        for key in keys:
            connection, unit = key
            for offset, block in _blocks(self.values[key]):
                out.append((connection, Transaction(unit, 16, offset, 0, tuple(block)), key))
        return out

    def done(self, key: tuple[str, int], ok: bool) -> None:
        if ok:
            with self._lock:
                self._due.pop(key, None)

    def substitute(self, connection: str, tx: Transaction) -> Transaction:
        """tx with the safe values in place of the program's for the
        registers of its unit that have one (register writes only)."""
        table = self.values.get((connection, tx.unit))
        if not table or tx.function not in _REGISTER_WRITES:
            return tx
        start = tx.write_offset if tx.function == 23 else tx.offset
        values = tuple(table.get(start + i, v) for i, v in enumerate(tx.values))
        return tx if values == tx.values else dataclasses.replace(tx, values=values)


def _blocks(table: dict[int, int]) -> list[tuple[int, list[int]]]:
    """Consecutive registers as (first offset, values), at most 123 each."""
    out: list[tuple[int, list[int]]] = []
    for offset in sorted(table):
        if out and out[-1][0] + len(out[-1][1]) == offset and len(out[-1][1]) < WRITE_LIMIT[16]:
            out[-1][1].append(table[offset])
        else:
            out.append((offset, [table[offset]]))
    return out


class NoModbusSafe:
    """MODBUS_SAFE_WRITE without a [[modbus]] connection: nothing to take."""

    def request(self, name: str, *args) -> bool:
        return False


_ARGS = ("CONNECTION", "UNIT", "OFFSET", "COUNT", "VALUES")

MODBUS_SAFE_WRITE = NativeFunction(
    "MODBUS_SAFE_WRITE",
    (
        Param("CONNECTION", STRING, "CONNECTION", "the name of a [[modbus]] connection, a STRING"),
        Param("UNIT", ANY_INT, "UNIT"),
        Param("OFFSET", ANY_INT, "OFFSET"),
        Param("COUNT", ANY_INT, "COUNT"),
        Param("VALUES", WORDS, "VALUES", "an ARRAY OF WORD (or INT/UINT)"),
    ),
    service=SERVICE,
    fallback=NoModbusSafe(),
    usage=f"MODBUS_SAFE_WRITE({', '.join(_ARGS)})",
)
