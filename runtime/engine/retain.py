"""RETAIN and PERSISTENT variables: which ones, their snapshot, the retain
file and the rules that bring them back at a start.

Start modes:

  cold  every variable gets its initial value; nothing is restored.
  warm  RETAIN and PERSISTENT variables get the values saved last, when the
        program's retained layout is unchanged. When the program changed (the
        layout hash differs: a new program version was loaded), PERSISTENT
        variables are restored one by one where the path and the type
        signature still match; RETAIN variables get their initial values.

Which variables are retained (CODESYS semantics):

  * VAR_GLOBAL RETAIN / PERSISTENT variables; path = the name, "G_total";
  * a PROGRAM instance's VAR RETAIN / PERSISTENT (also VAR_INPUT, VAR_OUTPUT,
    VAR_STAT with the qualifier); path = "<instance>.<name>", "Main.count";
  * inside FUNCTION_BLOCK instances that are not retained themselves (a program
    or global variable of an FB type, and recursively through their FB-typed
    variables): the FB's own RETAIN / PERSISTENT variables, in every instance;
    path "Main.motor1.hours". Arrays of FB instances and FB instances inside
    structs are not searched: declare the array (or struct) RETAIN to keep it.

A retained aggregate (ARRAY, STRUCT, FB instance) is retained whole, except
its VAR_IN_OUT / VAR_EXTERNAL / VAR_TEMP members (references to other data,
or nothing between calls), located (AT %...) members (they live in the process
image) and REF_TO / POINTER values (addresses in the memory of the old
process): those keep their initial values. A variable declared RETAIN
PERSISTENT counts as PERSISTENT. A located variable (AT %MW10) is never
retained: its value is the process image's.

Names are case-insensitive in ST, so paths are matched and hashed
case-insensitively and type signatures are upper case: renaming `count` to
`Count` keeps the value.

The retain file is written atomically (temporary file, fsync, rename, fsync
of the directory): after a crash or a kill it holds either the previous or
the new contents, never a mix. Line 1 is a JSON header with the SHA-256 and
length of the body; the body is the JSON of RetainData, one variable a line.
"""

from __future__ import annotations

import hashlib
import json
import os
import threading
from collections.abc import Callable
from dataclasses import dataclass, field
from operator import attrgetter
from pathlib import Path
from typing import Any

from ..st import types as T

RETAIN = "RETAIN"
PERSISTENT = "PERSISTENT"

FORMAT = "softplc-retain"
VERSION = 1

# Members that are not part of an instance's own state (as in valuejson).
_SKIPPED_SECTIONS = frozenset({"VAR_IN_OUT", "VAR_EXTERNAL", "VAR_TEMP"})


# ================================================================ type signatures


def type_signature(t: T.Type) -> str:
    """Canonical text of a type's structure: equal for two programs that
    declare the type the same way (names are upper-cased, as ST ignores case),
    different after any change a saved value could not survive."""
    t = T.resolve(t)
    if isinstance(t, T.ElementaryType):
        return t.name
    if isinstance(t, T.StringType):
        return t.name
    if isinstance(t, T.SubrangeType):
        return f"{t.base.name}({t.lo}..{t.hi})"
    if isinstance(t, T.EnumType):
        values = ",".join(f"{k}:={v}" for k, v in t.values.items())
        name = "" if t.name.startswith("(") else " " + t.name.upper()  # anonymous enum
        return f"ENUM{name}:{t.base.name}({values})"
    if isinstance(t, T.ArrayType):
        dims = ", ".join("*" if d is None else f"{d[0]}..{d[1]}" for d in t.dims)
        return f"ARRAY[{dims}] OF {type_signature(t.elem)}"
    if isinstance(t, T.RefType):
        # The target's name only: a REF_TO value is never saved, and a
        # struct may refer to itself (a linked list) through one.
        return ("POINTER TO " if t.pointer else "REF_TO ") + str(T.resolve(t.target)).upper()
    if isinstance(t, (T.StructType, T.FBType)):
        members = ";".join(f"{name.upper()}:{type_signature(mt)}" for name, _attr, mt in _members(t))
        return f"{t.name.upper()}{{{members}}}"
    return str(t).upper()  # ADR#, NULL; str() is the name (which Type itself does not declare)


