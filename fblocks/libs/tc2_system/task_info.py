"""TwinCAT_SystemInfoVarList (task_info.st): the engine's tasks as
TwinCAT's _TaskInfo[] and _AppInfo tell them ("PlcTaskSystemInfo" and
"PlcAppSystemInfo", Beckhoff Information System, TwinCAT 3 PLC > Reference
programming). TASK_START runs as each task cycle starts (the loaded
program's task hook, runtime/program/context.py ExecContext.begin_task)
and fills the entry of that task:

  CycleTime      the task's interval in 100 ns units (0: freewheeling)
  Priority       the configured priority
  CycleCount     the cycles the task started, this one included (1 in its
                 first cycle); TwinCAT counts the system task's cycles, so
                 only differences mean something there as here
  FirstCycle     TRUE in the task's first cycle
  LastExecTime   how long the previous cycle ran, 100 ns units
  CycleTimeExceeded, RTViolation   the previous cycle ran past the interval
  DcTaskTime     the cycle's start, ns since 2000-01-01 (TwinCAT's DC time)
  TaskName       the configured name

The static fields of every task, and _AppInfo.TaskCnt, are written once.
"""

from __future__ import annotations

_DC_EPOCH_NS = 946_684_800 * 1_000_000_000  # 2000-01-01, as UTC ns since 1970
_SLOT = "_TC2_TASK_INFO"  # the namespace's bound _TaskInfo (or False: the program has none)


def _attrs(obj) -> dict:
    """UPPER ST name -> Python attribute of a generated object's variables."""
    return {name.upper(): attr for name, attr, _ty, _section in getattr(type(obj), "_VARS_", ())}


class _Bound:
    """The program's _TaskInfo array and _AppInfo structure, by attribute."""

    def __init__(self, tasks: list, fields: dict, app) -> None:
        self.tasks = tasks  # the ARRAY[1..n] OF PlcTaskSystemInfo, as a list
        self.f = fields  # UPPER field -> attribute
        self.app = app
        self.static_done = False

    def _set(self, info, field: str, value) -> None:
        attr = self.f.get(field)
        if attr is not None:
            setattr(info, attr, value)

    def _static(self, ctx) -> None:
        for state in ctx.tasks:
            if 0 < state.index <= len(self.tasks):
                info = self.tasks[state.index - 1]
                self._set(info, "CYCLETIME", state.interval_ns // 100)
                self._set(info, "PRIORITY", state.priority)
                self._set(info, "TASKNAME", state.name[:63])
        if self.app is not None:
            app = _attrs(self.app)
            if "TASKCNT" in app:
                setattr(self.app, app["TASKCNT"], len(ctx.tasks))
        self.static_done = True

    def update(self, ctx) -> None:
        if not self.static_done:
            self._static(ctx)
        state = ctx.task
        if not 0 < state.index <= len(self.tasks):
            return
        info = self.tasks[state.index - 1]
        self._set(info, "CYCLECOUNT", state.cycles & 0xFFFFFFFF)
        self._set(info, "FIRSTCYCLE", state.cycles == 1)
        self._set(info, "LASTEXECTIME", (state.last_exec_ns // 100) & 0xFFFFFFFF)
        self._set(info, "CYCLETIMEEXCEEDED", state.overran)
        self._set(info, "RTVIOLATION", state.overran)
        self._set(info, "DCTASKTIME", ctx.epoch_ns + state.release_ns - _DC_EPOCH_NS)


def _bind(glob) -> _Bound | bool:
    g = _attrs(glob)
    if "_TASKINFO" not in g:
        return False  # the program does not use TwinCAT_SystemInfoVarList
    tasks = getattr(glob, g["_TASKINFO"])
    fields = _attrs(tasks[0]) if len(tasks) else {}
    app = getattr(glob, g["_APPINFO"]) if "_APPINFO" in g else None
    return _Bound(tasks, fields, app)


def TASK_START(ns: dict, ctx) -> None:
    """The hook: the running task's _TaskInfo entry, as its cycle starts."""
    bound = ns.get(_SLOT)
    if bound is None:
        glob = ns.get("_G")
        if glob is None:
            return  # not loaded yet
        bound = ns[_SLOT] = _bind(glob)
    if isinstance(bound, _Bound):
        bound.update(ctx)
