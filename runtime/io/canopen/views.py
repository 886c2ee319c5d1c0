"""What the scan sees of the CANopen nodes: an immutable view of each node's
supervisor, published by the supervision side (the service, the receive
thread, the SDO worker) after every change and read by the scan thread
(CANOPEN_NODE, the status line, the monitors' details) without a lock.

The supervision side swaps in a new tuple of views (one attribute write,
atomic); the scan reads the tuple it finds. So the scan never waits for a
supervisor that is in the middle of a change, a frame being sent, or an
SDO configuration: it sees the state before or after, never half of it.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

from .cia301 import STATE_NAMES
from .node import Emergency, NodeState, NodeSupervisor


@dataclass(frozen=True)
class NodeView:
    node_id: int
    name: str
    mandatory: bool
    version: int  # the supervisor's version when the view was taken
    state: NodeState
    nmt_state: int | None
    message: str
    boots: int
    toggle_errors: int
    emergencies: int
    malformed: int
    emcy_history: tuple[Emergency, ...]

    @property
    def last_emcy(self) -> Emergency | None:
        return self.emcy_history[-1] if self.emcy_history else None

    @property
    def operational(self) -> bool:
        return self.state == NodeState.OPERATIONAL


def view_of(sup: NodeSupervisor, mandatory: bool) -> NodeView:
    """A supervisor as it is now (the supervision lock held)."""
    return NodeView(
        node_id=sup.node_id,
        name=sup.name,
        mandatory=mandatory,
        version=sup.version,
        state=sup.state,
        nmt_state=sup.nmt_state,
        message=sup.message,
        boots=sup.boots,
        toggle_errors=sup.toggle_errors,
        emergencies=sup.emergencies,
        malformed=sup.malformed,
        emcy_history=tuple(sup.emcy_history),
    )


def nodes_status(views: tuple[NodeView, ...], malformed: int) -> tuple[bool, str]:
    """The driver's status line with the bus up: (ok, text); not ok while a
    mandatory node is not operational, which the text names, with why."""
    bad = [v for v in views if v.mandatory and not v.operational]
    up = sum(v.operational for v in views)
    counted = f", {malformed} malformed" if malformed else ""
    if bad:
        v = bad[0]
        why = v.message or v.state.name.lower()
        return False, f"canopen: {up}/{len(views)} up{counted}; {v.name} ({v.node_id}): {why}"
    return True, f"canopen: {up}/{len(views)} up{counted}"


def node_details(view: NodeView, emcy_text: Callable | None) -> dict:
    """A node for the monitors (Driver.details)."""
    nmt = None if view.nmt_state is None else STATE_NAMES.get(view.nmt_state & 0x7F, f"0x{view.nmt_state:02X}")
    return {
        "id": view.node_id,
        "name": view.name,
        "mandatory": view.mandatory,
        "state": view.state.name,
        "nmt": nmt,
        "error": view.message,
        "boots": view.boots,
        "emergencies": view.emergencies,
        "emcy": [_emcy_details(emcy_text, e) for e in view.emcy_history],
    }


def _emcy_details(emcy_text: Callable | None, emcy: Emergency) -> dict:
    try:
        text = emcy_text(emcy.code, emcy.register, emcy.data) if emcy_text is not None else ""
    except Exception:  # a device's words are a nicety: the numbers are shown anyway
        text = ""
    return {
        "time_ns": emcy.time_ns,
        "code": emcy.code,
        "register": emcy.register,
        "data": emcy.data.hex(" "),
        "text": text or ("error reset" if emcy.code == 0 else ""),
    }
