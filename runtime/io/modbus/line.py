"""Simulated devices on one Modbus line: a real pymodbus server (RTU on a
pseudo-terminal cable, or TCP on 127.0.0.1) whose units are device models
(SimulatedUnit: an Eaton drive of devices/eaton, a test's relay ...); or,
with wire = "memory" (virtual time), the same units behind pymodbus's
framers and request handling in memory (wire.py): no pty, no socket.

    line = SimulatedModbusLine("drives", {1: model}, clock=clock, transport="rtu")
    line.master_port         # the serial port the master opens (a NullModem end)
    line.start()
    line.unit(1)             # the model at unit 1
    line.silent = True       # every unit on the line stops answering
    line.cable.cut()         # RTU: the line itself is cut (in memory too)
    line.server              # wire = "memory": the MemoryServer the master's link uses

What the line does, as a real RS-485 line or TCP gateway does:
  * a request to a unit that is not on the line gets no answer; a frame with
    a bad CRC is dropped by pymodbus's framer, so the unit stays silent;
  * a function code the unit does not have (its ``functions``) is refused
    with exception 01; a unit refuses a request with ModbusRefusal(code);
  * address 0 is a broadcast: every unit executes it, none answers;
  * every request addressed to a unit goes to its telegram() first (a
    communication-loss watchdog restarts there).
The models run on the engine's clock: virtual time moves them at each tick
(advance_to), real time every millisecond (the service thread).
"""

from __future__ import annotations

import threading
from collections.abc import Callable

from pymodbus.constants import ExcCodes
from pymodbus.datastore import ModbusServerContext
from pymodbus.exceptions import NoSuchIdException
from pymodbus.framer import FramerType
from pymodbus.server import ModbusSerialServer, ModbusTcpServer

from ...plugin.driver import DriverError
from ...sim.base import SimulatedDevice
from ...sim.null_modem import NullModem
from ..loop_thread import LoopThread
from .unit import SILENT, ModbusRefusal, SimulatedUnit
from .wire import MemoryCable, MemoryServer

SIM_HOSTS = ("127.0.0.1", "localhost")


class _Line(ModbusServerContext):
    """pymodbus's datastore interface, answered by the line's units."""

    def __init__(self, sim: SimulatedModbusLine) -> None:  # no super(): no pymodbus datastore
        self.old_simulator = True  # pymodbus then calls async_getValues/async_setValues itself
        self.simdevices = []
        self._sim = sim

    async def async_getValues(self, device_id: int, func_code: int, address: int, count: int = 1):
        return self._sim.serve(device_id, func_code, address, count=count)

    async def async_setValues(self, device_id: int, func_code: int, address: int, values):
        return self._sim.serve(device_id, func_code, address, values=list(values))

    def device_ids(self):
        return list(self._sim.units)