def _members(t: T.StructType | T.FBType) -> list:
    """(name, python attribute, type) of the members of a STRUCT or FB type
    that belong to its retained state, in declaration order."""
    if isinstance(t, T.StructType):
        return [(f.name, f.pyname, f.type) for f in t.fields.values()]
    pou = t.pou
    if pou is None:
        return []
    return [
        (v.name, v.pyname, v.type)
        for v in pou.vars.values()
        if v.section not in _SKIPPED_SECTIONS and v.location is None
    ]


# ================================================================ snapshot codecs
# An encoder turns a live value into JSON-ready data (a deep copy). It is
# built once per variable at plan time so the scan thread only runs tight
# closures. _NO_DATA marks types with nothing to save (references).

_NO_DATA = object()


def _encoder(t: T.Type):
    """None for a scalar (immutable: the value is its own copy), _NO_DATA for
    a type with nothing to save, else a function value -> data."""
    t = T.resolve(t)
    if isinstance(t, T.RefType):
        return _NO_DATA
    if isinstance(t, T.ArrayType):
        elem = _encoder(t.elem)
        if elem is _NO_DATA:
            return _NO_DATA
        return _array_encoder(len(t.dims), elem)
    if isinstance(t, (T.StructType, T.FBType)):
        members = []
        for name, attr, mt in _members(t):
            enc = _encoder(mt)
            if enc is not _NO_DATA:
                members.append((name, attrgetter(attr), enc))
        if not members:
            return _NO_DATA

        def encode_object(obj, members=tuple(members)):
            # declaration order, so the file reads like the declaration
            return {name: (get(obj) if enc is None else enc(get(obj))) for name, get, enc in members}

        return encode_object
    if isinstance(t, (T.ElementaryType, T.StringType, T.EnumType, T.SubrangeType)):
        return None
    return _NO_DATA  # ADR#, NULL: not storable types


def _has_data(t: T.Type) -> bool:
    """Whether values of t have anything to save (not only references)."""
    t = T.resolve(t)
    if isinstance(t, T.ArrayType):
        return _has_data(t.elem)
    if isinstance(t, (T.StructType, T.FBType)):
        return any(_has_data(mt) for _name, _attr, mt in _members(t))
    return isinstance(t, (T.ElementaryType, T.StringType, T.EnumType, T.SubrangeType))


def _array_encoder(ndims: int, elem) -> Callable:
    if ndims == 1:
        if elem is None:
            return list
        return lambda v: [elem(x) for x in v]
    inner = _array_encoder(ndims - 1, elem)
    return lambda v: [inner(row) for row in v]


# ================================================================ restore (decode)


class _BadValue(Exception):
    """A saved value that does not fit its type (a hand-edited file)."""


def _check(t: T.Type, data: Any, where: str) -> Any:
    """The saved data validated against type t (floats made floats); raises
    _BadValue naming the element. Nothing is written here, so a bad value
    leaves the whole variable untouched."""
    t = T.resolve(t)
    if isinstance(t, T.ElementaryType) and t.is_bool:
        if not isinstance(data, bool):
            raise _BadValue(f"{where}: expected TRUE/FALSE, found {_short(data)}")
        return data
    if isinstance(t, T.ElementaryType) and t.is_real:
        if isinstance(data, bool) or not isinstance(data, (int, float)):
            raise _BadValue(f"{where}: expected a number, found {_short(data)}")
        try:
            return float(data)
        except OverflowError:
            raise _BadValue(f"{where}: {_short(data)} is too large for a {t.name}") from None
    if isinstance(t, (T.ElementaryType, T.EnumType, T.SubrangeType)):
        lo, hi = (t.lo, t.hi) if isinstance(t, (T.ElementaryType, T.SubrangeType)) else (t.base.lo, t.base.hi)
        if isinstance(data, bool) or not isinstance(data, int):
            raise _BadValue(f"{where}: expected an integer, found {_short(data)}")
        if lo is not None and hi is not None and not lo <= data <= hi:
            raise _BadValue(f"{where}: {data} is outside {lo}..{hi}")
        return data
    if isinstance(t, T.StringType):
        if not isinstance(data, str):
            raise _BadValue(f"{where}: expected a string, found {_short(data)}")
        if len(data) > t.length:
            raise _BadValue(f"{where}: the string is longer than {t.length} characters")
        return data
    if isinstance(t, T.ArrayType):
        return _check_array(t.dims, t.elem, data, where)
    if isinstance(t, (T.StructType, T.FBType)):
        if not isinstance(data, dict):
            raise _BadValue(f"{where}: expected an object, found {_short(data)}")
        by_name = {k.upper(): v for k, v in data.items()}
        out = {}
        for name, _attr, mt in _members(t):
            if not _has_data(mt):
                continue
            if name.upper() not in by_name:
                raise _BadValue(f"{where}.{name}: missing")
            out[name.upper()] = _check(mt, by_name[name.upper()], f"{where}.{name}")
        return out
    raise _BadValue(f"{where}: a {t} cannot be restored")


