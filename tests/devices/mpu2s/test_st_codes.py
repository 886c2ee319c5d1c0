"""fblocks/vendor/mpu2s_codes.st: generated from the MPU2-S tables, up to
date, and giving a running ST program the same numbers as the codec."""

from __future__ import annotations

from softplc.runtime.devices.mpu2s import DEVICE, st_codes, telegram
from softplc.runtime.devices.mpu2s import parameters as params
from softplc.runtime.program import compile_files


def run(decls: str, body: str):
    text = f"PROGRAM main\nVAR\n{decls}\nEND_VAR\n{body}\nEND_PROGRAM\n"
    runner = compile_files([], texts={"mpu2s_use.st": text}).runner("main")
    runner.run(1)
    return runner


def test_shipped_file_is_up_to_date():
    # regenerate with: python -m softplc.runtime.devices
    assert st_codes.ST_FILE.read_text(encoding="utf-8") == st_codes.render()


def test_the_device_ships_and_generates_it():
    assert "mpu2s_codes.st" in [lib.file for lib in DEVICE.libraries]
    assert [g.target.file for g in DEVICE.generated] == ["mpu2s_codes.st"]


def test_the_constants_the_synchronisation_uses():
    text = st_codes.render()
    for line in (
        "MPU2S_TELEGRAM_ID_BASE : UINT := 16#320;",  # §1.2
        "MPU2S_REQUEST_ID : UINT := 16#33F;",
        "MPU2S_KIND_TELEGRAM : BYTE := 16#DD;",  # §1.3
        "MPU2S_ID_SYNC_DF_MAX : UINT := 26;",  # 4.2.47
        "MPU2S_ID_SYNC_DF_MIN : UINT := 27;",
        "MPU2S_ID_SYNC_DU_MAX : UINT := 28;",
        "MPU2S_ID_SYNC_DU_MIN : UINT := 309;",
        "MPU2S_ID_SYNC_PULSE : UINT := 31;",
        "MPU2S_ID_GCB_CLOSING_TIME : UINT := 32;",
        "MPU2S_ID_SYNC_TIME_MONITORING : UINT := 21;",
        "MPU2S_MASK_SYNC_TIME_MONITORING : WORD := 16#0001;",  # §3.3 ID 21 bit 0
        "MPU2S_MASK_GCB_CLOSE_CONSTANT : WORD := 16#0008;",  # ID 21 bit 3
        "MPU2S_ID_SYNC_TIME_MONITORING_DELAY : UINT := 34;",
        "MPU2S_MASK_F_CONTROLLER_ON : WORD := 16#C000;",  # §3.3 masks of ID 19
        "MPU2S_MASK_BLACK_START : WORD := 16#0030;",
        "MPU2S_ID_BLACK_START_DF_MAX : UINT := 29;",
        "MPU2S_ID_BLACK_START_DU_MAX : UINT := 30;",
        "MPU2S_ID_BLACK_START_MAX_TIME : UINT := 142;",
        "MPU2S_MASK_BREAKER_LOGIC : WORD := 16#0F00;",  # ID 16 bits 11..8
        "MPU2S_MASK_GCB_MONITORING : WORD := 16#1000;",  # ID 17 bit 12
        "MPU2S_MASK_GCB_OPEN_RELAY_ENERGISE : WORD := 16#0004;",  # ID 248 bit 2
        "MPU2S_MASK_AUTO_BREAKER_UNLOCK : WORD := 16#0002;",  # ID 248 bit 1
        "MPU2S_ID_GEN_RATED_FREQUENCY : UINT := 12;",
        "MPU2S_ID_GEN_RATED_VOLTAGE : UINT := 296;",
        "MPU2S_ID_GEN_SETPOINT_FREQUENCY : UINT := 11;",
        "MPU2S_ID_GEN_SETPOINT_VOLTAGE : UINT := 10;",
        "MPU2S_ID_PASSWORD : UINT := 500;",
        "MPU2S_ID_KWUGNSEK : UINT := 507;",
        "MPU2S_ID_KWUNTSEK : UINT := 508;",
        "MPU2S_ID_ENGINE_MONITORING_DELAY : UINT := 122;",
        "MPU2S_ID_MONITORING_ON_FREQUENCY : UINT := 25;",
        "MPU2S_ID_F_CONTROLLER_DEADBAND : UINT := 44;",
        "MPU2S_ID_F_CONTROLLER_PULSE : UINT := 45;",
        "MPU2S_ID_F_CONTROLLER_KP : UINT := 46;",
        "MPU2S_ID_U_CONTROLLER_DEADBAND : UINT := 37;",
        "MPU2S_ID_U_CONTROLLER_PULSE : UINT := 38;",
        "MPU2S_ID_U_CONTROLLER_KP : UINT := 39;",
        "MPU2S_SCALE_FREQUENCY : LREAL := 256.0;",  # §3.1
        "MPU2S_SCALE_RAMP : LREAL := 102.4;",  # A13
        "MPU2S_SCALE_TIME : LREAL := 50.0;",
        "MPU2S_SCALE_PULSE : LREAL := 0.5;",
        "MPU2S_NR_F_GEN : UINT := 2;",  # §2.1
        "MPU2S_NR_F_BUS : UINT := 32;",
        "MPU2S_NR_F_MAINS : UINT := 39;",
        "MPU2S_NR_U_GEN_L12 : UINT := 20;",
        "MPU2S_NR_U_BUS_L12 : UINT := 7;",
        "MPU2S_NR_COS_PHI : UINT := 26;",
        "MPU2S_NR_STATES_MAINS_GEN : UINT := 30;",
        "MPU2S_NR_STATE_BUSBAR : UINT := 33;",
        "MPU2S_NR9_F3 : WORD := 16#00C0;",  # §2.2 Nr 9 bits 7+6
        "MPU2S_NR9_F2 : WORD := 16#0030;",
        "MPU2S_NR9_F1 : WORD := 16#000C;",
        "MPU2S_NR9_F0 : WORD := 16#0003;",
        "MPU2S_NR10_T3_GCB_RELEASE : WORD := 16#C000;",  # Nr 10 bits 15+14
        "MPU2S_NR10_T5_GCB_CLOSED : WORD := 16#3000;",
        "MPU2S_NR10_T4_BREAKER_OPEN : WORD := 16#00C0;",
        "MPU2S_NR10_T54_MAINS_PARALLEL : WORD := 16#0030;",
        "MPU2S_NR10_T6_SYNC_ON : WORD := 16#000C;",
        "MPU2S_NR12_ACK_F2_F3 : WORD := 16#0C00;",
        "MPU2S_NR12_ACK_F1 : WORD := 16#0300;",
        "MPU2S_STATE_PRESENT : BYTE := 16#FF;",
        "MPU2S_EVENT_GCB_CONNECT_TIME : USINT := 29;",  # §3.8
        "MPU2S_EVENT_GCB_CLOSED : USINT := 68;",
        "MPU2S_EVENT_GCB_CLOSE_FAULT : USINT := 89;",
        "MPU2S_EVENT_GCB_OPEN_FAULT : USINT := 91;",
        "MPU2S_EVENT_BLACK_START_TIME : USINT := 94;",
    ):
        assert line in text, line
    assert "GENERATED" in text and "python -m softplc.runtime.devices\n" in text


