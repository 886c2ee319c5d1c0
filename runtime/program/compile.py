"""Compiling: the user's ST files and the libraries they need, through the
compile side (st/: parse, check, generate) into a loadable Program.

    prog = compile_files(["plant.st"], profile="codesys")   # CompileError on errors
    r = prog.runner("Main", cycle_time_ms=10)
    r.run(100)                                              # STFault on a runtime fault

The IEC standard function blocks (fblocks/iec/*.st) and PLC_DIAG are
compiled into every program; a user POU or type of the same name replaces
the library one. The IEC typed counters (CTU_DINT ...), SPLIT_DATE/TOD/DT,
the communication and the device libraries are compiled in only when a
program names something they declare.
"""

from __future__ import annotations

import functools
import itertools
import re
from collections.abc import Mapping
from importlib import resources
from pathlib import Path

from ...fblocks.iec.functions import STANDARD_FUNCTIONS
from .. import cache
from ..collector import collector_off
from ..image.memory import ProcessImage
from ..plugin.registry import plugin_libraries, plugin_natives
from ..plugin.seams import StLibrary
from ..st import ast as A
from ..st.check.checker import CheckedProgram, Checker
from ..st.codegen import nesting
from ..st.codegen.codegen import CodeGen
from ..st.diagnostics import CompileError, DiagnosticBag, SourceSet
from ..st.importers import source_files
from ..st.limits import MAX_SOURCE_CHARS
from ..st.profile import DEFAULT, Profile, get_profile
from ..st.syntax.pragmas import attribute_value
from .libraries import parse_cached, parser_code
from .loaded import Program
from .reparse import parse_views
from .shipped import Elsewhere, functions_of, natives_of, with_required

_gen_counter = itertools.count(1)


# Compiled into every program: the standard blocks and PLC_DIAG.
_ALWAYS = ("softplc.fblocks.iec", "softplc.fblocks.system")
# IEC library files of those packages compiled in only when a program names
# what they declare: 15 typed counters and the SPLIT_ functions would cost
# every other program compile time.
_IEC_ON_DEMAND = (
    StLibrary("softplc.fblocks.iec", "typed_counters.st"),
    StLibrary("softplc.fblocks.iec", "date_time.st"),
)
_WORD = re.compile(r"[A-Za-z_][A-Za-z0-9_]*")
_THIS = Path(__file__)


def _always_sources() -> list:
    """(name, text) of the ST files compiled into every program."""
    out = []
    on_demand = {(lib.package, lib.file) for lib in _IEC_ON_DEMAND}
    for package in _ALWAYS:
        root = resources.files(package)
        for entry in sorted(root.iterdir(), key=lambda p: p.name):
            if entry.name.endswith(".st") and (package, entry.name) not in on_demand:
                out.append((f"<lib>/{package.rsplit('.', 1)[-1]}/{entry.name}", entry.read_text("utf-8")))
    return out


def _on_demand_sources() -> list:
    """(name, text) of the ST files of every registered bus and device,
    compiled in only when a program names something they declare (and then
    with the library files those name in turn). A program that never
    mentions a device's block does not pay for it, and a user POU that
    replaces a standard block (its own TON) cannot break a device block it
    does not use."""
    libraries = (*_IEC_ON_DEMAND, *plugin_libraries())
    return sorted((lib.name, lib.read_text()) for lib in libraries)


def _library_sources() -> list:
    """(name, text) of every ST library file: always compiled, then on demand."""
    return _always_sources() + _on_demand_sources()


def _declared(sf: A.SourceFile) -> set:
    """Every name a library file declares: POUs, types, globals and the
    values of its enumerations (``SysFile.AM_READ``, a bare ``AM_READ``) and
    the global variable lists it names ({attribute 'gvl_name' := 'GVL_Param'})."""
    names = _decl_names(sf)
    for d in sf.decls:
        if isinstance(d, A.VarBlock):
            names.update(v.name.upper() for v in d.decls)
            listed = attribute_value(d, "gvl_name")
            if listed:
                names.add(listed.upper())
        elif isinstance(d, A.TypeDecl) and isinstance(d.spec, A.EnumTypeSpec):
            names.update(value[0].upper() for value in d.spec.values)
    return names


