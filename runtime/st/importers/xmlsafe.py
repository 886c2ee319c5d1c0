"""Reading an XML file safely, with the position of every element.

defusedxml refuses what could make the parse itself the attack: entity
expansion (billion laughs), external entities and DTDs (PLCopen and TwinCAT
exports have none). Every element gets ``line`` and ``col`` (one-based, of
its start tag) and ``end_line`` (of its end tag) from expat.
"""

from __future__ import annotations

import bisect
import re
import xml.etree.ElementTree as ET
from typing import Any

from defusedxml import DefusedXmlException
from defusedxml.ElementTree import DefusedXMLParser

from ..ast import Pos
from ..diagnostics import DiagnosticBag

_REFUSED = {
    "DTDForbidden": "it has a DTD (<!DOCTYPE ...>)",
    "EntitiesForbidden": "it declares entities (<!ENTITY ...>)",
    "ExternalReferenceForbidden": "it refers to an external entity",
}


class PosElement(ET.Element):
    line = 0
    col = 0
    end_line = 0

    @property
    def name(self) -> str:
        """The tag without its namespace."""
        return self.tag.rsplit("}", 1)[-1]

    def kids(self, name: str | None = None) -> list[PosElement]:
        """The child elements (named name, namespace ignored)."""
        return [c for c in self if isinstance(c, PosElement) and (name is None or c.name == name)]

    def kid(self, name: str) -> PosElement | None:
        found = self.kids(name)
        return found[0] if found else None

    def walk(self, name: str) -> list[PosElement]:
        """Every descendant named name, in document order."""
        return [e for e in self.iter() if isinstance(e, PosElement) and e.name == name and e is not self]


# A line end as expat counts one (XML 1.0 2.11): CR LF, a lone CR (an old
# Mac editor's, met mixed with CR LF in real Beremiz projects) or LF.
_LINE_END = re.compile(r"\r\n?|\n")


class TextPositions:
    """Where an element's text starts in the XML file it was read from."""

    def __init__(self, raw: str) -> None:
        self.raw = raw
        self.line_starts = [0] + [m.end() for m in _LINE_END.finditer(raw)]

    def start(self, el: PosElement) -> tuple[int, int]:
        """(line, column) of el's text: after its start tag and <![CDATA[.
        Entities (&lt;) shift the columns of their own line only."""
        off = self.line_starts[el.line - 1] + el.col - 1
        off = self.raw.find(">", off) + 1
        if self.raw.startswith("<![CDATA[", off):
            off += len("<![CDATA[")
        line = bisect.bisect_right(self.line_starts, off)
        return line, off - self.line_starts[line - 1] + 1

    def attribute(self, el: PosElement, name: str) -> tuple[int, int]:
        """(line, column) of the value of el's attribute name (in its start
        tag), else of el itself. Entities shift the columns of their line."""
        off = self.line_starts[el.line - 1] + el.col - 1
        end = self.raw.find(">", off)
        m = re.compile(rf"\s{re.escape(name)}\s*=\s*[\"']").search(self.raw, off, end if end >= 0 else len(self.raw))
        if m is None:
            return el.line, el.col
        line = bisect.bisect_right(self.line_starts, m.end())
        return line, m.end() - self.line_starts[line - 1] + 1


class _Builder(ET.TreeBuilder):
    def __init__(self) -> None:
        super().__init__(element_factory=PosElement)
        self.expat: Any = None  # the parser's expat object, read during its callbacks

    def start(self, tag: Any, attrs: Any) -> Any:
        el = super().start(tag, attrs)
        el.line, el.col = self.expat.CurrentLineNumber, self.expat.CurrentColumnNumber + 1  # type: ignore[attr-defined]
        return el

    def end(self, tag: Any) -> Any:
        el = super().end(tag)
        el.end_line = self.expat.CurrentLineNumber  # type: ignore[attr-defined]
        return el


def parse_xml(text: str, path: str, diags: DiagnosticBag) -> PosElement | None:
    """The root element of text; None when it is not well-formed (E180) or
    refused (E181), reported at its position."""
    builder = _Builder()
    parser = DefusedXMLParser(target=builder, forbid_dtd=True, forbid_entities=True, forbid_external=True)
    builder.expat = parser.parser
    try:
        parser.feed(text)
        root = parser.close()
    except DefusedXmlException as exc:
        diags.error(
            "E181",
            f"refused XML: {_REFUSED.get(type(exc).__name__, type(exc).__name__)}",
            Pos(path, builder.expat.CurrentLineNumber, 1),
            "a DTD, entity declarations and external entities are not accepted (PLCopen and TwinCAT exports have none)",
        )
        return None
    except ET.ParseError as exc:
        line, col = exc.position
        diags.error("E180", f"not well-formed XML: {exc.msg if hasattr(exc, 'msg') else exc}", Pos(path, line, col + 1))
        return None
    assert isinstance(root, PosElement)  # (the element factory)
    return root
