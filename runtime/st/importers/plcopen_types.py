"""PLCopen XML types, values and declarations as ST (plcopen.py's reader).

A ``<type>`` (``<baseType>``, ``<returnType>``) becomes an ST type: the
elementary ones, ``<string length>`` (a number or a constant expression),
``<derived name>`` (also CODESYS's ``REFERENCE TO X``), ``<array>`` (bounds
that are constant expressions: ``0..ciN``, ``1..GVL.N - 1``), ``<pointer>``,
subranges, enumerations and structures. A ``<dataType>`` becomes ``TYPE
... END_TYPE`` with its attributes as pragmas; a STRUCT that EXTENDS
another (CODESYS datatypeinheritance) becomes ``TYPE B EXTENDS A : STRUCT``. A ``<variable>`` becomes a
declaration at its line: its attributes, address, type, initial value and
the FB_init inputs CODESYS writes as inputassignments (``fb : FB_X(n :=
5);``). Every text is checked first (plcopen_text.py).
"""

from __future__ import annotations

import contextlib
import re
from collections.abc import Callable, Iterator
from typing import Any

from ..ast import Pos
from ..diagnostics import DiagnosticBag
from . import codesys
from .bodies import ImportProblem
from .plcopen_text import address, ident, integer, pragma, st_const, st_value
from .view import LineView
from .xmlsafe import PosElement, TextPositions

ELEMENTARY = {
    t.lower(): t
    for t in (
        "BOOL SINT INT DINT LINT USINT UINT UDINT ULINT REAL LREAL TIME LTIME DATE LDATE DT LDT TOD LTOD "
        "BYTE WORD DWORD LWORD CHAR WCHAR DATE_AND_TIME TIME_OF_DAY"
    ).split()
}
SECTIONS = {
    "inputVars": "VAR_INPUT",
    "outputVars": "VAR_OUTPUT",
    "inOutVars": "VAR_IN_OUT",
    "localVars": "VAR",
    "tempVars": "VAR_TEMP",
    "externalVars": "VAR_EXTERNAL",
    "globalVars": "VAR_GLOBAL",
}
QUALIFIERS = (("CONSTANT", "constant"), ("RETAIN", "retain"), ("NON_RETAIN", "nonretain"), ("PERSISTENT", "persistent"))
MAX_NESTING = 100  # types and values nested deeper are refused (E183)
# CODESYS writes a type TC6 has no element for by its ST name: REFERENCE TO INT.
_REFERENCE = re.compile(r"(REFERENCE\s+TO|POINTER\s+TO|REF_TO)\s+(\S.*)\Z", re.IGNORECASE | re.ASCII)
# A piece of ST: (line, column) it is placed at, its text, and the (line,
# column) of the XML its tokens come from (view.LineView.put's origin): a
# piece placed apart from its XML (an FB_init input before the initial
# value it follows in the XML) keeps its tokens' positions.
Part = tuple[int, int, str, tuple[int, int]]
# Elements of a declaration that are no part of its ST.
_NOT_ST = ("documentation", "addData")