def _declared_in(files: list) -> set:
    """Every name the parsed files declare (a file's views: several)."""
    return set().union(*(_declared(sf) for sf in files))


@functools.cache
def _library_index(name: str, text: str) -> tuple:
    """(names the file declares, words it uses) of an on-demand library file,
    once per process and kept in softplc's cache (by the text, softplc's
    version and the code of the parser and of this module): the choice of
    files then costs no parsing, nor reading a parse."""
    key = cache.key("libindex", parser_code(), _THIS.read_bytes(), name, text)
    found = cache.load("libindex", key)
    if not (isinstance(found, tuple) and len(found) == 2):
        files, _ = parse_cached(name, text, DEFAULT)
        found = (
            frozenset(_declared_in(files)),
            frozenset(w.upper() for w in _WORD.findall(text)),
        )
        cache.store("libindex", key, found)
    return found


def _take_named(units: list, words: set, index) -> tuple:
    """(the units whose declared names the words name, and then those that
    the taken units' words name in turn, in that order; all the words).
    index(unit) -> (names it declares, words it uses), upper case."""
    pending, taken, words = list(units), [], set(words)
    grew = True
    while grew:
        grew = False
        for unit in list(pending):
            declared, used = index(unit)
            if declared & words:
                taken.append(unit)
                pending.remove(unit)
                words |= used
                grew = True
    return taken, words


def _needed_library(always: list, on_demand: list, user_words: set) -> list:
    """(name, text) of the always-compiled files, and of the on-demand ones
    that the user's words (or an already needed library file's words) name."""
    taken, _ = _take_named(on_demand, user_words, lambda unit: _library_index(*unit))
    return list(always) + taken


def _std_functions() -> dict:
    return STANDARD_FUNCTIONS


def _natives(extra: tuple = ()) -> Mapping:
    """The registered buses' and devices' native functions, and extra ones
    a caller compiles with (the test runner's assertions)."""
    return plugin_natives(extra)


def _read_text(p, diags: DiagnosticBag) -> str | None:
    """A source file's text (UTF-8, or Latin-1 as Windows tools still write
    it), or None with E000 when it cannot be read."""
    try:
        with open(p, "rb") as f:
            # no more than can hold MAX_SOURCE_CHARS characters and one:
            # the parser reports a larger file (E007) without reading on
            data = f.read(4 * MAX_SOURCE_CHARS + 4)
    except OSError as exc:
        diags.error("E000", f"cannot read the file: {exc.strerror or exc}", A.Pos(str(p), 1, 1))
        return None
    if data.startswith((b"\xff\xfe", b"\xfe\xff")):  # UTF-16 with its byte order mark, as Windows writes it
        try:
            return data.decode("utf-16")
        except UnicodeDecodeError:
            pass
    if b"\0" in data:  # a program (/bin/ls), an image: its bytes were 100 kB of errors
        diags.error(
            "E000",
            f"not a text file (a NUL byte at byte {data.index(0)}): an ST file is text",
            A.Pos(str(p), 1, 1),
            "name the .st (or .xml, .TcPOU) file, not a compiled or binary one",
        )
        return None
    try:
        return data.decode("utf-8-sig")
    except UnicodeDecodeError:
        return data.decode("latin-1")


