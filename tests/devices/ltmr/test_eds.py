"""The shipped EDS files: they load with the canopen stack, carry the LTMR
manual's factory values (manual 001 §4, digest 001 §4) and register map, and
are exactly what runtime/io/canopen/eds.py generates."""

from __future__ import annotations

from pathlib import Path

import canopen
import pytest
from canopen.objectdictionary import datatypes
from canopen.sdo.exceptions import SdoAbortedError

from softplc.runtime.devices import fc280 as fc280_device
from softplc.runtime.devices import ltmr as ltmr_device
from softplc.runtime.devices.ltmr import bits as ltmr_bits
from softplc.runtime.devices.ltmr import registers as ltmr
from softplc.runtime.io.canopen import eds
from softplc.runtime.io.canopen.cia301 import ABORT_NO_OBJECT, ABORT_NO_SUBINDEX, ABORT_READ_ONLY
from softplc.runtime.plugin.registry import registry

EDS_DIR = Path(__file__).resolve().parents[3] / "io_config" / "eds"
LTMR_EDS = EDS_DIR / "ltmr.eds"
FC280_EDS = EDS_DIR / "fc280.eds"


@pytest.fixture(scope="module")
def od():
    return canopen.import_od(str(LTMR_EDS), node_id=40)


def test_the_shipped_files_are_the_devices_eds():
    assert registry().files("eds") == {"ltmr": ltmr_device.EDS, "fc280": fc280_device.EDS}
    # the installed files: the source tree in a development install, site-packages otherwise
    assert ltmr_device.EDS.path.read_bytes() == LTMR_EDS.read_bytes()
    assert fc280_device.EDS.path.read_bytes() == FC280_EDS.read_bytes()


def test_the_file_says_where_it_comes_from():
    head = LTMR_EDS.read_text(encoding="ascii").splitlines()[:3]
    assert any("DOCA0132" in line for line in head)
    assert any("not Schneider Electric's EDS file" in line for line in head)


def test_examples_of_the_brief(od):
    assert ltmr.REGISTERS[652].name in od[0x2007][3].name
    assert od[0x1800][1].default == 0x1A8


def test_pdo_mappings_as_printed(od):
    # 0x1600 (L1186-1221), 0x1A00 (L1513-1548), 0x1603, 0x1A03
    assert [od[0x1600][s].default for s in range(5)] == [3, 0x20080510, 0x20080410, 0x20080110, 0]
    assert [od[0x1A00][s].default for s in range(5)] == [4, 0x20040610, 0x20040710, 0x20040810, 0x20040A10]
    assert [od[0x1603][s].default for s in range(5)] == [2, 0x30000120, 0x30000220, 0, 0]
    assert [od[0x1A03][s].default for s in range(5)] == [2, 0x30000320, 0x30000420, 0, 0]
    for index in (0x1601, 0x1602, 0x1A01, 0x1A02):
        assert [od[index][s].default for s in range(5)] == [0, 0, 0, 0, 0]
    assert all(od[index][0].access_type == "rw" for index in (0x1600, 0x1A00, 0x1603))


def test_pdo_communication_factory_values(od):
    node = 40
    expected = {
        0x1400: 0x200 + node,
        0x1401: 0x80000300 + node,
        0x1402: 0x80000400 + node,
        0x1403: 0x500 + node,
        0x1800: 0x180 + node,
        0x1801: 0x80000280 + node,
        0x1802: 0x80000380 + node,
        0x1803: 0x480 + node,
    }
    for index, cob_id in expected.items():
        assert od[index][1].default == cob_id
        assert od[index][2].default == 0xFF  # A4: factory transmission type 255
    for index in range(0x1800, 0x1804):
        assert [od[index][s].default for s in (0, 3, 4, 5)] == [5, 0, 0, 0]
    assert all(od[index][0].default == 2 for index in range(0x1400, 0x1404))


def test_communication_objects(od):
    assert od[0x1018][1].default == 0x0300005A and od[0x1018][2].default == 0x30
    assert od[0x1018][3].default == 0x00010001 and od[0x1018][0].default == 4
    assert (od[0x1005].default, od[0x1014].default, od[0x1017].default) == (0x80, 0x80 + 40, 0)
    assert (od[0x1200][1].default, od[0x1200][2].default) == (0x628, 0x5A8)
    assert (od[0x1016][0].default, od[0x1016][1].default, od[0x1029][1].default) == (1, 0, 0)
    assert (od[0x100C].default, od[0x100D].default) == (0, 0)
    assert od[0x1004][0].default == 0x00040004
    assert (od[0x1008].default, od[0x1009].default, od[0x100A].default) == ("LTM", "M1.0-ES1.0", "V01.01")
    assert od[0x1003][0].access_type == "rw" and len(list(od[0x1003])) == 6


