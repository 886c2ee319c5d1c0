"""The scan engine: one scan = read inputs, run the due tasks in priority
order, write outputs (DESIGN.md). Everything here runs in one thread, the
scan thread; drivers do their bus work in their own threads and meet the
scan only in read_inputs / write_outputs.

    engine = Engine(program, tasks, clock=VirtualClock())
    engine.start()                 # instances, retained values, drivers
    engine.run(duration_ns=10**9)  # or cycles=N; returns, the engine stays usable
    engine.stop()                  # outputs safe, retain saved, drivers closed

A runtime fault in a task (division by zero, bounds, watchdog ...) stops
that task, or every task with on_fault="plc"; from that tick on the drivers
are handed the safe output values, and the engine goes on serving: inputs
are read, the other tasks run (on_fault="task"), PLC_DIAG tells programs,
until restart() brings the faulted tasks back.

request_stop() (a signal) ends the run after the current tick; a task that
is in a loop then ends its cycle at the loop's next watchdog check instead
of finishing it, and that tick hands the drivers the safe output values.
"""

from __future__ import annotations

import logging
import threading
import time
from collections import deque
from collections.abc import Callable
from dataclasses import dataclass
from typing import TYPE_CHECKING

from ..config.values import cut
from ..image.address import default_type
from ..image.memory import ProcessImage
from ..program import ExecContext, Program
from ..st import types as T
from ..st.faults import STFault, fault_from_exception
from ..st.rtlib import rt_oop
from . import retain as R
from .clock import VirtualClock
from .cputime import COLLECTOR as _COLLECTOR
from .diag import DiagVariable
from .inspection import Inspection
from .lock_share import scan_ends
from .retain_file import ForeignRetainFile
from .tasks import Task

if TYPE_CHECKING:
    from .scenario import Scenario

log = logging.getLogger("softplc.engine")

ON_FAULT = ("task", "plc")
#: in virtual time, how old (wall time) the last reading of the scan thread's
#: CPU time may be for a tick to count from it (see Engine.__init__)
CPU_SAMPLE_NS = 1_000_000
START_MODES = ("warm", "cold")


class EngineError(Exception):
    """The engine cannot start: the message says where and what to change."""


@dataclass
class FaultRecord:
    task: str
    fault: STFault
    time_ns: int
    cycle: int

    def __str__(self) -> str:
        return f"task {self.task}: {self.fault}"


