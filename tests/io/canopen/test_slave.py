"""The generic simulated CANopen slave (CiA 301) on the virtual bus, byte by
byte, with no device behaviour: the LTMR's EDS (io_config/eds/ltmr.eds) is
only its object dictionary here. Node 40 = 0x28 as in the LTMR manual's
examples; the test is the master."""

from __future__ import annotations

from softplc.runtime.io.canopen.cia301 import (
    ABORT_BAD_COMMAND,
    ABORT_DEVICE_STATE,
    ABORT_NO_OBJECT,
    ABORT_NO_SUBINDEX,
    ABORT_NOT_MAPPABLE,
    ABORT_PDO_LENGTH,
    ABORT_READ_ONLY,
    ABORT_VALUE_RANGE,
    NMT_PRE_OPERATIONAL,
    NMT_RESET_COMMUNICATION,
    NMT_RESET_NODE,
    NMT_START,
    NMT_STOP,
    STATE_OPERATIONAL,
    STATE_PRE_OPERATIONAL,
    STATE_STOPPED,
)

from .bench import MS, abort_frame, write_ok
from .slaves import NODE, RecordingSlave, eds_path

TPDO1, RPDO1, EMCY, HEARTBEAT = 0x1A8, 0x228, 0x0A8, 0x728


def _remap_tpdo1(bench, entries, *, transmission=255, inhibit_100us=None, event_ms=None):
    """The CiA 301 procedure, as a master does it: invalidate, sub 0 := 0,
    entries, sub 0 := n, parameters, validate. Every step must be confirmed."""
    steps = [(0x1800, 1, 0x800001A8, 4), (0x1A00, 0, 0, 1)]
    steps += [(0x1A00, i, entry, 4) for i, entry in enumerate(entries, start=1)]
    steps += [(0x1A00, 0, len(entries), 1), (0x1800, 2, transmission, 1)]
    if inhibit_100us is not None:
        steps.append((0x1800, 3, inhibit_100us, 2))
    if event_ms is not None:
        steps.append((0x1800, 5, event_ms, 2))
    steps.append((0x1800, 1, 0x1A8, 4))
    for index, sub, value, size in steps:
        assert bench.sdo_write(NODE, index, sub, value, size) == write_ok(index, sub), (hex(index), sub)


# ---------------------------------------------------------------------------- NMT


def test_power_up_sends_the_boot_up_frame_and_enters_pre_operational(bench, slave):
    assert bench.frames == [(0, HEARTBEAT, b"\x00")]  # CiA 301 boot-up: 0x700 + 40, [00]
    assert slave.nmt_state == STATE_PRE_OPERATIONAL
    assert ("state", 0, STATE_PRE_OPERATIONAL) in slave.events
    bench.run_ms(500)
    assert bench.frames == [(0, HEARTBEAT, b"\x00")]  # 0x1017 = 0: no heartbeat, no PDO in pre-op


def test_nmt_start_sends_tpdo1_once_and_stop_silences_sdo(bench, slave):
    slave.write(0x2004, 0x06, 0x6083)  # 455 as digest 001 §6.3 decodes it
    bench.clear()
    bench.send(0x000, "01 28")  # start node 40
    assert slave.nmt_state == STATE_OPERATIONAL
    assert bench.frames_with(TPDO1) == [bytes.fromhex("83 60 00 00 00 00 00 00")]
    bench.run_ms(300)
    assert len(bench.frames_with(TPDO1)) == 1  # type 255: nothing changed, nothing sent
    bench.nmt(NMT_STOP, NODE)
    assert slave.nmt_state == STATE_STOPPED
    bench.clear()
    bench.send(0x628, "40 18 10 01 00 00 00 00")
    assert bench.frames == []  # Stopped: no SDO
    bench.nmt(NMT_PRE_OPERATIONAL, NODE)
    assert slave.nmt_state == STATE_PRE_OPERATIONAL
    assert bench.sdo_read(NODE, 0x1018, 1) == bytes.fromhex("43 18 10 01 5A 00 00 03")  # vendor 0x0300005A


