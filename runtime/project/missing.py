"""The errors a missing library causes, one line per library.

A project that uses a vendor library softplc does not have draws an error
at each use of its names: E010 (a name), E012 (a type), E043 (a function),
E019 (``Tc2_System.MEMCPY``), E140 (``EXTENDS FB_ListenerBase``), and E010
again at each use of a variable whose type is such a name. They are
grouped into one diagnostic per library, E223 ``needs Tc2_System (MEMCPY,
T_MaxString … 214 references): not installed``, at the project's reference
to the library where it has one.

Which library a name belongs to: a qualified name names it
(``Tc2_System.MEMCPY``, by the library's name or namespace); else the
table of what the common vendor libraries declare (fblocks/libs/catalogue.toml),
preferring a library the project references; else, when the project
references libraries softplc lacks, the name goes to E224 ``names not
found (…), maybe from LibA, LibB``. A library softplc has (its standard
library, under the names Standard and Tc2_Standard; a library given to the
compiler) is never missing.
"""

from __future__ import annotations

import collections
import re
from dataclasses import dataclass, field
from pathlib import Path

from ..program.shipped import catalogue, shipped
from ..st.ast import Pos
from ..st.check.namespaces import LIBRARY_NAMESPACES
from ..st.diagnostics import Diagnostic
from .units import Units

NOT_FOUND = ""  # the group of names no table knows

_MESSAGES = (
    re.compile(r"unknown (?:name|function|type) '([^']+)'"),
    re.compile(r"softplc has no library \S+ \('([^']+)'\)"),
    re.compile(r"^'([^']+)' is of a library the program did not choose"),
    re.compile(r"unknown namespace '[^']+' in '([^']+)'"),
    re.compile(r"VAR_EXTERNAL '([^']+)' has no VAR_GLOBAL"),
    # F := x in FUNCTION F whose return type is missing (a follow-on only: see _variable_type)
    re.compile(r"^'([^']+)' is a POU, not a variable"),
)
_BASE = re.compile(r"'([^']+)' is not (?:a FUNCTION_BLOCK|an INTERFACE)")
_CODES = ("E010", "E012", "E019", "E043", "E140")
_PARAMETER = re.compile(r"^(\w+) has no parameter '(\w+)'")
_NO_RETURN = re.compile(r"^METHOD (\w+) has no return type")
_TOO_MANY = re.compile(r"^too many arguments for (\w+) \(it takes \d+\)")
_NO_MEMBER = re.compile(r"^(\w+) has no member '\w+'")
#: names that are not a library's: the language of another tool
_NOT_LIBRARY = frozenset(("BIT", "UNION"))


def vendor_table() -> tuple:
    """The libraries of the catalogue (fblocks/libs/catalogue.toml), in its order."""
    return catalogue()


@dataclass
class MissingLibrary:
    """A library the project needs and softplc lacks (name NOT_FOUND: the
    names no table knows), the names used from it and how often, the
    diagnostics it replaces."""

    name: str
    pos: Pos
    referenced: bool
    names: collections.Counter = field(default_factory=collections.Counter)  # as spelled -> references
    replaced: list = field(default_factory=list)
    maybe: tuple = ()  # for NOT_FOUND: the libraries the project references that softplc lacks
    spelling: dict = field(default_factory=dict)  # UPPER name -> as first written
    _places: set = field(default_factory=set, repr=False)

    def add(self, name: str, d: Diagnostic) -> None:
        """One more error from name (counted as first spelled, once per place)."""
        spelled = self.spelling.setdefault(name.upper(), name)
        place = (d.pos.file, d.pos.line, d.pos.col)
        if place not in self._places:
            self._places.add(place)
            self.names[spelled] += 1
        self.replaced.append(d)

    @property
    def count(self) -> int:
        """The references: the places of the errors replaced (a qualified
        type can draw two errors at one place)."""
        return len({(d.pos.file, d.pos.line, d.pos.col) for d in self.replaced})

    def diagnostic(self) -> Diagnostic:
        top = [n for n, _ in self.names.most_common(3)]
        refs = f"{self.count} reference{'s' if self.count != 1 else ''}"
        used = f"{', '.join(top)} … {refs}" if len(self.names) > len(top) else f"{', '.join(top)}: {refs}"
        if self.name == NOT_FOUND:
            maybe = ", ".join(self.maybe[:4]) + (f" … {len(self.maybe)} libraries" if len(self.maybe) > 4 else "")
            return Diagnostic(
                "E224",
                f"names not found ({used}), maybe from {maybe}",
                self.pos,
                "the project references libraries softplc does not have; --all-errors shows each use",
            )
        where = "" if self.referenced else " (the project does not reference it either)"
        if self.name.upper() in shipped():
            return Diagnostic(
                "E223",
                f"needs {self.name} ({used}), which softplc ships: not chosen{where}",
                self.pos,
                f'add it: [plc] libraries = ["{self.name}"] or --library {self.name}; --all-errors shows each use',
            )
        return Diagnostic(
            "E223",
            f"needs {self.name} ({used}): not installed{where}",
            self.pos,
            f"softplc has no {self.name}: give the POUs the project uses from it as a library "
            "([plc] libraries), or leave out what uses them; --all-errors shows each use",
        )


