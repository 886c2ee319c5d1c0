"""A TwinCAT 3 project: the solution (.sln) names its system projects
(.tsproj), a system project its PLC projects (.plcproj, inline or through
an .xti under _Config/PLC), a PLC project its sources (``<Compile
Include="POUs\\MAIN.TcPOU">``), its libraries (``<PlaceholderReference
Include="Tc2_System">``, ``<LibraryReference>``) and its tasks (.TcTTO:
cycle time in microseconds, priority, the PROGRAMs called).

Problems of these files are coded diagnostics at their line: E220 a
project file that names no project or a missing one, E221 a source the
PLC project lists that is not there, E222 a task object that cannot be
run as it is written.
"""

from __future__ import annotations

import os
import re
from pathlib import Path, PureWindowsPath

from ..st.ast import Pos
from ..st.importers.twincat import SOURCE_SUFFIXES
from ..st.importers.xmlsafe import PosElement, parse_xml
from .model import LibraryRef, Project, TaskSpec
from .readtext import read_text

# Project("{type GUID}") = "Name", "relative\path.tsproj", "{GUID}"
_SLN_PROJECT = re.compile(r'^Project\("[^"]*"\)\s*=\s*"([^"]*)"\s*,\s*"([^"]*)"', re.M)
_IDENT = re.compile(r"[A-Za-z_][A-Za-z0-9_]*\Z")
_PROJECT_FILES = (".tsproj", ".tspproj", ".plcproj")


def _local(base: Path, windows_path: str) -> Path:
    """A path a project file writes the Windows way, relative to base."""
    return Path(os.path.normpath(base.joinpath(*PureWindowsPath(windows_path).parts)))


def plc_projects(path: Path, project: Project) -> list[Path]:
    """The PLC projects (.plcproj) a .sln, .tsproj/.tspproj or .plcproj
    stands for; the problems on the way go into project."""
    suffix = path.suffix.lower()
    if suffix == ".sln":
        return read_solution(path, project)
    if suffix in (".tsproj", ".tspproj"):
        return read_tsproj(path, project)
    return [path]


def names_twincat(path: Path) -> bool:
    """Whether a .sln names a TwinCAT project (a folder's C# solution does not)."""
    try:
        text = path.read_text(encoding="utf-8-sig", errors="replace")
    except OSError:
        return True  # (reported when it is read)
    return any(m.group(2).lower().endswith(_PROJECT_FILES) for m in _SLN_PROJECT.finditer(text))


def read_solution(path: Path, project: Project) -> list[Path]:
    """The PLC projects of the TwinCAT projects a Visual Studio solution names."""
    text = read_text(path, project)
    if text is None:
        return []
    found = 0
    out: list[Path] = []
    for m in _SLN_PROJECT.finditer(text):
        rel = m.group(2)
        if not rel.lower().endswith(_PROJECT_FILES):
            continue  # a C# or other project of the solution: not PLC code
        found += 1
        target = _local(path.parent, rel)
        if not target.is_file():
            project.diags.error(
                "E220",
                f"the solution names {rel}, which is not there",
                _pos_of(path, text, m.start()),
                "restore the project folder, or check the project file itself",
            )
            continue
        out.extend(plc_projects(target, project))
    if not found:
        project.diags.error(
            "E220",
            "the solution names no TwinCAT project (.tsproj or .plcproj)",
            Pos(str(path), 1, 1),
            "check the .tsproj or the .plcproj itself",
        )
    return out


def _pos_of(path: Path, text: str, offset: int) -> Pos:
    line = text.count("\n", 0, offset) + 1
    return Pos(str(path), line, offset - (text.rfind("\n", 0, offset) + 1) + 1)


def read_tsproj(path: Path, project: Project) -> list[Path]:
    """The PLC projects of a TwinCAT system project: ``<Plc><Project
    PrjFilePath="X\\X.plcproj">`` inline, or ``<Project File="X.xti"/>``
    whose .xti (in _Config/PLC) holds the same element."""
    root = _xml(path, project)
    if root is None:
        return []
    out: list[Path] = []
    plc = [p for el in root.walk("Plc") for p in el.kids("Project")]
    if not plc:
        project.diags.error(
            "E220",
            "the system project has no PLC project (no <Plc><Project>)",
            Pos(str(path), root.line, root.col),
            "a TwinCAT project without PLC code has nothing softplc runs",
        )
    for el in plc:
        if el.get("PrjFilePath"):
            out.extend(_plc_project(path.parent, el, path, project))
            continue
        xti_name = el.get("File")
        if not xti_name:
            project.diags.error(
                "E220",
                "a <Project> of <Plc> names neither PrjFilePath nor File",
                Pos(str(path), el.line, el.col),
                None,
            )
            continue
        xti = _local(path.parent / "_Config" / "PLC", xti_name)
        if not xti.is_file():
            project.diags.error(
                "E220", f"the PLC project's file _Config/PLC/{xti_name} is not there", Pos(str(path), el.line, el.col)
            )
            continue
        inner = _xml(xti, project)
        if inner is None:
            continue
        found = [p for p in (inner, *inner.walk("Project")) if p.name == "Project" and p.get("PrjFilePath")]
        if not found:
            project.diags.error(
                "E220", "the .xti names no PLC project (PrjFilePath)", Pos(str(xti), inner.line, inner.col)
            )
            continue
        out.extend(_plc_project(xti.parent, found[0], xti, project))
    return out


