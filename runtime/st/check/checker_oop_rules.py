"""The rules of object-oriented ST the checker applies once the members
are declared (checker_oop.py): overrides (E141, E143), ABSTRACT (E142),
IMPLEMENTS (E145), FB_init, FB_exit and FB_reinit (E149)."""

from __future__ import annotations

from .. import ast as A
from .. import types as T
from .checker_base import CheckerBase
from .conversions import same_type
from .oop import access_of, all_interfaces, find_method, find_property
from .symbols import POUInfo, PropertyInfo


class OopRules(CheckerBase):
    """Overrides, ABSTRACT, IMPLEMENTS and the lifecycle methods."""

    def _check_override(self, pou: POUInfo, info: POUInfo, m: A.Method) -> None:
        inherited = find_method(pou.base, info.name.upper()) if pou.base is not None else None
        if inherited is None or info.name.upper() == "FB_INIT":
            return  # each FB_init of the chain runs, with the inputs it declares (checker_fbinit.py)
        if "FINAL" in inherited.modifiers:
            self.d.error("E143", f"{inherited.fb.name}.{inherited.name} is FINAL: it cannot be overridden", m.pos)
        elif not self._same_signature(inherited, info):
            self.d.error(
                "E141",
                f"{pou.name}.{info.name} overrides {inherited.fb.name}.{info.name} with another signature",
                m.pos,
                "an override has the same return type and the same inputs, outputs and in-outs, in order",
            )

    def _check_property_override(self, pou: POUInfo, prop: PropertyInfo) -> None:
        inherited = find_property(pou.base, prop.name.upper()) if pou.base is not None else None
        if inherited is None:
            return
        if "FINAL" in inherited.modifiers:
            self.d.error("E143", f"{inherited.owner.name}.{prop.name} is FINAL: it cannot be overridden", prop.pos)
        elif not same_type(inherited.type, prop.type):
            self.d.error("E141", f"{pou.name}.{prop.name} overrides a PROPERTY of type {inherited.type}", prop.pos)

    @staticmethod
    def _same_signature(a: POUInfo, b: POUInfo) -> bool:
        def sig(p: POUInfo) -> list:
            return [(v.name.upper(), v.section, v.type) for v in p.params("VAR_INPUT", "VAR_OUTPUT", "VAR_IN_OUT")]

        ra, rb = a.return_type, b.return_type
        if ra is None or rb is None:
            if ra is not rb:
                return False
        elif not same_type(ra, rb):
            return False
        sa, sb = sig(a), sig(b)
        return len(sa) == len(sb) and all(
            x[0] == y[0] and x[1] == y[1] and same_type(x[2], y[2]) for x, y in zip(sa, sb)
        )

    def _check_abstract(self, pou: POUInfo) -> None:
        """IEC 61131-3 ed.3 6.6.5.6: an ABSTRACT method has no body and
        lives in an ABSTRACT FB; a FB that is not ABSTRACT defines every
        abstract method it inherits."""
        abstract_fb = "ABSTRACT" in pou.modifiers
        for m in pou.methods.values():
            if "ABSTRACT" not in m.modifiers:
                continue
            if m.node.body:
                self.d.error(
                    "E142",
                    f"the ABSTRACT METHOD {m.name} has a body",
                    m.node.pos,
                    "remove ABSTRACT, or the body (a derived FUNCTION_BLOCK defines it)",
                )
            if not abstract_fb:
                self.d.error(
                    "E142",
                    f"{pou.name} has an ABSTRACT METHOD {m.name}; declare the block ABSTRACT",
                    m.node.pos,
                    f"FUNCTION_BLOCK ABSTRACT {pou.name}",
                )
        if abstract_fb:
            return
        p = pou.base
        while p is not None:
            for key, m in p.methods.items():
                if "ABSTRACT" in m.modifiers and "ABSTRACT" in find_method(pou, key).modifiers:
                    self.d.error(
                        "E142",
                        f"{pou.name} does not define the ABSTRACT METHOD {m.name} of {p.name}",
                        pou.node.pos,
                        f"add METHOD {m.name} to {pou.name}, or declare it FUNCTION_BLOCK ABSTRACT",
                    )
            p = p.base

    def _check_implements(self, pou: POUInfo) -> None:
        if "ABSTRACT" in pou.modifiers:
            return
        for itf in all_interfaces(pou):
            for key, sig in itf.methods.items():
                m = find_method(pou, key)
                if m is None:
                    self.d.error(
                        "E145",
                        f"{pou.name} does not define METHOD {sig.name} of INTERFACE {itf.name}",
                        pou.node.pos,
                        f"add METHOD {sig.name} with the interface's signature",
                    )
                elif not self._same_signature(sig, m):
                    self.d.error(
                        "E145",
                        f"{pou.name}.{m.name} has another signature than in INTERFACE {itf.name}",
                        m.node.pos,
                        "the same return type and the same inputs, outputs and in-outs, in order",
                    )
                elif access_of(m.modifiers) != "PUBLIC":
                    self.d.error("E145", f"{pou.name}.{m.name} implements {itf.name}: it must be PUBLIC", m.node.pos)
            for key, sig in itf.properties.items():
                p = find_property(pou, key)
                if p is None or not same_type(p.type, sig.type):
                    self.d.error(
                        "E145",
                        f"{pou.name} does not define PROPERTY {sig.name} : {sig.type} of INTERFACE {itf.name}",
                        pou.node.pos,
                    )
                elif (sig.getter and not p.getter) or (sig.setter and not p.setter):
                    self.d.error("E145", f"{pou.name}.{p.name} lacks the GET or SET of INTERFACE {itf.name}", p.pos)

    # CODESYS "Method: FB_Init, FB_Reinit, FB_Exit": their inputs (C0119)
    _LIFECYCLE = {
        "FB_INIT": ("bInitRetains", "bInCopyCode"),
        "FB_EXIT": ("bInCopyCode",),
        "FB_REINIT": (),
    }

    def _check_lifecycle(self, pou: POUInfo) -> None:
        """FB_init(bInitRetains, bInCopyCode), FB_exit(bInCopyCode) and
        FB_reinit(), which the engine calls itself, take exactly these BOOL
        inputs; FB_init may take further inputs, set where an instance is
        declared (CODESYS "FB_init": ``fb : FB_X(nStart := 5);``)."""
        for key, names in self._LIFECYCLE.items():
            m = pou.methods.get(key)
            if m is None:
                continue
            got = [(v.name.upper(), v.type) for v in m.params("VAR_INPUT", "VAR_OUTPUT", "VAR_IN_OUT")]
            if key == "FB_INIT" and all(v.section == "VAR_INPUT" for v in m.params("VAR_INPUT", "VAR_OUTPUT")):
                got = got[: len(names)]  # further inputs: set where an instance is declared (checker_fbinit.py)
            if [n for n, _t in got] != [n.upper() for n in names] or any(t is not T.BOOL for _n, t in got):
                want = "; ".join(f"{n} : BOOL" for n in names) or "nothing"
                self.d.error(
                    "E149",
                    f"{m.name} takes the inputs {want}",
                    m.node.pos,
                    f"declare VAR_INPUT {want}; END_VAR" if names else "remove its inputs and outputs",
                )

    def _check_instances(self) -> None:
        """No variable holds an instance of an ABSTRACT FUNCTION_BLOCK."""
        syms = list(self.globals.values())
        for pou in self.pous.values():
            syms += [v for v in pou.vars.values() if v.owner is pou]
            for m in pou.methods.values():
                syms += [v for v in m.vars.values() if v.owner is m]
        for v in syms:
            if v.section == "VAR_IN_OUT":
                continue
            t = T.resolve(v.type)
            while isinstance(t, T.ArrayType):
                t = T.resolve(t.elem)
            if isinstance(t, T.FBType) and v.fb_init is None:
                self._fb_init_required(t.pou, v.name, v.pos)  # checker_fbinit.py
            if isinstance(t, T.FBType) and t.pou is not None and "ABSTRACT" in t.pou.modifiers:
                self.d.error(
                    "E142",
                    f"{t.name} is ABSTRACT: '{v.name}' cannot be an instance of it",
                    v.pos,
                    f"declare an instance of a FUNCTION_BLOCK that EXTENDS {t.name}, or a REF_TO/interface",
                )