def _subject(d: Diagnostic, declared: frozenset) -> str | None:
    """The name an error says is missing, as written (maybe qualified)."""
    if d.code not in _CODES:
        return None
    for pattern in _MESSAGES:
        m = pattern.search(d.message)
        if m:
            return m.group(1)
    m = _BASE.search(d.message)
    if m and m.group(1).upper() not in declared:  # EXTENDS a block nobody declares
        return m.group(1)
    return None


class _Resolver:
    def __init__(self, refs: list, installed: frozenset, own: frozenset, kind: str | None = None) -> None:
        self.refs = refs
        #: the libraries of the table this kind of project can have
        self.table = tuple(lib for lib in vendor_table() if not lib.tools or kind is None or kind in lib.tools)
        self.installed = installed
        self.own = own  # UPPER: the project's own names (its name, its objects' names)
        self.ref_of: dict = {}
        for r in refs:
            self.ref_of.setdefault(r.namespace.upper(), r)
            self.ref_of.setdefault(r.name.upper(), r)
        self.lacking = tuple(r.name for r in refs if not self._has(r.name, r.namespace))

    def _has(self, *names: str) -> bool:
        return any(n.upper() in self.installed for n in names)

    def library(self, subject: str) -> str | None:
        """The library a missing name belongs to, NOT_FOUND, or None (an
        error of the project's own)."""
        *path, name = subject.split(".")
        if path:
            ns = path[0].upper()
            ref = self.ref_of.get(ns)
            if ref is not None:
                return None if self._has(ref.name, ref.namespace) else ref.name
            for lib in self.table:
                if ns in lib.namespaces:
                    return lib.name
            return None
        key = name.upper()
        if key in _NOT_LIBRARY or key in self.own:
            return None
        ref = self.ref_of.get(key)
        if ref is not None:  # IBaseLibrary.TypeClass: the namespace itself is unknown
            return None if self._has(ref.name, ref.namespace) else ref.name
        candidates = [lib for lib in self.table if key in lib.names]
        if any(self._has(lib.name, *lib.namespaces) for lib in candidates):
            return None  # a library the compilation had: the error is the code's own
        if candidates:
            referenced = [lib for lib in candidates if any(ns in self.ref_of for ns in lib.namespaces)]
            return (referenced or candidates)[0].name
        return NOT_FOUND if self.lacking else None