class ReaderBase:
    """The reader's context: the file, where the ST goes, what was read."""

    def __init__(self, text: str, path: str, diags: DiagnosticBag) -> None:
        lines = text.count("\n") + 1
        self.texts = TextPositions(text)
        self.path = path
        self.diags = diags
        self.main = LineView(lines)  # types, POUs, interfaces, global variable lists
        self.actions = LineView(lines)  # ACTION Pou.Name: ... END_ACTION
        self.config = LineView(lines)  # the configurations
        self.data_types: dict[str, PosElement] = {}  # UPPER name -> the <dataType> (STRUCT EXTENDS)
        self.pou_elements: dict[str, PosElement] = {}  # UPPER name -> the <pou> (FB_init inputs)
        self.warned: set[str] = set()  # addData names reported unknown (W181 once each)
        self.defined: dict[str, tuple[str, int]] = {}  # UPPER name -> (what, line): POUs, types, interfaces
        self.depth = 0  # how deep type_text and value_parts are (nested)

    def problem(self, code: str, message: str, el: PosElement | None, hint: str | None = None) -> None:
        line, col = (el.line, el.col) if el is not None else (1, 1)
        self.diags.error(code, message, Pos(self.path, line, col), hint)

    def guard(self, fn: Callable[..., Any], el: PosElement, *args: Any) -> Any:
        """fn(el, *args); an ImportProblem becomes an E183 at its element,
        named in the message (and the element is left out: None)."""
        try:
            return fn(el, *args)
        except ImportProblem as exc:
            message, where, hint = exc.args
            where = where if where is not None else el
            self.problem("E183", f"{describe(where)}: {message}", where, hint)
            return None

    def unknown_data(self, el: PosElement | None, handled: tuple = ()) -> None:
        """W181 for el's addData that softplc does not read and whose
        handleUnknown does not say discard (once per name and file)."""
        for d in codesys.add_data(el):
            name = d.get("name", "")
            if codesys.short_name(d) in handled or not codesys.unknown(d) or name in self.warned:
                continue
            self.warned.add(name)
            self.diags.warning(
                "W181",
                f"<data name={name!r}> is not read by softplc",
                Pos(self.path, d.line, d.col),
                f"handleUnknown={d.get('handleUnknown', 'implementation')!r}: the exporting tool counts it as "
                "part of the program; check that the program does not need it",
            )

    @contextlib.contextmanager
    def nested(self, el: PosElement | None) -> Iterator[None]:
        """One level deeper into a type or value (E183 beyond MAX_NESTING:
        no export nests so deep, and Python's stack has an end)."""
        if self.depth >= MAX_NESTING:
            raise ImportProblem(f"types or values nested more than {MAX_NESTING} deep", el, None)
        self.depth += 1
        try:
            yield
        finally:
            self.depth -= 1

    def once(self, what: str, name: str, el: PosElement) -> bool:
        """Whether name is new in the file (else E184 at el: the second is
        left out; POUs, types and interfaces share ST's one namespace)."""
        first = self.defined.get(name.upper())
        if first is None:
            self.defined[name.upper()] = (what, el.line)
            return True
        self.problem(
            "E184",
            f"{what} {name} is declared twice in the file (a {first[0]} at line {first[1]}): this one is left out",
            el,
            "a PLCopen export holds one definition of each name; with several applications (CODESYS "
            "devices), export one of them, or rename one of the two",
        )
        return False

    def pragmas(self, *holders: PosElement | None) -> str:
        """The CODESYS attributes of the holders' addData as pragmas, each
        followed by a blank ('' if none)."""
        return "".join(pragma(a.get("Name"), a.get("Value"), a) + " " for a in codesys.attributes(*holders))


