"""The ``addData`` conventions of CODESYS V3 (and TwinCAT 3, which exports
PLCopen XML the same way) in a PLCopen XML file.

TC6 0201 lets a tool add data to most elements as ``<addData><data
name="URI" handleUnknown="...">``: ``discard`` (a reader that does not know
the name drops it), ``preserve`` or ``implementation`` (it is part of the
program). What softplc reads, by the last part of the name
(``http://www.3s-software.com/plcopenxml/<name>``):

* ``pouinheritance`` (``<Inheritance><Extends>``, ``<Implements>``) of a
  POU (in its ``<interface>``'s addData or its own) and of an interface,
  ``datatypeinheritance`` (STRUCT EXTENDS) of a data type;
* ``interface`` (an INTERFACE with its methods and properties), ``pou``
  and ``datatype`` (CODESYS puts an application's POUs and DUTs in its
  resource's addData), ``globalvars`` (a named global variable list);
* ``method``, ``property`` (Get/Set accessors), ``accessmodifiers``
  (PRIVATE, PROTECTED, INTERNAL, PUBLIC, ABSTRACT, FINAL);
* ``attributes`` (``{attribute '...'}`` pragmas), ``inputassignments``
  (the FB_init inputs of an instance), ``mixedattrsvarlist`` (the
  CONSTANT/RETAIN blocks of a global variable list);
* ``libraries``: the library references (``plcopen.plcopen_libraries``).

Known and left aside on purpose: object ids, the project structure
(folders), documentation, task settings (the task's own attributes hold
its interval and priority), SFC settings, the plain-text interface (the
structured one is read), build properties, project information. Any other
name is dropped when its handleUnknown says ``discard`` and reported once
(W181) otherwise: the tool says it is part of the program and softplc does
not read it.
"""

from __future__ import annotations

from collections.abc import Iterator
from typing import NamedTuple

from .xmlsafe import PosElement

# The addData names softplc knows and leaves aside on purpose.
IGNORED = frozenset(
    (
        "objectid",
        "projectstructure",
        "projectinformation",
        "documentation",
        "enumvaluedocumentation",
        "tasksettings",
        "sfcsettings",
        "interfaceasplaintext",
        "buildproperties",
        "textdeclaration",
    )
)
_MODIFIERS = ("PUBLIC", "PRIVATE", "PROTECTED", "INTERNAL", "ABSTRACT", "FINAL")


def short_name(data: PosElement) -> str:
    """The last part of a data element's name, lower-cased:
    'http://www.3s-software.com/plcopenxml/method' -> 'method'."""
    return data.get("name", "").rstrip("/").rsplit("/", 1)[-1].lower()


def add_data(el: PosElement | None) -> list[PosElement]:
    """The <data> elements of el's own <addData>."""
    if el is None:
        return []
    return [d for a in el.kids("addData") for d in a.kids("data")]


def data_named(el: PosElement | None, name: str) -> Iterator[PosElement]:
    """el's <data> elements of that short name."""
    return (d for d in add_data(el) if short_name(d) == name)


def unknown(data: PosElement) -> bool:
    """Whether data unknown here must be reported (its handleUnknown does
    not say discard, and it is not one left aside on purpose)."""
    return data.get("handleUnknown", "implementation") != "discard" and short_name(data) not in IGNORED


def inheritance(*holders: PosElement | None) -> tuple[list, list]:
    """([Extends elements], [Implements elements]) of the pouinheritance,
    datatypeinheritance or an <Inheritance> of the holders' addData."""
    extends: list = []
    implements: list = []
    for h in holders:
        for d in add_data(h):
            if short_name(d) in ("pouinheritance", "datatypeinheritance"):
                for inh in d.kids("Inheritance"):
                    extends += inh.kids("Extends")
                    implements += inh.kids("Implements")
    return extends, implements


def modifiers(*holders: PosElement | None) -> list[str]:
    """ABSTRACT, FINAL, PRIVATE ... of the accessmodifiers data (each an
    attribute set to true: <AccessModifiers Private="true" />), in the
    order ST writes them."""
    found: set = set()
    for h in holders:
        for d in data_named(h, "accessmodifiers"):
            for am in d.kids("AccessModifiers"):
                found.update(k.upper() for k, v in am.attrib.items() if v.strip().lower() == "true")
    return [m for m in _MODIFIERS if m in found]


def attributes(*holders: PosElement | None) -> list[PosElement]:
    """The <Attribute Name Value> elements of the holders' attributes data."""
    return [a for h in holders for d in data_named(h, "attributes") for b in d.kids("Attributes") for a in b.kids()]


def input_assignments(var: PosElement) -> list[tuple[PosElement, PosElement | None, PosElement | None]]:
    """(<InputAssignment>, its <Name> or None, its <Value> or None) of a
    variable's FB_init inputs: <InputAssignment><Name>n</Name><Value>5</Value>
    (CODESYS leaves the Name out of a positional input)."""
    return [
        (a, a.kid("Name"), a.kid("Value"))
        for d in data_named(var, "inputassignments")
        for group in d.kids("InputAssignments")
        for a in group.kids("InputAssignment")
    ]


def mixed_blocks(gv: PosElement) -> list[PosElement]:
    """The per-qualifier <globalVars> of a list's mixedattrsvarlist (CODESYS
    writes one list holding every variable, and the true blocks there)."""
    return [g for d in data_named(gv, "mixedattrsvarlist") for m in d.kids("MixedAttrsVarList") for g in m.kids()]


class LibraryRef(NamedTuple):
    """A library the project references: its name (the redirected one for
    a placeholder: 'MQTT, 1.2.0.6 (Stefan Dreyer)'), its namespace
    ('MQTT'), the placeholder it was named by ('' if none) and the line and
    column of its <Library> element (not compared)."""

    name: str
    namespace: str
    placeholder: str
    line: int = 0
    col: int = 0

    def __eq__(self, other: object) -> bool:
        return isinstance(other, LibraryRef) and self[:3] == other[:3]

    def __hash__(self) -> int:
        return hash(self[:3])


def library_refs(data: PosElement) -> list[LibraryRef]:
    """The libraries of one libraries data: <Library Name="#MQTT"
    Namespace="MQTT"> (a '#' name is a placeholder, resolved by the
    PlaceholderRedirections)."""
    out: list[LibraryRef] = []
    for libs in data.kids("Libraries"):
        redirect = {
            r.get("Placeholder", ""): r.get("Redirection", "")
            for group in libs.kids("PlaceholderRedirections")
            for r in group.kids("PlaceholderRedirection")
        }
        for lib in libs.kids("Library"):
            name = lib.get("Name", "").strip()
            placeholder = name[1:] if name.startswith("#") else ""
            if placeholder:
                name = redirect.get(placeholder, "") or placeholder
            if name:
                out.append(LibraryRef(name, lib.get("Namespace", "").strip(), placeholder, lib.line, lib.col))
    return out
