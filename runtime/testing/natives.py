"""The assertion functions of ST tests, and the service that records them.

    ASSERT_TRUE(Condition, Message)              ASSERT_FALSE(Condition, Message)
    ASSERT_EQUAL(Expected, Actual, Message)      ANY_ELEMENTARY: integers, reals,
                                                 BOOL, STRING, TIME..., enumerations
    ASSERT_NOT_EQUAL(Expected, Actual, Message)
    ASSERT_NEAR(Expected, Actual, Delta, Message)   reals: |Expected - Actual| <= Delta
    TEST_FINISHED()                              the test is over (it passed unless
                                                 an assertion failed)
    SIM_FAULT(Sim, Fault, Value, On)             a fault of a simulated device of the
                                                 configuration ([[sim]] faults): injected
                                                 when On becomes TRUE, undone (a lasting
                                                 one) when it becomes FALSE

They are native functions (st/native.py) declared with site=True: the
compiler hands the service the call's file:line:column and the types of the
arguments (Expected and Actual in their common type), so a failure names
the call and shows both values as ST literals (E_State#Running, T#2s500ms).
Every assertion returns TRUE when it holds, so a test can branch on it.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

from ..st import native as N
from ..st.native import CallSite, NativeFunction, Param
from ..st.rtlib.rt_text import iec_literal

SERVICE = "st_test"


class _NoRunner:
    """The fallback: a program compiled with the assertions but run
    without the test runner (compile_files(natives=NATIVES) by hand)."""

    def request(self, name: str, *args: Any) -> Any:
        raise RuntimeError(f"{name} runs only under the test runner (softplc test)")


def _fn(name: str, params: tuple, usage: str) -> NativeFunction:
    return NativeFunction(name, params, service=SERVICE, fallback=_NoRunner(), usage=usage, site=True)


_MSG = Param("Message", N.STRING, "the message")

NATIVES: tuple[NativeFunction, ...] = (
    _fn("ASSERT_TRUE", (Param("Condition", N.BOOL, "the condition"), _MSG), "ASSERT_TRUE(running, 'the motor runs')"),
    _fn("ASSERT_FALSE", (Param("Condition", N.BOOL, "the condition"), _MSG), "ASSERT_FALSE(tripped, 'no trip')"),
    _fn(
        "ASSERT_EQUAL",
        (
            Param("Expected", N.ANY_ELEMENTARY, "Expected", same="T"),
            Param("Actual", N.ANY_ELEMENTARY, "Actual", same="T"),
            _MSG,
        ),
        "ASSERT_EQUAL(E_State#Running, state, 'the state')",
    ),
    _fn(
        "ASSERT_NOT_EQUAL",
        (
            Param("Expected", N.ANY_ELEMENTARY, "Expected", same="T"),
            Param("Actual", N.ANY_ELEMENTARY, "Actual", same="T"),
            _MSG,
        ),
        "ASSERT_NOT_EQUAL(0, count, 'something was counted')",
    ),
    _fn(
        "ASSERT_NEAR",
        (
            Param("Expected", N.ANY_REAL, "Expected", same="T"),
            Param("Actual", N.ANY_REAL, "Actual", same="T"),
            Param("Delta", N.ANY_REAL, "Delta", same="T"),
            _MSG,
        ),
        "ASSERT_NEAR(80.0, speed, 0.5, 'the pump at 80 %')",
    ),
    _fn("TEST_FINISHED", (), "TEST_FINISHED()"),
    _fn(
        "SIM_FAULT",
        (
            Param("Sim", N.STRING, "the [[sim]] name"),
            Param("Fault", N.STRING, "the fault"),
            Param("Value", N.ANY_REAL, "the fault's value", same="V"),
            Param("On", N.BOOL, "On"),
        ),
        "SIM_FAULT(simName, faultName, 0, inject)",
    ),
)


@dataclass(frozen=True)
class Simulated:
    """A simulated device a test may fault: its [[sim]] name, the simulator
    (it takes inject(fault, value, on)) and its device's faults by name."""

    name: str
    simulator: Any
    faults: dict


