"""Libraries of the user: a folder of POUs (OSCAT BASIC, a company's own
blocks) that programs use by name, plain (``DEC_2``) or in the library's
namespace (``OSCAT.DEC_2``).

    lib = Library(Path("libs/oscat"), "OSCAT")
    prog = compile_files(["main.st"], libraries=[lib])

Every source file of the folder (``.st`` and the imported kinds, in
sub-folders too) is a unit that a program takes only when it names
something the file declares, as the on-demand files of the standard
library (compile.py): unused POUs cost nothing, neither at compile time
nor at run time. Parsing a file is done once per content: the parse and
its index (what it declares, the words it uses) are kept by the hash of
the text, the profile, softplc's version and its parser's code, in memory
and in softplc's cache (runtime/cache.py: the user's cache directory).
"""

from __future__ import annotations

import dataclasses
import pickle
from pathlib import Path

from .. import cache
from ..st.diagnostics import DiagnosticBag
from ..st.importers import is_source, st_views
from ..st.profile import Profile
from ..st.syntax.parser import parse_source

_ST = Path(__file__).resolve().parent.parent / "st"
_PARSES: dict[str, bytes] = {}  # key -> pickled (list of SourceFiles, diagnostics)


@dataclasses.dataclass(frozen=True)
class Library:
    """A folder (or one file) of POUs, types and global constants, known in
    ST under ``namespace``; ``profile``: how its files read (None: as the
    program's). A library softplc ships (shipped.py) may also have further
    ``namespaces``, ``functions`` written in Python (a module with a
    FUNCTIONS table of StdFuncs), ``natives`` a runtime service answers (a
    module with a NATIVES tuple, st/native.py), the shipped libraries it
    ``requires``, and a reason it is ``unavailable`` here (hardware, a
    runtime service: one warning when a program uses it), or such reasons
    for some of its files (``unavailable_parts``: (file name, why) pairs)."""

    path: Path
    namespace: str
    profile: str | None = None
    namespaces: tuple = ()
    functions: str | None = None
    natives: str | None = None
    unavailable: str = ""
    unavailable_parts: tuple = ()
    requires: tuple = ()  # names of the shipped libraries it uses (shipped.py with_required)

    def files(self) -> list[Path]:
        """The library's source files, sorted (sub-folders included, but for
        hidden and generated ones)."""
        if self.path.is_file():
            return [self.path]
        found = [
            p
            for p in self.path.rglob("*")
            if p.is_file() and is_source(p.name) and not _skipped(p.relative_to(self.path))
        ]
        return sorted(found)


# Folders of a library that hold no sources of its own: a Beremiz project's
# build/ (matiec's input, generated_plc.st, copies every POU), hidden ones.
_GENERATED = frozenset(("build", "__pycache__"))


def _skipped(rel: Path) -> bool:
    return any(part.startswith(".") or part in _GENERATED for part in rel.parts[:-1]) or rel.name.startswith(".")


def _version_salt() -> bytes:
    """What makes an old parse invalid besides the text: the language's
    code (all of runtime/st/: the grammar, the lexer and parser, the AST
    and its builders, what they build on, where each module is) and
    the importers' (an imported file's parse is what its importer wrote,
    and a newer softplc imports more: a cached parse of a PLCopen file
    from before its FBD bodies were read would keep them out)."""
    return cache.code_hash(*_ST.rglob("*.py"), *_ST.rglob("*.lark"))


_SALT: bytes | None = None


def parser_code() -> bytes:
    """The hash of the language's code (_version_salt), once per process."""
    global _SALT
    if _SALT is None:
        _SALT = _version_salt()
    return _SALT


def parse_cached(name: str, text: str, profile: Profile, disk: bool = True, slot: bool = False) -> tuple[list, list]:
    """(SourceFiles, diagnostics) of a library file, parsed once per content:
    from memory, else from the cache folder, else parsed (and kept in both).
    Every call returns new objects: the checker annotates them. slot: a
    project's own source, which changes with every edit: kept in the cache
    folder in one entry per file (its name and the profile), which holds the
    parse of its last content (SLOT); disk=False: in memory only."""
    key = cache.key("st", parser_code(), profile.name, name, text)
    data = _PARSES.get(key)
    if data is not None:
        return pickle.loads(data)
    if slot:
        data = _slot_load(name, profile, key) if disk else None
    else:
        data = cache.load_bytes("st", key) if disk else None
    if data is not None:
        try:
            parsed = pickle.loads(data)  # a damaged entry is parsed again (and rewritten)
        except Exception:
            data = None
    if data is None:
        diags = DiagnosticBag()
        files = [parse_source(v.text, name, diags, profile, v.lowered, v.origins) for v in st_views(name, text, diags)]
        parsed = (files, diags.items)  # (new objects: only their pickle is kept)
        data = cache.dumps(parsed)
        if data is None:  # an expression hundreds of operators long: parsed, not kept
            return parsed
        if disk and slot:
            cache.store_bytes(SLOT, _slot_key(name, profile), key.encode() + data)
        elif disk:
            cache.store_bytes("st", key, data)
    _PARSES[key] = data
    return parsed


#: the cache folder's kind of a project's own sources: an entry per file
#: (_slot_key), the key of the content it holds (64 hex digits), then its pickle
SLOT = "st-source"


def _slot_key(name: str, profile: Profile) -> str:
    return cache.key(SLOT, parser_code(), profile.name, name)


def _slot_load(name: str, profile: Profile, key: str) -> bytes | None:
    """The pickle the file's entry holds when it is of this content (key),
    else None: an edited file never meets its old parse."""
    data = cache.load_bytes(SLOT, _slot_key(name, profile))
    if data is None or data[:64] != key.encode():
        return None
    return data[64:]
