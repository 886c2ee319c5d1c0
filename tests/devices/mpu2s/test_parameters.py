"""The MPU2-S parameter table (parameters.csv, parameters.py): it loads,
has the 170 sub-sections, covers the ID index of digest 004 §3.9 and
shares no bit; lookups; encode/decode with the documented ranges; the
read-modify-write of bit fields; the voltage factor and device variants."""

from __future__ import annotations

import pytest

from softplc.runtime.devices.mpu2s import parameters as P
from softplc.runtime.devices.mpu2s.parameters import decode, encode, extract, merge, parameter

# digest 004 §3.9, "Index of all parameter IDs": (ID, bits, section); the
# relay manager 436 … 456, the fault texts 732 … 827 and the factors 507/508
# are below
INDEX = [
    (1, "", "4.2.5"),
    (2, "", "4.2.12"),
    (3, "", "4.2.9"),
    (7, "", "4.2.14"),
    (9, "", "4.2.4"),
    (10, "", "4.2.10"),
    (11, "", "4.2.2"),
    (12, "", "4.2.3"),
    (13, "", "4.2.30"),
    (15, "15", "4.2.109"),
    (15, "14", "4.2.104"),
    (15, "11", "4.2.61"),
    (15, "10", "4.2.69"),
    (15, "5", "4.2.66"),
    (15, "4", "4.2.72"),
    (15, "1", "4.2.114"),
    (16, "11+10+9+8", "4.2.43"),
    (16, "3", "4.2.157"),
    (16, "1", "4.2.153"),
    (17, "12", "4.2.59"),
    (18, "0", "4.2.167"),
    (19, "15+14", "4.2.18"),
    (19, "13+12", "4.2.33"),
    (19, "11+10", "4.2.25"),
    (19, "9+8", "4.2.29"),
    (19, "5+4", "4.2.55"),
    (21, "13", "4.2.115"),
    (21, "11", "4.2.13"),
    (21, "3", "4.2.45"),
    (21, "0", "4.2.53"),
    (25, "", "4.2.170"),
    (26, "", "4.2.47"),
    (27, "", "4.2.48"),
    (28, "", "4.2.49"),
    (29, "", "4.2.56"),
    (30, "", "4.2.57"),
    (31, "", "4.2.51"),
    (32, "", "4.2.52"),
    (34, "", "4.2.54"),
    (37, "", "4.2.26"),
    (38, "", "4.2.27"),
    (39, "", "4.2.28"),
    (40, "", "4.2.31"),
    (42, "", "4.2.32"),
    (44, "", "4.2.22"),
    (45, "", "4.2.23"),
    (46, "", "4.2.24"),
    (47, "", "4.2.37"),
    (49, "", "4.2.38"),
    (50, "", "4.2.39"),
    (57, "", "4.2.19"),
    (67, "", "4.2.34"),
    (68, "", "4.2.21"),
    (69, "", "4.2.16"),
    (70, "", "4.2.17"),
    (71, "", "4.2.15"),
    (73, "", "4.2.35"),
    (74, "", "4.2.36"),
    (75, "", "4.2.41"),
    (76, "", "4.2.40"),
    (85, "", "4.2.116"),
    (86, "", "4.2.117"),
    (87, "", "4.2.105"),
    (88, "", "4.2.106"),
    (89, "", "4.2.107"),
    (90, "", "4.2.108"),
    (91, "", "4.2.110"),
    (92, "", "4.2.111"),
    (93, "", "4.2.112"),
    (94, "", "4.2.113"),
    (104, "", "4.2.85"),
    (105, "", "4.2.86"),
    (106, "", "4.2.90"),
    (107, "", "4.2.91"),
    (108, "", "4.2.95"),
    (109, "", "4.2.96"),
    (110, "", "4.2.100"),
    (111, "", "4.2.101"),
    (112, "", "4.2.62"),
    (113, "", "4.2.63"),
    (114, "", "4.2.67"),
    (115, "", "4.2.68"),
    (116, "", "4.2.70"),
    (117, "", "4.2.71"),
    (118, "", "4.2.73"),
    (119, "", "4.2.74"),
    (122, "", "4.2.169"),
    (125, "11+10+9+8", "4.2.128"),
    (125, "7+6+5+4", "4.2.132"),
    (125, "3+2+1+0", "4.2.136"),
    (126, "", "4.2.65"),
    (127, "11+10+9+8", "4.2.130"),
    (127, "7+6+5+4", "4.2.134"),
    (127, "3+2+1+0", "4.2.138"),
    (130, "", "4.2.131"),
    (135, "", "4.2.135"),
    (136, "", "4.2.139"),
    (137, "", "4.2.126"),
    (141, "", "4.2.44"),
    (142, "", "4.2.58"),
    (192, "", "4.2.152"),
    (193, "", "4.2.154"),
    (194, "", "4.2.155"),
    (195, "", "4.2.156"),
    (196, "", "4.2.158"),
    (197, "", "4.2.159"),
    (201, "7+6", "4.2.42"),
    (201, "1 1", "4.2.168"),
    (248, "12", "4.2.118"),
    (248, "11", "4.2.82"),
    (248, "10", "4.2.77"),
    (248, "9", "4.2.123"),
    (248, "2", "4.2.46"),
    (248, "1", "4.2.60"),
    (282, "", "4.2.8"),
    (288, "", "4.2.87"),
    (289, "", "4.2.88"),
    (290, "", "4.2.92"),
    (291, "", "4.2.93"),
    (292, "", "4.2.97"),
    (293, "", "4.2.98"),
    (294, "", "4.2.102"),
    (295, "", "4.2.103"),
    (296, "", "4.2.11"),
    (298, "1+0", "4.2.78"),
    (299, "", "4.2.79"),
    (300, "", "4.2.80"),
    (301, "", "4.2.81"),
    (302, "", "4.2.83"),
    (303, "", "4.2.119"),
    (304, "", "4.2.121"),
    (305, "", "4.2.122"),
    (306, "", "4.2.120"),
    (307, "", "4.2.124"),
    (308, "", "4.2.125"),
    (309, "", "4.2.50"),
    (310, "12", "4.2.84"),
    (310, "3", "4.2.89"),
    (310, "1", "4.2.94"),
    (310, "0", "4.2.99"),
    (404, "", "4.2.129"),
    (405, "", "4.2.133"),
    (406, "", "4.2.137"),
    (414, "", "4.2.64"),
    (419, "", "4.2.127"),
    (428, "", "4.2.75"),
    (429, "", "4.2.76"),
    (497, "", "4.2.20"),
    (498, "", "4.2.6"),
    (499, "", "4.2.7"),
    (500, "", "4.2.1"),
]


