"""The simulated Danfoss FC 280: a CANopen slave (io/canopen/slave.py) built
from the shipped EDS (io_config/eds/fc280.eds), whose drive is model.py.

    sim = Fc280Simulator(5, settings=BusSettings("virtual", "plant"), clock=clock, pump=pump,
                         parameters={"8-04": 5})
    sim.start()                          # boot-up 0x705 [00]
    sim.model.over_current()             # fault injection (model.py)
    sim.parameter("16-03"), sim.power_cycle(), sim.unplug()

What the bus sees (manual 003, shared/manuals/003_*.txt; digest 003, with
its contradictions A1..A42):
- Objects 2000h + g*100 + nn are the parameters (§5.1): reads give the
  model's values, writes go through its rules. An array parameter's element
  [i] is sub-index i + 1, sub-index 0 the number of elements (A35). A refused write aborts with
  the code of Tabelle 8.8: 0609 0031h too high, 0609 0032h too low,
  0609 0030h no allowed value, 0601 0002h read-only, 0609 0011h no such
  element, 0800 0022h not in the drive's present state (the other profile's
  control objects, 8-02 while running).
- FC profile (8-10 [0]): 2690h control word, 2692h reference in, 2643h
  status word, 2645h HIW out (§4.4). DSP 402 (8-10 [7]): 6040h control
  word, 6042h vl target velocity in, 6041h status word, 6043h-6045h out
  (§4.3), in RPM times the vl dimension factor 604Ch (rpm = value x 604Ch:1
  / 604Ch:2; simulator choice, the manual defers to CiA 402, §4.3.5).
- 1010h "save" (65766173h) and 1011h "load" (64616F6Ch) on sub-indices 1, 2
  and 4 (Tabellen 3.9, 3.10); any other value, and sub-index 3
  ("reserviert"), aborts with 0800 0020h (CiA 301's code for a wrong
  signature). Communication parameters are the objects 1000h-1FFFh; the
  CiA 402 settings 6046h-604Ch are saved with the drive parameters.
- 1005h: bit 30 (SYNC producer) and bit 29 (29-bit ID) abort 0609 0030h
  (Tabelle 7.4). TPDO inhibit time and event timer: at most 32767
  (§4.1.4, §4.1.5), more aborts 0609 0031h.
- EMCY on every alarm (8-07 [1]) or alarm and warning (8-07 [2]) that
  appears, the all-zero EMCY when the last is gone; 8-07 [0] (factory)
  sends none (§3.1.4). Payload: emcy.py. 1001h and 603Fh are live.
- Life guarding (100Ch x 100Dh) lost: the model's lost-master reaction
  (8-04 and warning 34, A6), and CiA 301's pre-operational (no 1029h);
  guarding back: its end. The node has no heartbeat consumer (§3.1.4
  HINWEIS: no 1016h): the master writes no master_timeout to it (a node
  whose EDS lacks 1016h gets none by default; an explicit one is an error).
- power_cycle() applies a pending restore (§7.1.10); NMT reset node
  restarts the drive with its saved parameters.
- 10-01 and 10-02 show the configuration's bit rate and node id; a write
  is stored (and saved) but the node keeps both (simulator choice).
"""

from __future__ import annotations

import contextlib
from collections.abc import Mapping, Sequence
from fractions import Fraction

from canopen.objectdictionary import ODVariable
from canopen.sdo import SdoAbortedError

from ...io.can.bus import BusSettings
from ...io.canopen.cia301 import (
    ABORT_DEVICE_STATE,
    ABORT_NO_SUBINDEX,
    ABORT_READ_ONLY,
    ABORT_VALUE_HIGH,
    ABORT_VALUE_LOW,
    ABORT_VALUE_RANGE,
    STATE_BOOTUP,
    TPDO_COMM,
)
from ...io.canopen.eds import shipped_eds
from ...io.canopen.slave import UNPLUG, SimulatedCanopenSlave
from ...plugin.seams import SimFault
from . import emcy
from .diagnostics import emcy_text
from .model import Fc280Model
from .motor import int16, round_half_away
from .parameters import BAUD_CODES, PARAMETERS, number_of
from .store import COMMUNICATION, PROFILE, Refusal, Refused

