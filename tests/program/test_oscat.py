"""OSCAT BASIC 3.33 compiled whole, and the worked examples of its function
reference run on it with their documented results.

OSCAT's sources are not in the repository: the tests take them from the
environment, and skip without them.

  SOFTPLC_OSCAT          OSCAT BASIC 3.33 as ported to Beremiz/OpenPLC
                         (github.com/wonka929/OSCAT_OpenPLC): a folder of
                         Beremiz projects, one per chapter of the manual,
                         each compiled by matiec -> profile matiec
  SOFTPLC_OSCAT_CODESYS  OSCAT BASIC 3.33 as CODESYS 2.3 exports it
                         (OSCAT_BASIC_333.TXT in the Eclipse OSCAT libraries
                         archive, OSCAT_BASIC_LIB/ARCHIVE/rel333), or a folder
                         of .EXP files -> profile codesys

The examples are oscat/documented_examples.toml: each is run as a PROGRAM
of its own compiled with the corpus, for one cycle. Checking uses the
project analysis `softplc check` prints (runtime/project), so a POU that
does not compile is named, and the rest still runs.
"""

from __future__ import annotations

import os
import re
import tomllib
from pathlib import Path

import pytest

from softplc.runtime.project.analysis import analyse
from softplc.runtime.project.discover import open_projects
from softplc.runtime.project.model import Project

HERE = Path(__file__).parent / "oscat"
EXAMPLES = tomllib.loads((HERE / "documented_examples.toml").read_text(encoding="utf-8"))["example"]
PORT = os.environ.get("SOFTPLC_OSCAT")
EXPORT = os.environ.get("SOFTPLC_OSCAT_CODESYS")
NO_PORT = "set SOFTPLC_OSCAT to the folder of OSCAT BASIC 3.33 ported to Beremiz (github.com/wonka929/OSCAT_OpenPLC)"
NO_EXPORT = "set SOFTPLC_OSCAT_CODESYS to OSCAT_BASIC_333.TXT (CODESYS 2.3 export of OSCAT BASIC 3.33) or its folder"

# Two chapters of the port matiec never compiled (their build/ folder holds
# no C): each error softplc gives there is one matiec gives too.
#   String Functions: BYTE_TO_STRH calls BYTE_TO_STRING(IN, '%02X') (a
#     printf format: the function takes one input) and initialises a STRING
#     with the number 2;
#   Buffer Management: _BUFFER_CLEAR calls MEMSET, which matiec does not have.
PORT_NOT_MATIEC = {
    "String Functions": [("E020", "initial value of 'temp'"), ("E041", "BYTE_TO_STRING takes 1 argument")],
    "Buffer Management": [("E043", "unknown function 'MEMSET'")],
}
PORT_NOT_COMPILED = {"String Functions": ["BYTE_TO_STRH"], "Buffer Management": ["_BUFFER_CLEAR"]}
# POUs of the port's XML that become no ST, as with matiec: SHR_8UDE's
# body ends in '(*From OSCAT Library, www.oscat.de *' (edited after the
# port's build/), a comment that, not nesting, runs to TOGGLE's first '*)'.
PORT_LOST = {"Latches Flipflop and Shift Registers": ["STORE_8", "TOGGLE"]}
# The POUs of the CODESYS 2.3 export that do not compile under codesys, and
# why (what CODESYS 2.3 took that CODESYS V3, and softplc's codesys, do not):
EXPORT_NOT_COMPILED = {
    "_BUFFER_CLEAR": "a POINTER stored into a DWORD and compared with one (32-bit CODESYS 2.3)",
    "_BUFFER_INIT": "the same",
    "BYTE_TO_RANGE": "REAL arithmetic with a BYTE operand",
    "SCALE_B2": "the same",
    "SCALE_B4": "the same",
    "SCALE_B8": "the same",
    "FIFO_16": "an array bound naming a VAR CONSTANT declared after it",
    "FIFO_32": "the same",
    "STACK_16": "the same",
    "STACK_32": "the same",
    "LTIME_TO_UTC": "a variable named LTIME (an ed.3 type name CODESYS V3 reserves)",
    "RTC_2": "a variable named LDT (the same)",
}


def _port_projects() -> list[Path]:
    root = Path(PORT or ".")
    found = [p.parent for p in root.rglob("plc.xml") if (p.parent / "beremiz.xml").is_file()]
    return sorted(p for p in found if "build" not in p.parts)


def _chapter(folder: Path) -> str:
    return re.sub(r"^OSCAT BASIC [\d.]+-\s*\d+\s*", "", folder.name)


def _params(items: list, reason: str) -> list:
    return items if items else [pytest.param(None, marks=pytest.mark.skip(reason=reason))]


PORT_PROJECTS = _port_projects() if PORT else []


# ---------------------------------------------------------------- the whole corpus


