"""A compiled program: loaded into a namespace bound to an ExecContext, its
POUs instantiated, run cycle by cycle."""

from __future__ import annotations

import builtins
import importlib
import time
from typing import Any

from ..image.memory import ProcessImage
from ..st import values
from ..st.check.checker import CheckedProgram
from ..st.codegen.codegen import GeneratedModule
from ..st.diagnostics import Diagnostic, SourceSet
from ..st.faults import RangeFault, fault_from_exception, out_of_bounds, out_of_range
from ..st.profile import Profile
from ..st.rtlib import refs, rt_oop, rt_sfc, rtlib
from .context import ExecContext, TaskState
from .variables import locate

# The only builtins generated code may use.
_BUILTINS = {
    name: getattr(builtins, name)
    for name in ("range", "len", "abs", "max", "min", "float", "int", "property", "__build_class__", "object", "bool")
}


def _with_fields(obj, setters):
    for attr, value in setters:
        setattr(obj, attr, value)
    return obj


def _check_index(i: int, lo: int, hi: int) -> int:
    if lo <= i <= hi:
        return i - lo
    return out_of_bounds(i, lo, hi)


def _check_range(v: int, lo: int, hi: int) -> int:
    if lo <= v <= hi:
        return v
    return out_of_range(v, lo, hi)


def _for_range(start: int, end: int, step: int) -> range:
    if step == 0:
        raise RangeFault("range", "FOR loop with step 0 never ends")
    return range(start, end + (1 if step > 0 else -1), step)


class Program:
    """A compiled set of POUs, ready to be instantiated by runners."""

    def __init__(
        self,
        profile: Profile,
        checked: CheckedProgram,
        gen: GeneratedModule,
        code,
        filename: str,
        warnings: list,
        sources: SourceSet,
        user_pous: dict,
        library_modules: tuple = (),
    ) -> None:
        self.profile = profile
        # the task hooks of the libraries' Python modules (a module's
        # TASK_START(namespace, ctx), called as each task cycle starts:
        # TwinCAT's _TaskInfo, fblocks/libs/tc2_system)
        self.task_hooks = tuple(
            hook
            for hook in (getattr(importlib.import_module(m), "TASK_START", None) for m in library_modules)
            if hook is not None
        )
        self.checked = checked
        self.generated = gen
        self.code = code
        self.filename = filename
        self.warnings: list[Diagnostic] = warnings
        self.sources = sources
        self.pous = user_pous
        self.read_back = False  # transfer.loads() sets it: taken apart when an online change replaces it
        self.linemaps = {filename: gen.linemap}
        # Globals the libraries declare (PLC_DIAG, a shipped library's constants): not the user's state.
        self.library_globals = frozenset(
            g.name
            for g in checked.globals
            if g.pos is not None and (g.pos.file.startswith("<lib>/") or g.pos.file in checked.library_files)
        )

    @property
    def python_source(self) -> str:
        return self.generated.source

    def locate(self, path: str, roots: tuple) -> tuple:
        """variables.locate, and a global named by its list as in ST
        (``GVL.speed``: the variable speed of the global variable list of
        GVL.st, namespaces.py) where no variable of the roots is named
        like the list."""
        try:
            return locate(path, roots)
        except KeyError:
            first, _, rest = path.partition(".")
            names = self.checked.global_lists.get(first.upper())
            if not names or rest.partition(".")[0].upper() not in names:
                raise
            return locate(rest, roots[-1:])

    def pou(self, name: str):
        for info in self.checked.pous:
            if info.name.upper() == name.upper():
                return info
        raise KeyError(name)

    def load(self, ctx: ExecContext | None = None) -> dict:
        """Execute the generated module in a fresh namespace bound to ctx;
        returns the namespace (classes, functions, globals ``_G``)."""
        ctx = ctx or ExecContext(ProcessImage(self.profile.addressing))
        ns = self.module(ctx)
        self.attach(ns, ctx)
        self.make_globals(ns)
        return ns

    def module(self, ctx: ExecContext) -> dict:
        """The generated module executed in a fresh namespace bound to ctx's
        image and services, but not yet reading its clock and with no
        globals object: load()'s first half, which touches nothing that is
        running (an online change prepares it off the scan thread)."""
        ns: dict[str, Any] = {
            "__builtins__": _BUILTINS,
            "__name__": "softplc_generated",
            "_ctx": ctx,
            "_f32": rtlib.f32,
            "_idiv": rtlib.idiv,
            "_imod": rtlib.imod,
            "_rdiv": rtlib.rdiv,
            "_expt": rtlib.expt,
            "_INF": float("inf"),
            "_NAN": float("nan"),
            "_AttrRef": refs.AttrRef,
            "_ItemRef": refs.ItemRef,
            "_ElemPtr": refs.ElemPtr,
            "_CellRef": refs.CellRef,
            "_AccessorRef": refs.AccessorRef,
            "_assign_into": values.assign_into,
            "_copy_value": values.copy_value,
            "_slot_assign": values.slot_assign,
            "_slot_copy": values.slot_copy,
            "_with_fields": _with_fields,
            "_deref": refs.deref,
            "_elem_ptr": refs.elem_ptr,
            "_ptr_add": refs.ptr_add,
            "_ptr_diff": refs.ptr_diff,
            "_same_ref": refs.same_ref,
            "_query_itf": rt_oop.query_interface,
            "_query_into": rt_oop.query_into,
            "_fb_args": rt_oop.fb_init_args,
            "_check_index": _check_index,
            "_check_range": _check_range,
            "_out_of_bounds": out_of_bounds,
            "_for_range": _for_range,
            "_watchdog": ctx.check_watchdog,
            "_loop": ctx.loop_range,
            "_native": ctx.call_native,
            "_SfcStep": rt_sfc.Step,
            "_SfcAction": rt_sfc.ActionFlags,
            "_SfcState": rt_sfc.SfcState,
            # FB_init's (bInitRetains, bInCopyCode): an online change makes
            # its instances with (FALSE, TRUE), as CODESYS does
            "_INIT_FLAGS": (True, False),
            "_TASK_HOOKS": self.task_hooks,
        }
        ns.update(self.generated.consts)
        image = ctx.image
        for idx, acc in self.generated.accessors.items():
            if acc.type is None:
                ns[f"_A{idx}t"] = image.table(acc.addr)
            else:
                get, set_ = image.accessor(acc.addr, acc.type)
                ns[f"_A{idx}g"], ns[f"_A{idx}s"] = get, set_
        exec(self.code, ns)
        return ns

    @staticmethod
    def attach(ns: dict, ctx: ExecContext) -> None:
        """The module reads ctx's clock from now on (TIME())."""
        ctx.namespaces.append(ns)
        ctx.set_time(ctx.now_ns)

    def make_globals(self, ns: dict) -> None:
        """The globals object ``_G`` with its initial values (STFault when one faults)."""
        try:
            # _G is bound first: initial values may take references to globals
            ns["_G"] = glob = ns["_Globals"].__new__(ns["_Globals"])
            glob.__init__()
        except Exception as exc:
            raise fault_from_exception(exc, self.linemaps) from None

    def configured(self, ns: dict, instance: str, obj) -> Any:
        """What a task calls each cycle for the program instance obj of the
        CONFIGURATION (named instance): obj itself, or obj with its
        VAR_CONFIG settings applied now and its configured addresses
        copied around each call (st/codegen/codegen_config.py)."""
        configure = ns.get("_VAR_CONFIG", {}).get(instance.upper())
        if configure is None:
            return obj
        try:
            return configure(obj)
        except Exception as exc:
            raise fault_from_exception(exc, self.linemaps) from None

    def runner(self, entry: str, cycle_time_ms: int = 10, ctx: ExecContext | None = None) -> Runner:
        info = self.pou(entry)
        if info.kind == "FUNCTION_BLOCK":
            raise KeyError(f"{entry} is a FUNCTION_BLOCK; run a PROGRAM or a FUNCTION")
        return Runner(self, info, cycle_time_ms, ctx)


