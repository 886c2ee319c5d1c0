"""Reading and writing MPU2-S parameters over the bus: one request at a time
per device, paced, matched, timed out and retried, written values read back
(manual 004 ch. 2 and 4; digest 004 §1.7, §6.2).

    engine = RequestEngine(1, send, password=1234)
    engine.submit(Request(26, -1, write=True, value=0.20, done=callback))   # +df max
    engine.on_reply(frames.decode_reply(can_id, data), now)                 # from the bus
    engine.advance(now)                                                     # timers, the next frame

A request is a short sequence of transactions (one frame out, its reply
back), each an FF read or EE write of one parameter ID:

    write   the password to ID 500, if there is one and it is not yet given
            (4.2.1: "vor allen anderen Werten"); again after a communication
            loss (the node calls comm_lost(): A11, how long it holds is not said)
            the factor KWUGNSEK (ID 507) or KWUNTSEK (ID 508) for a voltage
            parameter (4.2.10, kept until a transformer parameter is written)
            the whole word first for a bit, double-bit or half-byte parameter,
            which is merged into it (4.1: "immer zuerst das gesamte Wort")
            the write; then a read of the same ID: the value the device holds
            must be the one written (A10: the write reply may be an echo)
    read    the factor if needed, then the parameter's word

The value is range-checked before anything of a write goes on the wire
("unbedingt einzuhalten", 4.1.3): a refusal costs no frame, only a read of
the voltage factor may come first. Decided where the manual is silent:
- A reply matches on its kind (FF/EE), device number and parameter ID; a
  reply that matches nothing (a late one after a timeout) is counted.
- No reply within `timeout` (default 300 ms, three message slots, §1.7 [I])
  sends the same frame again, `retries` times; then the request fails.
- Frames of one device are at least `pace` apart (default 100 ms, the
  manual's message spacing, §1.1, A32).
- Only the 170 parameters of ch. 4 (the "MPU2-S Low" set, A12) are known:
  any other ID, or a bit no parameter starts at, is UNKNOWN and costs no
  frame.
"""

from __future__ import annotations

import enum
from collections import deque
from collections.abc import Callable, Generator
from dataclasses import dataclass
from fractions import Fraction
from typing import Any

from . import frames, scaling
from . import parameters as P

PASSWORD_ID = 500  # 4.2.1, code level 2
VT_IDS = frozenset({1, 3, 9, 282, 498, 499})  # transformer parameters: the factors change (4.2.10)
MS = 1_000_000


class Outcome(enum.IntEnum):
    """MPU2S_PARAM's ERRORID (fblocks/vendor/mpu2s.st has them as MPU2S_ERR_*)."""

    OK = 0
    TIMEOUT = 1  # no reply after the retries
    RANGE = 2  # the value is outside the documented raw range: nothing was written
    UNKNOWN = 3  # no such parameter (ID, bit) in the manual's list
    VERIFY = 4  # the value read back is not the one written
    NO_DEVICE = 5  # no MPU2-S with that number in the configuration
    BUSY = 6  # the call came while the previous one with the same table was running


@dataclass
class Request:
    param_id: int
    bit: int  # the highest bit of a bit, double-bit or half-byte parameter; -1 for a whole word
    write: bool
    value: Any  # to write: in the parameter's unit (a number, TRUE/FALSE for a switch)
    done: Callable[[Result], None]


@dataclass
class Result:
    outcome: Outcome
    raw: int = 0  # the word as the device holds it (the whole word for a bit parameter)
    value: float = 0.0  # in the parameter's unit (1.0/0.0 for a flag or switch)
    transactions: int = 0  # frames sent, retries included
    message: str = ""
    exact: Fraction = Fraction(0)  # value as the manual's formula gives it: raw / (its factor)


class Failed(Exception):
    def __init__(self, outcome: Outcome, message: str) -> None:
        super().__init__(message)
        self.outcome = outcome


# one transaction: (FF read or EE write, parameter ID, raw word to write)
Step = tuple[int, int, int]
Steps = Generator[Step, int, Result]


