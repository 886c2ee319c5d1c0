"""What a flood of NMT reset-node commands or bogus heartbeats costs the scan
(issue 31): a 10 ms task on the real clock, the CANopen master and the
simulated LTMR (node 40) on python-can's virtual bus, and a foreign node
sending one hostile frame a millisecond for the whole measurement.

Four runs: the boot (the first seconds from the start: node 40 reset,
configured by SDO, started), then, each after WARM_UP_S of scans (node 40
operational): quiet (no flood), the flood with the boot limit
(node.BOOT_BURST boots in BOOT_WINDOW_NS), the flood without it (BOOT_BURST
set out of reach: the master as it was, booting the node on every frame).
Printed per run: the boots the master started (reset communication frames
and configurations, counted on the bus), the scans' wake-up lateness (how
long after its release a scan began: median, 99th percentile, worst), the
longest tick, the longest the scan spent in the master's read_inputs +
write_outputs ("io max": what it waits for the bus side) and the overruns
(the task's counter).

--send-ms makes the PLC's adapter slow: every frame the master sends (NMT,
SYNC, its heartbeat, SDO requests, RPDOs) takes that long to go, as on a
loaded bus or with a full transmit queue (python-can's virtual bus with a
sleep in send, registered as the interface "slowvirtual"). A master whose
scan calls wait behind its sends shows it in "io max" and the lateness.

    python benchmarks/bench_canopen_flood.py                 # 10 s a run
    python benchmarks/bench_canopen_flood.py --seconds 3 --frame heartbeat --send-ms 2
"""

from __future__ import annotations

import argparse
import tempfile
import threading
import time
from pathlib import Path

import can
import can.interfaces
import can.util
from can.interfaces.virtual import VirtualBus

from softplc.runtime.config import config_from_dict
from softplc.runtime.engine.build import build_engine
from softplc.runtime.io.canopen import node as supervision

WARM_UP_S = 2.0
FRAMES = {"reset-node": (0x000, bytes([0x81, 40])), "heartbeat": (0x728, bytes([0x7F]))}
#: --send-ms: how long a frame of the master takes to go (seconds)
SEND_S = 0.0


def _masters(can_id: int) -> bool:
    """A frame the master sends: NMT, SYNC, its heartbeat, an SDO request, an RPDO."""
    return can_id in (0x000, 0x080, 0x77F) or 0x600 < can_id < 0x680 or (0x200 <= can_id < 0x600 and not can_id & 0x80)


class SlowBus(VirtualBus):
    """python-can's virtual bus whose sends of the master's frames take SEND_S."""

    def send(self, msg: can.Message, timeout: float | None = None) -> None:
        if SEND_S and _masters(msg.arbitration_id):
            time.sleep(SEND_S)
        super().send(msg, timeout)


def _register_slow_bus() -> None:
    """ "slowvirtual" in python-can's table of interfaces, as an installed plugin's."""
    can.interfaces.BACKENDS["slowvirtual"] = (__name__, "SlowBus")
    can.util.VALID_INTERFACES = can.util.VALID_INTERFACES | {"slowvirtual"}


PROGRAM = "PROGRAM Main\nVAR n : DINT; END_VAR\nn := n + 1;\nEND_PROGRAM\n"


def _config(tmp: Path, channel: str):
    (tmp / "main.st").write_text(PROGRAM)
    node = {
        "name": "motor",
        "id": 40,
        "eds": "ltmr",
        "heartbeat": "100ms",
        "heartbeat_timeout": "300ms",
        "tpdo": [{"number": 1, "configure": False, "map": [{"object": "2004:06", "address": "%IW100"}]}],
    }
    data = {
        "plc": {"programs": [str(tmp / "main.st")]},
        "task": [{"name": "Main", "interval": "10ms", "programs": ["Main"]}],
        "can": [{"name": "can0", "interface": "slowvirtual" if SEND_S else "virtual", "channel": channel}],
        "canopen": {"node_id": 127, "heartbeat": "100ms", "sdo_timeout": "1s", "retry": "1s", "node": [node]},
        "sim": [{"type": "ltmr", "node_id": 40}],
    }
    return config_from_dict(data, tmp / "plant.toml")


