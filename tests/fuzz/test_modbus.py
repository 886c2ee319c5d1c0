"""Modbus replies into the master's link (runtime/io/modbus/link.py): pymodbus's
client framing in memory (wire.MemoryClient), a hostile unit at the other
end (modbus_replies.HostileLine) answering every request with a drawn frame.
Every transaction ends in an Outcome, never an exception and never a hang:
a faithful answer is taken (its values, error 0), a well-formed exception
response is an error, silence is a timeout, a read taken has its count of
items; nothing is logged with a traceback.
"""

from __future__ import annotations

from collections import Counter

from hypothesis import given
from hypothesis import strategies as st

from softplc.runtime.io.modbus.link import LinkSettings, ModbusError, ModbusLink

from .modbus_replies import HostileLine, replies, requests
from .support import LogWatch, assert_no_tracebacks, bounded, fuzz, long, short

S = 1_000_000_000


@st.composite
def exchanges(draw):
    """(settings, [(transaction, [planned replies, one per attempt])])."""
    tcp = draw(st.booleans())
    settings = LinkSettings(
        name="fuzz",
        transport="tcp" if tcp else "rtu",
        baud=draw(st.sampled_from([9600, 19200, 115200])),
        timeout_s=0.1,
        retries=draw(st.integers(0, 2)),
    )
    steps = []
    for _ in range(draw(st.integers(1, 6))):
        tx = draw(requests())
        steps.append((tx, [draw(replies(tx, tcp)) for _attempt in range(settings.retries + 1)]))
    return settings, steps


def check_exchanges(case) -> tuple[int, Counter]:
    """(the frames the unit sent, the transactions by outcome)"""
    settings, steps = case
    frames = 0
    outcomes: Counter = Counter()
    line = HostileLine([], settings.transport == "tcp")
    link = ModbusLink(settings, server=line)  # type: ignore[arg-type]  # duck-typed MemoryServer
    with LogWatch() as watch, bounded("Modbus replies"):
        for k, (tx, planned) in enumerate(steps):
            line.planned = list(planned)
            asked = len(line.requests)
            outcome = link.transact(tx, now_ns=k * 60 * S)  # a minute apart: past any reconnect back-off
            used = planned[: len(line.requests) - asked]
            frames += len(used)
            _judge(tx, used, outcome)
            outcomes["ok" if outcome.error == 0 else error_name(outcome.error)] += 1
    assert_no_tracebacks(watch, "Modbus replies")
    return frames, outcomes


def error_name(code: int) -> str:
    try:
        return ModbusError(code).name.lower()
    except ValueError:
        return "exception code"


def _judge(tx, used: list, outcome) -> None:
    what = f"request {tx}, replies {[(f.hex(' ') if f else None, r.how) for f, r in used]}: {outcome}"
    assert isinstance(outcome.error, int) and 0 <= outcome.error <= 0xFF, what
    assert isinstance(outcome.message, str), what
    if outcome.error == 0 and tx.count and tx.function in (1, 2, 3, 4, 23):
        assert len(outcome.values) == tx.count, what
    if not used:
        return
    _frame, last = used[-1]
    if last.faithful:
        assert outcome.error == 0, f"a faithful answer refused: {what}"
        if tx.count:
            assert tuple(outcome.values) == tuple(last.values), f"a faithful answer's values changed: {what}"
    if last.exception:
        assert outcome.error != 0, f"an exception response taken as success: {what}"
    # issue 16, "an exception response with code 0 is taken as success, and a
    # reply with the wrong function code is accepted ... Check function code,
    # exception code, unit, byte count and register count of every reply"
    if outcome.error == 0:
        taken = [r for _f, r in used if r.faithful is not False]
        assert taken, f"a reply that answers something else taken as success: {what}"


@short(60)
@given(exchanges())
def test_modbus_replies_give_outcomes(case):
    check_exchanges(case)


@fuzz
def test_long_modbus_replies(tally, shard):
    counts = tally("frames")

    @long("frames", 0.4, shard, per_example=3.7)
    @given(exchanges())
    def run(case):
        frames, outcomes = check_exchanges(case)
        counts.inputs += frames
        counts.update(outcomes)

    run()
