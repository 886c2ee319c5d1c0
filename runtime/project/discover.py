"""Which projects the paths a command is given stand for.

A TwinCAT ``.sln``, ``.tsproj`` or ``.plcproj`` is one project per PLC
project in it; a PLCopen XML file is a project of its own (a CODESYS export
with the libraries it lists); a folder holding ``plc.xml`` and
``beremiz.xml`` is a Beremiz project. Any other folder is searched: its
solutions, system and PLC projects and Beremiz folders are projects, and
the sources outside them (``.st``, PLCopen XML, TwinCAT files) one more,
"folder". Files named one by one (ST, TwinCAT files) are compiled with the
project given beside them, or form a project of their own, "files".
"""

from __future__ import annotations

import os
from pathlib import Path

from ..st.importers import is_source
from .model import Project
from .readtext import read_text

# The PLCopen and TwinCAT readers (plcopen_project.py, twincat.py and the
# importers they use) are imported by the functions that read such a
# project: checking or running a file of plain ST does not load them.

# Folders a project has that hold no sources of its own.
SKIPPED = {".git", "__pycache__", ".venv", "venv", "node_modules", "_Boot", "_CompileInfo", "_Libraries", "build"}
TWINCAT_SUFFIXES = (".sln", ".tsproj", ".tspproj", ".plcproj")


def is_project_file(path: str) -> bool:
    return path.lower().endswith(TWINCAT_SUFFIXES)


def open_projects(paths: list) -> list[Project]:
    """The projects of paths (files and folders), in the order given."""
    projects: list[Project] = []
    loose: list[str] = []
    for raw in paths:
        p = Path(raw)
        if p.is_dir():
            projects.extend(_folder(p))
        elif is_project_file(str(p)):
            projects.extend(_twincat(p, p.parent))
        elif p.suffix.lower() == ".xml":
            projects.append(_xml_file(p))
        else:
            loose.append(str(p))
    if loose:
        if projects:
            projects[0].files.extend(loose)  # compiled with the project beside them
        else:
            first = Path(loose[0])
            projects.append(Project("files", first.stem, first.parent, first, files=loose))
    return projects


def _twincat(path: Path, root: Path) -> list[Project]:
    """One project per PLC project of a .sln, .tsproj or .plcproj."""
    from .twincat import plc_projects, read_plcproj

    holder = Project("twincat", "", root, path)
    found = plc_projects(path, holder)
    if not found:
        holder.name = path.stem
        return [holder]  # its problems (E220) are the whole of it
    out = []
    for i, plcproj in enumerate(found):
        project = Project("twincat", "", root, path) if i else holder
        read_plcproj(plcproj, project)
        out.append(project)
    return out


def _xml_file(path: Path) -> Project:
    """A PLCopen XML file: plc.xml beside a beremiz.xml is that Beremiz
    project; a CODESYS export brings the libraries it lists."""
    from .plcopen_project import codesys_libraries, sniff

    if path.name.lower() == "plc.xml" and (path.parent / "beremiz.xml").is_file():
        return _beremiz(path.parent)
    project = Project("plcopen", path.stem, path.parent, path, files=[str(path)])
    text = read_text(path, project)
    kind = sniff(text) if text is not None else None
    if kind in ("codesys", "beremiz"):
        project.kind = kind
    if kind == "codesys" and text is not None:
        project.libraries.extend(codesys_libraries(text, str(path)))
    project.texts.pop(str(path), None)  # a source: compiled from the file itself
    return project


def _beremiz(folder: Path) -> Project:
    from .plcopen_project import read_beremiz

    project = Project("beremiz", folder.name, folder, folder)
    read_beremiz(folder, project)
    return project


def _walk(root: Path):
    """(folder, file names) under root, without the folders of SKIPPED and
    hidden ones, in sorted order."""
    for here, dirs, files in os.walk(root):
        dirs[:] = sorted(d for d in dirs if d not in SKIPPED and not d.startswith("."))
        yield Path(here), sorted(files)


def _folder(root: Path) -> list[Project]:
    from .twincat import names_twincat, plc_projects, read_plcproj

    if (root / "plc.xml").is_file() and (root / "beremiz.xml").is_file():
        return [_beremiz(root)]
    solutions, systems, plcs, beremiz, sources = [], [], [], [], []
    for here, files in _walk(root):
        names = {f.lower() for f in files}
        if "plc.xml" in names and "beremiz.xml" in names:
            beremiz.append(here)
        for f in files:
            low = f.lower()
            if low.endswith(".sln"):
                if names_twincat(here / f):  # (not a C# solution beside the PLC code)
                    solutions.append(here / f)
            elif low.endswith((".tsproj", ".tspproj")):
                systems.append(here / f)
            elif low.endswith(".plcproj"):
                plcs.append(here / f)
            elif is_source(f):
                sources.append(here / f)
    projects: list[Project] = []
    taken: set = set()  # the project files read already (absolute)
    homes: list[Path] = list(beremiz)  # the folders of the projects found
    for path in solutions + systems + plcs:
        if _key(path) in taken:
            continue
        holder = Project("twincat", "", root, path)
        found = [p for p in plc_projects(path, holder) if _key(p) not in taken]
        taken.update(map(_key, found))
        taken.update(map(_key, _systems_of(path, holder)))
        homes.extend(p.parent for p in found)
        if not found:
            if holder.diags.items:
                holder.name = path.stem
                projects.append(holder)
            continue
        for i, plcproj in enumerate(found):
            project = Project("twincat", "", root, path) if i else holder
            read_plcproj(plcproj, project)
            projects.append(project)
    projects.extend(_beremiz(b) for b in beremiz)
    home_keys = [Path(_key(h)) for h in homes]
    rest = [
        str(f) for f in sources if not any(Path(_key(f)).is_relative_to(h) for h in home_keys) and _is_plain_source(f)
    ]
    if rest:
        projects.append(Project("folder", root.name, root, root, files=rest))
    return projects


def _key(path: Path) -> str:
    return os.path.abspath(path)


def _systems_of(path: Path, holder: Project) -> list[Path]:
    """The .tsproj files a solution names (so that they are not read twice)."""
    if path.suffix.lower() != ".sln":
        return []
    text = holder.texts.get(str(path), "")
    out = []
    for line in text.splitlines():
        if line.startswith("Project(") and ".tsproj" in line.lower():
            parts = line.split('"')
            if len(parts) > 5:
                out.append(Path(os.path.normpath(path.parent / parts[5].replace("\\", "/"))))
    return out


def _is_plain_source(path: Path) -> bool:
    """A source of a folder: ST, TwinCAT files, and XML only when it is
    PLCopen XML (a folder holds other XML: configuration, HMI, build files)."""
    from .plcopen_project import sniff

    if path.suffix.lower() != ".xml":
        return True
    try:
        with open(path, "rb") as f:
            head = f.read(4096).decode("utf-8", errors="replace")
    except OSError:
        return True  # reported when it is read
    return sniff(head) is not None