SAVE_SIGNATURE = 0x65766173  # "save" (§3.1.5; M5)
LOAD_SIGNATURE = 0x64616F6C  # "load" (§3.1.5; M6)
STORE_PARAMETERS, RESTORE_DEFAULTS = 0x1010, 0x1011
ABORT_NOT_STORED = 0x08000020  # Tabelle 8.8 "Daten können nicht ... gespeichert werden"
SYNC_COB_ID = 0x1005
SYNC_PRODUCER, SYNC_EXTENDED = 1 << 30, 1 << 29  # Tabelle 7.4
PDO_TIME_MAX = 32767  # inhibit time (§4.1.4), event timer (§4.1.5)
TPDO_INHIBIT, TPDO_EVENT_TIMER = 3, 5
ERROR_REGISTER, ERROR_CODE = 0x1001, 0x603F
CONTROLWORD, STATUSWORD, TARGET_VELOCITY = 0x6040, 0x6041, 0x6042
VELOCITY_OUTPUTS = (0x6043, 0x6044, 0x6045)  # demand, control effort (actual), manipulated
DIMENSION_FACTOR, SETPOINT_FACTOR = 0x604C, 0x604B
PROFILE_SETTINGS = (0x6046, 0x6048, 0x6049, 0x604A, 0x604B, 0x604C)
NUMBERS = {p.index: p.number for p in PARAMETERS.values()}  # index -> parameter number (§5.1)
PARAMETER_INDICES = frozenset(NUMBERS)
ARRAYS = {p.index: p.elements for p in PARAMETERS.values() if p.elements}  # index -> number of elements

ABORTS = {
    Refusal.HIGH: ABORT_VALUE_HIGH,
    Refusal.LOW: ABORT_VALUE_LOW,
    Refusal.RANGE: ABORT_VALUE_RANGE,
    Refusal.READ_ONLY: ABORT_READ_ONLY,
    Refusal.STATE: ABORT_DEVICE_STATE,
    Refusal.NO_ELEMENT: ABORT_NO_SUBINDEX,
    Refusal.NOT_STORED: ABORT_NOT_STORED,
}


# [[sim]] faults = [...] (config/sim_faults.py); bits as Tabellen 8.1 and 8.3 number them
OVER_CURRENT_FAULT = SimFault("over_current", "alarm Überstrom, 16-90 00000020h: the drive trips")
ALARM = SimFault("alarm", "an alarm of 16-90: the drive trips until reset", value="a bit of alarm word 16-90")
TRIP_LOCK = SimFault("trip_lock", "an alarm with trip lock: only a power cycle clears it", value="a bit of 16-90")
WARNING = SimFault("warning", "a warning of 16-92", value="a bit of warning word 16-92", lasting=True)
POWER_CYCLE = SimFault("power_cycle", "mains off and on")
FAULTS = (UNPLUG, OVER_CURRENT_FAULT, ALARM, TRIP_LOCK, WARNING, POWER_CYCLE)
_OWN_FAULTS = {f.name for f in FAULTS if f is not UNPLUG}


def _element(index: int, subindex: int) -> int:
    """The element of a parameter an SDO sub-index names: [i] of an array at
    sub-index i + 1 (A35, as parameters.sdo_object), 0 for a single value."""
    return subindex - 1 if index in ARRAYS else subindex


def _baud_code(bitrate: int) -> int | None:
    """10-01 of a bus bit rate (Tabelle 6.1), None for one the drive does not offer."""
    for code, rate in BAUD_CODES.items():
        if rate == bitrate:
            return code
    return None


