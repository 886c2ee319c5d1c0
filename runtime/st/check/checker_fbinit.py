"""The checker's FB_init inputs set where an instance is declared.

CODESYS "Method FB_init" and TwinCAT "FB_init": FB_init(bInitRetains,
bInCopyCode) may declare further inputs; they are set in the declaration
of each instance, ``fb : FB_X(nStart := 5);`` (or, TwinCAT, positionally
with a variable: ``fb : FB_X(other);``), and per element of an array,
``fbs : ARRAY[1..3] OF FB_X[(nStart := 1), (nStart := 2), (nStart := 3)];``.
An input without an initial value must be set ("Any additional variables
specified there must be set when declaring a function block instance",
TwinCAT). The parser reads ``FB_X(nStart := 5)`` as a based enumeration;
here a base that names a FUNCTION_BLOCK makes it an instance.

The initial value plan of such a variable is ``("fbinit", [(input,
Expr)], plan)`` (codegen_oop.py builds the instance with those inputs).
Code: E170.
"""

from __future__ import annotations

from typing import Any

from .. import ast as A
from .. import types as T
from .checker_base import CheckerBase, Scope
from .oop import fb_init_inputs
from .symbols import POUInfo, VarSymbol


class FbInitChecks(CheckerBase):
    """FB_init inputs of declarations."""

    def fb_init_spec(self, spec: A.TypeSpec) -> tuple:
        """(the type declared, its FB_init arguments or None): ("one",
        [(name or None, Expr, Pos)], Pos) or ("each", [StructInit], Pos)."""
        if isinstance(spec, A.EnumTypeSpec) and isinstance(spec.base, A.NamedType):
            pou = self.pous.get(spec.base.name.upper())
            if pou is not None and pou.kind == "FUNCTION_BLOCK":
                args = [
                    (name, value, pos) if value is not None else (None, A.Name(name, pos=pos), pos)
                    for name, value, pos in spec.values
                ]
                return spec.base, ("one", args, spec.pos)
        if isinstance(spec, A.ArrayTypeSpec) and spec.fb_inits is not None:
            return spec, ("each", spec.fb_inits, spec.pos)
        return spec, None

    def _check_fb_init_var(self, sym: VarSymbol, scope: Scope) -> None:
        """sym.init_value with the FB_init inputs of its declaration."""
        kind, args, pos = sym.fb_init
        inner = self.init_value(sym.type, sym.init, scope, sym.name) if sym.init is not None else None
        t = T.resolve(sym.type)
        if sym.section in ("VAR_IN_OUT", "VAR_EXTERNAL"):
            self.d.error("E170", f"'{sym.name}' is a {sym.section}: it designates an instance declared elsewhere", pos)
        elif kind == "one":
            assert isinstance(t, T.FBType)  # fb_init_spec: the base names a FUNCTION_BLOCK
            bound = self._fb_init_args(t.pou, args, pos, scope)
            sym.init_value = ("fbinit", bound, inner) if bound is not None else inner
            return
        else:
            sym.init_value = self._fb_init_array(sym, t, args, pos, scope)
            return
        sym.init_value = inner

    def _fb_init_array(self, sym: VarSymbol, t: T.Type, inits: list, pos: A.Pos, scope: Scope) -> Any:
        elem = T.resolve(t.elem) if isinstance(t, T.ArrayType) else None
        if not isinstance(t, T.ArrayType) or not isinstance(elem, T.FBType):
            self.d.error("E170", f"'{sym.name}' is not an array of FUNCTION_BLOCK instances", pos)
            return None
        if sym.init is not None or len(t.dims) != 1:
            self.d.error(
                "E170",
                f"'{sym.name}': FB_init inputs per element are for a one-dimensional array without := initial value",
                pos,
                "set the elements' inputs in the code, or declare the instances one by one",
            )
            return None
        lo, hi = t.dims[0]
        if len(inits) > hi - lo + 1:
            self.d.error("E170", f"{len(inits)} FB_init input lists for {hi - lo + 1} elements of '{sym.name}'", pos)
            return None
        runs: list = []
        for init in inits:
            args = [(name, value, p) for name, value, p in init.fields]
            bound = self._fb_init_args(elem.pou, args, init.pos, scope)
            runs.append((1, ("fbinit", bound, None) if bound is not None else None))
        rest = hi - lo + 1 - len(inits)
        if rest:
            self._fb_init_required(elem.pou, sym.name, pos)
            runs.append((rest, None))
        return ("array", runs)

    def _fb_init_args(self, pou: POUInfo, args: list, pos: A.Pos, scope: Scope) -> list | None:
        """[(input, Expr)] bound to pou's FB_init inputs, or None (reported)."""
        params = fb_init_inputs(pou)
        if not params:
            self.d.error(
                "E170",
                f"{pou.name} has no FB_init inputs to set",
                pos,
                "declare METHOD FB_init with VAR_INPUT bInitRetains : BOOL; bInCopyCode : BOOL; and further inputs",
            )
            return None
        by_name = {p.name.upper(): p for p in params}
        bound: dict = {}
        ok = True
        for i, (name, value, p) in enumerate(args):
            if name is None:
                param = params[i] if i < len(params) else None
                if param is None:
                    self.d.error("E170", f"FB_init of {pou.name} takes {len(params)} further input(s)", p)
                    ok = False
                    continue
            else:
                param = by_name.get(name.upper())
                if param is None:
                    self.d.error(
                        "E170",
                        f"FB_init of {pou.name} has no input '{name}'",
                        p,
                        self._suggest(name.upper(), [q.name for q in params]),
                    )
                    ok = False
                    continue
            if param.name.upper() in bound:
                self.d.error("E170", f"FB_init input '{param.name}' is set twice", p)
                ok = False
                continue
            vty = self.expr(value, scope, expected=param.type)
            if vty is None or not self.check_convertible(vty, param.type, value, f"FB_init input '{param.name}'"):
                ok = False
            bound[param.name.upper()] = (param, value)
        missing = [q.name for q in params if q.init is None and q.name.upper() not in bound]
        if missing:
            self.d.error(
                "E170",
                f"the FB_init input(s) {', '.join(missing)} of {pou.name} are not set",
                pos,
                f"set them where the instance is declared: inst : {pou.name}({missing[0]} := ...);",
            )
            ok = False
        return list(bound.values()) if ok else None

    def _fb_init_required(self, pou: POUInfo | None, what: str, pos: A.Pos) -> None:
        """E170 where an instance of pou is declared without FB_init inputs
        it has to be given."""
        missing = [q.name for q in fb_init_inputs(pou) if q.init is None]
        if pou is not None and missing:
            self.d.error(
                "E170",
                f"the FB_init input(s) {', '.join(missing)} of {pou.name} are not set for '{what}'",
                pos,
                f"declare it as {what} : {pou.name}({missing[0]} := ...);",
            )
