"""The [[canopen.node.rpdo]] / [[canopen.node.tpdo]] tables: the COB-IDs,
transmission types and timers, the entries' addresses in the image, and
the overlaps refused (an entry with another, a PDO with another, a PDO
with a loopback target)."""

from __future__ import annotations

import pytest

from softplc.runtime.io.canopen.config import (
    PdoEntryConfig,
)

from ...config.support import NODE, PLC, addr, error, errors, load, pdo, plant

# ---------------------------------------------------------------- PDOs


def test_pdo_parameters(tmp_path):
    cfg = load(
        tmp_path,
        plant(
            "",
            "",
            pdo(
                "tpdo",
                2,
                ("2004:02", "%IW4"),
                keys='transmission = 0\ninhibit = "150us"\nevent = "2.5s"\nconfigure = false\n',
            ),
            pdo("tpdo", 512, ("2004:0b", "%IW5"), keys="transmission = 240\n"),
            pdo("rpdo", 2, ("2008:05", "%QW4"), keys='transmission = 254\ninhibit = "6553.5ms"\nevent = "65535ms"\n'),
        ),
    )
    node = cfg.canopen.nodes[0]
    assert [(p.number, p.transmission, p.inhibit_us, p.event_ms, p.configure) for p in node.tpdo + node.rpdo] == [
        (2, 0, 150, 2500, False),
        (512, 240, 0, 0, True),
        (2, 254, 6_553_500, 65535, True),
    ]
    assert node.tpdo[1].entries == [PdoEntryConfig(0x2004, 0x0B, addr("%IW5"), "canopen.node[0].tpdo[1].map[0]")]


@pytest.mark.parametrize(
    "keys, key, message",
    [
        ("transmission = 241\n", "transmission", "expected a transmission type 0..240, 254 or 255 (got 241)"),
        ("transmission = 253\n", "transmission", "expected a transmission type 0..240, 254 or 255 (got 253)"),
        ("transmission = -1\n", "transmission", "expected a transmission type 0..240, 254 or 255 (got -1)"),
        (
            'inhibit = "6553.6ms"\n',
            "inhibit",
            "expected a duration of at most 6553500us (the inhibit time is 16 "
            "bits of 100us), or false for none (got '6553.6ms')",
        ),
        (
            'event = "65.536s"\n',
            "event",
            "expected a duration of at most 65535ms (the event timer is 16 bits of "
            "ms), or false for none (got '65.536s')",
        ),
        ("configure = 1\n", "configure", "expected true or false (got 1)"),
        ("mapping = 1\n", "mapping", "unknown key (did you mean 'map'?)"),
    ],
)
def test_pdo_parameters_refused(tmp_path, keys, key, message):
    assert error(tmp_path, plant("", "", pdo("tpdo", 1, ("2004:06", "%IW0"), keys=keys))) == (
        f"canopen.node[0].tpdo[0].{key}",
        message,
    )


def test_pdo_numbers(tmp_path):
    text = plant("", "", pdo("tpdo", 0, ("2004:06", "%IW0")), pdo("rpdo", 513, ("2008:05", "%QW0")))
    assert errors(tmp_path, text) == [
        ("canopen.node[0].tpdo[0].number", "expected an integer from 1 to 512 (got 0)"),
        ("canopen.node[0].rpdo[0].number", "expected an integer from 1 to 512 (got 513)"),
    ]
    # unique per direction per node: TPDO1 and RPDO1 are two PDOs, and so are two nodes' TPDO1
    second = NODE.replace('"motor"', '"pump"').replace("40", "41")
    cfg = load(
        tmp_path,
        plant(
            "",
            "",
            pdo("tpdo", 1, ("2004:06", "%IW0")),
            pdo("rpdo", 1, ("2008:05", "%QW0")),
            second,
            pdo("tpdo", 1, ("2004:06", "%IW1")),
        ),
    )
    assert [len(n.tpdo) for n in cfg.canopen.nodes] == [1, 1]
    text = plant("", "", pdo("tpdo", 1, ("2004:06", "%IW0")), pdo("tpdo", 1, ("2004:07", "%IW1")))
    assert error(tmp_path, text) == (
        "canopen.node[0].tpdo[1].number",
        "duplicate TPDO number 1 (canopen.node[0].tpdo[0] has it)",
    )


