"""Parse, check, generate and load: the high-level API of the language core.

    prog = compile_files(["plant.st"], profile="codesys")   # CompileError on errors
    r = prog.runner("Main", cycle_time_ms=10)
    r.run(100)                                              # STFault on a runtime fault

The IEC standard function blocks (fblocks/iec/*.st) are compiled into every
program; a user POU or type of the same name replaces the library one.
"""
from __future__ import annotations

import builtins
import functools
import itertools
import re
import time
from importlib import resources
from pathlib import Path
from typing import Any, Optional

from . import ast as A
from . import refs, rtlib, values
from . import types as T
from .checker import Checker, CheckedProgram
from .codegen import CodeGen, GeneratedModule
from .diagnostics import CompileError, Diagnostic, DiagnosticBag, SourceSet
from .faults import RangeFault, STFault, WatchdogFault, fault_from_exception, out_of_bounds, out_of_range
from .parser import parse_source
from .profile import Profile, get_profile
from ..image.memory import ProcessImage

_gen_counter = itertools.count(1)

# The only builtins generated code may use.
_BUILTINS = {name: getattr(builtins, name) for name in
             ("range", "len", "abs", "max", "min", "float", "int", "property", "__build_class__",
              "object", "bool")}


# Compiled into every program: the standard blocks and PLC_DIAG.
_ALWAYS = ("softplc.fblocks.iec", "softplc.fblocks.system")
# Compiled in only when a program names something they declare (and then
# with the library files those name in turn): the communication and device
# blocks. A program that never mentions LTMR_CONTROL does not pay for it,
# and a user POU that replaces a standard block (its own TON) cannot break a
# device block it does not use.
_ON_DEMAND = ("softplc.fblocks.comm", "softplc.fblocks.vendor")
_WORD = re.compile(r"[A-Za-z_][A-Za-z0-9_]*")


def _library_sources(packages=_ALWAYS + _ON_DEMAND) -> list:
    """(path, text) of the ST library files of packages."""
    out = []
    for package in packages:
        root = resources.files(package)
        for entry in sorted(root.iterdir(), key=lambda p: p.name):
            if entry.name.endswith(".st"):
                out.append((f"<lib>/{package.rsplit('.', 1)[-1]}/{entry.name}", entry.read_text("utf-8")))
    return out


def _declared(sf: A.SourceFile) -> set:
    """Every name a library file declares: POUs, types and globals."""
    names = _decl_names(sf)
    for d in sf.decls:
        if isinstance(d, A.VarBlock):
            names.update(v.name.upper() for v in d.decls)
    return names


@functools.lru_cache(maxsize=None)
def _library_index(name: str, text: str) -> tuple:
    """(names the file declares, words it uses) of an on-demand library file,
    parsed once per process: the choice of files then costs no parsing."""
    return (frozenset(_declared(parse_source(text, name, DiagnosticBag()))),
            frozenset(w.upper() for w in _WORD.findall(text)))


def _needed_library(files: list, user_words: set) -> list:
    """(path, text) of the always-compiled files, and of the on-demand ones
    that the user's words (or an already needed library file's words) name."""
    on_demand = tuple(f"<lib>/{p.rsplit('.', 1)[-1]}/" for p in _ON_DEMAND)
    needed = [f for f in files if not f[0].startswith(on_demand)]
    pending = [f for f in files if f[0].startswith(on_demand)]
    words = set(user_words)
    grew = True
    while grew:
        grew = False
        for name, text in list(pending):
            declared, used = _library_index(name, text)
            if declared & words:
                needed.append((name, text))
                pending.remove((name, text))
                words |= used
                grew = True
    return needed


def _std_functions() -> dict:
    from softplc.fblocks.iec.functions import STANDARD_FUNCTIONS
    return STANDARD_FUNCTIONS


