"""The vendor libraries softplc ships (fblocks/libs) as user libraries,
chosen by name; and which library an unknown name comes from.

    libs = choose(["Tc2_System", "../libs/oscat"], base_dir)   # Library objects
    prog = compile_files(["main.st"], libraries=libs)

A name in ``[plc] libraries``, ``--library`` or a project's references
that is no path but names a shipped library (or one of its aliases, case
ignored) is that library; anything else is a folder or file, as before.

``elsewhere(chosen)`` is what the checker appends to an unknown name
(``unknown name 'MEMCPY' (Tc2_System; add it to libraries = [...])``):
built on first use, from the shipped libraries not chosen (what their
files declare) and from catalogue.toml (what the common vendor
libraries declare, shipped or not).
"""

from __future__ import annotations

import functools
import importlib
import tomllib
from collections.abc import Iterator, Mapping
from dataclasses import dataclass
from importlib import resources
from pathlib import Path

from ...fblocks.libs import SHIPPED, LibrarySpec
from ..st import ast as A
from ..st.profile import DEFAULT, get_profile
from .libraries import Library, parse_cached


@dataclass(frozen=True)
class VendorLibrary:
    """A library of catalogue.toml: what it declares (UPPER), the names its
    names are qualified with (UPPER: its own and its namespaces), the kinds
    of project that have it (empty: any)."""

    name: str
    namespaces: frozenset
    names: frozenset
    tools: frozenset


@functools.cache
def catalogue() -> tuple[VendorLibrary, ...]:
    """The libraries of fblocks/libs/catalogue.toml, in its order."""
    text = resources.files("softplc.fblocks.libs").joinpath("catalogue.toml").read_text("utf-8")
    return tuple(
        VendorLibrary(
            name,
            frozenset([name.upper(), *(n.upper() for n in entry.get("namespaces", ()))]),
            frozenset(n.upper() for n in entry.get("names", "").split()),
            frozenset(entry.get("tools", ())),
        )
        for name, entry in tomllib.loads(text).items()
    )


def shipped() -> dict[str, LibrarySpec]:
    """UPPER name or alias -> the shipped library."""
    out: dict[str, LibrarySpec] = {}
    for spec in SHIPPED:
        for name in (spec.name, *spec.aliases):
            out.setdefault(name.upper(), spec)
    return out


def is_shipped_name(value) -> bool:
    """Whether value is the bare name of a library softplc ships (no folder
    separator: "Tc2_System", case ignored)."""
    return isinstance(value, str) and not any(c in value for c in "/\\") and value.strip().upper() in shipped()


def as_library(spec: LibrarySpec) -> Library:
    """A shipped library as the compiler takes a user's."""
    return Library(
        Path(str(resources.files(spec.package))),
        spec.name,
        spec.profile,
        namespaces=tuple(spec.namespaces),
        functions=spec.functions,
        natives=spec.natives,
        unavailable=spec.unavailable,
        unavailable_parts=tuple(spec.unavailable_parts),
        requires=tuple(spec.requires),
    )


def shipped_named(name: str) -> Library | None:
    """The shipped library of that name or alias, or None."""
    spec = shipped().get(name.strip().upper())
    return as_library(spec) if spec is not None else None


def with_required(libraries: tuple) -> tuple:
    """libraries, and after them the shipped libraries they require (in
    turn: Tc2_Utilities brings Tc2_System), each once."""
    out: list = []
    have: set = set()
    for lib in libraries:
        if lib.namespace.upper() not in have:
            have.add(lib.namespace.upper())
            out.append(lib)
    i = 0
    while i < len(out):
        for name in out[i].requires:
            lib = shipped_named(name)
            if lib is not None and lib.namespace.upper() not in have:
                have.add(lib.namespace.upper())
                out.append(lib)
        i += 1
    return tuple(out)


def natives_of(libraries: tuple) -> tuple:
    """The native functions of the libraries (st/native.py NativeFunctions)."""
    out: list = []
    for lib in libraries:
        if lib.natives:
            out.extend(importlib.import_module(lib.natives).NATIVES)
    return tuple(out)


def functions_of(libraries: tuple) -> dict:
    """The Python functions of the libraries (name -> StdFunc), for the
    checker and the code generator beside the standard functions."""
    out: dict = {}
    for lib in libraries:
        if lib.functions:
            out.update(importlib.import_module(lib.functions).FUNCTIONS)
    return out


#: the chosen libraries' UPPER namespaces -> Elsewhere's table: the same in
#: every check of a process (the shipped libraries and the catalogue do not
#: change), so the re-checks under other profiles do not parse them again
_ELSEWHERE: dict[frozenset, dict[str, str]] = {}


class Elsewhere(Mapping):
    """UPPER name -> "Tc2_System; add it to libraries = [...]" (a shipped
    library the program did not choose declares it) or "Tc2_MC2, which
    softplc does not have" (only catalogue.toml knows it); "UTIL." (a
    namespace, with its dot) -> "Util; add it ...": a qualified name behind
    an unchosen library's namespace. Built when the checker first asks, that
    is only when a name is unknown."""

    def __init__(self, chosen: tuple) -> None:
        self._chosen = {lib.namespace.upper() for lib in chosen}
        self._table: dict[str, str] | None = None

    def _built(self) -> dict[str, str]:
        if self._table is None:
            self._table = _ELSEWHERE.get(frozenset(self._chosen))
        if self._table is None:
            table: dict[str, str] = {}
            have = {spec.name.upper() for spec in SHIPPED}
            for spec in SHIPPED:
                if spec.name.upper() in self._chosen:
                    continue
                for name in _declared(spec):
                    table.setdefault(name, f"{spec.name}; add it to libraries = [...]")
                for ns in (spec.name, *spec.namespaces, *spec.aliases):
                    table.setdefault(ns.upper() + ".", f"{spec.name}; add it to libraries = [...]")
            for lib in catalogue():
                if lib.name.upper() in self._chosen or lib.name.upper() in have:
                    continue
                for name in (*lib.names, lib.name.upper() + "."):
                    table.setdefault(name, f"{lib.name}, a library softplc does not have")
            self._table = _ELSEWHERE[frozenset(self._chosen)] = table
        return self._table

    def __getitem__(self, key: str) -> str:
        return self._built()[key]

    def __iter__(self) -> Iterator[str]:
        return iter(self._built())

    def __len__(self) -> int:
        return len(self._built())

    def __bool__(self) -> bool:
        return True  # (never empty; and a truth test must not build the table)


def _declared(spec: LibrarySpec) -> set:
    """UPPER names a shipped library's files declare (POUs, types, globals)."""
    lib = as_library(spec)
    prof = get_profile(spec.profile) if spec.profile else DEFAULT
    names: set = set()
    for f in lib.files():
        files, _ = parse_cached(str(f), f.read_text("utf-8"), prof)
        for sf in files:
            for d in sf.decls:
                if isinstance(d, (A.POU, A.TypeDecl, A.Interface)):
                    names.add(d.name.upper())
                elif isinstance(d, A.VarBlock):
                    names.update(v.name.upper() for v in d.decls)
    names.update(functions_of((lib,)))
    names.update(fn.name for fn in natives_of((lib,)) if not fn.name.startswith("__"))
    return names
