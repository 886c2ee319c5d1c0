"""What the tests of the simulated LTMR on the virtual bus share: node 40's
COB-IDs and the bench brought to a state (operational, running forward,
watching the master's heartbeat)."""

from __future__ import annotations

from softplc.runtime.devices.ltmr import registers as ltmr
from softplc.runtime.io.canopen.cia301 import (
    NMT_START,
)

from ...io.canopen.bench import write_ok

NODE = 40
TPDO1, RPDO1, TPDO4, RPDO4, EMCY, HEARTBEAT = 0x1A8, 0x228, 0x4A8, 0x528, 0x0A8, 0x728


def operational(bench, **kwargs):
    sim = bench.ltmr(NODE, **kwargs)
    bench.nmt(NMT_START, NODE)
    return sim


def running_forward(bench, **kwargs):
    sim = operational(bench, **kwargs)
    bench.send(RPDO1, "01 00 00 00 00 00")
    bench.run_ms(1500)  # past the 1 s start
    return sim


def watched(bench, fallback, registers=None):
    """Operational, watching the master's heartbeat (0x1016:01 = 0x007F01F4, 500 ms:
    digest 001 §1.5) with 682 = fallback, the motor running forward."""
    sim = bench.ltmr(NODE, registers={ltmr.REG_NETWORK_FALLBACK: fallback, **(registers or {})})
    assert bench.sdo_write(NODE, 0x1016, 1, 0x007F01F4, 4) == write_ok(0x1016, 1)
    bench.master_heartbeat_ms = 100
    bench.run_ms(100)
    bench.nmt(NMT_START, NODE)
    bench.send(RPDO1, "01 00 00 00 00 00")
    bench.run_ms(1500)
    return sim


def words(value: int) -> bytes:
    return value.to_bytes(2, "little")


def tpdo1(sim) -> bytes:
    return b"".join(words(sim.register(r)) for r in (455, 456, 457, 459))
