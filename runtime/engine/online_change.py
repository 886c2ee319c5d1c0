"""Online change: a newly compiled program swapped into the running engine
between two scans, its variables keeping their values (engine/carry.py has
the rules), without a scan run twice. The compile shares the interpreter
lock with the scan: scans may start late while it runs (docs/guide/running.md "Online change").

    change = OnlineChange(engine, config)   # softplc run makes one
    change.start()                          # watches the ST files; SIGHUP calls wake()
    report = change.request("web page")     # compile now, swap at the next scan, wait
    print(report.summary())

What runs where:

  * compiling (parse, check, generate, Python's compile()) runs in the
    compile process, the PLC's only child, started with the watcher and
    kept; the caller's thread (the watcher's, a web request's) waits for it
    without the interpreter lock, reads the Program back (program/
    transfer.py: no compile() here), plans the tasks and executes the
    generated module (Program.module), never in the scan thread; a compile
    error leaves the running program untouched and the report carries the
    child's diagnostics;
  * the swap (apply_program) runs in the scan thread at the start of the
    next tick (Engine.between_scans), before the inputs are read: the new
    globals and program instances are made (FB_init with bInitRetains FALSE,
    bInCopyCode TRUE), the old instances get FB_exit(bInCopyCode := TRUE),
    the values are carried, the copied instances get FB_reinit (CODESYS's
    "Online Change" operating case); then the drivers are bound to the new
    globals, PLC_DIAG, the retain plan and the forces follow, and
    Engine.generation moves on so that watchers resolve their paths again.
    That tick then runs as any other: same release grid, same time.

A change of the tasks (a task's interval, priority or watchdog, a program
instance added, removed or of another PROGRAM) is refused: it needs a
restart. The process image is the machine's: the swap writes nothing into
it (a located variable's initial value included).
"""

from __future__ import annotations

import logging
import threading
import weakref
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from ..program import Program, transfer
from ..st.diagnostics import CompileError
from ..st.faults import fault_from_exception
from ..st.rtlib import rt_oop
from .carry import Carry, global_members, members
from .change_forces import rebind_forces
from .change_memory import collector_paused, dismantle, freeze_new_program
from .compile_process import CompileProcess, CompileProcessError
from .diag import DiagVariable
from .lock_share import background, pause
from .tasks import TaskSetupError, plan_tasks

log = logging.getLogger("softplc.online_change")

POLL_S = 0.5  # how often the watcher looks at the files' modification times (wall time)
WAIT_S = 10.0  # how long request() waits for the scan to take the change


@dataclass
class ChangeReport:
    """What an online change did (applied) or why it did not (errors)."""

    reason: str
    applied: bool = False
    errors: list = field(default_factory=list)  # lines: compile diagnostics (file:line:col: error E..), refusals
    diagnostics: list = field(default_factory=list)  # the compile errors as Diagnostic objects
    kept: list = field(default_factory=list)
    initialised: list = field(default_factory=list)
    reset: list = field(default_factory=list)  # (path, why)
    dropped: list = field(default_factory=list)
    forces: list = field(default_factory=list)  # (key, "kept" or "released: why")
    notes: list = field(default_factory=list)
    cycle: int | None = None  # the scan it was applied before

    def summary(self) -> str:
        if not self.applied:
            return f"online change ({self.reason}) NOT applied: " + (self.errors[0] if self.errors else "?")
        released = sum(1 for _k, how in self.forces if how != "kept")
        return (
            f"online change ({self.reason}) applied before scan {self.cycle}: "
            f"{len(self.kept)} kept, {len(self.initialised)} initialised, {len(self.reset)} reset, "
            f"{len(self.dropped)} dropped" + (f", {released} force(s) released" if released else "")
        )

    def lines(self) -> list:
        """The summary and the details, a line each, for the log."""
        out = [self.summary()]
        if not self.applied:
            return out + self.errors[1:]
        out += [f"  initialised: {p}" for p in self.initialised]
        out += [f"  reset: {p}: {why}" for p, why in self.reset]
        out += [f"  dropped: {p}" for p in self.dropped]
        out += [f"  force {k}: {how}" for k, how in self.forces]
        out += [f"  note: {n}" for n in self.notes]
        return out


