"""PLCopen XML (IEC 61131-10 / TC6 XML, versions 0200 and 0201) read as
Structured Text, as CODESYS V3, TwinCAT 3 and Beremiz write it.

    views = plcopen_views(xml_text, path, diags)    # ST texts to parse
    libs = plcopen_libraries(xml_text)              # the libraries it names

What becomes ST, wherever the file keeps it: data types (``<types>``, and
CODESYS's ``datatype`` data in a resource), POUs (``<types><pous>``, and
the ``pou`` data CODESYS puts in a resource: the application's POUs) with
their actions, methods, properties and inheritance (plcopen_pous.py),
CODESYS's INTERFACEs (``interface`` data), global variable lists (named
ones as such: ``GVL_MQTT.x`` works) and the configurations: resources,
tasks (an IEC ``T#20ms`` or XSD ``PT0.02S`` interval), program instances
(``typeName=""``: the program of the instance's name). The addData rules
are codesys.py's: what softplc does not know is dropped when its
handleUnknown says ``discard`` (CODESYS's device tree) and reported once
(W181) otherwise.

Every piece of ST is written at the line and column of the XML it comes
from (view.LineView), so diagnostics and runtime faults point into the XML
file; a piece that must stand elsewhere (IMPLEMENTS in the header, written
at the end of the interface) keeps its tokens' XML positions (the view's
origins). Three views hold it, each parsed as a file of its own: the main
one (types, POUs, interfaces, lists), the actions (``ACTION Pou.Name:``,
after their POU in ST, before its body in XML) and the configurations
(their resources' tasks at their lines, the program instances at the end of
the resource, so the ST order holds whatever the XML's; the resources'
global variables go to the main view, where they mean the same).

A global variable list with a name gets ``{attribute 'gvl_name' :=
'GVL_MQTT'}`` before its VAR_GLOBAL blocks (namespaces.py names the list by
it, export-st keeps it). CODESYS writes a list as one ``<globalVars>``
holding every variable, with the true CONSTANT/RETAIN blocks in its
``mixedattrsvarlist`` data: each variable gets the qualifiers of its block
there. A definition that comes twice (two applications of one export) is
E184, unless it is the same variable with the same text; a program instance
naming no PROGRAM of the file E185.
"""

from __future__ import annotations

from collections.abc import Callable

from ..ast import Pos
from ..diagnostics import DiagnosticBag
from . import codesys
from .codesys import LibraryRef
from .plcopen_pous import PouReader
from .plcopen_text import duration, ident, integer, pragma
from .plcopen_types import QUALIFIERS, joined, put_at, put_head, put_parts
from .view import LineView
from .xmlsafe import PosElement, parse_xml

__all__ = ["LibraryRef", "plcopen_libraries", "plcopen_views"]

GVL_NAME = "gvl_name"  # the attribute that names a global variable list (namespaces.py)
# What a resource's addData may hold (CODESYS: the application's objects).
_APPLICATION_DATA = ("pou", "datatype", "interface", "globalvars", "libraries")


def _project(text: str, path: str, diags: DiagnosticBag) -> PosElement | None:
    root = parse_xml(text, path, diags)
    if root is None:
        return None
    if root.name != "project":
        diags.error(
            "E180",
            f"not a PLCopen XML project: the root element is <{root.name}>",
            Pos(path, root.line, root.col),
            'PLCopen XML (TC6) files start with <project xmlns="http://www.plcopen.org/xml/tc6_0201">',
        )
        return None
    return root


def plcopen_views(text: str, path: str, diags: DiagnosticBag) -> list[LineView]:
    """The ST views of a PLCopen XML file (laid out on its lines); problems
    become diagnostics at their XML position."""
    root = _project(text, path, diags)
    if root is None:
        return []
    r = _Reader(text, path, diags)
    r.project(root)
    return [v for v in (r.main, r.actions, r.config) if v.used]


def plcopen_libraries(text: str, path: str = "project.xml") -> list[LibraryRef]:
    """The libraries a PLCopen XML file references (CODESYS's libraries
    data, in the project and in each application), each once, in order:
    what the program needs beside its own POUs. [] for a file that does
    not read."""
    root = _project(text, path, DiagnosticBag())
    if root is None:
        return []
    out: list[LibraryRef] = []
    for holder in [root, *_resources(root)]:
        for data in codesys.data_named(holder, "libraries"):
            out.extend(lib for lib in codesys.library_refs(data) if lib not in out)
    return out


