"""Mutations of imported files (PLCopen XML, TwinCAT's .TcPOU/.TcDUT/.TcGVL/
.TcIO) for the importers' fuzz tests (test_importers.py).

The corpus is the exports the importer tests keep, written in the style of
each tool (CODESYS V3, Beremiz, TwinCAT): tests/st/importers. A mutant is
one of them with a few structural mutations, made on the element tree and
written back as XML:

  * an element dropped, duplicated, moved into another parent, or swapped
    with a sibling (the order the schema gives no longer holds);
  * an element renamed (to another name the formats use, or a stranger);
  * an attribute dropped or edited a few characters, or its value or an
    element's text made hostile:
    empty, blanks, ST that would end a declaration, comment and pragma
    openers, quotes, huge or negative numbers, durations that are none,
    control characters, unicode, very long;

and then, sometimes, the text itself cut short, changed byte-wise, put on
one line, or given CRLF line ends. `mutants(files)` draws (file name,
{file name: text}) with the mutant among its intact project neighbours.
"""

from __future__ import annotations

import xml.etree.ElementTree as ET
from pathlib import Path

from hypothesis import strategies as st

IMPORTERS = Path(__file__).resolve().parents[1] / "st" / "importers"
SUFFIXES = (".xml", ".tcpou", ".tcdut", ".tcgvl", ".tcio")


def _projects() -> list[dict[str, str]]:
    """Each project of the corpus: {file name: text}. A TwinCAT project is
    its folder's files; a PLCopen export is one file."""
    out: list[dict[str, str]] = []
    twincat: dict[Path, dict[str, str]] = {}
    for path in sorted(IMPORTERS.rglob("*")):
        if not path.is_file() or path.suffix.lower() not in SUFFIXES:
            continue
        rel = path.relative_to(IMPORTERS)
        if path.suffix.lower() == ".xml":
            out.append({str(rel): path.read_text(encoding="utf-8")})
        else:
            twincat.setdefault(IMPORTERS / rel.parts[0], {})[str(rel)] = path.read_text(encoding="utf-8")
    return out + list(twincat.values())


PROJECTS = _projects()

# What the formats name elements (renaming one to another is a mutation).
TAGS = (
    "project types dataTypes dataType baseType pous pou interface inputVars outputVars inOutVars localVars "
    "tempVars externalVars globalVars variable type derived string array dimension struct enum values value "
    "pointer subrangeSigned range initialValue simpleValue arrayValue structValue returnType body ST FBD LD "
    "SFC IL actions action transitions instances configurations configuration resource task pouInstance "
    "addData data Method Property GetAccessor SetAccessor Interface Methods Inheritance Extends Implements "
    "Attributes Attribute InputAssignments InputAssignment Name Value MixedAttrsVarList Libraries Library "
    "POU Declaration Implementation DUT GVL Itf Get Set Action TcPlcObject xhtml p accessVars configVars "
    "documentation Unknown_Thing"
).split()
HOSTILE = [
    "",
    " ",
    "\t\n",
    "x",
    "1",
    "-1",
    "0",
    "99999999999999999999999999",
    "2147483648",
    "1.5",
    "1e999",
    "T#",
    "T#1s",
    "PT",
    "P",
    "PT0.5S",
    "P1Y2M",
    "PT1H2M3.5S",
    "-PT1S",
    "PT0.0000000001S",
    "'",
    "''",
    "'abc",
    "x; END_VAR VAR y : INT",
    "END_VAR",
    "END_PROGRAM PROGRAM evil",
    "(*",
    "*)",
    "//",
    "/*",
    "{",
    "}",
    "{attribute 'x'}",
    "$",
    "a.b",
    "a..b",
    ".a",
    "a.",
    "GVL.N - 1",
    "(1",
    "1)",
    "[1, 2",
    "%IX0.0",
    "%",
    "%IX99999999999999999",
    "REFERENCE TO",
    "REFERENCE TO INT",
    "POINTER TO POINTER TO x",
    "ARRAY[1..2] OF INT",
    "STRING(10)",
    "http://www.3s-software.com/plcopenxml/method",
    "http://www.3s-software.com/plcopenxml/pou",
    "http://www.3s-software.com/plcopenxml/interface",
    "http://www.3s-software.com/plcopenxml/globalvars",
    "http://www.3s-software.com/plcopenxml/property",
    "http://www.3s-software.com/plcopenxml/inputassignments",
    "http://www.3s-software.com/plcopenxml/pouinheritance",
    "configurations",
    "discard",
    "implementation",
    "program",
    "function",
    "functionBlock",
    "true",
    "false",
    "\x00\x01",
    "\u202e\u00e9\u4e2d",
    "a" * 5000,
    "9" * 400,
]
_NAME_POOL = ["name", "typeName", "value", "interval", "priority", "length", "lower", "upper", "address", "pouType"]


