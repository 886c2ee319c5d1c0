"""What the CANopen master writes to a node after its boot-up, by SDO, in
the SDO worker (sdo.py): its error control (heartbeat or guarding, the
master's heartbeat to watch), the configured SDO writes, and every PDO:
remapped when configure = true (CiA 301: invalidate, clear, entries, count,
transmission type, inhibit time, event timer, validate), else only its
COB-ID read back. The first write that fails stops it (ConfigFailed, with
the configuration key)."""

from __future__ import annotations

from .cia301 import (
    COB_ID_INVALID,
    CONSUMER_HEARTBEAT,
    GUARD_TIME,
    LIFE_TIME_FACTOR,
    PRODUCER_HEARTBEAT,
    restricted_cob_id,
)
from .pdo import PdoBinding, default_cob_id
from .sdo import SdoJob, SdoWorker


class ConfigFailed(Exception):
    pass


def boot_steps(cfg, od, master_id: int) -> list[tuple[int, int, bytes, str]]:
    """(index, sub-index, data, config key) of a node's error control writes."""
    steps = [(PRODUCER_HEARTBEAT, 0, cfg.heartbeat_ms.to_bytes(2, "little"), f"{cfg.key}.heartbeat")]
    if cfg.guard_time_ms:
        steps.append((GUARD_TIME, 0, cfg.guard_time_ms.to_bytes(2, "little"), f"{cfg.key}.guard_time"))
        steps.append((LIFE_TIME_FACTOR, 0, bytes([cfg.life_time_factor]), f"{cfg.key}.life_time_factor"))
    # a node without a heartbeat consumer (no 1016h) is not told the default
    if cfg.master_timeout_ms and od.get_variable(CONSUMER_HEARTBEAT, 1) is not None:
        value = (master_id << 16) | cfg.master_timeout_ms
        steps.append((CONSUMER_HEARTBEAT, 1, value.to_bytes(4, "little"), f"{cfg.key}.master_timeout"))
    return steps


def configure_node(worker: SdoWorker, node_id: int, od, steps: list, bindings: list, timeout: float) -> None:
    """The steps, then every PDO binding; ConfigFailed at the first error."""
    for index, sub, data, key in steps:
        _sdo(worker, node_id, index, sub, data, key, timeout)
    for binding in bindings:
        _configure_pdo(worker, node_id, od, binding, timeout)


def _sdo(worker: SdoWorker, node_id: int, index: int, sub: int, data: bytes | None, key: str, timeout: float) -> bytes:
    job = SdoJob(node_id, index, sub, data, timeout)
    worker.transfer(job)
    if job.error:
        raise ConfigFailed(f"{key}: {job.error}")
    return job.received


def _configure_pdo(worker: SdoWorker, nid: int, od, b: PdoBinding, timeout: float) -> None:
    """CiA 301 PDO (re)mapping: invalidate, clear, write the entries, set
    their number, set the parameters, validate. configure = false only
    reads the COB-ID the node uses."""

    def sdo(index: int, sub: int, data: bytes | None, key: str) -> bytes:
        return _sdo(worker, nid, index, sub, data, key, timeout)

    raw = sdo(b.comm_index, 1, None, f"{b.key}: read COB-ID")
    cob = int.from_bytes(raw[:4].ljust(4, b"\0"), "little")
    if not b.configure:
        if cob & COB_ID_INVALID:
            raise ConfigFailed(
                f"{b.key}: the node's {b.direction.upper()} {b.number} is not valid "
                f"(COB-ID 0x{cob:08X}); set configure = true"
            )
        if restricted_cob_id(cob & 0x7FF):
            # taken as it is, NMT (0x000) or heartbeat frames would be read as
            # this TPDO, or this RPDO sent as them
            raise ConfigFailed(
                f"{b.key}: the node's {b.direction.upper()} {b.number} has COB-ID 0x{cob & 0x7FF:03X}, "
                "which CiA 301 keeps for other services; set configure = true"
            )
        b.cob_id = cob & 0x7FF
        return
    if restricted_cob_id(cob & 0x7FF):  # 0 (none), or one no PDO may use
        cob = default_cob_id(b.direction, b.number, nid)
    cob_id = cob & 0x7FF
    what = f"{b.key}"
    sdo(b.comm_index, 1, (cob_id | COB_ID_INVALID).to_bytes(4, "little"), what)
    sdo(b.map_index, 0, b"\0", what)
    for i, e in enumerate(b.entries, start=1):
        sdo(b.map_index, i, e.mapping_value.to_bytes(4, "little"), e.key)
    sdo(b.map_index, 0, bytes([len(b.entries)]), what)
    sdo(b.comm_index, 2, bytes([b.transmission]), f"{b.key}.transmission")
    # A TPDO's inhibit time and event timer are written even when 0: a node's
    # own default may not be (the FC 280 inhibits its TPDOs for 30 ms,
    # manual 003 §4.1.4), and the configuration says what is wanted.
    comm = od.get(b.comm_index)
    tpdo = b.direction == "tpdo"
    if (tpdo or b.inhibit_us) and comm is not None and 3 in comm:
        sdo(b.comm_index, 3, (b.inhibit_us // 100).to_bytes(2, "little"), f"{b.key}.inhibit")
    if (tpdo or b.event_ms) and comm is not None and 5 in comm:
        sdo(b.comm_index, 5, b.event_ms.to_bytes(2, "little"), f"{b.key}.event")
    sdo(b.comm_index, 1, cob_id.to_bytes(4, "little"), what)
    b.cob_id = cob_id