# ================================================================ the swap


def apply_program(
    engine, program: Program, reason: str = "", module: dict | None = None, carry: Carry | None = None
) -> ChangeReport:
    """Swap program into engine now, carrying the values; call it between
    two scans in the scan thread (Engine.between_scans), or before the
    first. module: program.module(engine.ctx), carry: prepared_carry(the
    running program, program), both made beforehand off the scan thread.
    The engine is left as it was when the report is not applied."""
    report = ChangeReport(reason)
    engine.load()
    refusal = _instances_refused(engine, program)
    if refusal:
        report.errors.append(refusal)
        return report
    ns = module if module is not None else program.module(engine.ctx)
    saved = _EngineState(engine)
    image = {area: bytes(data) for area, data in engine.image.areas.items()}
    Program.attach(ns, engine.ctx)
    try:
        ns["_INIT_FLAGS"] = (False, True)  # FB_init(bInitRetains := FALSE, bInCopyCode := TRUE)
        try:
            program.make_globals(ns)
            engine.program, engine.ns = program, ns
            for task in engine.tasks:
                task.instances = [(n, program.pou(_type_of(task, n)), None) for n, _i, _o in task.instances]
            engine._instantiate(engine.tasks)
        finally:
            ns["_INIT_FLAGS"] = (True, False)
            for area, data in image.items():  # initial values of located variables: the image keeps its own
                engine.image.areas[area][:] = data
        roots = [obj for _n, _i, obj in saved.instances.values()] + [saved.ns["_G"]]
        try:
            rt_oop.exit_instances(saved.ns, roots, in_copy_code=True)
        except Exception as exc:
            raise _Refused(f"FB_exit: {fault_from_exception(exc, saved.program.linemaps)}") from None
        carried = _carry(saved, engine, program, carry)
        engine._retain_plan = engine._plan_retain()  # ValueError: two retained variables of one path
    except Exception as exc:  # STFault of an initial value or FB_init, a refusal: the old program goes on
        saved.restore(engine)
        if ns in engine.ctx.namespaces:
            engine.ctx.namespaces.remove(ns)
        report.errors.append(f"the new program cannot start: {exc}")
        return report
    if saved.ns in engine.ctx.namespaces:
        engine.ctx.namespaces.remove(saved.ns)
    for name in ("kept", "initialised", "reset", "dropped", "notes"):
        getattr(report, name).extend(getattr(carried.out, name))
    engine.diag = DiagVariable(ns["_G"])
    report.forces = rebind_forces(engine, saved.program, saved.ns, saved.instances, saved.forces)
    if engine.started:
        for driver in engine.drivers:
            driver.bind_program(ns["_G"])
    for obj in carried.copied:
        try:
            rt_oop.reinit_instance(obj)
        except Exception as exc:
            report.notes.append(f"FB_reinit: {fault_from_exception(exc, program.linemaps)}")
    engine.generation += 1
    report.applied = True
    report.cycle = engine.cycle
    return report


class _Refused(Exception):
    pass


class _EngineState:
    """What the swap replaces, to put back when the new program cannot start."""

    def __init__(self, engine) -> None:
        self.program, self.ns, self.diag = engine.program, engine.ns, engine.diag
        self.instances = dict(engine.instances)
        self.tasks = [(t.instances, t.calls) for t in engine.tasks]
        self.retain_plan = engine._retain_plan
        self.forces = dict(engine.forces)
        self.forced_values = dict(engine.forced_values)

    def restore(self, engine) -> None:
        engine.program, engine.ns, engine.diag = self.program, self.ns, self.diag
        engine.instances = dict(self.instances)
        for task, (instances, calls) in zip(engine.tasks, self.tasks):
            task.instances, task.calls = instances, calls
        engine._retain_plan = self.retain_plan


def _type_of(task, instance: str) -> str:
    for inst in task.spec.programs:
        if inst.instance.upper() == instance.upper():
            return inst.program
    raise KeyError(instance)