def _natives() -> dict:
    from softplc.runtime.io.modbus_exchange import MODBUS_EXCHANGE
    from softplc.runtime.io.sdo_exchange import READ_VAR, WRITE_VAR
    return {fn.name: fn for fn in (READ_VAR, WRITE_VAR, MODBUS_EXCHANGE)}


def _read_sources(paths: list, texts: Optional[dict], diags: DiagnosticBag, sources: SourceSet) -> tuple:
    """(parsed files, the set of words in them, upper case)."""
    files = []
    for p in paths:
        try:
            text = Path(p).read_text(encoding="utf-8-sig")
        except UnicodeDecodeError:
            try:  # Windows tools still write Latin-1 ST files
                text = Path(p).read_text(encoding="latin-1")
            except OSError as exc:
                diags.error("E000", f"cannot read the file: {exc.strerror or exc}", A.Pos(str(p), 1, 1))
                continue
        except OSError as exc:
            diags.error("E000", f"cannot read the file: {exc.strerror or exc}", A.Pos(str(p), 1, 1))
            continue
        files.append((str(p), text))
    for name, text in (texts or {}).items():
        files.append((name, text))
    parsed = []
    words: set = set()
    for name, text in files:
        sources.add(name, text)
        parsed.append(parse_source(text, name, diags))
        words.update(w.upper() for w in _WORD.findall(text))
    return parsed, words


def _decl_names(sf: A.SourceFile) -> set:
    return {d.name.upper() for d in sf.decls if isinstance(d, (A.POU, A.TypeDecl))}


def _front_end(paths: list, profile: Profile, texts: Optional[dict]):
    diags = DiagnosticBag()
    sources = SourceSet()
    user, user_words = _read_sources(paths, texts, diags, sources)
    user_names = set().union(*(_decl_names(sf) for sf in user)) if user else set()
    lib_diags = DiagnosticBag()
    library = []
    for name, text in _needed_library(_library_sources(), user_words):
        sources.add(name, text)
        sf = parse_source(text, name, lib_diags)
        sf.decls = [d for d in sf.decls
                    if not (isinstance(d, (A.POU, A.TypeDecl)) and d.name.upper() in user_names)]
        library.append(sf)
    checker = Checker(profile, lib_diags if not user else diags, _std_functions(), _natives())
    checked = checker.run(library + user, library_files=tuple(sf.path for sf in library))
    diags.extend(d for d in lib_diags.items if d.is_error)
    return diags, sources, checked, user


def _back_end(checked: CheckedProgram, prof: Profile, diags: DiagnosticBag, where: A.Pos):
    """Generate and compile the Python module; CPython's own limits (20
    nested loops, 200 nested parentheses) become diagnostic E006.
    Returns (GeneratedModule, code object, filename), or None on E006."""
    gen = CodeGen(checked, prof).generate()
    filename = f"<softplc-{next(_gen_counter)}>"
    try:
        return gen, compile(gen.source, filename, "exec"), filename
    except (SyntaxError, RecursionError, MemoryError) as exc:
        line = getattr(exc, "lineno", None)
        diags.error("E006", "the program is nested too deeply for the Python compiler "
                    f"({getattr(exc, 'msg', None) or type(exc).__name__})",
                    (gen.linemap.get(line) if line else None) or where,
                    "move inner loops or long expressions into FUNCTIONs or intermediate variables")
        return None


def _first_position(paths: list, texts: Optional[dict]) -> A.Pos:
    names = [str(p) for p in paths] + list(texts or {})
    return A.Pos(names[0] if names else "<input>", 1, 1)


def check_files(paths: list, profile: str | Profile = "codesys", texts: Optional[dict] = None):
    """Diagnostics of the files (errors and warnings, sorted) and their texts.
    Never raises for problems in the sources. Reports exactly what
    compile_files would: the back end runs too when the front end is clean."""
    prof = get_profile(profile) if isinstance(profile, str) else profile
    diags, sources, checked, _ = _front_end(list(paths), prof, texts)
    if not diags.has_errors:
        _back_end(checked, prof, diags, _first_position(paths, texts))
    return diags.sorted(), sources