def test_the_table_loads_170_sub_sections():
    assert len(P.PARAMETERS) == 170
    assert [p.section for p in P.PARAMETERS] == [f"4.2.{n}" for n in range(1, 171)]
    assert len({p.key for p in P.PARAMETERS}) == 170
    assert len({p.name_de.casefold() for p in P.PARAMETERS}) == 170
    assert len({p.name_en.casefold() for p in P.PARAMETERS}) == 170


def test_the_csv_is_package_data():
    from importlib import resources

    text = resources.files("softplc.runtime.devices.mpu2s").joinpath("parameters.csv").read_text("utf-8")
    assert text.startswith("section,key,id,kind,bits,raw_min,raw_max,raw_min_400,raw_max_400,family,unit,signed,")
    assert P.load(text) == P.PARAMETERS


def test_no_two_parameters_share_a_bit():
    for param_id in P.all_ids():
        owners = P.by_id(param_id)
        if len(owners) > 1:
            assert all(p.kind in P.BIT_KINDS for p in owners), param_id
        masks = [p.mask for p in owners]
        for i, a in enumerate(masks):
            for b in masks[i + 1 :]:
                assert a & b == 0, (param_id, hex(a), hex(b))


@pytest.mark.parametrize("param_id, bits, section", INDEX, ids=lambda x: str(x))
def test_every_id_of_the_index_is_there(param_id, bits, section):
    p = parameter(section)
    assert p.id == param_id
    assert p in P.by_id(param_id)
    if bits == "1 1":
        assert p.bits == (11,)  # A23: printed '1 1', read as bit 11
    else:
        assert p.bits == tuple(int(b) for b in bits.split("+") if b)


