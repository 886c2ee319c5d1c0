"""The CANopen master boots, supervises and recovers nodes as a CANopen
manager does (CiA 301/302), against the simulated LTMR on the virtual bus."""

from __future__ import annotations

import logging

import pytest

from softplc.runtime.devices.ltmr.sim import LtmrSimulator
from softplc.runtime.engine.monitor import status_line
from softplc.runtime.io.can.bus import BusSettings
from softplc.runtime.io.canopen.node import NodeState

from .plant import LTMR_NODE

MS = 1_000_000

WATCH = """
PROGRAM Watch
VAR
    operational : BOOL;
    lost : BOOL;
    status1 AT %IW100 : WORD;
END_VAR
operational := CANOPEN_NODE[40].Operational;
lost := CANOPEN_NODE[40].HeartbeatLost;
END_PROGRAM
"""

NMT_RESET_COMM_40 = bytes([0x82, 0x28])  # CiA 301: reset communication, node 40
NMT_START_40 = bytes([0x01, 0x28])


def _index(frames, can_id, data=None, after=-1):
    for i, (_t, cid, d) in enumerate(frames):
        if i > after and cid == can_id and (data is None or d == data):
            return i
    raise AssertionError(f"no frame 0x{can_id:03X} {data.hex(' ') if data else ''} after frame {after}")


def test_boot_up_order_reset_bootup_configure_start_pdos(plants):
    plant = plants(WATCH, program="Watch")
    plant.run_until(lambda: plant.get("Watch.operational"), 200, "node 40 operational")
    f = plant.frames
    reset = _index(f, 0x000, NMT_RESET_COMM_40)
    bootup = _index(f, 0x728, b"\x00", after=reset)
    # configuration by SDO: producer heartbeat 0x1017 := 100 ms, consumer 0x1016:01 := master 127 at 500 ms
    hb = _index(f, 0x628, bytes.fromhex("2B 17 10 00 64 00 00 00"), after=bootup)
    consumer = _index(f, 0x628, bytes.fromhex("23 16 10 01 F4 01 7F 00"), after=hb)
    fallback = _index(f, 0x628, bytes.fromhex("2B 07 20 21 02 00 00 00"), after=consumer)  # 682 := 2
    # TPDO2 remapped (CiA 301: invalidate, sub0 := 0, entries, sub0 := 4, type, validate)
    invalidate = _index(f, 0x628, bytes.fromhex("23 01 18 01 A8 02 00 80"), after=fallback)
    entry1 = _index(f, 0x628, bytes.fromhex("23 01 1A 01 10 02 04 20"), after=invalidate)  # 2004:02, 16 bit
    count = _index(f, 0x628, bytes.fromhex("2F 01 1A 00 04 00 00 00"), after=entry1)
    # inhibit time and event timer written although 0: the node's defaults might not be
    inhibit = _index(f, 0x628, bytes.fromhex("2B 01 18 03 00 00 00 00"), after=count)
    _index(f, 0x628, bytes.fromhex("2B 01 18 05 00 00 00 00"), after=inhibit)
    validate = _index(f, 0x628, bytes.fromhex("23 01 18 01 A8 02 00 00"), after=count)
    start = _index(f, 0x000, NMT_START_40, after=validate)
    tpdo1 = _index(f, 0x1A8, after=start)
    assert reset < bootup < hb < consumer < fallback < invalidate < start < tpdo1
    assert plant.sims[40].register(682) == 2
    assert plant.master.status().ok


def test_master_heartbeat_and_node_heartbeat_in_virtual_time(plants):
    plant = plants(WATCH, program="Watch")
    plant.run_until(lambda: plant.get("Watch.operational"), 200, "node 40 operational")
    plant.frames.clear()
    plant.run_ms(1000)
    master = [t for t, cid, d in plant.frames if cid == 0x77F]
    node = [t for t, cid, d in plant.frames if cid == 0x728]
    assert [d for _t, cid, d in plant.frames if cid == 0x77F][0] == b"\x05"  # master: operational
    assert [d for _t, cid, d in plant.frames if cid == 0x728][0] == b"\x05"  # node 40: operational
    assert {b - a for a, b in zip(master, master[1:])} == {100_000_000}
    assert {b - a for a, b in zip(node, node[1:])} == {100_000_000} and len(node) >= 9