def _plc_project(base: Path, el: PosElement, where: Path, project: Project) -> list[Path]:
    rel = el.get("PrjFilePath", "")
    target = _local(base, rel)
    if not target.is_file():
        project.diags.error("E220", f"the PLC project {rel} is not there", Pos(str(where), el.line, el.col))
        return []
    return [target]


def _xml(path: Path, project: Project) -> PosElement | None:
    text = read_text(path, project)
    return None if text is None else parse_xml(text, str(path), project.diags)


def read_plcproj(path: Path, project: Project) -> None:
    """A PLC project's sources, libraries and tasks."""
    root = _xml(path, project)
    if root is None:
        return
    if not project.name:  # the first PLC project names the whole, its folder holds the sources
        names = [(n.text or "").strip() for n in root.walk("Name")[:1]]
        project.name = names[0] if names and _IDENT.match(names[0]) else path.stem
        project.root = path.parent
    for item in root.walk("Compile"):
        inc = item.get("Include", "")
        low = inc.lower()
        if not low.endswith((*SOURCE_SUFFIXES, ".tctto")):
            continue  # visualisations, text lists, alarm classes ...: nothing to compile
        target = _local(path.parent, inc)
        if not target.is_file():
            project.diags.error(
                "E221",
                f"the project lists {inc}, which is not there",
                Pos(str(path), item.line, item.col),
                "restore the file, or remove it from the project",
            )
            continue
        if low.endswith(".tctto"):
            task = read_task(target, project)
            if task is not None:
                project.tasks.append(task)
        else:
            project.files.append(str(target))
    for kind in ("PlaceholderReference", "LibraryReference"):
        for ref in root.walk(kind):
            _reference(ref, path, project)


def _reference(ref: PosElement, path: Path, project: Project) -> None:
    """<PlaceholderReference Include="Tc2_System"> or <LibraryReference
    Include="Tc2_System, 3.4.14.0 (Beckhoff Automation GmbH)">, with its
    <Namespace>."""
    name = ref.get("Include", "").split(",")[0].strip()
    if not name:
        return
    ns_el = ref.kid("Namespace")
    namespace = (ns_el.text or "").strip() if ns_el is not None and ns_el.text else name
    project.libraries.append(LibraryRef(name, namespace, Pos(str(path), ref.line, ref.col)))


def read_task(path: Path, project: Project) -> TaskSpec | None:
    """A .TcTTO: ``<Task Name="PlcTask"><CycleTime>10000</CycleTime>
    <Priority>20</Priority><PouCall><Name>MAIN</Name></PouCall>``
    (the cycle time in microseconds)."""
    root = _xml(path, project)
    if root is None:
        return None
    task = root if root.name == "Task" else root.kid("Task")
    here = Pos(str(path), root.line, root.col)
    if task is None:
        project.diags.error("E222", "the task object holds no <Task>", here, None)
        return None
    name = task.get("Name", "") or path.stem
    where = Pos(str(path), task.line, task.col)
    if not _IDENT.match(name):
        project.diags.error("E222", "the task's name is not an identifier", where, "rename the task in TwinCAT")
        return None
    cycle = _number(task, "CycleTime", path, project)
    priority = _number(task, "Priority", path, project)
    if cycle is None or priority is None:
        return None
    if cycle <= 0:
        project.diags.error(
            "E222",
            f"task {name}: a cycle time of {cycle} µs cannot run",
            where,
            "give the task a positive cycle time",
        )
        return None
    programs = []
    for call in task.kids("PouCall"):
        el = call.kid("Name")
        called = (el.text or "").strip() if el is not None else ""
        here_el = el if el is not None else call  # (an element without children is false)
        at = Pos(str(path), here_el.line, here_el.col)
        if not _IDENT.match(called):
            project.diags.error("E222", f"task {name} calls {called[:60]!r}, which is not a PROGRAM name", at, None)
            continue
        programs.append((called, at))
    return TaskSpec(name, cycle * 1000, priority, tuple(programs), where)


def _number(task: PosElement, tag: str, path: Path, project: Project) -> int | None:
    el = task.kid(tag)
    text = (el.text or "").strip() if el is not None else ""
    if text.isdigit() and len(text) <= 12:
        return int(text)
    at = el if el is not None else task
    project.diags.error(
        "E222",
        f"task {task.get('Name', '?')}: <{tag}> is {'missing' if el is None else repr(text[:40])}, not a whole number",
        Pos(str(path), at.line, at.col),
        "TwinCAT writes the cycle time in microseconds and the priority as a whole number",
    )
    return None