def test_nmt_for_all_nodes_and_for_another_node(bench, slave):
    bench.nmt(NMT_START, 41)
    assert slave.nmt_state == STATE_PRE_OPERATIONAL
    bench.nmt(NMT_START, 0)  # node 0: every node
    assert slave.nmt_state == STATE_OPERATIONAL


def test_reset_communication_restores_the_communication_objects_only(bench, slave):
    assert bench.sdo_write(NODE, 0x1017, 0, 100, 2) == write_ok(0x1017, 0)
    assert bench.sdo_write(NODE, 0x2007, 0x03, 50, 2) == write_ok(0x2007, 0x03)
    bench.nmt(NMT_START, NODE)
    bench.clear()
    bench.nmt(NMT_RESET_COMMUNICATION, NODE)
    assert bench.frames == [(0, HEARTBEAT, b"\x00")]
    assert slave.nmt_state == STATE_PRE_OPERATIONAL
    assert slave.read(0x1017) == 0  # back to the EDS value
    assert slave.read(0x2007, 0x03) == 50  # the application keeps its value
    assert ("reset application",) not in slave.events[1:]


def test_reset_node_also_restarts_the_application(bench, slave):
    assert bench.sdo_write(NODE, 0x2007, 0x03, 50, 2) == write_ok(0x2007, 0x03)
    events = len(slave.events)
    bench.clear()
    bench.nmt(NMT_RESET_NODE, NODE)
    assert bench.frames == [(0, HEARTBEAT, b"\x00")]
    assert ("reset application",) in slave.events[events:]
    assert slave.read(0x2007, 0x03) == 0


class SavingSlave(RecordingSlave):
    """A device that keeps a producer heartbeat time in non-volatile memory."""

    saved_heartbeat_ms = 0

    def on_reset_communication(self):
        self.events.append(("reset communication",))
        if self.saved_heartbeat_ms:
            self._store(0x1017, 0, self.saved_heartbeat_ms)


def test_saved_communication_parameters_come_back_at_every_reset_communication(bench):
    with eds_path("ltmr.eds") as path:
        slave = SavingSlave(NODE, eds=str(path), settings=bench.settings, clock=bench.clock, pump=bench.pump)
    bench.add(slave)
    assert slave.events.count(("reset communication",)) == 1  # power-up
    slave.saved_heartbeat_ms = 100
    bench.nmt(NMT_RESET_COMMUNICATION, NODE)
    assert slave.read(0x1017) == 100  # put back after the EDS values, before the heartbeat is set up
    bench.clear()
    bench.run_ms(250)
    assert bench.times_of(HEARTBEAT) == [t * MS for t in (100, 200)]
    slave.saved_heartbeat_ms = 0
    bench.nmt(NMT_RESET_NODE, NODE)
    assert slave.read(0x1017) == 0
    assert slave.events.count(("reset communication",)) == 3


def test_power_cycle_boots_again(bench, slave):
    bench.nmt(NMT_START, NODE)
    bench.clear()
    slave.power_cycle()
    bench.pump.settle()
    assert bench.frames == [(0, HEARTBEAT, b"\x00")]
    assert slave.nmt_state == STATE_PRE_OPERATIONAL


# ---------------------------------------------------------------------------- SDO server


def test_malformed_sdo_requests_are_counted_and_refused(bench, slave, caplog):
    """Found by the fuzz harness (tests/fuzz): a frame to 0x628 shorter than
    8 bytes, or an upload segment request before any upload, made canopen's
    SDO server fail, logged with a traceback for every such frame. The slave
    drops a short one (an SDO frame has 8 bytes) and aborts a segment before
    any segmented transfer (0504 0001, the request code is not valid),
    counting both; a whole request still gets its answer."""
    for short in ("", "40", "40 18 10 01 00 00 00"):
        bench.clear()
        bench.send(0x628, short)
        assert bench.frames_with(0x5A8) == []
    assert bench.sdo(NODE, "60 00 00 00 00 00 00 00") == abort_frame(0, 0, ABORT_BAD_COMMAND)
    assert bench.sdo_read(NODE, 0x1017, 0)[0] == 0x4B  # an expedited upload: still no segmented transfer
    assert bench.sdo(NODE, "00 01 02 03 04 05 06 07") == abort_frame(0x1017, 0, ABORT_BAD_COMMAND)
    assert slave.malformed == 5
    assert not [r for r in caplog.records if r.exc_info]
    assert bench.sdo_read(NODE, 0x1018, 1) == bytes.fromhex("43 18 10 01 5A 00 00 03")


