"""Qualified names: global variable lists (``GVL.x``) and the namespaces of
the CODESYS and TwinCAT standard libraries (``Tc2_Standard.TON``).

A global variable list is the VAR_GLOBAL blocks at the top level of one
file, named by the file (``build_decls.identifier_from_path``: ``GVL.st``
gives ``GVL``), as CODESYS names a GVL object and TwinCAT a ``.TcGVL`` file.
``GVL.x`` is its variable x wherever no variable called GVL is in scope;
``{attribute 'qualified_only'}`` before a block makes the list's variables
reachable only so (E018 for a bare ``x``), as in CODESYS. ``{attribute
'gvl_name' := 'GVL_Main'}`` before a block names its list otherwise than by
the file: a PLCopen XML export holds several named lists in one file
(importers/plcopen.py writes it), and so may any ST file.

``Standard.TON`` (CODESYS) and ``Tc2_Standard.TON`` (TwinCAT) name our
standard blocks and string functions (``STANDARD_LIBRARY``); other vendor
libraries (``Tc2_Utilities``, ``Util``, ``Tc2_System`` ...) are not here, and
a namespace nobody declares is E019 with the known ones in the hint.

The pass runs after the checker has collected POUs and types and before it
declares variables: it rewrites ``GVL.x`` into a ``Name`` qualified by the
list and ``Standard.TON`` into the plain name, in expressions and type
names, so the rest of the compiler sees ordinary names. It reads only the
files where a name before a '.' (``SourceFile.qualified_bases``) is not a
variable of the file, so code without namespaces pays nothing.
"""

from __future__ import annotations

import dataclasses
import re
from typing import Any

from .. import ast as A
from ..syntax.build_decls import identifier_from_path
from ..syntax.pragmas import attribute_value, has_attribute
from .checker_base import CheckerBase

# The CODESYS "Standard" library and TwinCAT's "Tc2_Standard": the IEC
# timers, counters, edge detectors and bistables and the string functions
# (CODESYS Online Help, Standard library; Beckhoff Information System,
# Tc2_Standard), all of which softplc has.
STANDARD_LIBRARY = frozenset(
    ("TON", "TOF", "TP", "LTON", "LTOF", "LTP", "CTU", "CTD", "CTUD", "R_TRIG", "F_TRIG", "SR", "RS")
    + ("CONCAT", "DELETE", "FIND", "INSERT", "LEFT", "LEN", "MID", "REPLACE", "RIGHT")
)
LIBRARY_NAMESPACES = {"STANDARD": "Standard", "TC2_STANDARD": "Tc2_Standard"}
# Vendor libraries softplc does not have (for a precise E019).
OTHER_LIBRARIES = {
    n.upper(): n
    for n in ("Util", "Tc2_Utilities", "Tc2_System", "Tc2_MC2", "Tc2_EtherCAT", "Tc3_Module", "CAA_Types", "SysTime")
}

_IDENTIFIER = re.compile(r"[A-Za-z_][A-Za-z0-9_]*", re.ASCII)
# Fields of AST nodes that never hold a node to rewrite.
_NOT_CHILDREN = frozenset(("pos", "ty", "const", "sym", "pragmas", "qualifier", "flexible"))
_CHILD_FIELDS: dict[type, tuple] = {}


