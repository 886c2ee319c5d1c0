"""The FC 280's EDS skeleton (io_config/eds/fc280.eds), written from digest
003 ([M] manual, [P] placeholder)."""

from __future__ import annotations

from ...io.canopen.eds import (
    INTEGER16,
    INTEGER32,
    UNSIGNED8,
    UNSIGNED16,
    UNSIGNED32,
    VISIBLE_STRING,
    EdsFile,
    Entry,
    compound,
    pdo_communication,
    pdo_mapping,
    sdo_server,
    var,
)

# ---------------------------------------------------------------------------
# Danfoss FC 280 skeleton (digest 003; [M] manual, [P] placeholder)
# ---------------------------------------------------------------------------

FC280_VENDOR_ID = 200008  # [M] 0x1018:01 "200008 dec" (digest 003 §6)
FC280_DEVICE_TYPE = 0x00010192  # [M] frequency converter (1), profile 402 (digest 003 §6)


def _fc_param(group: int, number: int) -> int:
    """Drive parameter g-nn is object 0x2000 + g*100 + nn (digest 003 §5.1)."""
    return 0x2000 + group * 100 + number


def fc280_objects() -> list:
    u8, u16, u32 = UNSIGNED8, UNSIGNED16, UNSIGNED32
    delta = [(1, Entry("Delta speed", u32, "rw", 0)), (2, Entry("Delta time", u16, "rw", 0))]
    objects = [
        var(0x1000, "Device type", u32, "ro", FC280_DEVICE_TYPE),  # [M]
        var(0x1001, "Error register", u8, "ro", 0),  # [M] bit 0 generic only
        var(0x1005, "COB-ID SYNC", u32, "rw", 0x80),  # [M] object; 0x80 [P] (manual prints 125)
        var(0x1008, "Manufacturer device name", VISIBLE_STRING, "ro", "FC 280"),  # [P] par. 15-40
        var(0x100A, "Manufacturer software version", VISIBLE_STRING, "ro", "1.1"),  # [P] par. 15-49
        var(0x100C, "Guard time", u16, "rw", 0),  # [M] ms
        var(0x100D, "Life time factor", u8, "rw", 0),  # [M]
        compound(
            0x1010,
            "Store parameters",  # [M] signature "save"
            [(n, Entry(f"Store parameters {n}", u32, "rw", 0)) for n in range(1, 5)],
            "ARRAY",
        ),
        compound(
            0x1011,
            "Restore default parameters",  # [M] signature "load"
            [(n, Entry(f"Restore parameters {n}", u32, "rw", 0)) for n in range(1, 5)],
            "ARRAY",
        ),
        var(0x1014, "COB-ID EMCY", u32, "ro", "$NODEID+0x80"),  # [M] read-only here
        var(0x1017, "Producer heartbeat time", u16, "rw", 0),  # [M] 0 = not used
        compound(
            0x1018,
            "Identity object",
            [
                (1, Entry("Vendor ID", u32, "ro", FC280_VENDOR_ID)),  # [M]
                (2, Entry("Product code", u32, "ro", 0)),  # [P]
                (3, Entry("Revision number", u32, "ro", 0)),  # [P]
                (4, Entry("Serial number", u32, "ro", 0)),
            ],  # [P]
            sub0=Entry("Number of entries", u8, "ro", 4),
        ),
        sdo_server(),
        # DSP 402 objects the manual names (digest 003 §3.1); types from CiA 402 [P]
        var(0x603F, "Error code", u16, "ro", 0),
        var(0x6040, "Controlword", u16, "rw", 0, pdo_mapping=True),
        var(0x6041, "Statusword", u16, "ro", 0, pdo_mapping=True),
        var(0x6042, "vl target velocity", INTEGER16, "rw", 0, pdo_mapping=True),  # RPM by default [M]
        var(0x6043, "vl velocity demand", INTEGER16, "ro", 0, pdo_mapping=True),
        var(0x6044, "vl control effort", INTEGER16, "ro", 0, pdo_mapping=True),
        compound(
            0x6046,
            "vl velocity min max amount",
            [(1, Entry("vl velocity min amount", u32, "rw", 0)), (2, Entry("vl velocity max amount", u32, "rw", 0))],
            "ARRAY",
        ),
        compound(0x6048, "vl velocity acceleration", delta),
        compound(0x6049, "vl velocity deceleration", delta),
        compound(0x604A, "vl velocity quick stop", delta),
        compound(
            0x604C,
            "vl dimension factor",
            [
                (1, Entry("vl dimension factor numerator", INTEGER32, "rw", 1)),
                (2, Entry("vl dimension factor denominator", INTEGER32, "rw", 1)),
            ],
            "ARRAY",
        ),
        var(0x6502, "Supported drive modes", u32, "ro", 0),
        # FC profile process data (digest 003 §4.1): 16-80 control word, 16-82 reference, 16-03 status word [M];
        # 16-05 main actual value by the index rule [P]
        var(_fc_param(16, 80), "Fieldbus CTW 1 (16-80)", u16, "rw", 0, pdo_mapping=True),
        var(_fc_param(16, 82), "Fieldbus REF 1 (16-82)", INTEGER16, "rw", 0, pdo_mapping=True),
        var(_fc_param(16, 3), "Status word (16-03)", u16, "ro", 0, pdo_mapping=True),
        var(_fc_param(16, 5), "Main actual value (16-05)", INTEGER16, "ro", 0, pdo_mapping=True),
    ]
    # Drive parameters of manual table 6.1 with their factory settings [M] (digest 003 §5.5)
    parameters = [
        ((8, 1), "Control site", u8, 0),
        ((8, 2), "Control source", u8, 3),
        ((8, 3), "Control word timeout time", u16, 10),  # 1 s, conversion index -1
        ((8, 4), "Control word timeout function", u8, 0),
        ((8, 7), "Diagnosis trigger", u8, 0),
        ((8, 10), "Control word profile", u8, 0),
        ((8, 14), "Configurable control word CTW", u8, 1),
        *(((8, n), f"Selection 8-{n}", u8, 3) for n in range(50, 57)),
        ((8, 90), "Bus jog 1 speed", u16, 6000),  # 100 RPM, conversion index 67 (A34)
        ((8, 91), "Bus jog 2 speed", u16, 12000),  # 200 RPM
        ((10, 1), "Baud rate select", u8, 20),
        ((10, 2), "Node ID", u8, 127),
        ((10, 5), "Transmit error counter", u8, 0),
        ((10, 6), "Receive error counter", u8, 0),
        ((10, 31), "Store data values", u8, 0),
        ((10, 33), "Store always", u8, 0),
        ((16, 84), "Fieldbus comm. status", u16, 0),
        ((16, 90), "Alarm word", u32, 0),
        ((16, 91), "Alarm word 2", u32, 0),
        ((16, 92), "Warning word", u32, 0),
        ((16, 93), "Warning word 2", u32, 0),
        ((16, 97), "Alarm word 3", u32, 0),
    ]
    # counters and status words are readouts [P]
    read_only = {(10, 5), (10, 6), (16, 84), (16, 90), (16, 91), (16, 92), (16, 93), (16, 97)}
    for (group, number), name, data_type, default in parameters:
        access = "ro" if (group, number) in read_only else "rw"
        objects.append(var(_fc_param(group, number), f"{name} ({group}-{number:02d})", data_type, access, default))
    # Three RPDOs and three TPDOs (digest 003 §2.1) [M]; TPDO inhibit time 300 = 30 ms [M].
    # The default mappings are only in a picture of the manual (digest 003 §2.7): the ones here are [P]:
    # PDO1 the FC profile words, PDO2 (disabled) the DSP 402 words, PDO3 empty and disabled.
    rx = {1: (0x26900010, 0x26920010), 2: (0x60400010, 0x60420010), 3: ()}
    tx = {1: (0x26430010, 0x26450010), 2: (0x60410010, 0x60440010), 3: ()}
    disabled = {1: 0, 2: 0x80000000, 3: 0x80000000}
    for k in (1, 2, 3):
        objects += [
            pdo_communication(0x1400 + k - 1, disabled[k] + 0x200 + 0x100 * (k - 1), transmit=False),
            pdo_mapping(0x1600 + k - 1, rx[k], slots=8),
            pdo_communication(0x1800 + k - 1, disabled[k] + 0x180 + 0x100 * (k - 1), transmit=True, inhibit_time=300),
            pdo_mapping(0x1A00 + k - 1, tx[k], slots=8),
        ]
    return objects