def resolve(param_id: int, bit: int) -> P.Parameter | None:
    """The parameter at an ID (and, for a word shared by several, the one
    whose highest bit is `bit`); None for a whole word shared by several
    (raw access) or for an ID the manual does not list."""
    found = P.by_id(param_id)
    if bit < 0:
        return found[0] if len(found) == 1 else None
    for p in found:
        if p.bits and p.bits[0] == bit:
            return p
    return None


def program_value(p: P.Parameter, value: Any) -> Any:
    """A value as a program writes it (MPU2S_PARAM's VALUE is an LREAL) as
    parameters.encode() takes it: a flag or a switch (bit, double bit) 1.0
    -> TRUE, 0.0 -> FALSE ("a switch or flag is 1.0 / 0.0", fblocks/vendor/
    mpu2s.st; a switch's TRUE is 11, 4.2.18), a code a whole number -> that
    int. Anything else is left to encode() to refuse."""
    if isinstance(value, bool) or not isinstance(value, int | float):
        return value
    if p.family in ("flag", "switch") and value in (0, 1):
        return bool(value)
    if p.family == "code" and float(value).is_integer():
        return int(value)
    return value


def _number(value: Any) -> float:
    if isinstance(value, bool):
        return 1.0 if value else 0.0
    if isinstance(value, (int, float)):
        return float(value)
    return 0.0