@dataclass(frozen=True)
class Failure:
    """One failed assertion: where, which, the message, both values as ST literals."""

    site: CallSite
    function: str
    message: str
    expected: str
    actual: str
    time_ns: int  # engine time of the cycle it failed in
    detail: str = ""  # a further line (TcUnit's own message of a failed assert)

    def describe(self) -> str:
        """The lines a report shows."""
        head = f"{self.site}: {self.function} failed"
        if self.message:
            head += f": {self.message}"
        text = f"{head}\n  expected: {self.expected}\n  actual:   {self.actual}"
        return f"{text}\n  {self.detail}" if self.detail else text


@dataclass
class Recorder:
    """The service behind the assertions of one test run (one engine)."""

    clock: Any = None  # the engine's clock, for the time of a failure
    simulated: dict = field(default_factory=dict)  # [[sim]] name, upper case -> Simulated
    failures: list[Failure] = field(default_factory=list)
    asserts: int = 0
    finished: bool = False
    faults_on: set = field(default_factory=set)  # (sim, fault) SIM_FAULT holds on

    def request(self, name: str, *args: Any) -> bool:
        *values, site = args
        if name == "TEST_FINISHED":
            self.finished = True
            return True
        if name == "SIM_FAULT":
            return self._sim_fault(site, *values)
        self.asserts += 1
        handler = getattr(self, "_" + name.lower())
        return handler(site, *values)

    def _fail(self, site: CallSite, name: str, message: str, expected: str, actual: str) -> bool:
        now = self.clock.now_ns() if self.clock is not None else 0
        self.failures.append(Failure(site, name, message, expected, actual, now))
        return False

    def _assert_true(self, site: CallSite, cond: bool, message: str) -> bool:
        return bool(cond) or self._fail(site, "ASSERT_TRUE", message, "TRUE", "FALSE")

    def _assert_false(self, site: CallSite, cond: bool, message: str) -> bool:
        return not cond or self._fail(site, "ASSERT_FALSE", message, "FALSE", "TRUE")

    def _assert_equal(self, site: CallSite, expected, actual, message: str) -> bool:
        if expected == actual:
            return True
        t = site.types[0]
        return self._fail(site, "ASSERT_EQUAL", message, iec_literal(t, expected), iec_literal(t, actual))

    def _assert_not_equal(self, site: CallSite, expected, actual, message: str) -> bool:
        if expected != actual:
            return True
        t = site.types[0]
        text = iec_literal(t, actual)
        return self._fail(site, "ASSERT_NOT_EQUAL", message, f"not {iec_literal(t, expected)}", text)

    def _assert_near(self, site: CallSite, expected, actual, delta, message: str) -> bool:
        if math.isfinite(expected) and math.isfinite(actual) and abs(expected - actual) <= abs(delta):
            return True
        t = site.types[0]
        return self._fail(
            site,
            "ASSERT_NEAR",
            message,
            f"{iec_literal(t, expected)} +/- {iec_literal(t, abs(delta))}",
            iec_literal(t, actual),
        )

    def _sim_fault(self, site: CallSite, sim: str, fault: str, value: float, on: bool) -> bool:
        """Edge-triggered, as a PLC command is: the fault is injected when On
        becomes TRUE and, if it lasts, undone when On becomes FALSE. A name
        that does not exist fails the test, naming what does."""
        target = self.simulated.get(sim.upper())
        if target is None:
            names = ", ".join(s.name for s in self.simulated.values()) or "none in this configuration"
            return self._fail(site, "SIM_FAULT", f"no simulated device {sim!r}", f"one of: {names}", repr(sim))
        kind = target.faults.get(fault.lower())
        if kind is None:
            names = ", ".join(target.faults)
            return self._fail(
                site, "SIM_FAULT", f"{target.name} has no fault {fault!r}", f"one of: {names}", repr(fault)
            )
        key = (target.name, kind.name)
        if bool(on) == (key in self.faults_on):
            return True
        if on:
            self.faults_on.add(key)
            target.simulator.inject(kind.name, value, True)
        else:
            self.faults_on.discard(key)
            if kind.lasting:
                target.simulator.inject(kind.name, value, False)
        return True
