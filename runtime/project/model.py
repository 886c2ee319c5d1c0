"""What a project is once found: its kind, its source files, the libraries
it references, its tasks, and the problems of the project files themselves
(a .sln naming a missing .tsproj, a .TcTTO without a cycle time)."""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

from ..st.ast import Pos
from ..st.diagnostics import DiagnosticBag

#: the kinds of project, and the profile each tool's code is written for
KINDS = {
    "twincat": "twincat",  # a .sln, .tsproj or .plcproj
    "codesys": "codesys",  # a CODESYS PLCopen XML export
    "beremiz": "matiec",  # a Beremiz (or OpenPLC editor) folder: plc.xml with beremiz.xml
    "plcopen": None,  # another PLCopen XML file
    "folder": None,  # a folder of sources
    "files": None,  # files named one by one
}


@dataclass(frozen=True)
class LibraryRef:
    """A library the project says it uses: name as the tool names it
    (``Tc2_System``), the namespace its code qualifies names with, and
    where the project says so."""

    name: str
    namespace: str
    pos: Pos


@dataclass(frozen=True)
class TaskSpec:
    """A task a project file declares (TwinCAT's .TcTTO): cycle time,
    priority and the PROGRAMs it calls, each with where it is named."""

    name: str
    interval_ns: int
    priority: int
    programs: tuple  # (name, Pos)
    pos: Pos


@dataclass
class Project:
    kind: str
    name: str
    root: Path  # a folder: the table names files relative to it
    path: Path  # what was given (a file or a folder)
    files: list[str] = field(default_factory=list)
    libraries: list[LibraryRef] = field(default_factory=list)
    tasks: list[TaskSpec] = field(default_factory=list)
    #: Beremiz extensions (folder name, kind): code softplc does not run (Python, C, HMI, buses)
    extensions: list[tuple] = field(default_factory=list)
    diags: DiagnosticBag = field(default_factory=DiagnosticBag)
    #: the texts of the project's own files (.plcproj, .TcTTO ...), for excerpts in messages
    texts: dict = field(default_factory=dict)
    #: file -> the ST it gives, laid on its lines (the variables of a Beremiz Python
    #: extension): compiled as that file, its messages show the file's own lines
    generated: dict = field(default_factory=dict)

    @property
    def profile(self) -> str | None:
        """The profile the tool's code reads as, None when the kind does not say."""
        return KINDS.get(self.kind)

    def label(self, path: str) -> str:
        """A source's name in the table: relative to the project's folder."""
        try:
            return str(Path(path).relative_to(self.root))
        except ValueError:
            return str(path)
