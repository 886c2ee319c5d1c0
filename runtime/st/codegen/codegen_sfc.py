"""Code generation of an SFC body (IEC 61131-3 ed.3 6.7): the cycle of a
PROGRAM's or FUNCTION_BLOCK's SFC network, on rt_sfc.py.

The POU's ``__call__`` becomes, per cycle::

    _steps = (self.v_fill, self.v_heat, ...)     # the step variables
    _sfc.elapse(_steps, _NOW_MS)                  # step.T as the cycle starts
    _f0 = _steps[0].v_x and (<condition>)         # enabled transitions only,
    ...                                           # all before any step changes
    _sfc.evolve(_steps, (_f0, ...), _NOW_MS)      # clear and activate at once
    _qa = _sfc.control(_steps, (<durations>,), _NOW_MS, (self.v_fill, None))
    if self.v_fill.v_a:                           # Fill.A: while Q, and once
        self.a_fill()                             # more (Q FALSE) as Q falls
    self.v_lamp = _qa[1][0]                       # a BOOL variable as action: Q

Transitions are evaluated and fire in priority order (checker_sfc.py sorts
them); their shape, and each step's associations, are one constant
(``rt_sfc.Network``).
"""

from __future__ import annotations

from .. import types as T
from ..check.symbols import POUInfo
from ..rtlib.rt_sfc import STEP_TYPE, Network
from .codegen_base import CodeGenBase

# The instance's action control blocks: a slot of the POU's class, copied
# and assigned with the instance like an aggregate (its _copy/_assign).
SFC_SLOT = "_sfc"
SFC_SLOT_TYPE = STEP_TYPE  # any aggregate type: the copy methods only ask is_aggregate


class SfcGen(CodeGenBase):
    """The SFC network of a POU's body."""

    def _sfc_network(self, pou: POUInfo) -> tuple[Network, list]:
        """The Network constant and the durations' expressions (by slot)."""
        info = pou.sfc
        durations: list = []
        assocs = []
        for step_assocs in info.assocs:
            row = []
            for action, qualifier, duration in step_assocs:
                slot = -1
                if duration is not None:
                    slot = len(durations)
                    durations.append(duration)
                row.append((action, qualifier, slot))
            assocs.append(tuple(row))
        transitions = tuple((t.sources, t.targets) for t in info.transitions)
        return Network(transitions, tuple(assocs), len(info.actions)), durations

    def _sfc_init(self, pou: POUInfo) -> None:
        """In __init__: the action control blocks."""
        net, _ = self._sfc_network(pou)
        self.emit(f"self.{SFC_SLOT} = _SfcState({self.const(net)})")

    def _sfc_body(self, pou: POUInfo) -> None:
        """The body of __call__: one cycle of the network."""
        info = pou.sfc
        _, durations = self._sfc_network(pou)
        self.pos = pou.node.sfc.pos
        steps = "".join(f"self.{s.pyname}, " for s in info.steps)
        self.emit(f"_steps = ({steps})")
        self.emit(f"_sfc = self.{SFC_SLOT}")
        self.emit("_sfc.elapse(_steps, _NOW_MS)")
        fires = []
        for k, t in enumerate(info.transitions):
            self.pos = t.node.pos
            fire = f"_f{k}"
            fires.append(fire)
            enabled = " and ".join(f"_steps[{i}].v_x" for i in t.sources)
            if t.node.cond is not None:
                self.emit(f"{fire} = {enabled} and ({self.ex(t.node.cond)})")
                continue
            self.emit(f"{fire} = False")
            self.emit(f"if {enabled}:")
            self.indent += 1
            if t.name_sym is not None:
                self.emit(f"{t.name_sym.pyname} = False")
            self._body(t.node.body or [])
            if t.name_sym is not None:
                self.pos = t.node.pos
                self.emit(f"{fire} = {t.name_sym.pyname}")
            self.indent -= 1
        self.pos = pou.node.sfc.pos
        self.emit(f"_sfc.evolve(_steps, ({''.join(f + ', ' for f in fires)}), _NOW_MS)")
        times = "".join(f"{self.ex(d)}, " for d in durations)
        flags = ""
        if any(a.flags is not None for a in info.actions):
            each = "".join(f"self.{a.flags.pyname}, " if a.flags is not None else "None, " for a in info.actions)
            flags = f", ({each})"
        self.emit(f"_qa = _sfc.control(_steps, ({times}), _NOW_MS{flags})")
        for j, action in enumerate(info.actions):
            self.pos = action.pos
            if action.flags is not None:  # an ACTION: its method (codegen_pous.py), while A
                self.emit(f"if self.{action.flags.pyname}.v_a:")
                self.emit(f"    self.{action.method}()")
            else:
                self.emit_store(action.target, f"_qa[{j}][0]", T.BOOL, None, trusted=True)