def test_index_ranges_relays_texts_and_factors():
    for param_id in range(436, 457):  # 436 … 456: relay manager relays 1-7
        (p,) = P.by_id(param_id)
        assert p.kind == "words3" and p.section == f"4.2.{160 + (param_id - 436) // 3}"
    for param_id in range(732, 828):  # 732 … 827: fault texts terminals 62-73
        (p,) = P.by_id(param_id)
        assert p.kind == "words8" and p.section == f"4.2.{140 + (param_id - 732) // 8}"
    # 507/508 are read, no sub-section of their own (4.2.10, 4.2.110)
    assert (P.KWUGNSEK_ID, P.KWUNTSEK_ID) == (507, 508)
    assert P.by_id(507) == [] and P.by_id(508) == []
    index_ids = {i for i, _b, _s in INDEX} | set(range(436, 457)) | set(range(732, 828))
    assert set(P.all_ids()) == index_ids


def test_lookups():
    p = parameter("4.2.47")
    assert p is parameter("sync_df_max") is parameter("Synchronisieren +df max") is parameter("SYNCHRONISING +DF MAX")
    assert (p.id, p.kind, p.family, p.unit, p.raw_min, p.raw_max) == (26, "word", "frequency", "Hz", 5, 125)
    assert str(p) == "4.2.47 Synchronisieren +df max (ID 26)"
    with pytest.raises(ValueError, match="no MPU2-S parameter"):
        parameter("4.2.171")
    assert [q.section for q in P.by_id(19)] == ["4.2.18", "4.2.25", "4.2.29", "4.2.33", "4.2.55"]
    assert P.by_id(4) == []


@pytest.mark.parametrize(
    "key, value, raw",
    [
        ("gen_setpoint_frequency", 70, 17920),  # E1
        ("gen_setpoint_frequency", 50, 12800),  # V5
        ("sync_df_max", 0.20, 51),  # V8
        ("sync_df_min", 0.10, 26),  # V9
        ("sync_du_max", 5.0, 200),  # V10
        ("sync_du_min", 5.0, 200),  # V11
        ("sync_pulse", 0.20, 10),  # V12
        ("gcb_closing_time", 80, 80),  # V13
        ("sync_time_monitoring_delay", 60, 60),  # V14
        ("power_setpoint_1", -100, 0xFF9C),  # V15
        ("pf_controller_setpoint", -0.95, 0xFFA1),  # V16
        ("password", 1234, 0x04D2),  # V4
        ("f_controller_ramp", 1, 102),  # A13
        ("f_controller_ramp", 50, 5120),
        ("black_start_df_max", 0.05, 13),
        ("sync_pulse", 0.26, 13),
        ("f_controller_pulse", 250, 125),
        ("reverse_power_pickup", -99, 0x10000 - 990),
        ("battery_undervoltage_pickup", 9.5, 95),
        ("amz_ip", 0.1, 100),
        ("gen_vt_primary", 65000, 65000),  # unsigned (A34)
        ("pf_controller_setpoint", 1.00, 100),
        ("ao1_source", 22, 22),
    ],
)
def test_encode(key, value, raw):
    assert encode(parameter(key), value) == raw


@pytest.mark.parametrize(
    "key, raw, value",
    [
        ("gen_setpoint_frequency", 17920, 70.0),
        ("power_setpoint_1", 0xFF9C, -100),
        ("pf_controller_setpoint", 0xFFA1, -0.95),
        ("reverse_power_pickup", 0xFC22, -99.0),
        ("sync_time_monitoring_delay", 60, 60),
        ("gen_vt_primary", 65000, 65000),
        ("sync_pulse", 13, 0.26),
        ("f_controller_pulse", 5, 10.0),
    ],
)
def test_decode(key, raw, value):
    got = decode(parameter(key), raw)
    assert got == value and type(got) is type(value)


@pytest.mark.parametrize(
    "key, value, raw, limits",
    [
        ("sync_df_max", 0.5, 128, "5..125"),
        ("sync_df_max", 0.01, 3, "5..125"),
        ("sync_pulse", 0.3, 15, "1..13"),
        ("gen_setpoint_frequency", 39.99, 10237, "10240..17920"),
        ("battery_undervoltage_delay", 0, 0, "1..4950"),  # A22
        ("password", 10000, 10000, "0..9999"),
        ("power_setpoint_1", -10000, -10000, "-9999..9999"),
        ("ao1_source", 23, 23, "0..22"),  # A24
    ],
)
def test_values_outside_the_documented_range_are_refused(key, value, raw, limits):
    p = parameter(key)
    with pytest.raises(ValueError) as caught:
        encode(p, value)
    message = str(caught.value)
    assert p.section in message and p.name_de in message
    assert f"{value}" in message and f"raw {raw}," in message and limits in message
    assert "unbedingt einzuhalten" in message