class RequestEngine:
    def __init__(
        self,
        device: int,
        send: Callable[[int, bytes], bool],
        *,
        password: int | None = None,
        timeout_ns: int = 300 * MS,
        retries: int = 2,
        pace_ns: int = 100 * MS,
        variant: int | None = None,
    ) -> None:
        self.device = device
        self._send = send
        self.password = password
        self.timeout_ns = timeout_ns
        self.retries = retries
        self.pace_ns = pace_ns
        self.variant = variant  # 100 or 400 V device; None: a value must suit both (parameters.py)
        self.authorized = False
        self._factors: dict[int, int] = {}  # 507/508 -> the factor read
        self._queue: deque[Request] = deque()
        self._current: tuple[Request, Steps] | None = None
        self._step: Step | None = None  # the transaction waiting for its reply
        self._reply: int | None = None  # its reply, until the next advance
        self._frames = 0
        self._attempt = 0
        self._deadline = 0
        self._next_send = 0
        self.sent = 0
        self.replies = 0
        self.unmatched = 0
        self.timeouts = 0
        self.failed = 0

    # ------------------------------------------------------------ the node's side

    def submit(self, request: Request) -> None:
        self._queue.append(request)

    def comm_lost(self) -> None:
        """The device was not heard: the password is given again before the next write (A11)."""
        self.authorized = False

    def busy(self) -> bool:
        return self._current is not None or bool(self._queue)

    def on_reply(self, reply: frames.Reply, now_ns: int) -> None:
        step = self._step
        if step is None or self._reply is not None or (reply.kind, reply.param_id) != (step[0], step[1]):
            self.unmatched += 1
            return
        self.replies += 1
        self._reply = reply.raw

    def advance(self, now_ns: int) -> None:
        if self._step is not None:
            if self._reply is not None:
                raw, self._reply, self._step = self._reply, None, None
                self._resume(raw, now_ns)
            elif now_ns >= self._deadline:
                self._retry(now_ns)
        if self._current is None and self._queue:
            self._start(self._queue.popleft(), now_ns)
        if self._step is not None and self._attempt == 0 and now_ns >= self._next_send:
            self._transmit(now_ns)

    # ------------------------------------------------------------ the sequence

    def _start(self, request: Request, now_ns: int) -> None:
        self._frames = 0
        gen = self._steps(request)
        self._current = (request, gen)
        self._advance_gen(lambda: next(gen))

    def _resume(self, raw: int, now_ns: int) -> None:
        assert self._current is not None
        gen = self._current[1]
        self._advance_gen(lambda: gen.send(raw))

    def _advance_gen(self, step_fn: Callable[[], Step]) -> None:
        assert self._current is not None
        request = self._current[0]
        try:
            self._step = step_fn()
            self._attempt = 0  # to be sent when the pace allows
        except StopIteration as stop:
            self._finish(request, stop.value)
        except Failed as exc:
            self._finish(request, Result(exc.outcome, transactions=self._frames, message=str(exc)))

    def _transmit(self, now_ns: int) -> None:
        assert self._step is not None
        kind, param_id, raw = self._step
        if kind == frames.KIND_WRITE:
            data = frames.write_request(self.device, param_id, raw)
        else:
            data = frames.read_request(self.device, param_id)
        self._send(frames.REQUEST_ID, data)
        self.sent += 1
        self._frames += 1
        self._attempt += 1
        self._deadline = now_ns + self.timeout_ns
        self._next_send = now_ns + self.pace_ns

    def _retry(self, now_ns: int) -> None:
        assert self._step is not None and self._current is not None
        if self._attempt <= self.retries:
            if now_ns >= self._next_send:
                self.timeouts += 1
                self._transmit(now_ns)
            return
        self.timeouts += 1
        kind, param_id, _raw = self._step
        request = self._current[0]
        what = "write to" if kind == frames.KIND_WRITE else "read of"
        message = f"no reply to the {what} ID {param_id} after {self._attempt} attempt(s)"
        self._step = None
        self._current[1].close()
        self._finish(request, Result(Outcome.TIMEOUT, transactions=self._frames, message=message))

    def _finish(self, request: Request, result: Result) -> None:
        self._current = None
        self._step = None
        if result.outcome != Outcome.OK:
            self.failed += 1
        request.done(result)

    def _steps(self, request: Request) -> Steps:
        """The transactions of one request; each yield sends one and takes its reply's word."""
        param_id, bit = request.param_id, request.bit
        p = resolve(param_id, bit)
        if p is None and (bit >= 0 or not P.by_id(param_id)):
            where = f"ID {param_id}" + (f" bit {bit}" if bit >= 0 else "")
            raise Failed(Outcome.UNKNOWN, f"the MPU2-S has no parameter at {where}")
        if p is not None and p.kind in ("words3", "words8"):
            raise Failed(Outcome.UNKNOWN, f"{p}: a parameter of several IDs; read or write its IDs one by one")
        factor = None
        if p is not None and p.factor_id is not None:
            factor = self._factors.get(p.factor_id)
            if factor is None:
                factor = yield (frames.KIND_READ, p.factor_id, 0)
                self._factors[p.factor_id] = factor
        if not request.write:
            word = yield (frames.KIND_READ, param_id, 0)
            return self._result(p, word, factor)
        if p is None:  # a whole word shared by several parameters
            raise Failed(Outcome.UNKNOWN, f"ID {param_id} holds several parameters: give the bit of the one to write")
        value = program_value(p, request.value)
        try:
            if p.bits:
                P.merge(p, 0, value)  # the value is checked before anything is written
            else:
                raw = P.encode(p, value, factor=factor, variant=self.variant)
        except ValueError as exc:
            raise Failed(Outcome.RANGE, str(exc)) from None
        if self.password is not None and not self.authorized:
            yield (frames.KIND_WRITE, PASSWORD_ID, self.password)
            self.authorized = True
        if p.bits:
            word = yield (frames.KIND_READ, param_id, 0)
            raw = P.merge(p, word, value)
        yield (frames.KIND_WRITE, param_id, raw)
        back = yield (frames.KIND_READ, param_id, 0)
        if param_id in VT_IDS:
            self._factors.clear()
        if back != raw:
            raise Failed(Outcome.VERIFY, f"{p}: wrote {raw:#06x}, the device holds {back:#06x}")
        return self._result(p, back, factor)

    def _result(self, p: P.Parameter | None, word: int, factor: int | None) -> Result:
        exact = _exact(p, word, factor)
        return Result(Outcome.OK, raw=word, value=float(exact), transactions=self._frames, exact=exact)


def _exact(p: P.Parameter | None, word: int, factor: int | None) -> Fraction:
    """The value of a word read, exactly: a scaled parameter's raw divided by
    its family's factor (59 at f[Hz]·256 is 59/256 Hz, 4.2.47), a flag or
    switch 1/0, a code or a plain word as it is; digit words (delays, fault
    classes) 0: read their RAW."""
    if p is None:
        return Fraction(word)
    value = P.extract(p, word) if p.bits else P.decode(p, word, factor=factor)
    if isinstance(value, float):  # a scaled family
        raw = word - 0x10000 if p.signed and word & 0x8000 else word
        return Fraction(raw) / scaling.family(p.family, factor).per_unit
    return Fraction(_number(value))
