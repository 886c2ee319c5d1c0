"""CANopen master figures on python-can's virtual bus, each beside a baseline
measured in the same run, in real time (threads as on a plant PC).

1. Received-PDO throughput: a sender blasts TPDO1 frames of the booted
   simulated LTMR (node 40) at the master as fast as the virtual bus takes
   them; the master's receive path (CanEndpoint + CanopenDriver._on_frame,
   which keeps the newest frame per PDO for the next cycle's inputs) must
   take every one (lost = 0). Printed: frames/s and CPU time per frame
   (process CPU / frames, sender included), against a bare python-can
   Notifier with an empty listener on the same bus. Then the scan side:
   read_inputs copying the newest frame into the image, per cycle.
2. SDO round trips per second: expedited uploads of 2004:06 (register 455)
   from the simulated LTMR through the master's SDO worker (the READ_VAR
   path: queue, worker thread, canopen SdoClient), against canopen's own
   SdoClient on a bare canopen.Network on the same bus.

    python benchmarks/bench_canopen.py              # about 20 s
    python benchmarks/bench_canopen.py --quick
"""

from __future__ import annotations

import argparse
import threading
import time
from pathlib import Path

import can
import canopen

from softplc.runtime.config import config_from_dict
from softplc.runtime.devices.ltmr.sim import LtmrSimulator
from softplc.runtime.engine.clock import RealClock
from softplc.runtime.image.memory import ProcessImage
from softplc.runtime.io.can import settings_of
from softplc.runtime.io.can.bus import BusSettings, CanEndpoint, open_bus
from softplc.runtime.io.canopen.master import CanopenDriver
from softplc.runtime.io.canopen.sdo import SdoJob

CHANNEL = "bench-canopen"
TPDO1 = 0x1A8


def _config():
    return config_from_dict(
        {
            "plc": {"programs": [str(Path(__file__).resolve().parents[1] / "st_programs" / "blink.st")]},
            "can": [{"name": "can0", "interface": "virtual", "channel": CHANNEL}],
            "canopen": {
                "node_id": 127,
                "heartbeat": "100ms",
                "sdo_timeout": "500ms",
                "node": [
                    {
                        "name": "motor",
                        "id": 40,
                        "eds": "ltmr",
                        "heartbeat": "0ms",
                        "master_timeout": False,
                        "tpdo": [
                            {
                                "number": 1,
                                "configure": False,
                                "map": [
                                    {"object": f"2004:{s}", "address": f"%IW{i}"}
                                    for i, s in enumerate(("06", "07", "08", "0A"))
                                ],
                            }
                        ],
                    }
                ],
            },
        },
        base_dir=".",
    )


def _wait(predicate, limit_s: float, what: str) -> None:
    end = time.monotonic() + limit_s
    while not predicate():
        if time.monotonic() > end:
            raise SystemExit(f"{what}: not within {limit_s} s")
        time.sleep(0.001)


def _blast(sender: CanEndpoint, n: int) -> None:
    for i in range(n):
        sender.send(TPDO1, i.to_bytes(8, "little"))


