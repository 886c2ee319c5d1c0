"""The simulated TeSys T LTMR: a CANopen slave (io/canopen/slave.py) whose
manufacturer objects are the registers of the device model (model.py).

    sim = LtmrSimulator(40, settings=BusSettings("virtual", "plant"), clock=clock, pump=pump,
                        registers={682: 2})
    sim.start()                       # boot-up 0x728 [00]
    sim.set_load(400)                 # a jammed machine
    sim.lo1, sim.motor_running, sim.register(455)

What the bus sees (manual 001, shared/manuals/001_*.txt "L<n>", and digest
001 with its ambiguities A1..A26):
- Objects 0x2000-0x2008 and 0x200D are the registers (one sub-index per
  register, digest §5.2). Reads return the model's values; writes go
  through the manual's rules: read-only tables refuse (ABORT_READ_ONLY),
  Reserved registers take only 0, Forbidden ones are not in the EDS
  (ABORT_NO_SUBINDEX, or ABORT_NO_OBJECT for a whole index: A21), notes
  A (motor off), B (configuration mode, 601 bit 0) and C (no trip) refuse
  with ABORT_DEVICE_STATE. Configuration registers (540-699) take network
  writes only while 601 bit 10 "config via network port" is set (L207-252).
- RPDO1 (704/703/700 by the factory mapping) drives the control register,
  TPDO1 sends 455/456/457/459 (A1), both from the OD's mapping.
- PKW on RPDO4/TPDO4 (0x3000:01-04, digest §2.5).
- Network communication loss: heartbeat consumer expiry, or leaving
  Operational by NMT ("Enter_Pre-Operational_State and apply fallback",
  L75-90; leaving it to Stopped or a reset is taken the same way) applies
  the fallback of 682 and the indications of the model. They clear when the
  node is Operational again with heartbeats; the fallback itself ends with
  the first RPDO after that.
- EMCY: the manual defines no payload (A22; emcy.py). On a trip: error code
  0x1000 (generic), error register 0x01, the trip code as U16 in the first
  two manufacturer bytes; on its reset: 0x0000 and error register 0x00.
"""

from __future__ import annotations

import contextlib
from functools import partial

from canopen.sdo import SdoAbortedError

from ...io.can.bus import BusSettings
from ...io.canopen.cia301 import (
    ABORT_ACCESS,
    ABORT_BAD_COMMAND,
    ABORT_DEVICE_STATE,
    ABORT_NO_OBJECT,
    ABORT_NO_SUBINDEX,
    ABORT_READ_ONLY,
    ABORT_VALUE_HIGH,
    ABORT_VALUE_LOW,
    ABORT_VALUE_RANGE,
    STATE_BOOTUP,
    STATE_OPERATIONAL,
)
from ...io.canopen.eds import shipped_eds
from ...io.canopen.slave import UNPLUG, SimulatedCanopenSlave
from ...plugin.seams import SimFault
from . import pkw
from .bits import GENERAL_CONFIG2_RESET_MODE_MASK, NetworkPortStatus
from .codes import CANOPEN_BAUD_CODES, FallbackStrategy, OperatingMode, ResetMode, fallback_allowed
from .defaults import DEFAULT_LOAD_PERCENT
from .emcy import EMCY_RESET, EMCY_TRIP, ERROR_REGISTER_DETECTED, emcy_text, trip_payload
from .model import LtmrModel
from .profile import PKW_INDEX, RPDO_MAPPABLE_INDICES, TPDO_MAPPABLE_INDICES, pkw_read_only
from .registers import (
    BIT_NOTES,
    REG_GENERAL_CONFIG_2,
    REG_NETWORK_BAUD_RATE,
    REG_NETWORK_FALLBACK,
    REG_NETWORK_PORT_STATUS,
    REG_NODE_ADDRESS,
    REG_OPERATING_MODE,
    REG_TRIP_CLASS,
    REG_TRIP_CODE,
    REGISTER_BLOCKS,
    REGISTERS,
    ForbiddenRegisterError,
    UnmappedRegisterError,
    object_to_register,
    register_to_object,
)

PRODUCT_CODE_OBJECT = (0x1018, 2)
REGISTER_INDICES = frozenset(index for _first, _last, index in REGISTER_BLOCKS)
CONFIGURATION_REGISTERS = range(540, 700)  # configuration and setting tables (L4011-4898)
PKW_REQUEST_SUBS = (1, 2)  # 0x3000:01/02 in RPDO4
PKW_RESPONSE_SUBS = (3, 4)  # 0x3000:03/04 in TPDO4
_PORT_CONNECTED, _PORT_COMMUNICATING = int(NetworkPortStatus.CONNECTED), int(NetworkPortStatus.COMMUNICATING)


