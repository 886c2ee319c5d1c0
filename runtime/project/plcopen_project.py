"""PLCopen XML projects: a CODESYS export names the libraries it uses in
``<data name="http://www.3s-software.com/plcopenxml/libraries">``; a
Beremiz project is a folder with plc.xml, beremiz.xml (which of Beremiz's
own libraries are on) and its extensions, one folder ``name@kind`` each
(Python, C, an HMI, a bus).
"""

from __future__ import annotations

import re
from pathlib import Path

from ..st.ast import Pos
from ..st.importers.plcopen import plcopen_libraries
from ..st.importers.view import LineView
from ..st.importers.xmlsafe import parse_xml
from .model import LibraryRef, Project
from .readtext import read_text

_IDENT = re.compile(r"[A-Za-z_][A-Za-z0-9_]*\Z")
#: what tells a CODESYS export from other PLCopen XML
_CODESYS = re.compile(r'productName="CODESYS|3s-software\.com/plcopenxml', re.I)
_BEREMIZ = re.compile(r'<fileHeader[^>]*companyName="Beremiz"', re.I)
_PLCOPEN = re.compile(r"plcopen\.org/xml/tc6")
#: Beremiz's libraries of POUs (features.py): on unless beremiz.xml says
#: otherwise, SVGHMI when the project has an svghmi extension
BEREMIZ_LIBRARIES = {"Native": True, "Python": True, "SVGHMI": False}


def sniff(text: str) -> str | None:
    """'codesys', 'beremiz' or 'plcopen' for the text of a PLCopen XML
    file (by its first 4 KB), None for other XML."""
    head = text[:4096]
    if not _PLCOPEN.search(head):
        return None
    if _CODESYS.search(head):
        return "codesys"
    if _BEREMIZ.search(head):
        return "beremiz"
    return "plcopen"


def codesys_libraries(text: str, path: str) -> list[LibraryRef]:
    """The libraries a CODESYS export lists (st/importers/plcopen.py reads
    ``<Library Name="#Util" Namespace="Util">`` and its redirections), each
    by its short name (``NETWORK, 1.3.5.3 (OSCAT)`` -> ``NETWORK``), at its
    <Library> element."""
    out: dict[str, LibraryRef] = {}
    for lib in plcopen_libraries(text, path):
        name = lib.name.split(",")[0].strip()
        namespace = lib.namespace if _IDENT.match(lib.namespace) else name
        out.setdefault(name.upper(), LibraryRef(name, namespace, Pos(path, lib.line, lib.col)))
    return list(out.values())


def read_beremiz(folder: Path, project: Project) -> None:
    """A Beremiz folder: plc.xml the sources, beremiz.xml which of Beremiz's
    libraries are on (``<Libraries Enable_Python_Library="false"/>``), and
    the extensions ``name@kind``."""
    project.files.append(str(folder / "plc.xml"))
    for sub in sorted(folder.iterdir()):
        if sub.is_dir() and "@" in sub.name:
            name, _, kind = sub.name.partition("@")
            project.extensions.append((name, kind))
    for name, kind in project.extensions:
        if kind in ("py_ext", "wxglade_hmi"):  # (a wxGlade HMI is a Python file too)
            python_variables(folder / f"{name}@{kind}" / "pyfile.xml", project)
    kinds = {kind for _name, kind in project.extensions}
    enabled = dict(BEREMIZ_LIBRARIES, SVGHMI="svghmi" in kinds)
    config = folder / "beremiz.xml"
    text = read_text(config, project)
    root = parse_xml(text, str(config), project.diags) if text is not None else None
    where = Pos(str(config), 1, 1)
    if root is not None:
        libs = root.kid("Libraries")
        if libs is not None:
            where = Pos(str(config), libs.line, libs.col)
            for lib in enabled:
                value = libs.get(f"Enable_{lib}_Library")
                if value is not None:
                    enabled[lib] = value.strip().lower() == "true"
    project.libraries.extend(LibraryRef(lib, lib, where) for lib, on in enabled.items() if on)


_TYPE = re.compile(r"[A-Za-z_][A-Za-z0-9_]*(?:\s*[\[(]\s*\d{1,5}\s*[\])])?\Z")
# An initial value as ST may take it: a number, TRUE/FALSE, a duration, a string without
# quotes, '$' or line ends inside (nothing that could end the declaration or open a comment).
_INITIAL = re.compile(r"(?:[+-]?\d+(?:\.\d+)?(?:[eE][+-]?\d+)?|TRUE|FALSE|T#[0-9a-zA-Z_.]+|'[^'$\n\r;]*')\Z", re.I)


def python_variables(pyfile: Path, project: Project) -> None:
    """The PLC variables a Beremiz Python extension declares (``<variable
    name="WiiButtons" type="WORD" initial="0"/>`` in its pyfile.xml), which
    the PLC's POUs name as VAR_EXTERNAL: a VAR_GLOBAL block laid on the
    lines of pyfile.xml. The Python code itself does not run in softplc."""
    if not pyfile.is_file():
        return
    text = read_text(pyfile, project)
    root = parse_xml(text, str(pyfile), project.diags) if text is not None else None
    block = root.kid("variables") if root is not None else None
    if block is None or text is None:
        return
    view = LineView(text.count("\n") + 1)
    written = 0
    for var in block.kids("variable"):
        name, type_, initial = var.get("name", ""), var.get("type", "").strip(), var.get("initial")
        ok = _IDENT.match(name) and _TYPE.match(type_) and (initial is None or _INITIAL.match(initial.strip()))
        if not ok:
            project.diags.error(
                "E183",
                f"the extension's variable {name[:40]!r} ({type_[:40]!r}) cannot become an ST declaration",
                Pos(str(pyfile), var.line, var.col),
                "a variable needs an identifier for its name, a type name and a literal initial value",
            )
            continue
        value = f" := {initial.strip()}" if initial is not None else ""
        view.put(var.line, 1, f"{name} : {type_.replace(' ', '')}{value};")
        written += 1
    if written:
        view.put(block.line, 1, "VAR_GLOBAL")
        view.put(block.end_line, 1, "END_VAR")
        project.generated[str(pyfile)] = view.text()
        project.files.append(str(pyfile))