def _read_sources(
    paths: list, texts: dict | None, diags: DiagnosticBag, sources: SourceSet, profile: Profile, keep: bool
) -> tuple:
    """(parsed files, the set of words in them, upper case), parsed as the
    profile reads ST; keep: each file's parse kept for the next check of it
    (reparse.py)."""
    files = []
    for p in source_files(paths, lambda p: _read_text(p, diags), diags):  # a .plcproj: its files
        text = _read_text(p, diags)
        if text is not None:
            files.append((str(p), text))
    for name, text in (texts or {}).items():
        files.append((name, text))
    parsed = []
    words: set = set()
    for name, text in files:
        sources.add(name, text)  # an imported file's own text: diagnostics show its lines
        sfs, items, found = parse_views(name, text, profile, words_of, keep)
        parsed.extend(sfs)
        diags.extend(items)
        words |= found
    return parsed, words


def words_of(text: str) -> set:
    """The identifiers of a text, upper case: which on-demand libraries a
    program takes (a name in a comment takes one too: it compiles cleanly)."""
    return {w.upper() for w in _WORD.findall(text)}


def _decl_names(sf: A.SourceFile) -> set:
    return {d.name.upper() for d in sf.decls if isinstance(d, (A.POU, A.TypeDecl, A.Interface))}


def _user_libraries(libraries: tuple, profile: Profile, words: set, diags: DiagnosticBag, sources: SourceSet):
    """(the parsed files of the user's libraries that the words name, and
    the words those use in turn; the namespaces for the checker). Errors in
    a library file that is taken are reported; the others cost nothing."""
    units = []  # (declared, used, name, text, parsed files, parse diagnostics) per file
    namespaces: dict = {}
    for lib in libraries:
        prof = get_profile(lib.profile) if lib.profile else profile
        declared_all: set = set()
        for f in lib.files():
            text = _read_text(f, diags)
            if text is None:
                continue
            files, items = parse_cached(str(f), text, prof)
            declared = _declared_in(files)
            declared_all |= declared
            units.append((declared, {w.upper() for w in _WORD.findall(text)}, str(f), text, files, items))
        declared_all |= set(functions_of((lib,)))  # Tc2_System.MEMCPY: its Python functions too
        for ns in (lib.namespace, *lib.namespaces):
            namespaces[ns.upper()] = (ns, frozenset(declared_all))
    taken, words = _take_named(units, words, lambda unit: unit[:2])
    parsed = []
    for _declared_names, _used, name, text, files, items in taken:
        sources.add(name, text)
        diags.extend(d for d in items if d.is_error)
        parsed.extend(files)  # (new objects of this compilation: parse_cached)
    return parsed, words, namespaces


def _unavailable(libraries: tuple, taken: list, user: list, words: set, diags: DiagnosticBag) -> None:
    """W230 once for each library the program uses that cannot do its work
    here (shipped.py: a library of hardware or a runtime service), and once
    for each such file of a library that otherwise works (Tc2_System's ADS
    blocks), naming what the program uses of it."""
    used: dict = {}  # resolved path -> the taken SourceFiles of it
    for sf in taken:
        used.setdefault(str(Path(sf.path).resolve()), []).append(sf)
    where = A.Pos(user[0].path if user else "<input>", 1, 1)
    hint = "the program compiles and runs; the library's blocks answer through their error outputs"
    for lib in libraries:
        if lib.unavailable and any(str(f.resolve()) in used for f in lib.files()):
            diags.warning("W230", f"{lib.namespace} is declared but not available here: {lib.unavailable}", where, hint)
            continue
        for file_name, why in lib.unavailable_parts:
            files = [sf for f in lib.files() if f.name == file_name for sf in used.get(str(f.resolve()), ())]
            if not files:
                continue
            names = sorted(_decl_spelled(files, words))
            what = ", ".join(names[:4]) + (" ..." if len(names) > 4 else "")
            verb = "is" if len(names) == 1 else "are"
            diags.warning("W230", f"{lib.namespace} {what} {verb} declared but not available here: {why}", where, hint)


def _decl_spelled(files: list, words: set) -> set:
    """The POUs and types the files declare that the words name, as spelled."""
    return {d.name for sf in files for d in sf.decls if isinstance(d, (A.POU, A.TypeDecl)) and d.name.upper() in words}


