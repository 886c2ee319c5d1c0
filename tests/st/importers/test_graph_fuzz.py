"""Mutated FBD and LD networks (the XML files of test_fbd.py and test_ld.py
with attributes dropped or changed, elements deleted or doubled, hostile
expressions) through `softplc check`'s entry: coded diagnostics or a clean
result, never a traceback and never an internal error (E009)."""

from __future__ import annotations

import xml.etree.ElementTree as ET
from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from softplc.runtime.program import check_files

HERE = Path(__file__).parent
FILES = ["fbd_beremiz.xml", "ld_beremiz.xml", "fbd_codesys.xml"]
ATTRIBUTES = [
    "localId",
    "refLocalId",
    "formalParameter",
    "typeName",
    "instanceName",
    "executionOrderId",
    "negated",
    "edge",
    "storage",
    "label",
    "name",
    "x",
    "y",
]
VALUES = ["", "0", "1", "-1", "14", "20", "22", "99", "a b", "x;y", "IN", "OUT", "Q", "ENO", "EN", "rising"]
VALUES += ["falling", "set", "reset", "true", "TON", "ADD", "Net", "Main", "over", "c", "1e9", "ß"]
TEXTS = ["", "a", "1", "t1.Q", "a; b := 1", "(* x", "x // y", "{attr}", "IF a THEN", "'str;'", "((a)", "a)", "END_IF"]
TEXTS += ["a\nb", "x]", "JMP over", "T#1s", "-", "NOT", "ADD(1, 2)", "a := 1", "over:"]

ET.register_namespace("", "http://www.plcopen.org/xml/tc6_0201")
ET.register_namespace("xhtml", "http://www.w3.org/1999/xhtml")


def _body_elements(root: ET.Element) -> list:
    bodies = [e for e in root.iter() if e.tag.rsplit("}", 1)[-1] in ("FBD", "LD")]
    return [e for b in bodies for e in b.iter() if e is not b]


@st.composite
def mutants(draw) -> str:
    name = draw(st.sampled_from(FILES))
    root = ET.fromstring((HERE / name).read_text())
    parents = {c: p for p in root.iter() for c in p}
    for _ in range(draw(st.integers(1, 4))):
        elements = _body_elements(root)
        el = draw(st.sampled_from(elements))
        op = draw(st.sampled_from(["drop", "set", "delete", "double", "text"]))
        if op == "drop" and el.attrib:
            el.attrib.pop(draw(st.sampled_from(sorted(el.attrib))))
        elif op == "set":
            el.set(draw(st.sampled_from(ATTRIBUTES)), draw(st.sampled_from(VALUES)))
        elif op == "delete" and el in parents:
            parents[el].remove(el)
        elif op == "double" and el in parents:
            parents[el].append(ET.fromstring(ET.tostring(el)))
            parents = {c: p for p in root.iter() for c in p}
        elif op == "text":
            el.text = draw(st.sampled_from(TEXTS))
    return ET.tostring(root, encoding="unicode")


@pytest.mark.filterwarnings("ignore")
@settings(max_examples=300, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(mutants())
def test_a_mutated_network_gives_coded_diagnostics_never_a_traceback(xml):
    diags, _ = check_files([], texts={"mutant.xml": xml})
    internal = [d.format() for d in diags if d.code == "E009"]
    assert not internal, "\n".join(internal)
    for d in diags:
        assert d.pos.line >= 1 and d.pos.col >= 1
