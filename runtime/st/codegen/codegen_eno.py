"""Code generation of EN/ENO (IEC 61131-3 ed.3 6.6.1.6, st/check/checker_eno.py).

A call with EN runs only when EN is TRUE; when it is FALSE nothing of the
call happens (no input is passed, no output written, a FUNCTION's value is
its result variable's initial value) but ENO, which becomes FALSE. The
code of a call without EN and ENO is the plain call: they cost only where
they are written.
"""

from __future__ import annotations

from .. import ast as A
from .. import types as T
from ..check.symbols import CallInfo
from ..rtlib import refs
from .codegen_base import CodeGenBase


class EnoGen(CodeGenBase):
    """Calls under EN, standard functions' ENO."""

    def gated_value(self, info: CallInfo, code: str, ty: T.Type | None, eno_out: A.Expr | None) -> str:
        """code (a call's value) under the call's EN; eno_out: an ENO =>
        target the call itself does not write (a standard function's)."""
        default = self._default_code(ty) if ty is not None else "False"
        if eno_out is not None:
            ref = self.ref_code(eno_out)
            code = f"{self.const(refs.eno_ok)}({ref}, {code})"
            default = f"{self.const(refs.eno_skip)}({ref}, {default})"
        if info.en is None:
            return code
        return f"({code} if {self.ex(info.en)} else {default})"

    def function_gate(self, info: CallInfo, code: str) -> str:
        """A user FUNCTION's call under EN: its own ENO output (if bound)
        is set FALSE instead of the call."""
        if info.en is None:
            return code
        pou = info.pou
        assert pou is not None  # a call of kind 'function' names its POU
        default = self._default_code(pou.result.type) if pou.result is not None else "False"
        for p, target, _negated in info.outputs:
            if p.name.upper() == "ENO":
                default = f"{self.const(refs.eno_skip)}({self.ref_code(target)}, {default})"
        return f"({code} if {self.ex(info.en)} else {default})"

    def fb_skipped(self, info: CallInfo, inst: str) -> None:
        """The else branch of an FB call under EN: the instance's ENO and
        the ENO => target become FALSE, nothing else changes."""
        pou = info.pou
        assert pou is not None  # an FB call names its POU
        eno = pou.vars.get("ENO")
        if eno is not None and eno.section == "VAR_OUTPUT":
            self.emit(f"{inst}.{eno.pyname} = False")
        else:
            self.emit("pass")
        for p, target, negated in info.outputs:
            if p.name.upper() == "ENO":
                self.emit_store(target, "True" if negated else "False", T.BOOL, None, trusted=True)