def run(seconds: float, frame: str | None, limit: bool, warm_up: bool = True) -> dict:
    channel = f"bench-flood-{time.monotonic_ns()}"
    burst = supervision.BOOT_BURST
    if not limit:
        supervision.BOOT_BURST = 10**9  # the master as it was: a boot on every frame
    try:
        with tempfile.TemporaryDirectory() as tmp:
            engine = build_engine(_config(Path(tmp), channel), virtual_time=False)
            spy = can.Bus(interface="virtual", channel=channel)
            boots = {"resets": 0, "configurations": 0}
            stop = threading.Event()

            def count(msg) -> None:
                if msg.arbitration_id == 0x000 and bytes(msg.data) == bytes([0x82, 40]):
                    boots["resets"] += 1
                elif msg.arbitration_id == 0x628 and bytes(msg.data[:4]) == bytes.fromhex("2B 17 10 00"):
                    boots["configurations"] += 1

            def flood() -> None:
                can_id, data = FRAMES[frame]  # type: ignore[index]
                msg = can.Message(arbitration_id=can_id, data=data, is_extended_id=False)
                while not stop.wait(0.001):
                    spy.send(msg)

            late: list = []
            longest = [0]
            io_longest = [0]
            tick = engine.tick
            master = next(d for d in engine.drivers if d.name == "canopen")
            read_inputs, write_outputs = master.read_inputs, master.write_outputs

            def timed_io(call):
                def timed_call(image) -> None:
                    t0 = time.perf_counter_ns()
                    call(image)
                    io_longest[0] = max(io_longest[0], time.perf_counter_ns() - t0)

                return timed_call

            master.read_inputs, master.write_outputs = timed_io(read_inputs), timed_io(write_outputs)

            def timed() -> None:
                late.append(engine.clock.now_ns() - engine.next_release())
                t0 = time.perf_counter_ns()
                tick()
                longest[0] = max(longest[0], time.perf_counter_ns() - t0)

            engine.tick = timed
            engine.start()
            notifier = can.Notifier(spy, [count], timeout=0.1)
            flooder = threading.Thread(target=flood, daemon=True) if frame else None
            try:
                if warm_up:
                    engine.run(duration_ns=int(WARM_UP_S * 1e9))
                late.clear()
                longest[0] = io_longest[0] = 0
                boots.update(resets=0, configurations=0)
                overruns = sum(t.stats.overruns for t in engine.tasks)
                if flooder is not None:
                    flooder.start()
                engine.run(duration_ns=int(seconds * 1e9))
                overruns = sum(t.stats.overruns for t in engine.tasks) - overruns
            finally:
                stop.set()
                if flooder is not None:
                    flooder.join()
                notifier.stop()
                engine.stop()
                spy.shutdown()
    finally:
        supervision.BOOT_BURST = burst
    lateness = sorted(late)
    return {
        **boots,
        "scans": len(lateness),
        "late_p50_ms": lateness[len(lateness) // 2] / 1e6,
        "late_max_ms": lateness[-1] / 1e6,
        "late_p99_ms": lateness[int(len(lateness) * 0.99)] / 1e6,
        "tick_max_ms": longest[0] / 1e6,
        "io_max_ms": io_longest[0] / 1e6,
        "overruns": overruns,
    }


def main() -> None:
    global SEND_S
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seconds", type=float, default=10.0)
    parser.add_argument("--frame", choices=sorted(FRAMES), default="reset-node")
    parser.add_argument("--send-ms", type=float, default=0.0, help="how long each frame of the master takes to go")
    args = parser.parse_args()
    SEND_S = args.send_ms / 1000
    if SEND_S:
        _register_slow_bus()
    runs = [
        ("boot", None, True, False),
        ("quiet", None, True, True),
        ("flood, limited", args.frame, True, True),
        ("flood, no limit", args.frame, False, True),
    ]
    print(f"{args.seconds:g} s a run, a {args.frame} frame every ms in the floods, {args.send_ms:g} ms a master's send")
    print(
        f"{'run':<16} {'resets':>7} {'configs':>8} {'scans':>6} {'late p50':>9} {'late p99':>9} {'late max':>9} "
        f"{'tick max':>9} {'io max':>9} {'overruns':>9}"
    )
    for name, frame, limit, warm_up in runs:
        r = run(args.seconds, frame, limit, warm_up)
        print(
            f"{name:<16} {r['resets']:>7} {r['configurations']:>8} {r['scans']:>6} {r['late_p50_ms']:>7.2f}ms "
            f"{r['late_p99_ms']:>7.2f}ms {r['late_max_ms']:>7.2f}ms {r['tick_max_ms']:>7.2f}ms "
            f"{r['io_max_ms']:>7.2f}ms {r['overruns']:>9}"
        )


if __name__ == "__main__":
    main()