def test_cos_phi_set_point_has_a_gap():
    p = parameter("pf_controller_setpoint")  # 4.2.30: -70..-99; 100; 70..99
    for ok in (-0.7, -0.99, 0.7, 0.99, 1.0):
        encode(p, ok)
    for bad in (0.69, -0.69, 0, -1.0, 1.01):
        with pytest.raises(ValueError, match="unbedingt"):
            encode(p, bad)


def test_voltage_parameters_need_the_factor():
    p = parameter("gen_rated_voltage")  # 4.2.11, ID 296
    assert p.factor_id == 507 and parameter("mains_overvoltage_pickup").factor_id == 508
    with pytest.raises(ValueError, match="KWUGNSEK.*ID 507"):
        encode(p, 100)
    # raw = U·KWUGNSEK/400: with 800, 100 V -> 200
    assert encode(p, 100, factor=800) == 200
    assert decode(p, 200, factor=800) == 100.0
    with pytest.raises(ValueError, match="no voltage factor"):
        encode(parameter("sync_df_max"), 0.2, factor=800)


def test_device_variants():
    # 4.2.10 a.) 100 V device 25..125 V, b.) 400 V device 50..480 V (·KWUGNSEK/400)
    p = parameter("gen_setpoint_voltage")
    assert P.raw_range(p, factor=400, variant=100) == (25, 125)
    assert P.raw_range(p, factor=400, variant=400) == (50, 480)
    assert P.raw_range(p, factor=400) == (50, 125)  # valid on both
    assert P.raw_range(p, factor=800, variant=400) == (100, 960)
    assert P.raw_range(p, factor=333, variant=100) == (21, 104)  # 20.8125 -> 21, 104.0625 -> 104
    assert encode(p, 25, factor=400, variant=100) == 25
    with pytest.raises(ValueError, match="on the 400 V device"):
        encode(p, 25, factor=400, variant=400)
    with pytest.raises(ValueError, match="variant=100 or 400"):
        encode(p, 400, factor=400)
    assert encode(p, 400, factor=400, variant=400) == 400
    # 4.2.4 VT secondary: 100 V device 50..125, 400 V device 50..480
    q = parameter("gen_vt_secondary")
    assert P.raw_range(q, variant=400) == (50, 480) and P.raw_range(q, variant=100) == (50, 125)
    with pytest.raises(ValueError):
        P.raw_range(q, variant=230)
    # the documented ends pass whatever the factor
    for factor in (1, 333, 399, 401, 65535):
        lo, hi = P.raw_range(p, factor=factor, variant=100)
        assert encode(p, 25, factor=factor, variant=100) == lo
        assert encode(p, 125, factor=factor, variant=100) == hi


def test_bit_parameters_read_modify_write():
    black_start = parameter("black_start")  # ID 19 bits 5+4 (4.2.55)
    assert (black_start.mask, black_start.shift) == (0x0030, 4)
    assert merge(black_start, 0xC000, True) == 0xC030  # the frequency controller stays on
    assert merge(black_start, 0xFFFF, False) == 0xFFCF
    assert extract(black_start, 0xFF30) is True and extract(black_start, 0xFF00) is False
    assert extract(black_start, 0x0010) is None  # 01: neither off nor on
    sync_mon = parameter("sync_time_monitoring")  # ID 21 bit 0 (4.2.53, A33)
    assert merge(sync_mon, 0x0808, True) == 0x0809
    assert extract(sync_mon, 0x0809) is True
    # §3.3 masks: ID 19 f-ctrl C000h, P-ctrl 3000h, U-ctrl 0C00h, cos φ 0300h, black start 0030h
    masks = {p.key: p.mask for p in P.by_id(19)}
    assert masks == {
        "f_controller_on": 0xC000,
        "p_controller_on": 0x3000,
        "u_controller_on": 0x0C00,
        "pf_controller_on": 0x0300,
        "black_start": 0x0030,
    }
    # ID 21: sync-time-mon 0001h, GCB signal logic 0008h, 3-phase power 0800h, phase jump 2000h
    assert {p.section: p.mask for p in P.by_id(21)} == {
        "4.2.13": 0x0800,
        "4.2.45": 0x0008,
        "4.2.53": 0x0001,
        "4.2.115": 0x2000,
    }
    with pytest.raises(ValueError):
        merge(parameter("sync_df_max"), 0, 1)
    with pytest.raises(ValueError):
        extract(parameter("sync_df_max"), 0)