class NamespaceChecks(CheckerBase):
    """The pass over qualified names (see the module docstring)."""

    def _resolve_namespaces(self, files: list) -> None:
        self.list_of: dict[str, str] = {}  # UPPER global -> its list's name
        self.qualified_only: set[str] = set()  # UPPER globals reachable only as List.x
        self._hidden_globals: set[str] = set()
        lists: dict[str, set] = {}  # UPPER list name -> UPPER variable names
        spelled: dict[str, str] = {}
        for sf in files:
            blocks = [b for b in sf.decls if isinstance(b, A.VarBlock) and b.kind == "VAR_GLOBAL"]
            if not blocks:
                continue
            # a library's globals are a list only where it names one (TcUnit's GVL_Param_TcUnit)
            file_list = None if sf.path in self.library_files else identifier_from_path(sf.path)
            for b in blocks:
                name = self._list_name(b) or file_list
                if name is None:
                    continue
                names = lists.setdefault(name.upper(), set())
                spelled.setdefault(name.upper(), name)
                only = has_attribute(b, "qualified_only")
                for d in b.decls:
                    key = d.name.upper()
                    if has_attribute(d, "hide"):
                        self._hidden_globals.add(key)
                    names.add(key)
                    self.list_of.setdefault(key, spelled[name.upper()])
                    if only:
                        self.qualified_only.add(key)
        self._lists, self._list_names = lists, spelled
        self._unqualify_bases(files)
        if not any(sf.qualified_bases for sf in files):
            return
        global_names = set(self.list_of)
        for sf in files:
            local = _declared_names(sf)
            if sf.qualified_bases - local - global_names - set(self.types) - set(self.type_decls):
                _Rewrite(self, global_names).file(sf)

    def _unqualify_bases(self, files: list) -> None:
        """EXTENDS TcUnit.FB_TestSuite, IMPLEMENTS Lib.I_X: the base named in
        a library's namespace is the plain name (E019 when the library has
        none such); another dotted name is left to the checker (E140)."""
        for sf in files:
            for d in sf.decls:
                if not isinstance(d, A.POU):
                    continue
                if d.extends is not None and "." in d.extends[0]:
                    d.extends = (self._unqualified(*d.extends), d.extends[1])
                d.implements = [(self._unqualified(n, p) if "." in n else n, p) for n, p in d.implements]

    def _unqualified(self, name: str, pos: A.Pos) -> str:
        ns, _, rest = name.rpartition(".")
        key = ns.upper()
        if key in self.user_namespaces:
            spelled, names = self.user_namespaces[key]
            if rest.upper() not in names:
                self.d.error(
                    "E019",
                    f"the library {spelled} has no '{rest}'",
                    pos,
                    self._suggest(rest.upper(), sorted(names)) or None,
                )
            return rest
        if key in LIBRARY_NAMESPACES:
            return rest  # (the standard library declares no FUNCTION_BLOCK to extend: E140 says so)
        return name

    def _list_name(self, block: A.VarBlock) -> str | None:
        """The name {attribute 'gvl_name' := 'GVL_Main'} gives a VAR_GLOBAL
        block (a PLCopen XML file holds several named lists), else None."""
        name = attribute_value(block, "gvl_name")
        if name is None:
            return None
        if not _IDENTIFIER.fullmatch(name):
            self.d.error(
                "E019",
                f"{{attribute 'gvl_name' := '{name}'}}: a global variable list is named by an identifier",
                block.pos,
                "the list keeps the name of its file",
            )
            return None
        return name

    def _namespace_hint(self) -> str:
        known = sorted(set(LIBRARY_NAMESPACES.values()) | {s for s, _ in self.user_namespaces.values()})
        known += sorted(self._list_names.values())
        known = list(dict.fromkeys(known))  # Tc2_Standard: the standard names and a shipped library
        return "known namespaces: " + ", ".join(known) if known else ""

    def _check_qualified_only(self, e: A.Name) -> None:
        """E018 for a bare name of a {attribute 'qualified_only'} list's global."""
        key = e.name.upper()
        if e.qualifier is None and key in self.qualified_only:
            gvl = self.list_of[key]
            if gvl == self.initialising_list:
                return  # in an initial value of its own list (CODESYS resolves it there)
            self.d.error(
                "E018",
                f"'{e.name}' belongs to the global variable list {gvl}, which is qualified_only",
                e.pos,
                f"write {gvl}.{e.name} ({{attribute 'qualified_only'}} before its VAR_GLOBAL)",
            )

    def _mark_hidden(self) -> None:
        """{attribute 'hide'} before a declaration: the variable is left out
        of listings (the exec dump, the engine's snapshot), as CODESYS hides
        it from monitoring; a path that names it still reaches it."""
        for pou in self.pous.values():
            for b in pou.node.var_blocks:
                for d in b.decls:
                    sym = pou.vars.get(d.name.upper())
                    if sym is not None and has_attribute(d, "hide"):
                        sym.hidden = True
        for key, sym in self.globals.items():
            if key in self._hidden_globals:
                sym.hidden = True


def _declared_names(sf: A.SourceFile) -> set:
    """UPPER names of the variables the file declares (in POUs and lists)."""
    out: set[str] = set()
    for d in sf.decls:
        blocks = d.var_blocks if isinstance(d, A.POU) else [d] if isinstance(d, A.VarBlock) else []
        for b in blocks:
            out.update(v.name.upper() for v in b.decls)
    return out