def fc280_eds() -> EdsFile:
    return EdsFile(
        file_name="fc280.eds",
        description="Danfoss VLT Midi Drive FC 280, CANopen (skeleton)",
        created_by="softplc runtime/devices/fc280/eds.py",
        device_info={
            "VendorName": "Danfoss",
            "VendorNumber": FC280_VENDOR_ID,
            "ProductName": "VLT FC 280",
            "ProductNumber": 0,
            "RevisionNumber": 0,
            **{f"BaudRate_{rate}": int(rate != 100) for rate in (10, 20, 50, 125, 250, 500, 800, 1000)},
            "SimpleBootUpMaster": 0,
            "SimpleBootUpSlave": 1,
            "Granularity": 8,
            "DynamicChannelsSupported": 0,
            "GroupMessaging": 0,
            "NrOfRXPDO": 3,
            "NrOfTXPDO": 3,
            "LSS_Supported": 0,
        },
        objects=tuple(fc280_objects()),
        comments=(
            "A skeleton written from the Danfoss FC 280 CANopen programming guide (digest 003),",
            "not Danfoss's EDS file. Values the manual gives: device type, vendor ID 200008, the DSP 402",
            "and FC profile objects, the parameter factory settings, TPDO inhibit time 300 (30 ms).",
            "Placeholders: product code, revision, device name and software version strings, the SYNC",
            "COB-ID 0x80 (manual prints 125), data types of the 0x6000 objects (CiA 402) and every",
            "default PDO mapping (the manual shows them only in a picture).",
            "Generated by python -m softplc.runtime.devices. Do not edit.",
        ),
    )