def _check_array(dims: list, elem: T.Type, data: Any, where: str) -> list:
    lo, hi = dims[0]
    if not isinstance(data, list) or len(data) != hi - lo + 1:
        raise _BadValue(f"{where}: expected a list of {hi - lo + 1} elements, found {_short(data)}")
    if len(dims) > 1:
        return [_check_array(dims[1:], elem, row, f"{where}[{lo + i}]") for i, row in enumerate(data)]
    return [_check(elem, x, f"{where}[{lo + i}]") for i, x in enumerate(data)]


def _short(data: Any) -> str:
    return _clip(json.dumps(data, allow_nan=True, default=str), 40)


def _clip(text: Any, limit: int = 80) -> str:
    # keep log lines readable when a signature or value is large
    text = str(text)
    return text if len(text) <= limit else text[: limit - 3] + "..."


def _apply(t: T.Type, holder: Any, attr: str, data: Any) -> None:
    """holder.attr := checked data. Aggregates are updated in place, so
    references to them (REF, VAR_IN_OUT, cached FB instances) stay valid."""
    rt = T.resolve(t)
    if rt.is_aggregate:
        _apply_into(rt, getattr(holder, attr), data)
    else:
        setattr(holder, attr, data)


def _apply_into(t: T.Type, obj: Any, data: Any) -> None:
    t = T.resolve(t)
    if isinstance(t, T.ArrayType):
        _apply_array(len(t.dims), t.elem, obj, data)
        return
    assert isinstance(t, (T.StructType, T.FBType)), t  # an aggregate (is_aggregate) other than an array
    for name, attr, mt in _members(t):
        if name.upper() in data:
            _apply(mt, obj, attr, data[name.upper()])


def _apply_array(ndims: int, elem: T.Type, live: list, data: list) -> None:
    if ndims > 1:
        for row, drow in zip(live, data):
            _apply_array(ndims - 1, elem, row, drow)
    elif T.resolve(elem).is_aggregate:
        for item, ditem in zip(live, data):
            _apply_into(elem, item, ditem)
    elif _has_data(elem):
        live[:] = data


# ================================================================ the plan


@dataclass(eq=False)
class RetainedVar:
    """One retained variable and where its value lives: getattr(holder, attr)."""

    path: str
    kind: str  # RETAIN or PERSISTENT
    signature: str
    holder: object
    attr: str
    type: T.Type
    encode: Any = field(default=None, repr=False)  # live value -> data (None: a scalar)

    def __post_init__(self) -> None:
        if self.encode is None:
            enc = _encoder(self.type)
            self.encode = None if enc is _NO_DATA else enc


def _kind(sym) -> str | None:
    if sym.persistent:
        return PERSISTENT  # RETAIN PERSISTENT counts as PERSISTENT
    if sym.retain:
        return RETAIN
    return None


def plan_retain(checked, instances: dict, globals_obj) -> list:
    """The retained variables of a loaded program, sorted by path.
    instances: program instance name -> (POUInfo, instance object);
    globals_obj: the loaded module's ``_G``."""
    plan: list[RetainedVar] = []
    for sym in checked.globals:
        _visit(plan, sym.name, sym, globals_obj, set())
    for inst_name, (info, obj) in instances.items():
        for sym in info.vars.values():
            _visit(plan, f"{inst_name}.{sym.name}", sym, obj, set())
    plan.sort(key=lambda rv: rv.path.upper())
    seen: dict = {}
    for rv in plan:
        key = rv.path.upper()
        if key in seen:
            raise ValueError(
                f"two retained variables have the path {rv.path}: rename the program "
                "instance or the global variable so they differ"
            )
        seen[key] = rv
    return plan


