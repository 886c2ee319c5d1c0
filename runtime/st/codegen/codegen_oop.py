"""Code generation of object-oriented ST: methods, properties, EXTENDS,
interfaces.

A FUNCTION_BLOCK that EXTENDS another is a Python subclass of the base's
class (only its own variables in its ``__slots__``); a METHOD is a Python
method ``m_<name>(self, inputs..., _o_<output>=None)`` built as a FUNCTION
is, so a call ``inst.M(...)`` is one attribute lookup and one call, and an
override is Python's own dispatch. A PROPERTY is two methods,
``pg_<name>(self)`` and ``ps_<name>(self, value)``. SUPER^.M() calls the
base class's function directly; SUPER^() its ``__call__``. A variable of an
interface type holds the instance itself (None when unassigned); a call
through it checks for None first (a ``reference`` fault at the call).
Plain FB calls are as before: nothing here is on their path.
"""

from __future__ import annotations

from .. import ast as A
from .. import types as T
from ..check.oop import all_interfaces, fb_init_inputs
from ..check.symbols import CallInfo, POUInfo, PropertyInfo
from .codegen_base import CodeGenBase


class OopGen(CodeGenBase):
    """Methods, properties, subclasses and interface calls."""

    @staticmethod
    def _class_order(pous: list) -> list:
        """The POUs with every base class before the classes extending it."""
        out: list = []
        placed: set = set()

        def place(p: POUInfo) -> None:
            if id(p) in placed:
                return
            if p.base is not None:
                place(p.base)
            placed.add(id(p))
            out.append(p)

        for p in pous:
            place(p)
        return out

    def _class_header(self, pou: POUInfo) -> str:
        if pou.base is not None:
            return f"class {pou.pyname}({pou.base.pyname}):"
        return f"class {pou.pyname}:"

    def _oop_members(self, pou: POUInfo) -> None:
        """The methods and property accessors of a FUNCTION_BLOCK's class,
        and the names of the interfaces it implements (for ?= and
        __QUERYINTERFACE)."""
        if pou.kind == "PROGRAM" and (pou.methods or pou.properties):
            self.emit("_INST_ = None")  # the program's instance, for Prog.M() elsewhere
        itfs = sorted(i.name.upper() for i in all_interfaces(pou))
        if itfs:
            self.emit(f"_ITFS_ = {tuple(itfs)!r}")  # interface names: checked identifiers
        for m in pou.methods.values():
            if "ABSTRACT" not in m.modifiers:
                self._method_def(m)
        for p in pou.properties.values():
            for acc in (p.getter, p.setter):
                if acc is not None and "ABSTRACT" not in p.modifiers:
                    self._method_def(acc)

    def _fb_init_calls(self, pou: POUInfo) -> None:
        """At the end of __init__, the FB_init methods of the block and its
        bases, base first, with bInitRetains TRUE and bInCopyCode FALSE:
        every start initialises all variables (retained values are written
        into the instances afterwards); the module's _INIT_FLAGS hold the
        two, (FALSE, TRUE) while an online change makes its instances. TwinCAT "Behavior with derived
        function blocks": the base's FB_init runs, then the derived one's."""
        if pou.kind == "PROGRAM" and (pou.methods or pou.properties):
            # CODESYS: a PROGRAM is one instance; Prog.M() from another POU
            # reaches the one created last (the task's, after a restart too)
            self.emit(f"{pou.pyname}._INST_ = self")
        chain = []
        p: POUInfo | None = pou
        while p is not None:
            m = p.methods.get("FB_INIT")
            if m is not None:
                chain.append(m)
            p = p.base
        for m in reversed(chain):
            assert m.fb is not None
            names = tuple(v.pyname for v in m.params("VAR_INPUT")[2:])
            further = f", **_fb_args(_fbi, {names!r})" if names else ""  # pynames: checked identifiers
            self.emit(f"{m.fb.pyname}.{m.pyname}(self, *_INIT_FLAGS{further})")

    @staticmethod
    def _init_params(pou: POUInfo) -> str:
        """The parameter of __init__ that takes the FB_init inputs of a
        declaration (a dict by their Python names), where FB_init has them."""
        return ", _fbi=None" if pou.kind == "FUNCTION_BLOCK" and fb_init_inputs(pou) else ""

    def _fb_init_construct(self, ty: T.Type, plan: tuple) -> str:
        """A new instance given FB_init inputs: ``FB_x({'v_nstart': 5})``,
        with the instance's own initial values, if any, set around it."""
        _kind, bound, inner = plan
        t = T.resolve(ty)
        assert isinstance(t, T.FBType)  # the checker gives FB_init inputs to instances only
        args = ", ".join(f"{p.pyname!r}: {self.coerce(self.ex(e), e.ty, p.type, e)}" for p, e in bound)
        ctor = f"{t.pou.pyname}()"
        return self._aggregate_expr(ty, inner).replace(ctor, f"{t.pou.pyname}({{{args}}})", 1)

    def _method_def(self, m: POUInfo) -> None:
        saved = self.fn
        self.emit("")
        self._function(m, method=True)
        self.fn = saved

    # ------------------------------------------------------------ uses

    def _instance_code(self, inst: A.Expr | None) -> str:
        """The instance a member is taken of: self for THIS^/SUPER^ and
        the block's own; an interface's value (None when it holds none)."""
        if inst is None:
            return self.fn.self_name
        if isinstance(inst, A.Name) and isinstance(inst.sym, POUInfo):  # Prog.M(), Prog.P
            prog = inst.sym
            here = self.fn.pou
            if here is prog or (here is not None and here.fb is prog):
                return self.fn.self_name
            # a program no task runs is created at its first use (it exists in CODESYS)
            return f"({prog.pyname}._INST_ or {prog.pyname}())"
        # through an interface that holds none, None has no such method:
        # Python's AttributeError is the NULL interface fault (st/faults.py)
        return self.ex(inst)

    def _method_invoke(self, e: A.Call, info: CallInfo) -> str:
        m = info.pou
        assert m is not None  # a method call names its METHOD
        if info.func == "body":  # SUPER^(): the base's body on this instance
            return f"{m.pyname}.__call__({self.fn.self_name})"
        args = self._function_args(info, positional=True)
        if info.func == "super":  # SUPER^.M(): the base's own, no dispatch
            assert m.fb is not None
            sep = ", " if args else ""
            return f"{m.fb.pyname}.{m.pyname}({self.fn.self_name}{sep}{args})"
        return f"{self._instance_code(info.instance)}.{m.pyname}({args})"

    @staticmethod
    def _action_invoke(info: CallInfo, inst: str) -> str:
        """inst.a_act(); SUPER^.Act(): the base's own action, not the
        derived block's that overwrites it (CODESYS lets a derived block
        overwrite an inherited action as it does a method)."""
        act = info.func
        base = info.instance
        if isinstance(base, A.Deref) and isinstance(base.base, A.Name) and base.base.sym == "SUPER":
            return f"{act.pou.pyname}.{act.pyname}({inst})"
        return f"{inst}.{act.pyname}()"

    def _accessor_call(self, e: A.Name | A.Member, acc: POUInfo, arg: str) -> str:
        """inst.pg_p() / inst.ps_p(v); SUPER^.P: the base's accessor itself."""
        base = e.base if isinstance(e, A.Member) else None
        if isinstance(base, A.Deref) and isinstance(base.base, A.Name) and base.base.sym == "SUPER":
            assert acc.fb is not None
            sep = ", " if arg else ""
            return f"{acc.fb.pyname}.{acc.pyname}({self.fn.self_name}{sep}{arg})"
        return f"{self._instance_code(base)}.{acc.pyname}({arg})"

    def _property_read(self, e: A.Name | A.Member) -> str:
        prop: PropertyInfo = e.sym
        assert prop.getter is not None  # the checker refuses reading one without GET
        return self._accessor_call(e, prop.getter, "")

    def _property_store(self, target: A.Name | A.Member, code: str) -> None:
        prop: PropertyInfo = target.sym
        assert prop.setter is not None  # the checker refuses assigning one without SET
        self.emit(self._accessor_call(target, prop.setter, code))

    def _query_code(self, src: A.Expr, itf: T.Type) -> str:
        """The instance behind src when it implements itf, else None."""
        name = T.resolve(itf).name.upper()
        return f"_query_itf({self.ex(src)}, {name!r})"

    def _this_code(self, e: A.Deref) -> str | None:
        if isinstance(e.base, A.Name) and e.base.sym in ("THIS", "SUPER"):
            return self.fn.self_name
        return None
