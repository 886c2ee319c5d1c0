"""A project checked as a whole, and the largest part of it that compiles.

The whole project is checked once: those are the diagnostics a user reads.
Then, as long as errors remain, the units they lie in are left out (a POU
with its methods and actions, a type, a global variable, a program
instance of the CONFIGURATION), and with them every unit that names one
left out, and the rest is checked again, at most MAX_ROUNDS times. A POU
"compiles" when it is in the part that is left, which compiles cleanly: a
POU broken only by a library POU it calls is not compiled, its neighbours
are. That part's Program is what `exec --partial`, `run --partial` and the
benchmark run, and what `export-st` marks as compiled.

Each file is parsed once (libraries.parse_cached): kept in memory, and in
the cache folder in one entry per file (a project's sources change with
every edit: an entry per content would fill the folder), so a check of an
unchanged file does not parse it again; a round takes a fresh copy of the
parse and prunes it, so no file is read or parsed again.
"""

from __future__ import annotations

import re
from collections.abc import Callable
from dataclasses import dataclass, field

from ..collector import collector_off
from ..program.compile import build_parsed, check_parsed, words_of
from ..program.libraries import parse_cached
from ..program.loaded import Program
from ..program.shipped import shipped_named
from ..st.ast import Pos
from ..st.diagnostics import Diagnostic, DiagnosticBag, SourceSet
from ..st.limits import MAX_SOURCE_CHARS
from ..st.profile import DEFAULT, Profile, get_profile
from ..st.syntax.parser import parse_source
from .model import Project
from .units import Unit, Units, prune

MAX_ROUNDS = 12
# A POU element of a PLCopen XML file (<pou name="X">) or a TwinCAT file (<POU Name="X">).
_POU_ELEMENT = re.compile(r'<(?:pou|POU)\s[^>]*?\b[Nn]ame="([A-Za-z_][A-Za-z0-9_]*)"')


@dataclass
class Analysis:
    project: Project
    profile: Profile
    diagnostics: list  # the whole project's, sorted: project files, sources, compilation
    sources: SourceSet
    #: the units, or how to find them when first asked (see analyse)
    units_of: Units | Callable[[], Units]
    dropped: set = field(default_factory=set)  # ids of the units left out
    #: id of a unit left out for a name it uses (not an error of its own) -> that name
    because: dict = field(default_factory=dict)
    #: file -> (name, line) of each POU its XML declares that did not become
    #: ST (in a language not imported, or its file not read)
    lost: dict = field(default_factory=dict)
    texts: dict = field(default_factory=dict)  # file -> the text parsed (ST a project file gives, for one)
    clean: bool = False  # the part left compiled
    program: Program | None = None  # that part's Program (None when nothing compiles)
    rounds: int = 0
    libraries: tuple = ()  # the libraries compiled with: given, and the shipped ones the project references

    @property
    def units(self) -> Units:
        if not isinstance(self.units_of, Units):
            self.units_of = self.units_of()
        return self.units_of

    def compiled(self, unit: Unit) -> bool:
        return self.clean and unit.id not in self.dropped

    @property
    def errors(self) -> list:
        return [d for d in self.diagnostics if d.is_error]


def with_referenced(libraries: tuple, project: Project) -> tuple:
    """libraries, and the libraries softplc ships that the project references
    (by name, or by the namespace a CODESYS export gives it) and libraries
    does not have yet."""
    have = {lib.namespace.upper() for lib in libraries}
    out = list(libraries)
    for ref in project.libraries:
        lib = shipped_named(ref.name) or shipped_named(ref.namespace)
        if lib is not None and lib.namespace.upper() not in have:
            have.add(lib.namespace.upper())
            out.append(lib)
    return tuple(out)


def _read(path: str, diags: DiagnosticBag) -> str | None:
    try:
        with open(path, "rb") as f:
            data = f.read(4 * MAX_SOURCE_CHARS + 4)
    except OSError as exc:
        diags.error("E000", f"cannot read the file: {exc.strerror or exc}", Pos(path, 1, 1))
        return None
    try:
        return data.decode("utf-8-sig")
    except UnicodeDecodeError:
        return data.decode("latin-1")