def _visit(plan: list, path: str, sym, holder, active: set) -> None:
    if sym.section in _SKIPPED_SECTIONS or sym.location is not None or sym.constant:
        return
    kind = _kind(sym)
    if kind is not None:
        if _has_data(sym.type):  # a REF_TO has nothing to keep
            plan.append(RetainedVar(path, kind, type_signature(sym.type), holder, sym.pyname, sym.type))
        return
    t = T.resolve(sym.type)
    if isinstance(t, T.FBType) and t.pou is not None:
        obj = getattr(holder, sym.pyname, None)
        if obj is None or id(obj) in active:
            return
        active.add(id(obj))
        for inner in t.pou.vars.values():
            _visit(plan, f"{path}.{inner.name}", inner, obj, active)
        active.discard(id(obj))


def layout_hash(plan) -> str:
    """SHA-256 (hex) over the sorted "path kind signature" lines: equal for
    two loads of the same program, different when a retained variable was
    added, removed, renamed, re-typed or changed between RETAIN and
    PERSISTENT."""
    lines = sorted(f"{rv.path.upper()} {rv.kind} {rv.signature}" for rv in plan)
    return hashlib.sha256("\n".join(lines).encode("utf-8")).hexdigest()


def snapshot(plan) -> dict:
    """path -> JSON-ready deep copy of the value (plain lists, dicts and
    scalars; floats exact, inf/nan kept as floats). Runs in the scan thread
    between cycles, so it only copies: the writer thread encodes."""
    out = {}
    for rv in plan:
        v = getattr(rv.holder, rv.attr)
        out[rv.path] = v if rv.encode is None else rv.encode(v)
    return out


@dataclass
class RetainData:
    """What a retain file holds."""

    layout: str
    saved_ns: int
    cycle: int
    vars: dict  # path -> {"kind": str, "type": signature, "value": data}


def capture(plan, saved_ns: int, cycle: int) -> RetainData:
    values = snapshot(plan)
    return RetainData(
        layout_hash(plan),
        int(saved_ns),
        int(cycle),
        {rv.path: {"kind": rv.kind, "type": rv.signature, "value": values[rv.path]} for rv in plan},
    )


@dataclass
class RestoreReport:
    restored: list  # paths
    dropped: list  # (path, reason): retained variables that got their initial values in a warm start
    mode: str
    layout_matched: bool


def restore(plan, data: RetainData | None, mode: str) -> RestoreReport:
    """Write saved values into the live instances by the start-mode rules
    (module docstring). In a warm start every planned variable is either in
    ``restored`` or in ``dropped`` with the reason; a cold start lists
    neither (everything is initialised on purpose)."""
    mode = mode.lower()
    if mode not in ("cold", "warm"):
        raise ValueError(f"unknown start mode {mode!r} (use 'cold' or 'warm')")
    matched = data is not None and data.layout == layout_hash(plan)
    report = RestoreReport([], [], mode, matched)
    if mode == "cold":
        return report
    if data is None:
        report.dropped = [(rv.path, "no retain data") for rv in plan]
        return report
    saved = {p.upper(): entry for p, entry in data.vars.items()}
    for rv in plan:
        entry = saved.get(rv.path.upper())
        if not matched and rv.kind == RETAIN:
            report.dropped.append((rv.path, "program changed (RETAIN)"))
            continue
        if entry is None:
            report.dropped.append((rv.path, "not in the file"))
            continue
        if entry.get("type") != rv.signature:
            report.dropped.append(
                (rv.path, f"type changed (saved {_clip(entry.get('type'))}, now {_clip(rv.signature)})")
            )
            continue
        try:
            value = _check(rv.type, entry.get("value"), rv.path)
        except _BadValue as exc:
            report.dropped.append((rv.path, f"bad value in the file ({exc})"))
            continue
        _apply(rv.type, rv.holder, rv.attr, value)
        report.restored.append(rv.path)
    return report


# ================================================================ the file


class RetainFileError(Exception):
    """A retain file that cannot be used; the message names the file and
    what is wrong with it. damaged: the contents are bad (as opposed to the
    file not being readable at all)."""

    def __init__(self, message: str, damaged: bool = True) -> None:
        super().__init__(message)
        self.damaged = damaged


def _temp_prefix(path: Path) -> str:
    # A dot file with a .tmp suffix: never taken for a retain file, and
    # recognisable as ours when a killed process leaves one behind.
    return f".{path.name}."


def _is_temp_of(name: str, path: Path) -> bool:
    return name.startswith(_temp_prefix(path)) and name.endswith(".tmp")


