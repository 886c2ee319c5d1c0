"""The retain file: RetainData written atomically (temporary file, fsync,
rename, fsync of the directory), so that after a crash or a kill it holds
either the previous or the new contents, never a mix; read back with its
damage named; and RetainStore, the writer thread the engine hands
snapshots to. Line 1 is a JSON header with the SHA-256 and length of the
body; the body is the JSON of RetainData, one variable a line."""

from __future__ import annotations

import errno
import hashlib
import json
import os
import threading
from pathlib import Path
from typing import Any

from ..config.values import not_regular
from .retain import FORMAT, VERSION, RetainData


class RetainFileError(Exception):
    """A retain file that cannot be used; the message names the file and
    what is wrong with it. damaged: the contents are bad (as opposed to the
    file not being readable at all); ours: it has softplc's header, so
    softplc wrote it (and may set it aside)."""

    def __init__(self, message: str, damaged: bool = True, ours: bool = True) -> None:
        super().__init__(message)
        self.damaged = damaged
        self.ours = ours


class ForeignRetainFile(RetainFileError):
    """The retain path holds something softplc did not write (a device such
    as /dev/null, a FIFO, a link, a file without softplc's header): it is
    neither read, renamed nor written over; the PLC does not start."""

    def __init__(self, message: str) -> None:
        super().__init__(message, damaged=False, ours=False)


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
    other = not_regular(path)
    if other is not None:  # never renamed over: root would replace /dev/null
        raise OSError(errno.EEXIST, f"{other} is there, not a retain file; softplc writes over none")
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
        raise RetainFileError(f"{path}: the retain file is empty", ours=False)
    head, sep, body = raw.partition(b"\n")
    try:
        header = json.loads(head.decode("utf-8"))
    except (UnicodeDecodeError, ValueError, RecursionError):
        header = None
    if not isinstance(header, dict) or header.get("format") != FORMAT:
        raise RetainFileError(f"{path}: not a softplc retain file (no '{FORMAT}' header on line 1)", ours=False)
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
        """(data, warning). A damaged file that softplc wrote (its header on
        line 1) is renamed to <name>.corrupt and kept for a human; the
        warning says so and data is None; an empty one is only written
        over. ForeignRetainFile when the path holds anything else: nothing
        but a file softplc wrote is renamed or written over. Temporary files
        left by a killed process are removed first."""
        other = not_regular(self.path)
        if other is not None:  # never read (a FIFO blocks), never renamed (/dev/null)
            raise ForeignRetainFile(
                f"{self.path}: {other}, not a retain file: softplc reads, renames and writes over "
                "nothing but a file of its own; name a file in [retain] file"
            )
        self._remove_stale_temps()
        try:
            return read_file(self.path), None
        except RetainFileError as exc:
            if not exc.damaged:  # unreadable (permissions): nothing to move aside
                return None, f"{exc}; starting with initial values"
            if not exc.ours:
                if self.path.stat().st_size == 0:  # nothing to lose: written at the first save
                    return None, f"{exc}; starting with initial values"
                raise ForeignRetainFile(
                    f"{exc}: softplc would write over it; move it away or name another file in [retain] file"
                ) from None
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
