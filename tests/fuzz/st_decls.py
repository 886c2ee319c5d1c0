"""The declarations of a generated ST program (st_grammar.py): enumerations,
structures, globals, FUNCTIONs, FUNCTION_BLOCKs and the PROGRAM main, each
body generated with the variables it sees."""

from __future__ import annotations

from hypothesis import strategies as st

from .st_grammar import ELEMENTARY, STANDARD_FBS, Gen, Pou, Scope, Ty, elem


def _value_type(g: Gen, structs: bool = True, arrays: bool = True) -> Ty:
    options = ["elem"] * 6
    if g.world.enums:
        options.append("enum")
    if structs and g.world.structs:
        options.append("struct")
    if arrays:
        options.append("array")
    kind = g.pick(options)
    if kind == "enum":
        return Ty("enum", g.pick(g.world.enums))
    if kind == "struct":
        return Ty("struct", g.pick(g.world.structs))
    if kind == "array":
        dims = []
        for _ in range(g.int_in(1, 2)):
            lo = g.int_in(-3, 3)
            dims.append((lo, lo + g.int_in(0, 4)))
        inner = _value_type(g, structs=structs, arrays=False)
        return Ty("array", "", inner, tuple(dims))
    return elem(g.pick(ELEMENTARY))


def _init(g: Gen, ty: Ty) -> str:
    """An initial value (with its " := "), or ""."""
    if not g.chance(0.4):
        return ""
    if ty.kind in ("elem", "enum"):
        return f" := {g.literal(ty)}"
    if ty.kind == "array" and ty.elem is not None and ty.elem.kind in ("elem", "enum"):
        total = 1
        for lo, hi in ty.dims:
            total *= hi - lo + 1
        items = []
        while total:
            k = g.int_in(1, total)
            value = g.literal(ty.elem)
            items.append(value if k == 1 else f"{k}({value})")
            total -= k
        return f" := [{', '.join(items)}]"
    if ty.kind == "struct":
        fields = [(f, t) for f, t in g.world.structs[ty.name] if t.kind in ("elem", "enum")]
        chosen = [f"{f} := {g.literal(t)}" for f, t in fields if g.chance(0.5)]
        return f" := ({', '.join(chosen)})" if chosen else ""
    return ""


def _var_block(g: Gen, keyword: str, variables: list, inits: bool = True) -> str:
    if not variables:
        return ""
    lines = [f"    {n} : {t.decl()}{_init(g, t) if inits else ''};" for n, t in variables]
    return f"{keyword}\n" + "\n".join(lines) + "\nEND_VAR\n"


def _loop_vars(g: Gen) -> tuple[list, list]:
    n = g.int_in(0, 3)
    return [g.fresh("i") for _ in range(n)], [g.fresh("w") for _ in range(n)]


def _body(g: Gen, scope: Scope, counters: list, guards: list) -> str:
    scope.counters, scope.guards = counters, guards
    return g.block(scope, 0, 0, (1, 5))


def _enum(g: Gen) -> str:
    name = g.fresh("E")
    values = [f"{name}v{i}" for i in range(g.int_in(1, 4))]
    g.world.enums[name] = values
    if g.chance(0.3):  # explicit values, increasing
        start = g.int_in(0, 5)
        body = ", ".join(f"{v} := {start + 3 * i}" for i, v in enumerate(values))
    else:
        body = ", ".join(values)
    return f"TYPE {name} : ({body}); END_TYPE\n"


def _struct(g: Gen) -> str:
    name = g.fresh("S")
    fields = [(g.fresh("f"), _value_type(g)) for _ in range(g.int_in(1, 4))]
    lines = "\n".join(f"    {f} : {t.decl()}{_init(g, t) if t.kind in ('elem', 'enum') else ''};" for f, t in fields)
    g.world.structs[name] = fields
    return f"TYPE {name} :\nSTRUCT\n{lines}\nEND_STRUCT\nEND_TYPE\n"