def _encode_body(data: RetainData) -> bytes:
    # One variable a line, so a human can read and diff the file.
    head = (
        f'{{"layout": {json.dumps(data.layout)}, "saved_ns": {int(data.saved_ns)}, '
        f'"cycle": {int(data.cycle)}, "vars": {{'
    )
    items = [f"\n{json.dumps(path)}: {json.dumps(entry, allow_nan=True)}" for path, entry in data.vars.items()]
    return (head + ",".join(items) + "\n}}\n").encode("utf-8")


def write_file(path: Path, data: RetainData) -> None:
    """Write data to path atomically; raises OSError when the disk refuses."""
    path = Path(path)
    body = _encode_body(data)
    header = json.dumps(
        {"format": FORMAT, "version": VERSION, "sha256": hashlib.sha256(body).hexdigest(), "length": len(body)}
    )
    directory = path.parent
    tmp = directory / f"{_temp_prefix(path)}{os.getpid()}.{os.urandom(4).hex()}.tmp"
    fd = os.open(tmp, os.O_WRONLY | os.O_CREAT | os.O_EXCL | getattr(os, "O_BINARY", 0), 0o644)
    try:
        with os.fdopen(fd, "wb") as f:
            f.write(header.encode("ascii") + b"\n" + body)
            f.flush()
            os.fsync(f.fileno())
        os.replace(tmp, path)
    except BaseException:
        try:
            os.unlink(tmp)
        except OSError:
            pass
        raise
    _fsync_dir(directory)


def _fsync_dir(directory: Path) -> None:
    """Make the rename itself durable (POSIX); not possible on Windows."""
    if not hasattr(os, "O_DIRECTORY"):
        return
    try:
        fd = os.open(directory, os.O_RDONLY | os.O_DIRECTORY)
    except OSError:
        return
    try:
        os.fsync(fd)
    except OSError:
        pass
    finally:
        os.close(fd)


def read_file(path: Path) -> RetainData | None:
    """The data in a retain file; None if there is no file; RetainFileError
    if it is not a valid retain file."""
    path = Path(path)
    try:
        raw = path.read_bytes()
    except FileNotFoundError:
        return None
    except OSError as exc:
        raise RetainFileError(f"{path}: cannot read the retain file: {exc.strerror or exc}", damaged=False) from None
    if not raw:
        raise RetainFileError(f"{path}: the retain file is empty")
    head, sep, body = raw.partition(b"\n")
    try:
        header = json.loads(head.decode("utf-8"))
    except (UnicodeDecodeError, ValueError, RecursionError):
        header = None
    if not isinstance(header, dict) or header.get("format") != FORMAT:
        raise RetainFileError(f"{path}: not a softplc retain file (no '{FORMAT}' header on line 1)")
    version = header.get("version")
    if version != VERSION:
        raise RetainFileError(
            f"{path}: retain file version {version!r} is not known to this softplc (it reads version {VERSION})"
        )
    length, digest = header.get("length"), header.get("sha256")
    if not isinstance(length, int) or isinstance(length, bool) or not isinstance(digest, str):
        raise RetainFileError(f"{path}: the retain file header lacks the length or sha256")
    if len(body) < length or not sep:
        raise RetainFileError(f"{path}: the retain file is truncated ({len(body)} of {length} bytes)")
    if len(body) > length:
        raise RetainFileError(f"{path}: the retain file has {len(body) - length} bytes of trailing data")
    if hashlib.sha256(body).hexdigest() != digest:
        raise RetainFileError(f"{path}: bad checksum: the retain file was changed or damaged")
    try:
        doc = json.loads(body.decode("utf-8"))
    except (UnicodeDecodeError, ValueError, RecursionError) as exc:
        raise RetainFileError(f"{path}: the retain file body is not valid JSON ({exc})") from None
    return _data_from_json(doc, path)


def _data_from_json(doc: Any, path: Path) -> RetainData:
    def bad(what: str) -> RetainFileError:
        return RetainFileError(f"{path}: malformed retain file: {what}")

    if not isinstance(doc, dict):
        raise bad("the body is not an object")
    layout, saved_ns, cycle, variables = (doc.get(k) for k in ("layout", "saved_ns", "cycle", "vars"))
    if not isinstance(layout, str):
        raise bad("'layout' is missing")
    if not isinstance(saved_ns, int) or not isinstance(cycle, int):
        raise bad("'saved_ns' or 'cycle' is not an integer")
    if not isinstance(variables, dict):
        raise bad("'vars' is not an object")
    for name, entry in variables.items():
        if not (
            isinstance(entry, dict)
            and isinstance(entry.get("kind"), str)
            and isinstance(entry.get("type"), str)
            and "value" in entry
        ):
            raise bad(f"variable {name!r} lacks kind, type or value")
    return RetainData(layout, saved_ns, cycle, variables)