def _configurations(root: PosElement) -> list[PosElement]:
    return [c for i in root.kids("instances") for g in i.kids("configurations") for c in g.kids("configuration")]


def _resources(root: PosElement) -> list[PosElement]:
    return [r for c in _configurations(root) for r in c.kids("resource")]


def _qualifiers(block: PosElement) -> tuple:
    return tuple(q for q, attr in QUALIFIERS if block.get(attr, "").strip().lower() in ("true", "1"))


class _Reader(PouReader):
    def __init__(self, text: str, path: str, diags: DiagnosticBag) -> None:
        super().__init__(text, path, diags)
        self.globals: dict[str, tuple[str, int]] = {}  # UPPER global -> (its declaration, line)

    # ------------------------------------------------------------ project

    def project(self, root: PosElement) -> None:
        types = root.kids("types")
        data_types = [dt for t in types for g in t.kids("dataTypes") for dt in g.kids("dataType")]
        pous = [p for t in types for g in t.kids("pous") for p in g.kids("pou")]
        interfaces: list[PosElement] = []
        lists: list[PosElement] = []
        configurations = _configurations(root)
        self.unknown_data(root, _APPLICATION_DATA)
        for header in root.kids("contentHeader"):
            self.unknown_data(header)
        for holder in [root, *_resources(root)]:
            for data in codesys.add_data(holder):
                what = codesys.short_name(data)
                if what == "datatype":
                    data_types += data.kids("dataType")
                elif what == "pou":
                    pous += data.kids("pou")
                elif what == "interface":
                    interfaces += data.kids("Interface")
                elif what == "globalvars":
                    lists += data.kids("globalVars")
        for conf in configurations:
            lists += conf.kids("globalVars")
            lists += [gv for res in conf.kids("resource") for gv in res.kids("globalVars")]
        for dt in data_types:
            self.data_types.setdefault(dt.get("name", "").upper(), dt)
        for pou in pous:
            self.pou_elements.setdefault(pou.get("name", "").upper(), pou)
        # In document order: what shares a line (a file without line breaks)
        # is written after what comes before it.
        items: list[tuple[PosElement, Callable[[PosElement], None]]] = [(dt, self.data_type) for dt in data_types]
        items += [(i, self.interface_decl) for i in interfaces]
        items += [(p, self.pou) for p in pous]
        items += [(gv, self.global_list) for gv in lists]
        for el, read in sorted(items, key=lambda item: (item[0].line, item[0].col)):
            self.guard(read, el)
            if read == self.pou and el.get("name", "").upper() not in self.pou_kinds:
                self.refused.add(el.get("name", "").upper())  # (reported: no cascade at its instances)
        for conf in configurations:
            self.guard(self.configuration, conf)

    # ------------------------------------------------------------ global variables

    def global_list(self, gv: PosElement) -> None:
        """A <globalVars> into the main view: VAR_GLOBAL blocks at its
        variables' lines, named by a pragma when the list has a name."""
        head = self.pragmas(gv)
        if gv.get("name"):
            head += pragma(GVL_NAME, ident(gv.get("name"), gv, "the list name"), gv)
        self.unknown_data(gv, ("attributes", "mixedattrsvarlist"))
        own = _qualifiers(gv)
        quals = {
            v.get("name", "").upper(): _qualifiers(b) for b in codesys.mixed_blocks(gv) for v in b.kids("variable")
        }
        runs: list[tuple[tuple, list]] = []  # (qualifiers, [(variable, declaration parts)])
        for v in gv.kids("variable"):
            parts = self.guard(self.declaration, v)
            q = quals.get(v.get("name", "").upper(), own)
            if parts is None or not self._new_global(v, " ".join(q) + " " + head + joined(parts)):
                continue
            if not runs or runs[-1][0] != q:
                runs.append((q, []))
            runs[-1][1].append((v, parts))
        for i, (q, decls) in enumerate(runs):
            first, last = decls[0][0], decls[-1][0]
            at = gv if i == 0 else first  # (the first block at the list's start tag)
            put_head(self.main, at, head, " ".join(["VAR_GLOBAL", *q]))
            for _, parts in decls:
                put_parts(self.main, parts)
            put_at(self.main, last.end_line, 1, "END_VAR", own_line=True)

    def _new_global(self, v: PosElement, text: str) -> bool:
        """Whether v is a global not declared yet; the same declaration
        again (a second application's copy of a list) is dropped, another
        one is E184."""
        key = v.get("name", "").upper()
        first = self.globals.get(key)
        if first is None:
            self.globals[key] = (text, v.line)
            return True
        if first[0] != text:
            self.problem(
                "E184",
                f"global variable {v.get('name')} is declared twice in the file (line {first[1]}): "
                "this one is left out",
                v,
                "with several applications (CODESYS devices) in one export, export one of them",
            )
        return False

    # ------------------------------------------------------------ configurations

    def configuration(self, conf: PosElement) -> None:
        name = ident(conf.get("name"), conf, "the configuration name")
        self.unknown_data(conf)
        resources = [(res, self.guard(self.resource_text, res)) for res in conf.kids("resource")]
        put_at(self.config, conf.line, conf.col, f"CONFIGURATION {name}", own_line=True)
        for res, parts in resources:
            if parts is None:
                continue
            head, tasks, programs = parts
            put_at(self.config, res.line, res.col, head, 4, own_line=True)
            for task, text in tasks:
                put_at(self.config, task.line, task.col, text, 8, own_line=True)
            for program, inst in programs:  # at the end of the resource, the tokens at the pouInstance
                self.config.put(res.end_line, 1, program, 8, origin=(inst.line, inst.col), own_line=True)
            put_at(self.config, res.end_line, 1, "END_RESOURCE", 4, own_line=True)
        for block in conf.kids("configVars"):
            self.var_block(block, self.config, "VAR_CONFIG")
        for block in conf.kids("accessVars"):
            self.problem("E182", "<accessVars> (VAR_ACCESS) is not imported", block, "softplc has no VAR_ACCESS")
        put_at(self.config, conf.end_line, 1, "END_CONFIGURATION", own_line=True)

    def resource_text(self, res: PosElement) -> tuple[str, list, list]:
        """(RESOURCE line, [(task, TASK line)], [(PROGRAM line, pouInstance)]):
        a task or instance that cannot become ST is reported and left out."""
        name = ident(res.get("name"), res, "the resource name")
        self.unknown_data(res, _APPLICATION_DATA)
        tasks, programs = [], []
        for task in res.kids("task"):
            done = self.guard(self.task_text, task)
            if done is None:
                continue
            tname, text = done
            tasks.append((task, text))
            programs += [(p, i) for i in task.kids("pouInstance") if (p := self.guard(self.instance_text, i, tname))]
        programs += [(p, i) for i in res.kids("pouInstance") if (p := self.guard(self.instance_text, i, None))]
        return f"RESOURCE {name} ON PLC", tasks, programs

    def task_text(self, task: PosElement) -> tuple[str, str]:
        name = ident(task.get("name"), task, "the task name")
        params = []
        if task.get("interval") is not None:
            params.append(f"INTERVAL := {duration(task.get('interval'), task)}")
        if task.get("single"):
            params.append(f"SINGLE := {ident(task.get('single'), task, 'the SINGLE variable')}")
        params.append(f"PRIORITY := {integer(task.get('priority', '0'), task, 'the priority')}")
        self.unknown_data(task)
        return name, f"TASK {name}({', '.join(params)});"

    def instance_text(self, inst: PosElement, task: str | None) -> str | None:
        """PROGRAM name [WITH task] : Type; None when the program was left
        out (reported there) or is no PROGRAM of the file (E185)."""
        name = ident(inst.get("name"), inst, "the instance name")
        type_name = ident(inst.get("typeName") or name, inst, "the program")  # CODESYS: typeName=""
        self.unknown_data(inst)
        key = type_name.upper()
        if key in self.refused:
            return None
        kind = self.pou_kinds.get(key)
        if kind != "PROGRAM":
            self.problem(
                "E185",
                f"the program instance {name} names {type_name}, "
                + (f"a {kind}, not a PROGRAM" if kind else "which is no POU of this file"),
                inst,
                "a task runs PROGRAMs declared in the same file (typeName, or the instance's name)",
            )
            return None
        return f"PROGRAM {name}" + (f" WITH {task}" if task else "") + f" : {type_name};"
