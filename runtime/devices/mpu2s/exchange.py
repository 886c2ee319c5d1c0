"""MPU2S_EXCHANGE: one parameter read or write started by the program, the
runtime side of MPU2S_PARAM (fblocks/vendor/mpu2s.st), asynchronous like
READ_VAR and MODBUS_EXCHANGE:

    MPU2S_EXCHANGE(DEVICE, ID, BIT, WRITE, VALUE, MGMT)

DEVICE the device number (1..30), ID the parameter ID, BIT the highest bit
of a bit, double-bit or half-byte parameter (-1: a whole word), WRITE 1 to
write, 0 to read, VALUE the value to write in thousandths of its unit (a
DINT: 0.20 Hz is 200; every MPU2-S unit has 0.001 to spare: the raw word
is rounded from it). The call queues the request to the device's
RequestEngine (requests.py) and returns at once; the result lands in MGMT
at the start of a later cycle:

    MGMT[0]  bit 0 activity (set by the call, cleared when it ends), MSB an exchange number
    MGMT[1]  the outcome: 0 done, or requests.Outcome (MPU2S_ERR_* in ST)
    MGMT[2]  the word the device holds (the whole word for a bit parameter)
    MGMT[3]  the value in its unit as numerator / denominator, two DINTs: the
    MGMT[4]  numerator's high and low word,
    MGMT[5]  frames sent, retries included
    MGMT[6]  the denominator's high and low word (1 or more): 59/256 Hz is
    MGMT[7]  59 / 256, which ST divides in LREAL to the nearest double, as
             Python's float(Fraction) does (no decimal rounding)

A call while MGMT[0] bit 0 is set starts nothing and returns FALSE.
"""

from __future__ import annotations

import threading
from collections.abc import Callable

from ...st.native import ANY_INT, WORDS, NativeFunction, Param
from .requests import Outcome, Request, Result

SERVICE = "mpu2s.exchange"
MGMT_WORDS = 8
DINT_MAX = (1 << 31) - 1


def _store(table, i: int, value: int, signed: bool) -> None:
    value &= 0xFFFF
    table[i] = value - 0x10000 if signed and value & 0x8000 else value


def finish(mgmt, signed: bool, result: Result) -> None:
    """The result into the program's table (the scan thread, at a cycle start)."""
    exact = result.exact
    if abs(exact.numerator) > DINT_MAX or exact.denominator > DINT_MAX:  # no word's value is
        exact = exact.limit_denominator(0xFFFF)
    numerator = max(-DINT_MAX - 1, min(DINT_MAX, exact.numerator))
    _store(mgmt, 1, int(result.outcome), signed)
    _store(mgmt, 2, result.raw, signed)
    _store(mgmt, 3, (numerator >> 16) & 0xFFFF, signed)
    _store(mgmt, 4, numerator & 0xFFFF, signed)
    _store(mgmt, 5, result.transactions, signed)
    _store(mgmt, 6, exact.denominator >> 16, signed)
    _store(mgmt, 7, exact.denominator & 0xFFFF, signed)
    _store(mgmt, 0, int(mgmt[0]) & ~1, signed)


class Mpu2sExchangeService:
    """One per engine (every MPU2-S node registers its submit function)."""

    def __init__(self) -> None:
        self._devices: dict[int, Callable[[Request], None]] = {}
        self._lock = threading.Lock()

    def add(self, device: int, submit: Callable[[Request], None]) -> None:
        self._devices[device] = submit

    def request(self, name: str, device, param_id, bit, write, value, mgmt, mgmt_signed: bool = False) -> bool:
        m0 = int(mgmt[0]) & 0xFFFF
        if m0 & 1:
            return False
        _store(mgmt, 0, ((((m0 >> 8) + 1) & 0xFF) << 8) | 1, mgmt_signed)
        for i in range(1, MGMT_WORDS):
            _store(mgmt, i, 0, mgmt_signed)
        submit = self._devices.get(int(device))
        if submit is None:
            message = f"no MPU2-S with device number {int(device)} in the configuration"
            finish(mgmt, mgmt_signed, Result(Outcome.NO_DEVICE, message=message))
            return False
        write = bool(int(write))
        # the node hands the result back at the start of a cycle (Mpu2sNode.read_inputs)
        submit(
            Request(
                int(param_id),
                int(bit),
                write,
                int(value) / 1000 if write else None,
                lambda result: finish(mgmt, mgmt_signed, result),
            )
        )
        return True


class NoMpu2s:
    """MPU2S_EXCHANGE without an MPU2-S in the configuration: ends at once with NO_DEVICE."""

    def request(self, name: str, device, param_id, bit, write, value, mgmt, *signed) -> bool:
        mgmt[0] = int(mgmt[0]) & ~1
        mgmt[1] = int(Outcome.NO_DEVICE)
        return False


MPU2S_EXCHANGE = NativeFunction(
    "MPU2S_EXCHANGE",
    (
        Param("DEVICE", ANY_INT, "the device number"),
        Param("ID", ANY_INT, "the parameter ID"),
        Param("BIT", ANY_INT, "the highest bit of the parameter, -1 for a word"),
        Param("WRITE", ANY_INT, "1 to write, 0 to read"),
        Param("VALUE", ANY_INT, "the value to write, in thousandths of its unit"),
        Param("MGMT", WORDS, "the management table", min_words=MGMT_WORDS),
    ),
    service=SERVICE,
    fallback=NoMpu2s(),
    usage="MPU2S_EXCHANGE(DEVICE, ID, BIT, WRITE, VALUE, MGMT)",
)