# ================================================================ the store


class RetainStore:
    """The retain file of a running engine. Writes happen in a background
    thread so the scan thread never waits on the disk; a newer snapshot
    replaces one that is still waiting. A failed write (disk full, no
    permission) is reported in last_error, never raised into the scan
    thread, and the next submit tries again."""

    def __init__(self, path: Path, threaded: bool = True) -> None:
        self.path = Path(path)
        self.threaded = threaded
        self.writes = 0  # successful writes
        self.errors = 0  # failed writes
        self.last_error: str | None = None  # the last failure; None after a success
        self._cond = threading.Condition()
        self._pending: RetainData | None = None
        self._failed: RetainData | None = None  # data of the last failed write, not yet superseded
        self._busy = False
        self._closed = False
        self._thread: threading.Thread | None = None
        if threaded:
            self._thread = threading.Thread(target=self._run, name=f"retain-writer {self.path.name}", daemon=True)
            self._thread.start()

    # ------------------------------------------------------------ start

    def load(self) -> tuple:
        """(data, warning). A corrupt file is renamed to <name>.corrupt and
        kept for a human; the warning says so and data is None. Temporary
        files left by a killed process are removed first."""
        self._remove_stale_temps()
        try:
            return read_file(self.path), None
        except RetainFileError as exc:
            if not exc.damaged:  # unreadable (permissions, a directory): nothing to move aside
                return None, f"{exc}; starting with initial values"
            try:
                kept = self._move_aside()
            except OSError as err:
                return None, (f"{exc}; starting with initial values (could not rename it: {err.strerror or err})")
            return None, f"{exc}; kept as {kept}; starting with initial values"

    def _move_aside(self) -> Path:
        target = self.path.with_name(self.path.name + ".corrupt")
        n = 2
        while target.exists():  # keep earlier ones too
            target = self.path.with_name(f"{self.path.name}.corrupt.{n}")
            n += 1
        os.replace(self.path, target)
        return target

    def _remove_stale_temps(self) -> None:
        try:
            names = os.listdir(self.path.parent)
        except OSError:
            return
        for name in names:
            if _is_temp_of(name, self.path):
                try:
                    os.unlink(self.path.parent / name)
                except OSError:
                    pass

    # ------------------------------------------------------------ writing

    def submit(self, data: RetainData) -> None:
        """Queue data for writing (non-blocking when threaded)."""
        if not self.threaded or self._closed:
            self._write(data)
            return
        with self._cond:
            self._pending = data
            self._failed = None
            self._cond.notify_all()

    def flush(self, timeout: float = 10) -> bool:
        """Wait until everything submitted is on disk; a write that failed
        and was not superseded is tried once more. False if the data is not
        on disk (see last_error) or the timeout passed."""
        if self.threaded and self._thread is not None and self._thread.is_alive():
            with self._cond:
                if self._failed is not None and self._pending is None:
                    self._pending, self._failed = self._failed, None
                    self._cond.notify_all()
                if not self._cond.wait_for(lambda: self._pending is None and not self._busy, timeout):
                    return False
                return self._failed is None
        if self._failed is not None:
            data, self._failed = self._failed, None
            self._write(data)
        return self._failed is None

    def close(self) -> None:
        """Flush and stop the writer thread."""
        if self._closed:
            return
        self.flush()
        with self._cond:
            self._closed = True
            self._cond.notify_all()
        if self._thread is not None:
            self._thread.join(timeout=10)

    def _run(self) -> None:
        while True:
            with self._cond:
                self._cond.wait_for(lambda: self._pending is not None or self._closed)
                if self._pending is None:
                    return  # closed and nothing left
                data, self._pending = self._pending, None
                self._busy = True
            try:
                self._write(data)
            finally:
                with self._cond:
                    self._busy = False
                    self._cond.notify_all()

    def _write(self, data: RetainData) -> None:
        try:
            write_file(self.path, data)
        except Exception as exc:  # OSError, or data that cannot be encoded: never into the scan
            self.errors += 1
            reason = exc.strerror if isinstance(exc, OSError) and exc.strerror else str(exc)
            self.last_error = f"{self.path}: cannot write the retain file: {reason}"
            with self._cond:
                if self._pending is None:
                    self._failed = data
            return
        self.writes += 1
        self.last_error = None
