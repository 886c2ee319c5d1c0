"""What the parts of the code generator share: output, constants, state.

The CodeGen (codegen.py) is one class composed of a part per concern,
each in its own module: codegen_pous (classes, functions, initial values),
codegen_stmts (statements, conversions on store, stores), codegen_jumps
(JMP and labels), codegen_exprs
(expressions, references) and codegen_calls. They emit lines through
CodeGenBase, which remembers each line's ST position, and register the
objects the code needs as numbered constants. A part calls the others
through ``self``; what it may call is declared at the end of CodeGenBase,
for the type checker.
"""

from __future__ import annotations

import math
from collections import ChainMap
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from .. import ast as A
from .. import types as T
from ..check.symbols import CallInfo, POUInfo, VarSymbol
from ..profile import Profile
from . import ranges as R

if TYPE_CHECKING:
    from ..check.checker import CheckedProgram


#: the sections of a POU's own variables that its body alone may name (not VAR_IN_OUT, not globals)
_OWN_SECTIONS = ("VAR", "VAR_TEMP", "VAR_INPUT", "VAR_OUTPUT")


def py_literal(v: Any) -> str:
    """Python source for a parsed scalar value."""
    if isinstance(v, bool):
        return "True" if v else "False"
    if isinstance(v, int):
        return str(v)
    if isinstance(v, float):
        if math.isnan(v):
            return "_NAN"
        if math.isinf(v):
            return "_INF" if v > 0 else "(-_INF)"
        return repr(v)
    if isinstance(v, str):
        return repr(v)  # repr of a str is always a valid, inert Python literal
    raise TypeError(f"no literal form for {type(v).__name__}")


def elementary(ty: T.Type) -> T.ElementaryType:
    """The elementary type values of the checked type ty are stored as
    (asked only where the checker made sure there is one)."""
    be = T.base_elementary(ty)
    if be is None:
        raise TypeError(f"{ty} is not stored as an elementary value")
    return be


def array_type(ty: T.Type) -> T.ArrayType:
    """The checked type ty of an indexed value: an ARRAY."""
    t = T.resolve(ty)
    if not isinstance(t, T.ArrayType):
        raise TypeError(f"{ty} is not an array")
    return t


@dataclass
class Accessor:
    """A process-image address the loader binds: _A<n>g / _A<n>s (scalar
    get/set) or _A<n>t (a word table)."""

    addr: A.LocatedAddress
    type: Any  # ElementaryType, or None for a table


class FnState:
    """Per-body state: how variables are reached from the code being emitted."""

    def __init__(self, pou: POUInfo | None, self_name: str = "self") -> None:
        self.pou = pou
        self.self_name = self_name
        # ('for', (var, loop local, read from it?)), ('while', budget local), ('repeat', (cond, budget local)),
        # ('jump', JumpFrame): a statement list with labels (codegen_jumps.py)
        self.loop_kinds: list = []
        # FOR variables currently read from the Python loop local: id(VarSymbol) -> local name
        self.for_locals: dict = {}
        # ... and of those the (lowest, highest) value when the bounds are constant
        self.loop_ranges: dict = {}
        # what the statements before tell of integer variables (codegen_facts.py):
        # id(VarSymbol) -> (lowest, highest); None where none are kept (a list with labels)
        self.facts: dict | None = {}
        # ... of those, the ids of the variables a call may reach (an FB's own)
        self.fact_reachable: set = set()
        # JMP (codegen_jumps.py): id(Label) -> (JumpFrame, index); transfers out
        # of loops waiting after the loop at a depth of loop_kinds; their count
        self.labels: dict = {}
        self.crossing: dict = {}
        self.transfers = 0
        # array elements bound to locals (codegen_reuse.py): the ids of the
        # variables the body takes references to (found when first asked), and
        # the indent of the plain assignment being emitted (binding allowed)
        self.referenced: set | None = None
        self.bind_at: int | None = None
        # expressions bound to a local before the FOR loop whose body repeats
        # them (codegen_hoist.py): id(Expr) -> local name
        self.hoisted: dict = {}
        # a PROGRAM's scalars held in locals while its body runs (codegen_locals.py):
        # id(VarSymbol) -> local name; the ids of those the body stores
        self.promoted: dict = {}
        self.promoted_stored: set = set()
        # aggregates of self read through a local (codegen_pous.py _aliased_body):
        # pyname -> reads, while a body that takes them is emitted; None: not here
        self.aliases: dict | None = None
        # the FOR loops of such a body whose body reads the loop local, as
        # (variable, local): a fault stores the local (codegen_pous.py _loop_faults)
        self.loop_locals: list | None = None

    @property
    def is_function(self) -> bool:
        return self.pou is not None and self.pou.kind == "FUNCTION"