def pdo_throughput(driver: CanopenDriver, n: int) -> dict:
    settings = BusSettings("virtual", CHANNEL)
    sender = CanEndpoint(open_bus(settings), name="blaster")
    before = driver.endpoint.received
    cpu0, t0 = time.process_time(), time.perf_counter()
    _blast(sender, n)
    _wait(lambda: driver.endpoint.received - before >= n, 60, "master received every frame")
    wall, cpu = time.perf_counter() - t0, time.process_time() - cpu0
    got = driver.endpoint.received - before
    image = ProcessImage("iec")
    driver.read_inputs(image)
    last = int.from_bytes(bytes(image.areas["I"][0:8]), "little")
    sender.stop()
    # baseline: the same frames into a bare Notifier with an empty listener, on a
    # channel of their own (no other receiver), as the master had it
    bare_settings = BusSettings("virtual", CHANNEL + "-bare")
    sender = CanEndpoint(open_bus(bare_settings), name="blaster")
    bare_bus = open_bus(bare_settings)
    counted = [0]

    def listener(_msg):
        counted[0] += 1

    notifier = can.Notifier(bare_bus, [listener], timeout=0.1)
    cpu0, t0 = time.process_time(), time.perf_counter()
    _blast(sender, n)
    _wait(lambda: counted[0] >= n, 60, "bare listener received every frame")
    bare_wall, bare_cpu = time.perf_counter() - t0, time.process_time() - cpu0
    notifier.stop()
    bare_bus.shutdown()
    sender.stop()
    # the scan side: one fresh frame per cycle copied into the image
    cycles = 20000
    t0 = time.perf_counter()
    for i in range(cycles):
        with driver._lock:
            driver._rx_fresh[driver.nodes[40].tpdos[0]] = i.to_bytes(8, "little")
        driver.read_inputs(image)
    read_us = (time.perf_counter() - t0) / cycles * 1e6
    return {
        "frames": n,
        "lost": n - got,
        "newest_in_image": last == n - 1,
        "rate": n / wall,
        "cpu_us": cpu / n * 1e6,
        "bare_rate": n / bare_wall,
        "bare_cpu_us": bare_cpu / n * 1e6,
        "read_inputs_us": read_us,
    }


def sdo_round_trips(driver: CanopenDriver, n: int) -> dict:
    done = threading.Event()
    t0 = time.perf_counter()
    for _ in range(n):
        job = SdoJob(40, 0x2004, 0x06, None, 0.5, on_done=lambda _j: done.set())
        done.clear()
        driver.worker.submit(job)
        done.wait(5)
        if job.error:
            raise SystemExit(job.error)
    ours = n / (time.perf_counter() - t0)
    network = canopen.Network()
    network.connect(interface="virtual", channel=CHANNEL)
    node = canopen.RemoteNode(40, canopen.ObjectDictionary())
    network.add_node(node)
    t0 = time.perf_counter()
    for _ in range(n):
        node.sdo.upload(0x2004, 0x06)
    bare = n / (time.perf_counter() - t0)
    network.disconnect()
    return {"n": n, "rate": ours, "bare_rate": bare}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="fewer frames and round trips")
    args = ap.parse_args()
    frames, trips = (20_000, 300) if args.quick else (200_000, 3000)
    cfg = _config()
    clock = RealClock()
    sim = LtmrSimulator(40, settings=BusSettings("virtual", CHANNEL), clock=clock)
    driver = CanopenDriver(cfg.canopen, settings_of(cfg.can[0]), clock=clock)
    sim.start()
    driver.start()
    try:
        _wait(lambda: driver.status().ok, 10, "node 40 operational")
        s = sdo_round_trips(driver, trips)
        sim.stop()  # from here on only the blaster sends TPDO1, and only the master receives
        p = pdo_throughput(driver, frames)
    finally:
        driver.stop()
        sim.stop()
    print("1. received PDOs into the master (virtual bus, real time)")
    print(
        f"   master:   {p['rate']:10,.0f} frames/s  {p['cpu_us']:6.1f} us CPU/frame  "
        f"lost {p['lost']} of {p['frames']:,}  newest frame in the image: {p['newest_in_image']}"
    )
    print(
        f"   baseline: {p['bare_rate']:10,.0f} frames/s  {p['bare_cpu_us']:6.1f} us CPU/frame  "
        "(bare python-can Notifier, empty listener)"
    )
    print(
        f"   ratio:    {p['rate'] / p['bare_rate']:.2f} of the baseline's rate, "
        f"{p['cpu_us'] / p['bare_cpu_us']:.2f}x its CPU per frame"
    )
    print(f"   scan side: read_inputs with one fresh TPDO per cycle: {p['read_inputs_us']:.2f} us")
    print("2. SDO round trips (expedited upload of 2004:06 from the simulated LTMR)")
    print(f"   master (READ_VAR path, worker thread): {s['rate']:8,.0f} /s")
    print(f"   baseline (canopen SdoClient, bare):    {s['bare_rate']:8,.0f} /s")
    print(f"   ratio: {s['rate'] / s['bare_rate']:.2f}")


if __name__ == "__main__":
    main()