def test_sdo_aborts_for_read_only_missing_objects_and_sub_indices(bench, slave):
    assert bench.sdo(NODE, "23 18 10 01 00 00 00 00") == abort_frame(0x1018, 1, ABORT_READ_ONLY)
    assert bench.sdo_read(NODE, 0x2009, 0) == abort_frame(0x2009, 0, ABORT_NO_OBJECT)
    assert bench.sdo_read(NODE, 0x1018, 5) == abort_frame(0x1018, 5, ABORT_NO_SUBINDEX)
    # an ARRAY object (0x1003 has 5 history entries, manual 001 §4)
    assert bench.sdo_read(NODE, 0x1003, 6) == abort_frame(0x1003, 6, ABORT_NO_SUBINDEX)
    assert bench.sdo_write(NODE, 0x1003, 0, 1, 1) == abort_frame(0x1003, 0, ABORT_VALUE_RANGE)  # "only 0"
    assert bench.sdo_write(NODE, 0x1029, 1, 3, 1) == abort_frame(0x1029, 1, ABORT_VALUE_RANGE)


def test_segmented_upload_of_the_hardware_version(bench, slave):
    # 0x1009 "M1.0-ES1.0" (manual 001 §4): 10 bytes, more than an expedited transfer carries
    assert bench.sdo_read(NODE, 0x1009, 0) == bytes.fromhex("41 09 10 00 0A 00 00 00")
    assert bench.sdo(NODE, "60 00 00 00 00 00 00 00") == b"\x00" + b"M1.0-ES"
    assert bench.sdo(NODE, "70 00 00 00 00 00 00 00") == bytes([0x10 | (4 << 1) | 1]) + b"1.0" + bytes(4)


# ---------------------------------------------------------------------------- PDO mapping


def test_a_valid_pdo_is_not_remapped(bench, slave):
    assert bench.sdo_write(NODE, 0x1A00, 0, 0, 1) == abort_frame(0x1A00, 0, ABORT_DEVICE_STATE)
    assert bench.sdo_write(NODE, 0x1A00, 1, 0x20040210, 4) == abort_frame(0x1A00, 1, ABORT_DEVICE_STATE)
    # CiA 301: no new COB-ID for a valid PDO
    assert bench.sdo_write(NODE, 0x1800, 1, 0x1A9, 4) == abort_frame(0x1800, 1, ABORT_VALUE_RANGE)


def test_mapping_entries_need_sub_index_0_cleared_first(bench, slave):
    assert bench.sdo_write(NODE, 0x1800, 1, 0x800001A8, 4) == write_ok(0x1800, 1)
    assert bench.sdo_write(NODE, 0x1A00, 1, 0x20040210, 4) == abort_frame(0x1A00, 1, ABORT_DEVICE_STATE)