def _instances_refused(engine, program: Program) -> str | None:
    """Why program cannot replace the running one without a restart, or None."""
    programs = {name.upper() for name, kind in program.pous.items() if kind == "PROGRAM"}
    for task in engine.tasks:
        for inst in task.spec.programs:
            if inst.program.upper() not in programs:
                return (
                    f"program instance {inst.instance}: PROGRAM {inst.program} is not in the new "
                    "sources: that needs a restart"
                )
    return None


def tasks_refused(engine, specs: list) -> str | None:
    """Why the planned tasks specs differ from the running ones (a restart is needed), or None."""

    def key(spec) -> tuple:
        insts = tuple((i.instance.upper(), i.program.upper()) for i in spec.programs)
        return (spec.interval_ns, spec.pause_ns, spec.priority, spec.watchdog_ns, spec.sensitivity, insts)

    running = {t.spec.name.upper(): t.spec for t in engine.tasks}
    planned = {s.name.upper(): s for s in specs}
    for name in running.keys() | planned.keys():
        old, new = running.get(name), planned.get(name)
        if old is None or new is None:
            what = f"{new.name} is new" if new is not None else f"{old.name} is gone" if old is not None else ""
            return f"task {what}: a change of the tasks needs a restart"
        if key(old) != key(new):
            return f"task {new.name} changed (interval, priority, watchdog or program instances): that needs a restart"
    return None


def _new_carry(old: Program, new: Program) -> Carry:
    """A Carry from old to new, quiet about the libraries' globals."""
    return Carry(frozenset(n.upper() for n in new.library_globals | old.library_globals))


def prepared_carry(old: Program, new: Program) -> Carry:
    """The Carry of a change from old to new, with what depends on the
    types only worked out (in the requester's thread, before the swap)."""
    carry = _new_carry(old, new)
    carry.prepare(global_members(old.checked), global_members(new.checked))
    for info in new.checked.pous:
        if info.kind == "PROGRAM":
            pause()  # the requester's thread: while the scan sleeps
            try:
                before = old.pou(info.name)
            except KeyError:
                continue
            carry.prepare(members(None, before), members(None, info))
    return carry


def _carry(saved: _EngineState, engine, program: Program, carry: Carry | None) -> Carry:
    old_program = saved.program
    old_g, new_g = saved.ns["_G"], engine.ns["_G"]
    if carry is None:
        carry = _new_carry(old_program, program)
    carry.moved[id(old_g)] = new_g
    carry.members("", global_members(old_program.checked), global_members(program.checked), old_g, new_g)
    for key, (name, info, obj) in engine.instances.items():
        _old_name, old_info, old_obj = saved.instances[key]
        carry.moved[id(old_obj)] = obj
        carry.members(name, members(None, old_info), members(None, info), old_obj, obj)
    carry.finish()
    return carry


# ================================================================ requests and the watcher


class ChangeRequest:
    """A compiled change waiting for the scan (or already refused); wait() gives its report."""

    def __init__(self, reason: str, program: Program | None = None, module: dict | None = None) -> None:
        self.reason = reason
        self.program = program
        self.module = module
        self.report: ChangeReport | None = None
        self.replaced: tuple | None = None  # (program, module) set by the scan: released by wait()
        self.carry: tuple | None = None  # (the program it was prepared from, prepared_carry())
        self.done = threading.Event()
        self._engine: Any = None  # the engine that took it (wait() tears down while it sleeps)

    def refused(self, report: ChangeReport) -> ChangeRequest:
        self.report = report
        self.done.set()
        return self

    def __call__(self, engine) -> None:  # in the scan thread, between two scans
        assert self.program is not None
        self._engine = engine
        before, before_ns = engine.program, engine.ns
        prepared_for, carry = self.carry if self.carry is not None else (None, None)
        self.carry = None
        try:
            carry = carry if prepared_for is before else None  # another change came first: made here
            self.report = apply_program(engine, self.program, self.reason, self.module, carry)
        except Exception as exc:  # never into the scan
            self.report = ChangeReport(self.reason, errors=[f"the online change failed: {exc!r}"])
        if self.report.applied and before is not self.program:  # what nothing runs now
            self.replaced = (before, before_ns)
        else:
            self.replaced = (self.program, self.module)
        self.program = self.module = None
        self.done.set()

    def wait(self, timeout: float = WAIT_S) -> ChangeReport:
        """The report, once the scan has taken the change; the program it
        replaced (or the one refused) taken apart meanwhile, in this thread."""
        if not self.done.wait(timeout):
            return ChangeReport(
                self.reason,
                errors=[f"not applied yet: no scan within {timeout:g} s (it is applied at the next one)"],
            )
        assert self.report is not None
        replaced, self.replaced = self.replaced, None
        if replaced is not None and replaced[0] is not None:
            _scan_idle(self._engine)
            with background():
                if transfer.release(replaced[0], pause):
                    dismantle(replaced[1], pause)
            if self.report.applied and getattr(self._engine.program, "read_back", False):
                freeze_new_program()
        return self.report