def test_heartbeat_loss_is_seen_by_the_program_and_the_node_recovers_by_itself(plants):
    plant = plants(WATCH, program="Watch")
    plant.run_until(lambda: plant.get("Watch.operational"), 200, "node 40 operational")
    sim = plant.sims[40]
    sim.unplug()
    took = plant.run_until(lambda: plant.get("Watch.lost"), 1000, "heartbeat lost")
    assert 200 <= took <= 310  # heartbeat_timeout = 300 ms after the last heartbeat
    assert plant.master.node_state(40) == NodeState.LOST
    assert not plant.master.status().ok
    assert "heartbeat lost" in plant.master.status().message
    assert "canopen: 0/1 up; motor (40): heartbeat lost" in status_line(plant.engine)  # what the operator sees
    assert (plant.get("CANOPEN_MASTER.NodesConfigured"), plant.get("CANOPEN_MASTER.NodesOperational")) == (1, 0)
    sim.plug()
    plant.run_until(lambda: plant.get("Watch.operational"), 2000, "node 40 operational again")
    assert plant.master.status().ok
    assert (plant.get("CANOPEN_MASTER.NodesConfigured"), plant.get("CANOPEN_MASTER.NodesOperational")) == (1, 1)
    assert plant.node_diag(40, "Boots") >= 2


def test_a_missing_node_is_reported_and_booted_when_it_appears(plants, tmp_path):
    plant = plants(WATCH, program="Watch", sims=[])
    plant.run_ms(600)
    assert plant.master.node_state(40) == NodeState.MISSING
    assert plant.node_diag(40, "Missing")
    assert "no boot-up" in plant.master.status().message
    bus = plant.config.can[0]
    sim = LtmrSimulator(
        40, settings=BusSettings(bus.interface, bus.channel, bus.bitrate), clock=plant.engine.clock, pump=plant.pump
    )
    sim.start()
    plant.engine.drivers.insert(0, sim)
    try:
        plant.run_until(lambda: plant.get("Watch.operational"), 3000, "node 40 operational")
    finally:
        plant.engine.drivers.remove(sim)
        sim.stop()


def test_a_node_that_falls_to_pre_operational_is_restarted(plants):
    plant = plants(WATCH, program="Watch")
    plant.run_until(lambda: plant.get("Watch.operational"), 200, "node 40 operational")
    boots = plant.node_diag(40, "Boots")
    plant.master.endpoint.send(0x000, bytes([0x80, 40]))  # someone sends it to pre-operational
    plant.run_ms(300)
    plant.run_until(lambda: plant.get("Watch.operational"), 2000, "node 40 operational again")
    assert plant.node_diag(40, "Boots") == boots + 1  # reset communication, boot-up, configure, start


@pytest.mark.parametrize(
    ("frame", "what"),
    [((0x000, bytes([0x81, 40])), "NMT reset-node"), ((0x728, b"\x7f"), "bogus pre-operational heartbeat")],
)
def test_a_flood_of_resets_or_bogus_heartbeats_boots_the_node_three_times_in_ten_seconds(plants, caplog, frame, what):
    """Issue 31: a flood of NMT reset-node commands or bogus heartbeat states
    made the master reset the node 2,000 times in 10 s (and configure it as
    often: 13 SDO transfers each)."""
    plant = plants(WATCH, program="Watch")
    plant.run_until(lambda: plant.get("Watch.operational"), 200, "node 40 operational")
    plant.frames.clear()
    caplog.set_level(logging.INFO, logger="softplc.runtime.io.canopen")
    for _ in range(2000):  # 10 s: one every 5 ms, from another node of the bus
        plant.spy.send(*frame)
        plant.run_ms(5)
    resets = plant.frames_with(0x000).count(NMT_RESET_COMM_40)
    configurations = plant.frames_with(0x628).count(bytes.fromhex("2B 17 10 00 64 00 00 00"))  # 1017h := 100 ms
    assert resets <= 4 and configurations <= 4, (what, resets, configurations)
    assert plant.master.nodes[40].sup.held_off > 1900
    held = [r.getMessage() for r in caplog.records if "a flood of resets or bogus heartbeats?" in r.getMessage()]
    assert 1 <= len(held) <= 4 and held[0].startswith("canopen: node motor (40): ")
    # the flood over, the node is booted when its hold ends and runs
    plant.run_until(lambda: plant.get("Watch.operational"), 10_000, "node 40 operational after the flood")
    assert plant.master.status().ok