class Fc280Simulator(SimulatedCanopenSlave):
    """See the module docstring. parameters: raw values by parameter number
    (arrays as lists), the drive's saved values when it is first switched on."""

    emcy_text = staticmethod(emcy_text)  # its EMCYs in the manual's words, in its records

    def __init__(
        self,
        node_id: int,
        *,
        settings: BusSettings,
        clock,
        pump=None,
        name: str | None = None,
        parameters: Mapping[str, int | Sequence[int]] | None = None,
        eds=None,
    ) -> None:
        with shipped_eds("fc280.eds") if eds is None else contextlib.nullcontext(eds) as path:
            super().__init__(
                node_id, eds=str(path), settings=settings, clock=clock, pump=pump, name=name or f"fc280 {node_id}"
            )
        kept = {"10-02": node_id}
        code = _baud_code(settings.bitrate)
        if code is not None:
            kept["10-01"] = code
        self.model = Fc280Model(parameters, kept=kept, now_ns=clock.now_ns())
        self.model.snapshot = self._snapshot
        self._power_on = True  # the next application reset is a power-up
        self._reported: list[tuple[str, int]] = []  # the events the last EMCYs told about
        self._reported_from: tuple | None = None  # the words and 8-07 _reported was found in
        self._error_code = 0  # 603Fh
        self._dimension_key: tuple | None = None  # the stored bytes of 604Ch sub 1, 2 _dimension_value is of
        self._dimension_value = (1, 1)

    # ------------------------------------------------------------------ test and operator API

    def parameter(self, number: str, sub: int = 0) -> int | str:
        """A parameter's raw value (text for VisStr), as the drive has it."""
        with self._lock:
            return self.model.read(number, sub)

    def set_parameter(self, number: str, raw: int, sub: int = 0) -> None:
        """A write from the drive's LCP: the model's rules (Refused), no bus."""
        with self._lock:
            self.model.write(number, raw, self._clock_ns(), sub)
            self._flush_writes(self._clock_ns())

    def inject(self, fault: str, value, on: bool) -> None:
        """The faults of FAULTS (from [[sim]] faults or a test); unplug is
        every CANopen slave's."""
        if fault not in _OWN_FAULTS:
            super().inject(fault, value, on)
            return
        if fault == POWER_CYCLE.name:
            self.power_cycle()
            return
        with self._lock:
            model = self.model
            model.advance(self._clock_ns())
            if fault == OVER_CURRENT_FAULT.name:
                model.over_current()
            elif fault == ALARM.name:
                model.trip(int(value))
            elif fault == TRIP_LOCK.name:
                model.trip(int(value), lock=True)
            elif on:  # WARNING
                model.warn(int(value))
            else:
                model.clear_warning(int(value))
            self._report_events()

    def power_cycle(self) -> None:
        """Mains off and on: RAM from the non-volatile memory, a pending
        restore applied (Alarm 80), boot-up frame, pre-operational."""
        with self._lock:
            self._power_on = True
            super().power_cycle()

    # ------------------------------------------------------------------ device behaviour

    def run_device(self, now_ns: int) -> None:
        self.model.advance(now_ns)
        self._report_events()

    def _report_events(self) -> None:
        """EMCY per 8-07 (§3.1.4): one for each alarm (and warning) that
        appears; the all-zero one when none is left."""
        model = self.model
        words = {**model.alarms, **model.warnings()}
        trigger = model.settings().diagnosis
        key = (trigger, *words.values())
        if key == self._reported_from:
            return  # the same events as last time: nothing to send
        self._reported_from = key
        active = emcy.events(words, emcy.watched_words(trigger))
        if not active and self._reported and trigger != emcy.DIAGNOSIS_OFF:
            self._error_code = 0
            self.send_emcy(0x0000, 0x00)
        for word, bit in active:
            if (word, bit) not in self._reported:
                code, register, data = emcy.payload(word, bit, words)
                self._error_code = code
                self.send_emcy(code, register, data)
        self._reported = active

    def on_state_change(self, old: int, new: int) -> None:
        if old == STATE_BOOTUP:
            self._reported = []  # an alarm still present is reported again after booting
            self._reported_from = None

    def on_reset_application(self) -> None:
        super().on_reset_application()  # the application area back to the EDS values
        now = self._clock_ns()
        if self._power_on:
            self.model.power_cycle(now)
        else:
            self.model.reset_node(now)
        self._power_on = False
        self._error_code = 0
        self._put_back(PROFILE)

    def on_reset_communication(self) -> None:
        self._put_back(COMMUNICATION)

    def on_comm_error(self) -> None:
        self.model.comm_lost(self._clock_ns())
        self._report_events()

    def on_comm_restored(self) -> None:
        self.model.comm_restored(self._clock_ns())

    def on_rpdo(self, number: int) -> None:
        self.model.advance(self._clock_ns())

    # ------------------------------------------------------------------ saved objects

    def _snapshot(self) -> dict[str, dict]:
        """The object values the non-volatile memory keeps besides the parameters."""
        store = self.node.data_store
        communication = {
            (index, sub): data
            for index, subs in store.items()
            if 0x1000 <= index <= 0x1FFF and index not in (STORE_PARAMETERS, RESTORE_DEFAULTS)
            for sub, data in subs.items()
        }
        profile = {(index, sub): data for index in PROFILE_SETTINGS for sub, data in store.get(index, {}).items()}
        return {COMMUNICATION: communication, PROFILE: profile}

    def _put_back(self, section: str) -> None:
        for (index, sub), data in self.model.store.saved_objects.get(section, {}).items():
            self._store(index, sub, data)

    # ------------------------------------------------------------------ objects

    def object_read(self, index: int, subindex: int, od: ODVariable):
        model = self.model
        number = NUMBERS.get(index)
        if number is not None:
            if ARRAYS.get(index) and subindex == 0:
                return ARRAYS[index]  # the number of elements (CiA 301 ARRAY)
            value = self._refusing(model.read, number, _element(index, subindex))
            return value.encode("ascii") if isinstance(value, str) else value
        if index in (STORE_PARAMETERS, RESTORE_DEFAULTS):
            return od.default  # what the device can do (CiA 301), not the last signature
        if index == ERROR_REGISTER:
            return emcy.ERROR_REGISTER_GENERIC if model.tripped else 0
        if index == ERROR_CODE:
            return self._error_code if model.tripped or any(model.warnings().values()) else 0
        if index == STATUSWORD:
            return model.dsp_status_word()
        if index in VELOCITY_OUTPUTS:
            numerator, denominator = self._dimension()
            return int16(round_half_away(model.velocity_rpm * denominator / numerator))
        return None

    def pdo_source(self, index: int, subindex: int):
        """A TPDO-mapped parameter (a readout such as 16-03 or an alarm word)
        straight from the parameter memory, as object_read gives it: the
        packing runs at every step. An element that does not exist reads 0,
        as object_read's refusal packs; VisStr and the element count keep
        the object_read path."""
        number = NUMBERS.get(index)
        if number is None or (ARRAYS.get(index) and subindex == 0) or PARAMETERS[number].type == "VisStr":
            return None
        element = _element(index, subindex)

        def read() -> int:
            value = self.model.store.values[number]  # model and memory are replaced at a power cycle
            if isinstance(value, list):
                return value[element] if 0 <= element < len(value) else 0
            return value  # type: ignore[return-value]  # VisStr left out above

        return read

    def object_write(self, index: int, subindex: int, od: ODVariable, data: bytes, local: bool) -> None:
        value = od.decode_raw(data)
        if not isinstance(value, int):
            return  # the VisStr parameters are read-only; LocalNode refused a write already
        now = self._clock_ns()
        model = self.model
        if index in PARAMETER_INDICES:
            self._refusing(model.write, number_of(index), value, now, _element(index, subindex))
        elif index == CONTROLWORD:
            self._refusing(model.dsp_control, value, now)
        elif index == TARGET_VELOCITY:
            numerator, denominator = self._dimension()
            self._refusing(model.dsp_target, Fraction(value * numerator, denominator), now)
        elif index in (DIMENSION_FACTOR, SETPOINT_FACTOR) and value == 0:
            raise SdoAbortedError(ABORT_VALUE_RANGE)  # a factor of 0 (or a division by it)
        elif index == STORE_PARAMETERS:
            if value != SAVE_SIGNATURE:
                raise SdoAbortedError(ABORT_NOT_STORED)
            self._refusing(model.save, subindex)
        elif index == RESTORE_DEFAULTS:
            if value != LOAD_SIGNATURE:
                raise SdoAbortedError(ABORT_NOT_STORED)
            self._refusing(model.restore, subindex)
        elif index == SYNC_COB_ID and value & (SYNC_PRODUCER | SYNC_EXTENDED):
            raise SdoAbortedError(ABORT_VALUE_RANGE)  # Tabelle 7.4: the drive makes no SYNC, 11-bit only
        elif TPDO_COMM <= index <= TPDO_COMM + 2 and subindex in (TPDO_INHIBIT, TPDO_EVENT_TIMER):
            if value > PDO_TIME_MAX:
                raise SdoAbortedError(ABORT_VALUE_HIGH)

    def _dimension(self) -> tuple[int, int]:
        """604Ch vl dimension factor (numerator, denominator); decoded again only
        when its stored bytes change (object_read adds nothing to 604Ch)."""
        stored = self.node.data_store.get(DIMENSION_FACTOR, {})
        key = (stored.get(1), stored.get(2))
        if key != self._dimension_key:
            numerator = self.read(DIMENSION_FACTOR, 1)
            denominator = self.read(DIMENSION_FACTOR, 2)
            self._dimension_key, self._dimension_value = key, ((numerator or 1), (denominator or 1))
        return self._dimension_value

    @staticmethod
    def _refusing(action, *args):
        """Run a model action; its refusal is the SDO abort of Tabelle 8.8."""
        try:
            return action(*args)
        except Refused as exc:
            raise SdoAbortedError(ABORTS[exc.reason]) from None
