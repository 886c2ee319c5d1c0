"""Long expressions (issue 31: 198 operators in one expression were E006):
random chains of DINT + - * and BOOL AND XOR OR, up to 2,000 operators,
across the lengths where the checker and the code generator change method
(checker_exprs.CHAIN_AHEAD, codegen_exprs.CHAIN_CHUNK), compile, run one
cycle and give what Python computes from the same operands (+ - * and
& ^ | have IEC's precedence in Python too; DINT wraps at the store)."""

from __future__ import annotations

from dataclasses import dataclass

from hypothesis import given
from hypothesis import strategies as st

from softplc.runtime.program import compile_files

from .support import bounded, fuzz, long, short

NAMES = ("a", "b", "c", "d")
_OPS = {"DINT": (("+", "+"), ("-", "-"), ("*", "*")), "BOOL": (("AND", "&"), ("XOR", "^"), ("OR", "|"))}


@dataclass(frozen=True)
class Chain:
    ty: str
    values: tuple
    ops: tuple  # (ST operator, Python operator, operand name) after the first operand

    def source(self) -> str:
        decls = " ".join(f"{n} : {self.ty} := {str(v).upper()};" for n, v in zip(NAMES, self.values))
        expr = "a" + "".join(f" {op} {name}" for op, _, name in self.ops)
        return f"PROGRAM Main\nVAR {decls} x : {self.ty}; END_VAR\nx := {expr};\nEND_PROGRAM\n"

    def expected(self):
        text = "a" + "".join(f" {py} {name}" for _, py, name in self.ops)
        value = eval(text, {}, dict(zip(NAMES, self.values)))  # the same chain in Python
        if self.ty == "BOOL":
            return bool(value)
        return (value + (1 << 31)) % (1 << 32) - (1 << 31)


@st.composite
def chains(draw) -> Chain:
    ty = draw(st.sampled_from(("DINT", "BOOL")))
    if ty == "DINT":
        values = tuple(draw(st.lists(st.integers(-3, 3), min_size=4, max_size=4)))  # products stay small
    else:
        values = tuple(draw(st.lists(st.booleans(), min_size=4, max_size=4)))
    n = draw(st.one_of(st.integers(1, 40), st.integers(40, 2000)))
    ops = draw(st.lists(st.tuples(st.sampled_from(_OPS[ty]), st.sampled_from(NAMES)), min_size=n, max_size=n))
    return Chain(ty, values, tuple((st_op, py_op, name) for (st_op, py_op), name in ops))


def _check(chain: Chain) -> str:
    with bounded("a long expression"):
        runner = compile_files([], texts={"chain.st": chain.source()}).runner("Main")
        runner.run(1)
    assert runner.get("x") == chain.expected(), chain.source()[:400]
    return chain.ty


@short(8)
@given(chains())
def test_a_long_chain_gives_what_python_computes(chain):
    _check(chain)


@fuzz
def test_long_chains(tally, shard):
    counts = tally("st")

    @long("st", 0.01, shard)
    @given(chains())
    def run(chain):
        counts.add(_check(chain))

    run()