def test_breaker_logic_half_byte_e8():
    p = parameter("breaker_logic")  # ID 16 bits 11..8: 0000 Extern, 0001 Parallel (4.2.43)
    assert p.mask == 0x0F00
    assert merge(p, 0x000A, 0) == 0x000A  # Extern -> 0000h, the AO bits kept
    assert merge(p, 0x000A, 1) == 0x010A  # Parallel -> 0100h
    assert extract(p, 0x010A) == 1
    with pytest.raises(ValueError, match="unbedingt"):
        merge(p, 0, 0b1001)  # E8: "Andere Werte, z.B. 1001, sind ungültig !"
    for bad in range(2, 16):
        with pytest.raises(ValueError):
            encode(p, bad)


def test_other_bit_fields():
    amz = parameter("amz_characteristic")  # ID 298 bits 1+0: 00/01/10, 11 undefined
    assert [merge(amz, 0xFFFC, c) for c in (0, 1, 2)] == [0xFFFC, 0xFFFD, 0xFFFE]
    with pytest.raises(ValueError):
        merge(amz, 0, 3)
    di = parameter("di_5_8_energise")  # ID 125 bits 7..4: bit 7 DI 5 ... bit 4 DI 8
    assert merge(di, 0x0F0F, 0b1000) == 0x0F8F  # DI 5 Arbeitsstrom
    gcb_open = parameter("gcb_open_relay_energise")  # ID 248 bit 2
    assert merge(gcb_open, 0, True) == 0x0004 and merge(gcb_open, 0xFFFF, 0) == 0xFFFB
    with pytest.raises(ValueError):
        merge(gcb_open, 0, 2)
    with pytest.raises(ValueError):
        encode(parameter("black_start"), 3)  # a switch is True or False
    shutdown = parameter("shutdown")  # 4.2.168, A23: bit 11 of ID 201
    assert shutdown.mask == 0x0800 and parameter("control_via_interface").mask == 0x00C0


def test_digit_words():
    delay = parameter("di_1_4_delay")  # ID 404 (E6)
    assert encode(delay, (0.1, 1, 5, 100)) == 359  # digits 0, 3, 5, 9 (A26: DI 1 the thousands)
    assert decode(delay, 359) == (0.1, 1.0, 5.0, 100.0)
    with pytest.raises(ValueError):
        encode(delay, (0.3, 1, 5, 100))
    classes = parameter("di_9_12_fault_class")  # ID 136 (E7)
    assert encode(classes, (3, 3, 3, 3)) == 3333 and encode(classes, (0, 1, 2, 3)) == 123
    assert decode(classes, 3210) == (3, 2, 1, 0)
    with pytest.raises(ValueError):
        encode(classes, (4, 0, 0, 0))
    with pytest.raises(ValueError):
        decode(classes, 3400)


def test_texts_and_relays_take_their_own_functions():
    with pytest.raises(ValueError, match="encode_words"):
        encode(parameter("fault_text_62"), "X")
    with pytest.raises(ValueError, match="decode_words"):
        decode(parameter("relay_1"), 0)


def test_wrong_value_types():
    with pytest.raises(ValueError):
        encode(parameter("sync_df_max"), "0.2")
    with pytest.raises(ValueError):
        encode(parameter("sync_df_max"), True)
    with pytest.raises(ValueError):
        encode(parameter("ao1_source"), 1.0)
    with pytest.raises(ValueError):
        encode(parameter("sync_time_monitoring"), "on")
    with pytest.raises(ValueError):
        decode(parameter("sync_time_monitoring"), 2)  # a 1-bit field
    with pytest.raises(ValueError):
        decode(parameter("sync_df_max"), 0x10000)


def test_every_documented_range_end_round_trips():
    for p in P.PARAMETERS:
        if p.raw_min is None or p.family in ("di_delay", "fault_class", "switch"):
            continue
        factor = 400 if p.factor_id else None
        for variant in (100, 400):
            lo, hi = P.raw_range(p, factor=factor, variant=variant)
            for raw in (lo, hi):
                if p.family == "cos_phi" and abs(raw) < 70:
                    continue
                word = raw & 0xFFFF if p.kind == "word" else raw
                assert encode(p, decode(p, word, factor=factor), factor=factor, variant=variant) == word, p
