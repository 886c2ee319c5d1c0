"""CANOPEN_NODE[id] and CANOPEN_MASTER (fblocks/comm/canopen_diag.st) as
the program sees them, filled by the CANopen master. Written only when
something changed, so the scan pays (almost) nothing for them."""

from __future__ import annotations

from ...program import StructWriter
from ...program import global_variable as _global
from .node import NodeState

#: CANOPEN_MASTER's fields, in the order of the master's view (CanopenDriver._master_view)
MASTER_FIELDS = (
    "BusOk",
    "NodesConfigured",
    "NodesOperational",
    "FramesReceived",
    "FramesSent",
    "SendErrors",
    "Malformed",
)


class CanopenDiag:
    """CANOPEN_NODE[id] and CANOPEN_MASTER, from the master's node
    supervisors (runtime/io/canopen/node.py)."""

    def __init__(self, globals_obj) -> None:
        nodes = _global(globals_obj, "CANOPEN_NODE")
        self._nodes = [StructWriter(s) for s in nodes] if nodes is not None else []
        self._master = StructWriter(_global(globals_obj, "CANOPEN_MASTER"))
        self._seen: dict = {}  # node id -> version written
        self._master_seen: tuple | None = None  # the master's view written last

    def update(self, snapshot, master: tuple) -> None:
        """snapshot: (node id, version, node) for every configured node;
        master: CANOPEN_MASTER's values in MASTER_FIELDS order."""
        if master != self._master_seen:
            self._master_seen = master
            self._master.set(**dict(zip(MASTER_FIELDS, master, strict=True)))
        for node_id, version, node in snapshot:
            if self._seen.get(node_id) == version or node_id >= len(self._nodes):
                continue
            self._seen[node_id] = version
            sup = node.sup
            emcy = sup.last_emcy
            self._nodes[node_id].set(
                Configured=True,
                State=int(sup.state),
                Operational=sup.state == NodeState.OPERATIONAL,
                Lost=sup.state == NodeState.LOST,
                HeartbeatLost=sup.state == NodeState.LOST,
                Missing=sup.state == NodeState.MISSING,
                NmtState=sup.nmt_state or 0,
                Boots=sup.boots,
                GuardingErrors=sup.toggle_errors,
                Emergencies=sup.emergencies,
                EmcyCode=emcy.code if emcy else 0,
                EmcyRegister=emcy.register if emcy else 0,
                EmcyData=int.from_bytes(emcy.data[:4], "little") if emcy else 0,
                Malformed=sup.malformed,
                Message=sup.message if sup.state != NodeState.OPERATIONAL else "",
            )