class TypeReader(ReaderBase):
    """Types, values and declarations."""

    def type_text(self, t: PosElement | None, owner: PosElement | None = None) -> str:
        """The ST type of a <type>, <baseType> or <returnType>."""
        with self.nested(t or owner):
            return self._type_text(t, owner)

    def _type_text(self, t: PosElement | None, owner: PosElement | None) -> str:
        if t is None:
            raise ImportProblem("no type given", owner, None)
        kids = [k for k in t.kids() if k.name not in _NOT_ST]
        if not kids:
            raise ImportProblem(f"<{t.name}> names no type", t, None)
        k = kids[0]
        n = k.name
        if n.lower() in ELEMENTARY:
            return ELEMENTARY[n.lower()]
        if n in ("string", "wstring"):
            length = k.get("length")
            return n.upper() + (f"[{st_const(length, k, 'the string length')}]" if length else "")
        if n == "derived":
            return _derived(k.get("name", ""), k)
        if n == "array":
            dims = k.kids("dimension")
            if not dims:
                raise ImportProblem("an array without <dimension>", k, None)
            ranges = ", ".join(
                f"{st_const(d.get('lower'), d, 'the lower bound')}..{st_const(d.get('upper'), d, 'the upper bound')}"
                for d in dims
            )
            return f"ARRAY[{ranges}] OF {self.type_text(k.kid('baseType'), k)}"
        if n == "pointer":
            return f"POINTER TO {self.type_text(k.kid('baseType'), k)}"
        if n in ("subrangeSigned", "subrangeUnsigned"):
            rng = k.kid("range")
            if rng is None:
                raise ImportProblem("a subrange without <range>", k, None)
            lo, hi = (
                st_const(rng.get("lower"), rng, "the lower bound"),
                st_const(rng.get("upper"), rng, "the upper bound"),
            )
            return f"{self.type_text(k.kid('baseType'), k)}({lo}..{hi})"
        if n == "enum":
            return self.enum_text(k)
        if n == "struct":
            fields = " ".join(joined(self.declaration(v)) for v in k.kids("variable"))
            return f"STRUCT {fields} END_STRUCT"
        raise ImportProblem(f"the type <{n}> is not supported", k, None)

    def enum_text(self, k: PosElement) -> str:
        values = []
        for v in (v for vs in k.kids("values") for v in vs.kids("value")):
            name = ident(v.get("name"), v, "the enumeration value")
            values.append(
                f"{name} := {st_const(v.get('value'), v, 'the value')}" if v.get("value") is not None else name
            )
        if not values:
            raise ImportProblem("an enumeration without values", k, None)
        base = k.kid("baseType")
        return f"({', '.join(values)})" + (f" {self.type_text(base, k)}" if base is not None and base.kids() else "")

    def init_text(self, v: PosElement) -> str:
        return joined(self.init_parts(v))

    def init_parts(self, v: PosElement) -> list[Part]:
        """':= value' of v's <initialValue>, each value at its attribute."""
        iv = v.kid("initialValue")
        if iv is None:
            return []
        parts = self.value_parts(iv)
        return [here(parts[0][0], max(1, parts[0][1] - 3), ":="), *parts]

    def value_parts(self, iv: PosElement) -> list[Part]:
        """An <initialValue> (or a <value> in one) as ST, in parts placed
        where the XML has them (a simpleValue's text at its value)."""
        with self.nested(iv):
            return self._value_parts(iv)

    def _value_parts(self, iv: PosElement) -> list[Part]:
        kids = [k for k in iv.kids() if k.name not in _NOT_ST]
        if not kids:
            raise ImportProblem("an empty initial value", iv, None)
        k = kids[0]
        if k.name == "simpleValue":
            return [here(*self.texts.attribute(k, "value"), st_value(k.get("value"), k, "the initial value"))]
        if k.name not in ("arrayValue", "structValue"):
            raise ImportProblem(f"the initial value <{k.name}> is not supported", k, None)
        parts: list[Part] = [here(k.line, k.col, "[" if k.name == "arrayValue" else "(")]
        for i, v in enumerate(k.kids("value")):
            if i:
                parts.append(here(v.line, v.col, ","))
            if k.name == "structValue":
                parts.append(here(*self.texts.attribute(v, "member"), f"{ident(v.get('member'), v, 'the member')} :="))
                parts += self.value_parts(v)
            elif v.get("repetitionValue"):
                inner = self.value_parts(v)
                parts.append(here(v.line, v.col, f"{integer(v.get('repetitionValue'), v, 'the repetition')}("))
                parts += [*inner, here(inner[-1][0], inner[-1][1], ")")]
            else:
                parts += self.value_parts(v)
        if len(parts) == 1:
            raise ImportProblem(f"an empty <{k.name}>", k, None)
        parts.append(here(k.end_line, 1, "]" if k.name == "arrayValue" else ")"))
        return parts

    def declaration(self, v: PosElement) -> list[Part]:
        """A <variable> as ``name [AT %addr] : type [:= value];`` in parts
        at the XML they come from: its attributes as pragmas before it, the
        name and address at theirs, the type at its element, the FB_init
        inputs after the type (their tokens at the inputassignments), the
        initial value at its values."""
        name = ident(v.get("name"), v, "the variable name")
        pragmas = self.pragmas(v).strip()
        parts: list[Part] = [here(v.line, v.col, pragmas)] if pragmas else []
        parts.append(here(*self.texts.attribute(v, "name"), name))
        if v.get("address") is not None:
            line, col = self.texts.attribute(v, "address")
            parts.append((line, col, f"AT {address(v.get('address'), v)}", (line, max(1, col - 3))))
        t = v.kid("type")
        ty = self.type_text(t, v)
        line, col = self.type_position(t, v)
        inputs = codesys.input_assignments(v)
        derived = t.kid("derived") if t is not None else None
        if inputs and derived is None:
            raise ImportProblem(f"{name}: FB_init inputs for a variable that is no block instance", v, None)
        parts.append((line, col, f": {ty}" + ("(" if inputs else ""), (line, max(1, col - 2))))
        if inputs and derived is not None:
            parts += self._fb_init_parts(derived.get("name", ""), inputs, line, col)
        self.unknown_data(v, ("inputassignments", "attributes"))
        parts += self.init_parts(v)
        return [*parts, here(parts[-1][0], parts[-1][1], ";")]

    def type_position(self, t: PosElement | None, owner: PosElement) -> tuple[int, int]:
        """Where a type's name is in the XML: a derived type's name
        attribute, else its element."""
        kids = [k for k in t.kids() if k.name not in _NOT_ST] if t is not None else []
        if not kids:
            return (t.line, t.col) if t is not None else (owner.line, owner.col)
        if kids[0].name == "derived":
            return self.texts.attribute(kids[0], "name")
        return kids[0].line, kids[0].col

    def _fb_init_parts(self, fb: str, inputs: list, line: int, col: int) -> list[Part]:
        """name := value, ...) of the FB_init inputs, placed after the type
        and its '(' at (line, col), each token at its <Name> and <Value>. One CODESYS
        writes without its name (a positional input) is named after the
        FB_init inputs of the block (of this file) after bInitRetains and
        bInCopyCode."""
        declared: list[str] | None = None
        parts: list[Part] = []
        for i, (el, name_el, value_el) in enumerate(inputs):
            arg = (name_el.text or "") if name_el is not None else ""
            if not arg.strip():
                if declared is None:
                    declared = self._fb_init_inputs(fb, [])
                if i >= len(declared):
                    raise ImportProblem(
                        f"FB_init input {i + 1} of {fb} has no name, and {fb}'s FB_init in this file "
                        f"declares {len(declared)} input(s) after bInitRetains and bInCopyCode",
                        el,
                        None,
                    )
                arg = declared[i]
            value = (value_el.text or "") if value_el is not None else ""
            where = self.texts.start(name_el) if name_el is not None else (el.line, el.col)
            at = self.texts.start(value_el) if value_el is not None else (el.line, el.col)
            if i:
                parts.append((line, col, ",", at))
            parts.append((line, col, f"{ident(arg, el, 'the FB_init input')} :=", where))
            parts.append((line, col, st_value(value, value_el or el, "the FB_init value"), at))
        return [*parts, (line, col, ")", parts[-1][3])]

    def _fb_init_inputs(self, fb: str, seen: list) -> list[str]:
        """The inputs of fb's FB_init after the two BOOLs (its base's when it
        has none of its own)."""
        pou = self.pou_elements.get(fb.upper())
        if pou is None or fb.upper() in seen or len(seen) > MAX_NESTING:
            return []
        for data in codesys.data_named(pou, "method"):
            for m in data.kids("Method"):
                if m.get("name", "").upper() == "FB_INIT":
                    itf = m.kid("interface")
                    blocks = itf.kids("inputVars") if itf is not None else []
                    return [v.get("name", "") for b in blocks for v in b.kids("variable")][2:]
        extends, _ = codesys.inheritance(pou.kid("interface"), pou)
        return self._fb_init_inputs((extends[0].text or "").strip(), [*seen, fb.upper()]) if extends else []

    def var_block(self, block: PosElement, view: LineView, keyword: str | None = None, head: str = "") -> None:
        """A block of variables (an interface's section, a global list) at
        its lines; a variable that cannot become ST is reported and left out."""
        quals = [q for q, attr in QUALIFIERS if block.get(attr, "").strip().lower() in ("true", "1")]
        put_at(view, block.line, block.col, head + " ".join([keyword or SECTIONS[block.name], *quals]), own_line=True)
        for v in block.kids("variable"):
            parts = self.guard(self.declaration, v)
            if parts is not None:
                put_parts(view, parts)
        put_at(view, block.end_line, 1, "END_VAR", own_line=True)

    # ------------------------------------------------------------ data types

    def data_type(self, dt: PosElement) -> None:
        """TYPE name : ... END_TYPE at the <dataType>'s lines."""
        name = ident(dt.get("name"), dt, "the data type name")
        if not self.once("data type", name, dt):
            return
        base = dt.kid("baseType")
        kids = [k for k in base.kids() if k.name not in _NOT_ST] if base is not None else []
        if any(True for _ in codesys.data_named(dt, "union")):
            raise ImportProblem(f"data type {name} is a UNION: softplc has no UNION", dt, "use a STRUCT")
        pragmas, head = self.pragmas(dt), f"TYPE {name} :"
        self.unknown_data(dt, ("attributes", "datatypeinheritance", "union"))
        if kids and kids[0].name == "struct":
            extends = self._struct_base(dt, [name.upper()])
            if extends is not None:
                head = f"TYPE {name} EXTENDS {extends} :"
            fields = [self.guard(self.declaration, v) for v in kids[0].kids("variable")]
            put_head(self.main, dt, pragmas, head + " STRUCT")
            for parts in fields:
                if parts is not None:
                    put_parts(self.main, parts)
            put_at(self.main, kids[0].end_line, 1, "END_STRUCT;", own_line=True)
        else:
            init = self.init_text(dt)
            put_head(self.main, dt, pragmas, f"{head} {self.type_text(base, dt)}{' ' + init if init else ''};")
        put_at(self.main, dt.end_line, 1, "END_TYPE", own_line=True)

    def _struct_base(self, dt: PosElement, seen: list) -> str | None:
        """The STRUCT a data type EXTENDS (CODESYS datatypeinheritance), its
        chain checked through the file's types for a cycle."""
        extends, _ = codesys.inheritance(dt)
        if not extends:
            return None
        base_name = ident((extends[0].text or "").strip(), extends[0], "the base type")
        if base_name.upper() in seen or len(seen) > MAX_NESTING:
            raise ImportProblem(f"STRUCT {dt.get('name')} EXTENDS itself (through {base_name})", extends[0], None)
        base = self.data_types.get(base_name.upper())
        if base is not None:  # (a base of a library is the checker's)
            self._struct_base(base, [*seen, base_name.upper()])
        return base_name


