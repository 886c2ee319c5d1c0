"""A library's Python functions for the tests of StdFunc context and
pointer parameters (tests/program/test_context_functions.py,
tests/engine/test_task_state.py): what a vendor library's functions read
of the engine (the date, the running task) and of memory."""

from __future__ import annotations

from softplc.fblocks.iec.functions import StdFunc
from softplc.runtime.st.rtlib.refs import BytePtr

FUNCTIONS = {
    "DATE_NS": StdFunc("DATE_NS", (), "LINT", lambda ctx: ctx.date_ns(), context=True),
    "TASK_INDEX": StdFunc("TASK_INDEX", (), "DINT", lambda ctx: ctx.task.index, context=True),
    "TASK_CYCLES": StdFunc("TASK_CYCLES", (), "UDINT", lambda ctx: ctx.task.cycles, context=True),
    "TASK_RELEASE_NS": StdFunc("TASK_RELEASE_NS", (), "LINT", lambda ctx: ctx.task.release_ns, context=True),
    # the n-th byte where p points: p arrives as a byte view of its target
    "PEEK": StdFunc(
        "PEEK",
        (("p", "POINTER TO BYTE"), ("n", "DINT")),
        "BYTE",
        lambda p, n: p.layout.read(p.holder, p.offset + n, 1)[0] if type(p) is BytePtr else -1,
    ),
}


def TASK_START(ns: dict, ctx) -> None:
    """Counts the task starts in the program's global TASK_STARTS, if it has one."""
    glob = ns.get("_G")
    for name, attr, _ty, _section in getattr(type(glob), "_VARS_", ()):
        if name.upper() == "TASK_STARTS":
            setattr(glob, attr, getattr(glob, attr) + 1)
