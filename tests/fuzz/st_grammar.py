"""Valid ST programs from the grammar, typed: every expression is built for
the type its place wants, so the checker must accept the program and the
code generator and the runtime get legal programs of every shape.

    valid_programs()     (st_decls.py) a hypothesis strategy of source
                         texts: enumerations, structures (with arrays and
                         earlier structures), FUNCTIONs, FUNCTION_BLOCKs (with
                         standard FBs and earlier FBs inside), globals,
                         constants, references and one PROGRAM main;
                         IF/ELSIF/CASE/FOR/WHILE/REPEAT, EXIT, CONTINUE, calls
                         with named and positional arguments, array, field,
                         bit and reference access

Only the division by zero, an index out of bounds, an overflowing conversion
or an endless WHILE may stop a generated program at run time (a runtime
fault, which is fine); a compile error is a finding.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from hypothesis import strategies as st

SIGNED = {"SINT": 8, "INT": 16, "DINT": 32, "LINT": 64}
UNSIGNED = {"USINT": 8, "UINT": 16, "UDINT": 32, "ULINT": 64}
BITS = {"BYTE": 8, "WORD": 16, "DWORD": 32, "LWORD": 64}
INTS = {**SIGNED, **UNSIGNED}
REALS = ("REAL", "LREAL")
ELEMENTARY = (*INTS, *BITS, *REALS, "BOOL", "TIME", "STRING")

# issue 16, "FOR loops are not checked by the watchdog": the bounds of a
# generated FOR loop may be any DINT expression (the loop watchdog stops it)
FOR_ANY_BOUNDS = True


@dataclass(frozen=True)
class Ty:
    kind: str  # "elem" | "enum" | "array" | "struct" | "fb" | "ref"
    name: str  # the elementary type, the enumeration, structure or FB name; "" for arrays
    elem: Ty | None = None  # an array's element type, what a reference points to
    dims: tuple = ()  # an array's ((lo, hi), ...)

    def decl(self) -> str:
        if self.kind == "array":
            assert self.elem is not None
            ranges = ", ".join(f"{lo}..{hi}" for lo, hi in self.dims)
            return f"ARRAY[{ranges}] OF {self.elem.decl()}"
        if self.kind == "ref":
            assert self.elem is not None
            return f"REF_TO {self.elem.decl()}"
        return "STRING[12]" if self.name == "STRING" else self.name


def elem(name: str) -> Ty:
    return Ty("elem", name)


@dataclass
class Leaf:
    """A place of an elementary or enumerated type reachable from a
    variable: its text, with a hole (a tuple of (lo, hi) dimensions) for
    each array index to fill, and whether a statement may write it."""

    parts: tuple
    ty: Ty
    writable: bool
    const: bool = False  # a VAR CONSTANT


@dataclass
class Pou:
    kind: str  # "FUNCTION" | "FUNCTION_BLOCK" | "PROGRAM"
    name: str
    inputs: list = field(default_factory=list)  # (name, Ty)
    outputs: list = field(default_factory=list)
    result: Ty | None = None  # a FUNCTION's


class World:
    """What the program declared so far, for the parts generated next."""

    def __init__(self) -> None:
        self.enums: dict[str, list[str]] = {}
        self.structs: dict[str, list] = {}  # name -> [(field, Ty)]
        self.functions: list[Pou] = []
        self.fbs: dict[str, Pou] = {}
        self.globals: list = []  # (name, Ty)


STANDARD_FBS = {
    "TON": (
        [("IN", elem("BOOL")), ("PT", elem("TIME"))],
        [("Q", elem("BOOL")), ("ET", elem("TIME"))],
    ),
    "TOF": (
        [("IN", elem("BOOL")), ("PT", elem("TIME"))],
        [("Q", elem("BOOL")), ("ET", elem("TIME"))],
    ),
    "TP": ([("IN", elem("BOOL")), ("PT", elem("TIME"))], [("Q", elem("BOOL")), ("ET", elem("TIME"))]),
    "CTU": (
        [("CU", elem("BOOL")), ("R", elem("BOOL")), ("PV", elem("INT"))],
        [("Q", elem("BOOL")), ("CV", elem("INT"))],
    ),
    "CTD": (
        [("CD", elem("BOOL")), ("LD", elem("BOOL")), ("PV", elem("INT"))],
        [("Q", elem("BOOL")), ("CV", elem("INT"))],
    ),
    "R_TRIG": ([("CLK", elem("BOOL"))], [("Q", elem("BOOL"))]),
    "F_TRIG": ([("CLK", elem("BOOL"))], [("Q", elem("BOOL"))]),
    "SR": ([("S1", elem("BOOL")), ("R", elem("BOOL"))], [("Q1", elem("BOOL"))]),
    "RS": ([("S", elem("BOOL")), ("R1", elem("BOOL"))], [("Q1", elem("BOOL"))]),
}


class Scope:
    """The variables one POU body sees, as leaves by type."""

    def __init__(self, world: World, variables: list, readonly: set, constants: frozenset = frozenset()) -> None:
        self.world = world
        self.variables = variables  # (name, Ty)
        self.leaves: list[Leaf] = []
        for name, ty in variables:
            self._walk((name,), ty, name not in readonly and name not in constants, 0)
        for leaf in self.leaves:
            leaf.const = leaf.parts[0] in constants
        self.counters: list[str] = []  # FOR counters (DINT), one per nesting level
        self.guards: list[str] = []  # WHILE/REPEAT guards (INT)
        self.instances = [(n, t) for n, t in variables if t.kind == "fb"]

    def _walk(self, parts: tuple, ty: Ty, writable: bool, depth: int) -> None:
        if ty.kind in ("elem", "enum"):
            self.leaves.append(Leaf(parts, ty, writable))
            if ty.kind == "elem" and ty.name in BITS:
                for bit in (0, BITS[ty.name] - 1):
                    self.leaves.append(Leaf((*parts, f".{bit}"), elem("BOOL"), writable))
        elif ty.kind == "ref":  # set to REF(a variable) before the body runs
            assert ty.elem is not None
            self.leaves.append(Leaf((*parts, "^"), ty.elem, True))
        elif ty.kind == "array" and depth < 3:
            assert ty.elem is not None
            self._walk((*parts, ty.dims), ty.elem, writable, depth + 1)
        elif ty.kind == "struct" and depth < 3:
            for fname, fty in self.world.structs[ty.name]:
                self._walk((*parts, f".{fname}"), fty, writable, depth + 1)
        elif ty.kind == "fb" and depth < 2:
            if ty.name in STANDARD_FBS:
                ins, outs = STANDARD_FBS[ty.name]
            else:
                pou = self.world.fbs[ty.name]
                ins, outs = pou.inputs, pou.outputs
            for fname, fty in [*ins, *outs]:
                if fty.kind in ("elem", "enum"):
                    self.leaves.append(Leaf((*parts, f".{fname}"), fty, False))

    def of(self, ty: Ty, writable: bool = False, constant: bool = True) -> list[Leaf]:
        return [
            leaf
            for leaf in self.leaves
            if leaf.ty == ty and (leaf.writable or not writable) and (constant or not leaf.const)
        ]


class Gen:
    """One program being generated: hypothesis's draw and the world."""

    def __init__(self, draw) -> None:
        self.draw = draw
        self.world = World()
        self.names = 0

    def pick(self, options):
        return self.draw(st.sampled_from(list(options)))

    def chance(self, p: float) -> bool:
        return self.draw(st.integers(0, 99)) < p * 100

    def int_in(self, lo: int, hi: int) -> int:
        return self.draw(st.integers(lo, hi))

    def fresh(self, prefix: str) -> str:
        self.names += 1
        return f"{prefix}{self.names}"

    # ------------------------------------------------------------ literals

    def literal(self, ty: Ty, nonzero: bool = False) -> str:
        if ty.kind == "enum":
            value = self.pick(self.world.enums[ty.name])
            return f"{ty.name}#{value}" if self.chance(0.5) else value
        n = ty.name
        if n == "BOOL":
            return self.pick(["TRUE", "FALSE"])
        if n in SIGNED:
            bits = SIGNED[n]
            v = self.draw(st.sampled_from([0, 1, -1, 2, 7, 100]) | st.integers(-(1 << bits - 1), (1 << bits - 1) - 1))
            v = v or (3 if nonzero else 0)
            return f"{n}#{v}" if self.chance(0.3) else (f"({v})" if v < 0 else str(v))
        if n in UNSIGNED or n in BITS:
            bits = INTS.get(n) or BITS[n]
            v = self.draw(st.sampled_from([0, 1, 2, 255]) | st.integers(0, (1 << bits) - 1))
            v = v or (3 if nonzero else 0)
            if n in BITS:  # an untyped literal is an INT, not a bit string
                return f"{n}#16#{v:X}" if self.chance(0.5) else f"{n}#{v}"
            return f"{n}#{v}" if self.chance(0.3) else str(v)
        if n in REALS:
            v = self.pick(["1.5", "-2.25", "1.0E3", "3.0E-2", "100.0", "0.5"] + ([] if nonzero else ["0.0"]))
            if self.chance(0.3):
                return f"{n}#{v}"
            return f"({v})" if v.startswith("-") else v
        if n == "TIME":
            return self.pick(["T#0ms", "T#5ms", "T#1s", "T#1m30s", "TIME#250ms", "T#-5ms", "T#2h"])
        if n == "STRING":
            return self.pick(["''", "'a'", "'hello'", "'$N$T'", "'$$'", "'it$'s'", "'0123456789'"])
        raise AssertionError(n)

    # ------------------------------------------------------------ places

    def place(self, leaf: Leaf, scope: Scope, depth: int) -> str:
        out = []
        for part in leaf.parts:
            if isinstance(part, tuple):
                out.append("[" + ", ".join(self.index(lo, hi, scope, depth) for lo, hi in part) + "]")
            else:
                out.append(part)
        return "".join(out)

    def index(self, lo: int, hi: int, scope: Scope, depth: int) -> str:
        if depth < 2 and self.chance(0.3):
            # any INT that is not constant (a constant one out of bounds is a
            # compile error): out of bounds at run time, a runtime fault
            text, const = self.term(elem("INT"), scope, depth + 1)
            if not const:
                return text
        v = self.int_in(lo, hi)
        return f"({v})" if v < 0 else str(v)

    def variable(self, ty: Ty, scope: Scope, depth: int) -> str | None:
        """A place of type ty that is not a constant, or None."""
        leaves = scope.of(ty, constant=False)
        return self.place(self.pick(leaves), scope, depth) if leaves else None

    # ------------------------------------------------------------ expressions
    #
    # The checker folds constant expressions and rejects what folds to an
    # error (a constant out of range, a division by the constant zero, an
    # index out of bounds), and an expression of untyped literals alone is an
    # INT. So every compound expression holds at least one variable in a
    # value position: a bare literal is the only constant expression made.

    def expr(self, ty: Ty, scope: Scope, depth: int = 0) -> str:
        return self.term(ty, scope, depth)[0]

    def term(self, ty: Ty, scope: Scope, depth: int = 0) -> tuple[str, bool]:
        """An expression of type ty and whether it is constant."""
        leaves = scope.of(ty)
        if depth >= 3 or self.chance(0.25) or ty.kind == "enum":
            if leaves and self.chance(0.6):
                leaf = self.pick(leaves)
                return self.place(leaf, scope, depth), leaf.const
            return self.literal(ty), True
        n = ty.name
        forms = ["leaf", "literal"]
        calls = [f for f in self.world.functions if f.result == ty]
        if calls:
            forms.append("call")
        if n in INTS:
            forms += ["arith", "arith", "minmax", "convert", "sel"]
            if n in SIGNED:
                forms += ["neg", "abs"]
            if n == "INT":
                forms.append("len")
        elif n in BITS:
            forms += ["logic", "logic", "shift", "not", "convert"]
        elif n in REALS:
            forms += ["arith", "arith", "math", "convert", "neg", "minmax"]
        elif n == "BOOL":
            forms += ["compare", "compare", "logic", "logic", "not", "equal"]
        elif n == "TIME":
            forms += ["time_arith", "convert", "minmax"]
        elif n == "STRING":
            forms += ["concat", "cut"]
        form = self.pick(forms)
        if form == "leaf" and leaves:
            leaf = self.pick(leaves)
            return self.place(leaf, scope, depth), leaf.const
        if form == "call":
            return self.call_function(self.pick(calls), scope, depth + 1), False
        if form in ("leaf", "literal"):
            return self.literal(ty), True
        text = self._compound(form, ty, scope, depth + 1)
        return (text, False) if text is not None else (self.literal(ty), True)

    def _operands(self, ty: Ty, scope: Scope, depth: int, k: int) -> list[str] | None:
        """k operands of type ty, at least one of them not constant (None
        when no variable of that type is in reach)."""
        made = [self.term(ty, scope, depth) for _ in range(k)]
        if all(const for _t, const in made):
            var = self.variable(ty, scope, depth)
            if var is None:
                return None
            made[self.int_in(0, k - 1)] = (var, False)
        return [text for text, _c in made]

    def _compound(self, form: str, ty: Ty, scope: Scope, depth: int) -> str | None:
        n = ty.name
        if form == "arith":
            op = self.pick(["+", "-", "*", "/"] + (["MOD"] if n in INTS else []))
            left, right = self.term(ty, scope, depth), self.term(ty, scope, depth)
            if right[1] and op in ("/", "MOD"):
                right = (self.literal(ty, nonzero=True), True)
            if left[1] and right[1]:
                var = self.variable(ty, scope, depth)
                if var is None:
                    return None
                left = (var, False)
            return f"({left[0]} {op} {right[0]})"
        if form in ("neg", "abs", "not", "math", "shift"):
            ops = self._operands(ty, scope, depth, 1)
            if ops is None:
                return None
            if form == "neg":
                return f"-{ops[0]}"
            if form == "not":
                return f"NOT {ops[0]}"
            if form == "shift":
                return f"{self.pick(['SHL', 'SHR', 'ROL', 'ROR'])}({ops[0]}, {self.int_in(0, BITS[n] + 2)})"
            if form == "math":
                fn = self.pick(["SQRT", "ABS", "SIN", "COS", "EXP", "LN", "TRUNC"])
                return f"DINT_TO_{n}(TRUNC({ops[0]}))" if fn == "TRUNC" else f"{fn}({ops[0]})"
            return f"ABS({ops[0]})"
        if form == "minmax":
            fn = self.pick(["MIN", "MAX", "LIMIT"])
            ops = self._operands(ty, scope, depth, 3 if fn == "LIMIT" else 2)
            return None if ops is None else f"{fn}({', '.join(ops)})"
        if form == "sel":
            ops = self._operands(ty, scope, depth, 2)
            return None if ops is None else f"SEL({self.expr(elem('BOOL'), scope, depth)}, {ops[0]}, {ops[1]})"
        if form in ("logic", "time_arith", "concat"):
            ops = self._operands(ty, scope, depth, 2)
            if ops is None:
                return None
            if form == "concat":
                return f"CONCAT({ops[0]}, {ops[1]})"
            if form == "time_arith":
                op = self.pick(["+", "-"])
            elif n == "BOOL":
                op = self.pick(["AND", "OR", "XOR", "AND_THEN", "OR_ELSE", "&"])
            else:
                op = self.pick(["AND", "OR", "XOR"])
            return f"({ops[0]} {op} {ops[1]})"
        if form == "len":
            ops = self._operands(elem("STRING"), scope, depth, 1)
            return None if ops is None else f"LEN({ops[0]})"
        if form == "cut":
            text = self.variable(ty, scope, depth)
            count = self.variable(elem("INT"), scope, depth)
            if text is None or count is None:
                return None
            return f"{self.pick(['LEFT', 'RIGHT'])}({text}, {count})"
        if form == "convert":
            return self.conversion(ty, scope, depth)
        if form == "compare":
            other = elem(self.pick([*INTS, *REALS, "TIME", *BITS]))
            op = self.pick(["=", "<>", "<", ">", "<=", ">="] if other.name not in BITS else ["=", "<>"])
            # two bare literals: `2 < 18446744073709551615` is INT against ULINT
            ops = self._operands(other, scope, depth, 2)
            return None if ops is None else f"({ops[0]} {op} {ops[1]})"
        if form == "equal":
            enums = list(self.world.enums)
            other = Ty("enum", self.pick(enums)) if enums and self.chance(0.5) else elem("STRING")
            # a variable on one side at least: ('' = '') is the constant TRUE, and
            # BOOL_TO_INT of it a constant index the checker rightly bounds (E051)
            ops = self._operands(other, scope, depth, 2)
            return None if ops is None else f"({ops[0]} = {ops[1]})"
        raise AssertionError(form)

    def conversion(self, ty: Ty, scope: Scope, depth: int) -> str | None:
        n = ty.name
        if n == "TIME":
            src = "DINT"
        else:
            sources = [*INTS, *REALS] if n not in BITS else [*UNSIGNED, *BITS]
            if n in INTS:
                sources += ["BOOL", *BITS]
            src = self.pick([s for s in sources if s != n])
        ops = self._operands(elem(src), scope, depth, 1)
        return None if ops is None else f"{src}_TO_{n}({ops[0]})"

    def call_function(self, fn: Pou, scope: Scope, depth: int) -> str:
        if self.chance(0.5):
            args = ", ".join(f"{a} := {self.expr(t, scope, depth)}" for a, t in fn.inputs)
        else:
            args = ", ".join(self.expr(t, scope, depth) for _a, t in fn.inputs)
        return f"{fn.name}({args})"

    # ------------------------------------------------------------ statements

    def block(self, scope: Scope, depth: int, loops: int, size: tuple = (0, 3)) -> str:
        return "\n".join(self.stmt(scope, depth, loops) for _ in range(self.int_in(*size)))

    def stmt(self, scope: Scope, depth: int, loops: int) -> str:
        kinds = ["assign", "assign", "assign"]
        if depth < 3:
            kinds += ["if", "case", "for", "while", "repeat"]
        if scope.instances:
            kinds += ["fbcall", "fbcall"]
        if loops:
            kinds += ["exit", "continue"]
        kind = self.pick(kinds)
        if kind == "assign":
            return self.assign(scope, depth)
        if kind == "exit":
            return "EXIT;" if self.chance(0.5) else f"IF {self.expr(elem('BOOL'), scope, 2)} THEN EXIT; END_IF;"
        if kind == "continue":
            return f"IF {self.expr(elem('BOOL'), scope, 2)} THEN CONTINUE; END_IF;"
        if kind == "if":
            out = f"IF {self.expr(elem('BOOL'), scope)} THEN\n{self.block(scope, depth + 1, loops)}\n"
            for _ in range(self.int_in(0, 2)):
                out += f"ELSIF {self.expr(elem('BOOL'), scope)} THEN\n{self.block(scope, depth + 1, loops)}\n"
            if self.chance(0.5):
                out += f"ELSE\n{self.block(scope, depth + 1, loops)}\n"
            return out + "END_IF;"
        if kind == "case":
            return self.case(scope, depth, loops)
        if kind == "for":
            return self.for_loop(scope, depth, loops)
        if kind in ("while", "repeat"):
            return self.guarded_loop(kind, scope, depth, loops)
        return self.fb_call(scope, depth)

    def assign(self, scope: Scope, depth: int) -> str:
        targets = [leaf for leaf in scope.leaves if leaf.writable and leaf.parts[0] not in scope.counters]
        if not targets:
            return ";"
        leaf = self.pick(targets)
        return f"{self.place(leaf, scope, 1)} := {self.expr(leaf.ty, scope)};"

    def case(self, scope: Scope, depth: int, loops: int) -> str:
        enums = list(self.world.enums)
        if enums and self.chance(0.3):
            ty = Ty("enum", self.pick(enums))
            values = self.world.enums[ty.name]
            chosen = self.draw(st.lists(st.sampled_from(values), min_size=1, max_size=len(values), unique=True))
            arms = []
            while chosen:
                k = self.int_in(1, len(chosen))
                arms.append(", ".join(chosen[:k]))
                chosen = chosen[k:]
        else:
            ty = elem(self.pick(["INT", "DINT", "SINT", "UINT"]))
            lo = 0 if ty.name == "UINT" else -5
            starts = sorted(self.draw(st.lists(st.integers(lo, 20), min_size=1, max_size=4, unique=True)))
            arms = []
            for i, s in enumerate(starts):
                nxt = starts[i + 1] if i + 1 < len(starts) else 30
                if nxt - s > 1 and self.chance(0.3):
                    arms.append(f"{s}..{self.int_in(s + 1, nxt - 1)}")
                else:
                    arms.append(str(s))
        out = f"CASE {self.expr(ty, scope)} OF\n"
        for label in arms:
            out += f"{label}:\n{self.block(scope, depth + 1, loops)}\n"
        if self.chance(0.5):
            out += f"ELSE\n{self.block(scope, depth + 1, loops)}\n"
        return out + "END_CASE;"

    def for_loop(self, scope: Scope, depth: int, loops: int) -> str:
        counter = scope.counters[depth] if depth < len(scope.counters) else None
        if counter is None or counter in scope.counters[:depth]:
            return self.assign(scope, depth)
        if FOR_ANY_BOUNDS and self.chance(0.3):  # the counters are DINTs
            start = self.expr(elem("DINT"), scope, 2)
            end = self.pick(["2147483647", self.expr(elem("DINT"), scope, 2)])
        else:
            start, end = str(self.int_in(-3, 6)), str(self.int_in(-3, 8))
        step = self.pick(["", "", " BY 1", " BY 2", " BY -1", " BY 3"])
        body = self.block(scope, depth + 1, loops + 1)
        return f"FOR {counter} := {start} TO {end}{step} DO\n{body}\nEND_FOR;"

    def guarded_loop(self, kind: str, scope: Scope, depth: int, loops: int) -> str:
        guard = scope.guards[depth] if depth < len(scope.guards) else None
        if guard is None:
            return self.assign(scope, depth)
        cond = self.expr(elem("BOOL"), scope, 1)
        body = self.block(scope, depth + 1, loops + 1)
        if not self.chance(0.9):  # unguarded: the watchdog ends an endless one
            if kind == "while":
                return f"WHILE {cond} DO\n{body}\nEND_WHILE;"
            return f"REPEAT\n{body}\nUNTIL {cond}\nEND_REPEAT;"
        limit = self.int_in(0, 6)
        if kind == "while":
            return (
                f"{guard} := 0;\nWHILE {guard} < {limit} AND ({cond}) DO\n{guard} := {guard} + 1;\n{body}\nEND_WHILE;"
            )
        return (
            f"{guard} := 0;\nREPEAT\n{guard} := {guard} + 1;\n{body}\nUNTIL {guard} >= {limit} OR ({cond})\nEND_REPEAT;"
        )

    def fb_call(self, scope: Scope, depth: int) -> str:
        name, ty = self.pick(scope.instances)
        if ty.name in STANDARD_FBS:
            ins, outs = STANDARD_FBS[ty.name]
        else:
            pou = self.world.fbs[ty.name]
            ins, outs = pou.inputs, pou.outputs
        args = [f"{a} := {self.expr(t, scope, 1)}" for a, t in ins if self.chance(0.7)]
        targets = [leaf for leaf in scope.leaves if leaf.writable and leaf.parts[0] not in scope.counters]
        for a, t in outs:
            fits = [leaf for leaf in targets if leaf.ty == t]
            if fits and self.chance(0.3):
                args.append(f"{a} => {self.place(self.pick(fits), scope, 2)}")
        return f"{name}({', '.join(args)});"
