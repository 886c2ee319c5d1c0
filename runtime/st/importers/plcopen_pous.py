"""PLCopen XML POUs as ST (plcopen.py's reader): programs, functions and
function blocks with their actions, and what CODESYS adds to them in
``addData`` (codesys.py): EXTENDS/IMPLEMENTS, methods, properties with
Get/Set accessors, access modifiers and attributes; and CODESYS's
INTERFACEs.

A POU goes into the main view: its header at the ``<pou>``, its variables
at theirs, its body where the body is (bodies.translate: the body's
language, ST or one another module registers), ``END_...`` at the end of
the body, then its methods and properties at their lines (the grammar
attaches a METHOD or PROPERTY after ``END_FUNCTION_BLOCK`` to that block,
as TwinCAT's text export writes them). Actions go into the actions view
as ``ACTION Pou.Name: ... END_ACTION``. Each part computes its text before
it writes any, so a part that cannot become ST (E183) is left out whole
and leaves no half-written ST behind.
"""

from __future__ import annotations

from . import codesys
from .bodies import BodyOut, ImportProblem, body_language, supported, translate
from .plcopen_text import ident
from .plcopen_types import SECTIONS, TypeReader, describe, put_at, put_head
from .view import LineView
from .xmlsafe import PosElement

POU_KINDS = {"program": "PROGRAM", "function": "FUNCTION", "functionBlock": "FUNCTION_BLOCK"}
_MEMBER_DATA = ("method", "property")
_POU_DATA = ("pouinheritance", "attributes", "accessmodifiers")
Piece = tuple[str, tuple[int, int]]  # a header's text and the (line, column) of the XML it comes from


