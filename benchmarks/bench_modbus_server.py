"""What the Modbus TCP server ([modbus_server]) costs the scan: the default
plant on the real clock, its scans timed (Engine.tick, the after_tick
snapshot included), with an HMI on 127.0.0.1 polling 1,000 holding
registers (%MW0..%MW999: 8 requests of 125) beside the same plant whose
server has no client.

    none      the server listens, no client
    100ms     a client polls the 1,000 registers every 100 ms (an HMI's pace)
    flat-out  a client polls them back to back (the worst a client can do)

Rounds of ROUND_S seconds, the modes in a rotating order, each round on a
fresh engine; printed per mode: the mean and the 99th percentile of the scan
time over all rounds, the ratio of its mean to the "none" mean of the same
round (median over the rounds: the VM's load moves from round to round),
and how long one poll of the 1,000 registers took (median).

    python benchmarks/bench_modbus_server.py            # about 60 s
    python benchmarks/bench_modbus_server.py --quick    # about 20 s
"""

from __future__ import annotations

import argparse
import statistics
import threading
import time

from pymodbus.client import ModbusTcpClient

from softplc.runtime.config import default_config_path, load_config
from softplc.runtime.config.servers import ServerConfig
from softplc.runtime.engine.build import build_engine
from softplc.runtime.surfaces.host import Surfaces

MODES = ("none", "100ms", "flat-out")
FIRST, REGISTERS, PER_REQUEST = 1024, 1000, 125  # holding 1024.. = %MW0..


def one_round(config, mode: str, seconds: float) -> tuple:
    engine = build_engine(config)
    server = ServerConfig("modbus_server", "127.0.0.1", 0, ("%Q*", "%M*"), 100_000_000, {"unit": 0})
    surfaces = Surfaces(engine, {"modbus_server": server})
    surfaces.start()
    ticks: list = []
    polls: list = []
    tick = engine.tick

    def timed_tick() -> None:
        t0 = time.perf_counter_ns()
        tick()
        ticks.append(time.perf_counter_ns() - t0)

    engine.tick = timed_tick  # type: ignore[method-assign]
    stop = threading.Event()

    def poll() -> None:
        client = ModbusTcpClient("127.0.0.1", port=surfaces.handles["modbus_server"].port)
        client.connect()
        while not stop.is_set():
            t0 = time.perf_counter()
            for address in range(FIRST, FIRST + REGISTERS, PER_REQUEST):
                reply = client.read_holding_registers(address, count=PER_REQUEST)
                assert not reply.isError(), reply
            polls.append(time.perf_counter() - t0)
            if mode == "100ms":
                stop.wait(0.1)
        client.close()

    poller = threading.Thread(target=poll) if mode != "none" else None
    try:
        engine.start()
        engine.run(duration_ns=200_000_000)  # the buses up
        ticks.clear()
        if poller is not None:
            poller.start()
        engine.run(duration_ns=int(seconds * 1e9))
    finally:
        stop.set()
        if poller is not None and poller.is_alive():
            poller.join()
        surfaces.stop()
        engine.stop()
    return ticks, polls


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--quick", action="store_true", help="fewer, shorter rounds")
    args = parser.parse_args()
    rounds, seconds = (2, 2.0) if args.quick else (4, 4.0)
    config = load_config(default_config_path())
    ticks: dict = {m: [] for m in MODES}
    polls: dict = {m: [] for m in MODES}
    ratios: dict = {m: [] for m in MODES}
    for r in range(rounds):
        order = MODES[r % 3 :] + MODES[: r % 3]
        means = {}
        for mode in order:
            t, p = one_round(config, mode, seconds)
            ticks[mode] += t
            polls[mode] += p
            means[mode] = statistics.mean(t)
        for mode in MODES:
            ratios[mode].append(means[mode] / means["none"])
    print(f"default plant, real clock, {rounds} rounds of {seconds:.0f} s per mode")
    print(f"{'mode':10} {'scans':>7} {'mean us':>8} {'p99 us':>8} {'vs none':>8} {'1,000 registers':>16}")
    for mode in MODES:
        t = sorted(ticks[mode])
        p99 = t[int(0.99 * (len(t) - 1))] / 1e3
        poll = f"{statistics.median(polls[mode]) * 1e3:.1f} ms x{len(polls[mode])}" if polls[mode] else "-"
        print(
            f"{mode:10} {len(t):7d} {statistics.mean(t) / 1e3:8.0f} {p99:8.0f} "
            f"{statistics.median(ratios[mode]):8.2f} {poll:>16}"
        )


if __name__ == "__main__":
    main()
