"""softplc's cache on disk: what is slow to build and depends only on
content (the ST grammar's LALR table, the parses of library files and what
they declare), kept between runs.

    key = cache.key("st", grammar_text, profile_name, text)   # str or bytes parts
    value = cache.load("st", key)                              # None: not there (or unreadable)
    if value is None:
        value = build()
        cache.store("st", key, value)

Where: ``$SOFTPLC_CACHE`` if set, else the user's cache directory
(platformdirs: ``~/.cache/softplc`` on Linux, ``$XDG_CACHE_HOME`` honoured;
``~/Library/Caches/softplc``; ``%LOCALAPPDATA%\\softplc\\Cache``), one
folder per kind. A key is the hash of softplc's version and of every part
the caller gives (the text, and a hash of the code that builds the value),
so an upgrade or an edited file never meets an old entry. An entry is
written whole or not at all (a temporary file of its own, then
os.replace), so concurrent runs (pytest-xdist workers, two compilers) never
read half an entry; a damaged or truncated one reads as missing and is
written again. A cache that cannot be written is skipped.

Off: ``softplc --no-cache ...`` (``disabled()``) or ``SOFTPLC_NO_CACHE=1``
in the environment (the pytest plugin, any run): nothing is read or written.
Entries are pickles of softplc's own objects, read only from the user's own
folder (created 0700).
"""

from __future__ import annotations

import hashlib
import os
import pickle
import tempfile
from collections import Counter
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import Any

ENV_DIR = "SOFTPLC_CACHE"
ENV_OFF = "SOFTPLC_NO_CACHE"

#: loads that found an entry ("hit"), did not ("miss"), entries written
#: ("write"), by (what, kind): for tests and benchmarks
stats: Counter = Counter()

_off = False
_version: str | None = None


def enabled() -> bool:
    """Whether the cache is read and written: not under --no-cache, nor with
    SOFTPLC_NO_CACHE set to anything but "" or "0"."""
    return not _off and os.environ.get(ENV_OFF, "") in ("", "0")


def set_enabled(on: bool) -> None:
    global _off
    _off = not on


@contextmanager
def disabled() -> Iterator[None]:
    """The cache off until the block ends (softplc --no-cache)."""
    global _off
    before, _off = _off, True
    try:
        yield
    finally:
        _off = before


def directory() -> Path:
    env = os.environ.get(ENV_DIR)
    if env:
        return Path(env)
    import platformdirs  # (only when the cache is used)

    return Path(platformdirs.user_cache_dir("softplc", appauthor=False))


def version() -> str:
    """softplc's version, part of every key: the package's own constant
    (which pyproject.toml takes as the distribution's version), not the
    installed metadata, whose lookup cost every start 12 ms of imports."""
    global _version
    if _version is None:
        from . import __version__

        _version = __version__
    return _version


def key(kind: str, *parts: str | bytes) -> str:
    """The key of an entry: a hash of the kind, softplc's version and the parts."""
    h = hashlib.sha256(f"{kind}\0{version()}\0".encode())
    for part in parts:
        data = part.encode() if isinstance(part, str) else part
        h.update(len(data).to_bytes(8, "little"))
        h.update(data)
    return h.hexdigest()


def code_hash(*files: Path) -> bytes:
    """A hash of source files' paths (inside softplc) and contents: part of
    a key when the value is built by that code (an edited checkout keeps the
    same version; a module moved to another package changes the key: the
    pickles name classes by module)."""
    h = hashlib.sha256()
    for f in sorted(files):
        name = _inside(f).encode()
        try:
            h.update(name + b"\0" + f.read_bytes() + b"\0")
        except OSError:
            h.update(name + b"\0?\0")
    return h.digest()


_ROOT = Path(__file__).resolve().parent.parent  # the softplc package


def _inside(f: Path) -> str:
    if f.is_absolute() and f.is_relative_to(_ROOT):  # (a path found under the package: no resolve(),
        return f.relative_to(_ROOT).as_posix()  # a system call per part of it, 40 µs a file)
    try:
        return f.resolve().relative_to(_ROOT).as_posix()
    except ValueError:  # not softplc's (a plugin's file)
        return f.name


def path(kind: str, key: str) -> Path:
    return directory() / kind / f"{key}.pickle"


def load_bytes(kind: str, key: str) -> bytes | None:
    """The bytes stored under the key, or None (cache off, no entry)."""
    if not enabled():
        return None
    try:
        data = path(kind, key).read_bytes()
    except OSError:
        stats["miss", kind] += 1
        return None
    stats["hit", kind] += 1
    return data


def load(kind: str, key: str) -> Any | None:
    """The value stored under the key, or None: cache off, no entry, or an
    entry that does not read (damaged, truncated, of another Python)."""
    data = load_bytes(kind, key)
    if data is None:
        return None
    try:
        return pickle.loads(data)  # our own entry, in the user's own folder
    except Exception:
        stats["hit", kind] -= 1
        stats["miss", kind] += 1
        stats["damaged", kind] += 1
        return None


def dumps(value: Any) -> bytes | None:
    """The pickle of a value, or None when it does not pickle (an
    expression hundreds of operators deep)."""
    try:
        return pickle.dumps(value, protocol=pickle.HIGHEST_PROTOCOL)
    except (RecursionError, pickle.PicklingError, TypeError, AttributeError):
        return None


def store(kind: str, key: str, value: Any) -> None:
    """Keep the value under the key (whole or not at all); nothing when the
    cache is off, the value does not pickle or the folder cannot be written."""
    if enabled():
        data = dumps(value)
        if data is not None:
            store_bytes(kind, key, data)


def store_bytes(kind: str, key: str, data: bytes) -> None:
    """Keep the bytes under the key: a temporary file of its own, then
    os.replace; nothing when the cache is off or cannot be written."""
    if not enabled():
        return
    target = path(kind, key)
    try:
        target.parent.mkdir(parents=True, exist_ok=True, mode=0o700)
        fd, tmp = tempfile.mkstemp(dir=target.parent, prefix=f".{key[:16]}.", suffix=".tmp")
        try:
            with os.fdopen(fd, "wb") as f:
                f.write(data)
            os.replace(tmp, target)  # atomic: a reader sees the old entry or the new one
        except BaseException:
            try:
                os.unlink(tmp)
            except OSError:
                pass
            raise
    except OSError:
        return  # a read-only home: built each time
    stats["write", kind] += 1