def _front_end(
    paths: list,
    profile: Profile,
    texts: dict | None,
    natives: tuple = (),
    libraries: tuple = (),
    keep: bool = False,
    files: list | None = None,
):
    diags = DiagnosticBag()
    sources = SourceSet()
    user, user_words = _read_sources(paths, texts, diags, sources, profile, keep)
    checked = _check(user, user_words, profile, natives, libraries, diags, sources, files)
    return diags, sources, checked, user


def _check(
    user: list,
    user_words: set,
    profile: Profile,
    natives: tuple,
    libraries: tuple,
    diags: DiagnosticBag,
    sources,
    files: list | None = None,
) -> CheckedProgram:
    """Check the user's parsed files with the libraries their words name
    (every file checked, library and user, appended to files when given)."""
    libraries = with_required(tuple(libraries))
    user_names = set().union(*(_decl_names(sf) for sf in user)) if user else set()
    lib_diags = DiagnosticBag()
    library = []
    namespaces: dict = {}
    if libraries:
        own_words = user_words
        taken, user_words, namespaces = _user_libraries(tuple(libraries), profile, user_words, diags, sources)
        for sf in taken:  # a user POU of the same name replaces the library's
            sf.decls = [
                d for d in sf.decls if not (isinstance(d, (A.POU, A.TypeDecl)) and d.name.upper() in user_names)
            ]
        library.extend(taken)
        _unavailable(tuple(libraries), taken, user, own_words, diags)
    # a chosen library's POU replaces the IEC one of the same name (CODESYS
    # Standard's CTU with RESET, Tc2_Standard's), as a user's POU replaces either
    replaced = user_names.union(*(_decl_names(sf) for sf in library))
    for name, text in _needed_library(_always_sources(), _on_demand_sources(), user_words):
        sources.add(name, text)
        # written to read alike in every profile (tests/program/test_compile.py);
        # parsed once per content, as the user's libraries (libraries.py)
        [sf], items = parse_cached(name, text, DEFAULT)
        lib_diags.extend(items)
        sf.decls = [d for d in sf.decls if not (isinstance(d, (A.POU, A.TypeDecl)) and d.name.upper() in replaced)]
        library.append(sf)
    checker = Checker(
        profile,
        lib_diags if not user else diags,
        {**_std_functions(), **functions_of(tuple(libraries))},
        _natives((*natives, *natives_of(tuple(libraries)))),
        ProcessImage(profile.addressing),
        Elsewhere(tuple(libraries)),
    )
    checked = checker.run(library + user, library_files=tuple(sf.path for sf in library), namespaces=namespaces)
    if files is not None:
        files.extend(library + user)
    diags.extend(d for d in lib_diags.items if d.is_error)
    return checked


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
        diags.error(
            "E006",
            "the program is nested too deeply for the Python compiler "
            f"({getattr(exc, 'msg', None) or type(exc).__name__})",
            (gen.linemap.get(line) if line else None) or where,
            "move inner loops or long expressions into FUNCTIONs or intermediate variables",
        )
        return None


def _first_position(paths: list, texts: dict | None) -> A.Pos:
    names = [str(p) for p in paths] + list(texts or {})
    return A.Pos(names[0] if names else "<input>", 1, 1)


@collector_off()
def check_files(
    paths: list,
    profile: str | Profile = "codesys",
    texts: dict | None = None,
    natives: tuple = (),
    libraries: tuple = (),
):
    """Diagnostics of the files (errors and warnings, sorted) and their texts.
    Never raises for problems in the sources. Reports exactly what
    compile_files would: the back end runs too when the front end is clean
    and the back end may refuse the generated Python (st/codegen/nesting.py)."""
    prof = get_profile(profile) if isinstance(profile, str) else profile
    libraries = with_required(tuple(libraries))
    files: list = []
    diags, sources, checked, _ = _front_end(list(paths), prof, texts, natives, libraries, keep=True, files=files)
    if not diags.has_errors and nesting.too_deep(files):
        _back_end(checked, prof, diags, _first_position(paths, texts))
    return diags.sorted(), sources