class PouReader(TypeReader):
    """POUs, their members, interfaces."""

    def __init__(self, text: str, path: str, diags) -> None:
        super().__init__(text, path, diags)
        self.pou_kinds: dict[str, str] = {}  # UPPER POU name -> PROGRAM, FUNCTION, FUNCTION_BLOCK
        self.refused: set[str] = set()  # UPPER names of POUs reported and left out

    # ------------------------------------------------------------ POUs

    def pou(self, pou: PosElement) -> None:
        name = ident(pou.get("name"), pou, "the POU name")
        kind = POU_KINDS.get(pou.get("pouType", ""))
        if kind is None:
            raise ImportProblem(f"POU {name}: unknown pouType {pou.get('pouType')!r}", pou, None)
        body = pou.kid("body")
        lang = body_language(body)
        if body is not None and not supported(lang):
            self.refused.add(name.upper())
            self.problem(
                "E182",
                f"POU {name} is written in {lang.name if lang is not None else 'no language'}: "
                "only ST bodies are imported",
                body,
                "rewrite it in ST, or export it as ST from the editor; the other POUs are imported",
            )
            return
        itf = pou.kid("interface")
        pragmas = self.pragmas(itf, pou)
        header = self.heading(pou, " ".join([kind, *codesys.modifiers(itf, pou)]), name)
        if kind != "FUNCTION":
            header += self.inheritance(itf, pou)
        else:
            header += self.return_type(itf, pou)
        if not self.once("POU", name, pou):
            return
        self.pou_kinds[name.upper()] = kind
        self.unknown_data(itf, _POU_DATA)
        self.unknown_data(pou, _MEMBER_DATA + _POU_DATA)
        put_head(self.main, pou, pragmas, header)
        self.interface_vars(itf, self.main)
        hidden: list[str] = []
        actions = pou.kid("actions")
        if actions is not None:
            for act in actions.kids("action"):
                self.guard(lambda a: self.action(name, a, hidden), act)
        if body is not None and lang is not None:
            self.body_with_decls(body, lang, name, hidden, pou)
            end = body.end_line
        else:  # no <body>: an empty one
            end = pou.end_line
            if hidden:
                put_at(self.main, end, 1, "VAR " + " ".join(hidden) + " END_VAR", own_line=True)
        put_at(self.main, end, 1, f"END_{kind}", own_line=True)
        for data in codesys.add_data(pou):
            what = codesys.short_name(data)
            for m in data.kids("Method" if what == "method" else "Property" if what == "property" else "-"):
                if kind == "FUNCTION":
                    self.problem("E183", f"FUNCTION {name} cannot have a {m.name.lower()}", m)
                    continue
                self.guard(self.method if m.name == "Method" else self.property, m, name)

    def heading(self, el: PosElement, keywords: str, name: str) -> list[Piece]:
        """[keywords at el, the name at its attribute]: a header's pieces."""
        return [(keywords, (el.line, el.col)), (name, self.texts.attribute(el, "name"))]

    def return_type(self, itf: PosElement | None, owner: PosElement) -> list[Piece]:
        """[': TYPE' at its element] of an interface's <returnType>, or []."""
        rt = itf.kid("returnType") if itf is not None else None
        if rt is None:
            return []
        line, col = self.type_position(rt, owner)
        return [(f": {self.type_text(rt, owner)}", (line, max(1, col - 2)))]

    def inheritance(self, *holders: PosElement | None, keyword: str = "IMPLEMENTS") -> list[Piece]:
        """EXTENDS Base IMPLEMENTS I_a, I_b (CODESYS's pouinheritance), each
        name at its text; an INTERFACE (keyword EXTENDS) takes every
        Extends as a base."""
        extends, implements = codesys.inheritance(*holders)
        if keyword == "EXTENDS":
            extends, implements = [], extends
        out: list[Piece] = []
        if extends:
            e = extends[0]
            out += [("EXTENDS", (e.line, e.col)), *self.names(e, "the base")[:1]]
        names = [n for el in implements for n in self.names(el, "the interface")]
        if names:
            out.append((keyword, (implements[0].line, implements[0].col)))
            for k, n in enumerate(names):
                out += [(",", n[1]), n] if k else [n]
        return out

    def names(self, el: PosElement, what: str) -> list[Piece]:
        """The names of an element's text ('I_a, I_b'), each at its place."""
        line, col = self.texts.start(el)
        text = el.text or ""
        out: list[Piece] = []
        offset = 0
        for part in text.split(","):
            if part.strip():
                lead = len(part) - len(part.lstrip())
                at = (line, col + offset + lead) if "\n" not in text[: offset + lead] else (el.line, el.col)
                out.append((ident(part.strip(), el, what), at))
            offset += len(part) + 1
        return out

    def interface_vars(self, itf: PosElement | None, view: LineView) -> None:
        """The variable sections of an <interface>, at their lines."""
        if itf is None:
            return
        for block in itf.kids():
            if block.name in SECTIONS:
                self.var_block(block, view)
            elif block.name not in ("returnType", "documentation", "addData"):
                self.problem(
                    "E182", f"<{block.name}> is not imported", block, "softplc reads the TC6 variable sections"
                )

    def body_with_decls(
        self, body: PosElement, lang: PosElement, pou: str, hidden: list, owner: PosElement | None = None
    ) -> None:
        """A POU's, method's or accessor's body into the main view, after a
        VAR block of the variables it and hidden (those its actions need)
        declare (an SFC body writes its POU's named <transitions> before the
        <body>: the VAR block goes before them). owner: the element whose
        body it is. A body that cannot become ST is reported and left empty."""
        scratch = LineView(0)
        out = BodyOut(scratch, self.texts, self.path, self.diags, pou, owner)
        try:
            translate(lang, out)
        except ImportProblem as exc:
            message, where, hint = exc.args
            where = where if where is not None else body
            self.problem("E183", f"{describe(where)}: {message}", where, hint)
            out.decls.clear()
            scratch = LineView(0)
        decls = [*hidden, *(d for d in out.decls if d not in hidden)]
        if decls:
            first = min(scratch.written, default=body.line)
            line, col = (body.line, body.col) if first >= body.line else (first, 1)
            put_at(self.main, line, col, "VAR " + " ".join(decls) + " END_VAR", own_line=True)
        self.main.absorb(scratch, own_line=True)

    def action(self, pou_name: str, act: PosElement, hidden: list) -> None:
        """An action of pou_name into the actions view; the variables its
        body needs go to hidden (declared with the POU's)."""
        body = act.kid("body")
        lang = body_language(body)
        name = ident(act.get("name"), act, "the action name")
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
        self.unknown_data(act)
        scratch = LineView(0)
        out = BodyOut(scratch, self.texts, self.path, self.diags, pou_name)
        translate(lang, out)  # (an ImportProblem leaves the action out: guard)
        put_at(self.actions, act.line, act.col, f"ACTION {pou_name}.{name}:", own_line=True)
        self.actions.absorb(scratch, own_line=True)
        hidden.extend(d for d in out.decls if d not in hidden)
        put_at(self.actions, act.end_line, 1, "END_ACTION", own_line=True)

    # ------------------------------------------------------------ members

    def method(self, m: PosElement, owner: str, signature_only: bool = False) -> None:
        """METHOD [modifiers] name [: type], its variables and body; in an
        INTERFACE the signature only."""
        name = ident(m.get("name"), m, "the method name")
        itf = m.kid("interface")
        body = None if signature_only else m.kid("body")
        lang = body_language(body)
        if body is not None and not supported(lang):
            self.problem(
                "E182",
                f"method {owner}.{name} is written in {lang.name if lang is not None else 'no language'}: "
                "only ST bodies are imported",
                body,
                "rewrite it in ST; the rest of the POU is imported",
            )
            return
        pragmas = self.pragmas(itf, m)
        head = self.heading(m, " ".join(["METHOD", *codesys.modifiers(itf, m)]), name) + self.return_type(itf, m)
        self.unknown_data(itf, _POU_DATA)
        self.unknown_data(m, _POU_DATA)
        put_head(self.main, m, pragmas, head)
        self.interface_vars(itf, self.main)
        if body is not None and lang is not None:
            self.body_with_decls(body, lang, f"{owner}.{name}", [], m)
        put_at(self.main, m.end_line, 1, "END_METHOD", own_line=True)

    def property(self, p: PosElement, owner: str, signature_only: bool = False) -> None:
        """PROPERTY [modifiers] name : type with its GET and SET accessors
        (CODESYS's GetAccessor and SetAccessor, in the order written)."""
        name = ident(p.get("name"), p, "the property name")
        itf = p.kid("interface")
        rt = itf.kid("returnType") if itf is not None else None
        if rt is None:
            raise ImportProblem(f"property {owner}.{name} has no type (<returnType>)", p, None)
        pragmas = self.pragmas(itf, p)
        head = self.heading(p, " ".join(["PROPERTY", *codesys.modifiers(itf, p)]), name) + self.return_type(itf, p)
        self.unknown_data(itf, _POU_DATA)
        self.unknown_data(p, _POU_DATA)
        put_head(self.main, p, pragmas, head)
        for acc in p.kids():
            kw = {"GetAccessor": "GET", "SetAccessor": "SET", "Get": "GET", "Set": "SET"}.get(acc.name)
            if kw is None:
                continue
            body = None if signature_only else acc.kid("body")
            lang = body_language(body)
            if body is not None and not supported(lang):
                self.problem("E182", f"the {kw} accessor of {owner}.{name} is not written in ST", body)
                body = None
            acc_itf = acc.kid("interface")
            self.unknown_data(acc_itf, _POU_DATA)
            self.unknown_data(acc, _POU_DATA)
            put_head(self.main, acc, self.pragmas(acc_itf, acc), kw)
            self.interface_vars(acc_itf, self.main)
            if body is not None and lang is not None:
                self.body_with_decls(body, lang, f"{owner}.{name}", [])
            put_at(self.main, acc.end_line, 1, f"END_{kw}", own_line=True)
        put_at(self.main, p.end_line, 1, "END_PROPERTY", own_line=True)

    def interface_decl(self, itf: PosElement) -> None:
        """A CODESYS INTERFACE (<Interface name> in the interface data):
        its methods' and properties' signatures."""
        name = ident(itf.get("name"), itf, "the interface name")
        pragmas = self.pragmas(itf)
        head = self.heading(itf, "INTERFACE", name) + self.inheritance(itf, keyword="EXTENDS")
        if not self.once("INTERFACE", name, itf):
            return
        self.unknown_data(itf, ("pouinheritance", "attributes", "property", "method"))
        put_head(self.main, itf, pragmas, head)
        members = [k for group in itf.kids() if group.name in ("Methods", "Properties") for k in group.kids()]
        members += [k for d in codesys.add_data(itf) if codesys.short_name(d) in _MEMBER_DATA for k in d.kids()]
        for k in sorted(members, key=lambda e: (e.line, e.col)):
            if k.name == "Method":
                self.guard(self.method, k, name, True)
            elif k.name == "Property":
                self.guard(self.property, k, name, True)
        put_at(self.main, itf.end_line, 1, "END_INTERFACE", own_line=True)