def test_a_failed_bus_is_reported_and_reopened(plants):
    plant = plants(WATCH, program="Watch")
    plant.run_until(lambda: plant.get("Watch.operational"), 200, "node 40 operational")
    plant.master.endpoint.bus.shutdown()  # the adapter goes away under the driver
    plant.run_ms(200)
    status = plant.master.status()
    assert not status.ok and "bus down" in status.message
    plant.run_until(
        lambda: plant.master.status().ok and plant.get("Watch.operational"), 3000, "bus reopened, node operational"
    )


# ---------------------------------------------------------------------------- node guarding

GUARDED = {k: v for k, v in LTMR_NODE.items() if k not in ("heartbeat", "heartbeat_timeout", "master_timeout")}
GUARDED.update(guard_time="50ms", life_time_factor=3)


def test_a_guarded_node_is_told_its_guard_time_and_asked_every_guard_time(plants):
    plant = plants(WATCH, program="Watch", nodes=[GUARDED])
    plant.run_until(lambda: plant.get("Watch.operational"), 300, "node 40 operational")
    sdo = plant.frames_with(0x628)
    # 0x1017 := 0 (no heartbeat), 0x100C := 50 ms, 0x100D := 3; no 0x1016 (the node watches by guarding)
    assert bytes.fromhex("2B 17 10 00 00 00 00 00") in sdo
    assert bytes.fromhex("2B 0C 10 00 32 00 00 00") in sdo
    assert bytes.fromhex("2F 0D 10 00 03 00 00 00") in sdo
    assert not any(frame[1:3] == bytes.fromhex("16 10") for frame in sdo)
    sim = plant.sims[40]
    assert (sim.read(0x100C), sim.read(0x100D), sim.read(0x1017)) == (50, 3, 0)
    plant.frames.clear()
    plant.remote.clear()
    plant.run_ms(500)
    requests = [t for t, cid in plant.remote if cid == 0x728]
    assert {b - a for a, b in zip(requests, requests[1:])} == {50_000_000} and len(requests) >= 9
    # the replies: operational (05) with the toggle bit alternating, one per request
    replies = plant.frames_with(0x728)
    assert {r[0] & 0x7F for r in replies} == {0x05}
    assert all(a[0] ^ b[0] == 0x80 for a, b in zip(replies, replies[1:]))
    assert len(replies) == len(requests)
    assert plant.master.node_state(40) == NodeState.OPERATIONAL and plant.master.status().ok


def test_a_guarded_node_that_stops_answering_is_lost_and_recovered(plants):
    plant = plants(WATCH, program="Watch", nodes=[GUARDED])
    plant.run_until(lambda: plant.get("Watch.operational"), 300, "node 40 operational")
    sim = plant.sims[40]
    sim.unplug()
    took = plant.run_until(lambda: plant.get("Watch.lost"), 1000, "node lost")
    assert 100 < took <= 160  # guard time 50 ms x life time factor 3 after the last good reply
    assert "node guarding lost (no good reply for 150 ms)" in plant.master.status().message
    assert plant.node_diag(40, "Lost") and plant.node_diag(40, "State") == NodeState.LOST
    plant.run_ms(100)
    assert sim.guarding_lost  # and the node's side: no request for its life time, the master is lost
    sim.plug()
    plant.run_until(lambda: plant.get("Watch.operational"), 2000, "node 40 operational again")
    assert plant.master.status().ok
    assert plant.node_diag(40, "Boots") >= 2