def test_pdo_carries_eight_bytes(tmp_path):
    nine = [(f"2004:{k:02X}", f"%IB{k}") for k in range(9)]
    eight_words = [(f"2004:{k:02X}", f"%IW{k}") for k in range(5)]
    assert error(tmp_path, plant("", "", pdo("tpdo", 1, *nine))) == (
        "canopen.node[0].tpdo[0].map",
        'expected an array of 1 to 8 { object = "2004:06", address = "%IW0" } '
        "tables; a PDO carries 8 bytes (got 9 entries)",
    )
    assert (
        load(tmp_path, plant("", "", pdo("tpdo", 1, *nine[:8]))).canopen.nodes[0].tpdo[0].entries[7].key
        == "canopen.node[0].tpdo[0].map[7]"
    )
    assert error(tmp_path, plant("", "", pdo("tpdo", 1, *eight_words))) == (
        "canopen.node[0].tpdo[0].map",
        "the addresses hold 80 bits; a PDO carries at most 64 (8 bytes)",
    )
    assert error(tmp_path, plant("", "", pdo("tpdo", 1))) == (
        "canopen.node[0].tpdo[0].map",
        'expected an array of 1 to 8 { object = "2004:06", address = "%IW0" } '
        "tables; a PDO carries 8 bytes (got an empty array)",
    )


def test_pdo_bit_addresses(tmp_path):
    cfg = load(
        tmp_path, plant("", "", pdo("tpdo", 1, ("2004:06", "%IX0.0"), ("2004:07", "%IX0.1"), ("2004:08", "%IB1")))
    )
    assert [e.address for e in cfg.canopen.nodes[0].tpdo[0].entries] == [addr("%IX0.0"), addr("%IX0.1"), addr("%IB1")]
    cfg = load(
        tmp_path,
        plant("", "", pdo("rpdo", 1, ("2008:05", "%QW3:X2"), ("2008:06", "%QW3:X3"), ("2008:07", "%QW4"))).replace(
            PLC, PLC + 'profile = "schneider"\n'
        ),
    )
    assert [e.address.text for e in cfg.canopen.nodes[0].rpdo[0].entries] == ["%QW3:X2", "%QW3:X3", "%QW4"]


@pytest.mark.parametrize(
    "direction, address, message",
    [
        ("tpdo", "%QW0", "expected a %I address: a TPDO's entries go to %I inputs (got '%QW0', an output)"),
        ("tpdo", "%MW0", "expected a %I address: a TPDO's entries go to %I inputs (got '%MW0', a memory address)"),
        ("rpdo", "%IW0", "expected a %Q address: an RPDO's entries come from %Q outputs (got '%IW0', an input)"),
        ("tpdo", "IW0", "expected a direct address such as %IW0, %IX0.0 (got 'IW0')"),
        ("rpdo", "%QX0.8", "bit number 8 is not 0..7"),
        ("tpdo", "%IW40000", "%IW40000 (bytes 80000..80001) is outside the 65536-byte %I area"),
        ("tpdo", "%IX70000.0", "'%IX70000.0' is outside the 65536-byte %I area"),
    ],
)
def test_pdo_addresses_refused(tmp_path, direction, address, message):
    obj = "2004:06" if direction == "tpdo" else "2008:05"
    assert error(tmp_path, plant("", "", pdo(direction, 1, (obj, address)))) == (
        f"canopen.node[0].{direction}[0].map[0].address",
        message,
    )


def test_pdo_word_tables_refused(tmp_path):
    text = plant("", "", pdo("tpdo", 1, ("2004:06", "%IW3:4"))).replace(PLC, PLC + 'profile = "schneider"\n')
    assert error(tmp_path, text) == (
        "canopen.node[0].tpdo[0].map[0].address",
        "expected a bit, byte, word, dword or lword address (got '%IW3:4', a word table): map one object per address",
    )