def compile_files(paths: list, profile: str | Profile = "codesys", *,
                  texts: Optional[dict] = None) -> "Program":
    """Compile ST files (and/or in-memory texts: name -> source) into a
    loadable Program. Raises CompileError with every diagnostic on errors."""
    prof = get_profile(profile) if isinstance(profile, str) else profile
    diags, sources, checked, user = _front_end(list(paths), prof, texts)
    built = None if diags.has_errors else _back_end(checked, prof, diags, _first_position(paths, texts))
    if built is None:
        raise CompileError(diags.sorted(), sources)
    gen, code, filename = built
    user_pous = {d.name: d.kind for sf in user for d in sf.decls if isinstance(d, A.POU)}
    return Program(prof, checked, gen, code, filename, [d for d in diags.sorted() if not d.is_error],
                   sources, user_pous)


class ExecContext:
    """What generated code reaches at run time: the task clock, the
    watchdog, the process image and communication services."""

    def __init__(self, image: ProcessImage, watchdog_s: float = 1.0) -> None:
        self.now_ns = 0
        self.image = image
        self.watchdog_s = watchdog_s
        self.deadline = float("inf")
        # native function services (st/native.py) by name, bound by the drivers
        self.services: dict = {}
        self.namespaces: list = []  # loaded modules that read the clock

    def set_time(self, now_ns: int) -> None:
        """Set the task clock. TIME() and LTIME() are constant within a cycle,
        so the loaded modules get the value once instead of a call per use."""
        self.now_ns = now_ns
        ms, ns = self.time_ms(), self.time_ns()
        for namespace in self.namespaces:
            namespace["_NOW_MS"] = ms
            namespace["_NOW_NS"] = ns

    def call_native(self, fn, *args):
        """A native function call: to the service bound under its name, or
        the declaration's fallback when no driver offers one."""
        return self.services.get(fn.service, fn.fallback).request(fn.name, *args)

    def time_ms(self) -> int:
        return rtlib.wrap(T.TIME, self.now_ns // 1_000_000)

    def time_ns(self) -> int:
        return rtlib.wrap(T.LTIME, self.now_ns)

    def arm_watchdog(self) -> None:
        self.deadline = time.perf_counter() + self.watchdog_s

    def check_watchdog(self) -> None:
        if time.perf_counter() > self.deadline:
            raise WatchdogFault(f"watchdog: the cycle ran longer than {self.watchdog_s * 1000:g} ms "
                                "(endless loop?)")


def _with_fields(obj, setters):
    for attr, value in setters:
        setattr(obj, attr, value)
    return obj


def _deref(ref):
    if ref is None:
        raise RangeFault("reference", "invalid reference: dereferenced a NULL REF_TO/POINTER")
    return ref


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

    def __init__(self, profile: Profile, checked: CheckedProgram, gen: GeneratedModule, code, filename: str,
                 warnings: list, sources: SourceSet, user_pous: dict) -> None:
        self.profile = profile
        self.checked = checked
        self.generated = gen
        self.code = code
        self.filename = filename
        self.warnings: list[Diagnostic] = warnings
        self.sources = sources
        self.pous = user_pous
        self.linemaps = {filename: gen.linemap}
        # Globals the libraries declare (PLC_DIAG): not the user's state.
        self.library_globals = frozenset(g.name for g in checked.globals
                                         if g.pos is not None and g.pos.file.startswith("<lib>/"))

    @property
    def python_source(self) -> str:
        return self.generated.source

    def pou(self, name: str):
        for info in self.checked.pous:
            if info.name.upper() == name.upper():
                return info
        raise KeyError(name)

    def load(self, ctx: Optional[ExecContext] = None) -> dict:
        """Execute the generated module in a fresh namespace bound to ctx;
        returns the namespace (classes, functions, globals ``_G``)."""
        ctx = ctx or ExecContext(ProcessImage(self.profile.addressing))
        ns: dict[str, Any] = {
            "__builtins__": _BUILTINS,
            "__name__": "softplc_generated",
            "_ctx": ctx,
            "_f32": rtlib.f32, "_idiv": rtlib.idiv, "_imod": rtlib.imod, "_rdiv": rtlib.rdiv,
            "_expt": rtlib.expt,
            "_INF": float("inf"), "_NAN": float("nan"),
            "_AttrRef": refs.AttrRef, "_ItemRef": refs.ItemRef, "_CellRef": refs.CellRef,
            "_AccessorRef": refs.AccessorRef,
            "_assign_into": values.assign_into, "_copy_value": values.copy_value,
            "_with_fields": _with_fields, "_deref": _deref,
            "_check_index": _check_index, "_check_range": _check_range, "_out_of_bounds": out_of_bounds,
            "_for_range": _for_range,
            "_watchdog": ctx.check_watchdog,
            "_native": ctx.call_native,
        }
        ns.update(self.generated.consts)
        image = ctx.image
        for idx, acc in self.generated.accessors.items():
            if acc.type is None:
                ns[f"_A{idx}t"] = image.table(acc.addr)
            else:
                get, set_ = image.accessor(acc.addr, acc.type)
                ns[f"_A{idx}g"], ns[f"_A{idx}s"] = get, set_
        ctx.namespaces.append(ns)
        ctx.set_time(ctx.now_ns)
        exec(self.code, ns)
        try:
            ns["_G"] = ns["_Globals"]()
        except Exception as exc:
            raise fault_from_exception(exc, self.linemaps) from None
        return ns

    def runner(self, entry: str, cycle_time_ms: int = 10, ctx: Optional[ExecContext] = None) -> "Runner":
        info = self.pou(entry)
        if info.kind == "FUNCTION_BLOCK":
            raise KeyError(f"{entry} is a FUNCTION_BLOCK; run a PROGRAM or a FUNCTION")
        return Runner(self, info, cycle_time_ms, ctx)


class Runner:
    """Runs one PROGRAM (or calls one FUNCTION) cycle after cycle in virtual
    time: the task clock advances by the cycle time after each cycle."""

    def __init__(self, program: Program, info, cycle_time_ms: int, ctx: Optional[ExecContext]) -> None:
        self.program = program
        self.info = info
        self.cycle_ns = int(cycle_time_ms * 1_000_000)
        self.ctx = ctx or ExecContext(ProcessImage(program.profile.addressing))
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
        for _ in range(cycles):
            ctx.arm_watchdog()
            try:
                call()
            except Exception as exc:
                raise fault_from_exception(exc, self.program.linemaps) from None
            self.cycles += 1
            ctx.set_time(ctx.now_ns + self.cycle_ns)

    def get(self, path: str):
        """The value of a variable by its ST path, e.g. 'counter.CV' or 'G_speed'."""
        roots = ((self.instance,) if self.instance is not None else ()) + (self.globals,)
        holder, attr, _ty = locate(path, roots)
        return getattr(holder, attr)


def locate(path: str, roots) -> tuple:
    """(holder, attribute, Type) of the variable at an ST path such as
    'motor.speed' (dotted names, no indices; case-insensitive), looked up in each root object in turn (a program
    instance, then the globals). KeyError(path) if there is none."""
    parts = path.split(".")
    for root in roots:
        found = _member(root, parts[0])
        if found is not None:
            break
    else:
        raise KeyError(path)
    for part in parts[1:]:
        holder, attr, _ty = found
        found = _member(getattr(holder, attr), part)
        if found is None:
            raise KeyError(path)
    return found


def _member(obj, name: str):
    """(obj, attribute, Type) of the variable called name (case-insensitive) in obj, or None."""
    for st_name, attr, ty, _section in getattr(type(obj), "_VARS_", ()):
        if st_name.upper() == name.upper():
            return obj, attr, ty
    return None
