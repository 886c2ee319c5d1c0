"""PLCopen XML (IEC 61131-10 / TC6 XML, versions 0200 and 0201, as CODESYS,
Beremiz and others export it) read as Structured Text.

    views = plcopen_views(xml_text, path, diags)    # ST texts to parse

What becomes ST: data types (structures, enumerations, arrays, subranges,
aliases), POUs with ST bodies (their interface, actions, and the methods
CODESYS puts in its addData), global variable lists and the configuration
(resources, tasks, program instances). A body in another language (FBD, LD,
IL, SFC) is reported by the POU's name (E182) and the POU is left out.

Every piece of ST is written at the line and column of the XML it comes
from (view.LineView): a body at its text, a declaration at its <variable>,
so diagnostics and runtime faults point into the XML file. The actions come
before the body in the XML but after it in ST; they go into a second view
as ``ACTION Pou.Name: ... END_ACTION``, parsed as a file of its own.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from ..ast import Pos
from ..diagnostics import DiagnosticBag
from .bodies import BodyOut, ImportProblem, body_language, supported, translate
from .view import LineView
from .xmlsafe import PosElement, TextPositions, parse_xml

ELEMENTARY = {
    t.lower(): t
    for t in (
        "BOOL SINT INT DINT LINT USINT UINT UDINT ULINT REAL LREAL TIME LTIME DATE LDATE DT LDT TOD LTOD "
        "BYTE WORD DWORD LWORD CHAR WCHAR DATE_AND_TIME TIME_OF_DAY"
    ).split()
}
_SECTIONS = {
    "inputVars": "VAR_INPUT",
    "outputVars": "VAR_OUTPUT",
    "inOutVars": "VAR_IN_OUT",
    "localVars": "VAR",
    "tempVars": "VAR_TEMP",
    "externalVars": "VAR_EXTERNAL",
    "globalVars": "VAR_GLOBAL",
}
_POU_KINDS = {"program": "PROGRAM", "function": "FUNCTION", "functionBlock": "FUNCTION_BLOCK"}
_CODESYS_METHOD = "http://www.3s-software.com/plcopenxml/method"


def plcopen_views(text: str, path: str, diags: DiagnosticBag) -> list[LineView]:
    """The ST views of a PLCopen XML file (one or two, laid out on its
    lines); problems become diagnostics at their XML position."""
    root = parse_xml(text, path, diags)
    if root is None:
        return []
    if root.name != "project":
        diags.error(
            "E180",
            f"not a PLCopen XML project: the root element is <{root.name}>",
            Pos(path, root.line, root.col),
            'PLCopen XML (TC6) files start with <project xmlns="http://www.plcopen.org/xml/tc6_0201">',
        )
        return []
    lines = text.count("\n") + 1
    r = _Reader(text, path, diags, LineView(lines), LineView(lines))
    r.project(root)
    return [v for v in (r.main, r.actions) if v.used]


class _Reader:
    def __init__(self, text: str, path: str, diags: DiagnosticBag, main: LineView, actions: LineView) -> None:
        self.texts = TextPositions(text)
        self.path = path
        self.diags = diags
        self.main = main
        self.actions = actions

    def problem(self, code: str, message: str, el: PosElement | None, hint: str | None = None) -> None:
        line, col = (el.line, el.col) if el is not None else (1, 1)
        self.diags.error(code, message, Pos(self.path, line, col), hint)

    # ------------------------------------------------------------ project

    def project(self, root: PosElement) -> None:
        self.parents = {c: p for p in root.iter() for c in p}
        for dt in root.walk("dataType"):
            self._guard(self.data_type, dt)
        for pou in root.walk("pou"):
            self._guard(self.pou, pou)
        for gv in root.walk("globalVars"):
            if not self._inside(gv, ("interface", "resource", "configuration")):
                self._guard(self.var_block, gv, self.main, "VAR_GLOBAL")
        for conf in root.walk("configuration"):
            self._guard(self.configuration, conf)

    def _guard(self, fn: Callable[..., None], el: PosElement, *args: Any) -> None:
        try:
            fn(el, *args)
        except ImportProblem as exc:
            message, where, hint = exc.args
            self.problem("E183", message, where, hint)

    def _inside(self, el: PosElement, names: tuple) -> bool:
        p = self.parents.get(el)
        while p is not None:
            if p.name in names:  # type: ignore[attr-defined]
                return True
            p = self.parents.get(p)
        return False

    # ------------------------------------------------------------ types

    def type_text(self, t: PosElement | None) -> str:
        """The ST type of a <type> or <baseType> element."""
        if t is None:
            raise ImportProblem("a variable without a type", None, None)
        kids = t.kids()
        if not kids:
            raise ImportProblem(f"<{t.name}> names no type", t, None)
        k = kids[0]
        n = k.name
        if n.lower() in ELEMENTARY:
            return ELEMENTARY[n.lower()]
        if n in ("string", "wstring"):
            length = k.get("length")
            return n.upper() + (f"[{int(length)}]" if length else "")
        if n == "derived":
            return _ident(k.get("name", ""), k)
        if n == "array":
            dims = ", ".join(f"{_int(d.get('lower'), d)}..{_int(d.get('upper'), d)}" for d in k.kids("dimension"))
            return f"ARRAY[{dims}] OF {self.type_text(k.kid('baseType'))}"
        if n == "pointer":
            return f"POINTER TO {self.type_text(k.kid('baseType'))}"
        if n in ("subrangeSigned", "subrangeUnsigned"):
            rng = k.kid("range")
            if rng is None:
                raise ImportProblem("a subrange without <range>", k, None)
            return f"{self.type_text(k.kid('baseType'))}({_int(rng.get('lower'), rng)}..{_int(rng.get('upper'), rng)})"
        if n == "enum":
            values = []
            for v in k.walk("value"):
                name = _ident(v.get("name", ""), v)
                values.append(f"{name} := {_int(v.get('value'), v)}" if v.get("value") is not None else name)
            base = k.kid("baseType")
            return f"({', '.join(values)})" + (f" {self.type_text(base)}" if base is not None and base.kids() else "")
        if n == "struct":
            fields = []
            for v in k.kids("variable"):
                fields.append(f"{_ident(v.get('name', ''), v)} : {self.type_text(v.kid('type'))}{self.init_text(v)};")
            return "STRUCT " + " ".join(fields) + " END_STRUCT"
        raise ImportProblem(f"the type <{n}> is not supported", k, None)

    def init_text(self, v: PosElement) -> str:
        iv = v.kid("initialValue")
        return "" if iv is None else " := " + self.value_text(iv)

    def value_text(self, iv: PosElement) -> str:
        kids = iv.kids()
        if not kids:
            raise ImportProblem("an empty initial value", iv, None)
        k = kids[0]
        if k.name == "simpleValue":
            return _no_newline(k.get("value", ""), k)
        if k.name == "arrayValue":
            items = []
            for v in k.kids("value"):
                rep = v.get("repetitionValue")
                inner = self.value_text(v)
                items.append(f"{_int(rep, v)}({inner})" if rep else inner)
            return "[" + ", ".join(items) + "]"
        if k.name == "structValue":
            items = [f"{_ident(v.get('member', ''), v)} := {self.value_text(v)}" for v in k.kids("value")]
            return "(" + ", ".join(items) + ")"
        raise ImportProblem(f"the initial value <{k.name}> is not supported", k, None)

    def data_type(self, dt: PosElement) -> None:
        name = _ident(dt.get("name", ""), dt)
        self.main.put(dt.line, dt.col, f"TYPE {name} : {self.type_text(dt.kid('baseType'))}{self.init_text(dt)};")
        self.main.put(dt.end_line, 1, "END_TYPE")

    # ------------------------------------------------------------ variables

    def var_block(self, block: PosElement, view: LineView, keyword: str | None = None) -> None:
        kw = keyword or _SECTIONS[block.name]
        quals = [
            q
            for q, attr in (("CONSTANT", "constant"), ("RETAIN", "retain"), ("PERSISTENT", "persistent"))
            if block.get(attr) == "true"
        ]
        view.put(block.line, block.col, " ".join([kw, *quals]))
        for v in block.kids("variable"):
            name = _ident(v.get("name", ""), v)
            at = v.get("address")
            located = f" AT {_no_newline(at, v)}" if at else ""
            view.put(v.line, v.col, f"{name}{located} : {self.type_text(v.kid('type'))}{self.init_text(v)};", 4)
        view.put(block.end_line, 1, "END_VAR")

    def interface(self, itf: PosElement | None, view: LineView) -> None:
        if itf is None:
            return
        for block in itf.kids():
            if block.name in _SECTIONS:
                self.var_block(block, view)

    # ------------------------------------------------------------ POUs

    def pou(self, pou: PosElement) -> None:
        name = _ident(pou.get("name", ""), pou)
        kind = _POU_KINDS.get(pou.get("pouType", ""))
        if kind is None:
            raise ImportProblem(f"POU {name}: unknown pouType {pou.get('pouType')!r}", pou, None)
        body = pou.kid("body")
        lang = body_language(body)
        if not supported(lang):
            self.problem(
                "E182",
                f"POU {name} is written in {lang.name if lang is not None else 'no language'}: "
                "only ST bodies are imported",
                body if body is not None else pou,
                "rewrite it in ST, or export it as ST from the editor; the other POUs are imported",
            )
            return
        assert body is not None and lang is not None
        itf = pou.kid("interface")
        header = f"{kind} {name}"
        if kind == "FUNCTION_BLOCK":
            header += self._inheritance(pou)
        if kind == "FUNCTION":
            rt = itf.kid("returnType") if itf is not None else None
            header += f" : {self.type_text(rt)}" if rt is not None else ""
        self.main.put(pou.line, pou.col, header)
        self.interface(itf, self.main)
        hidden: list[str] = []
        actions = pou.kid("actions")
        if actions is not None:
            for act in actions.kids("action"):
                self.action(name, act, hidden)
        self.body_with_decls(body, lang, name, hidden, pou)
        self.main.put(body.end_line, 1, f"END_{kind}")
        for data in pou.walk("data"):
            if data.get("name") == _CODESYS_METHOD:
                for m in data.kids("Method"):
                    self.method(m)

    def body_with_decls(
        self, body: PosElement, lang: PosElement, pou: str, hidden: list, owner: PosElement | None = None
    ) -> None:
        """A POU's or method's body into the main view, after a VAR block of
        the variables it and hidden (those its actions need) declare. (An
        SFC body writes its POU's named <transitions> before the <body>: the
        VAR block goes before them.)"""
        scratch = LineView(len(self.main.lines))
        out = BodyOut(scratch, self.texts, self.path, self.diags, pou, owner)
        translate(lang, out)
        decls = [*hidden, *(d for d in out.decls if d not in hidden)]
        if decls:
            first = min(scratch.written, default=body.line)
            at = (body.line, body.col) if first >= body.line else (first, 1)
            self.main.put(*at, "VAR " + " ".join(decls) + " END_VAR")
        self.main.absorb(scratch)

    def _inheritance(self, pou: PosElement) -> str:
        """EXTENDS and IMPLEMENTS: CODESYS writes them into the POU's addData
        as <Extends>Base</Extends> and <Implements>I_x</Implements>."""
        out = ""
        add = pou.kid("addData")
        if add is None:
            return out
        extends = [e for e in add.walk("Extends") if not self._inside(e, ("Method",))]
        implements = [e for e in add.walk("Implements") if not self._inside(e, ("Method",))]
        if extends:
            out += f" EXTENDS {_ident((extends[0].text or '').strip(), extends[0])}"
        if implements:
            out += " IMPLEMENTS " + ", ".join(_ident((i.text or "").strip(), i) for i in implements)
        return out

    def action(self, pou_name: str, act: PosElement, hidden: list) -> None:
        """An action of pou_name into the actions view; the variables its
        body needs go to hidden (declared with the POU's)."""
        body = act.kid("body")
        lang = body_language(body)
        name = _ident(act.get("name", ""), act)
        if not supported(lang):
            self.problem(
                "E182",
                f"action {pou_name}.{name} is written in {lang.name if lang is not None else 'no language'}: "
                "only ST bodies are imported",
                act,
                "rewrite it in ST; the rest of the POU is imported",
            )
            return
        assert lang is not None
        self.actions.put(act.line, act.col, f"ACTION {pou_name}.{name}:")
        out = BodyOut(self.actions, self.texts, self.path, self.diags, pou_name)
        translate(lang, out)
        hidden.extend(d for d in out.decls if d not in hidden)
        self.actions.put(act.end_line, 1, "END_ACTION")

    def method(self, m: PosElement) -> None:
        name = _ident(m.get("name", ""), m)
        itf = m.kid("interface")
        rt = itf.kid("returnType") if itf is not None else None
        body = m.kid("body")
        lang = body_language(body)
        if not supported(lang):
            raise ImportProblem(f"method {name} is not written in a language softplc imports", m, None)
        assert body is not None and lang is not None
        self.main.put(m.line, m.col, f"METHOD {name}" + (f" : {self.type_text(rt)}" if rt is not None else ""))
        self.interface(itf, self.main)
        self.body_with_decls(body, lang, name, [])
        self.main.put(m.end_line, 1, "END_METHOD")

    # ------------------------------------------------------------ configuration

    def configuration(self, conf: PosElement) -> None:
        v = self.main
        v.put(conf.line, conf.col, f"CONFIGURATION {_ident(conf.get('name', ''), conf)}")
        for gv in conf.kids("globalVars"):
            self.var_block(gv, v, "VAR_GLOBAL")
        for res in conf.kids("resource"):
            v.put(res.line, res.col, f"RESOURCE {_ident(res.get('name', ''), res)} ON PLC", 4)
            for gv in res.kids("globalVars"):
                self.var_block(gv, v, "VAR_GLOBAL")
            for task in res.kids("task"):
                params = []
                if task.get("interval"):
                    params.append(f"INTERVAL := {_no_newline(task.get('interval', ''), task)}")
                if task.get("single"):
                    params.append(f"SINGLE := {_ident(task.get('single', ''), task)}")
                params.append(f"PRIORITY := {_int(task.get('priority', '0'), task)}")
                tname = _ident(task.get("name", ""), task)
                v.put(task.line, task.col, f"TASK {tname}({', '.join(params)});", 8)
                for inst in task.kids("pouInstance"):
                    iname, tn = _ident(inst.get("name", ""), inst), _ident(inst.get("typeName", ""), inst)
                    v.put(inst.line, inst.col, f"PROGRAM {iname} WITH {tname} : {tn};", 8)
            for inst in res.kids("pouInstance"):
                iname, tn = _ident(inst.get("name", ""), inst), _ident(inst.get("typeName", ""), inst)
                v.put(inst.line, inst.col, f"PROGRAM {iname} : {tn};", 8)
            v.put(res.end_line, 1, "END_RESOURCE", 4)
        v.put(conf.end_line, 1, "END_CONFIGURATION")


def _ident(name: str, el: PosElement | None) -> str:
    """An identifier from an attribute: only what ST allows (no ST is made
    of an attribute that could end a declaration or open a comment)."""
    parts = name.split(".")
    if not name or not all(p.replace("_", "a").isalnum() and p.isascii() and not p[0].isdigit() for p in parts):
        raise ImportProblem(f"{name!r} is not an ST identifier", el, None)
    return name


def _int(value: str | None, el: PosElement | None) -> str:
    v = (value or "").strip()
    if not (v.lstrip("+-").isdigit()):
        raise ImportProblem(f"{value!r} is not an integer", el, None)
    return v


def _no_newline(value: str, el: PosElement | None) -> str:
    """A literal or address attribute: one line, no ';' or comment opener
    that would let it run into the next declaration."""
    if any(bad in value for bad in ("\n", ";", "(*", "*)", "//", "/*", "{")):
        raise ImportProblem(f"{value!r} cannot be an ST value here", el, None)
    return value.strip()