# [[sim]] faults = [...] (config/sim_faults.py)
LOAD = SimFault("load", "the motor's load changes (a jam: 400): it draws that current", value="% of FLC", lasting=True)
FAULTS = (UNPLUG, LOAD)


class LtmrSimulator(SimulatedCanopenSlave):
    #: A21 leaves the abort code of a note A/B/C violation open; this one by default
    note_abort = ABORT_DEVICE_STATE
    emcy_text = staticmethod(emcy_text)  # its EMCYs in the manual's words, in its records

    def __init__(
        self,
        node_id: int = 40,
        *,
        settings: BusSettings,
        clock,
        pump=None,
        name: str | None = None,
        product_code: int = 0x30,
        registers: dict | None = None,
        eds=None,
        load_percent: float = DEFAULT_LOAD_PERCENT,
    ) -> None:
        pkw_read_only(product_code)  # ValueError for an unknown product code
        with shipped_eds("ltmr.eds") if eds is None else contextlib.nullcontext(eds) as path:
            super().__init__(
                node_id, eds=str(path), settings=settings, clock=clock, pump=pump, name=name or f"ltmr {node_id}"
            )
        self.product_code = product_code
        identity = self.od.get_variable(*PRODUCT_CODE_OBJECT)
        if identity is None:
            raise KeyError(f"the EDS has no product code 0x{PRODUCT_CODE_OBJECT[0]:04X}:{PRODUCT_CODE_OBJECT[1]:02X}")
        identity.default = product_code  # L1034-1050
        if identity.value is not None:
            identity.value = product_code
        initial = {REG_NODE_ADDRESS: node_id, REG_NETWORK_BAUD_RATE: _baud_code(settings.bitrate)}
        initial.update(registers or {})
        self.model = LtmrModel(initial, load_percent=load_percent)
        self._pkw_function_byte = 0  # toggle + function code of the last request seen
        self._emcy_trip_code = 0  # the trip the last EMCY told about
        self._load_before = self.model.load_percent  # the load a lasting "load" fault goes back to

    # ------------------------------------------------------------------ test and operator API

    def register(self, reg: int) -> int:
        with self._lock:
            return self.model.registers[reg]

    def set_register(self, reg: int, value: int) -> None:
        """A local (HMI) write, with no access checks."""
        with self._lock:
            self.model.set_register(reg, value)

    def set_load(self, percent_flc: float) -> None:
        with self._lock:
            self.model.set_load(percent_flc)

    def press_reset(self) -> None:
        with self._lock:
            self.model.press_reset()

    def inject(self, fault: str, value, on: bool) -> None:
        """The faults of FAULTS (from [[sim]] faults or a test); unplug is
        every CANopen slave's."""
        if fault != LOAD.name:
            super().inject(fault, value, on)
            return
        with self._lock:
            if on:
                self._load_before = self.model.load_percent
                self.model.set_load(float(value))
            else:
                self.model.set_load(self._load_before)

    @property
    def lo1(self) -> bool:
        return self.model.lo1

    @property
    def lo2(self) -> bool:
        return self.model.lo2

    @property
    def motor_running(self) -> bool:
        return self.model.motor_running

    @property
    def fallback_applied(self) -> bool:
        return self.model.fallback is not None

    # ------------------------------------------------------------------ device behaviour

    def run_device(self, now_ns: int) -> None:
        model = self.model
        model.advance_to(now_ns)
        status = _PORT_CONNECTED if self.plugged else 0  # plain ints: this runs at every step
        if self.nmt_state == STATE_OPERATIONAL and not self.heartbeat_lost:
            status |= _PORT_COMMUNICATING
        model.registers[REG_NETWORK_PORT_STATUS] = status
        if model.registers[REG_TRIP_CODE] != self._emcy_trip_code:
            self._report_trip()

    def _report_trip(self) -> None:
        code = self.model.registers[REG_TRIP_CODE]
        if code == self._emcy_trip_code:
            return
        self._emcy_trip_code = code
        if code:
            self.send_emcy(EMCY_TRIP, ERROR_REGISTER_DETECTED, trip_payload(code))
        else:
            self.send_emcy(EMCY_RESET, 0x00)

    def on_state_change(self, old: int, new: int) -> None:
        if old == STATE_BOOTUP:
            self._emcy_trip_code = 0  # a trip still present is reported again after booting
        if old == STATE_OPERATIONAL:
            self.model.network_lost()
        elif new == STATE_OPERATIONAL and not self.heartbeat_lost:
            self.model.network_restored()

    def on_comm_error(self) -> None:
        self.model.network_lost()

    def on_comm_restored(self) -> None:
        if self.nmt_state == STATE_OPERATIONAL:
            self.model.network_restored()

    def on_reset_application(self) -> None:
        self.model.restart()
        self._pkw_function_byte = 0
        self._clear_stored(PKW_INDEX, PKW_INDEX)

    def on_rpdo(self, number: int) -> None:
        # The first RPDO with communication back ends the fallback
        if self.model.fallback is not None and not self.model.comm_lost and not self.heartbeat_lost:
            self.model.clear_fallback()
        self._serve_pkw()
        self.model.advance_to(self._clock_ns())  # the new command takes effect now

    # ------------------------------------------------------------------ objects <-> registers

    def object_read(self, index: int, subindex: int, od):
        if index in REGISTER_INDICES:
            reg = object_to_register(index, subindex)
            return self.model.registers.get(reg, 0).to_bytes(2, "little")
        return None

    def pdo_source(self, index: int, subindex: int):
        """A TPDO-mapped register straight from the model (object_read, without
        the object dictionary's look-ups): TPDOs are packed at every step."""
        if index not in REGISTER_INDICES:
            return None
        try:
            reg = object_to_register(index, subindex)
        except (ForbiddenRegisterError, UnmappedRegisterError):
            return None  # refused as object_read refuses it
        return partial(self.model.registers.get, reg, 0)  # a C call: no Python frame per read

    def object_write(self, index: int, subindex: int, od, data: bytes, local: bool) -> None:
        if index not in REGISTER_INDICES:
            return
        reg = object_to_register(index, subindex)
        value = int.from_bytes(data, "little")
        if local:
            self.model.set_register(reg, value)
        else:
            self._network_write(reg, value)

    def pdo_mappable(self, index: int, subindex: int, rpdo: bool) -> bool:
        # Monitoring objects 0x2004 into TPDOs, settings 0x2007 and commands 0x2008
        # into RPDOs (L253-280); PKW requests into RPDOs, responses into TPDOs.
        if index == PKW_INDEX:
            return subindex in (PKW_REQUEST_SUBS if rpdo else PKW_RESPONSE_SUBS)
        return index in (RPDO_MAPPABLE_INDICES if rpdo else TPDO_MAPPABLE_INDICES)

    def _network_write(self, reg: int, value: int) -> None:
        self._check_network_write(reg, value)
        self.model.set_register(reg, value)

    def _check_network_write(self, reg: int, value: int) -> None:
        """The manual's write rules for a write from the network (SDO, PDO, PKW):
        raises SdoAbortedError with the code the master gets."""
        register = REGISTERS.get(reg)
        if register is None or register.kind == "forbidden":
            raise SdoAbortedError(ABORT_NO_SUBINDEX)  # A21
        if register.access != "rw":
            raise SdoAbortedError(ABORT_READ_ONLY)
        if register.kind == "reserved" and value != 0:
            raise SdoAbortedError(ABORT_VALUE_RANGE)  # "you must write 0" (§5.3)
        if reg in CONFIGURATION_REGISTERS and not self.model.config_via_network:
            raise SdoAbortedError(ABORT_ACCESS)  # local configuration (601 bit 10)
        model = self.model
        notes = self._notes_touched(reg, value)
        if (
            ("A" in notes and model.motor_on)
            or ("B" in notes and not model.config_mode)
            or ("C" in notes and model.tripped)
        ):
            raise SdoAbortedError(self.note_abort)
        self._check_value(reg, value)

    def _notes_touched(self, reg: int, value: int) -> str:
        """The notes of a register, or for 601/602 those of the bits the write changes."""
        per_bit = BIT_NOTES.get(reg)
        if per_bit is None:
            return REGISTERS[reg].notes
        changed = value ^ self.model.registers[reg]
        return "".join(note for bit, note in per_bit.items() if changed >> bit & 1)

    def _check_value(self, reg: int, value: int) -> None:
        """Value checks the simulator makes where the manual lists the values."""
        if reg == REG_OPERATING_MODE and value not in OperatingMode._value2member_map_:
            raise SdoAbortedError(ABORT_VALUE_RANGE)  # 2..11; custom logic (256-511) is not simulated
        if (
            reg == REG_GENERAL_CONFIG_2
            and (value & GENERAL_CONFIG2_RESET_MODE_MASK) not in ResetMode._value2member_map_
        ):
            raise SdoAbortedError(ABORT_VALUE_RANGE)  # DT_ResetMode: 1, 2 or 4 (L2204-2214)
        if reg == REG_NETWORK_FALLBACK:
            if value > max(FallbackStrategy):
                raise SdoAbortedError(ABORT_VALUE_HIGH)
            if not fallback_allowed(value, self.model.operating_mode):
                raise SdoAbortedError(ABORT_VALUE_RANGE)  # "Motor Modes" column (L2171-2194)
        if reg == REG_TRIP_CLASS and value == 0:
            raise SdoAbortedError(ABORT_VALUE_LOW)

    # ------------------------------------------------------------------ PKW (digest 001 §2.5)

    def _serve_pkw(self) -> None:
        """ "Any changes in the function code will trigger the handling of the
        request (unless function code [b8...b14] = 0x00)": the request byte is
        toggle + function code; a function code 0 is echoed (the HMI re-trigger)."""
        frame = b"".join(self.node.get_data(PKW_INDEX, sub) for sub in PKW_REQUEST_SUBS)
        request = pkw.decode_frame(frame)
        function_byte = request.w2 >> 8
        if function_byte == self._pkw_function_byte:
            return
        self._pkw_function_byte = function_byte
        if request.function == pkw.NONE:
            response = pkw.response(request)
        else:
            response = self._pkw_execute(request)
        data = pkw.encode_frame(response)
        for i, sub in enumerate(PKW_RESPONSE_SUBS):
            self._store(PKW_INDEX, sub, int.from_bytes(data[4 * i : 4 * i + 4], "little"))
            self.mark_changed(PKW_INDEX, sub)  # a response goes out even if it equals the last one

    def _pkw_execute(self, request: pkw.PkwWords) -> pkw.PkwWords:
        function = request.function
        try:
            if function not in pkw.REQUESTS:
                raise SdoAbortedError(ABORT_BAD_COMMAND)
            if function in pkw.BY_OBJECT:
                reg = self._pkw_object_register(request.w1, request.subindex)
            else:
                reg = self._pkw_register(request.w1)
            regs = [reg, reg + 1] if function in pkw.IS_32BIT else [reg]
            if function in pkw.READS:
                for r in regs[1:]:
                    self._pkw_register(r)
                words = [self.model.registers[r] for r in regs] + [0]
                return pkw.response(request, (words[0], words[1]))
            if pkw_read_only(self.product_code):
                raise SdoAbortedError(ABORT_READ_ONLY)  # MMC L variants (L343)
            values = [request.w3, request.w4][: len(regs)]  # word 3 = register n, word 4 = n + 1
            for r, value in zip(regs, values):
                self._pkw_register(r)
                self._check_network_write(r, value)
            for r, value in zip(regs, values):  # all or nothing
                self.model.set_register(r, value)
            return pkw.response(request)
        except SdoAbortedError as exc:
            # "The request is not accepted and the object/register remains at the original value"
            return pkw.error_response(request, exc.code)

    @staticmethod
    def _pkw_register(reg: int) -> int:
        try:
            register_to_object(reg)
        except ForbiddenRegisterError:
            raise SdoAbortedError(ABORT_NO_SUBINDEX) from None
        except UnmappedRegisterError:
            raise SdoAbortedError(ABORT_NO_OBJECT) from None
        return reg

    @staticmethod
    def _pkw_object_register(index: int, subindex: int) -> int:
        try:
            return object_to_register(index, subindex)
        except ForbiddenRegisterError:
            raise SdoAbortedError(ABORT_NO_SUBINDEX) from None
        except UnmappedRegisterError:
            raise SdoAbortedError(ABORT_NO_SUBINDEX if index in REGISTER_INDICES else ABORT_NO_OBJECT) from None


def _baud_code(bitrate: int) -> int:
    """491, DT_CANopenExtBaudRate code of the bus bitrate (L183-206)."""
    for code, rate in CANOPEN_BAUD_CODES.items():
        if rate == bitrate:
            return code
    return 9
