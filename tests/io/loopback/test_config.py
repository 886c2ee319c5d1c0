"""[[loopback]] (runtime/io/loopback/config.py)."""

from __future__ import annotations

from softplc.runtime.config import load_config
from softplc.runtime.io.loopback import LoopbackLink

from ...config.support import EXAMPLES, PLC, addr, errors


def test_example_loopback():
    cfg = load_config(EXAMPLES / "loopback.toml")
    assert cfg.loopback == [
        LoopbackLink(addr("%QB0"), addr("%IB0"), 2, "loopback[0]"),
        LoopbackLink(addr("%QD1"), addr("%ID2"), 4, "loopback[1]"),
    ]
    assert [(t.name, t.programs[0].program) for t in cfg.tasks] == [("Main", "Echo")]


# ====================================================================== [[loopback]]


def test_loopback_errors(tmp_path):
    assert errors(
        tmp_path,
        PLC + '[[loopback]]\nfrom = "%IB0"\nto = "%QB0"\nbytes = 0\n'
        '[[loopback]]\nfrom = "%QX0.0"\nto = "%IX0.0"\nbytes = 1\n'
        '[[loopback]]\nfrom = "%QB0"\nbytes = true\n'
        '[[loopback]]\nfrom = 3\nto = "%IZ0"\nbytes = 1\nsize = 2\n',
    ) == [
        ("loopback[0].bytes", "expected an integer from 1 to 65536 (got 0)"),
        ("loopback[0].from", "expected a %Q output address (got '%IB0', an input)"),
        ("loopback[0].to", "expected a %I input address (got '%QB0', an output)"),
        (
            "loopback[1].from",
            "expected a %Q output byte, word, dword or lword address such as %QB0 "
            "(got '%QX0.0'); the link copies whole bytes",
        ),
        (
            "loopback[1].to",
            "expected a %I input byte, word, dword or lword address such as %IB0 "
            "(got '%IX0.0'); the link copies whole bytes",
        ),
        ("loopback[2].to", 'required key missing (expected a %I byte/word/dword/lword address such as "%IB0")'),
        ("loopback[2].bytes", "expected an integer from 1 to 65536 (got true)"),
        ("loopback[3].size", "unknown key (expected one of from, to, bytes)"),
        ("loopback[3].from", "expected a direct address such as %QB0, %QW2 (got 3)"),
        ("loopback[3].to", "expected a direct address such as %IB0, %IW2 (got '%IZ0')"),
    ]


def test_links_past_the_end_of_the_image_or_into_the_same_inputs(tmp_path):
    """What the driver refused at start (naming neither the file nor the
    key) is the configuration's error."""
    assert errors(
        tmp_path,
        PLC + '[[loopback]]\nfrom = "%QB65535"\nto = "%IB0"\nbytes = 2\n'
        '[[loopback]]\nfrom = "%QB0"\nto = "%ID16383"\nbytes = 8\n'
        '[[loopback]]\nfrom = "%QB0"\nto = "%IB0"\nbytes = 65537\n'
        '[[loopback]]\nfrom = "%QB10"\nto = "%IB10"\nbytes = 4\n'
        '[[loopback]]\nfrom = "%QB20"\nto = "%IW6"\nbytes = 4\n',
    ) == [
        (
            "loopback[0].bytes",
            "2 bytes from '%QB65535' (byte 65535) run past the end of the 65536-byte %Q area: at most 1 from there",
        ),
        (
            "loopback[1].bytes",
            "8 bytes from '%ID16383' (byte 65532) run past the end of the 65536-byte %I area: at most 4 from there",
        ),
        ("loopback[2].bytes", "expected an integer from 1 to 65536 (got 65537)"),
        (
            "loopback[4].to",
            "'%IW6', 4 bytes, writes input bytes 12..15; loopback[3] (to = '%IB10', bytes = 4) already writes 12..13",
        ),
    ]