def test_every_id_of_the_synchronisation_is_there():
    text = st_codes.render()
    for param_id in (26, 27, 28, 309, 31, 32, 21, 34, 19, 29, 30, 142, 16, 17, 248, 12, 296, 11, 10, 500):
        for p in params.by_id(param_id):
            assert f"MPU2S_ID_{p.key.upper()} : UINT := {param_id};" in text
    for param_id in (122, 25, 44, 45, 46, 37, 38, 39):
        assert f" : UINT := {param_id};    (* 4.2." in text


def test_a_program_reads_the_constants():
    names = {
        "MPU2S_TELEGRAM_ID_BASE": 0x320,
        "MPU2S_REQUEST_ID": 0x33F,
        "MPU2S_KIND_WRITE": 0xEE,
        "MPU2S_ID_SYNC_DU_MIN": 309,
        "MPU2S_ID_BLACK_START": 19,
        "MPU2S_MASK_BLACK_START": 0x0030,
        "MPU2S_MASK_BREAKER_LOGIC": 0x0F00,
        "MPU2S_ID_KWUNTSEK": 508,
        "MPU2S_NR_F_GEN": 2,
        "MPU2S_NR_BATTERY": 52,
        "MPU2S_NR10_T3_GCB_RELEASE": 0xC000,
        "MPU2S_NR9_F2": 0x0030,
        "MPU2S_STATE_PRESENT": 0xFF,
        "MPU2S_EVENT_BLACK_START_TIME": 94,
        **{f"MPU2S_NR_{w.key.upper()}": w.nr for w in telegram.WORD_TABLE if w.coding is not telegram.Coding.INTERNAL},
    }
    r = run(
        "".join(f"v{i} : LINT;\n" for i in range(len(names))) + "f : LREAL;\nramp : LREAL;\nraw : UINT;\n",
        "".join(f"v{i} := {name};\n" for i, name in enumerate(names))
        + "f := MPU2S_SCALE_FREQUENCY;\nramp := MPU2S_SCALE_RAMP;\n"
        + "raw := LREAL_TO_UINT(0.2 * MPU2S_SCALE_FREQUENCY);\n",
    )
    for i, (name, value) in enumerate(names.items()):
        assert r.get(f"v{i}") == value, name
    assert r.get("f") == 256.0 and r.get("ramp") == 102.4
    assert r.get("raw") == 51  # V8: 0.20 Hz -> 51