def test_a_guarding_reply_whose_toggle_did_not_alternate_is_no_good_reply(plants):
    from softplc.runtime.io.canopen.node import NodeSupervisor

    sup = NodeSupervisor(
        "x",
        5,
        mandatory=True,
        heartbeat_timeout_ns=0,
        boot_timeout_ns=10**9,
        retry_ns=10**9,
        guard_ns=50 * 10**6,
        life_time_factor=3,
    )
    sup.tick(0)
    sup.heartbeat(0x00, 0)  # boot-up
    sup.configured(True, "", 0)
    assert sup.guard_due(0) and not sup.guard_due(49 * 10**6) and sup.guard_due(50 * 10**6)
    sup.guard_reply(0x05, 10**6)  # toggle 0: good
    sup.guard_reply(0x05, 60 * 10**6)  # toggle 0 again: a reply went missing
    assert sup.toggle_errors == 1
    sup.guard_reply(0x85, 110 * 10**6)  # 0x85 is what follows 0x05: good again
    assert sup.toggle_errors == 1 and sup.deadline_ns == 260 * 10**6
    assert sup.tick(261 * 10**6) is None and sup.state == NodeState.LOST


def test_a_guarded_node_the_master_waits_for_is_asked_and_booted_once_it_answers():
    """Issue 33: a guarded node sends nothing unasked; a drive whose cable
    came back waited the boot timeout and the retry time (2.2 s) though
    it would have answered. Now the master asks while it waits, and boots
    it at its answer; a reset that never reached it is sent again."""
    from softplc.runtime.io.canopen.node import NodeSupervisor

    ms = 10**6
    sup = NodeSupervisor(
        "x",
        5,
        mandatory=True,
        heartbeat_timeout_ns=0,
        boot_timeout_ns=2000 * ms,
        retry_ns=200 * ms,
        guard_ns=50 * ms,
        life_time_factor=3,
    )
    assert sup.tick(0) == "reset" and sup.state == NodeState.BOOTING  # the cable is cut: nobody hears it
    assert not sup.guard_due(10 * ms)  # its boot-up is due first: no request, no early life guarding
    assert sup.guard_reply(0x7F, 20 * ms) is None  # an answer then is no reason yet
    assert sup.guard_due(50 * ms)  # a guard time on, no boot-up: is it there at all?
    assert sup.guard_reply(0x7F, 52 * ms) == "reset"  # alive, never booted: the reset did not reach it
    assert sup.state == NodeState.BOOTING and sup.boot_sent_ns == 52 * ms
    assert sup.tick(2052 * ms) is None and sup.state == NodeState.MISSING  # gone again: no boot-up
    assert sup.guard_due(2110 * ms)  # asked while missing, not only at the retry
    assert sup.guard_reply(0x7F, 2111 * ms) == "reset"  # heard: booted now, not at 2252 ms
    assert sup.heartbeat(0x00, 2115 * ms) == "configure"


def test_a_node_without_a_heartbeat_consumer_cannot_be_given_a_master_timeout(tmp_path):
    import pytest

    from softplc.runtime.config import config_from_dict
    from softplc.runtime.engine.build import build_engine
    from softplc.runtime.plugin.driver import DriverError

    from .plant import plant_config

    node = {"name": "pump", "id": 20, "eds": "fc280", "master_timeout": "500ms"}
    data = plant_config(tmp_path, WATCH, program="Watch", nodes=[node], sims=[])
    with pytest.raises(
        DriverError,
        match=r"canopen.node\[0\].master_timeout: the node has no heartbeat consumer "
        r"\(no 1016h in its EDS\): it cannot watch the master's heartbeat; "
        r"watch it with node guarding \(guard_time\) instead",
    ):
        build_engine(config_from_dict(data, tmp_path / "plant.toml"), virtual_time=True)