class Engine(Inspection):
    def __init__(
        self,
        program: Program,
        tasks: list,
        *,
        clock=None,
        image: ProcessImage | None = None,
        drivers=(),
        on_fault: str = "task",
        safe_outputs=(),
        retain_store=None,
        retain_period_ns: int = 1_000_000_000,
        start_mode: str = "warm",
        simulators: dict | None = None,
    ) -> None:
        if on_fault not in ON_FAULT:
            raise ValueError(f"on_fault must be one of {ON_FAULT}")
        if start_mode not in START_MODES:
            raise ValueError(f"start_mode must be one of {START_MODES}")
        self.program = program
        self.clock = clock if clock is not None else VirtualClock()
        self.image = image if image is not None else ProcessImage(program.profile.addressing)
        self.ctx = ExecContext(self.image)
        # The watchdog's verdict: wall time in real time. In virtual time a
        # cycle is late only when the scan thread's CPU time says so too, so
        # that the verdict does not depend on how busy the host is (a
        # descheduled test process is no slow program). CPU time is a system
        # call (a microsecond in a loop, three or four inside a tick, whose
        # caches it disturbs), wall time is not. So the engine reads CPU time
        # at a tick's start only when its last reading is more than
        # CPU_SAMPLE_NS of wall time old, and otherwise starts from that
        # reading (_tick_cpu_ns). It reads CPU time again only for a cycle
        # whose wall time is past its watchdog; that cycle's CPU time is then
        # the thread's since that reading, an upper bound: the drivers' work
        # and the tasks before it in the tick count too, and whatever the
        # thread computed in at most CPU_SAMPLE_NS before the tick. Time the
        # thread was descheduled never counts.
        self._tick_cpu_ns = 0
        self._cpu_read_wall_ns = -CPU_SAMPLE_NS - 1  # perf_counter_ns when _tick_cpu_ns was read
        if self.clock.virtual:
            self.ctx.timer = _COLLECTOR.cpu_s
        # the date and the clock the functions that read them see (F_GetSystemTime)
        self.ctx.epoch_ns = getattr(self.clock, "epoch_ns", self.ctx.epoch_ns)
        self.ctx.local_zone = not self.clock.virtual
        self.ctx.clock_ns = self.clock.now_ns
        self.drivers = list(drivers)
        #: the simulated devices of the configuration's [[sim]] tables, by name:
        #: what a test or a scheduled fault reaches (their inject() ...)
        self.simulators: dict = dict(simulators or {})
        for driver in self.drivers:  # a native function's service: the first driver's that offers it
            for name, service in driver.services.items():
                self.ctx.services.setdefault(name, service)
        self.on_fault = on_fault
        self.start_mode = start_mode
        self.retain_store = retain_store
        self.retain_period_ns = retain_period_ns
        ordered = sorted(enumerate(tasks), key=lambda it: (it[1].priority, it[0]))
        self.tasks = [Task(spec, order) for order, spec in ordered]
        self.ctx.tasks = [task.state for task in sorted(self.tasks, key=lambda t: t.order)]
        self.safe_q = self._safe_area(safe_outputs)
        self._safe_view = self.image.outputs_view(self.safe_q)
        self.outputs_safe = False
        self.faults: list[FaultRecord] = []
        self.restarts = 0
        #: bumped whenever program instances are replaced (a restart, an
        #: online change): whoever holds resolved paths resolves them again
        self.generation = 0
        #: called with the engine at the start of the next tick, before the
        #: inputs are read (an online change's swap); any thread may append
        self.between_scans: deque = deque()
        self.cycle = 0  # ticks since start
        self.started = False
        self.stopped = False
        self.after_tick: list[Callable] = []  # called with the engine after the outputs are written
        #: called with the engine at the start of every tick, before anything
        #: else (the snapshot hub waits there for a copy still being taken)
        self.before_tick: list[Callable] = []
        self.restore_report: R.RestoreReport | None = None
        #: the writes of [init] and [[schedule]] (engine/scenario.py; build.py installs it), or None
        self.scenario: Scenario | None = None
        self._stop_requested = False
        #: why the run stopped (request_stop's reason), None until then
        self.stop_reason: str | None = None
        self._restart_requested = False
        self._next_retain_ns = 0
        self._retain_plan: list = []
        self._retain_error: str | None = None
        self.ns: dict = {}
        self.instances: dict = {}  # instance name (upper) -> (name, POUInfo, object)
        self.diag: DiagVariable | None = None
        self.loaded = False
        #: forced values by key (a path): each callable stores its value again;
        #: tick() calls them after the inputs are read and after the tasks ran
        self.forces: dict[str, Callable[[], None]] = {}
        #: the forced values as the one who forced them gave them, by key (engine/access.py)
        self.forced_values: dict = {}
        #: the thread in run(), None outside it (engine/access.py queues writes for it)
        self.scan_thread: int | None = None
        #: called once with the engine in the next tick, after the inputs are
        #: read, before the forces and the tasks (a surface's write); any
        #: thread may append
        self.before_tasks: deque = deque()

    # ------------------------------------------------------------ set-up

    def _safe_area(self, safe_outputs) -> bytearray:
        """The %Q bytes the drivers get while outputs are held safe: 0 except
        the configured values."""
        scratch = ProcessImage(self.image.addressing, self.image.size)
        for item in safe_outputs:
            addr, value = item.address, item.value
            ty = default_type(addr)
            if isinstance(value, float) and addr.size in ("D", "L"):
                ty = T.REAL if addr.size == "D" else T.LREAL
            scratch.write(addr, value, ty)  # ValueError for a value the address cannot hold
        return scratch.areas["Q"]

    def start(self) -> None:
        """Instantiate the programs, restore retained values, start the drivers.
        Raises STFault when an initial value faults, EngineError otherwise."""
        if self.started:
            return
        self.load()
        started = []
        try:
            for driver in self.drivers:
                driver.start()
                started.append(driver)
        except Exception:
            for driver in started:
                driver.stop()
            raise
        for driver in self.drivers:
            driver.bind_program(self.ns["_G"])
        now = self.clock.now_ns()
        for task in self.tasks:
            task.next_ns = now
        self._next_retain_ns = now + self.retain_period_ns
        self.started = True
        for task in self.tasks:
            log.info("%s", task.describe())

    def load(self) -> None:
        """The first half of start(): the program instances with their
        initial values and the retained values, but no driver started and no
        scan run, so that variables can be read and set before the first
        scan (a test's initial conditions). start() calls it if need be."""
        if self.loaded:
            return
        self.ns = self.program.load(self.ctx)
        for task in self.tasks:
            for inst in task.spec.programs:
                key = inst.instance.upper()
                if key in self.instances:
                    raise EngineError(f"{inst.key}: program instance {inst.instance} is assigned twice")
                info = self.program.pou(inst.program)
                self.instances[key] = (inst.instance, info, None)
                task.instances.append((inst.instance, info, None))
        self._instantiate(self.tasks)
        self.diag = DiagVariable(self.ns["_G"])
        self._retain_plan = self._plan_retain()
        if self.retain_store is not None:
            try:
                data, warning = self.retain_store.load()
            except ForeignRetainFile as exc:  # not the PLC's to read, rename or write over: no start
                raise EngineError(str(exc)) from None
            if warning:
                log.warning("%s", warning)
            self.restore_report = R.restore(self._retain_plan, data, self.start_mode)
            self._log_restore(self.restore_report)
        self.diag.set(StartMode=self.start_mode)
        self.loaded = True

    def _instantiate(self, tasks: list) -> None:
        """Fresh program instances for tasks (initial values run here)."""
        for task in tasks:
            fresh = []
            for name, info, _old in task.instances:
                try:
                    obj = self.ns[info.pyname]()
                except Exception as exc:
                    raise fault_from_exception(exc, self.program.linemaps) from None
                fresh.append((name, info, obj))
                self.instances[name.upper()] = (name, info, obj)
            task.instances = fresh
            task.calls = [self.program.configured(self.ns, name, obj) for name, _info, obj in fresh]

    def _plan_retain(self) -> list:
        return R.plan_retain(
            self.program.checked, {name: (info, obj) for name, info, obj in self.instances.values()}, self.ns["_G"]
        )

    def _log_restore(self, report) -> None:
        if report.restored:
            log.info("%s start: %d retained variable(s) restored", report.mode, len(report.restored))
        for path, reason in report.dropped:
            log.warning("%s start: %s initialised: %s", report.mode, path, reason)
        for path, where in report.repaired:
            log.warning(
                "%s start: %s restored, U+FFFD for a lone surrogate: %s", report.mode, path, cut(" ".join(where))
            )

    # ------------------------------------------------------------ running

    def run(self, cycles: int | None = None, duration_ns: int | None = None) -> int:
        """Scan until cycles ticks ran, the engine clock passed duration_ns
        from now, or request_stop(). Returns the number of ticks run."""
        if not self.started:
            self.start()
        clock = self.clock
        now = clock.now_ns()
        for task in self.tasks:  # what ran between start() and here (softplc run's servers, traces,
            if task.state.cycles == 0 and task.next_ns < now:  # watcher) is no first scan's lateness
                task.next_ns = now
        end_ns = None if duration_ns is None else now + duration_ns
        self.scan_thread = threading.get_ident()
        clock.claim_thread()
        try:
            return self._scan(cycles, end_ns)
        finally:
            self.scan_thread = None
            if not clock.virtual:
                scan_ends()  # background work no longer waits for a scan's idle

    def _scan(self, cycles: int | None, end_ns: int | None) -> int:
        clock, ran = self.clock, 0
        while not self._stop_requested and (cycles is None or ran < cycles):
            release = self.next_release()
            if end_ns is not None and release >= end_ns:
                clock.sleep_until(end_ns)
                break
            clock.sleep_until(release)
            if self._stop_requested:  # asked for while sleeping: no new scan
                break
            self.tick()
            ran += 1
        return ran

    def next_release(self) -> int:
        """When the next task is due. A task stopped by a fault keeps its
        release grid, so the engine goes on ticking (serving the drivers) at
        the same moments as before."""
        return min(task.next_ns for task in self.tasks)

    def tick(self) -> None:
        """One scan at the clock's current time."""
        for callback in self.before_tick:
            callback(self)
        if self._restart_requested:
            self._restart_requested = False
            self.restart()
        while self.between_scans:
            self.between_scans.popleft()(self)
        now = self.clock.now_ns()
        self.ctx.set_time(now)
        image = self.image
        if self.clock.virtual:
            wall = time.perf_counter_ns()
            if wall - self._cpu_read_wall_ns > CPU_SAMPLE_NS:
                self._tick_cpu_ns = _COLLECTOR.cpu_ns()
                self._cpu_read_wall_ns = wall
            # Virtual time: the bus work due by now happens first, in this
            # thread, so the inputs read below are the same on every run.
            for driver in self.drivers:
                driver.advance_to(now)
        for driver in self.drivers:
            driver.read_inputs(image)
        while self.before_tasks:
            self.before_tasks.popleft()(self)
        forces = list(self.forces.values())
        for apply in forces:  # over what the drivers read ...
            apply()
        mark = None  # the execution clock where the last task ended: the next one starts there
        same = now if self.clock.virtual else None  # the virtual clock stands still within a tick
        for task in self.tasks:
            if task.next_ns <= now:
                if task.fault is None:
                    mark = self._run_task(task, mark, same)
                else:
                    self._release_next(task, task.next_ns)
        for apply in forces:  # ... and over what the program wrote
            apply()
        out = self._safe_view if self.outputs_safe else image
        for driver in self.drivers:
            driver.write_outputs(out)
        self.cycle += 1
        if now >= self._next_retain_ns and self.retain_store is not None:
            self._next_retain_ns = now + self.retain_period_ns
            self.save_retain()
        for callback in tuple(self.after_tick):  # a callback may remove itself
            callback(self)

    def _run_task(self, task: Task, t0: int | None = None, now: int | None = None) -> int | None:
        """One cycle of a task. t0: perf_counter_ns where the task before it
        in this scan ended, or None to read it. Returns the counter where
        this one ended, for the next (None after a fault): between two tasks
        there is only this bookkeeping to count. now: the engine clock, when
        it cannot have moved since the tick read it (virtual time), else None."""
        clock = self.clock
        released = task.next_ns
        start_ns = clock.now_ns() if now is None else now
        counter = time.perf_counter_ns
        if t0 is None:
            t0 = counter()
        ctx = self.ctx
        budget = task.budget_s
        ctx.wall_deadline = t0 * 1e-9 + budget
        # the loops' check (ExecContext.check_watchdog) reads ctx.timer once
        # wall time is past wall_deadline: CPU time in virtual time, counted
        # from the tick's start as for the cycle's verdict below
        ctx.deadline = self._tick_cpu_ns * 1e-9 + budget if clock.virtual else ctx.wall_deadline
        ctx.watchdog_s = budget
        state = task.state
        state.cycles += 1
        state.release_ns = released
        try:
            ctx.begin_task(state)
            for call in task.calls:
                call()
        except Exception as exc:
            fault = fault_from_exception(exc, self.program.linemaps)
            if fault.kind == "stop":
                self._cut_short(task, fault)
            else:
                self._fault(task, fault)
            self._release_next(task, released)  # keep the grid: no second tick at this time
            return None
        t1 = counter()
        exec_ns = t1 - t0
        task.stats.record(exec_ns, start_ns - released)
        state.last_exec_ns = exec_ns
        state.overran = task.interval_ns is not None and exec_ns > task.interval_ns
        if task.watchdog_ns is not None:
            if exec_ns > task.watchdog_ns and clock.virtual:
                exec_ns = min(exec_ns, _COLLECTOR.cpu_ns() - self._tick_cpu_ns)
            if exec_ns > task.watchdog_ns:
                task.late_cycles += 1
                if task.late_cycles >= task.sensitivity:
                    self._fault(
                        task,
                        STFault(
                            "watchdog",
                            f"watchdog: {task.late_cycles} cycle(s) in a row longer than "
                            f"{task.watchdog_ns / 1e6:g} ms (last {exec_ns / 1e6:.3f} ms)",
                        ),
                    )
            else:
                task.late_cycles = 0
        self._release_next(task, released, now)
        return t1

    def _release_next(self, task: Task, released: int, end: int | None = None) -> None:
        if end is None:
            end = self.clock.now_ns()
        if task.interval_ns is None:
            task.next_ns = end + task.pause_ns
            return
        nxt = released + task.interval_ns
        if nxt <= end:  # ran past the next release: skip what was missed
            missed = (end - nxt) // task.interval_ns + 1
            if task.fault is None:
                task.stats.overruns += missed
            nxt += missed * task.interval_ns
        task.next_ns = nxt

    # ------------------------------------------------------------ faults

    def _fault(self, task: Task, fault: STFault) -> None:
        now = self.clock.now_ns()
        task.fault = fault
        task.stats.faults += 1
        record = FaultRecord(task.name, fault, now, self.cycle)
        self.faults.append(record)
        log.error("task %s stopped by a runtime fault: %s", task.name, fault)
        if self.on_fault == "plc":
            for other in self.tasks:
                if other.fault is None:
                    other.fault = fault
            log.error("on_fault = plc: every task is stopped")
        if not self.outputs_safe:
            log.warning("outputs are held at their safe values until a restart")
        self.outputs_safe = True
        assert self.diag is not None  # tasks run, and fault, only after start()
        self.diag.set(
            Faulted=True,
            OutputsSafe=True,
            FaultCount=len(self.faults),
            FaultTask=task.name,
            FaultKind=fault.kind,
            FaultText=fault.message,
            FaultWhere=str(fault.pos) if fault.pos else "",
        )

    def _cut_short(self, task: Task, ended: STFault) -> None:
        """A stop request ended the task's cycle in a loop: no fault of the
        program, but its outputs are half-computed, so the drivers get the
        safe values from this tick on (the run ends after it)."""
        where = f" at {ended.pos}" if ended.pos else ""
        log.warning(
            "task %s: %s: its cycle was ended in the loop%s; outputs go to their safe values",
            task.name,
            self.stop_reason or "stop requested",
            where,
        )
        self.outputs_safe = True

    def faulted_tasks(self) -> list:
        return [t for t in self.tasks if t.fault is not None]

    def request_restart(self) -> None:
        """Ask for restart() at the next tick; safe from a signal handler or another thread."""
        self._restart_requested = True

    def restart(self) -> bool:
        """Bring the faulted tasks back: their program instances start afresh
        with their RETAIN and PERSISTENT values kept (a warm start of those
        instances; global variables keep their values). False if no task was
        faulted."""
        faulted = self.faulted_tasks()
        if not faulted:
            return False
        carried = R.capture(self._retain_plan, self.clock.now_ns(), self.cycle)
        self._instantiate(faulted)
        self._retain_plan = self._plan_retain()
        R.restore(self._retain_plan, carried, "warm")
        for task in faulted:  # they run again at their next release
            task.fault = None
            task.late_cycles = 0
        self.outputs_safe = False
        self.restarts += 1
        self.generation += 1
        assert self.diag is not None  # a task faulted, so start() ran
        self.diag.set(Faulted=False, OutputsSafe=False, Restarts=self.restarts)
        log.warning("restarted task(s) %s; outputs live again", ", ".join(t.name for t in faulted))
        return True

    # ------------------------------------------------------------ stopping

    def request_stop(self, reason: str = "stop requested") -> None:
        """Make run() return after the current tick, a task in a loop ending
        its cycle at the loop's next watchdog check; safe from a signal
        handler. reason (e.g. "SIGTERM") is what the log says."""
        if self.stop_reason is None:
            self.stop_reason = reason
        self._stop_requested = True
        self.ctx.stop_reason = self.stop_reason

    def stop(self) -> None:
        """Outputs to their safe values, retained data saved, drivers closed."""
        if self.stopped or not self.started:
            if self.loaded and not self.stopped and self.retain_store is not None:
                self.retain_store.close()  # loaded, never started: nothing ran to save
            self.stopped = self.loaded
            return
        self.stopped = True
        self._exit_instances()
        self.outputs_safe = True
        for driver in self.drivers:
            driver.write_outputs(self._safe_view)
        if self.retain_store is not None:
            self.save_retain()
            self.retain_store.close()
        # bus drivers before the simulated devices they talk to (build.make_drivers
        # lists those first), so no master reports its devices going away
        for driver in reversed(self.drivers):
            driver.stop()

    def _exit_instances(self) -> None:
        """The FB_exit methods of the program's instances (CODESYS calls
        them before it removes the instances); a fault there is logged."""
        roots = [obj for _name, _info, obj in self.instances.values() if obj is not None] + [self.ns["_G"]]
        try:
            rt_oop.exit_instances(self.ns, roots)
        except Exception as exc:
            log.error("FB_exit: %s", fault_from_exception(exc, self.program.linemaps))

    def save_retain(self) -> None:
        if not self._retain_plan:
            return
        store = self.retain_store
        store.submit(R.capture(self._retain_plan, self.clock.now_ns(), self.cycle))
        # The writer thread reports a failed write here; say it once, not every period.
        if store.last_error != self._retain_error:
            self._retain_error = store.last_error
            if store.last_error:
                log.error("%s (retrying every period)", store.last_error)
            else:
                log.info("the retain file is written again")

    def now_ns(self) -> int:
        return self.clock.now_ns()