def test_mapping_refuses_what_cannot_be_mapped_or_does_not_fit(bench, slave):
    assert bench.sdo_write(NODE, 0x1800, 1, 0x800001A8, 4) == write_ok(0x1800, 1)
    assert bench.sdo_write(NODE, 0x1A00, 0, 0, 1) == write_ok(0x1A00, 0)
    # 540 operating mode (0x2005:01) has no PDO mapping in the EDS
    assert bench.sdo_write(NODE, 0x1A00, 1, 0x20050110, 4) == abort_frame(0x1A00, 1, ABORT_NOT_MAPPABLE)
    # a 16-bit object mapped with 8 bits
    assert bench.sdo_write(NODE, 0x1A00, 1, 0x20040608, 4) == abort_frame(0x1A00, 1, ABORT_NOT_MAPPABLE)
    # 0x2004 is read-only: not into an RPDO
    assert bench.sdo_write(NODE, 0x1400, 1, 0x80000228, 4) == write_ok(0x1400, 1)
    assert bench.sdo_write(NODE, 0x1600, 0, 0, 1) == write_ok(0x1600, 0)
    assert bench.sdo_write(NODE, 0x1600, 1, 0x20040610, 4) == abort_frame(0x1600, 1, ABORT_NOT_MAPPABLE)
    # 32 + 32 + 16 bits: more than 8 bytes
    for sub, entry in ((1, 0x30000320), (2, 0x30000420), (3, 0x20040610)):
        assert bench.sdo_write(NODE, 0x1A00, sub, entry, 4) == write_ok(0x1A00, sub)
    assert bench.sdo_write(NODE, 0x1A00, 0, 3, 1) == abort_frame(0x1A00, 0, ABORT_PDO_LENGTH)
    assert bench.sdo_write(NODE, 0x1A00, 0, 5, 1) == abort_frame(0x1A00, 0, ABORT_PDO_LENGTH)  # 4 entries
    assert bench.sdo_write(NODE, 0x1A00, 0, 2, 1) == write_ok(0x1A00, 0)


def test_a_remapped_tpdo_carries_what_the_master_mapped(bench, slave):
    # the lead's TPDO2 layout on TPDO1: 451 trip code, 460 alarm code, 465, 466
    _remap_tpdo1(bench, [0x20040210, 0x20040B10, 0x20041010, 0x20041110])
    for sub, value in ((0x02, 4), (0x0B, 109), (0x10, 87), (0x11, 250)):
        slave.write(0x2004, sub, value)
    bench.clear()
    bench.nmt(NMT_START, NODE)
    assert bench.frames_with(TPDO1) == [bytes.fromhex("04 00 6D 00 57 00 FA 00")]


# ---------------------------------------------------------------------------- TPDO transmission


def test_tpdo_on_change_respects_the_inhibit_time(bench, slave):
    _remap_tpdo1(bench, [0x20040610], inhibit_100us=1000)  # 100 ms
    bench.nmt(NMT_START, NODE)
    bench.clear()
    for value in range(1, 31):  # a new value every 10 ms for 300 ms
        slave.write(0x2004, 0x06, value)
        bench.run_ms(10)
    times = bench.times_of(TPDO1)
    assert all(b - a >= 100 * MS for a, b in zip(times, times[1:]))
    assert len(times) == 3
    bench.run_ms(200)
    assert bench.frames_with(TPDO1)[-1] == (30).to_bytes(2, "little")  # the last change still goes out


def test_tpdo_event_timer_is_in_milliseconds(bench, slave):
    # A7: the manual says 0.1 ms, CiA 301 says ms; 200 means 200 ms here
    _remap_tpdo1(bench, [0x20040610], event_ms=200)
    bench.nmt(NMT_START, NODE)
    start = bench.clock.now_ns()
    bench.run_ms(1000)
    assert [t - start for t in bench.times_of(TPDO1)] == [0, 200 * MS, 400 * MS, 600 * MS, 800 * MS, 1000 * MS]


def test_synchronous_tpdos_type_0_on_change_and_type_3_every_third_sync(bench, slave):
    _remap_tpdo1(bench, [0x20040610], transmission=0)
    bench.nmt(NMT_START, NODE)
    assert bench.frames_with(TPDO1) == []  # synchronous: nothing before a SYNC
    bench.send(0x080, b"")
    bench.send(0x080, b"")
    assert len(bench.frames_with(TPDO1)) == 1  # the first SYNC after entering Operational
    slave.write(0x2004, 0x06, 7)
    bench.run_ms(50)
    assert len(bench.frames_with(TPDO1)) == 1  # a change waits for the SYNC
    bench.send(0x080, b"")
    assert bench.frames_with(TPDO1)[-1] == b"\x07\x00"

    bench.nmt(NMT_PRE_OPERATIONAL, NODE)
    assert bench.sdo_write(NODE, 0x1800, 1, 0x800001A8, 4) == write_ok(0x1800, 1)
    assert bench.sdo_write(NODE, 0x1800, 2, 3, 1) == write_ok(0x1800, 2)
    assert bench.sdo_write(NODE, 0x1800, 1, 0x1A8, 4) == write_ok(0x1800, 1)
    bench.nmt(NMT_START, NODE)
    bench.clear()
    for _ in range(9):
        bench.send(0x080, b"")
    assert len(bench.frames_with(TPDO1)) == 3


