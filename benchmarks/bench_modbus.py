"""Modbus TCP master figures on loopback (127.0.0.1 only), each beside a
baseline measured in the same run against the same server, in real time.

The server is the simulated Eaton DA1 drive (unit 1; a pymodbus TCP server
on a free port of 127.0.0.1, runtime/io/modbus/line.py); every request is
FC03, 6 holding registers from offset 5 (IDs 6..11). Client and server share
one process, so the CPU time per transaction includes the server's share.

1. baseline: pymodbus's ModbusTcpClient.read_holding_registers in a tight
   loop.
2. link: ModbusLink.transact of the same request in a tight loop: what a
   connection's worker runs per transaction (request check, connect check,
   frame gap (none on TCP), error mapping, Outcome).
3. channel: a ModbusDriver with one cyclic channel at the shortest period
   allowed (1 ms), its worker thread running for a fixed wall time while this
   thread calls read_inputs every 1 ms as a scan would (the double-buffer
   hand-over into %IW100); transactions counted from the channel's stats,
   errors must be 0, and how many scans found fresh data. The period caps it
   at 1000/s; its ratio is against the baseline's overall rate.
4. MODBUS_EXCHANGE (the MODBUS_REQUEST path): request() from this thread,
   the connection's worker thread transacts, collect() polled (sleep(0)
   between polls) until the activity bit drops; one after the other, on a
   driver with no channels.
1, 2 and 4 are connected at once and run N transactions each in 20 rounds,
one chunk of each per round back to back, the order rotating; their ratio is
the median over the rounds of rate / baseline rate in the same round (the
VM's load swings chunk rates by 2x, a paired ratio stays steady).

    python benchmarks/bench_modbus.py              # about 15 s
    python benchmarks/bench_modbus.py --quick      # about 5 s
"""

from __future__ import annotations

import argparse
import socket
import statistics
import time

from pymodbus.client import ModbusTcpClient

from softplc.runtime.devices.eaton.model import EatonDriveModel
from softplc.runtime.devices.eaton.registers import Family
from softplc.runtime.engine.clock import RealClock
from softplc.runtime.image.address import parse_address
from softplc.runtime.image.memory import ProcessImage
from softplc.runtime.io.modbus import ModbusChannelConfig, ModbusConnectionConfig
from softplc.runtime.io.modbus.line import SimulatedModbusLine
from softplc.runtime.io.modbus.link import LinkSettings, ModbusLink, Transaction
from softplc.runtime.io.modbus.master import ModbusDriver

HOST = "127.0.0.1"  # loopback only
UNIT, FUNCTION, OFFSET, COUNT = 1, 3, 5, 6
CONNECTION = "drive"
WARM_UP = 200
ROUNDS = 20


def _free_port() -> int:
    with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as s:
        s.bind((HOST, 0))
        return s.getsockname()[1]


class Side:
    """One way of doing the transaction: run(k) does k of them, raising on a
    bad answer; the chunks' wall and CPU times add up in s and cpu."""

    def __init__(self, run) -> None:
        self.run = run
        self.n, self.s, self.cpu = 0, 0.0, 0.0
        self.rates: list = []

    def chunk(self, k: int) -> None:
        cpu0, t0 = time.process_time(), time.perf_counter()
        self.run(k)
        wall, cpu = time.perf_counter() - t0, time.process_time() - cpu0
        self.n, self.s, self.cpu = self.n + k, self.s + wall, self.cpu + cpu
        self.rates.append(k / wall)

    def figures(self) -> dict:
        return {"n": self.n, "s": self.s, "cpu": self.cpu}


def bare_pymodbus(client: ModbusTcpClient):
    def run(k: int) -> None:
        read = client.read_holding_registers
        for _ in range(k):
            r = read(OFFSET, count=COUNT, device_id=UNIT)
            if r.isError() or len(r.registers) != COUNT:
                raise SystemExit(f"pymodbus: bad answer {r}")

    return run


def link_loop(link: ModbusLink, clock: RealClock):
    tx = Transaction(unit=UNIT, function=FUNCTION, offset=OFFSET, count=COUNT)

    def run(k: int) -> None:
        transact, now = link.transact, clock.now_ns
        for _ in range(k):
            out = transact(tx, now())
            if out.error != 0 or len(out.values) != COUNT:
                raise SystemExit(f"link: error 16#{out.error:02X} {out.message}")

    return run


