"""The optimised code does what the plain code does: random programs of
integers near their limits, arrays, branches, loops, RETURN, FB calls and
methods, compiled with the facts, locals and bound elements
(codegen_facts.py, codegen_locals.py, codegen_reuse.py) and without them
(CodeGen.optimise False), run for some cycles, end in the same state."""

from __future__ import annotations

import pytest

hypothesis = pytest.importorskip("hypothesis")
from hypothesis import given  # noqa: E402
from hypothesis import strategies as st  # noqa: E402

from softplc.runtime import cache  # noqa: E402
from softplc.runtime.program import compile_files  # noqa: E402

from ..conftest import plain_codegen  # noqa: E402
from ..fuzz_support import fuzz_settings  # noqa: E402

TARGETS = ("a", "b", "c", "d", "arr[1]", "arr[4]")
READS = (*TARGETS, "w", "fb.n")
CONSTS = (0, 1, 2, 5, 100, 16384, 32766, 32767, -1, -32767, -32768)

BLOCK = """
FUNCTION_BLOCK FB_K
VAR_INPUT inc : INT; END_VAR
VAR n : INT; END_VAR
METHOD Poke
VAR_INPUT v : INT; END_VAR
n := v;
END_METHOD
n := n + inc;
IF n > 30000 THEN THIS^.Poke(v := 32767); n := n + 1; END_IF
END_FUNCTION_BLOCK
"""

DECLS = "a, b, c, w : INT; d : DINT; arr : ARRAY[1..4] OF INT; i : INT; go : BOOL; fb : FB_K;"


@st.composite
def exprs(draw, in_for: bool) -> str:
    reads = (*READS, "arr[i]") if in_for else READS
    kind = draw(st.integers(0, 3))
    if kind == 0:
        return str(draw(st.sampled_from(CONSTS)))
    if kind == 1:
        return draw(st.sampled_from(reads))
    left, right = draw(st.sampled_from(reads)), draw(st.sampled_from((*reads, *map(str, CONSTS))))
    return f"{left} {draw(st.sampled_from(('+', '-')))} {right}"


@st.composite
def conds(draw, in_for: bool) -> str:
    if draw(st.booleans()):
        return draw(st.sampled_from(("go", "NOT go")))
    op = draw(st.sampled_from(("<", ">", ">=", "<=", "=")))
    cond = f"{draw(st.sampled_from(READS))} {op} {draw(st.sampled_from(CONSTS))}"
    if draw(st.booleans()):
        cond += f" AND {draw(exprs(in_for))} < {draw(st.sampled_from(CONSTS))}"
    return cond


@st.composite
def stmts(draw, depth: int, in_for: bool = False, action: bool = False) -> str:
    out = []
    for _ in range(draw(st.integers(1, 4))):
        kinds = ["assign", "assign", "inc", "inc", "toggle", "fb", "poke", "bit"]
        if action:
            kinds.append("action")
        if depth > 0:
            kinds += ["if", "case", "return", "probe", "probe"] + ([] if in_for else ["for", "while"])
        kind = draw(st.sampled_from(kinds))
        targets = (*TARGETS, "arr[i]") if in_for else TARGETS
        if kind == "probe":  # a value known, then something, then a sum that wraps unless it is still known
            target, middle = draw(st.sampled_from(targets)), draw(stmts(depth - 1, in_for, action))
            step = draw(st.sampled_from((1, 16384, 32767, -1)))
            out.append(f"{target} := {draw(st.sampled_from(CONSTS))};\n{middle}\n{target} := {target} + {step};")
        elif kind == "inc":
            target = draw(st.sampled_from(targets))
            out.append(f"{target} := {target} + {draw(st.sampled_from((1, 16384, 32767, -1)))};")
        elif kind == "assign":
            out.append(f"{draw(st.sampled_from(targets))} := {draw(exprs(in_for))};")
        elif kind == "toggle":
            out.append("go := NOT go;")
        elif kind == "fb":
            out.append(f"fb(inc := {draw(st.sampled_from(CONSTS))});")
        elif kind == "poke":
            out.append(f"fb.Poke(v := {draw(exprs(in_for))});")
        elif kind == "bit":
            out.append(f"{draw(st.sampled_from(('a', 'b', 'd')))}.15 := go;")
        elif kind == "action":
            out.append("Bump();")
        elif kind == "return":
            out.append(f"IF {draw(conds(in_for))} THEN RETURN; END_IF")
        elif kind == "if":
            text = f"IF {draw(conds(in_for))} THEN\n{draw(stmts(depth - 1, in_for, action))}\n"
            if draw(st.booleans()):
                text += f"ELSIF {draw(conds(in_for))} THEN\n{draw(stmts(depth - 1, in_for, action))}\n"
            if draw(st.booleans()):
                text += f"ELSE\n{draw(stmts(depth - 1, in_for, action))}\n"
            out.append(text + "END_IF")
        elif kind == "case":
            zero, some, other = (draw(stmts(depth - 1, in_for, action)) for _ in range(3))
            out.append(f"CASE {draw(st.sampled_from(READS))} OF\n0: {zero}\n1..100: {some}\nELSE {other}\nEND_CASE")
        else:  # a loop, often after a value it then adds to (its body runs again with what it stored)
            target = draw(st.sampled_from(TARGETS))
            before = f"{target} := {draw(st.sampled_from(CONSTS))};\n" if draw(st.booleans()) else ""
            grow = f"{target} := {target} + 16384;\n" if draw(st.booleans()) else ""
            if kind == "for":
                body = draw(stmts(depth - 1, True, action))
                out.append(f"{before}FOR i := 1 TO 4 DO\n{grow}{body}\nEND_FOR")
            else:  # w counts the passes; nothing else assigns it
                body = draw(stmts(depth - 1, in_for, action))
                out.append(f"{before}w := 0;\nWHILE w < 3 DO\nw := w + 1;\n{grow}{body}\nEND_WHILE")
    return "\n".join(out)


def final_state(text: str, cycles: int = 4) -> dict:
    with cache.disabled():  # the two compiles must not share a cached module
        runner = compile_files([], texts={"plain.st": text}).runner("main")
    runner.run(cycles)
    return {name: runner.get(name) for name in ("a", "b", "c", "d", "w", "i", "go", "arr", "fb.n")}


@fuzz_settings(200)
@given(body=stmts(3), with_action=st.booleans(), data=st.data())
def test_the_optimised_program_ends_where_the_plain_one_does(body, with_action, data):
    action = ""
    if with_action:  # a program with an action: its variables are reachable from calls
        body = data.draw(stmts(3, action=True))
        action = "ACTION main.Bump:\na := 32767; arr[2] := 32767; d := 2147483647;\nEND_ACTION\n"
    text = f"{BLOCK}\nPROGRAM main\nVAR {DECLS} END_VAR\n{body}\nEND_PROGRAM\n{action}"
    optimised = final_state(text)
    with plain_codegen():
        expected = final_state(text)
    assert optimised == expected, text