def test_an_sdo_value_too_large_for_its_object_names_the_file_and_the_key(tmp_path):
    """'canopen.node[0].sdo[0]: 999… does not fit' named no file."""
    from softplc.runtime.config import config_from_dict
    from softplc.runtime.engine.build import build_engine
    from softplc.runtime.plugin.driver import DriverError

    from .plant import plant_config

    node = dict(LTMR_NODE, sdo=[{"object": "2007:21", "value": 99_999_999_999}])
    data = plant_config(tmp_path, WATCH, program="Watch", nodes=[node])
    with pytest.raises(DriverError) as info:
        build_engine(config_from_dict(data, tmp_path / "plant.toml"), virtual_time=True)
    assert (
        str(info.value) == f"{tmp_path / 'plant.toml'}: canopen.node[0].sdo[0]: 99999999999 does not fit in 2 byte(s)"
    )


# ---------------------------------------------------------------------------- the CAN adapter comes up late


def test_a_can_adapter_missing_at_start_is_waited_for_and_the_node_booted(tmp_path, monkeypatch, caplog):
    """The PLC starts before its adapter (a plant PC's USB adapter comes up
    later): the master starts, says the bus is down, tries again with back-off
    (0.5 s doubling up to 10 s, engine time), and boots its node once it is
    there. The adapter is python-can's interface "late" (tests/io/can)."""
    from softplc.runtime.config import config_from_dict
    from softplc.runtime.engine.build import build_engine

    from ..can import late_adapter
    from .plant import plant_config

    late_adapter.register(monkeypatch)
    caplog.set_level(logging.INFO)
    data = plant_config(tmp_path, WATCH, program="Watch", sims=[])
    channel = data["can"][0]["channel"]
    data["can"][0]["interface"] = "late"
    late_adapter.ABSENT.add(channel)
    engine = build_engine(config_from_dict(data, tmp_path / "plant.toml"), virtual_time=True)
    try:
        engine.start()  # no DriverError: it waits for the adapter
        master = next(d for d in engine.drivers if d.name == "canopen")
        engine.run(duration_ns=100 * MS)
        status = master.status()
        assert not status.ok and "bus down" in status.message and "no CAN adapter" in status.message
        assert "canopen: bus down" in status_line(engine)
        assert not engine.get("CANOPEN_MASTER.BusOk")
        engine.run(duration_ns=19_900 * MS)  # 20 s: tries at 0.5, 1.5, 3.5, 7.5, 15.5 s
        assert late_adapter.ATTEMPTS[channel] == 6
        # one line at the start, then one at most every 10 s for the tries that fail
        waiting = [r.getMessage() for r in caplog.records if "no CAN adapter" in r.getMessage()]
        assert 2 <= len(waiting) <= 4, waiting
        assert "trying again in 0.5 s" in waiting[0]
        late_adapter.ABSENT.discard(channel)  # plugged in at 20 s; the next try is at 25.5 s
        sim = LtmrSimulator(40, settings=BusSettings("virtual", channel, 250_000), clock=engine.clock, pump=master.pump)
        sim.start()
        engine.drivers.insert(0, sim)
        engine.run(duration_ns=5_400 * MS)
        assert not master.status().ok
        engine.run(duration_ns=1_000 * MS)
        assert master.status().ok and engine.get("Watch.operational") and engine.get("CANOPEN_MASTER.BusOk")
        assert any("CAN bus open" in r.getMessage() for r in caplog.records)
    finally:
        engine.stop()
        for d in list(engine.drivers):
            if isinstance(d, LtmrSimulator):
                d.stop()
        late_adapter.ABSENT.discard(channel)


