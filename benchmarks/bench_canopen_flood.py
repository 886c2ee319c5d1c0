"""What a flood of NMT reset-node commands or bogus heartbeats costs the scan
(issue 31): a 10 ms task on the real clock, the CANopen master and the
simulated LTMR (node 40) on python-can's virtual bus, and a foreign node
sending one hostile frame a millisecond for the whole measurement.

Three runs, each after WARM_UP_S of scans (node 40 operational): quiet (no
flood), the flood with the boot limit (node.BOOT_BURST boots in
BOOT_WINDOW_NS), the flood without it (BOOT_BURST set out of reach: the
master as it was, booting the node on every frame). Printed per run: the
boots the master started (reset communication frames and configurations,
counted on the bus), the scans' worst and 99th-percentile wake-up lateness
(how long after its release a scan began), the longest tick and the
overruns (the task's counter).

    python benchmarks/bench_canopen_flood.py                 # 10 s a run
    python benchmarks/bench_canopen_flood.py --seconds 3 --frame heartbeat
"""

from __future__ import annotations

import argparse
import tempfile
import threading
import time
from pathlib import Path

import can

from softplc.runtime.config import config_from_dict
from softplc.runtime.engine.build import build_engine
from softplc.runtime.io.canopen import node as supervision

WARM_UP_S = 2.0
FRAMES = {"reset-node": (0x000, bytes([0x81, 40])), "heartbeat": (0x728, bytes([0x7F]))}
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
        "can": [{"name": "can0", "interface": "virtual", "channel": channel}],
        "canopen": {"node_id": 127, "heartbeat": "100ms", "sdo_timeout": "1s", "retry": "1s", "node": [node]},
        "sim": [{"type": "ltmr", "node_id": 40}],
    }
    return config_from_dict(data, tmp / "plant.toml")


def run(seconds: float, frame: str | None, limit: bool) -> dict:
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
            tick = engine.tick

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
                engine.run(duration_ns=int(WARM_UP_S * 1e9))
                late.clear()
                longest[0] = 0
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
        "late_max_ms": lateness[-1] / 1e6,
        "late_p99_ms": lateness[int(len(lateness) * 0.99)] / 1e6,
        "tick_max_ms": longest[0] / 1e6,
        "overruns": overruns,
    }


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seconds", type=float, default=10.0)
    parser.add_argument("--frame", choices=sorted(FRAMES), default="reset-node")
    args = parser.parse_args()
    runs = [("quiet", None, True), ("flood, limited", args.frame, True), ("flood, no limit", args.frame, False)]
    print(f"{args.seconds:g} s a run, a {args.frame} frame every ms in the floods")
    print(
        f"{'run':<16} {'resets':>7} {'configs':>8} {'scans':>6} {'late max':>9} {'late p99':>9} "
        f"{'tick max':>9} {'overruns':>9}"
    )
    for name, frame, limit in runs:
        r = run(args.seconds, frame, limit)
        print(
            f"{name:<16} {r['resets']:>7} {r['configurations']:>8} {r['scans']:>6} {r['late_max_ms']:>7.2f}ms "
            f"{r['late_p99_ms']:>7.2f}ms {r['tick_max_ms']:>7.2f}ms {r['overruns']:>9}"
        )


if __name__ == "__main__":
    main()