def _parse(path: str, text: str, profile: Profile, diags: DiagnosticBag | None) -> list:
    """The SourceFiles of a file (a fresh copy each call); its diagnostics
    into diags when given. An importer's own failure is E009 for that file
    alone: the rest of the project is still checked."""
    try:
        files, items = parse_cached(path, text, profile, slot=True)  # (in memory for the rounds, one entry a file)
    except Exception as exc:  # a bug in an importer must not lose the project
        if diags is not None:
            diags.error(
                "E009",
                f"internal error reading the file: {type(exc).__name__}: {exc}",
                Pos(path, 1, 1),
                "please report this with the file; the rest of the project is checked",
            )
        return []
    if diags is not None:
        diags.extend(items)
    return files


@collector_off()
def analyse(
    project: Project,
    profile: str | Profile | None = None,
    *,
    natives: tuple = (),
    libraries: tuple = (),
    subset: bool = True,
    check_only: bool = False,
) -> Analysis:
    """Check project; with subset, find the part that compiles (see the
    module docstring). check_only: the diagnostics and what compiles, no
    Program (`softplc check`: the back end runs only when it may report)."""
    prof = profile if isinstance(profile, Profile) else get_profile(profile or project.profile or DEFAULT.name)
    libraries = with_referenced(tuple(libraries), project)
    sources = SourceSet()
    for name, text in project.texts.items():
        sources.add(name, text)
    diags = DiagnosticBag()
    diags.extend(project.diags.items)
    texts: dict[str, str] = {}
    for path in project.files:
        if path in project.generated:  # ST the project's files give (messages show those files)
            texts[path] = project.generated[path]
            continue
        text = _read(path, diags)
        if text is not None:
            texts[path] = text
            sources.add(path, text)
    parse_items = DiagnosticBag()

    def parse(path: str, text: str, into: DiagnosticBag | None) -> list:
        if path in project.generated:
            bag = into if into is not None else DiagnosticBag()
            return [parse_source(text, path, bag, prof)]
        return _parse(path, text, prof, into)

    def fresh() -> dict:
        return {path: parse(path, text, None) for path, text in texts.items()}

    parsed = {path: parse(path, text, parse_items) for path, text in texts.items()}
    xml = {
        path: text
        for path, text in texts.items()
        if path.lower().endswith(_XML_KINDS) and path not in project.generated
    }
    units_of: Units | Callable[[], Units]
    if project.kind == "files" and not xml and not project.tasks:
        # Plain ST files: the libraries they take found as compile_files finds
        # them (by the words of their texts), and their units (a walk of every
        # POU: 25 ms for 10,000 lines) only when asked, for errors, from a
        # fresh parse (the check annotates this one).
        words = frozenset().union(*map(words_of, texts.values()))
        units_of, lost = (lambda: Units(fresh())), {}
    else:
        units = Units(parsed)
        words = frozenset().union(*(u.words for u in units.all))
        units_of, lost = units, {path: _lost(path, text, units) for path, text in xml.items()}

    compiled_diags = DiagnosticBag()
    compiled_diags.extend(parse_items.items)
    files = [sf for views in parsed.values() for sf in views]

    def build(part: list, words: frozenset, into: DiagnosticBag) -> tuple[bool, Program | None]:
        """(whether the files compile, their Program unless check_only)"""
        if check_only:
            return check_parsed(part, words, prof, sources, into, natives=natives, libraries=libraries), None
        built = build_parsed(part, words, prof, sources, into, natives=natives, libraries=libraries)
        return built is not None, built

    clean, program = build(files, words, compiled_diags)
    diags.extend(compiled_diags.items)
    result = Analysis(project, prof, diags.sorted(), sources, units_of, lost={p: x for p, x in lost.items() if x})
    result.libraries = libraries
    result.texts = texts
    _check_tasks(result, program)
    result.diagnostics = sorted(result.diagnostics, key=lambda d: (d.pos.file, d.pos.line, d.pos.col, d.code))
    if clean:
        result.clean, result.program = True, program
        return result
    if not subset or not texts:
        return result
    units = result.units
    outside = {id(d) for d in parse_items.items if not _inside(d, units, set())}
    errors = [d for d in compiled_diags.items if d.is_error and id(d) not in outside]
    for _ in range(MAX_ROUNDS):
        result.rounds += 1
        hits = _hits(errors, units)
        if hits is None:  # an error no unit holds: nothing left out would clear it
            return result
        _drop(result, hits)
        kept = [u for u in units.all if u.id not in result.dropped]
        round_diags = DiagnosticBag()
        round_diags.extend(d for d in parse_items.items if _inside(d, units, result.dropped))
        pruned = prune(fresh(), units, result.dropped)
        words = frozenset().union(*(u.words for u in kept))
        clean, program = build(pruned, words, round_diags)
        if clean:
            result.clean, result.program = True, program
            return result
        errors = [d for d in round_diags.items if d.is_error]
    return result


