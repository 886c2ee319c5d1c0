"""The checker's EN/ENO: the execution control of functions and FBs.

IEC 61131-3 ed.3 6.6.1.6 (Table 18): a call may pass a BOOL ``EN``; when it
is FALSE the body is not executed and ``ENO`` is reset to FALSE, otherwise
ENO is set TRUE before the body runs, which may assign it. Every user
FUNCTION and FUNCTION_BLOCK has them without declaring them (the standard's
implicit EN/ENO): ENO is a BOOL VAR_OUTPUT made the first time a body, a
caller (``ENO => ok``) or a reader (``inst.ENO``) names it, so a POU that
never does pays nothing. A POU may declare its own ``ENO : BOOL`` output
(the same ENO); a declared ``EN`` input is an ordinary input. The standard
functions take EN/ENO too when called formally (``SQRT(EN := c, IN := x,
ENO => ok)``).
"""

from __future__ import annotations

from dataclasses import dataclass

from .. import ast as A
from .. import types as T
from .checker_base import CheckerBase, Scope
from .symbols import CallInfo, POUInfo, VarSymbol, pyname


@dataclass
class Gate:
    """The EN and ENO arguments taken out of a standard function's call."""

    en: A.Expr | None = None
    eno: A.Expr | None = None
    ok: bool = True


class EnEnoChecks(CheckerBase):
    """EN/ENO on calls and the implicit ENO of a POU."""

    def implicit_eno(self, pou: POUInfo | None) -> VarSymbol | None:
        """The POU's ENO output, made now if the POU has none (FUNCTION and
        FUNCTION_BLOCK only: a PROGRAM is not called)."""
        if pou is None or pou.kind not in ("FUNCTION", "FUNCTION_BLOCK"):
            return None
        sym = pou.vars.get("ENO")
        if sym is None:
            sym = VarSymbol("ENO", "VAR_OUTPUT", T.BOOL, pou.node.pos, pyname("v_", "ENO"), pou)
            sym.init_value = False
            pou.vars["ENO"] = sym
        return sym

    def check_declared_eno(self, pou: POUInfo) -> None:
        """E045: a declared ENO is the POU's ENO, so it is a BOOL output."""
        sym = pou.vars.get("ENO")
        if sym is None or pou.kind not in ("FUNCTION", "FUNCTION_BLOCK"):
            return
        be = T.base_elementary(sym.type)
        if sym.section != "VAR_OUTPUT" or be is None or not be.is_bool:
            self.d.error(
                "E045",
                f"ENO is the enable output of {pou.name}: it must be a BOOL VAR_OUTPUT, not {sym.section} {sym.type}",
                sym.pos,
                "declare it in VAR_OUTPUT as ENO : BOOL, or leave it out (every FUNCTION and FUNCTION_BLOCK has one)",
            )

    def en_argument(self, a: A.Arg, info: CallInfo, scope: Scope) -> None:
        """EN := expr of a call: the condition the call runs under."""
        if a.output or a.value is None:
            self.d.error("E046", "EN is an input: pass it with EN := condition", a.pos)
            return
        if info.en is not None:
            self.d.error("E041", "parameter 'EN' is given twice", a.pos)
            return
        ty = self.expr(a.value, scope, expected=T.BOOL)
        if ty is not None:
            self.check_convertible(ty, T.BOOL, a.value, "EN")
        info.en = a.value

    def split_en_eno(self, e: A.Call, scope: Scope) -> Gate:
        """Take EN and ENO out of a standard function's arguments (e.args
        keeps the others); checks both."""
        gate = Gate()
        rest = []
        probe = CallInfo("std")
        for a in e.args:
            name = a.name.upper() if a.name is not None else None
            if name == "EN":
                self.en_argument(a, probe, scope)
                gate.ok = gate.ok and probe.en is not None
            elif name == "ENO":
                if not a.output:
                    self.d.error("E046", "ENO is an output: bind it with ENO => variable", a.pos)
                    gate.ok = False
                elif a.value is not None:
                    tty = self.lvalue(a.value, scope)
                    if tty is not None:
                        self.check_convertible(T.BOOL, tty, A.Name("ENO", pos=a.pos, ty=T.BOOL), "output 'ENO'")
                        gate.eno = a.value
                    else:
                        gate.ok = False
            else:
                rest.append(a)
        gate.en = probe.en
        if gate.en is not None or gate.eno is not None:
            e.args = rest
        return gate

    def attach_gate(self, e: A.Call, gate: Gate) -> None:
        """The checked standard call runs under the gate: no folding (the
        ENO target is written at run time)."""
        if gate.en is None and gate.eno is None:
            return
        if isinstance(e.target, CallInfo):
            e.target.en = gate.en
            e.target.eno = gate.eno
            e.const = None
            if gate.eno is not None:
                self._mark_boxed(gate.eno, Scope(None))