def _scan_idle(engine, timeout: float = 1.0) -> None:
    """Return once the scan that took a change has ended and its thread
    goes to sleep (the real clock's on_idle): the teardown of the replaced
    program (some 7 ms of work, in steps) then runs while the scan sleeps,
    not beside the tasks of the scan the change was applied before, which
    it made late by as much (a live soak's overruns). At once in virtual
    time, and when nothing scans."""
    on_idle = getattr(engine.clock, "on_idle", None) if engine is not None else None
    if on_idle is None or engine.scan_thread is None or engine.scan_thread == threading.get_ident():
        return
    idle = threading.Event()
    on_idle(idle.set)
    try:
        idle.wait(timeout)
    finally:
        on_idle(idle.set, add=False)


class OnlineChange:
    """softplc run's online change: the configuration's ST files (and its
    libraries') compiled again when one changes, on SIGHUP (wake()) or on
    request(), and swapped in at the next scan. compile: what to compile,
    in the caller's thread (a test's, an embedding's hook); by default the
    configuration's programs, profile and libraries, in the compile process."""

    def __init__(self, engine, config, *, compile: Callable[[], Program] | None = None) -> None:
        self.engine = engine
        self.config = config
        self.worker = CompileProcess()  # started at the first compile, or by start()
        self._finalizer = weakref.finalize(self, self.worker.close)  # stop() not called: closed when dropped
        self._compile = compile or self._compile_config
        self._lock = threading.Lock()  # one compile at a time
        self._wake = threading.Event()
        self._woken_by = "SIGHUP"
        self._stop = threading.Event()
        self._thread: threading.Thread | None = None
        self.reports: list[ChangeReport] = []
        self._mtimes = self._stat()

    # ------------------------------------------------------------ compiling and asking the scan

    def _compile_config(self) -> Program:
        return self.worker.compile(self.config)

    def submit(self, reason: str) -> ChangeRequest:
        """Compile now (in this thread) and queue the swap for the next scan;
        the request is done already when the sources do not compile or the
        tasks changed."""
        with self._lock:
            request = ChangeRequest(reason)
            compiled: Program | ChangeReport | None = None

            def read_back() -> bool:
                return isinstance(compiled, Program) and compiled.read_back

            with collector_paused(read_back):  # and frozen or collected before it is loaded
                compiled = self._compiled(reason)
            with background():  # the scan waits for the interpreter lock 0.5 ms, not 5
                prepared = compiled if isinstance(compiled, ChangeReport) else self._loaded(reason, compiled)
                if isinstance(prepared, ChangeReport):
                    return request.refused(prepared)
                request.program, request.module = prepared
                running = self.engine.program
                if running is not None:
                    request.carry = (running, prepared_carry(running, request.program))
            self.engine.between_scans.append(request)
            return request

    def _compiled(self, reason: str) -> Program | ChangeReport:
        """The program compiled, or the report of why not."""
        try:
            return self._compile()
        except CompileError as exc:
            errors = [d for d in exc.diagnostics if d.is_error]
            report = ChangeReport(reason, diagnostics=errors)
            report.errors = [f"{len(errors)} compile error(s); the running program is unchanged"]
            report.errors += [d.format(exc.sources) for d in errors]
            return report
        except CompileProcessError as exc:
            return ChangeReport(reason, errors=[str(exc)])

    def _loaded(self, reason: str, program: Program) -> tuple | ChangeReport:
        """(the program, its module) loaded, or the report of why not. The
        module's classes and functions are made here, after the freeze: a
        class is a ring of its own, which only a collection frees when the
        module is replaced (a walk of a few thousand objects)."""
        try:
            where = str(self.config.path) if getattr(self.config, "path", None) else "<config>"
            refusal = tasks_refused(self.engine, plan_tasks(program, list(self.config.tasks), where))
            module = None if refusal else program.module(self.engine.ctx)
        except TaskSetupError as exc:
            refusal = str(exc)
        except Exception as exc:  # the module refused by the image (an address it does not have) ...
            refusal = f"the new program cannot be loaded: {exc}"
        if refusal:
            return ChangeReport(reason, errors=[refusal])
        return program, module

    def request(self, reason: str, timeout: float = WAIT_S) -> ChangeReport:
        """Compile, swap at the next scan, wait for it: the report (logged
        too). What the web page calls."""
        return self.record(self.submit(reason).wait(timeout))

    def record(self, report: ChangeReport) -> ChangeReport:
        """Keep and log a report."""
        self.reports.append(report)
        level = logging.INFO if report.applied else logging.ERROR
        for line in report.lines():
            log.log(level, "%s", line)
        return report

    # ------------------------------------------------------------ watching the files

    def files(self) -> list[Path]:
        """The files a change of which starts an online change."""
        cfg = self.config
        if cfg is None:
            return []
        out = [Path(p) for p in cfg.programs]
        for lib in cfg.libraries:
            out += lib.files()
        return out

    def _stat(self) -> dict:
        out: dict = {}
        for path in self.files():
            try:
                st = path.stat()
                out[path] = (st.st_mtime_ns, st.st_size)
            except OSError:
                out[path] = None
        return out

    def poll(self) -> list[Path]:
        """The files changed since the last poll (modification time or size)."""
        now = self._stat()
        changed = [p for p in now.keys() | self._mtimes.keys() if now.get(p) != self._mtimes.get(p)]
        self._mtimes = now
        return sorted(changed)

    def check(self) -> ChangeRequest | None:
        """One pass of the watcher: the files changed, or a wake() came →
        submit(); None when neither."""
        woken = self._wake.is_set()
        self._wake.clear()
        changed = self.poll()
        if not changed and not woken:
            return None
        reason = self._woken_by if woken else "changed: " + ", ".join(p.name for p in changed)
        return self.submit(reason)

    def wake(self, reason: str = "SIGHUP") -> None:
        """Ask the watcher thread for an online change now (safe from a signal handler)."""
        self._woken_by = reason
        self._wake.set()

    def start(self) -> None:
        """The compile process started and warmed (one compile of the
        configuration, in the background) and the file watcher."""
        self._thread = threading.Thread(target=self._run, name="softplc-online-change", daemon=True)
        self._thread.start()
        log.info("online change: watching %d file(s); SIGHUP compiles and swaps in now", len(self._mtimes))

    def warm(self) -> None:
        """The compile process started and its caches filled (the
        configuration compiled once, nothing swapped): start() does it
        first, so that the first change does not pay the start-up."""
        if self._compile == self._compile_config:
            with self._lock:
                self.worker.warm(self.config)

    def _run(self) -> None:
        try:
            self.warm()  # its start-up and first parse now, not at the first change
        except (CompileProcessError, OSError) as exc:
            if not self._stop.is_set():
                log.warning("online change: the compile process: %s (started again at the first change)", exc)
        while not self._stop.is_set():
            self._wake.wait(POLL_S)
            if self._stop.is_set():
                return
            try:
                request = self.check()
                if request is not None:
                    self.record(request.wait())
            except Exception:  # never let the watcher die silently
                log.exception("online change failed")

    def stop(self) -> None:
        self._stop.set()
        self._wake.set()
        if self._thread is not None:
            self._thread.join(timeout=5)
        self.worker.close()


__all__ = ["ChangeReport", "ChangeRequest", "OnlineChange", "apply_program", "prepared_carry", "tasks_refused"]