_XML_KINDS = (".xml", ".tcpou")


def _lost(path: str, text: str, units: Units) -> list:
    """(name, line) of the POUs the file's XML declares that no unit is."""
    have = {u.name.upper() for u in units.by_file.get(path, ()) if u.is_pou}
    out = []
    for m in _POU_ELEMENT.finditer(text):
        if m.group(1).upper() not in have:
            out.append((m.group(1), text.count("\n", 0, m.start()) + 1))
    return out


def _inside(d: Diagnostic, units: Units, dropped: set) -> bool:
    """Whether a parse diagnostic lies in a unit that is kept (one outside
    every unit, such as a POU in a language not imported, does not stop
    the others from compiling)."""
    u = units.hit(d.pos.file, d.pos.line, d.pos.col)
    return u is not None and u.id not in dropped and (u.parent is None or u.parent not in dropped)


def _hits(errors: list, units: Units) -> set | None:
    """The units the errors lie in; None when an error lies in none of
    them (in a library file, or outside every declaration)."""
    out = set()
    for d in errors:
        u = units.hit(d.pos.file, d.pos.line, d.pos.col)
        if u is None:
            return None
        out.add(u.id)
    return out


def _drop(result: Analysis, hits: set) -> None:
    """Leave out the hit units (a block or a CONFIGURATION with what is in
    it), then every unit that names what no kept unit declares any more."""
    units = result.units
    pending = list(hits)
    while pending:
        uid = pending.pop()
        if uid in result.dropped:
            continue
        result.dropped.add(uid)
        pending.extend(units.all[uid].members)
    while True:
        kept = [u for u in units.all if u.id not in result.dropped]
        alive = frozenset().union(*(u.declares for u in kept))
        gone = frozenset().union(*(units.all[i].declares for i in result.dropped)) - alive
        grew = False
        for u in kept:
            lost = u.uses & gone
            if lost:
                result.dropped.add(u.id)
                result.because[u.id] = _spelled(units, min(lost))
                result.dropped.update(u.members)
                grew = True
        if not grew:
            return


def _spelled(units: Units, key: str) -> str:
    for u in units.all:
        if u.name.upper() == key:
            return u.name
    return key


def _check_tasks(result: Analysis, program: Program | None) -> None:
    """E222 for a task of the project (.TcTTO) that calls what the project
    does not declare as a PROGRAM."""
    if not result.project.tasks:
        return
    kinds = {u.name.upper(): u.kind for u in result.units.all if u.is_pou}
    bag = DiagnosticBag()
    for task in result.project.tasks:
        for name, pos in task.programs:
            kind = kinds.get(name.upper())
            if kind == "PROGRAM":
                continue
            what = f"a {kind}" if kind else "not declared in the project"
            bag.error(
                "E222",
                f"task {task.name} calls {name}, which is {what}",
                pos,
                "a task calls PROGRAMs; add the PROGRAM to the project or remove the call from the task",
            )
    result.diagnostics.extend(bag.items)