def _function(g: Gen) -> str:
    name = g.fresh("Fn")
    result = elem(g.pick(ELEMENTARY))
    inputs = [(g.fresh("a"), _value_type(g, structs=False, arrays=False)) for _ in range(g.int_in(1, 3))]
    local = [(g.fresh("t"), _value_type(g)) for _ in range(g.int_in(0, 2))]
    counters, guards = _loop_vars(g)
    loops = [(v, elem("DINT")) for v in counters] + [(v, elem("INT")) for v in guards]
    scope = Scope(g.world, [*inputs, *local, *loops, (name, result), *g.world.globals], {n for n, _ in inputs})
    body = _body(g, scope, counters, guards)
    final = f"{name} := {g.expr(result, scope)};"
    text = (
        f"FUNCTION {name} : {result.decl()}\n"
        + _var_block(g, "VAR_INPUT", inputs, inits=False)
        + _var_block(g, "VAR", local + loops)
        + f"{body}\n{final}\nEND_FUNCTION\n"
    )
    g.world.functions.append(Pou("FUNCTION", name, inputs, [], result))
    return text


def _instances(g: Gen, n: int) -> list:
    kinds = list(STANDARD_FBS) + list(g.world.fbs)
    return [(g.fresh("fb"), Ty("fb", g.pick(kinds))) for _ in range(n)]


def _function_block(g: Gen) -> str:
    name = g.fresh("Blk")
    inputs = [(g.fresh("in"), _value_type(g, structs=False, arrays=False)) for _ in range(g.int_in(1, 3))]
    outputs = [(g.fresh("out"), _value_type(g, structs=False, arrays=False)) for _ in range(g.int_in(1, 3))]
    local = [(g.fresh("s"), _value_type(g)) for _ in range(g.int_in(0, 2))] + _instances(g, g.int_in(0, 2))
    counters, guards = _loop_vars(g)
    loops = [(v, elem("DINT")) for v in counters] + [(v, elem("INT")) for v in guards]
    scope = Scope(g.world, [*inputs, *outputs, *local, *loops, *g.world.globals], {n for n, _ in inputs})
    body = _body(g, scope, counters, guards)
    text = (
        f"FUNCTION_BLOCK {name}\n"
        + _var_block(g, "VAR_INPUT", inputs)
        + _var_block(g, "VAR_OUTPUT", outputs)
        + _var_block(g, "VAR", [(n, t) for n, t in local + loops if t.kind != "fb"])
        + _var_block(g, "VAR", [(n, t) for n, t in local if t.kind == "fb"], inits=False)
        + f"{body}\nEND_FUNCTION_BLOCK\n"
    )
    g.world.fbs[name] = Pou("FUNCTION_BLOCK", name, inputs, outputs)
    return text


def _program(g: Gen) -> str:
    variables = [(g.fresh("v"), _value_type(g)) for _ in range(g.int_in(2, 8))]
    instances = _instances(g, g.int_in(0, 3))
    constants = [(g.fresh("c"), elem(g.pick(["INT", "DINT", "REAL", "BOOL", "TIME"]))) for _ in range(g.int_in(0, 2))]
    counters, guards = _loop_vars(g)
    loops = [(v, elem("DINT")) for v in counters] + [(v, elem("INT")) for v in guards]
    plain = [(n, t) for n, t in variables if t.kind == "elem"]
    refs = [(g.fresh("r"), Ty("ref", "", t), n) for n, t in plain[: g.int_in(0, 2)]]
    every = [*variables, *instances, *constants, *loops, *g.world.globals, *((r, t) for r, t, _n in refs)]
    scope = Scope(g.world, every, set(), frozenset(n for n, _ in constants))
    body = "".join(f"{r} := REF({n});\n" for r, _t, n in refs) + _body(g, scope, counters, guards)
    const_block = ""
    if constants:
        lines = "\n".join(f"    {n} : {t.decl()} := {g.literal(t)};" for n, t in constants)
        const_block = f"VAR CONSTANT\n{lines}\nEND_VAR\n"
    return (
        "PROGRAM main\n"
        + _var_block(g, "VAR", variables + loops)
        + _var_block(g, "VAR", [(r, t) for r, t, _n in refs], inits=False)
        + _var_block(g, "VAR", instances, inits=False)
        + const_block
        + f"{body}\nEND_PROGRAM\n"
    )


@st.composite
def valid_programs(draw) -> str:
    g = Gen(draw)
    parts = [_enum(g) for _ in range(g.int_in(0, 2))]
    parts += [_struct(g) for _ in range(g.int_in(0, 2))]
    g.world.globals = [(g.fresh("g"), _value_type(g)) for _ in range(g.int_in(0, 3))]
    if g.world.globals:
        parts.append(_var_block(g, "VAR_GLOBAL", g.world.globals))
    parts += [_function(g) for _ in range(g.int_in(0, 2))]
    parts += [_function_block(g) for _ in range(g.int_in(0, 2))]
    parts.append(_program(g))
    return "\n".join(parts)