def group(
    diagnostics: list,
    units: Units,
    refs: list,
    installed: frozenset = frozenset(),
    own: tuple = (),
    kind: str | None = None,
) -> tuple:
    """(the MissingLibrary groups, the diagnostics they do not replace).
    installed: the names of the libraries the compilation had; own: the
    project's own names (its name; its files' stems, which name TwinCAT
    objects even when one does not parse); kind: the kind of project
    (twincat, codesys, beremiz), whose tool's libraries the table offers."""
    have = frozenset(installed) | frozenset(LIBRARY_NAMESPACES) | frozenset(LIBRARY_NAMESPACES.values())
    declared = frozenset().union(*(u.declares for u in units.all))
    # the names of the project's own POUs and types (a variable may be named like a library's type)
    own_types = frozenset().union(*(u.declares for u in units.all if u.kind not in ("VAR_GLOBAL", "CONFIGURATION")))
    resolver = _Resolver(refs, frozenset(n.upper() for n in have), own_types | frozenset(n.upper() for n in own), kind)
    groups: dict[str, MissingLibrary] = {}
    rest = []
    subjects = [_subject(d, declared) if d.is_error else None for d in diagnostics]
    unknown = frozenset(s.upper() for s, d in zip(subjects, diagnostics) if s and d.code != "E010")
    for d, subject in zip(diagnostics, subjects):
        typed = None
        if subject and d.code in ("E010", "E043"):  # a variable (an instance) whose declaration failed?
            typed = _variable_type(d, subject, units)
        elif subject is None and d.is_error and d.code in ("E013", "E040", "E041", "E148"):
            typed = _parameter_type(d, units, unknown)  # a parameter (a return type, a base) whose declaration failed?
        if typed is not None:  # named by its type, when that is a missing library's
            lib = resolver.library(typed) if typed.upper() in unknown else None
            subject = typed
        else:
            lib = resolver.library(subject) if subject else None
            if lib == NOT_FOUND and d.hint and d.hint.startswith("did you mean"):
                lib = None  # a near name is declared: a typing mistake, not a library's name
        if lib is None or subject is None:
            rest.append(d)
            continue
        g = groups.get(lib)
        if g is None:
            ref = resolver.ref_of.get(lib.upper())
            g = groups[lib] = MissingLibrary(lib, ref.pos if ref else d.pos, ref is not None, maybe=resolver.lacking)
        g.add(subject.split(".")[-1], d)
    ordered = sorted(groups.values(), key=lambda g: (g.name == NOT_FOUND, -g.count, g.name))
    return ordered, rest


def _variable_type(d: Diagnostic, name: str, units: Units) -> str | None:
    """The type (as written) of a variable name that the unit holding d
    declares (its declaration failed, or the error would not be)."""
    unit = units.hit(d.pos.file, d.pos.line, d.pos.col)
    while unit is not None:
        found = unit.type_of(name, d.pos.line, d.pos.col)
        if found is not None:
            return found
        unit = units.all[unit.parent] if unit.parent is not None else None
    return None


def _parameter_type(d: Diagnostic, units: Units, unknown: frozenset) -> str | None:
    """E040 'F has no parameter P', E148 'METHOD M has no return type',
    E041 'too many arguments for F (it takes 0)', E013 'FB has no member
    M': the type of P (of M's return, of an input of F, of FB's base) where
    F (M, FB) is declared, when its declaration failed."""
    m = _TOO_MANY.search(d.message)
    if m:
        for u in _declaring(units, m.group(1), d):
            inputs = u.signatures.get(m.group(1).upper())
            if inputs is not None:
                return next((t for t in inputs if t.upper() in unknown), None)
        return None
    m = _NO_MEMBER.search(d.message) if d.code == "E013" else None
    if m:
        owner = [u for u in units.all if u.name.upper() == m.group(1).upper()]
        member = d.message.split("'")[1]
        found = [u.declares_variable(member) for u in owner] + [u.extends for u in owner]
        return next((t for t in found if t is not None and t.upper() in unknown), None)
    m = _PARAMETER.search(d.message) or _NO_RETURN.search(d.message)
    if m:
        callee = m.group(1)
        name = m.group(2) if m.re is _PARAMETER else callee
        types = (u.declares_variable(name) for u in _declaring(units, callee, d))
        return next((t for t in types if t is not None and t.upper() in unknown), None)
    return None


def _declaring(units: Units, name: str, d: Diagnostic) -> list:
    """The units that may declare name: the POU of that name, the unit the
    error is in (its own methods), then every unit."""
    key = name.upper()
    first = [u for u in units.all if u.name.upper() == key]
    here = units.hit(d.pos.file, d.pos.line, d.pos.col)
    return [*first, *([here] if here is not None else []), *units.all]


def group_analysis(analysis, installed: frozenset = frozenset()) -> tuple:
    """group() for an analysis.Analysis of a project: its references, its
    own names, its kind."""
    if not any(d.is_error for d in analysis.diagnostics):  # only errors are grouped (and the units not found for none)
        return [], list(analysis.diagnostics)
    project = analysis.project
    lost = [name for names in analysis.lost.values() for name, _line in names]  # its POUs not imported
    own = (project.name, *(Path(f).stem for f in project.files), *lost)
    kind = project.kind if project.kind in ("twincat", "codesys", "beremiz") else None
    return group(analysis.diagnostics, analysis.units, project.libraries, installed, own, kind)