def test_every_register_is_a_sub_entry(od):
    for reg, register in ltmr.REGISTERS.items():
        if register.kind == "forbidden":
            continue
        index, sub = ltmr.register_to_object(reg)
        entry = od[index][sub]
        assert entry.name == ltmr.register_label(reg)
        assert entry.access_type == register.access
        assert entry.data_type == (datatypes.INTEGER16 if register.type == "Int" else datatypes.UNSIGNED16)
        assert entry.pdo_mappable == (index in (0x2004, 0x2007, 0x2008))
        assert entry.default == ltmr_bits.FACTORY_SETTINGS.get(reg, 0)


def test_forbidden_registers_are_absent_and_sub0_is_the_highest_sub_index(od):
    assert 0x62 not in od[0x2000] and 0x4B not in od[0x2004] and 0x0B not in od[0x2008]
    for _first, _last, index in ltmr.REGISTER_BLOCKS:
        subs = [s for s in od[index] if s]
        assert od[index][0].default == max(subs)
    assert od[0x2004][0].default == 0x4A and od[0x200D][0].default == 0xC8


def test_reserved_read_write_registers_accept_only_zero(od):
    # "Reserved, in Read/Write tables, means that you must write 0 in these variables."
    assert (od[0x2008][0x04].min, od[0x2008][0x04].max) == (0, 0)  # 703, RPDO1 word 2 (A2)
    assert od[0x2007][0x21].max == 5  # 682 fallback strategy 0-5


def test_pkw_objects(od):
    assert [od[0x3000][s].access_type for s in (1, 2, 3, 4)] == ["rw", "rw", "ro", "ro"]
    assert all(od[0x3000][s].data_type == datatypes.UNSIGNED32 and od[0x3000][s].pdo_mappable for s in (1, 2, 3, 4))


def test_a_canopen_slave_serving_the_file_answers_with_the_manual_abort_codes(od):
    node = canopen.LocalNode(40, od)
    with pytest.raises(SdoAbortedError) as err:
        node.set_data(0x2004, 0x06, b"\x00\x00", check_writable=True)  # 455 is read-only
    assert err.value.code == ABORT_READ_ONLY
    with pytest.raises(SdoAbortedError) as err:
        node.get_data(0x2004, 0x4B)  # 524: Forbidden (A21)
    assert err.value.code == ABORT_NO_SUBINDEX
    with pytest.raises(SdoAbortedError) as err:
        node.get_data(0x2009, 0x01)
    assert err.value.code == ABORT_NO_OBJECT
    node.set_data(0x2007, 0x03, (50).to_bytes(2, "little"), check_writable=True)  # FLC1 := 50 %
    assert node.sdo[0x2007][3].raw == 50
    assert node.sdo[0x2006][0x02].raw == ltmr_bits.GeneralConfig1.CONFIG_VIA_NETWORK  # factory 601


def test_fc280_skeleton_loads():
    od = canopen.import_od(str(FC280_EDS), node_id=5)
    assert od[0x1000].default == 0x00010192  # frequency converter, DSP 402
    assert od[0x1018][1].default == 200008
    assert od[0x1800][1].default == 0x185 and od[0x1800][3].default == 300  # TPDO inhibit 30 ms
    assert od[0x6040].pdo_mappable and od[0x6040].access_type == "rw"
    assert od[0x6041].access_type == "ro" and od[0x6042].data_type == datatypes.INTEGER16
    assert od[0x2690].pdo_mappable and od[0x2643].pdo_mappable  # FC profile control and status word
    assert od[0x2323].default == 10 and od[0x23EA].default == 127  # 8-03 1 s, 10-02 node 127
    assert od[0x1600][1].default == 0x26900010
    text = FC280_EDS.read_text(encoding="ascii")
    assert "Placeholders" in text and "not Danfoss's EDS file" in text


def test_writer_rejects_what_an_eds_cannot_hold():
    with pytest.raises(ValueError):
        eds.Entry("x", eds.UNSIGNED8, "readwrite")
    with pytest.raises(ValueError):
        eds.EdsObject(0x2000, "x", "VAR")
    bad = eds.EdsFile("x.eds", "x", "x", {}, (eds.var(0x2000, "a;b", eds.UNSIGNED8),))
    with pytest.raises(ValueError):
        eds.render(bad)