class _Rewrite:
    """One walk over a file: qualified names to plain or list-qualified ones."""

    def __init__(self, checker: NamespaceChecks, global_names: set) -> None:
        self.c = checker
        self.global_names = global_names
        self.local: set = set()

    def file(self, sf: A.SourceFile) -> None:
        for d in sf.decls:
            self.local = set()
            if isinstance(d, A.POU):
                self.local = {v.name.upper() for b in d.var_blocks for v in b.decls}
            try:
                self.walk(d)
            except RecursionError:
                pass  # nested too deeply: the checker reports E006 where it is

    def walk(self, node: Any) -> Any:
        """node with its qualified names rewritten (a new node or node itself)."""
        if isinstance(node, A.Member) and isinstance(node.base, A.Member):
            node = self.nested(node)
        if isinstance(node, A.Member) and isinstance(node.base, A.Member):
            node.base = self.walk(node.base)  # TcUnit.GVL_Param_TcUnit.x: the list in a library's namespace
            base = node.base
            if isinstance(base, A.Name) and base.qualifier is None and base.name.upper() in self.c._lists:
                new = self.member(node)
                if new is not None:
                    return new
            return node
        if isinstance(node, A.Member) and isinstance(node.base, A.Name):
            new = self.member(node)
            if new is not None:
                return new
        if isinstance(node, A.NamedType) and "." in node.name:
            self.type_name(node)
            return node
        if type(node) is A.Binary and type(node.left) is A.Binary:
            return self.chain(node)
        for f in self.fields(node):
            value = getattr(node, f)
            new = self.value(value)
            if new is not value:
                setattr(node, f, new)
        return node

    @staticmethod
    def fields(node: Any) -> tuple:
        fields = _CHILD_FIELDS.get(type(node))
        if fields is None:
            fields = tuple(f.name for f in dataclasses.fields(node) if f.name not in _NOT_CHILDREN)
            _CHILD_FIELDS[type(node)] = fields
        return fields

    def chain(self, node: A.Binary) -> A.Binary:
        """A chain a + b + c ... walked from its first operation up, in a
        loop (it may be 10,000 operators long), in the order walk takes."""
        spine = [node]
        while type(spine[-1].left) is A.Binary:
            spine.append(spine[-1].left)
        first = spine[-1]
        first.left = self.walk(first.left)
        for op in reversed(spine):
            for f in self.fields(op):
                if f != "left":
                    value = getattr(op, f)
                    new = self.value(value)
                    if new is not value:
                        setattr(op, f, new)
        return node

    def value(self, value: Any) -> Any:
        if isinstance(value, A.Node):
            return self.walk(value)
        if isinstance(value, list):
            for i, item in enumerate(value):
                new = self.value(item)
                if new is not item:
                    value[i] = new
            return value
        if isinstance(value, tuple):
            items = tuple(self.value(v) for v in value)
            return value if all(a is b for a, b in zip(items, value)) else items
        if isinstance(value, dict):
            for k, v in value.items():
                value[k] = self.value(v)
        return value

    def nested(self, e: A.Member) -> A.Member:
        """``SysFile.SysTypes.RTS_INVALID_HANDLE``, ``SysDir.CmpErrors.Errors.ERR_OK``:
        a name behind several namespaces of the chosen libraries (CODESYS
        reaches a library's own references through it) as behind the last
        one; anything else as it is."""
        parts: list = []
        base: A.Expr = e.base
        while isinstance(base, A.Member):
            parts.append(base.name)
            base = base.base
        if not isinstance(base, A.Name):
            return e
        chain = [base.name, *reversed(parts)]
        first = chain[0].upper()
        if first in self.local or first in self.global_names:
            return e
        if not all(self._namespace(n.upper()) for n in chain):
            return e
        return A.Member(A.Name(chain[-1], pos=base.pos), e.name, pos=e.pos)

    def _namespace(self, ns: str) -> bool:
        return ns in self.c.user_namespaces or ns in LIBRARY_NAMESPACES

    def member(self, e: A.Member) -> A.Expr | None:
        assert isinstance(e.base, A.Name)
        ns = e.base.name.upper()
        if ns in self.local or ns in self.global_names:
            return None  # a variable: ns.x is its member
        key = e.name.upper()
        if ns in self.c._lists and key in self.c._lists[ns]:
            return A.Name(e.name, pos=e.pos, qualifier=self.c._list_names[ns])
        if self._chosen(ns, key):
            return self.user_library(ns, e.name, e.pos)
        if ns in LIBRARY_NAMESPACES:
            return self.library(LIBRARY_NAMESPACES[ns], e.name, e.pos)
        if ns in self.c._lists:
            self.c.d.error(
                "E019",
                f"the global variable list {self.c._list_names[ns]} has no variable '{e.name}'",
                e.pos,
                self.c._suggest(key, sorted(self.c._lists[ns])) or None,
            )
            return A.Name(e.name, pos=e.pos, qualifier=self.c._list_names[ns])
        declared = ns in self.c.types or ns in self.c.type_decls or ns in self.c.pous
        if ns in OTHER_LIBRARIES or (not declared and self._known(key)):
            self.unknown(e.base.name, e.name, e.pos)
            return A.Name(e.name, pos=e.pos)
        return None

    def _chosen(self, ns: str, key: str) -> bool:
        """Whether ns.key names a library the program chose: a user's, or one
        softplc ships (the CODESYS Standard library's CTU, when chosen, before
        the IEC one the namespace Standard names otherwise)."""
        if ns not in self.c.user_namespaces:
            return False
        return ns not in LIBRARY_NAMESPACES or key in self.c.user_namespaces[ns][1]

    def _known(self, key: str) -> bool:
        """A POU, standard function or global variable that a namespace may hold."""
        return key in self.c.pous or key in self.c.std or key in self.global_names

    def library(self, ns: str, name: str, pos: A.Pos) -> A.Name:
        if name.upper() not in STANDARD_LIBRARY:
            self.c.d.error(
                "E019",
                f"'{name}' is not in the {ns} library as softplc has it",
                pos,
                "it holds " + ", ".join(sorted(STANDARD_LIBRARY)),
            )
        return A.Name(name, pos=pos)

    def user_library(self, ns: str, name: str, pos: A.Pos) -> A.Name:
        """OSCAT.DEC_2: a name of one of the user's libraries (program/libraries.py)."""
        spelled, names = self.c.user_namespaces[ns]
        if name.upper() not in names:
            self.c.d.error(
                "E019",
                f"the library {spelled} has no '{name}'",
                pos,
                self.c._suggest(name.upper(), sorted(names)) or None,
            )
        return A.Name(name, pos=pos)

    def unknown(self, ns: str, name: str, pos: A.Pos) -> None:
        # " (Util; add it to libraries = [...])": a library softplc ships, by
        # the namespace written (Util.LEN) or else by the name (X.BLINK);
        # " (Tc3_JsonXml, a library softplc does not have)": the catalogue's
        known = self.c._elsewhere(ns + ".")
        what = OTHER_LIBRARIES.get(ns.upper()) or (known[2:].split(",")[0] if "does not have" in known else None)
        where = known if "add it to" in known else self.c._elsewhere(name)
        if where and "add it to" in where:
            message = f"'{ns}.{name}' is of a library the program did not choose{where}"
        elif what:
            message = f"softplc has no library {what} ('{ns}.{name}')"
        else:
            message = f"unknown namespace '{ns}' in '{ns}.{name}'"
        self.c.d.error("E019", message, pos, self.c._namespace_hint())

    def type_name(self, spec: A.NamedType) -> None:
        *path, name = spec.name.split(".")
        if len(path) > 1 and all(self._namespace(p.upper()) for p in path):
            path = path[-1:]  # SysFile.SysTypes.RTS_IEC_RESULT: as SysTypes.RTS_IEC_RESULT
        ns = ".".join(path)
        if len(path) == 1 and self._chosen(path[0].upper(), name.upper()):
            self.user_library(path[0].upper(), name, spec.pos)
        elif len(path) == 1 and path[0].upper() in LIBRARY_NAMESPACES:
            self.library(LIBRARY_NAMESPACES[path[0].upper()], name, spec.pos)
        else:
            self.unknown(ns, name, spec.pos)
        spec.name = name