@collector_off()
def compile_files(
    paths: list,
    profile: str | Profile = "codesys",
    *,
    texts: dict | None = None,
    natives: tuple = (),
    libraries: tuple = (),
) -> Program:
    """Compile ST files (and/or in-memory texts: name -> source) into a
    loadable Program. Raises CompileError with every diagnostic on errors.
    natives: NativeFunctions beyond the registered ones (st/native.py); the
    ExecContext's services execute them (the test runner binds its own).
    libraries: the user's libraries (program/libraries.py Library)."""
    prof = get_profile(profile) if isinstance(profile, str) else profile
    libraries = with_required(tuple(libraries))
    diags, sources, checked, user = _front_end(list(paths), prof, texts, natives, libraries)
    built = None if diags.has_errors else _back_end(checked, prof, diags, _first_position(paths, texts))
    if built is None:
        raise CompileError(diags.sorted(), sources)
    return _program(prof, checked, built, diags, sources, user, libraries)


def build_parsed(
    user: list,
    words: set | frozenset,
    profile: str | Profile,
    sources: SourceSet,
    diags: DiagnosticBag,
    *,
    natives: tuple = (),
    libraries: tuple = (),
) -> Program | None:
    """A Program of already parsed files (SourceFiles the caller parsed, and
    may have pruned: runtime/project/ compiles the part of a project that
    compiles), or None with the errors in diags. words: the names the files
    use, upper case (which on-demand libraries they take); sources: their
    texts, for the messages. The checker annotates the files: give fresh
    ones each time (libraries.parse_cached)."""
    prof, libraries, checked = _check_parsed(user, words, profile, sources, diags, natives, libraries)
    if diags.has_errors:
        return None
    built = _back_end(checked, prof, diags, _parsed_position(user))
    if built is None:
        return None
    return _program(prof, checked, built, diags, sources, user, libraries)


def check_parsed(
    user: list,
    words: set | frozenset,
    profile: str | Profile,
    sources: SourceSet,
    diags: DiagnosticBag,
    *,
    natives: tuple = (),
    libraries: tuple = (),
) -> bool:
    """What build_parsed reports into diags, without a Program: whether the
    files compile. The back end runs only when it may refuse the generated
    Python (E006, st/codegen/nesting.py): `softplc check` does not wait for code
    it does not run."""
    files: list = []
    prof, _libraries, checked = _check_parsed(user, words, profile, sources, diags, natives, libraries, files)
    if diags.has_errors:
        return False
    if not nesting.too_deep(files):
        return True
    return _back_end(checked, prof, diags, _parsed_position(user)) is not None


def _check_parsed(
    user: list, words, profile: str | Profile, sources: SourceSet, diags: DiagnosticBag, natives, libraries, files=None
) -> tuple:
    """(the profile, the libraries with the required ones, the checked
    program) of already parsed files: what build_parsed and check_parsed
    both do first."""
    prof = get_profile(profile) if isinstance(profile, str) else profile
    libraries = with_required(tuple(libraries))
    return prof, libraries, _check(user, set(words), prof, natives, libraries, diags, sources, files)


def _parsed_position(user: list) -> A.Pos:
    """Where an E006 of already parsed files points without a line of its own."""
    return A.Pos(user[0].path if user else "<input>", 1, 1)


def _program(prof: Profile, checked, built: tuple, diags: DiagnosticBag, sources, user: list, libraries: tuple):
    """The Program of a checked and generated program (its warnings, the
    user's POUs by kind, the libraries' Python functions)."""
    gen, code, filename = built
    user_pous = {d.name: d.kind for sf in user for d in sf.decls if isinstance(d, A.POU)}
    return Program(
        prof,
        checked,
        gen,
        code,
        filename,
        [d for d in diags.sorted() if not d.is_error],
        sources,
        user_pous,
        tuple(lib.functions for lib in libraries if lib.functions),
    )