@pytest.mark.parametrize("folder", _params(PORT_PROJECTS, NO_PORT), ids=lambda p: p.name if p else "no corpus")
def test_every_chapter_of_the_port_compiles_under_matiec(folder):
    [project] = open_projects([str(folder)])
    a = analyse(project, "matiec")
    assert not any(d.code == "E009" for d in a.diagnostics)
    got = sorted((d.code, d.message) for d in a.errors)
    expected = PORT_NOT_MATIEC.get(_chapter(folder), [])
    assert [code for code, _ in got] == sorted(code for code, _ in expected), [d.format() for d in a.errors]
    for (code, message), (want_code, want_text) in zip(got, sorted(expected)):
        assert code == want_code and want_text in message
    lost = [name for names in a.lost.values() for name, _line in names]
    assert lost == PORT_LOST.get(_chapter(folder), [])
    pous = [u for u in a.units.all if u.is_pou]
    assert pous and [u.name for u in pous if not a.compiled(u)] == PORT_NOT_COMPILED.get(_chapter(folder), [])


def _export_project() -> Project:
    [project] = open_projects([EXPORT or "."])
    return project


@pytest.mark.skipif(not EXPORT, reason=NO_EXPORT)
def test_the_codesys_export_compiles_but_for_what_only_codesys_2_3_took():
    a = analyse(_export_project(), "codesys")
    assert not any(d.code == "E009" for d in a.diagnostics)
    pous = [u for u in a.units.all if u.is_pou]
    missing = {u.name for u in pous if not a.compiled(u)}
    assert len(pous) > 500 and missing <= set(EXPORT_NOT_COMPILED), sorted(missing - set(EXPORT_NOT_COMPILED))


# ---------------------------------------------------------------- the documented examples


def _name(call: str) -> str:
    return call.split("(", 1)[0].strip().upper()


def _functions(text: str) -> set:
    """The FUNCTIONs a PLCopen XML file or a CODESYS export declares (the port
    made some of the manual's functions blocks: their examples do not apply)."""
    found = re.findall(r'<pou name="([A-Za-z_]\w*)" pouType="function"', text)
    found += re.findall(r"^\s*FUNCTION\s+([A-Za-z_]\w*)", text, re.M)
    return {n.upper() for n in found}


def _case(ex: dict, port: bool) -> dict:
    """The call, result and type of an example as the corpus takes it."""
    if port and "port_call" in ex:
        ex = {**ex, "call": ex["port_call"]}
    if port and "port_result" in ex:
        ex = {**ex, "result": ex["port_result"], "type": ex["port_type"]}
    return ex


def _program(i: int, ex: dict) -> str:
    """One example as PROGRAM Ex_i: got, the call's value (or the checked
    variable's after the call), and want, the documented result."""
    decls = ex.get("decls", "")
    if "check" in ex:
        body = f"ret := {ex['call']};\ngot := {ex['check']};"
        decls += f" ret : {ex['returns']};"
    else:
        body = f"got := {ex['call']};"
    return (
        f"PROGRAM Ex_{i}\nVAR\n{decls}\ngot : {ex['type']};\nwant : {ex['type']} := {ex['result']};\nEND_VAR\n"
        f"{body}\nEND_PROGRAM\n"
    )


def _run(project: Project, profile: str, cases: list) -> list:
    """(example, got, want) of each case, or (example, None, reason) when its
    program did not compile."""
    name = str(project.root / "oscat_examples.st")
    project.files.append(name)
    project.generated[name] = "\n".join(_program(i, ex) for i, ex in enumerate(cases))
    a = analyse(project, profile)
    units = {u.name.upper(): u for u in a.units.all if u.is_pou}
    out = []
    for i, ex in enumerate(cases):
        unit = units[f"EX_{i}"]
        if a.program is None or not a.compiled(unit):
            why = [d.format() for d in a.errors if d.pos.file == name] or [a.because.get(unit.id, "not compiled")]
            out.append((ex, None, why))
            continue
        r = a.program.runner(f"Ex_{i}")
        r.run(1)
        out.append((ex, r.get("got"), r.get("want")))
    return out


def _mismatches(results: list) -> list:
    bad = []
    for ex, got, want in results:
        tol = ex.get("tolerance")
        same = got is not None and (got == want or (tol is not None and abs(got - want) <= tol))
        if not same:
            bad.append(f"{ex['page']}: {ex['call']} gave {got!r}, documented {ex['result']} ({want!r})")
    return bad


@pytest.mark.skipif(not PORT, reason=NO_PORT)
def test_the_documented_examples_give_their_results_on_the_port():
    chapters = [(folder, _functions((folder / "plc.xml").read_text(encoding="utf-8"))) for folder in PORT_PROJECTS]
    by_chapter: dict = {}
    for ex in EXAMPLES:
        case = _case(ex, port=True)
        home = next((f for f, names in chapters if _name(case["call"]) in names), None)
        if home is not None:
            by_chapter.setdefault(home, []).append(case)
    results = []
    for folder, cases in by_chapter.items():
        [project] = open_projects([str(folder)])
        results += _run(project, "matiec", cases)
    assert len(results) >= 50  # the port has the logic, mathematics and time chapters' examples
    assert _mismatches(results) == []


@pytest.mark.skipif(not EXPORT, reason=NO_EXPORT)
def test_the_documented_examples_give_their_results_on_the_codesys_export():
    project = _export_project()
    names: set = set()
    for f in project.files:
        names |= _functions(Path(f).read_text(encoding="latin-1"))
    cases = [ex for ex in EXAMPLES if _name(ex["call"]) in names]
    results = _run(project, "codesys", cases)
    assert len(results) == len(EXAMPLES)  # every example's function is in the export
    assert _mismatches(results) == []
