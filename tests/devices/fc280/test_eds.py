"""The FC 280's shipped EDS (io_config/eds/fc280.eds, from
runtime/devices/fc280/eds.py): the communication objects of manual 003
Tabelle 7.1, every parameter of parameters.PARAMETERS at 2000h + g*100 + nn
(§5.1) with its type, access, factory setting and PDO mapping flag, the
CiA 402 objects of §4.3.1, read with the canopen stack."""

from __future__ import annotations

from pathlib import Path

import canopen
import pytest
from canopen.objectdictionary import ODArray, ODVariable, datatypes

from softplc.runtime.devices.fc280 import DEVICE
from softplc.runtime.devices.fc280.parameters import PARAMETERS, index_of
from softplc.runtime.devices.fc280.store import RANGES

EDS = Path(__file__).resolve().parents[3] / "io_config" / "eds" / "fc280.eds"
TYPES = {
    "UInt8": datatypes.UNSIGNED8,
    "UInt16": datatypes.UNSIGNED16,
    "UInt32": datatypes.UNSIGNED32,
    "Int16": datatypes.INTEGER16,
    "Int32": datatypes.INTEGER32,
    "VisStr": datatypes.VISIBLE_STRING,
}
READ_ONLY = {"15-40", "15-49", "16-03", "16-05", "16-84", "16-90", "16-91", "16-92", "16-93", "16-97"}
MAPPABLE = {0x2690, 0x2692, 0x2643, 0x2645, 0x269A, 0x269B, 0x269C, 0x269D}


@pytest.fixture(scope="module")
def od():
    return canopen.import_od(str(EDS), node_id=5)


def test_the_shipped_file_is_the_devices():
    assert DEVICE.files["eds"]["fc280"].path.read_bytes() == EDS.read_bytes()
    head = EDS.read_text(encoding="ascii").splitlines()[:2]
    assert "not Danfoss's EDS file" in head[0]


def test_identity_and_device_type(od):
    assert od[0x1000].default == 0x00010192  # M14: 0 / 1 frequency converter / 402 (Tabelle 7.2)
    assert od[0x1018][1].default == 200008  # Tabelle 7.7
    assert od[0x1014].default == 0x85 and od[0x1014].access_type == "ro"  # 80h + node id, read-only
    assert od[0x1001].access_type == "ro" and od[0x1017].default == 0
    assert od[0x1008].default == "FC 280" and od[0x100A].default == "1.1"


def test_communication_objects_of_tabelle_7_1(od):
    for index in (0x1000, 0x1001, 0x1005, 0x1008, 0x100A, 0x100C, 0x100D, 0x1010, 0x1011, 0x1014, 0x1017, 0x1018):
        assert index in od
    for k in range(3):
        assert od[0x1400 + k][1].default == (0x200 + 0x100 * k + 5) | (0x80000000 if k else 0)
        assert od[0x1800 + k][1].default == (0x180 + 0x100 * k + 5) | (0x80000000 if k else 0)
        assert od[0x1800 + k][3].default == 300  # M9: 30 ms (§4.1.4)
        assert od[0x1800 + k][5].default == 0  # M10: off (§4.1.5)
        assert len([s for s in od[0x1600 + k].subindices if s]) == 8  # first .. eighth mapped object
    for index in (0x1403, 0x1803, 0x1016):  # no PDO4 (A3), no heartbeat consumer (§3.1.4 HINWEIS)
        assert index not in od
    assert [od[0x1600][s].default for s in range(3)] == [2, 0x26900010, 0x26920010]
    assert [od[0x1A00][s].default for s in range(3)] == [2, 0x26430010, 0x26450010]


def test_store_and_restore_have_sub_indices_1_to_4(od):
    for index in (0x1010, 0x1011):
        assert sorted(od[index].subindices) == [0, 1, 2, 3, 4]
        assert od[index][0].default == 4
        assert [od[index][s].default for s in (1, 2, 3, 4)] == [1, 1, 0, 1]  # saves on command; 3 reserved
        assert all(od[index][s].access_type == "rw" for s in (1, 2, 3, 4))


@pytest.mark.parametrize("number", sorted(PARAMETERS))
def test_every_parameter_is_an_object(od, number):
    p = PARAMETERS[number]
    obj = od[index_of(number)]
    assert obj.index == 0x2000 + p.group * 100 + int(number.split("-")[1])
    if p.elements:
        assert isinstance(obj, ODArray)
        # element [i] at sub-index i + 1, sub-index 0 the count, as CiA 301 (A35)
        assert sorted(obj.subindices) == list(range(p.elements + 1))
        assert obj[0].default == p.elements and obj[0].access_type == "ro"
        entries = [obj[i + 1] for i in range(p.elements)]
    else:
        assert isinstance(obj, ODVariable)
        entries = [obj]
    for entry in entries:
        assert entry.data_type == TYPES[p.type]
        assert entry.access_type == ("ro" if number in READ_ONLY else "rw")
        assert entry.pdo_mappable == (p.index in MAPPABLE)
        if p.type != "VisStr":
            assert entry.default == p.default
        assert number in entry.name
        if number in RANGES and entry.access_type == "rw":
            assert entry.min is not None and entry.max is not None


def test_the_manuals_examples_of_the_index_rule(od):
    # M7 (Tabelle 5.1) and digest 003 §5.1
    for number, index in (("0-01", 0x2001), ("0-10", 0x200A), ("0-11", 0x200B), ("1-00", 0x2064), ("1-01", 0x2065)):
        assert index_of(number) == index and index in od
    assert od[0x23E9].default == 20  # 10-01 [20] 125 kBit/s
    assert od[0x23EA].default == 127 and (od[0x23EA].min, od[0x23EA].max) == (1, 127)  # 10-02
    assert od[0x2323].default == 10 and od[0x2323].min == 1  # 8-03 1 s, 0.1 s the least (A27)
    assert od[0x2356].default == 3  # 8-54 [3] Bus ODER Klemme (A25)
    assert od[0x237A].default == 6000  # 8-90 100 RPM, conversion index 67 (A34)


def test_dsp_402_objects(od):
    i16, u16, u32 = datatypes.INTEGER16, datatypes.UNSIGNED16, datatypes.UNSIGNED32
    expected = {
        0x6040: (u16, "rw", True),
        0x6041: (u16, "ro", True),
        0x6042: (i16, "rw", True),
        0x6043: (i16, "ro", True),
        0x6044: (i16, "ro", True),
        0x6045: (i16, "ro", True),
        0x6502: (u32, "ro", False),
    }
    for index, (data_type, access, mappable) in expected.items():
        assert (od[index].data_type, od[index].access_type, od[index].pdo_mappable) == (data_type, access, mappable)
    assert od[0x6502].default == 0x2  # bit 1: vl
    assert [od[0x6046][s].data_type for s in (1, 2)] == [u32, u32]
    for index in (0x6048, 0x6049, 0x604A):
        assert (od[index][1].data_type, od[index][2].data_type) == (u32, u16)
    assert [od[0x604B][s].data_type for s in (1, 2)] == [i16, i16]
    assert [(od[0x604C][s].data_type, od[0x604C][s].default) for s in (1, 2)] == [(datatypes.INTEGER32, 1)] * 2


def test_a_local_node_serves_it(od):
    node = canopen.LocalNode(5, od)
    assert node.sdo[0x2690].raw == 0 and node.sdo[0x2136][7].raw == 0
    assert node.sdo[0x2604].raw == "FC 280"  # 15-40