class CodeGenBase:
    """The generator's state and output; the parts add the code for each
    kind of node (see the module docstring)."""

    #: the cooperative watchdog's checks on loop back-edges (codegen_stmts.py);
    #: False only to measure what they cost (benchmarks/bench_loops.py)
    watchdog_checks = True

    #: the facts, locals and bound elements (codegen_facts.py, codegen_locals.py,
    #: codegen_reuse.py) and a result stored first without its default; False
    #: only to compare against the plain code (tests/st/codegen/test_codegen_plain.py)
    optimise = True

    def _body_state(self, pou: POUInfo) -> FnState:
        """The state for emitting a body of pou: facts kept unless not optimise."""
        fn = FnState(pou)
        if not self.optimise:
            fn.facts = None
        return fn

    def __init__(self, checked: CheckedProgram, profile: Profile) -> None:
        self.prog = checked
        self.profile = profile
        self.out: list = []  # (text, pos)
        self.indent = 0
        self.pos: A.Pos | None = None
        self.consts: dict = {}
        self._const_ids: dict = {}
        self.accessors: dict = {}
        self._acc_keys: dict = {}
        self._tmp = 0
        self.fn = FnState(None)
        # element stores bound to a local, and the locals of those a read used (codegen_reuse.py)
        self._stores_bound = 0
        self._stores_read: set[str] = set()
        self._ref_inits: list = []  # (target, REF() call, pos, type) to emit after the other initial values

    def emit(self, line: str) -> None:
        self.out.append(("    " * self.indent + line, self.pos))

    def tmp(self, base: str = "t") -> str:
        self._tmp += 1
        return f"_{base}{self._tmp}"

    def const(self, obj: Any, label: str = "") -> str:
        key = id(obj)
        if key in self._const_ids:
            return self._const_ids[key]
        name = f"_K{len(self.consts)}"
        self.consts[name] = obj
        self._const_ids[key] = name
        return name

    def accessor(self, addr: A.LocatedAddress, ty: T.ElementaryType | None) -> int:
        key = (addr.area, addr.size, addr.indices, addr.bit, addr.table, ty.name if ty else None)
        if key not in self._acc_keys:
            idx = len(self.accessors)
            self.accessors[idx] = Accessor(addr, ty)
            self._acc_keys[key] = idx
        return self._acc_keys[key]

    def _range(self, e: A.Expr | None) -> R.Range | None:
        """What range analysis knows of an integer expression here (ranges.py):
        the ranges of FOR variables, and the facts (codegen_facts.py)."""
        facts = self.fn.facts
        return R.value_range(e, ChainMap(self.fn.loop_ranges, facts) if facts else self.fn.loop_ranges)

    def _own_unreferenced(self, sym: Any) -> bool:
        """A variable of the POU being emitted, not located, that no
        reference reaches (REF, ADR, VAR_IN_OUT, =>): only its own code
        names it (codegen_facts.py, codegen_locals.py, codegen_reuse.py)."""
        pou = self.fn.pou
        return (
            isinstance(sym, VarSymbol)
            and pou is not None
            and sym.owner is pou
            and sym.section in _OWN_SECTIONS
            and sym.location is None
            and not sym.address_taken
            and not sym.boxed
        )

    @staticmethod
    def _closed_program(pou: POUInfo) -> bool:
        """A PROGRAM whose variables no code but its body's can reach while
        it runs: no other POU names a program's variables, a task alone
        calls it, and it has no actions, methods, properties or SFC steps."""
        return pou.kind == "PROGRAM" and not (pou.actions or pou.methods or pou.properties or pou.sfc)

    @staticmethod
    def _temp_local(v: VarSymbol) -> bool:
        """A VAR_TEMP of a PROGRAM or FB lives in a Python local of the body
        (it starts afresh every call) unless a reference to it is taken."""
        return v.section == "VAR_TEMP" and not v.address_taken and v.owner is not None and v.owner.kind != "FUNCTION"

    @staticmethod
    def wrap(t: T.ElementaryType, code: str) -> str:
        """Python wrapping the integer code to the width of t (rtlib.wrap, inline)."""
        mask = (1 << t.bits) - 1
        if t.lo is not None and t.lo < 0:
            half = 1 << (t.bits - 1)
            return f"((({code}) + {half} & {mask}) - {half})"
        return f"(({code}) & {mask})"

    if TYPE_CHECKING:
        # Implemented by the parts: what one part calls of another.
        # codegen_pous
        def _function_epilogue(self) -> None: ...

        # codegen_stmts
        def _body(self, stmts: list) -> None: ...

        def _stmt(self, s: A.Stmt) -> None: ...

        def _loop_budget_take(self) -> str: ...

        def _loop_budget_give(self, wd: str) -> None: ...

        def _watchdog_tick(self, wd: str) -> None: ...

        # codegen_reuse
        def _index_read(self, e: A.Index) -> str: ...

        # codegen_locals
        def _locals_begin(self, stmts: list) -> list: ...

        def _locals_end(self, syms: list) -> None: ...

        # codegen_jumps
        def _dispatch(self, stmts: list) -> None: ...

        def _jump(self, s: A.Jump) -> None: ...

        def _leave_through_labels(self, word: str) -> bool: ...

        def _after_loop(self) -> None: ...

        def coerce(self, code: str, src: T.Type, dst: T.Type, e: A.Expr | None) -> str: ...

        def _store_name(self, sym: VarSymbol, code: str) -> None: ...

        def emit_store(
            self, target: A.Expr, value_code: str, value_ty: T.Type, value_expr: A.Expr | None, trusted: bool = False
        ) -> None: ...

        # codegen_exprs
        def ex(self, e: A.Expr) -> str: ...

        def _read_name(self, sym: Any) -> str: ...

        def _index_target(self, e: A.Index) -> str: ...

        def ref_code(self, e: A.Expr) -> str: ...

        def _copied_cell(self, sym: Any) -> bool: ...

        def ref_value(self, e: A.Expr) -> str: ...

        def bind_code(self, e: A.Expr) -> str: ...

        def cut_ref(self, code: str, actual: T.Type | None, formal: T.Type | None) -> str: ...

        # codegen_pointers
        def pointer_op(self, e: A.Binary) -> str: ...

        def decay_code(self, code: str, target: T.Type) -> str: ...

        def byte_view_code(self, code: str, src: T.Type | None, dst: T.Type) -> str: ...

        def string_leaf(self, e: A.Index) -> str: ...

        def adr_code(self, e: A.Expr) -> str: ...

        def _index_code(self, ix: A.Expr, dim: tuple | None) -> str: ...

        # codegen_pous
        def _emit_init(self, target: str, ty: T.Type, plan: Any, ref_target: str | None = None) -> None: ...

        def _aggregate_expr(self, ty: T.Type, plan: Any) -> str: ...

        def _default_code(self, ty: T.Type) -> str: ...

        # codegen_calls
        def _call_expr(self, e: A.Call) -> str: ...

        def _std_invoke(self, info: CallInfo, args: list) -> str: ...

        def _call_stmt(self, e: A.Call) -> None: ...

        def _function(self, pou: POUInfo, method: bool = False) -> None: ...

        def _function_args(self, info: CallInfo, positional: bool = False) -> str: ...

        # codegen_oop
        def _class_header(self, pou: POUInfo) -> str: ...

        def _oop_members(self, pou: POUInfo) -> None: ...

        def _fb_init_calls(self, pou: POUInfo) -> None: ...

        def _init_params(self, pou: POUInfo) -> str: ...

        def _action_invoke(self, info: CallInfo, inst: str) -> str: ...

        def _fb_init_construct(self, ty: T.Type, plan: Any) -> str: ...

        def _method_invoke(self, e: A.Call, info: CallInfo) -> str: ...

        def _property_read(self, e: A.Name | A.Member) -> str: ...

        def _property_store(self, target: A.Name | A.Member, code: str) -> None: ...

        def _query_code(self, src: A.Expr, itf: T.Type) -> str: ...

        def _this_code(self, e: A.Deref) -> str | None: ...

        # codegen_eno
        def gated_value(self, info: CallInfo, code: str, ty: T.Type | None, eno_out: A.Expr | None) -> str: ...

        def function_gate(self, info: CallInfo, code: str) -> str: ...

        def fb_skipped(self, info: CallInfo, inst: str) -> None: ...