class Runner:
    """Runs one PROGRAM (or calls one FUNCTION) cycle after cycle in virtual
    time: the task clock advances by the cycle time after each cycle."""

    def __init__(self, program: Program, info, cycle_time_ms: int, ctx: ExecContext | None) -> None:
        self.program = program
        self.info = info
        self.cycle_ns = int(cycle_time_ms * 1_000_000)
        if ctx is None:
            ctx = ExecContext(ProcessImage(program.profile.addressing))
            ctx.timer = time.thread_time  # virtual time: the watchdog counts this thread's CPU time
        self.ctx = ctx
        # the one task the program runs in (GETCURTASKINDEX answers 1)
        self.task = TaskState(1, "", self.cycle_ns)
        ctx.tasks = [self.task]
        self.ns = program.load(self.ctx)
        self.instance = None
        self.result = None
        self.result_type = info.return_type
        self.cycles = 0
        if info.kind == "PROGRAM":
            try:
                self.instance = self.ns[info.pyname]()
            except Exception as exc:
                raise fault_from_exception(exc, program.linemaps) from None
            self._call = self.instance
        else:
            fn = self.ns[info.pyname]
            self._call = lambda: setattr(self, "result", fn())

    @property
    def now_ms(self) -> float:
        return self.ctx.now_ns / 1_000_000

    @property
    def globals(self):
        return self.ns["_G"]

    def run(self, cycles: int = 1) -> None:
        ctx = self.ctx
        call = self._call
        task = self.task
        for _ in range(cycles):
            ctx.arm_watchdog()
            task.cycles += 1
            task.release_ns = ctx.now_ns
            try:
                ctx.begin_task(task)
                call()
            except Exception as exc:
                raise fault_from_exception(exc, self.program.linemaps) from None
            self.cycles += 1
            ctx.set_time(ctx.now_ns + self.cycle_ns)

    def exit(self) -> None:
        """Take the program down: the FB_exit methods of its instances
        (rt_oop.exit_instances), as the engine does when it stops."""
        roots = ([self.instance] if self.instance is not None else []) + [self.globals]
        try:
            rt_oop.exit_instances(self.ns, roots)
        except Exception as exc:
            raise fault_from_exception(exc, self.program.linemaps) from None

    def get(self, path: str):
        """The value of a variable by its ST path, e.g. 'counter.CV' or 'G_speed'."""
        roots = ((self.instance,) if self.instance is not None else ()) + (self.globals,)
        holder, attr, _ty = self.program.locate(path, roots)
        return getattr(holder, attr)