def test_reserved_transmission_types_are_refused(bench, slave):
    assert bench.sdo_write(NODE, 0x1800, 2, 245, 1) == abort_frame(0x1800, 2, ABORT_VALUE_RANGE)
    assert bench.sdo_write(NODE, 0x1800, 2, 253, 1) == abort_frame(0x1800, 2, ABORT_VALUE_RANGE)  # RTR only


# ---------------------------------------------------------------------------- RPDO


def test_rpdo_only_in_operational_little_endian_into_the_mapped_objects(bench, slave):
    # RPDO1 factory mapping (manual 001 §4): 0x2008:05, 0x2008:04, 0x2008:01
    bench.send(RPDO1, "01 00 00 00 34 12")
    assert slave.read(0x2008, 0x05) == 0 and ("rpdo", 1) not in slave.events  # pre-operational
    bench.nmt(NMT_START, NODE)
    bench.send(RPDO1, "01 00 00 00 34 12")
    assert slave.read(0x2008, 0x05) == 0x0001
    assert slave.read(0x2008, 0x01) == 0x1234  # digest 001 §7.2: 700 = 0x1234
    assert ("rpdo", 1) in slave.events
    bench.send(RPDO1, "08 00")  # shorter than the 6 mapped bytes
    assert slave.read(0x2008, 0x05) == 0x0001


def test_a_synchronous_rpdo_takes_effect_at_the_next_sync(bench, slave):
    assert bench.sdo_write(NODE, 0x1400, 2, 1, 1) == write_ok(0x1400, 2)
    bench.nmt(NMT_START, NODE)
    bench.send(RPDO1, "02 00 00 00 00 00")
    assert slave.read(0x2008, 0x05) == 0
    bench.send(0x080, b"")
    assert slave.read(0x2008, 0x05) == 0x0002


# ---------------------------------------------------------------------------- EMCY


def test_emcy_frame_error_register_and_history(bench, slave):
    bench.nmt(NMT_START, NODE)
    bench.clear()
    slave.send_emcy(0x1000, 0x01, b"\x04\x00")
    slave.send_emcy(0x8130, 0x11)
    bench.pump.settle()
    assert bench.frames_with(EMCY) == [
        bytes.fromhex("00 10 01 04 00 00 00 00"),
        bytes.fromhex("30 81 11 00 00 00 00 00"),
    ]
    assert bench.sdo_read(NODE, 0x1001, 0) == bytes.fromhex("4F 01 10 00 11 00 00 00")
    assert bench.sdo_read(NODE, 0x1003, 0) == bytes.fromhex("4F 03 10 00 02 00 00 00")
    assert bench.sdo_read(NODE, 0x1003, 1) == bytes.fromhex("43 03 10 01 30 81 00 00")  # newest first
    assert bench.sdo_read(NODE, 0x1003, 2) == bytes.fromhex("43 03 10 02 00 10 00 00")
    slave.send_emcy(0x0000, 0x00)  # error reset: not in the history
    assert slave.read(0x1003, 0) == 2
    assert bench.sdo_write(NODE, 0x1003, 0, 0, 1) == write_ok(0x1003, 0)
    assert slave.read(0x1003, 0) == 0 and slave.read(0x1003, 1) == 0


def test_the_history_keeps_the_newest_five(bench, slave):
    for code in range(0x1001, 0x1008):
        slave.send_emcy(code, 0x01)
    assert slave.read(0x1003, 0) == 5
    assert [slave.read(0x1003, sub) for sub in range(1, 6)] == [0x1007, 0x1006, 0x1005, 0x1004, 0x1003]


def test_no_emcy_in_stopped(bench, slave):
    bench.nmt(NMT_STOP, NODE)
    bench.clear()
    slave.send_emcy(0x1000, 0x01)
    bench.pump.settle()
    assert bench.frames_with(EMCY) == []
    assert slave.read(0x1001) == 0x01