def test_pdo_entries_may_not_overlap(tmp_path):
    key = "canopen.node[0].tpdo[0].map"
    assert error(tmp_path, plant("", "", pdo("tpdo", 1, ("2004:06", "%IW0"), ("2004:07", "%IB1")))) == (
        f"{key}[1].address",
        f"'%IB1' overlaps {key}[0].address ('%IW0')",
    )
    assert error(tmp_path, plant("", "", pdo("tpdo", 1, ("2004:06", "%IX1.3"), ("2004:07", "%IW0")))) == (
        f"{key}[1].address",
        f"'%IW0' overlaps {key}[0].address ('%IX1.3')",
    )
    assert error(tmp_path, plant("", "", pdo("tpdo", 1, ("2004:06", "%ID1"), ("2004:07", "%IW3")))) == (
        f"{key}[1].address",
        f"'%IW3' overlaps {key}[0].address ('%ID1')",
    )  # %ID1 = bytes 4-7, %IW3 = 6-7
    # neighbours do not overlap, and %I and %Q are different areas
    cfg = load(
        tmp_path,
        plant(
            "",
            "",
            pdo("tpdo", 1, ("2004:06", "%IW0"), ("2004:07", "%IB2"), ("2004:08", "%IX3.0"), ("2004:09", "%IX3.1")),
            pdo("rpdo", 1, ("2008:05", "%QW0")),
        ),
    )
    assert len(cfg.canopen.nodes[0].tpdo[0].entries) == 4


def test_pdos_may_not_overlap_each_other(tmp_path):
    second = NODE.replace('"motor"', '"pump"').replace("40", "41")
    text = plant(
        "",
        "",
        pdo("tpdo", 1, ("2004:06", "%IW100")),
        pdo("rpdo", 1, ("2008:05", "%QW100")),
        second,
        pdo("tpdo", 1, ("2004:06", "%IB201")),
        pdo("rpdo", 1, ("2008:05", "%QD50")),
    )
    assert errors(tmp_path, text) == [
        (
            "canopen.node[1].tpdo[0].map[0].address",
            "'%IB201' overlaps canopen.node[0].tpdo[0].map[0].address ('%IW100')",
        ),
        (
            "canopen.node[1].rpdo[0].map[0].address",
            "'%QD50' overlaps canopen.node[0].rpdo[0].map[0].address ('%QW100')",
        ),
    ]


def test_pdos_may_not_overlap_a_loopback_target(tmp_path):
    loopback = '[[loopback]]\nfrom = "%QB0"\nto = "%IB10"\nbytes = 4\n'
    assert error(tmp_path, plant("", "", pdo("tpdo", 1, ("2004:06", "%IW6")), loopback)) == (
        "canopen.node[0].tpdo[0].map[0].address",
        "'%IW6' overlaps loopback[0].to ('%IB10', 4 bytes)",
    )
    # %IW7 (bytes 14-15) is past the link's bytes 10-13; an RPDO may read what a link reads
    cfg = load(
        tmp_path, plant("", "", pdo("tpdo", 1, ("2004:06", "%IW7")), pdo("rpdo", 1, ("2008:05", "%QW0")), loopback)
    )
    assert cfg.loopback[0].nbytes == 4 and len(cfg.canopen.nodes[0].tpdo) == 1


def test_pdo_entry_errors(tmp_path):
    assert errors(
        tmp_path,
        plant(
            "",
            "",
            pdo("tpdo", 1).replace("map = []", 'map = [{ object = "2004:06" }, { address = "%IW0", obj = 1 }, 3]'),
        ),
    ) == [
        (
            "canopen.node[0].tpdo[0].map[0].address",
            'required key missing (expected an image address such as "%IW0" for a TPDO, "%QW0" for an RPDO)',
        ),
        (
            "canopen.node[0].tpdo[0].map[1].object",
            'required key missing (expected an object "index:subindex" in hex, such as "2004:06")',
        ),
        ("canopen.node[0].tpdo[0].map[1].obj", "unknown key (did you mean 'object'?)"),
        ("canopen.node[0].tpdo[0].map[2]", "expected a table (got 3)"),
    ]