def describe(el: PosElement) -> str:
    """An element as a message names it: <variable name='speed'>."""
    name = el.get("name") or el.get("Name")
    if name is None:
        return f"<{el.name}>"
    shown = name if len(name) <= 40 else name[:37] + "..."
    return f"<{el.name} name={shown!r}>"


def here(line: int, col: int, text: str) -> Part:
    """A piece placed where its XML is."""
    return line, col, text, (line, col)


def joined(parts: list[Part]) -> str:
    """The parts of a declaration or value as one text."""
    out = ""
    for part in parts:
        text = part[2]
        out += text if not out or out.endswith(("(", "[")) or text.startswith((")", "]", ",", ";")) else " " + text
    return out


def placed(view: LineView, line: int, col: int) -> tuple[int, int]:
    """Where view.put(line, col, ...) places a text (after what the line
    holds): as an origin, its tokens keep their place. A text after a
    pragma must: the parser attaches a pragma to what follows it."""
    cur = view.lines.get(line, "")
    return line, max(col, len(cur) + 2 if cur else col)


def put_at(view: LineView, line: int, col: int, text: str, indent: int = 0, *, own_line: bool = False) -> None:
    """view.put, the tokens' positions those of the place it lands (not
    those of a text on the line before it that comes from elsewhere)."""
    view.put(line, col, text, indent, origin=placed(view, line, col), own_line=own_line)