# ---------------------------------------------------------------------------- the cable


def test_an_unplugged_slave_neither_hears_nor_speaks(bench, slave):
    assert bench.sdo_write(NODE, 0x1017, 0, 100, 2) == write_ok(0x1017, 0)
    slave.unplug()
    bench.clear()
    bench.send(0x628, "40 18 10 01 00 00 00 00")
    bench.nmt(NMT_START, NODE)
    bench.run_ms(300)
    assert bench.frames == []
    assert slave.nmt_state == STATE_PRE_OPERATIONAL
    slave.plug()
    bench.run_ms(100)
    assert bench.frames_with(HEARTBEAT) == [b"\x7f"]
    assert bench.sdo_read(NODE, 0x1018, 1) == bytes.fromhex("43 18 10 01 5A 00 00 03")


def test_any_eds_will_do(bench):
    """The slave knows no device: the FC 280's EDS gives an FC 280-shaped node."""
    with eds_path("fc280.eds") as path:
        other = bench.add(RecordingSlave(1, eds=str(path), settings=bench.settings, clock=bench.clock, pump=bench.pump))
    assert bench.frames_with(0x701) == [b"\x00"]
    vendor = other.read(0x1018, 1)
    assert bench.sdo_read(1, 0x1018, 1) == bytes.fromhex("43 18 10 01") + vendor.to_bytes(4, "little")


class LiveSlave(RecordingSlave):
    """A device whose 0x2004:06 is live: object_read and pdo_source both give it."""

    live = 7

    def object_read(self, index, subindex, od):
        return self.live if (index, subindex) == (0x2004, 0x06) else None

    def pdo_source(self, index, subindex):
        return (lambda: self.live) if (index, subindex) == (0x2004, 0x06) else None


def test_a_live_value_goes_out_at_the_next_step_without_any_write(bench):
    with eds_path("ltmr.eds") as path:
        slave = LiveSlave(NODE, eds=str(path), settings=bench.settings, clock=bench.clock, pump=bench.pump)
    bench.add(slave)
    _remap_tpdo1(bench, [0x20040610, 0x20040710])  # 0x2004:07 from the store
    bench.nmt(NMT_START, NODE)
    assert bench.frames_with(TPDO1) == [bytes.fromhex("07 00 00 00")]
    assert bench.sdo_read(NODE, 0x2004, 0x06)[4:6] == (7).to_bytes(2, "little")  # the same value both ways
    bench.clear()
    slave.live = 0x1234
    bench.run_ms(10)
    slave._store(0x2004, 0x07, 0x55)  # a value the device puts in the store itself
    bench.run_ms(10)
    assert bench.frames_with(TPDO1) == [bytes.fromhex("34 12 00 00"), bytes.fromhex("34 12 55 00")]


class _LiveSlave(RecordingSlave):
    """A device whose 2004:06 and 2004:07 are live values (object_read), as
    a device model's measurements are."""

    live = {0x06: 1234, 0x07: b"\x34\x12"}

    def object_read(self, index, subindex, od):
        return self.live.get(subindex) if index == 0x2004 else None


def test_a_tpdo_packs_the_devices_live_values_and_a_read_callback_added_later(bench):
    with eds_path("ltmr.eds") as path:
        live = bench.add(_LiveSlave(NODE, eds=str(path), settings=bench.settings, clock=bench.clock, pump=bench.pump))
    _remap_tpdo1(bench, [0x20040610, 0x20040710, 0x20040810])
    live.write(0x2004, 0x08, 7)  # a stored value: no live one for it
    bench.clear()
    bench.nmt(NMT_START, NODE)
    assert bench.frames_with(TPDO1) == [bytes.fromhex("D2 04 34 12 07 00")]
    # canopen's own API: a read callback added later answers first from then on
    live.node.add_read_callback(lambda index, subindex, od: 99 if (index, subindex) == (0x2004, 0x08) else None)
    live.live = {0x06: 1235, 0x07: b"\x34\x12"}
    bench.run_ms(10)
    assert bench.frames_with(TPDO1)[-1] == bytes.fromhex("D3 04 34 12 63 00")