def exchange_loop(driver: ModbusDriver, polls: list):
    send, receive, mgmt = [0] * 125, [0] * 125, [0] * 4

    def run(k: int) -> None:
        request, collect = driver.exchange.request, driver.exchange.collect
        for _ in range(k):
            if not request("MODBUS_EXCHANGE", CONNECTION, UNIT, FUNCTION, OFFSET, COUNT, 0, 0, send, receive, mgmt):
                raise SystemExit(f"MODBUS_EXCHANGE refused: error 16#{mgmt[1]:02X}")
            while mgmt[0] & 1:  # a scan collects once per cycle; here as soon as it can
                time.sleep(0)
                collect()
                polls[0] += 1
            if mgmt[1] != 0 or mgmt[2] != COUNT:
                raise SystemExit(f"MODBUS_EXCHANGE: error 16#{mgmt[1]:02X}, {mgmt[2]} registers")

    return run


def paired(port: int, n: int, clock: RealClock) -> tuple:
    """Figures 1, 2 and 4: the three clients connected to the server at once,
    N transactions each in ROUNDS chunks; in each round one chunk of each side,
    back to back, the order rotating from round to round."""
    client = ModbusTcpClient(HOST, port=port, timeout=1, retries=0)
    link = ModbusLink(LinkSettings(name=CONNECTION, transport="tcp", host=HOST, port=port, timeout_s=1.0, retries=0))
    driver = ModbusDriver([_connection(port, [])], "iec", clock=clock)
    polls = [0]
    try:
        if not client.connect():
            raise SystemExit(f"pymodbus: cannot connect to {HOST}:{port}")
        driver.start()
        sides = [Side(bare_pymodbus(client)), Side(link_loop(link, clock)), Side(exchange_loop(driver, polls))]
        for side in sides:
            side.run(WARM_UP)
        polls[0] = 0
        k = max(1, n // ROUNDS)
        for r in range(ROUNDS):
            for i in range(len(sides)):
                sides[(r + i) % len(sides)].chunk(k)
    finally:
        driver.stop()
        link.close()
        client.close()
    return sides, polls[0]


def _connection(port: int, channels: list) -> ModbusConnectionConfig:
    return ModbusConnectionConfig(
        name=CONNECTION,
        transport="tcp",
        device="",
        baud=19200,
        parity="N",
        stop_bits=1,
        data_bits=8,
        frame_gap_us=None,
        host=HOST,
        port=port,
        timeout_ms=1000,
        retries=0,
        reconnect_ms=1000,
        reconnect_max_ms=10000,
        channels=channels,
        key="modbus[0]",
    )


def _channel(period_ns: int) -> ModbusChannelConfig:
    return ModbusChannelConfig(
        name="status",
        connection=CONNECTION,
        unit=UNIT,
        function=FUNCTION,
        offset=OFFSET,
        count=COUNT,
        write_offset=0,
        write_count=0,
        read_to=parse_address("%IW100"),
        write_from=None,
        trigger="cyclic",
        period_ns=period_ns,
        edge=None,
        key="modbus[0].channel[0]",
    )


def channel_run(port: int, seconds: float, clock: RealClock) -> dict:
    period_ns = 1_000_000  # the shortest period the configuration allows (1ms)
    driver = ModbusDriver([_connection(port, [_channel(period_ns)])], "iec", clock=clock)
    ch = driver.channels[0]
    image = ProcessImage("iec")
    # count the scans whose read_inputs found new data (Channel.publish says so;
    # read_inputs drops the answer): an instance-level wrapper, nothing else changes
    publish, fresh = ch.publish, [0]

    def counting_publish(img) -> bool:
        got = publish(img)
        fresh[0] += got
        return got

    ch.publish = counting_publish
    driver.start()
    try:
        end = time.monotonic() + 5
        while ch.stats.requests == 0:  # connected and a first answer
            if time.monotonic() > end:
                raise SystemExit(f"channel: no transaction within 5 s ({driver.status().message})")
            time.sleep(0.001)
        driver.read_inputs(image)
        fresh[0] = 0
        req0, err0 = ch.stats.requests, ch.stats.errors
        scans = 0
        cpu0, t0 = time.process_time(), time.perf_counter()
        release, stop_at = t0, t0 + seconds
        while True:
            driver.read_inputs(image)
            scans += 1
            release += period_ns / 1e9
            if release >= stop_at:
                break
            pause = release - time.perf_counter()
            if pause > 0:
                time.sleep(pause)  # no spin (RealClock spins its last 1 ms: at 1 ms it would only spin)
        wall, cpu = time.perf_counter() - t0, time.process_time() - cpu0
        n, errors = ch.stats.requests - req0, ch.stats.errors - err0
    finally:
        driver.stop()
    if errors:
        raise SystemExit(f"channel: {errors} errors ({ch.stats.message})")
    return {"n": n, "s": wall, "cpu": cpu, "scans": scans, "fresh": fresh[0], "errors": errors}


def _line(label: str, r: dict, base: dict | None = None, paired_ratio: float | None = None) -> str:
    rate, us, cpu_us = r["n"] / r["s"], r["s"] / r["n"] * 1e6, r["cpu"] / r["n"] * 1e6
    text = f"   {label:<12}{r['n']:7,}  {r['s']:6.2f} s  {rate:8,.0f} /s  {us:7.1f} us/tx  {cpu_us:7.1f} us CPU/tx"
    if base is not None:
        b_rate, b_cpu = base["n"] / base["s"], base["cpu"] / base["n"] * 1e6
        ratio = paired_ratio if paired_ratio is not None else rate / b_rate
        text += f"   ratio {ratio:4.2f} of the rate, {cpu_us / b_cpu:4.2f}x the CPU"
    return text


def _median_ratio(side: Side, base: Side) -> float:
    return statistics.median(a / b for a, b in zip(side.rates, base.rates))


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="fewer transactions, a shorter channel run")
    args = ap.parse_args()
    n, seconds = (1000, 0.5) if args.quick else (5000, 2.0)
    clock = RealClock()
    port = _free_port()
    sim = SimulatedModbusLine(
        "bench", {UNIT: EatonDriveModel(Family.DA1)}, clock=clock, transport="tcp", host=HOST, port=port
    )
    sim.start()
    try:
        (base, link, exch), polls = paired(port, n, clock)
        chan = channel_run(port, seconds, clock)
    finally:
        sim.stop()
    b = base.figures()
    print(f"Modbus TCP on {HOST}:{port}: FC03, {COUNT} registers from offset {OFFSET}, unit {UNIT} of a simulated")
    print("Eaton DA1 (pymodbus server in this process: CPU/tx includes the server's share), real time.")
    print("   1 baseline  pymodbus ModbusTcpClient.read_holding_registers, tight loop")
    print("   2 link      ModbusLink.transact, tight loop (what a connection's worker runs per transaction)")
    print("   3 channel   ModbusDriver, one cyclic channel, period 1 ms (so at most 1000/s), its worker")
    print(f"               thread running {seconds:g} s while this thread calls read_inputs every 1 ms;")
    print("               ratio against the baseline's overall rate")
    print("   4 exchange  MODBUS_EXCHANGE: request(), then collect() polled until done; one after another")
    print(f"   1, 2 and 4: {ROUNDS} rounds, one chunk of each per round, order rotating; their ratio is")
    print("   the median over the rounds of (rate / baseline rate in the same round).")
    print("   The figures swing with the VM's load: compare the ratios, not the rates.")
    print(f"   {'':<12}{'tx':>7}  {'wall':>8}  {'rate':>11}")
    print(_line("1 baseline", b))
    print(_line("2 link", link.figures(), b, _median_ratio(link, base)))
    print(_line("3 channel", chan, b))
    print(
        f"     {chan['scans']:,} scans (read_inputs), {chan['fresh']:,} found fresh data "
        f"({chan['fresh'] / max(chan['scans'], 1):.0%}); errors {chan['errors']}"
    )
    print(_line("4 exchange", exch.figures(), b, _median_ratio(exch, base)))
    print(f"     {polls / exch.n:.1f} collect() polls per round trip; every answer good (mgmt[1] = 0)")


if __name__ == "__main__":
    main()
