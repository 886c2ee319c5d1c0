"""The native functions behind softplc's TcUnit: what the library's ST hands
to the service that keeps TcUnit's books (service.py), bound by the test
runner (runtime/testing/tcunit.py) as ``ctx.services["tcunit"]``.

All but one are the library's own (``__TCUNIT_...``, called from its ST
files, never from a user's code); ``AssertEquals`` is TcUnit's assert of
two values of ANY type (tcunit.org, API: "AssertEquals"): its inputs are
not elementary, which a METHOD of ST cannot take here, so it is a native
function a test suite's methods call as they would the method.

Run without the test runner (``softplc run`` of a project with TcUnit
tests), the calls go to the fallback: RUN() does nothing and the asserts
are not recorded, with one warning in the log.
"""

from __future__ import annotations

import logging
from typing import Any

from softplc.runtime.st import native as N
from softplc.runtime.st.native import NativeFunction, Param

SERVICE = "tcunit"

log = logging.getLogger("softplc.tcunit")


class _Idle:
    """The fallback: TcUnit's tests run under ``softplc test`` only."""

    def __init__(self) -> None:
        self.warned = False

    def request(self, name: str, *args: Any) -> Any:
        if not self.warned:
            self.warned = True
            log.warning("TcUnit: the test suites run under `softplc test`; here RUN() does nothing")
        return False


_IDLE = _Idle()


def _fn(name: str, params: tuple, usage: str, site: bool = False) -> NativeFunction:
    return NativeFunction(name, params, service=SERVICE, fallback=_IDLE, usage=usage, site=site)


_NAME = Param("TestName", N.STRING, "the test's name")
_MSG = Param("Message", N.STRING, "the message", default="")
_KIND = Param("Kind", N.STRING, "the assert")

NATIVES: tuple[NativeFunction, ...] = (
    _fn("__TCUNIT_RUN", (Param("InSequence", N.BOOL, "in sequence"),), "__TCUNIT_RUN(FALSE)"),
    _fn(
        "__TCUNIT_TEST",
        (_NAME, Param("Ordered", N.BOOL, "ordered")),
        "__TCUNIT_TEST(TestName, FALSE)",
        site=True,
    ),
    _fn("__TCUNIT_FINISHED", (_NAME, Param("Named", N.BOOL, "named")), "__TCUNIT_FINISHED(TestName, TRUE)"),
    _fn("__TCUNIT_IS_FINISHED", (_NAME,), "__TCUNIT_IS_FINISHED(TestName)"),
    _fn(
        "__TCUNIT_EQUALS",
        (
            Param("Holds", N.BOOL, "whether it holds"),
            _KIND,
            Param("Expected", N.ANY_ELEMENTARY, "Expected", same="T"),
            Param("Actual", N.ANY_ELEMENTARY, "Actual", same="T"),
            _MSG,
        ),
        "__TCUNIT_EQUALS(Expected = Actual, 'AssertEquals_INT', Expected, Actual, Message)",
        site=True,
    ),
    _fn(
        "__TCUNIT_ARRAYS",
        (
            _KIND,
            Param("Expecteds", N.ANY, "Expecteds"),
            Param("Actuals", N.ANY, "Actuals"),
            Param("Delta", N.ANY_REAL, "Delta"),
            _MSG,
        ),
        "__TCUNIT_ARRAYS('AssertArrayEquals_INT', Expecteds, Actuals, 0.0, Message)",
        site=True,
    ),
    _fn(
        "ASSERTEQUALS",
        (Param("Expected", N.ANY, "Expected", same="T"), Param("Actual", N.ANY, "Actual", same="T"), _MSG),
        "AssertEquals(Expected := a, Actual := b, Message := 'a and b differ')",
        site=True,
    ),
    _fn(
        "__TCUNIT_LOG",
        (
            Param("MsgCtrlMask", N.ANY_INT, "the message type"),
            Param("MsgFmtStr", N.STRING, "the format"),
            Param("StrArg", N.STRING, "the argument"),
        ),
        "__TCUNIT_LOG(msgCtrlMask, msgFmtStr, strArg)",
    ),
)