class SimulatedModbusLine(SimulatedDevice):
    def __init__(
        self,
        name: str,
        units: dict,
        *,
        clock,
        transport: str = "rtu",
        host: str = "127.0.0.1",
        port: int = 0,
        baud: int = 115200,
        parity: str = "N",
        stop_bits: int = 1,
        wire: str = "port",
    ) -> None:
        super().__init__(name, clock=clock)
        if transport == "tcp" and host not in SIM_HOSTS:
            raise DriverError(f"sim {name}: a simulated device listens on 127.0.0.1 only, not {host}")
        self.units: dict[int, SimulatedUnit] = dict(units)
        self.transport = transport
        self.host, self.port = host, port
        self.baud, self.parity, self.stop_bits = baud, parity, stop_bits  # rtu: the serial settings
        self.wire = wire
        self.server: MemoryServer | None = MemoryServer(self, _Line(self)) if wire == "memory" else None
        self.cable: NullModem | MemoryCable | None = None
        if transport == "rtu":
            self.cable = MemoryCable() if self.server is not None else NullModem(f"sim {name} cable")
        self.master_port = self.cable.master_port if isinstance(self.cable, NullModem) else None
        self.silent = False
        self.muted: set[int] = set()  # unit ids that do not answer (the SILENT fault)
        self.requests = 0
        self._lock = threading.Lock()
        self._runner: LoopThread | None = None  # real time, on a port: the server's thread
        self._server: ModbusTcpServer | ModbusSerialServer | None = None

    def unit(self, unit: int):
        """The model at a unit id."""
        return self.units[unit]

    # ---------------------------------------------------------------- requests (server thread)

    def serve(self, unit: int, function: int, address: int, *, count: int = 0, values=None):
        """One datastore access of pymodbus: a list of registers, None after a
        good write, or an ExcCodes refusal."""
        model = self.units.get(unit)
        if model is None or unit in self.muted:
            raise NoSuchIdException(f"unit {unit} is not on this line")  # pymodbus stays silent
        if function not in model.functions:
            return ExcCodes.ILLEGAL_FUNCTION
        now = self.clock.now_ns()
        with self._lock:
            model.telegram(now)
            self.requests += 1
            try:
                if values is None:
                    return model.serve_read(address, count, now)
                model.serve_write(address, values, now)
                return None
            except ModbusRefusal as refusal:
                return ExcCodes(refusal.code)

    def _trace(self, sending: bool, data: bytes) -> bytes:
        if self.silent and not sending:
            return b""  # the request never reaches the units: no answer
        return data

    # ---------------------------------------------------------------- device behaviour

    def service(self, now_ns: int) -> None:
        with self._lock:
            for model in self.units.values():
                model.advance(now_ns)

    def open(self) -> None:
        if self.server is not None:
            return  # in memory: the master's link calls server.exchange()
        self._runner = LoopThread(f"sim {self.name}")
        try:
            self._runner.start(self._serve, timeout_s=5)
        except Exception as exc:
            raise DriverError(f"sim {self.name}: the Modbus server did not start: {exc}") from None

    async def _serve(self, ready: Callable[[], None]) -> None:
        line = _Line(self)
        server: ModbusTcpServer | ModbusSerialServer
        if self.transport == "tcp":
            server = ModbusTcpServer(
                line,
                address=(self.host, self.port),
                ignore_missing_devices=True,
                broadcast_enable=True,
                trace_packet=self._trace,
            )
        else:
            assert isinstance(self.cable, NullModem)  # a port rtu line has its cable until close()
            server = ModbusSerialServer(
                line,
                framer=FramerType.RTU,
                port=self.cable.slave_port,
                ignore_missing_devices=True,
                broadcast_enable=True,
                trace_packet=self._trace,
                baudrate=self.baud,
                parity=self.parity,
                stopbits=self.stop_bits,
            )
        self._server = server
        await server.serve_forever(background=True)
        ready()
        await server.serving

    def close(self) -> None:
        runner, self._runner = self._runner, None
        if self._server is not None and runner is not None and runner.alive:
            try:
                runner.run(self._server.shutdown(), timeout_s=5)
            except Exception:  # already down
                pass
        if runner is not None:
            runner.join(timeout_s=5)
        self._server = None
        if isinstance(self.cable, NullModem):
            self.cable.close()
            self.cable = None


class UnitOnLine:
    """A simulated unit as the engine and tests find it by its [[sim]] name:
    its model on its line. inject() takes SILENT itself and hands the
    device's own faults to the model, under the line's lock."""

    def __init__(self, line: SimulatedModbusLine, unit: int) -> None:
        self.line = line
        self.unit = unit

    @property
    def model(self) -> SimulatedUnit:
        return self.line.units[self.unit]

    def inject(self, fault: str, value, on: bool) -> None:
        if fault == SILENT.name:
            if on:
                self.line.muted.add(self.unit)
            else:
                self.line.muted.discard(self.unit)
            return
        with self.line._lock:
            self.model.advance(self.line.clock.now_ns())
            self.model.inject(fault, value, on)
