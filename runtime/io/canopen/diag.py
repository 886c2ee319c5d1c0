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
    """CANOPEN_NODE[id] and CANOPEN_MASTER, from the views of the master's
    node supervisors (views.py), in the scan thread."""

    def __init__(self, globals_obj) -> None:
        nodes = _global(globals_obj, "CANOPEN_NODE")
        self._nodes = [StructWriter(s) for s in nodes] if nodes is not None else []
        self._master = StructWriter(_global(globals_obj, "CANOPEN_MASTER"))
        self._seen: dict = {}  # node id -> version written
        self._master_seen: tuple | None = None  # the master's view written last

    def update(self, views, master: tuple) -> None:
        """views: a NodeView (views.py) of every configured node; master:
        CANOPEN_MASTER's values in MASTER_FIELDS order."""
        if master != self._master_seen:
            self._master_seen = master
            self._master.set(**dict(zip(MASTER_FIELDS, master, strict=True)))
        for view in views:
            node_id = view.node_id
            if self._seen.get(node_id) == view.version or node_id >= len(self._nodes):
                continue
            self._seen[node_id] = view.version
            emcy = view.last_emcy
            self._nodes[node_id].set(
                Configured=True,
                State=int(view.state),
                Operational=view.state == NodeState.OPERATIONAL,
                Lost=view.state == NodeState.LOST,
                HeartbeatLost=view.state == NodeState.LOST,
                Missing=view.state == NodeState.MISSING,
                NmtState=view.nmt_state or 0,
                Boots=view.boots,
                GuardingErrors=view.toggle_errors,
                Emergencies=view.emergencies,
                EmcyCode=emcy.code if emcy else 0,
                EmcyRegister=emcy.register if emcy else 0,
                EmcyData=int.from_bytes(emcy.data[:4], "little") if emcy else 0,
                Malformed=view.malformed,
                Message=view.message if view.state != NodeState.OPERATIONAL else "",
            )