def _serialize(root: ET.Element) -> str:
    return ET.tostring(root, encoding="unicode")


def _mutate_tree(draw, root: ET.Element) -> None:
    elems = list(root.iter())
    parents = {c: p for p in root.iter() for c in p}
    el = elems[draw(st.integers(0, len(elems) - 1))]
    parent = parents.get(el)
    how = draw(
        st.sampled_from(
            [
                "drop",
                "duplicate",
                "move",
                "swap",
                "rename",
                "drop attribute",
                "attribute",
                "text",
                "new attribute",
                "edit",
            ]
        )
    )
    if how in ("drop", "duplicate", "move", "swap") and parent is None:
        how = "text"
    if how == "drop":
        assert parent is not None
        parent.remove(el)
    elif how == "duplicate":
        assert parent is not None
        parent.insert(list(parent).index(el), _copy(el))
    elif how == "move":
        assert parent is not None
        target = elems[draw(st.integers(0, len(elems) - 1))]
        if target is not el and el not in target.iter():
            parent.remove(el)
            target.insert(draw(st.integers(0, len(target))), el)
    elif how == "swap":
        assert parent is not None
        siblings = list(parent)
        j = draw(st.integers(0, len(siblings) - 1))
        i = siblings.index(el)
        siblings[i], siblings[j] = siblings[j], siblings[i]
        parent[:] = siblings
    elif how == "rename":
        ns = el.tag[: el.tag.index("}") + 1] if el.tag.startswith("{") else ""
        el.tag = ns + draw(st.sampled_from(TAGS))
    elif how == "drop attribute" and el.attrib:
        del el.attrib[draw(st.sampled_from(sorted(el.attrib)))]
    elif how in ("attribute", "drop attribute") and el.attrib:
        el.set(draw(st.sampled_from(sorted(el.attrib))), _xml_safe(draw(st.sampled_from(HOSTILE))))
    elif how == "edit" and el.attrib:  # a few characters of a value changed
        key = draw(st.sampled_from(sorted(el.attrib)))
        value = el.attrib[key]
        i = draw(st.integers(0, len(value)))
        cut = draw(st.integers(0, 3))
        el.set(key, _xml_safe(value[:i] + draw(st.text(min_size=0, max_size=3)) + value[i + cut :]))
    elif how == "new attribute":
        el.set(draw(st.sampled_from(_NAME_POOL)), _xml_safe(draw(st.sampled_from(HOSTILE))))
    else:
        el.text = _xml_safe(draw(st.sampled_from(HOSTILE)))


def _copy(el: ET.Element) -> ET.Element:
    return ET.fromstring(ET.tostring(el))


def _xml_safe(text: str) -> str:
    """text without the characters XML 1.0 cannot hold at all."""
    return "".join(c for c in text if c in "\t\n\r" or c >= " ")


@st.composite
def mutants(draw, projects: list | None = None):
    """(the mutated file's name, {file name: text} of its project)."""
    project = dict(draw(st.sampled_from(projects or PROJECTS)))
    name = draw(st.sampled_from(sorted(project)))
    text = project[name]
    try:
        root = ET.fromstring(text.encode("utf-8"))
    except ET.ParseError:
        root = None
    if root is not None:
        for _ in range(draw(st.integers(1, 4))):
            _mutate_tree(draw, root)
        text = _serialize(root)
    finish = draw(st.sampled_from(["as is", "as is", "as is", "truncate", "bytes", "one line", "crlf"]))
    if finish == "truncate":
        text = text[: draw(st.integers(0, len(text)))]
    elif finish == "bytes":
        i = draw(st.integers(0, len(text)))
        text = text[:i] + draw(st.text(min_size=0, max_size=4)) + text[i + draw(st.integers(0, 4)) :]
    elif finish == "one line":
        text = " ".join(text.split("\n"))
    elif finish == "crlf":
        text = text.replace("\n", "\r\n")
    project[name] = text
    return name, project