def put_parts(view: LineView, parts: list[Part], indent: int = 4) -> None:
    """A declaration's parts at their places: in plain(), its pragmas on
    lines of their own, then the declaration on one line."""
    head = True
    after_pragma = False
    before = ""
    for line, col, text, origin in parts:
        if after_pragma:
            origin = placed(view, line, col)
        tight = before.endswith(("(", "[")) or text.startswith((")", "]", ",", ";"))
        view.put(line, col, text, indent, origin=origin, sep="" if tight else " ", join=not head, own_line=head)
        head = after_pragma = text.startswith("{")
        before = text


def put_head(view: LineView, el: PosElement, pragmas: str, pieces: str | list, indent: int = 0) -> None:
    """A header (TYPE, a POU's, METHOD ...) at el, after its pragmas; in
    plain() each on a line of its own. pieces: the header's text, or
    [(text, origin (line, column) of its tokens)]."""
    if isinstance(pieces, str):
        pieces = [(pieces, (el.line, el.col))]
    if pragmas:
        view.put(el.line, el.col, pragmas.strip(), indent, origin=placed(view, el.line, el.col), own_line=True)
    for i, (text, origin) in enumerate(pieces):
        if i == 0 and pragmas:
            origin = placed(view, el.line, el.col)
        view.put(el.line, el.col, text, indent, origin=origin, own_line=i == 0)


def _derived(name: str, el: PosElement) -> str:
    """A <derived name>: a (dotted) type name, or REFERENCE TO / POINTER TO
    one as CODESYS writes them."""
    name = " ".join(name.split())
    m = _REFERENCE.match(name)
    if m:
        return f"{m.group(1).upper()} {_derived(m.group(2), el)}"
    if name.lower() in ELEMENTARY:
        return ELEMENTARY[name.lower()]
    return ident(name, el, "the type")
