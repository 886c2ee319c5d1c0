"""Tc2_System's functions written in Python: memory through pointers, the
clock and the task, ADSLOG* (fblocks/libs/memory.py, filetime.py). The
Beckhoff Information System page of each is named at its definition.
"""

from __future__ import annotations

import logging

from softplc.fblocks.iec.functions import StdFunc
from softplc.fblocks.libs import filetime, memory

from .task_info import TASK_START  # noqa: F401  (the loaded program's task hook)

_PTR = "POINTER TO BYTE"  # PVOID: any pointer, as a byte view of its target
log = logging.getLogger("softplc.plc")

FUNCTIONS: dict[str, StdFunc] = {}


def _def(name: str, params, ret: str, impl, context: bool = False) -> None:
    FUNCTIONS[name] = StdFunc(name, tuple(params), ret, impl, context=context)


# ---------------------------------------------------------------- memory
# MEMCPY, MEMMOVE: "0: incorrect parameter values (destAddr == 0 or
# srcAddr == 0 or n == 0); > 0: if successful, the number of bytes copied
# (n)". MEMCPY's behaviour on overlapping areas is undefined; here both
# read first and write then, which is MEMMOVE's.


def _memcpy(dest, src, n: int, fn: str = "MEMCPY") -> int:
    if dest is None or src is None or n <= 0:
        return 0
    memory.write(dest, memory.read(src, n, fn), fn)
    return n


def _memmove(dest, src, n: int) -> int:
    return _memcpy(dest, src, n, "MEMMOVE")


def _memset(dest, fill: int, n: int) -> int:
    """MEMSET: n bytes at destAddr set to fillByte; 0 for destAddr == 0 or n == 0."""
    if dest is None or n <= 0:
        return 0
    memory.write(dest, bytes([fill & 0xFF]) * n, "MEMSET")
    return n


def _memcmp(a, b, n: int) -> int:
    """MEMCMP: the first differing byte of pBuf1 lower -1, greater 1, none
    0; 16#FF for incorrect parameter values (pBuf1 = 0 or pBuf2 = 0 or n = 0)."""
    if a is None or b is None or n <= 0:
        return 0xFF
    x, y = memory.read(a, n, "MEMCMP"), memory.read(b, n, "MEMCMP")
    return 0 if x == y else (-1 if x < y else 1)


_def("MEMCPY", (("destAddr", _PTR), ("srcAddr", _PTR), ("n", "UDINT")), "UDINT", _memcpy)  # Tc2_System, MEMCPY
_def("MEMMOVE", (("destAddr", _PTR), ("srcAddr", _PTR), ("n", "UDINT")), "UDINT", _memmove)  # Tc2_System, MEMMOVE
_def("MEMSET", (("destAddr", _PTR), ("fillByte", "USINT"), ("n", "UDINT")), "UDINT", _memset)  # Tc2_System, MEMSET
_def("MEMCMP", (("pBuf1", _PTR), ("pBuf2", _PTR), ("n", "UDINT")), "DINT", _memcmp)  # Tc2_System, MEMCMP


# ---------------------------------------------------------------- clock and task
# F_GetSystemTime: "the operating system timestamp ... the number of 100 ns
# intervals since January 1, 1601 (UTC)". F_GetTaskTime: "the start time of
# the task (time at which the task should start)", same unit. Here the
# engine's date (filetime.py): in virtual time the virtual clock.


def _system_time(ctx) -> int:
    return filetime.now(ctx)


def _task_time(ctx) -> int:
    return filetime.from_unix_ns(ctx.epoch_ns + ctx.task.release_ns)


def _task_index(ctx) -> int:
    """GETCURTASKINDEXEX: the index of the task the caller runs in (1..,
    the configuration's order of tasks), the index of _TaskInfo."""
    return ctx.task.index


def _cpu_counter(ctx) -> int:
    """GETCPUCOUNTER's value: the engine clock in 100 ns ticks."""
    return ctx.clock_ns() // 100


_def("F_GETSYSTEMTIME", (), "ULINT", _system_time, context=True)  # Tc2_System, F_GetSystemTime
_def("F_GETTASKTIME", (), "ULINT", _task_time, context=True)  # Tc2_System, F_GetTaskTime
_def("GETCURTASKINDEXEX", (), "DINT", _task_index, context=True)  # Tc2_System, GETCURTASKINDEXEX
_def("F_GETCPUCOUNTER100NS", (), "ULINT", _cpu_counter, context=True)  # softplc's: GETCPUCOUNTER reads it


# ---------------------------------------------------------------- ADSLOG*
# ADSLOGSTR, ADSLOGDINT, ADSLOGLREAL: "outputs a message box with a
# predefinable text to the screen and writes an entry to the system's event
# log"; the format string holds %s (%d, %f) where the argument goes; the
# message is limited to 253 bytes; "the return parameter contains the
# function error code, or 0 if successful". Here the message goes to
# softplc's log (logger softplc.plc): ADSLOG_MSGTYPE_ERROR (16#4) as an
# error, _WARN (16#2) as a warning, anything else as information.

_ERROR, _WARN = 0x4, 0x2


def _adslog(mask: int, text: str) -> int:
    level = logging.ERROR if mask & _ERROR else logging.WARNING if mask & _WARN else logging.INFO
    log.log(level, "%s", text[:253])
    return 0


def _adslogstr(mask: int, fmt: str, arg: str) -> int:
    return _adslog(mask, fmt.replace("%s", arg, 1))


def _adslogdint(mask: int, fmt: str, arg: int) -> int:
    return _adslog(mask, fmt.replace("%d", str(arg), 1))


def _adsloglreal(mask: int, fmt: str, arg: float) -> int:
    return _adslog(mask, fmt.replace("%f", f"{arg:f}", 1))


_MSG = (("msgCtrlMask", "DWORD"), ("msgFmtStr", "STRING"))
_def("ADSLOGSTR", (*_MSG, ("strArg", "STRING")), "DINT", _adslogstr)  # Tc2_System, ADSLOGSTR
_def("ADSLOGDINT", (*_MSG, ("dintArg", "DINT")), "DINT", _adslogdint)  # Tc2_System, ADSLOGDINT
_def("ADSLOGLREAL", (*_MSG, ("lrealArg", "LREAL")), "DINT", _adsloglreal)  # Tc2_System, ADSLOGLREAL