def test_fail_fast_stops_at_the_start_when_the_adapter_is_missing(tmp_path, monkeypatch):
    from softplc.runtime.config import config_from_dict
    from softplc.runtime.engine.build import build_engine
    from softplc.runtime.plugin.driver import DriverError

    from ..can import late_adapter
    from .plant import plant_config

    late_adapter.register(monkeypatch)
    data = plant_config(tmp_path, WATCH, program="Watch", sims=[])
    channel = data["can"][0]["channel"]
    data["can"][0].update(interface="late", missing_adapter="fail")
    late_adapter.ABSENT.add(channel)
    try:
        engine = build_engine(config_from_dict(data, tmp_path / "plant.toml"), virtual_time=True)
        with pytest.raises(DriverError, match=r"can0: cannot open CAN bus \(late channel .*no CAN adapter"):
            engine.start()
        engine.stop()
    finally:
        late_adapter.ABSENT.discard(channel)


ROGUE = {
    "name": "rogue",
    "id": 41,
    "eds": "ltmr",
    "tpdo": [{"number": 1, "configure": False, "map": [{"object": "2004:06", "address": "%IW100"}]}],
}


def test_a_pdo_on_a_restricted_cob_id_is_refused(plants):
    """Found by the fuzz harness (tests/fuzz): a node that reported COB-ID 0
    for a TPDO the master does not configure (configure = false) had its
    TPDO taken on 0x000, so every NMT command on the bus was read into the
    image as that TPDO (and an RPDO would have gone out as NMT commands).
    A COB-ID that CiA 301 keeps for other services now fails the node's
    configuration, naming the PDO."""
    from softplc.runtime.io.can.bus import CanEndpoint, open_bus

    plant = plants(WATCH, program="Watch", nodes=[ROGUE], sims=[])
    bus = plant.config.can[0]
    node = CanEndpoint(open_bus(BusSettings(bus.interface, bus.channel, bus.bitrate)), name="node 41", pump=plant.pump)

    def answer(msg):
        if msg.arbitration_id == 0x629:  # downloads confirmed; every upload: 0x00000000
            command = 0x60 if msg.data[0] & 0xE0 == 0x20 else 0x43
            node.send(0x5A9, bytes([command]) + bytes(msg.data[1:4]) + bytes(4))

    node.add_handler(answer)
    node.start()
    try:
        node.send(0x729, b"\x00")  # boot-up
        plant.run_ms(300)
        assert "canopen.node[0].tpdo[0]: the node's TPDO 1 has COB-ID 0x000" in plant.master.status().message
        node.send(0x000, bytes([0x01, 0x00, 0x11, 0x22, 0x33, 0x44, 0x55, 0x66]))  # 8 bytes on the NMT id
        plant.run_ms(20)
        assert plant.get("Watch.status1") == 0
        assert plant.master.rx_short == 0
    finally:
        node.stop()


def test_details_give_each_node_its_states_last_error_and_emergencies_for_the_monitors(plants):
    plant = plants(WATCH, program="Watch")
    plant.run_until(lambda: plant.get("Watch.operational"), 200, "node 40 operational")
    sim = plant.sims[40]
    sim.send_emcy(0x1000, 0x01, bytes([109, 0]))  # the LTMR's trip 109, as its simulator reports it
    sim.send_emcy(0x0000, 0x00)  # error reset
    plant.run_ms(250)  # two heartbeats: the node's NMT state is known
    (node,) = plant.master.details()["nodes"]
    assert (node["id"], node["name"], node["state"], node["nmt"], node["error"]) == (
        40,
        "motor",
        "OPERATIONAL",
        "operational",
        "",
    )
    assert [(e["code"], e["register"], e["data"]) for e in node["emcy"]] == [
        (0x1000, 0x01, "6d 00 00 00 00"),
        (0x0000, 0x00, "00 00 00 00 00"),
    ]
    # in the LTMR's words (runtime/devices/ltmr/emcy.py)
    assert node["emcy"][0]["text"].endswith("trip code 109 Network port comm detected error (register 451)")
    assert node["emcy"][1]["text"] == "EMCY 0000h error reset or no error: no detected error"
    assert node["emergencies"] == 2
    sim.unplug()  # the heartbeat stops: the node is lost, and the monitors say why
    plant.run_ms(500)
    (node,) = plant.master.details()["nodes"]
    assert node["state"] == "LOST" and "heartbeat lost" in node["error"]
